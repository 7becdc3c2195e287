#!/usr/bin/env bash
# A wheel of the Python package `powderfmu` that carries the three FMI 2.0 FMUs (their binaries as
# target/fmu holds them: linux64, and win64 where fmu_build made them), so that it installs anywhere
# (`pip install WHEEL`) and runs with no clone of the repository and no Rust toolchain. The package
# finds its FMUs in the wheel (python/powderfmu/fmus.py). Builds the FMUs first when target/fmu has none.
#
#   bash tools/wheel.sh [OUTDIR]          (default target/wheels; prints the wheel's path)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/wheels}
python=$(bash tools/venv.sh)
units=(ParticleWallImpact ContactElement BallIndentation UnconfinedCompression)
for u in "${units[@]}"; do
    if [ ! -f "target/fmu/$u.fmu" ]; then
        cargo run --locked --quiet --release -p fmu_build -- --linux-only >&2
        break
    fi
done
# The package is copied out so that the FMUs never land in the source tree.
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
cp -r python "$stage/python"
rm -rf "$stage/python/build" "$stage"/python/*.egg-info
mkdir -p "$stage/python/powderfmu/fmus"
for u in "${units[@]}"; do
    cp "target/fmu/$u.fmu" "$stage/python/powderfmu/fmus/"
done
mkdir -p "$out"
rm -f "$out"/powderfmu-*.whl
"$python" -m pip wheel --quiet --disable-pip-version-check --no-deps --no-build-isolation "$stage/python" -w "$out" >&2
ls "$out"/powderfmu-*.whl
