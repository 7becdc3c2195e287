"""004 Ch. 5's bed height on the soft beds (benches/indentation_height.sh): per height the plateau
hardness (mean F/A(h) while loading at 0.1 <= h/r <= 0.2) and F_max/A(h_c) of each of three beds, their
mean and standard deviation over the beds.

    python benches/indentation_height.py OUT_DIR [--plot FIGURE.png]
"""

import argparse
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from indentation_rate import load, summary  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    p.add_argument("--plot")
    a = p.parse_args()
    out = Path(a.out)
    rows = []
    print("| spheres | bed height per bed [mm] | H / d (mean) | plateau hardness per bed [Pa] | mean [Pa] | standard deviation | F_max/A(h_c) per bed [Pa] | mean [Pa] |")
    print("|---:|---|---:|---|---:|---:|---|---:|")
    for n in [2000, 4000, 6000]:
        beds = []
        for seed in [1, 2, 3]:
            f = out / f"height_n{n}_seed{seed}.csv"
            if not f.exists():
                continue
            prep = (out / f"prepare_n{n}_seed{seed}.txt").read_text().splitlines()
            h = float(next(x.split()[2] for x in prep if x.startswith("bed height")))
            beds.append((h, summary(load(f))))
        if not beds:
            continue
        pl = [s["plateau"] for _, s in beds]
        tg = [s["tangent"] for _, s in beds]
        hs = [h for h, _ in beds]
        sd = statistics.stdev(pl) if len(pl) > 1 else float("nan")
        rows.append((n, hs, pl, tg))
        print(f"| {n} | {', '.join(f'{1e3 * h:.1f}' for h in hs)} | {statistics.fmean(hs) / 1e-3:.1f} | {', '.join(f'{x:.0f}' for x in pl)} |"
              f" {statistics.fmean(pl):.0f} | {sd:.0f} ({100 * sd / statistics.fmean(pl):.1f} %) | {', '.join(f'{x:.0f}' for x in tg)} | {statistics.fmean(tg):.0f} |")
    if a.plot and rows:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5.5, 3.8))
        for k, (n, hs, pl, tg) in enumerate(rows):
            ax.plot([1e3 * h for h in hs], pl, "o", color="tab:blue", label="plateau F/A(h), each bed" if k == 0 else None)
            ax.plot([1e3 * h for h in hs], tg, "s", mfc="none", color="tab:orange", label="F_max/A(h_c), each bed" if k == 0 else None)
        ax.plot([1e3 * statistics.fmean(hs) for _, hs, _, _ in rows], [statistics.fmean(pl) for _, _, pl, _ in rows], "-", color="tab:blue", label="plateau, mean of three beds")
        ax.set_xlabel("bed height [mm] (= H / d)")
        ax.set_ylabel("hardness [Pa]")
        ax.set_title("14 mm indenter, three beds per height", fontsize=9)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=130)
        print(f"\nfigure: {a.plot}")


if __name__ == "__main__":
    main()
