"""What a 5 % interval on the seed's test costs: for each way of running the test on the seed's Ch. 6 bed
(whole or quarter die, gamma*), the recorded runs' mean over beds, its bias against the reference of
record, the scatter from run to run on one bed and from bed to bed, and the half-width of the 95 %
interval of a mean over n tests against the wall time of those n tests on two cores.

    python benches/indentation_halfwidth.py [--plot docs/figures/indentation_halfwidth.png]
        [--csv docs/data/indentation_halfwidth.csv]
    python benches/indentation_halfwidth.py --window 0.1-0.2 [--plot docs/figures/indentation_halfwidth_h0.1-0.2.png]
        [--csv docs/data/indentation_halfwidth_h0.1-0.2.csv]

The seed's window (the default): the runs to h/r 0.5 of docs/data/ch6_indentation/window (`powderfmu bed
indent` CSVs, plateau = mean F/A(h) over 0.35 <= h/r <= 0.5 while loading) and docs/data/default_replicas.csv
(the FMU's default, five runs on the shipped quarter bed), against docs/data/reference_of_record.csv (three
whole beds at the seed's speed in that window). The window of the earlier default, 0.1-0.2: the runs of
docs/data/ch6_indentation and docs/data/default_replicas_h0.1-0.2.csv (that default ten times), against
docs/data/reference_of_record_h0.1-0.2.csv.
Runs on one bed differ only by a step a few parts in 10^4 shorter (the dynamics are chaotic, so they are
independent samples of that bed). The scatter from run to run, s_run, is pooled over the beds with more
than one run; the bed-to-bed part, s_bed, is what the spread of the beds' means leaves after s_run/n_b:
s_bed^2 = var(bed means) - mean(s_run^2 / n_b), at least 0. A mean over n tests has the half-width
1.96 (s_run^2 + s_bed^2)^(1/2) / n^(1/2) when every test has its own bed, and 1.96 (s_run^2 / n +
s_bed^2)^(1/2) when all run on one bed (the bed's own offset does not average out).
"""

import argparse
import csv
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from indentation_work_precision import plateau as run_plateau  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "docs", "data")
RUNS = os.path.join(DATA, "ch6_indentation")

# (name, gamma*, wall time of one test on two cores [s], preparation of one bed [min], {bed: [run CSVs]}):
# the seed's window, h/r 0.35-0.5 (the default's since 2026-12-06). The default's first bed is its five
# replicas only: the first of them steps what window/quarter1_g0.04.csv records (the FMU's test asserts it).
SEED_WINDOW = [
    ("whole, gamma* 0.01", 0.01, 1824, 120,
     {f"whole {k}": [f"window/whole{k}_g0.01.csv"] for k in (1, 2, 3)}),
    ("quarter, gamma* 0.01", 0.01, 447, 45, {f"quarter {k}": [f"window/quarter{k}_g0.01.csv"] for k in (1, 2, 3)}),
    ("quarter, gamma* 0.02", 0.02, 214, 45, {f"quarter {k}": [f"window/quarter{k}_g0.02.csv"] for k in (1, 2, 3)}),
    ("quarter, gamma* 0.04 (the default)", 0.04, 110, 45,
     {"quarter 1": ["default_replicas.csv"], "quarter 2": ["window/quarter2_g0.04.csv"], "quarter 3": ["window/quarter3_g0.04.csv"]}),
    ("quarter, gamma* 0.08", 0.08, 60, 45, {f"quarter {k}": [f"window/quarter{k}_g0.08.csv"] for k in (1, 2, 3)}),
]

