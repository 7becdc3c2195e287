#!/usr/bin/env bash
# The reading window of issue 31 on the 004 Ch. 6 bed: the unit's window (h/r 0.1-0.2) against the seed's
# (after h/r 0.35, read to 0.5: 004 Figs. 5.3-5.4, 5.19, 6.3). The 16 mm indenter taken on to h/r 0.5
# (max penetration 4 mm) on the three quarter beds the FMU ships, at the default's speed (gamma* 0.02),
# the seed's (0.01) and faster (0.04, 0.08), and on the shipped whole bed at the seed's speed; every
# sphere moving, 2.5e-7 s steps, the unit's own plateau over 0.35-0.5 in each log; about 75 minutes on
# two cores. A run whose log holds a result is not run again, so the study can be stopped and resumed.
#
#   bash benches/indentation_window.sh OUT_DIR [BIN]
#   then: python3 benches/indentation_windows.py q1=OUT_DIR/quarter1_g0.02.csv ...
#
# POWDERFMU_WHOLE_BEDS="BED2 BED3" adds the other whole beds of the reference of record at the seed's speed
# (whole2_g0.01, whole3_g0.01; about 30 minutes each). They are not shipped: `powderfmu bed prepare` of
# scenes/bed_004_ch6.json with "seed": 2 and 3 (about 2 hours each on two cores; docs/indentation.md).
#
# speed = gamma* x 1.786 m/s: gamma* = (v / H) (d / g)^(1/2) with H = 18.0 mm and d = 1 mm (004 Eq. 5.4);
# 0.035726 m/s is the FMU's default indentation_speed.
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:?usage: indentation_window.sh OUT_DIR [BIN]}
BIN=${2:-target/release/powderfmu}
[ -x "$BIN" ] || cargo build --locked --quiet --release --bin powderfmu
mkdir -p "$OUT"
run() { # name bed speed
    local name=$1 bed=$2 speed=$3 log="$OUT/$1.log"
    if [ -f "$log" ] && grep -q "plateau hardness" "$log"; then return; fi
    echo "$(date +%T) $name: $bed at $speed m/s to h/r 0.5" >&2
    "$BIN" bed indent "$bed" --diameter 0.016 --max-penetration 0.004 --speed "$speed" --time-step 2.5e-7 \
        --fidelity full --threads 2 --every 1e-4 --plateau-start 0.35 --plateau-end 0.5 \
        --out "$OUT/$name.csv" 2>"$log.part" >/dev/null && mv "$log.part" "$log"
}
Q=(beds/bed_004_ch6_quarter.pfbed beds/bed_004_ch6_quarter_seed2.pfbed beds/bed_004_ch6_quarter_seed3.pfbed)
for i in 1 2 3; do run "quarter${i}_g0.02" "${Q[$((i - 1))]}" 0.035726; done
run whole1_g0.01 beds/bed_004_ch6.pfbed 0.01786
i=1
for bed in ${POWDERFMU_WHOLE_BEDS:-}; do
    i=$((i + 1))
    run "whole${i}_g0.01" "$bed" 0.01786
done
for i in 1 2 3; do run "quarter${i}_g0.01" "${Q[$((i - 1))]}" 0.01786; done
for g in 0.04 0.08; do
    for i in 1 2 3; do run "quarter${i}_g$g" "${Q[$((i - 1))]}" "$(python3 -c "print(f'{$g * 1.786:.5g}')")"; done
done
