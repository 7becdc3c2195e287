"""The spread of the indentation over independently prepared beds of the seed's Ch. 6 scene (fill seeds
1, 2, 3...): for each bed, the plateau hardness of the default test and of the run at the seed's speed,
and across the beds their mean, spread and the default's error against each bed's own reference.

Reads a CSV (columns seed, file, gamma, time_step_s, fidelity, wall_s, note) whose `file`s are
`powderfmu bed indent ... --every 1e-4 --out FILE` records relative to the table's folder; a row with
gamma 0.01 is its bed's reference, the others are compared with it.

    python benches/indentation_beds.py docs/data/ch6_indentation/beds.csv
"""

import argparse
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from indentation_work_precision import read_runs  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("table")
    a = p.parse_args()
    runs = read_runs(a.table)
    seeds = sorted({r["seed"] for r in runs}, key=int)
    refs = {s: next((r for r in runs if r["seed"] == s and float(r["gamma"]) == 0.01), None) for s in seeds}
    print("| bed (fill seed) | gamma* | time step [s] | fidelity | wall time [s] | plateau hardness [Pa] | fluctuation [Pa] | against the bed's gamma* 0.01 | note |")
    print("|---:|---:|---:|---|---:|---:|---:|---:|---|")
    for r in sorted(runs, key=lambda r: (int(r["seed"]), float(r["gamma"]), float(r["time_step_s"]))):
        ref = refs[r["seed"]]
        err = f"{100 * (r['plateau'] / ref['plateau'] - 1):+.1f} %" if ref is not None and ref is not r else ("reference" if ref is r else "")
        print(f"| {r['seed']} | {float(r['gamma']):g} | {float(r['time_step_s']):.2g} | {r['fidelity']} | {float(r['wall_s']):.0f} |"
              f" {r['plateau']:.0f} | {r['spread']:.0f} | {err} | {r['note']} |")
    print()
    groups = sorted({(float(r["gamma"]), float(r["time_step_s"]), r["fidelity"]) for r in runs})
    print("| gamma* | time step [s] | fidelity | beds | mean plateau [Pa] | standard deviation over beds [Pa] | range [Pa] |")
    print("|---:|---:|---|---:|---:|---:|---:|")
    for g in groups:
        vals = [r["plateau"] for r in runs if (float(r["gamma"]), float(r["time_step_s"]), r["fidelity"]) == g]
        sd = statistics.stdev(vals) if len(vals) > 1 else float("nan")
        print(f"| {g[0]:g} | {g[1]:.2g} | {g[2]} | {len(vals)} | {statistics.fmean(vals):.0f} | {sd:.0f} ({100 * sd / statistics.fmean(vals):.1f} %) |"
              f" {min(vals):.0f}-{max(vals):.0f} |")


if __name__ == "__main__":
    main()
