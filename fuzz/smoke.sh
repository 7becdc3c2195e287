#!/usr/bin/env bash
# A short run of both fuzz targets from the checked-in corpus (needs the nightly toolchain and cargo-fuzz).
set -euo pipefail
cd "$(dirname "$0")"
command -v cargo-fuzz >/dev/null || cargo install --locked cargo-fuzz
for target in state_bytes call_sequence; do
    cargo +nightly fuzz run "$target" "corpus/$target" -- -max_total_time=30 -max_len=4096 -timeout=30 2>&1 | grep -E "^Done|ERROR|SUMMARY"
done
