"""Rate dependence of the ball indentation: hardness against h/r for several indentation speeds.

Reads the CSV files `powderfmu bed indent ... --out FILE` writes, one per speed, and prints for each the
plateau hardness (mean of F/A(h) over loading at 0.1 <= h/r <= 0.2, 004 Figs. 5.2-5.3), its spread (the
standard deviation of the same samples), the tangent hardness F_max/A(h_c) (last row) and the mean
hydrostatic and deviatoric stress of the dynamic bin over the same depths; with --plot, a figure of
hardness against h/r.

    python benches/indentation_rate.py --bed-height 0.013 --diameter 0.001 OUT.png g0.01.csv g0.05.csv ...

gamma* = (v / bed height) (d / g)^(1/2) (004 Eq. 7.1 with the strain rate read as v / bed height).
"""

import argparse
import csv
import math
import statistics


def load(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def summary(rows, plateau=(0.1, 0.2)):
    loading = [r for r in rows if r["state"] == 0 and plateau[0] <= r["depth_over_r"] <= plateau[1]]
    h = [r["hardness_Pa"] for r in loading]
    hyd = [r["hydrostatic_Pa"] for r in loading]
    dev = [r["deviatoric_Pa"] for r in loading]
    last = rows[-1]
    return {
        "plateau": statistics.fmean(h) if h else math.nan,
        "spread": statistics.pstdev(h) if len(h) > 1 else math.nan,
        "tangent": last["hardness_Pa"] if last["state"] == 2 else math.nan,
        "hydrostatic": statistics.fmean(hyd) if hyd else math.nan,
        "deviatoric": statistics.fmean(dev) if dev else math.nan,
        "samples": len(h),
    }


def speed(rows):
    """The loading speed [m/s] from the depth record."""
    loading = [r for r in rows if r["state"] == 0]
    a, b = loading[len(loading) // 4], loading[-1]
    return (b["depth_m"] - a["depth_m"]) / (b["time_s"] - a["time_s"])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--bed-height", type=float, required=True, help="bed height [m]")
    p.add_argument("--diameter", type=float, required=True, help="mean particle diameter [m]")
    p.add_argument("--plot", help="write a figure of hardness against h/r here")
    p.add_argument("csv", nargs="+")
    a = p.parse_args()
    runs = []
    for path in a.csv:
        rows = load(path)
        v = speed(rows)
        gamma = v / a.bed_height * math.sqrt(a.diameter / 9.81)
        runs.append((gamma, v, path, rows, summary(rows)))
    runs.sort()
    print("| gamma* | speed [m/s] | plateau hardness [Pa] (0.1 <= h/r <= 0.2) | spread [Pa] | F_max/A(h_c) [Pa] | hydrostatic [Pa] | deviatoric [Pa] |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for gamma, v, path, rows, s in runs:
        print(f"| {gamma:.3g} | {v:.3g} | {s['plateau']:.4g} | {s['spread']:.3g} | {s['tangent']:.4g} | {s['hydrostatic']:.4g} | {s['deviatoric']:.4g} |")
    if a.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6, 4))
        for gamma, v, path, rows, s in runs:
            loading = [r for r in rows if r["state"] == 0 and r["depth_over_r"] > 0.02]
            ax.plot([r["depth_over_r"] for r in loading], [r["hardness_Pa"] for r in loading], label=f"gamma* = {gamma:.3g}")
        ax.set_xlabel("dimensionless penetration h/r [-]")
        ax.set_ylabel("hardness F/A(h) [Pa]")
        ax.set_yscale("log")
        ax.legend()
        ax.grid(True, alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
        print(f"figure: {a.plot}")


if __name__ == "__main__":
    main()
