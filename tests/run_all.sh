#!/usr/bin/env bash
# Runs every test of the project: the Rust tests of the crate and of the packaging tool, then prints
# one closing line with the totals. Needs only a Rust toolchain (cargo); it installs nothing else yet.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v cargo >/dev/null 2>&1; then
    echo "run_all.sh: cargo is not on PATH; install a Rust toolchain (https://rustup.rs) and rerun" >&2
    exit 1
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
echo "== Rust tests (workspace: powderfmu, fmu_build)"
status=0
cargo test --workspace --locked 2>&1 | tee "$log" || status=$?
passed=$(awk '/^test result:/ {s += $4} END {print s + 0}' "$log")
failed=$(awk '/^test result:/ {s += $6} END {print s + 0}' "$log")
echo
echo "rust: ${passed} passed, ${failed} failed"
exit "$status"
