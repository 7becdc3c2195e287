"""The default BallIndentation test on the FMU's independently prepared quarter beds at once (`replicas`),
through fmpy: the plateau hardness over the beds, its standard error from their spread beside the runs'
own, each bed's plateau (from the unit's log), the wall time, and the 95 % interval of the mean (Student's
t with replicas - 1 degrees of freedom) against the reference of record (--reference: three whole beds at
the seed's speed in the default's window; docs/data/default_over_beds.csv and its figure were made with
the default until 2026-12-06 and docs/data/reference_of_record_h0.1-0.2.csv, 8408 +- 313 Pa).

    .venv/bin/python benches/indentation_over_beds.py [--replicas 2 3] [--threads 2]
        [--fmu target/fmu/BallIndentation.fmu] [--csv docs/data/default_over_beds.csv]
    .venv/bin/python benches/indentation_over_beds.py --from-csv docs/data/default_over_beds.csv
        --reference docs/data/reference_of_record_h0.1-0.2.csv --plot docs/figures/default_over_beds.png
"""

import argparse
import csv
import re
import time
from pathlib import Path

from fmpy import simulate_fmu

REPO = Path(__file__).resolve().parents[1]


def reference(path: Path) -> tuple:
    """(mean, standard error) of a reference-of-record CSV's `mean` row [Pa]."""
    with open(path, newline="") as fh:
        row = next(r for r in csv.DictReader(fh) if r["bed_fill_seed"] == "mean")
    return float(row["plateau_Pa"]), float(row["own_standard_error_Pa"])


REFERENCE_PA, REFERENCE_SE = reference(REPO / "docs" / "data" / "reference_of_record.csv")
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
    ap.add_argument("--from-csv", type=Path, help="plot a CSV this script wrote instead of running")
    ap.add_argument("--plot", type=Path, help="each bed's plateau and the 95 %% interval over the beds against the reference")
    ap.add_argument("--reference", type=Path, help="the reference of record (default docs/data/reference_of_record.csv)")
    args = ap.parse_args()
    if args.reference:
        global REFERENCE_PA, REFERENCE_SE
        REFERENCE_PA, REFERENCE_SE = reference(args.reference)
    if args.from_csv:
        with open(args.from_csv, newline="") as fh:
            rows = list(csv.DictReader(fh))
        if args.plot:
            plot(rows, args.plot)
        return
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
    if args.plot:
        plot([{k: str(v) for k, v in r.items()} for r in rows], args.plot)


def plot(rows: list, path: Path):
    """Each bed's plateau (dots) and the mean over the beds with its 95 % interval (bars), one column per
    run, the reference of record as a band."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    ax.axhspan(REFERENCE_PA - REFERENCE_SE, REFERENCE_PA + REFERENCE_SE, color="0.85", label="reference of record: 3 whole beds at the seed's speed, +- its standard error")
    ax.axhline(REFERENCE_PA, color="0.4", lw=1)
    labels = []
    for k, r in enumerate(rows):
        each = [float(x) for x in r["each_bed_Pa"].split()]
        ax.plot([k] * len(each), each, "o", color="tab:blue", ms=5, alpha=0.7, label="each bed" if k == 0 else None)
        half = float(r["half_width_95_Pa"])
        mean = float(r["plateau_Pa"])
        if half == half:  # not NaN: two beds or more
            labelled = any(t.startswith("mean") for t in ax.get_legend_handles_labels()[1])
            ax.errorbar([k + 0.15], [mean], yerr=[[min(half, mean)], [half]], fmt="s", color="tab:red", capsize=4,
                        label=None if labelled else "mean over the beds, 95 % interval (Student's t, n - 1 degrees of freedom)")
        else:
            ax.plot([k + 0.15], [mean], "s", color="tab:red")
        how = "side by side" if r["beds_step"].startswith("side") else ("one bed" if r["beds_step"] == "one bed" else "one after the other")
        labels.append(f"{r['replicas']} bed(s)\n{how}\n{float(r['wall_s']):.0f} s")
    ax.set_xticks(range(len(rows)))
    ax.set_xticklabels(labels, fontsize=8)
    ax.set_ylim(0, 20000)
    ax.set_ylabel("plateau hardness, h/r 0.1-0.2 [Pa]")
    ax.set_title("BallIndentation's default test on the shipped quarter beds (replicas)", fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
