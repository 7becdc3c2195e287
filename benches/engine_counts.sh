#!/usr/bin/env bash
# Instructions and simulated cache misses per particle-step of the bed engine's step (force loop, kick,
# list upkeep), the counts the engine-speed work is judged by where hardware counters are not offered
# (this VM's perf has none). Cachegrind (Debian's valgrind) runs `powderfmu bed bench` twice, with S1 and
# S2 timed steps and no warm-up, and the difference is divided by (S2 - S1) x particles: loading the bed
# and building the engine cancel. Deterministic for a given binary, so two builds compare to the
# instruction on a shared machine. Cachegrind's cache model is its own (first-level data 32-48 KiB,
# last level the host's L3 as it reads it), so misses are a model's, not this CPU's.
#
#   bash benches/engine_counts.sh [BED] [LAWS] [S1] [S2] [BIN]
#   defaults: beds/bed_004_ch6_quarter.pfbed, "pasha_simplified hooke hertz jkr nan", 40, 120,
#             target/release/powderfmu
# Prints one Markdown row per law: instructions, D1 read+write misses and last-level misses per
# particle-step.
set -euo pipefail
cd "$(dirname "$0")/.."
BED=${1:-beds/bed_004_ch6_quarter.pfbed}
LAWS=${2:-pasha_simplified hooke hertz jkr nan}
S1=${3:-40}
S2=${4:-120}
BIN=${5:-target/release/powderfmu}
command -v valgrind >/dev/null || { echo "engine_counts: valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
[ -x "$BIN" ] || cargo build --release --bin powderfmu
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Counts of one run: Ir, D1mr + D1mw, DLmr + DLmw (cachegrind's summary line), and the particle count.
counts() {
    local law=$1 steps=$2 out="$work/cg.$1.$2"
    valgrind --tool=cachegrind --cache-sim=yes --cachegrind-out-file="$out" "$BIN" bed bench "$BED" --model "$law" --steps "$steps" --warmup 0 >"$work/bench.txt" 2>/dev/null
    local particles
    particles=$(grep -o 'particles=[0-9]*' "$work/bench.txt" | cut -d= -f2)
    # events: Ir I1mr ILmr Dr D1mr DLmr Dw D1mw DLmw
    awk -v p="$particles" '/^summary:/ {print $2, $6 + $9, $7 + $10, p}' "$out"
}
echo "| law | instructions | D1 misses | LL misses | per particle-step ($BED, steps $S1 to $S2) |"
echo "|---|---:|---:|---:|---|"
for law in $LAWS; do
    read -r i1 d1 l1 n < <(counts "$law" "$S1")
    read -r i2 d2 l2 _ < <(counts "$law" "$S2")
    awk -v law="$law" -v i1="$i1" -v i2="$i2" -v d1="$d1" -v d2="$d2" -v l1="$l1" -v l2="$l2" -v n="$n" -v s="$((S2 - S1))" \
        'BEGIN { ps = n * s; printf "| %s | %.0f | %.2f | %.3f | %d particles |\n", law, (i2 - i1) / ps, (d2 - d1) / ps, (l2 - l1) / ps, n }'
done
