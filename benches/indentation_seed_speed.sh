#!/usr/bin/env bash
# The seed's test at its own speed (gamma* = 0.01: 0.0179 m/s, 2.5e-7 s steps, every sphere moving) on
# the shipped quarter and whole beds, two threads, through the command-line tool: wall time and hardness.
# Pass builds to compare (an earlier binary kept aside, then this one); they alternate, bed by bed.
#     bash benches/indentation_seed_speed.sh [BIN ...]      # default: target/release/powderfmu
#     BEDS="beds/bed_004_ch6_quarter.pfbed" bash benches/indentation_seed_speed.sh OLD NEW
#     SKIN=2.5e-5 bash benches/indentation_seed_speed.sh OLD NEW   # also the last build at that skin
# About 3-4 minutes per quarter-bed run and 10-12 per whole-bed run on this machine's two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -gt 0 ] || { cargo build --locked --quiet --release --bin powderfmu; set -- target/release/powderfmu; }
BEDS=${BEDS:-beds/bed_004_ch6_quarter.pfbed beds/bed_004_ch6.pfbed}
for bed in $BEDS; do
    for bin in "$@"; do
        printf '%s, %s: ' "$(basename "$bed")" "$bin"
        "$bin" bed indent "$bed" --speed 0.0179 --time-step 2.5e-7 --fidelity full --threads 2 --every 1e-4 --out /dev/null 2>&1 \
            | grep -o 'hardness [0-9.e]* \(+- [0-9.e]* Pa (standard error of the force at the turn)\|Pa\), plateau hardness .*particle-steps/s'
    done
    if [ -n "${SKIN:-}" ]; then
        bin=${!#}
        printf '%s, %s, skin %s: ' "$(basename "$bed")" "$bin" "$SKIN"
        "$bin" bed indent "$bed" --speed 0.0179 --time-step 2.5e-7 --fidelity full --threads 2 --every 1e-4 --out /dev/null --change "{\"skin\": $SKIN}" 2>&1 \
            | grep -o 'hardness [0-9.e]* \(+- [0-9.e]* Pa (standard error of the force at the turn)\|Pa\), plateau hardness .*particle-steps/s'
    fi
done
