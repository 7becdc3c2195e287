#!/usr/bin/env bash
# Leaks and memory of the C ABI (docs/robustness.md): 1e4 instantiate / initialize / step / save /
# restore / free cycles under valgrind (no leak, no invalid access: valgrind's exit code), then 1e5
# cycles natively with the resident memory printed every tenth of the way. About half a minute.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v valgrind >/dev/null || { echo "leak_check: valgrind is not installed (apt-get install valgrind)" >&2; exit 2; }
cargo build --locked -q --release --example lifecycle
echo "leak_check: 10000 cycles under valgrind"
valgrind --quiet --leak-check=full --show-leak-kinds=definite,indirect,possible \
    --errors-for-leak-kinds=definite,indirect,possible --error-exitcode=1 \
    target/release/examples/lifecycle 10000 | tail -1
echo "leak_check: valgrind found no leak and no invalid access"
echo "leak_check: 100000 cycles natively"
target/release/examples/lifecycle 100000
