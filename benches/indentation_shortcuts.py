"""The indentation's work-precision table and figure from benches/indentation_shortcuts.sh's runs.

For each speed (gamma*) and mobile zone (full, or m contact radii): the CPU time of the run (median over
the beds) and the error of the plateau hardness (mean F/A(h) while loading at 0.1 <= h/r <= 0.2) and of
F_max/A(h_c) against the same bed's reference, the full run at gamma* = 0.01, as the mean and the largest
over the three beds. The beds' own spread (of the reference plateau) is printed beside it: a shortcut
whose error is below it changes the answer less than preparing the bed again does.

    python benches/indentation_shortcuts.py OUT_DIR [--plot FIGURE.png]
"""

import argparse
import math
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from indentation_rate import load, summary  # noqa: E402

GAMMAS = ["0.01", "0.05", "0.2"]
# The runs: full; held beyond m a_max and never released ("m"); released at E sigma_c d^2 ("mrE");
# full with a 1 % shorter time step ("fulldt", the noise floor).
ZONES = ["full", "fulldt", "4", "3", "2", "3r0.1", "2r0.1", "3r0.01", "2r0.01"]


def label(z):
    if z == "full":
        return "full"
    if z == "fulldt":
        return "full, time step -1 %"
    if "r" in z:
        m, e = z.split("r")
        return f"{m} a_max, released at {e}"
    return f"{z} a_max, never released"



def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out", help="the runs' folder")
    p.add_argument("--plot", help="write the work-precision figure here")
    a = p.parse_args()
    out = Path(a.out)
    seeds = sorted({f.name.split("_")[0] for f in out.glob("seed*_g*.csv")})
    runs = {}
    for seed in seeds:
        for g in GAMMAS:
            for z in ZONES:
                # (Not with_suffix: the speed's decimal point would be read as the suffix.)
                csv, cpu = out / f"{seed}_g{g}_{z}.csv", out / f"{seed}_g{g}_{z}.cpu"
                if csv.exists():
                    s = summary(load(csv))
                    s["cpu"] = float(cpu.read_text().split()[-1])
                    runs[seed, g, z] = s
    refs = {s: runs[s, "0.01", "full"] for s in seeds if (s, "0.01", "full") in runs}
    plateaus = [r["plateau"] for r in refs.values()]
    print(f"beds: {len(refs)}; reference plateau hardness (full, gamma* = 0.01): "
          + ", ".join(f"{x:.0f}" for x in plateaus) + " Pa"
          + (f"; spread (max - min) / mean {100 * (max(plateaus) - min(plateaus)) / statistics.fmean(plateaus):.1f} %" if len(plateaus) > 1 else ""))
    print()
    print("| gamma* | run | CPU time [s] (median) | plateau error mean / max [%] | F_max/A(h_c) error mean / max [%] |")
    print("|---:|---:|---:|---:|---:|")
    points = []
    for g in GAMMAS:
        for z in ZONES:
            have = [s for s in refs if (s, g, z) in runs]
            if not have:
                continue
            cpu = statistics.median(runs[s, g, z]["cpu"] for s in have)
            ep = [100 * abs(runs[s, g, z]["plateau"] / refs[s]["plateau"] - 1) for s in have]
            et = [100 * abs(runs[s, g, z]["tangent"] / refs[s]["tangent"] - 1) for s in have]
            zone = label(z)
            print(f"| {g} | {zone} | {cpu:.1f} | {statistics.fmean(ep):.2f} / {max(ep):.2f} | {statistics.fmean(et):.2f} / {max(et):.2f} |")
            points.append((g, z, cpu, statistics.fmean(ep), min(ep), max(ep)))
    if a.plot and points:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        markers = {"full": "o", "fulldt": "x", "4": "s", "3": "^", "2": "v", "3r0.1": "<", "2r0.1": ">", "3r0.01": "P", "2r0.01": "X"}
        colors = {"0.01": "tab:blue", "0.05": "tab:orange", "0.2": "tab:red"}
        for g, z, cpu, mean, lo, hi in points:
            if (g, z) == ("0.01", "full"):
                continue  # the reference itself
            y = max(mean, 0.01)
            ax.errorbar(cpu, y, yerr=[[y - max(lo, 0.01)], [max(hi - y, 0)]], fmt=markers[z], color=colors[g], capsize=3)
        for g, c in colors.items():
            ax.plot([], [], "s", color=c, label=f"gamma* = {g}")
        for z, m in markers.items():
            ax.plot([], [], m, color="grey", label=label(z))
        ax.axhline(5, color="k", lw=0.8, ls="--")
        ax.text(ax.get_xlim()[0] if False else min(p[2] for p in points), 5.3, "5 %", fontsize=8)
        if len(plateaus) > 1:
            ax.axhline(100 * (max(plateaus) - min(plateaus)) / statistics.fmean(plateaus), color="grey", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("CPU time of the test [s], one thread")
        ax.set_ylabel("plateau hardness error vs full at gamma* = 0.01 [%]")
        ax.set_title("Indentation work-precision (3 beds; bars: min-max; dotted: bed-to-bed spread)", fontsize=9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=130)
        print(f"\nfigure: {a.plot}")


if __name__ == "__main__":
    main()