# The window of the earlier default, h/r 0.1-0.2 (until 2026-12-06), its runs as recorded then.
UNIT_WINDOW = [
    ("whole, gamma* 0.01", 0.01, 730, 120,
     {"whole 1": ["gamma0.01_full_dt2.5e-7.csv", "gamma0.01_full_dt2.4975e-7.csv"],
      "whole 2": ["seed2_gamma0.01_full_dt2.5e-7.csv"], "whole 3": ["seed3_gamma0.01_full_dt2.5e-7.csv"]}),
    ("whole, gamma* 0.08, fast", 0.08, 85, 120,
     {"whole 1": ["gamma0.08_fast_dt2.5e-7.csv"], "whole 2": ["seed2_gamma0.08_fast_dt2.5e-7.csv"],
      "whole 3": ["seed3_gamma0.08_fast_dt2.5e-7.csv"]}),
    ("quarter, gamma* 0.01", 0.01, 240, 45,
     {"quarter 1": ["quarter1_gamma0.01_full_dt2.5e-7.csv", "quarter1_gamma0.01_full_dt2.4975e-7.csv"],
      "quarter 2": ["quarter2_gamma0.01_full_dt2.5e-7.csv"]}),
    # Beds 2 and 3 are the FMU's replica beds (fill seeds 2 and 3); `over_beds:K:T` is bed K's plateau in
    # docs/data/default_over_beds.csv's three-bed run on T threads per bed (one and two threads step
    # different trajectories, so they are two runs of the bed; bed 2's two-thread run is the command
    # line's quarter2 run sampled by the FMU, so it is not counted twice).
    ("quarter, gamma* 0.02 (the default)", 0.02, 145, 45,
     {"quarter 1": ["default_replicas_h0.1-0.2.csv", "over_beds:1:1"],
      "quarter 2": ["quarter2_gamma0.02_full_dt2.5e-7.csv", "over_beds:2:1"],
      "quarter 3": ["over_beds:3:2", "over_beds:3:1"]}),
]


def plateau(name, window):
    """The plateau of one recorded run, or the plateaus of the default's replicas."""
    if name.startswith("default_replicas"):
        with open(os.path.join(DATA, name)) as f:
            return [float(r["plateau_hardness"]) for r in csv.DictReader(f)]
    if name.startswith("over_beds:"):
        _, bed, threads = name.split(":")
        # Three beds one after the other on two threads each, or side by side on one thread each.
        kind = "one after the other" if threads == "2" else "side by side"
        with open(os.path.join(DATA, "default_over_beds.csv")) as f:
            row = next(r for r in csv.DictReader(f) if r["replicas"] == "3" and r["beds_step"].startswith(kind))
        return [float(row["each_bed_Pa"].split()[int(bed) - 1])]
    return [run_plateau(os.path.join(RUNS, name), window)[0]]


def reference(suffix):
    with open(os.path.join(DATA, f"reference_of_record{suffix}.csv")) as f:
        rows = list(csv.DictReader(f))
    mean = next(r for r in rows if r["bed_fill_seed"] == "mean")
    return float(mean["plateau_Pa"]), float(mean["own_standard_error_Pa"])


