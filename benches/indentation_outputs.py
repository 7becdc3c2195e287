"""BallIndentation's post-unloading outputs read again from the force-depth records in
docs/data/ch6_indentation (`powderfmu bed indent` CSVs, a row every 1e-4 s), old and new definitions side
by side:

- plateau: the mean of F/A(h) over the loading rows at 0.1 <= h/r <= 0.2, with its standard error from
  the rows' autocorrelation (the estimator of `src/bed/series.rs`: deviations from the mean, integrated
  autocorrelation time in Sokal's window, C = 5, corrected for the sample mean's wander);
- old hardness: the largest force sample over A(h_max), what the unit reported before (the recorded
  unloading never gave a tangent on these beds, so A(h_max));
- new hardness: the mean of F/A(h) over the loading rows in the last tenth of the loading depth (the
  unit's force_at_turn is A(h_max) times it; h_c = h_max where the unloading gives no tangent, as here);
- line: the least-squares line of F(h) over the same rows taken at h_max, over A(h_max) (an alternative,
  not kept: see the summary it prints).

Each against the plateau, in per cent and in units of the combined error. The rows are four times coarser
than the unit's own samples (every 100 engine steps of 2.5e-7 s): the errors here are those of the rows.

It ends with the reference of record: the seed's speed (gamma* = 0.01, 2.5e-7 s steps, every sphere
moving) on the three whole beds of docs/data/ch6_indentation/beds.csv, each with its own error, and their
mean with the error over beds (`--reference` writes it).

    .venv/bin/python benches/indentation_outputs.py [--csv docs/data/indentation_outputs.csv]
        [--reference docs/data/reference_of_record_h0.1-0.2.csv]
"""

import argparse
import csv
import math
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
DATA = REPO / "docs" / "data" / "ch6_indentation"
D = 0.016  # the indenter of every recorded run [m]
WINDOW = (0.1, 0.2)
TURN_FIT = 0.1


