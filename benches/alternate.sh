#!/usr/bin/env bash
# Builds of the engine timed side by side: `powderfmu bed bench` with the same arguments, the builds
# taking turns for ROUNDS rounds, then per build the median, least and largest particle-steps per second.
# On a shared machine only figures measured this way (alternating, in one run) compare.
#
#   bash benches/alternate.sh ROUNDS BED "BENCH ARGS" BIN...
#   e.g. bash benches/alternate.sh 7 target/bench/settled.bed \
#        "--model hooke --steps 2000 --threads 1 --stiffness 1000 --surface-energy 0.1 --rolling-friction 0 --skin 1e-4" \
#        /tmp/old/powderfmu target/release/powderfmu
# A BIN may be a wrapper script (e.g. one setting POWDERFMU_ENGINE_ISA=avx2 before exec'ing a build).
set -euo pipefail
[ $# -ge 4 ] || { echo "usage: bash benches/alternate.sh ROUNDS BED \"BENCH ARGS\" BIN..." >&2; exit 2; }
rounds=$1 bed=$2 args=$3
shift 3
declare -A all
for r in $(seq "$rounds"); do
    for b in "$@"; do
        # shellcheck disable=SC2086 # the bench arguments are words
        v=$("$b" bed bench "$bed" $args | tr ' ' '\n' | grep '^particle_steps_per_s=' | cut -d= -f2)
        [ -n "$v" ] || { echo "alternate: $b printed no particle_steps_per_s" >&2; exit 1; }
        all[$b]="${all[$b]:-} $v"
        printf '\rround %d of %d' "$r" "$rounds" >&2
    done
done
echo >&2
for b in "$@"; do
    python3 -c '
import statistics, sys
b, v = sys.argv[1], [float(x) for x in sys.argv[2:]]
print(f"{b:40s} median {statistics.median(v):.3e}  least {min(v):.3e}  largest {max(v):.3e}  particle-steps/s, n {len(v)}")' "$b" ${all[$b]}
done
