"""The flow function from unconfined compression tests (`powderfmu bed compress`, 004 Sec. 2.1, Eq. 2.1):
sigma_c against the consolidation stress sigma_1, with Jenike's flowability classes (004 Table 2.1: ff_c =
sigma_1 / sigma_c of 1, 2, 4 and 10 as lines), beside the stress-strain curves. Each test is given as
SIGMA_1_PA=CSV; sigma_c is the largest mean over --window strain (as `bed compress` reads it).

    python benches/flow_function.py --window 0.0005 --plot docs/figures/flow_function_ch6.png --csv docs/data/flow_function_ch6.csv \\
        3000=uct_3000.csv 10000=uct_10000.csv 20000=uct_20000.csv
"""

import argparse
import csv
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import compression_curves  # noqa: E402 (the window reading, shared)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--window", type=float, default=0.005)
    p.add_argument("--plot", required=True)
    p.add_argument("--csv")
    p.add_argument("tests", nargs="+", help="SIGMA_1_PA=CSV")
    a = p.parse_args()
    compression_curves.WINDOW = a.window
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(12, 5))
    points = []
    for k, item in enumerate(a.tests):
        s1, path = item.split("=", 1)
        s1 = float(s1)
        e, s = compression_curves.read(path)
        pe, ps = compression_curves.peak(e, s)
        points.append((s1, ps, pe))
        ax[0].plot([100 * x for x in e], s, lw=1, color=f"C{k}", label=f"sigma_1 = {s1 / 1e3:g} kPa: sigma_c {ps:.0f} Pa at {100 * pe:.2f} %")
        ax[0].plot([100 * pe], [ps], "o", color=f"C{k}")
    ax[0].set(xlabel="axial strain [%]", ylabel="platen stress [Pa]", title="stress-strain curves")
    ax[0].legend(fontsize=8)
    top = 1.2 * max(p[0] for p in points)
    ymax = 2.5 * max(p[1] for p in points)
    for ff in (1, 2, 4, 10):
        ax[1].plot([0, top / 1e3], [0, top / ff / 1e3], color="0.7", lw=0.8, ls="--")
        x_end = min(top, ff * ymax)
        ax[1].annotate(f"ff_c = {ff}", (0.97 * x_end / 1e3, 0.97 * x_end / ff / 1e3), fontsize=7, color="0.4", ha="right", va="top")
    ax[1].plot([p[0] / 1e3 for p in points], [p[1] / 1e3 for p in points], "o-", color="C3")
    ax[1].set(xlabel="sigma_1, consolidation stress [kPa]", ylabel="sigma_c, unconfined yield strength [kPa]", title="flow function",
              xlim=(0, top / 1e3), ylim=(0, ymax / 1e3))
    for axis in ax:
        axis.grid(alpha=0.3)
    fig.suptitle(f"Unconfined compression of 004 Ch. 6's material (scenes/uct_004_ch6.json), sigma_c as the largest {a.window:g}-strain mean")
    fig.tight_layout()
    fig.savefig(a.plot, dpi=110)
    print(f"wrote {a.plot}")
    for s1, ps, pe in points:
        print(f"sigma_1 {s1:8.0f} Pa  sigma_c {ps:7.1f} Pa at strain {pe:.4f}  ff_c {s1 / ps:.2f}")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["consolidation_stress_Pa", "unconfined_yield_strength_Pa", "strain_at_peak", "flow_function"])
            for s1, ps, pe in points:
                w.writerow([f"{s1:.6g}", f"{ps:.6g}", f"{pe:.6g}", f"{s1 / ps:.6g}"])


if __name__ == "__main__":
    main()
