"""The default BallIndentation test on the FMU's independently prepared quarter beds at once (`replicas`),
through fmpy: the plateau hardness over the beds, its standard error from their spread beside the runs'
own, each bed's plateau (from the unit's log), the wall time, and the 95 % interval of the mean (Student's
t with replicas - 1 degrees of freedom) against the reference of record (docs/data/indentation_halfwidth.csv:
three whole beds at the seed's speed, 8408 +- 313 Pa).

    .venv/bin/python benches/indentation_over_beds.py [--replicas 2 3] [--threads 2]
        [--fmu target/fmu/BallIndentation.fmu] [--csv docs/data/default_over_beds.csv]
"""

import argparse
import csv
import re
import time
from pathlib import Path

from fmpy import simulate_fmu

REPO = Path(__file__).resolve().parents[1]
REFERENCE_PA = 8408.0
# Student's t at 97.5 % for 1-4 degrees of freedom.
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776}
OUTPUTS = ["plateau_hardness", "plateau_hardness_standard_error", "plateau_hardness_standard_error_over_beds", "plateau_samples", "hardness", "test_state"]
EACH = re.compile(r"each bed: ([^)]*) Pa\)")


def run(fmu: Path, replicas: int, threads: int) -> dict:
    messages = []

    def logger(_env, _instance, _status, category, message):
        text = message.decode() if isinstance(message, bytes) else str(message)
        if (category.decode() if isinstance(category, bytes) else str(category)) == "logEvents":
            messages.append(text)

    start = time.perf_counter()
    r = simulate_fmu(str(fmu), start_values={"replicas": replicas, "threads": threads}, output=OUTPUTS, debug_logging=True, logger=logger)
    wall = time.perf_counter() - start
    last = r[-1]
    each = [float(x) for m in messages for g in EACH.findall(m) for x in g.split(",")] if replicas > 1 else [float(last["plateau_hardness"])]
    mean, se_beds = float(last["plateau_hardness"]), float(last["plateau_hardness_standard_error_over_beds"])
    half = T975.get(replicas - 1, 1.96) * se_beds if replicas > 1 else float("nan")
    return {
        "replicas": replicas,
        "threads": threads,
        "wall_s": wall,
        "plateau_Pa": mean,
        "se_own_Pa": float(last["plateau_hardness_standard_error"]),
        "se_over_beds_Pa": se_beds,
        "half_width_95_Pa": half,
        "contains_reference": bool(abs(mean - REFERENCE_PA) <= half) if replicas > 1 else "",
        "each_bed_Pa": " ".join(f"{x:.0f}" for x in each),
        "hardness_Pa": float(last["hardness"]),
        "done": int(last["test_state"]) == 2,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--replicas", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--fmu", type=Path, default=REPO / "target" / "fmu" / "BallIndentation.fmu")
    ap.add_argument("--csv", type=Path)
    args = ap.parse_args()
    rows = []
    for n in args.replicas:
        row = run(args.fmu, n, args.threads)
        rows.append(row)
        print(
            f"replicas {n}, threads {args.threads}: {row['wall_s']:.0f} s wall; plateau {row['plateau_Pa']:.0f} Pa, own standard error "
            f"{row['se_own_Pa']:.0f} Pa, over the beds {row['se_over_beds_Pa']:.0f} Pa (95 % +-{row['half_width_95_Pa']:.0f} Pa, "
            f"reference {REFERENCE_PA:.0f} Pa inside: {row['contains_reference']}); each bed {row['each_bed_Pa']} Pa",
            flush=True,
        )
    if args.csv:
        with open(args.csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0]))
            w.writeheader()
            for r in rows:
                w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
        print(f"wrote {args.csv}")


if __name__ == "__main__":
    main()
