"""The unconfined compression test's stress-strain curves (`powderfmu bed compress`, 004 Sec. 2.1) as a figure:
each CSV given as LABEL=PATH, the largest window mean (sigma_c, or its lower bound) marked.

    powderfmu bed prepare scenes/uct_004_ch6.json -o uct.pfbed        # about 23 minutes on one thread
    powderfmu bed compress uct.pfbed --out uct.csv
    python benches/compression_curves.py --plot docs/figures/compression_curves.png "Ch. 6 material, 15 mm specimen=uct.csv" ...

docs/figures/compression_curves.png: the curves in docs/data/compression/ (every tenth sample of `bed compress
--out`; the 0.1/s run with --max-strain 0.01 --window 0.0005; the quick beds prepared as tests/compression.rs
prepares them).
"""

import argparse
import csv

WINDOW = 0.005


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [float(r["strain"]) for r in rows], [float(r["stress_Pa"]) for r in rows]


def peak(strain, stress):
    """The largest mean over a window of WINDOW strain (as `bed compress` reads sigma_c): (strain, mean)."""
    loaded = [(e, s) for e, s in zip(strain, stress) if e > 0]
    best = (0.0, 0.0)
    j = 0
    total = 0.0
    for i, (e, s) in enumerate(loaded):
        total += s
        while loaded[j][0] < e - WINDOW:
            total -= loaded[j][1]
            j += 1
        mean = total / (i - j + 1)
        if e - loaded[j][0] >= 0.9 * WINDOW and mean > best[1]:
            best = (0.5 * (e + loaded[j][0]), mean)
    return best


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plot", required=True)
    p.add_argument("curves", nargs="+", help="LABEL=CSV")
    a = p.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    for k, item in enumerate(a.curves):
        label, path = item.split("=", 1)
        e, s = read(path)
        pe, ps = peak(e, s)
        for ax in axes:
            ax.plot([100 * x for x in e], s, lw=1, color=f"C{k}", label=f"{label}: largest 0.5 % mean {ps:.0f} Pa at {100 * pe:.1f} %")
            ax.plot([100 * pe], [ps], "o", color=f"C{k}")
    axes[0].set(xlabel="axial strain [%]", ylabel="platen stress [Pa]", title="to 10 % strain")
    axes[1].set(xlabel="axial strain [%]", ylabel="platen stress [Pa]", title="the first 1 % (log stress)", xlim=(0, 1), yscale="log", ylim=(1, 6000))
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Unconfined compression (004 Sec. 2.1): die removed, platen down at a strain rate, consolidated to 10 kPa")
    fig.tight_layout()
    fig.savefig(a.plot, dpi=110)
    print(f"wrote {a.plot}")


if __name__ == "__main__":
    main()