def scatter(beds):
    """(mean over beds, s_run, s_bed, their sum in quadrature, runs) from {bed: [plateau, ...]}."""
    means = [statistics.mean(v) for v in beds.values()]
    repeated = [v for v in beds.values() if len(v) > 1]
    dof = sum(len(v) - 1 for v in repeated)
    s_run = math.sqrt(sum(sum((x - statistics.mean(v)) ** 2 for x in v) for v in repeated) / dof) if dof else float("nan")
    between = statistics.variance(means) if len(means) > 1 else float("nan")
    within = statistics.mean(s_run**2 / len(v) for v in beds.values())
    if math.isnan(s_run):
        # One run per bed: their spread is s_run and s_bed together, not separable.
        return statistics.mean(means), float("nan"), float("nan"), math.sqrt(between), sum(len(v) for v in beds.values())
    s_bed = math.sqrt(max(between - within, 0.0))
    return statistics.mean(means), s_run, s_bed, math.hypot(s_run, s_bed), sum(len(v) for v in beds.values())


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--plot", help="write the half-width against wall time figure here")
    p.add_argument("--csv", help="write each setting's mean, bias and scatter here (tests/python/test_default_bed.py reads it)")
    p.add_argument("--window", choices=["0.35-0.5", "0.1-0.2"], default="0.35-0.5",
                   help="the seed's window (the default's) or the earlier default's, h/r")
    a = p.parse_args()
    seed = a.window == "0.35-0.5"
    settings, window, suffix = (SEED_WINDOW, (0.35, 0.5), "") if seed else (UNIT_WINDOW, (0.1, 0.2), "_h0.1-0.2")
    ref, ref_se = reference(suffix)
    target = 0.05 * ref
    print(f"window h/r {a.window}; reference of record: {ref:.0f} +- {ref_se:.0f} Pa (whole beds at gamma* 0.01); 5 % of it: {target:.0f} Pa\n")
    print("| setting | beds | runs | mean over beds [Pa] | against the reference (+- standard error over beds) | s_run [Pa] | s_bed [Pa] | one test [s] |"
          " half-width, one test | tests for 5 %, each on its own bed | their wall time [min] | beds to prepare [h] |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    curves = []
    table = []
    for name, gamma, wall, prep, files in settings:
        beds = {b: [x for f in fs for x in plateau(f, window)] for b, fs in files.items()}
        mean, s_run, s_bed, s_tot, runs = scatter(beds)
        bias_se = statistics.stdev([statistics.mean(v) for v in beds.values()]) / math.sqrt(len(beds))
        one = 1.96 * s_tot
        n = math.ceil((1.96 * s_tot / target) ** 2)
        pct = lambda s: "together: " + f"{s_tot:.0f} ({100 * s_tot / mean:.1f} %)" if math.isnan(s) else f"{s:.0f} ({100 * s / mean:.1f} %)"  # noqa: E731
        print(f"| {name} | {len(beds)} | {runs} | {mean:.0f} | {round(100 * (mean / ref - 1), 1) + 0.0:+.1f} +- {100 * bias_se / ref:.1f} % | {pct(s_run)} |"
              f" {pct(s_bed)} | {wall} | {100 * one / ref:.1f} % | {n} | {n * wall / 60:.0f} | {n * prep / 60:.0f} |")
        curves.append((name, wall, s_run, s_bed, s_tot, mean))
        table.append({"setting": name, "gamma": gamma, "beds": len(beds), "runs": runs, "mean_Pa": mean, "bias_standard_error_Pa": bias_se,
                      "s_run_Pa": s_run, "s_bed_Pa": s_bed, "s_total_Pa": s_tot, "wall_s": wall, "reference_Pa": ref})
    print("\nOne bed, n tests (step replicas): the half-width never falls below 1.96 s_bed:")
    print("\n| setting | n = 1 | n = 4 | n = 16 | limit |")
    print("|---|---:|---:|---:|---:|")
    for name, wall, s_run, s_bed, s_tot, mean in curves:
        if math.isnan(s_bed):
            continue
        hw = [1.96 * math.sqrt(s_run**2 / n + s_bed**2) / ref for n in (1, 4, 16)]
        print(f"| {name} | {100 * hw[0]:.1f} % | {100 * hw[1]:.1f} % | {100 * hw[2]:.1f} % | {100 * 1.96 * s_bed / ref:.1f} % |")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0]))
            w.writeheader()
            for r in table:
                w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
        print(f"\n{len(table)} settings -> {a.csv}")
    if a.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7.5, 4.8))
        for name, wall, s_run, s_bed, s_tot, mean in curves:
            n = [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64]
            hw = [100 * 1.96 * s_tot / math.sqrt(k) / ref for k in n]
            line = ax.loglog([k * wall / 60 for k in n], hw, marker="o", ms=3,
                             label=f"{name}: bias {round(100 * (mean / ref - 1)) + 0.0:+.0f} %")[0]
            if not math.isnan(s_bed):
                ax.loglog([k * wall / 60 for k in n], [100 * 1.96 * math.sqrt(s_run**2 / k + s_bed**2) / ref for k in n],
                          ls=":", color=line.get_color())
        ax.axhline(5, color="k", lw=0.8)
        ax.axvline(2, color="grey", lw=0.8, ls="--")
        ax.text(2.1, 2.0, "2 minutes", color="grey", rotation=90)
        ax.text(300, 5.3, "5 %")
        ax.set_xlabel("wall time of n tests on two cores [min]")
        ax.set_ylabel("half-width of the 95 % interval [% of the reference]")
        ax.set_title(f"A mean over n tests, window h/r {a.window}: each on its own bed (solid), all on one bed (dotted)", fontsize=10)
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
        print(f"\nfigure -> {a.plot}")


if __name__ == "__main__":
    main()
