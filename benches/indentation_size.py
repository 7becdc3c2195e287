"""004 Ch. 5 on the soft beds: hardness against the indenter's size (three beds).

Reads benches/indentation_size.sh's runs and prints, per indenter diameter, the plateau hardness (mean
F/A(h) while loading at 0.1 <= h/r <= 0.2) and F_max/A(h_c) of each bed with their spread between the
beds, (max - min) / mean.

    python benches/indentation_size.py OUT_DIR [--plot FIGURE.png]
"""

import argparse
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from indentation_rate import load, summary  # noqa: E402


def spread(xs):
    return 100 * (max(xs) - min(xs)) / statistics.fmean(xs)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    p.add_argument("--plot")
    a = p.parse_args()
    out = Path(a.out)
    sizes = {}
    print("| indenter diameter [mm] | d_i / d | plateau hardness per bed [Pa] | spread [%] | F_max/A(h_c) per bed [Pa] | spread [%] |")
    print("|---:|---:|---|---:|---|---:|")
    for d in ["0.004", "0.008", "0.014"]:
        runs = [summary(load(f)) for f in sorted(out.glob(f"size_seed*_d{d}.csv"))]
        if not runs:
            continue
        pl = [r["plateau"] for r in runs]
        tg = [r["tangent"] for r in runs]
        sizes[float(d)] = pl
        print(f"| {1e3 * float(d):.0f} | {float(d) / 1e-3:.0f} | {', '.join(f'{x:.0f}' for x in pl)} | {spread(pl):.0f} | "
              f"{', '.join(f'{x:.0f}' for x in tg)} | {spread(tg):.0f} |")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax1 = plt.subplots(figsize=(5, 3.6))
        for d, pl in sizes.items():
            ax1.plot([1e3 * d] * len(pl), pl, "o", color="tab:blue")
        ax1.set_xlabel("indenter diameter [mm] (= d_i / d)")
        ax1.set_ylabel("plateau hardness [Pa]")
        ax1.set_title("the same three beds, each indenter size", fontsize=9)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=130)
        print(f"\nfigure: {a.plot}")


if __name__ == "__main__":
    main()
