#!/usr/bin/env bash
# Throughput of the bed engine against LAMMPS, side by side in one run (see benches/vs_lammps.py).
# Installs LAMMPS from Debian's packages if it is missing; the first run prepares the bench bed.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin powderfmu
python3 benches/vs_lammps.py "$@"
