"""The default BallIndentation test through fmpy, repeated with the engine's time step changed by a few
parts in 10^4 (2.5e-7 s x (1 - k 1e-4)): each run steps the same bed and the same indenter, and the bed's
dynamics, chaotic, turn the small change into an independent path. The spread of the plateau hardness
over the runs is the run-to-run scatter of one bed; the unit's plateau_hardness_standard_error, from one
run's own fluctuations, should be of the same size, and so should hardness_standard_error against the
spread of the hardness after unloading. (Bed-to-bed scatter, a different bed each, is larger:
docs/indentation.md.)

    .venv/bin/python benches/indentation_replicas.py [--runs 5] [--fmu target/fmu/BallIndentation.fmu]
        [--csv docs/data/default_replicas.csv] (the default in the seed's window since 2026-12-06; the ten runs of the default before it: default_replicas_h0.1-0.2.csv)
"""

import argparse
import csv
import math
import time
from pathlib import Path

import numpy as np
from fmpy import simulate_fmu

REPO = Path(__file__).resolve().parents[1]
OUTPUTS = ["hardness", "hardness_standard_error", "plateau_hardness", "plateau_hardness_standard_error", "plateau_samples", "contact_depth", "contact_depth_from_tangent", "force_at_turn"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--fmu", type=Path, default=REPO / "target" / "fmu" / "BallIndentation.fmu")
    ap.add_argument("--csv", type=Path)
    args = ap.parse_args()
    rows = []
    for k in range(args.runs):
        dt = 2.5e-7 * (1 - k * 1e-4)
        start = time.perf_counter()
        r = simulate_fmu(str(args.fmu), start_values={"time_step": dt}, output=OUTPUTS)
        wall = time.perf_counter() - start
        last = r[-1]
        row = {"time_step_s": dt, "wall_s": wall, **{n: float(last[n]) for n in OUTPUTS}}
        rows.append(row)
        print(
            f"run {k + 1}/{args.runs}: time step {dt:.6e} s, {wall:.0f} s wall: plateau {row['plateau_hardness']:.0f} +- "
            f"{row['plateau_hardness_standard_error']:.0f} Pa ({row['plateau_samples']:.0f} samples), hardness {row['hardness']:.0f} +- {row['hardness_standard_error']:.0f} Pa, "
            f"h_c {row['contact_depth']:.4e} m (tangent: {bool(row['contact_depth_from_tangent'])})",
            flush=True,
        )
    plateau = np.array([r["plateau_hardness"] for r in rows])
    se = np.array([r["plateau_hardness_standard_error"] for r in rows])
    hardness = np.array([r["hardness"] for r in rows])
    hse = np.array([r["hardness_standard_error"] for r in rows])
    sd = plateau.std(ddof=1)
    # The spread's own relative error with n runs: about 1 / sqrt(2 (n - 1)).
    print(
        f"\n{len(rows)} runs: plateau mean {plateau.mean():.0f} Pa, standard deviation over runs {sd:.0f} Pa "
        f"(+-{100 / math.sqrt(2 * (len(rows) - 1)):.0f} %), root mean square of the runs' own standard errors {math.sqrt(np.mean(se**2)):.0f} Pa: "
        f"ratio {sd / math.sqrt(np.mean(se**2)):.2f}; hardness after unloading mean {hardness.mean():.0f} Pa, "
        f"{100 * (hardness.mean() / plateau.mean() - 1):+.1f} % from the plateau, standard deviation {hardness.std(ddof=1):.0f} Pa "
        f"against the root mean square of its own standard errors {math.sqrt(np.mean(hse**2)):.0f} Pa: ratio {hardness.std(ddof=1) / math.sqrt(np.mean(hse**2)):.2f}"
    )
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0]))
            w.writeheader()
            for r in rows:
                w.writerow({k: f"{v:.6g}" for k, v in r.items()})
        print(f"wrote {args.csv}")


if __name__ == "__main__":
    main()
