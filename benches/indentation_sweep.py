"""Hardness and bin stresses against one property of the bed or the indenter (004 Secs. 6.2-6.3).

Each run is a CSV of `powderfmu bed indent ... --out FILE`, given as VALUE=FILE. Prints per value the
plateau hardness (mean F/A(h) while loading at 0.1 <= h/r <= 0.2), its spread, F_max/A(h_c) and the mean
hydrostatic and deviatoric stress of the dynamic bin over the same depths; with --plot, a figure.

    python benches/indentation_sweep.py --parameter "sliding friction" 0.05=a.csv 0.15=b.csv --plot f.png
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from indentation_rate import load, summary  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--parameter", required=True, help="what VALUE is (for the table and the axis)")
    p.add_argument("--plot")
    p.add_argument("runs", nargs="+", metavar="VALUE=CSV")
    a = p.parse_args()
    rows = []
    for spec in a.runs:
        value, path = spec.split("=", 1)
        rows.append((float(value), summary(load(path))))
    rows.sort(key=lambda r: r[0])
    print(f"| {a.parameter} | plateau hardness [Pa] | spread [Pa] | F_max/A(h_c) [Pa] | hydrostatic [Pa] | deviatoric [Pa] |")
    print("|---:|---:|---:|---:|---:|---:|")
    for value, s in rows:
        print(f"| {value:g} | {s['plateau']:.4g} | {s['spread']:.3g} | {s['tangent']:.4g} | {s['hydrostatic']:.4g} | {s['deviatoric']:.4g} |")
    if a.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(5.5, 4))
        x = [v for v, _ in rows]
        ax.errorbar(x, [s["plateau"] for _, s in rows], yerr=[s["spread"] for _, s in rows], marker="o", capsize=3, label="hardness (plateau)")
        ax.plot(x, [s["hydrostatic"] for _, s in rows], "s-", label="hydrostatic stress, dynamic bin")
        ax.plot(x, [s["deviatoric"] for _, s in rows], "^-", label="deviatoric stress, dynamic bin")
        ax.set(xlabel=a.parameter, ylabel="[Pa]")
        ax.legend(fontsize=8)
        ax.grid(True, alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=110)
        print(f"figure: {a.plot}")


if __name__ == "__main__":
    main()
