"""The reference of record in the seed's window, and the hardness after unloading against the plateau
there, from the runs to h/r 0.5 in docs/data/ch6_indentation/window (`benches/indentation_window.sh`:
`powderfmu bed indent` CSVs, a row every 1e-4 s, the 16 mm indenter, 2.5e-7 s steps, every sphere moving).

- Each run: the plateau, the mean of F/A(h) over the loading rows at 0.35 <= h/r <= 0.5, with its standard
  error from the rows' autocorrelation (benches/indentation_outputs.py's estimator, the unit's); and the
  hardness after unloading as the unit reads it where the unloading gives no tangent (every run here):
  A(h_max) times the mean F/A over the last tenth of the loading depth, over A(h_max); its deviation from
  the plateau in per cent. In this window the turn lies at the window's deep end.
- The reference of record: the whole beds at the seed's speed (wholeK_g0.01.csv, K = 1, 2, 3: fills 1-3 of
  scenes/bed_004_ch6.json), each with its own error, and their mean with the standard error from their
  spread (`--reference` writes it in the format docs/data/reference_of_record_h0.1-0.2.csv has).

    .venv/bin/python benches/reference_of_record.py [--reference docs/data/reference_of_record.csv]
"""

import argparse
import csv
import math
import statistics
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from indentation_outputs import D, TURN_FIT, area, mean_with_error  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
RUNS = REPO / "docs" / "data" / "ch6_indentation" / "window"
WINDOW = (0.35, 0.5)


def analyse(path):
    """(plateau, its standard error, hardness after unloading) [Pa] of one run."""
    rows = [r for r in csv.DictReader(open(path)) if r["state"] == "0"]
    if not rows:
        sys.exit(f"{path}: no loading rows (state 0)")
    h = np.array([float(r["depth_m"]) for r in rows])
    f = np.array([float(r["force_N"]) for r in rows])
    win = (h / (D / 2) >= WINDOW[0]) & (h / (D / 2) <= WINDOW[1])
    if win.sum() < 10:
        sys.exit(f"{path}: {win.sum()} loading rows at {WINDOW[0]} <= h/r <= {WINDOW[1]}; the run must reach h/r 0.5")
    mean, se, _ = mean_with_error(f[win] / area(h[win]))
    tail = h >= (1 - TURN_FIT) * h.max()
    hardness = float(np.mean(f[tail] / area(h[tail])))
    return mean, se, hardness


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--reference", type=Path, help="write the reference of record here")
    args = ap.parse_args()
    runs = sorted(RUNS.glob("*_g*.csv"))
    if not runs:
        sys.exit(f"no runs in {RUNS}: bash benches/indentation_window.sh {RUNS}")
    print(f"| run | plateau, h/r {WINDOW[0]}-{WINDOW[1]} [Pa] | hardness after unloading [Pa] | against the plateau |")
    print("|---|---:|---:|---:|")
    read, bias = {}, []
    for path in runs:
        mean, se, hardness = analyse(path)
        read[path.name] = (mean, se)
        bias.append(100 * (hardness / mean - 1))
        print(f"| {path.stem} | {mean:.0f} +- {se:.0f} | {hardness:.0f} | {bias[-1]:+.1f} % |")
    print(f"\n{len(bias)} runs: the hardness after unloading lies {statistics.fmean(bias):+.1f} % from the plateau on average, "
          f"standard deviation {statistics.stdev(bias):.1f} %, range {min(bias):+.1f} to {max(bias):+.1f} %")
    whole = [(k, f"whole{k}_g0.01.csv") for k in (1, 2, 3) if f"whole{k}_g0.01.csv" in read]
    if len(whole) < 2:
        sys.exit(f"{len(whole)} whole bed(s) at gamma* 0.01 in {RUNS}: the reference needs at least two")
    values = [read[f][0] for _, f in whole]
    mean, sd = statistics.fmean(values), statistics.stdev(values)
    print(f"\nReference of record, h/r {WINDOW[0]}-{WINDOW[1]}: gamma* = 0.01 on {len(whole)} whole beds")
    for k, f in whole:
        print(f"  bed {k}: {read[f][0]:.0f} +- {read[f][1]:.0f} Pa (the run's own error)")
    print(f"  mean {mean:.0f} Pa, standard deviation over beds {sd:.0f} Pa ({100 * sd / mean:.1f} %), "
          f"standard error of the mean {sd / math.sqrt(len(whole)):.0f} Pa")
    if args.reference:
        with open(args.reference, "w", newline="") as out:
            w = csv.writer(out)
            w.writerow(["bed_fill_seed", "file", "plateau_Pa", "own_standard_error_Pa"])
            for k, f in whole:
                w.writerow([k, f"window/{f}", f"{read[f][0]:.6g}", f"{read[f][1]:.6g}"])
            w.writerow(["mean", f"standard deviation over beds {sd:.0f} Pa", f"{mean:.6g}", f"{sd / math.sqrt(len(whole)):.6g}"])
        print(f"wrote {args.reference}")


if __name__ == "__main__":
    main()
