#!/usr/bin/env bash
# The work-precision study in one command: native errors and costs of every law and solver, the fidelity
# axis, fmpy's end-to-end costs, then the figures and the tables of docs/benchmarks.md. About 3 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
python=$(bash tools/venv.sh)
cargo bench --locked --bench work_precision
cargo run --locked -q -p fmu_build
"$python" benches/fmpy_cost.py
"$python" benches/work_precision_plot.py
