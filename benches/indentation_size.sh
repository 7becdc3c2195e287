#!/usr/bin/env bash
# 004 Ch. 5 on the soft beds: the indenter's size (the bed's height: indentation_height.sh).
# - Indenter size: 4, 8 and 14 mm (4, 8, 14 d) in each of the three beds of indentation_shortcuts.sh, to
#   h/r = 0.2 at gamma* = 0.02 with every sphere moving. The spread between the beds says how reliable a
#   size is.
# Needs the beds of benches/indentation_shortcuts.sh in OUT_DIR. About 20 CPU minutes.
#     bash benches/indentation_size.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/indentation_shortcuts}
cargo build --release --locked -q
bin=target/release/powderfmu
python=$(bash tools/venv.sh)
indent() { # BED HEIGHT DIAMETER RUN
    local speed
    speed=$("$python" -c "print(0.02 * $2 / (1e-3 / 9.81) ** 0.5)")
    [ -f "$4.csv" ] && return 0
    /usr/bin/time -f "%U" -o "$4.cpu" "$bin" bed indent "$1" --diameter "$3" --max-penetration "$("$python" -c "print(0.1 * $3)")" \
        --speed "$speed" --every 2e-4 --threads 1 --fidelity full --out "$4.csv" 2> "$4.log"
    echo "$4: $(tail -1 "$4.log")"
}
for seed in 1 2 3; do
    height=$(grep "bed height" "$out/prepare_seed$seed.txt" | awk '{print $3}')
    for d in 0.004 0.008 0.014; do
        indent "$out/bed_seed$seed.pfbed" "$height" "$d" "$out/size_seed${seed}_d$d"
    done
done
"$python" benches/indentation_size.py "$out" --plot docs/figures/indentation_size.png
