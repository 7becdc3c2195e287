"""Whether one run's plateau standard error is the size of the run-to-run scatter, from the seed's test
at its own speed (gamma* = 0.01, 2.5e-7 s steps, every sphere moving, two threads) on the shipped quarter
and whole beds, run again with another skin, list schedule or forgetting rule: each such run follows its
own path (the bed's dynamics are chaotic), so the runs are realisations of one test on one bed
(docs/data/seed_speed_realisations.csv, recorded by `SKIN=... bash benches/indentation_seed_speed.sh`).

Prints, per bed: the runs' mean plateau, their standard deviation, the root mean square of their own
errors, and the ratio of the two (about 0.8 where the estimator is right, docs/indentation.md); and the
same within each forgetting rule.

Usage: python3 benches/realisation_scatter.py [docs/data/seed_speed_realisations.csv]
"""

import csv
import math
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def summary(rows):
    p = [float(r["plateau_Pa"]) for r in rows]
    e = [float(r["plateau_standard_error_Pa"]) for r in rows]
    sd = statistics.stdev(p)
    rms = math.sqrt(sum(x * x for x in e) / len(e))
    # The standard deviation of n normal samples is known to about 1 / sqrt(2 (n - 1)) of itself.
    return (f"{len(p)} runs: mean {statistics.mean(p):.0f} Pa, standard deviation {sd:.0f} Pa ({100 * sd / statistics.mean(p):.1f} %, "
            f"+-{100 / math.sqrt(2 * (len(p) - 1)):.0f} %), own errors' rms {rms:.0f} Pa, rms / sd {rms / sd:.2f}")


def main():
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "data" / "seed_speed_realisations.csv"
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for bed in ["quarter", "whole"]:
        mine = [r for r in rows if r["bed"] == bed]
        print(f"{bed}: {summary(mine)}")
        for rule in sorted({r["rule"] for r in mine}):
            group = [r for r in mine if r["rule"] == rule]
            if len(group) > 1:
                print(f"  {rule}: {summary(group)}")


if __name__ == "__main__":
    main()
