#!/usr/bin/env bash
# Runs every test of the project: the Rust tests of the crate and of the packaging tool.
# Needs only a Rust toolchain (cargo); it installs nothing else yet.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v cargo >/dev/null 2>&1; then
    echo "run_all.sh: cargo is not on PATH; install a Rust toolchain (https://rustup.rs) and rerun" >&2
    exit 1
fi
echo "== Rust tests (workspace: powderfmu, fmu_build)"
cargo test --workspace --locked
