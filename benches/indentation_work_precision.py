"""Work against precision of the ball indentation on one bed: plateau hardness error against wall time.

Reads a table of runs (CSV with columns file, gamma, time_step_s, fidelity, wall_s, note), each `file` a
`powderfmu bed indent ... --every 1e-4 --out FILE` record relative to the table's folder. The reference
is the row whose `note` starts with `reference` (full fidelity at the slowest speed). For every run it prints the
plateau hardness (mean F/A(h) while loading at 0.1 <= h/r <= 0.2, 004 Figs. 5.2-5.3), its error against
the reference, and the wall time; with --plot, a figure of the error against wall time, one marker per
shortcut (time step, fidelity) and the speed written beside each point, the error signed.

    python benches/indentation_work_precision.py docs/data/ch6_indentation/runs.csv \\
        --plot docs/figures/indentation_work_precision_ch6.png
"""

import argparse
import csv
import math
import os
import statistics


def plateau(path, window=(0.1, 0.2)):
    with open(path) as f:
        h = [float(r["hardness_Pa"]) for r in csv.DictReader(f) if r["state"] == "0" and window[0] <= float(r["depth_over_r"]) <= window[1]]
    if not h:
        raise SystemExit(f"{path}: no loading rows at {window[0]} <= h/r <= {window[1]}")
    return statistics.fmean(h), statistics.pstdev(h)


def read_runs(table):
    """The rows of a table of runs, each with the plateau hardness and its fluctuation of its `file`
    (relative to the table's folder)."""
    folder = os.path.dirname(os.path.abspath(table))
    with open(table) as f:
        runs = list(csv.DictReader(f))
    for r in runs:
        r["plateau"], r["spread"] = plateau(os.path.join(folder, r["file"]))
    return runs


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("table", help="CSV: file, gamma, time_step_s, fidelity, wall_s, note")
    p.add_argument("--plot", help="write the figure here (PNG)")
    a = p.parse_args()
    runs = read_runs(a.table)
    refs = [r for r in runs if r["note"].startswith("reference")]
    if len(refs) != 1:
        raise SystemExit(f"{a.table}: mark exactly one run `reference` in `note` (found {len(refs)})")
    ref = refs[0]["plateau"]
    print("| gamma* | time step [s] | fidelity | wall time [s] | plateau hardness [Pa] | spread [Pa] | error against the reference | note |")
    print("|---:|---:|---|---:|---:|---:|---:|---|")
    for r in sorted(runs, key=lambda r: (float(r["gamma"]), float(r["time_step_s"]), r["fidelity"])):
        r["error"] = (r["plateau"] - ref) / ref
        print(f"| {float(r['gamma']):g} | {float(r['time_step_s']):.2g} | {r['fidelity']} | {float(r['wall_s']):.0f} | {r['plateau']:.0f} |"
              f" {r['spread']:.0f} | {100 * r['error']:+.1f} % | {r['note']} |")
    if a.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7.5, 4.8))
        groups = sorted({(float(r["time_step_s"]), r["fidelity"]) for r in runs})
        for k, (dt, fid) in enumerate(groups):
            pts = sorted((float(r["wall_s"]), r["error"], float(r["gamma"])) for r in runs if (float(r["time_step_s"]), r["fidelity"]) == (dt, fid))
            ax.plot([x[0] for x in pts], [100 * x[1] for x in pts], marker="osD^"[k % 4], ls="-", label=f"time step {dt:.4g} s, {fid}")
            for w, e, g in pts:
                ax.annotate(f"{g:g}", (w, 100 * e), textcoords="offset points", xytext=(4, 3), fontsize=7)
        ax.axhspan(-5, 5, color="C2", alpha=0.12, label="within 5 % of the reference")
        ax.axvline(120, color="0.5", ls=":", lw=1, label="2 minutes")
        ax.set(xscale="log", xlabel="wall time of the whole test, two threads [s]",
               ylabel="plateau hardness against the reference [%]",
               title=f"work against precision (labels: gamma*); reference {ref:.0f} Pa")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
        fig.tight_layout()
        fig.savefig(a.plot, dpi=110)
        print(f"\nfigure: {a.plot}")


if __name__ == "__main__":
    main()