def mean_with_error(y):
    """Mean of y and its standard error (series.rs's estimator)."""
    n = len(y)
    r = y - np.mean(y)
    c0 = np.mean(r * r)
    tau, window = 1.0, 0
    for w in range(1, n // 2):
        tau += 2.0 * np.sum(r[: n - w] * r[w:]) / n / c0
        window = w
        if w >= 5.0 * tau:
            break
    tau = max(tau / max(1.0 - (2 * window + 1) / n, 0.25), 1.0)
    return float(np.mean(y)), math.sqrt(c0 * n / (n - 1) * tau / n), tau


def area(h):
    return math.pi * (D * h - h * h)


def fit_error(x, y, at):
    """The least-squares line at `at` and its standard error (white residuals; the last tenth spans few
    correlation times, so this is a lower bound)."""
    slope, intercept = np.polyfit(x, y, 1)
    r = y - (intercept + slope * x)
    n = len(x)
    s2 = np.sum(r * r) / (n - 2)
    se = math.sqrt(s2 * (1.0 / n + (at - np.mean(x)) ** 2 / np.sum((x - np.mean(x)) ** 2)))
    return intercept + slope * at, se


def analyse(path):
    rows = list(csv.DictReader(open(path)))
    h = np.array([float(r["depth_m"]) for r in rows])
    f = np.array([float(r["force_N"]) for r in rows])
    state = np.array([int(r["state"]) for r in rows])
    load = state == 0
    hl, fl = h[load], f[load]
    h_max = hl.max()
    win = (hl / (D / 2) >= WINDOW[0]) & (hl / (D / 2) <= WINDOW[1])
    mean, se, tau = mean_with_error(fl[win] / area(hl[win]))
    old = fl.max() / area(h_max)
    tail = hl >= (1 - TURN_FIT) * h_max
    local = fl[tail] / area(hl[tail])
    new = float(np.mean(local))
    # Its error from the rows' own scatter, as if independent (the last tenth spans one or two correlation
    # times at the slow speeds: a lower bound).
    new_se = float(np.std(local, ddof=1) / math.sqrt(len(local)))
    f_line, _ = fit_error(hl[tail], fl[tail], h_max)
    line = f_line / area(h_max)
    return {
        "file": path.name,
        "rows_in_window": int(win.sum()),
        "plateau_Pa": mean,
        "plateau_se_Pa": se,
        "tau_rows": tau,
        "old_hardness_Pa": old,
        "old_bias_pct": 100 * (old / mean - 1),
        "new_hardness_Pa": new,
        "new_se_Pa": new_se,
        "new_bias_pct": 100 * (new / mean - 1),
        "new_z": (new - mean) / math.hypot(se, new_se),
        "line_bias_pct": 100 * (line / mean - 1),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--csv", type=Path, help="also write the table here")
    ap.add_argument("--reference", type=Path, help="also write the reference of record here")
    args = ap.parse_args()
    out = []
    for path in sorted(DATA.glob("*.csv")):
        if path.name in ("runs.csv", "beds.csv"):
            continue
        out.append(analyse(path))
    print(f"{'run':42s} {'n':>4s} {'plateau [Pa]':>16s} {'tau':>5s} {'old H':>7s} {'bias':>7s} {'new H':>13s} {'bias':>7s} {'z':>5s}")
    for r in out:
        print(
            f"{r['file']:42s} {r['rows_in_window']:4d} {r['plateau_Pa']:8.0f} +- {r['plateau_se_Pa']:4.0f} {r['tau_rows']:5.1f} "
            f"{r['old_hardness_Pa']:7.0f} {r['old_bias_pct']:+6.1f}% {r['new_hardness_Pa']:7.0f} +- {r['new_se_Pa']:3.0f} {r['new_bias_pct']:+6.1f}% {r['new_z']:+5.1f}"
        )
    old = np.array([r["old_bias_pct"] for r in out])
    new = np.array([r["new_bias_pct"] for r in out])
    z = np.array([r["new_z"] for r in out])
    line = np.array([r["line_bias_pct"] for r in out])
    print(f"\n{len(out)} runs. Old hardness against the plateau: mean {old.mean():+.1f} %, range {old.min():+.1f} to {old.max():+.1f} %.")
    print(f"New hardness against the plateau: mean {new.mean():+.1f} %, standard deviation {new.std(ddof=1):.1f} %, range {new.min():+.1f} to {new.max():+.1f} %; |z| < 2 in {np.sum(abs(z) < 2)} of {len(z)}.")
    print(f"(The least-squares line over the same rows at h_max: mean {line.mean():+.1f} %, standard deviation {line.std(ddof=1):.1f} %.)")
    print(f"Old: standard deviation {old.std(ddof=1):.1f} %.")
    beds = {1: "gamma0.01_full_dt2.5e-7.csv", 2: "seed2_gamma0.01_full_dt2.5e-7.csv", 3: "seed3_gamma0.01_full_dt2.5e-7.csv"}
    by_file = {r["file"]: r for r in out}
    ref = [{"bed_fill_seed": k, "file": f, "plateau_Pa": by_file[f]["plateau_Pa"], "own_standard_error_Pa": by_file[f]["plateau_se_Pa"]} for k, f in beds.items()]
    values = np.array([r["plateau_Pa"] for r in ref])
    mean, sd = values.mean(), values.std(ddof=1)
    print("\nReference of record: gamma* = 0.01, 2.5e-7 s, full, the three whole beds (rows of 1e-4 s)")
    for r in ref:
        print(f"  bed {r['bed_fill_seed']}: {r['plateau_Pa']:.0f} +- {r['own_standard_error_Pa']:.0f} Pa (the run's own error)")
    print(f"  mean {mean:.0f} Pa, standard deviation over beds {sd:.0f} Pa ({100 * sd / mean:.1f} %), standard error of the mean {sd / math.sqrt(len(ref)):.0f} Pa")
    if args.reference:
        summary = {"bed_fill_seed": "mean", "file": f"standard deviation over beds {sd:.0f} Pa", "plateau_Pa": mean, "own_standard_error_Pa": sd / math.sqrt(len(ref))}
        write_csv(args.reference, ref + [summary])
    if args.csv:
        write_csv(args.csv, out)


def write_csv(path, rows):
    """The rows (dicts with the same keys) as a CSV, floats to six digits."""
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    print(f"wrote {path}")

if __name__ == "__main__":
    main()
