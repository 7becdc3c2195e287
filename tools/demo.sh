#!/usr/bin/env bash
# The main job (README command 1): builds the FMUs and the command-line tool, then runs the fmpy
# demonstration on the default scene, printing results and writing plots to out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
python=$(bash tools/venv.sh)
echo "== Windows toolchain (Rust target, mingw-w64, wine): the FMUs carry win64 binaries"
bash tools/windows_toolchain.sh
echo "== Building the FMUs (target/fmu) and the command-line tool"
cargo run --locked --quiet -p fmu_build
cargo build --locked --quiet --release --bin powderfmu
echo "== fmpy demonstration"
"$python" tools/demo.py "$@"
