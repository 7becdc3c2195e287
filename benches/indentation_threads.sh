#!/usr/bin/env bash
# The BallIndentation default test through the command-line tool on the shipped bed, one and two threads
# alternating, REPS times each (default 3): one summary line per run (wall time, particle-steps/s).
#     bash benches/indentation_threads.sh [REPS]       # about 4 minutes per repetition on two cores
set -euo pipefail
cd "$(dirname "$0")/.."
reps=${1:-3}
cargo build --locked --quiet --release --bin powderfmu
for rep in $(seq "$reps"); do
    for threads in 1 2; do
        printf 'threads %s, run %s: ' "$threads" "$rep"
        target/release/powderfmu bed indent beds/bed_004_ch6.pfbed --diameter 0.016 --max-penetration 0.0016 --speed 0.1429 --time-step 2.5e-7 --fidelity fast \
            --threads "$threads" --every 1e-4 --out /dev/null 2>&1 | grep -o '[0-9.]* s wall time, [0-9]* steps, [0-9.e]* particle-steps/s'
    done
done
