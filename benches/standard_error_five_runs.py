"""Can a table of a few runs tell whether the plateau's own standard error is right? The unit's estimator
(benches/indentation_outputs.py's port of src/bed/series.rs) on AR(1) series of the default window's
length and correlation time, whose true error is known:

- over many single series: the spread of their means against the root mean square of their own errors
  (1 for an unbiased estimator);
- over many tables of `--runs` series each: the distribution of that ratio as one table reads it, to set
  beside the ratio of docs/data/default_replicas.csv.

    .venv/bin/python benches/standard_error_five_runs.py [--samples 672] [--tau 263] [--runs 5]

(672 samples and 263 samples of correlation time: the default's window, h/r 0.35-0.5 at gamma* 0.04, and
the correlation time its first run's log gives.)
"""

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from indentation_outputs import mean_with_error  # noqa: E402

REPO = Path(__file__).resolve().parents[1]


def ar1(rng, runs, n, tau):
    """`runs` AR(1) series of n samples whose integrated autocorrelation time is tau, started stationary."""
    phi = (tau - 1) / (tau + 1)
    x = np.empty((runs, n))
    x[:, 0] = rng.standard_normal(runs) / math.sqrt(1 - phi * phi)
    e = rng.standard_normal((runs, n))
    for i in range(1, n):
        x[:, i] = phi * x[:, i - 1] + e[:, i]
    return x


def ratio(series):
    means, errors = zip(*[mean_with_error(s)[:2] for s in series])
    return float(np.std(means, ddof=1) / math.sqrt(np.mean(np.square(errors))))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=int, default=672)
    ap.add_argument("--tau", type=float, default=263.0)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--tables", type=int, default=600)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    print(f"AR(1) series of {a.samples} samples, correlation time {a.tau:g} samples ({a.samples / a.tau:.1f} correlation times)")
    print(f"one ratio over {a.tables} series: {ratio(ar1(rng, a.tables, a.samples, a.tau)):.2f} (1 = unbiased)")
    tables = np.array([ratio(ar1(rng, a.runs, a.samples, a.tau)) for _ in range(a.tables)])
    lo, hi = np.percentile(tables, [2.5, 97.5])
    print(f"tables of {a.runs} runs: median ratio {np.median(tables):.2f}, 95 % of tables between {lo:.2f} and {hi:.2f}")
    with open(REPO / "docs" / "data" / "default_replicas.csv") as f:
        rows = list(csv.DictReader(f))
    p = np.array([float(r["plateau_hardness"]) for r in rows])
    se = np.array([float(r["plateau_hardness_standard_error"]) for r in rows])
    read = float(np.std(p, ddof=1) / math.sqrt(np.mean(se * se)))
    print(f"docs/data/default_replicas.csv ({len(rows)} runs): ratio {read:.2f}; {100 * np.mean(tables >= read):.1f} % of the "
          f"tables of unbiased errors read at least as much")


if __name__ == "__main__":
    main()
