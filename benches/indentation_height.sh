#!/usr/bin/env bash
# 004 Ch. 5's bed height on the soft beds, three beds per height: scenes/bed_soft_4000.json with 2000,
# 4000 and 6000 spheres in the same 20 mm die (about 6.5, 13 and 19.5 d high), fill seeds 1, 2, 3, each
# indented by the 14 mm sphere (the size the soft beds agree on, indentation_size.sh) to h/r = 0.2 at
# gamma* = 0.02, every sphere moving, one thread. Then benches/indentation_height.py prints the table and
# draws the figure. About 15 CPU minutes.
#     bash benches/indentation_height.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/indentation_height}
mkdir -p "$out"
cargo build --release --locked -q
bin=target/release/powderfmu
python=$(bash tools/venv.sh)
for n in 2000 4000 6000; do
    for seed in 1 2 3; do
        bed="$out/bed_n${n}_seed$seed.pfbed"
        if [ ! -f "$bed" ]; then
            "$python" -c "import json,sys; s=json.load(open('scenes/bed_soft_4000.json')); s['particle_count']=$n; s['seed']=$seed; json.dump(s, open(sys.argv[1],'w'))" "$out/scene_n${n}_seed$seed.json"
            "$bin" bed prepare "$out/scene_n${n}_seed$seed.json" --threads 1 -o "$bed" > "$out/prepare_n${n}_seed$seed.txt"
        fi
        run="$out/height_n${n}_seed$seed"
        [ -f "$run.csv" ] && continue
        height=$(grep "bed height" "$out/prepare_n${n}_seed$seed.txt" | awk '{print $3}')
        # gamma* = (v / H) (d / g)^(1/2), 004 Eq. 7.1, d = 1 mm.
        speed=$("$python" -c "print(0.02 * $height / (1e-3 / 9.81) ** 0.5)")
        "$bin" bed indent "$bed" --diameter 0.014 --max-penetration 0.0014 --speed "$speed" --every 2e-4 --threads 1 \
            --fidelity full --out "$run.csv" 2> "$run.log"
        echo "$run: $(tail -1 "$run.log")"
    done
done
"$python" benches/indentation_height.py "$out" --plot docs/figures/indentation_height.png
