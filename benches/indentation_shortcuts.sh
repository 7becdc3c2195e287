#!/usr/bin/env bash
# The indentation's work-precision study: three independently prepared beds (scenes/bed_soft_4000.json
# with fill seeds 1, 2, 3), each indented by an 8 mm sphere to h/r = 0.2 at three speeds (gamma* = 0.01,
# 0.05, 0.2) with every sphere moving (fidelity full) and with the shortcut of fidelity fast: the spheres
# beyond m = 4, 3 or 2 contact radii held, never released (M) or released when the force on one changes
# by E = 0.1 or 0.01 of sigma_c d^2 (M:E). Plus the noise floor: the full test at gamma* = 0.01 with a
# time step 1 % shorter (the same physics, other rounding). One thread per run; the CPU time of each run
# is what `time` measures. Then benches/indentation_shortcuts.py prints the table and draws the figure.
# About 60 CPU minutes.
#     bash benches/indentation_shortcuts.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/indentation_shortcuts}
mkdir -p "$out"
cargo build --release --locked -q
bin=target/release/powderfmu
python=$(bash tools/venv.sh)
for seed in 1 2 3; do
    bed="$out/bed_seed$seed.pfbed"
    if [ ! -f "$bed" ]; then
        "$python" -c "import json,sys; s=json.load(open('scenes/bed_soft_4000.json')); s['seed']=$seed; json.dump(s, open(sys.argv[1],'w'))" "$out/scene_seed$seed.json"
        /usr/bin/time -f "%U" -o "$out/prepare_seed$seed.cpu" "$bin" bed prepare "$out/scene_seed$seed.json" --threads 1 -o "$bed" > "$out/prepare_seed$seed.txt"
    fi
    height=$(grep "bed height" "$out/prepare_seed$seed.txt" | awk '{print $3}')
    for gamma in 0.01 0.05 0.2; do
        # gamma* = (v / H) (d / g)^(1/2), 004 Eq. 7.1, d = 1 mm.
        speed=$("$python" -c "print($gamma * $height / (1e-3 / 9.81) ** 0.5)")
        for zone in full 4 3 2 3:0.1 2:0.1 3:0.01 2:0.01 fulldt; do
            run="$out/seed${seed}_g${gamma}_${zone/:/r}"
            [ -f "$run.csv" ] && continue
            case "$zone" in
                full) fidelity=(--fidelity full) ;;
                fulldt)
                    [ "$gamma" = 0.01 ] || continue
                    dt=$(grep "^time step:" "$out/prepare_seed$seed.txt" | head -1 | awk '{print $3}')
                    fidelity=(--fidelity full --time-step "$("$python" -c "print(0.99 * $dt)")") ;;
                *:*) fidelity=(--mobile-zone "${zone%:*}" --release "${zone#*:}") ;;
                *) fidelity=(--mobile-zone "$zone" --release inf) ;;
            esac
            /usr/bin/time -f "%U" -o "$run.cpu" "$bin" bed indent "$bed" --diameter 0.008 --max-penetration 0.0008 \
                --speed "$speed" --every 2e-4 --threads 1 "${fidelity[@]}" --out "$run.csv" 2> "$run.log"
            echo "seed $seed gamma* $gamma zone $zone: $(tail -1 "$run.log")"
        done
    done
done
"$python" benches/indentation_shortcuts.py "$out" --plot docs/figures/indentation_work_precision.png
