"""A quarter of the die against the whole die (benches/indentation_sector.sh): per bed the height, solid
fraction and coordination number the preparation printed, the plateau hardness (mean F/A(h) while
loading at 0.1 <= h/r <= 0.2), F_max/A(h_c) and the CPU time of the indentation; then the mean and
standard deviation of each kind over its beds.

    python benches/indentation_sector.py OUT_DIR
"""

import argparse
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from indentation_rate import load, summary  # noqa: E402


def field(text, label, index=0):
    line = next(x for x in text.splitlines() if x.startswith(label))
    return float(line.split(":", 1)[1].split()[index])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    a = p.parse_args()
    out = Path(a.out)
    rows = {}
    print("| die | fill seed | spheres | bed height [mm] | solid fraction | coordination | plateau hardness [Pa] | F_max/A(h_c) [Pa] | preparation CPU [s] | indentation CPU [s] |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for kind in ["whole", "quarter"]:
        for seed in [1, 2, 3]:
            run = out / f"{kind}_seed{seed}"
            if not run.with_suffix(".csv").exists():
                continue
            prep = (out / f"prepare_{kind}_seed{seed}.txt").read_text()
            s = summary(load(run.with_suffix(".csv")))
            cpu_p = float((out / f"prepare_{kind}_seed{seed}.cpu").read_text().split()[-1])
            cpu_i = float(run.with_suffix(".cpu").read_text().split()[-1])
            rows.setdefault(kind, []).append(s)
            print(f"| {kind} | {seed} | {int(field(prep, 'particles'))} | {1e3 * field(prep, 'bed height'):.2f} | {field(prep, 'solid fraction'):.4f} |"
                  f" {field(prep, 'coordination number'):.3f} | {s['plateau']:.0f} | {s['tangent']:.0f} | {cpu_p:.0f} | {cpu_i:.1f} |")
    print()
    print("| die | beds | mean plateau [Pa] | standard deviation [Pa] | mean F_max/A(h_c) [Pa] | standard deviation [Pa] |")
    print("|---|---:|---:|---:|---:|---:|")
    for kind, runs in rows.items():
        pl = [r["plateau"] for r in runs]
        tg = [r["tangent"] for r in runs]
        sd = (lambda xs: statistics.stdev(xs) if len(xs) > 1 else float("nan"))
        print(f"| {kind} | {len(runs)} | {statistics.fmean(pl):.0f} | {sd(pl):.0f} ({100 * sd(pl) / statistics.fmean(pl):.1f} %) |"
              f" {statistics.fmean(tg):.0f} | {sd(tg):.0f} |")
    if "whole" in rows and "quarter" in rows:
        w = statistics.fmean(r["plateau"] for r in rows["whole"])
        q = statistics.fmean(r["plateau"] for r in rows["quarter"])
        print(f"\nquarter against whole (mean plateau): {100 * (q / w - 1):+.1f} %")


if __name__ == "__main__":
    main()
