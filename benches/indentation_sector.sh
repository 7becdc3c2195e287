#!/usr/bin/env bash
# A quarter of the die against the whole die, on the soft beds: three beds of scenes/bed_soft_4000.json
# (fill seeds 1, 2, 3; 4000 spheres in a 20 mm die) and three quarter beds of the same scene
# (die_sector 0.25, 1000 spheres between the mirror planes x = 0 and y = 0), each indented by the 14 mm
# sphere (the size whose hardness the soft beds agree on, indentation_size.sh) to h/r = 0.2 at
# gamma* = 0.02, every sphere moving, one thread. Then benches/indentation_sector.py prints the table:
# whether the quarter's hardness is the whole die's within the spread between beds, and at what cost.
# About 15 CPU minutes.
#     bash benches/indentation_sector.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/indentation_sector}
mkdir -p "$out"
cargo build --release --locked -q
bin=target/release/powderfmu
python=$(bash tools/venv.sh)
for seed in 1 2 3; do
    for kind in whole quarter; do
        bed="$out/${kind}_seed$seed.pfbed"
        if [ ! -f "$bed" ]; then
            "$python" -c "
import json, sys
s = json.load(open('scenes/bed_soft_4000.json'))
s['seed'] = $seed
if '$kind' == 'quarter':
    s['die_sector'] = 0.25
    s['particle_count'] = 1000
json.dump(s, open(sys.argv[1], 'w'))" "$out/${kind}_seed$seed.json"
            /usr/bin/time -f "%U" -o "$out/prepare_${kind}_seed$seed.cpu" "$bin" bed prepare "$out/${kind}_seed$seed.json" --threads 1 -o "$bed" > "$out/prepare_${kind}_seed$seed.txt"
        fi
        run="$out/${kind}_seed$seed"
        [ -f "$run.csv" ] && continue
        height=$(grep "bed height" "$out/prepare_${kind}_seed$seed.txt" | awk '{print $3}')
        # gamma* = (v / H) (d / g)^(1/2), 004 Eq. 7.1, d = 1 mm.
        speed=$("$python" -c "print(0.02 * $height / (1e-3 / 9.81) ** 0.5)")
        /usr/bin/time -f "%U" -o "$run.cpu" "$bin" bed indent "$bed" --diameter 0.014 --max-penetration 0.0014 \
            --speed "$speed" --every 2e-4 --threads 1 --fidelity full --out "$run.csv" 2> "$run.log"
        echo "$run: $(tail -1 "$run.log")"
    done
done
"$python" benches/indentation_sector.py "$out"
