#!/usr/bin/env bash
# The rate question of issue 31 on the shipped whole bed (004 Ch. 6 bed, the 16 mm indenter to h/r = 0.2,
# every sphere moving, 2.5e-7 s steps unless halved): the four gamma* of 004 Ch. 7 (0.0115, 0.2297,
# 0.4594, 2.2969), then one change at a time against the same bed (`bed indent --change`) at the slow
# end (gamma* = 0.0115) and at gamma* = 0.08: a tenth of the particle-particle damping, no rolling
# friction, no cohesion, and the time step halved. Replicas at gamma* = 0.08 with steps a few parts in
# 10^4 shorter (the same physics, other rounding: the bed's dynamics are chaotic, so they follow
# independent paths) give the run-to-run scatter the changes are judged against. One run per row; a row
# whose log holds a result is not run again, so the study can be stopped and resumed.
#
#   bash benches/indentation_rate_changes.sh OUT_DIR [BIN]
#   then: python benches/indentation_rate_changes.py OUT_DIR --csv docs/data/rate_changes.csv
#
# speed = gamma* x 1.786 m/s: gamma* = (v / H) (d / g)^(1/2) with H = 18.0 mm and d = 1 mm (004 Eq. 5.4).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:?usage: indentation_rate_changes.sh OUT_DIR [BIN]}
BIN=${2:-target/release/powderfmu}
BED=${BED:-beds/bed_004_ch6.pfbed}
[ -x "$BIN" ] || cargo build --locked --quiet --release --bin powderfmu
mkdir -p "$OUT"
speed() { python3 -c "print(f'{$1 * 1.786:.5g}')"; }
run() { # name gamma change time_step
    local name=$1 gamma=$2 change=$3 dt=$4 log="$OUT/$1.log"
    if [ -f "$log" ] && grep -q "plateau hardness" "$log"; then return; fi
    local args=(bed indent "$BED" --speed "$(speed "$gamma")" --time-step "$dt" --fidelity full --threads 2 --every 1e-4
        --out "$OUT/$name.csv" --samples-out "$OUT/$name.samples.csv")
    [ -z "$change" ] || args+=(--change "$change")
    echo "$(date +%T) $name: gamma* $gamma, change ${change:-none}, dt $dt" >&2
    { echo "gamma=$gamma dt=$dt change=${change:-none}"; "$BIN" "${args[@]}" 2>&1 >/dev/null; } >"$log.part" && mv "$log.part" "$log"
}
DAMP='{"particle_particle": {"damping_factor_elastic": 0.1, "damping_factor_plastic": 0.1}}'
ROLL='{"rolling_friction": 0}'
COH='{"particle_particle": {"surface_energy": 0}}'
for g in 2.2969 0.4594 0.2297 0.08 0.0115; do run "base_g$g" "$g" "" 2.5e-7; done
for g in 0.08 0.0115; do
    run "roll0_g$g" "$g" "$ROLL" 2.5e-7
    run "damp01_g$g" "$g" "$DAMP" 2.5e-7
    run "coh0_g$g" "$g" "$COH" 2.5e-7
done
run "dthalf_g0.08" 0.08 "" 1.25e-7
run "replica1_g0.08" 0.08 "" 2.4975e-7
run "replica2_g0.08" 0.08 "" 2.495e-7
run "dthalf_replica1_g0.08" 0.08 "" 1.24875e-7
run "dthalf_g0.0115" 0.0115 "" 1.25e-7
