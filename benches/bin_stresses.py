#!/usr/bin/env python3
"""The dynamic bin's stresses in the seed's window, over the recorded runs on the seed's bed.

004 reads the hydrostatic and deviatoric stresses of a bin 5.2 x 5.2 x 4.2 mm under the indenter, moving
with it (Sec. 5.3, Fig. 5.18; Eqs. 5.2-5.3), as levels over the depth where the hardness is level (Fig.
5.19) and as means with the fluctuations' standard deviation against gamma* (Figs. 7.3-7.5). BallIndentation
gives the same levels as `plateau_hydrostatic_stress` and `plateau_deviatoric_stress`. This reads the
rows of the runs in docs/data/ch6_indentation/window (every 1e-4 s, every fourth of the unit's samples)
and writes, per run and per setting (bed size and gamma*), the window means of the hardness and both
stresses, the rows' standard deviation (the fluctuations, as 004's error bars), the ratios H / sigma_hyd
and tau_D / sigma_hyd, and per setting the mean over beds with its standard error from their spread.

    .venv/bin/python benches/bin_stresses.py --csv docs/data/bin_stresses_ch6.csv
"""

import argparse
import csv
import math
import re
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from indentation_rate import load  # noqa: E402  (a `bed indent --out` CSV as rows of floats)

ROOT = Path(__file__).resolve().parent.parent
RUNS = ROOT / "docs" / "data" / "ch6_indentation" / "window"
WINDOW = (0.35, 0.5)


def window_rows(path):
    return [r for r in load(path) if r["state"] == 0 and WINDOW[0] <= r["depth_over_r"] <= WINDOW[1]]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csv", help="write the table here")
    a = p.parse_args()
    runs = []
    for path in sorted(RUNS.glob("*_g*.csv")):
        m = re.fullmatch(r"(quarter|whole)(\d)_g([0-9.]+)", path.stem)
        if not m:
            continue
        rows = window_rows(path)
        if len(rows) < 10:
            raise SystemExit(f"{path}: {len(rows)} rows in h/r {WINDOW[0]}-{WINDOW[1]}: the run did not reach the window")
        col = {k: [r[k] for r in rows] for k in ["hardness_Pa", "hydrostatic_Pa", "deviatoric_Pa"]}
        mean = {k: statistics.fmean(v) for k, v in col.items()}
        runs.append({
            "bed": m[1], "fill": int(m[2]), "gamma_star": float(m[3]), "rows": len(rows),
            "hardness_Pa": mean["hardness_Pa"],
            "hydrostatic_Pa": mean["hydrostatic_Pa"], "hydrostatic_fluctuation_sd_Pa": statistics.stdev(col["hydrostatic_Pa"]),
            "deviatoric_Pa": mean["deviatoric_Pa"], "deviatoric_fluctuation_sd_Pa": statistics.stdev(col["deviatoric_Pa"]),
            "hardness_over_hydrostatic": mean["hardness_Pa"] / mean["hydrostatic_Pa"],
            "deviatoric_over_hydrostatic": mean["deviatoric_Pa"] / mean["hydrostatic_Pa"],
        })
    settings = sorted({(r["bed"], r["gamma_star"]) for r in runs}, key=lambda s: (s[0] != "whole", s[1]))
    table = []
    for bed, g in settings:
        group = [r for r in runs if (r["bed"], r["gamma_star"]) == (bed, g)]
        n = len(group)
        row = {"bed": bed, "fill": "mean", "gamma_star": g, "rows": sum(r["rows"] for r in group)}
        for k in ["hardness_Pa", "hydrostatic_Pa", "hydrostatic_fluctuation_sd_Pa", "deviatoric_Pa", "deviatoric_fluctuation_sd_Pa", "hardness_over_hydrostatic", "deviatoric_over_hydrostatic"]:
            row[k] = statistics.fmean(r[k] for r in group)
        for k in ["hydrostatic_Pa", "deviatoric_Pa"]:
            row[k.replace("_Pa", "_standard_error_over_beds_Pa")] = statistics.stdev(r[k] for r in group) / math.sqrt(n) if n > 1 else float("nan")
        table += group + [row]
    fields = list(table[-1].keys())
    print(f"{'run':<22} {'H':>6} {'sigma_hyd':>10} {'(SD)':>6} {'tau_D':>6} {'(SD)':>6} {'H/s_hyd':>8} {'tau/s_hyd':>9}  [Pa]")
    for r in table:
        name = f"{r['bed']} {r['fill']} g* {r['gamma_star']}"
        err = f" +- {r['hydrostatic_standard_error_over_beds_Pa']:.0f}, +- {r['deviatoric_standard_error_over_beds_Pa']:.0f} over beds" if r["fill"] == "mean" else ""
        print(f"{name:<22} {r['hardness_Pa']:6.0f} {r['hydrostatic_Pa']:10.0f} {r['hydrostatic_fluctuation_sd_Pa']:6.0f} {r['deviatoric_Pa']:6.0f} "
              f"{r['deviatoric_fluctuation_sd_Pa']:6.0f} {r['hardness_over_hydrostatic']:8.3f} {r['deviatoric_over_hydrostatic']:9.3f}{err}")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            f.write(f"# The dynamic bin's stresses (004 Eqs. 5.2-5.3, Sec. 5.3) over h/r {WINDOW[0]}-{WINDOW[1]} while loading, from the rows (every 1e-4 s) of the runs in\n")
            f.write("# docs/data/ch6_indentation/window; _fluctuation_sd the rows' standard deviation (004 Figs. 7.3-7.5's error bars); per setting the mean over beds with\n")
            f.write("# the standard error from their spread. Written by benches/bin_stresses.py (docs/indentation.md).\n")
            w = csv.DictWriter(f, fieldnames=fields, restval="")
            w.writeheader()
            for r in table:
                w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
        print(f"wrote {a.csv}")


if __name__ == "__main__":
    main()
