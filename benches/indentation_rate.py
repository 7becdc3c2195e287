"""Rate dependence of the ball indentation: hardness against indentation speed, for one or more beds.

Reads the CSV files `powderfmu bed indent BED --speed V ... --out FILE` writes (one per speed) and prints,
per bed and speed, the plateau hardness (mean of F/A(h) while loading at 0.1 <= h/r <= 0.2, 004 Figs.
5.2-5.3) with its spread (standard deviation of the same samples), F_max/A(h_c), the mean hydrostatic and
deviatoric stress of the dynamic bin over the same depths, and two dimensionless rates:

- gamma* = (v / H) (d / g)^(1/2), 004 Eq. 7.1 with the strain rate read as v over the bed height H;
- I = (v / H) d / (P / rho)^(1/2), the inertial number of dense granular flow (GDR MiDi 2004), with the
  stress scale P the bed's quasi-static hardness (the plateau at the slowest speed) and rho the solid
  density.

    python benches/indentation_rate.py --diameter 0.001 --density 2456 \\
        --bed hertz 0.0124 hertz_g*.csv --bed jkr 0.0130 jkr_g*.csv --plot rate.png
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
    last = rows[-1]
    return {
        "plateau": statistics.fmean(h) if h else math.nan,
        "spread": statistics.pstdev(h) if len(h) > 1 else math.nan,
        "tangent": last["hardness_Pa"] if last["state"] == 2 else math.nan,
        "hydrostatic": statistics.fmean(r["hydrostatic_Pa"] for r in loading) if loading else math.nan,
        "deviatoric": statistics.fmean(r["deviatoric_Pa"] for r in loading) if loading else math.nan,
    }


def speed(rows):
    """The loading speed [m/s] from the depth record."""
    loading = [r for r in rows if r["state"] == 0]
    a, b = loading[len(loading) // 4], loading[-1]
    return (b["depth_m"] - a["depth_m"]) / (b["time_s"] - a["time_s"])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--diameter", type=float, required=True, help="mean particle diameter d [m]")
    p.add_argument("--density", type=float, required=True, help="solid density rho [kg/m^3]")
    p.add_argument("--bed", nargs="+", action="append", required=True, metavar=("LABEL HEIGHT", "CSV"),
                   help="a bed: its label, its height H [m], and its CSV files")
    p.add_argument("--plot", help="write a figure of hardness (relative to the slowest) against gamma* and I")
    a = p.parse_args()
    beds = []
    for spec in a.bed:
        label, height, files = spec[0], float(spec[1]), spec[2:]
        runs = []
        for path in files:
            rows = load(path)
            v = speed(rows)
            runs.append({"v": v, "rate": v / height, "path": path, "rows": rows, **summary(rows)})
        runs.sort(key=lambda r: r["v"])
        p_qs = runs[0]["plateau"]
        for r in runs:
            r["gamma"] = r["rate"] * math.sqrt(a.diameter / 9.81)
            r["inertial"] = r["rate"] * a.diameter / math.sqrt(p_qs / a.density)
            r["ratio"] = r["plateau"] / p_qs
        beds.append((label, height, runs))
        print(f"\n{label} (H = {height * 1e3:.2f} mm):\n")
        print("| gamma* | I | speed [m/s] | plateau hardness [Pa] | spread [Pa] | / slowest | F_max/A(h_c) [Pa] | hydrostatic [Pa] | deviatoric [Pa] |")
        print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for r in runs:
            print(f"| {r['gamma']:.3g} | {r['inertial']:.3g} | {r['v']:.3g} | {r['plateau']:.4g} | {r['spread']:.3g} | {r['ratio']:.3f} |"
                  f" {r['tangent']:.4g} | {r['hydrostatic']:.4g} | {r['deviatoric']:.4g} |")
    if a.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
        for k, (label, height, runs) in enumerate(beds):
            for r in runs:
                loading = [x for x in r["rows"] if x["state"] == 0 and x["depth_over_r"] > 0.02]
                if k == 0:
                    ax[0].plot([x["depth_over_r"] for x in loading], [x["hardness_Pa"] for x in loading], lw=1, label=f"gamma* = {r['gamma']:.2g}")
            err = [r["spread"] / r["plateau"] * r["ratio"] for r in runs]
            ax[1].errorbar([r["gamma"] for r in runs], [r["ratio"] for r in runs], yerr=err, marker="o", capsize=3, label=label)
            ax[2].errorbar([r["inertial"] for r in runs], [r["ratio"] for r in runs], yerr=err, marker="o", capsize=3, label=label)
        ax[0].set(xlabel="h / r [-]", ylabel="F / A(h) [Pa]", yscale="log", title=f"{beds[0][0]}: hardness while loading")
        ax[0].legend(fontsize=7)
        ax[1].set(xlabel="gamma* = (v/H)(d/g)^1/2 [-]", ylabel="plateau hardness / slowest [-]", xscale="log", yscale="log", title="against 004 Eq. 7.1")
        ax[2].set(xlabel="I = (v/H) d / (H_qs/rho)^1/2 [-]", ylabel="plateau hardness / slowest [-]", xscale="log", yscale="log", title="against the inertial number")
        for x in ax[1:]:
            x.axhline(1.05, color="0.5", ls=":", lw=1)
            x.legend(fontsize=8)
            x.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=110)
        print(f"\nfigure: {a.plot}")


if __name__ == "__main__":
    main()
