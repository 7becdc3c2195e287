#!/usr/bin/env python3
"""The figure of docs/indentation.md's "The seed's window on the seed's bed": the hardness F/A(h) against
h/r on the three shipped quarter beds and the whole beds, and the two windows' means against gamma*.

Reads the runs `benches/indentation_window.sh` wrote (docs/data/ch6_indentation/window/<bed>_g<gamma*>.csv)
and writes docs/figures/indentation_window.png. Left: F/A(h) of the loading rows, averaged in bins of 0.01
h/r, for the quarter beds at gamma* 0.01 and 0.04 and the whole beds at 0.01 (whole<N>_g0.01.csv, as
many as there are), with the window of the default until 2026-12-06 (0.1-0.2) and the seed's (0.35-0.5) shaded. Right: each
window's mean over the three quarter beds against gamma*, the bars their bed-to-bed standard deviation
(n - 1), each whole bed's reading beside them.

    .venv/bin/python benches/plot_indentation_window.py [DIR] [OUT.png]
"""

import statistics
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from indentation_rate import load, summary  # noqa: E402  (the window mean of every indentation bench)

REPO = Path(__file__).resolve().parent.parent
GAMMAS = ["0.01", "0.02", "0.04", "0.08"]
WINDOWS = {"earlier default's window, h/r 0.1-0.2": (0.1, 0.2), "seed's window, h/r 0.35-0.5": (0.35, 0.5)}


def binned(rows, width=0.01):
    """(h/r, mean F/A(h)) of the loading rows in bins of `width` in h/r."""
    bins = {}
    for r in rows:
        if r["state"] == 0 and r["depth_over_r"] > 0.02:
            bins.setdefault(int(r["depth_over_r"] / width), []).append(r["hardness_Pa"])
    keys = sorted(bins)
    return [(k + 0.5) * width for k in keys], [statistics.fmean(bins[k]) / 1e3 for k in keys]


def main(folder, out):
    runs = {p.stem: load(p) for p in sorted(folder.glob("*_g*.csv"))}
    quarters = sorted({name.split("_g")[0] for name in runs if name.startswith("quarter")})
    if len(quarters) < 2 or not all(f"{q}_g{g}" in runs for q in quarters for g in GAMMAS):
        sys.exit(f"{folder}: expected quarter<N>_g<gamma*>.csv for gamma* {', '.join(GAMMAS)} on at least two beds")
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.8))
    for lo, hi in WINDOWS.values():
        ax.axvspan(lo, hi, color="0.92", zorder=0)
    for gamma, colour in [("0.01", "tab:blue"), ("0.04", "tab:orange")]:
        for k, q in enumerate(quarters):
            x, y = binned(runs[f"{q}_g{gamma}"])
            ax.plot(x, y, color=colour, lw=0.9, alpha=0.8, label=f"quarter beds, gamma* {gamma}" if k == 0 else None)
    wholes = sorted(name for name in runs if name.startswith("whole") and name.endswith("_g0.01"))
    for k, name in enumerate(wholes):
        x, y = binned(runs[name])
        ax.plot(x, y, color="black", lw=1.4, ls=["-", "--", ":"][k % 3], label=f"whole bed {name[5:-6]}, gamma* 0.01")
    ax.set_xlabel("h / r [-] (depth from the first touch)")
    ax.set_ylabel("F / A(h) [kPa] (mean over bins of 0.01 h/r)")
    ax.set_xlim(0.0, 0.5)
    ax.set_ylim(0.0, 16.0)
    ax.text(0.15, 15.2, "until 2026-12-06", ha="center", fontsize=9)
    ax.text(0.425, 15.2, "seed's window (default)", ha="center", fontsize=9)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title("16 mm indenter on the 004 Ch. 6 bed, 2.5e-7 s, every sphere moving", fontsize=10)
    x = [float(g) for g in GAMMAS]
    for (label, window), marker in zip(WINDOWS.items(), ["o", "s"]):
        means, sds = [], []
        for g in GAMMAS:
            column = [summary(runs[f"{q}_g{g}"], window)["plateau"] / 1e3 for q in quarters]
            means.append(statistics.fmean(column))
            sds.append(statistics.stdev(column))
        bx.errorbar(x, means, yerr=sds, marker=marker, capsize=4, label=f"{label}: {len(quarters)} quarter beds, mean +- SD")
        if wholes:
            readings = [summary(runs[name], window)["plateau"] / 1e3 for name in wholes]
            bx.plot([0.01] * len(readings), readings, marker=marker, color="black", ls="none", mfc="none", ms=9,
                    label=f"{label.split(',')[0]}: whole beds {', '.join(name[5:-6] for name in wholes)}")
    bx.set_xscale("log")
    bx.set_xticks(x, GAMMAS)
    bx.minorticks_off()
    bx.set_xlabel("gamma* = v / sqrt(g d) [-] (004 Eq. 5.6)")
    bx.set_ylabel("window mean of F / A(h) [kPa]")
    bx.set_ylim(0.0, 12.0)
    bx.legend(loc="lower left", fontsize=8)
    bx.set_title("The seed's window reads the same from gamma* 0.01 to 0.04", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    folder = Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "docs" / "data" / "ch6_indentation" / "window"
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else REPO / "docs" / "figures" / "indentation_window.png"
    main(folder, out)
