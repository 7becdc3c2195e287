#!/usr/bin/env bash
# Runs every test of the project: the Rust tests (crate and packaging tool, including the importer test
# and the check of every FMI 2.0 and 3.0 signature against the official headers), then builds the .fmu files and runs
# the fmpy suite (tests/python) against them; cargo clippy with warnings as errors and the format check
# (cargo fmt --check) run in between.
# Installs what it needs: the project's Python virtual environment (.venv, pinned fmpy, numpy,
# matplotlib, pytest) and the Windows toolchain of the win64 binaries and their test under wine (the Rust
# target x86_64-pc-windows-gnu, Debian's gcc-mingw-w64-x86-64 and wine; tools/windows_toolchain.sh) and
# the peer DEM codes the peer tests compare with (Debian's lammps and yade; tools/peers.sh).
# POWDERFMU_SKIP_WINDOWS=1 builds linux64 only and skips the wine tests. The fmpy suite runs on
# POWDERFMU_TEST_WORKERS pytest-xdist workers (default 2, CI's cores), each test file on one worker, so a
# module's fixtures are built once. Ends with each phase's wall time and one line of totals.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v cargo >/dev/null 2>&1; then
    echo "run_all.sh: cargo is not on PATH; install a Rust toolchain (https://rustup.rs) and rerun" >&2
    exit 1
fi
# Each phase's wall time is printed at the end: CI's budget is 20 minutes on two cores.
phases=()
phase_start=$SECONDS
phase_name=""
phase() {
    [ -n "$phase_name" ] && phases+=("$(printf '%5d s  %s' $((SECONDS - phase_start)) "$phase_name")")
    phase_name=$1
    phase_start=$SECONDS
    [ -n "$1" ] && echo "== $1"
    return 0
}
phase "Python environment (.venv, pinned requirements.txt)"
python=$(bash tools/venv.sh)
fmu_flags=()
if [ "${POWDERFMU_SKIP_WINDOWS:-0}" = 1 ]; then
    echo "== Windows: skipped (POWDERFMU_SKIP_WINDOWS=1): the FMUs get linux64 binaries only"
    fmu_flags=(--linux-only)
else
    phase "Windows toolchain (Rust target, mingw-w64, wine)"
    bash tools/windows_toolchain.sh
fi
phase "Peer DEM codes (LAMMPS, Yade: the peer tests of the fmpy suite)"
bash tools/peers.sh || echo "run_all.sh: the peer codes could not be installed; their tests skip" >&2
headers=$("$python" -c 'import fmpy, os; print(os.path.join(os.path.dirname(fmpy.__file__), "c-code"))')

log=$(mktemp)
pylog=$(mktemp)
trap 'rm -f "$log" "$pylog"' EXIT
status=0

phase "Rust tests (workspace: powderfmu, fmu_build; debug build included)"
FMI2_HEADERS="$headers" FMI3_HEADERS="$headers" cargo test --workspace --locked 2>&1 | tee "$log" || status=$?
rust_passed=$(awk '/^test result:/ {s += $4} END {print s + 0}' "$log")
rust_failed=$(awk '/^test result:/ {s += $6} END {print s + 0}' "$log")

phase "Lints (cargo clippy, warnings are errors)"
if cargo clippy --version >/dev/null 2>&1; then
    cargo clippy --workspace --all-targets --locked --quiet -- -D warnings || status=1
else
    echo "run_all.sh: cargo clippy is not installed (rustup component add clippy); lints skipped" >&2
fi

phase "Format (cargo fmt --check, rustfmt.toml)"
if cargo fmt --version >/dev/null 2>&1; then
    cargo fmt --all --check -- -l || { echo "run_all.sh: the files above are not formatted; run cargo fmt --all" >&2; status=1; }
else
    echo "run_all.sh: rustfmt is not installed (rustup component add rustfmt); the format check skipped" >&2
fi

phase "Building the FMUs (target/fmu)"
# The packaging tool as the Rust tests built it (cargo puts their binaries in target/debug): `cargo run -p
# fmu_build` resolves the dependencies' features without the dev-dependencies and compiled the library
# again (92 s of CI's packaging phase).
fmu_build=$PWD/target/debug/fmu_build
if [ ! -x "$fmu_build" ]; then
    echo "run_all.sh: the Rust tests left no $fmu_build; building it" >&2
    cargo build --locked --quiet -p fmu_build
fi
export POWDERFMU_FMU_BUILD=$fmu_build
"$fmu_build" "${fmu_flags[@]}" || status=$?

phase "fmpy suite (tests/python) and the Python package's own tests (python/tests)"
POWDERFMU_FMU_DIR="$PWD/target/fmu" POWDERFMU_CLI="$PWD/target/debug/powderfmu" \
    "$python" -m pytest tests/python python/tests -q -rs -p no:cacheprovider --durations=30 \
    -n "${POWDERFMU_TEST_WORKERS:-2}" --dist loadfile 2>&1 | tee "$pylog" || status=$?
py_passed=$( (grep -Eo '[0-9]+ passed' "$pylog" || true) | tail -1 | grep -Eo '[0-9]+' || true)
py_failed=$( (grep -Eo '[0-9]+ (failed|error)' "$pylog" || true) | awk '{s += $1} END {print s + 0}')

phase ""
echo
echo "wall time by phase (total ${SECONDS} s):"
printf '%s\n' "${phases[@]}"
echo "rust: ${rust_passed} passed, ${rust_failed} failed; fmpy: ${py_passed:-0} passed, ${py_failed} failed"
exit "$status"
