"""The constraint factor C = H / sigma_c (004 Eq. 2.10, Sec. 2.3.5) against the consolidation stress
sigma_1: H from BallIndentation's default test (the sweep's `indentation` task) on beds consolidated to
sigma_1, sigma_c from UnconfinedCompression's (the `compression` task) on specimens consolidated to the
same stress. Writes the table BallIndentation reads with `constraint_factor_source = measured` and a
figure.

    D=docs/data/constraint_factor_ch6 S=docs/data/constraint_factor_ch6/seed_window
    .venv/bin/python benches/constraint_factor.py --compression $D/compression_fill1.csv $D/compression_fill2.csv \\
        --indentation 1000=$S/indentation_1kPa.csv 3000=$S/indentation_3kPa.csv \\
                      10000=$S/indentation_10kPa.csv 20000=$S/indentation_20kPa.csv --window 0.35-0.5 \\
        --csv docs/data/constraint_factor_ch6_seed_window.csv --plot docs/figures/constraint_factor_ch6_seed_window.png

(the table BallIndentation reads; the earlier one, read over h/r 0.1-0.2, by the command in
docs/data/constraint_factor_ch6/README.md). The sweep rows do not carry the plateau window: `--window`
names the one the indentation runs used (BallIndentation's default when they ran), for the table's
comment and the figure.

Errors: the fill-to-fill scatter (independently prepared beds and specimens; it holds each run's own
fluctuation too) is taken as one relative standard deviation for all stresses, pooled over the stresses'
fills (sum of squared relative deviations from each stress's mean over sum(fills - 1)); the standard
error of a stress's mean is that times the mean over sqrt(fills). Two fills alone would give a standard
deviation of one degree of freedom. C's relative error is H's and sigma_c's in quadrature (the beds and
the specimens are different fills).
"""

import argparse
import csv
import math
import statistics


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def pooled_scatter(groups):
    """The relative standard deviation between fills, pooled over groups (the stresses) of values, and
    its degrees of freedom."""
    squares = sum(sum((v / statistics.fmean(g) - 1) ** 2 for v in g) for g in groups)
    dof = sum(len(g) - 1 for g in groups)
    return math.sqrt(squares / dof), dof


def summary(values, scatter):
    """(mean, standard error) of one quantity over its fills, with the pooled relative scatter."""
    mean = statistics.fmean(values)
    return mean, scatter * mean / math.sqrt(len(values))


def upper_tail(k, x):
    """P(chi^2 with k degrees of freedom >= x), by the series of the lower regularized gamma function (no
    scipy in the project's environment)."""
    a, term, total, n = k / 2, 1.0, 1.0, 1
    while term > 1e-15 * total:
        term *= (x / 2) / (a + n)
        total += term
        n += 1
    return 1 - (math.exp(a * math.log(x / 2) - x / 2 - math.lgamma(a + 1)) * total if x > 0 else 0.0)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--compression", nargs="+", required=True, help="the compression sweep's CSVs (consolidation_stress per row)")
    p.add_argument("--indentation", nargs="+", required=True, help="SIGMA_1_PA=CSV: indentation sweep rows on beds consolidated to SIGMA_1_PA")
    p.add_argument("--csv", required=True)
    p.add_argument("--plot", required=True)
    p.add_argument("--window", required=True, help="the indentation runs' plateau window in h/r, START-END (0.35-0.5 for the default since 2026-12-06)")
    a = p.parse_args()

    sigma_c = {}
    for r in [r for path in a.compression for r in rows(path)]:
        assert r["status"] == "ok", r
        if r["failed"] != "True":
            print(f"note: {r['bed_file']} did not fail within max_strain: its sigma_c is a lower bound")
        sigma_c.setdefault(float(r["consolidation_stress"]), []).append((float(r["unconfined_yield_strength"]), float(r["unconfined_yield_strength_standard_error"])))
    hardness = {}
    for item in a.indentation:
        s1, path = item.split("=", 1)
        for r in rows(path):
            assert r["status"] == "ok" and int(r["test_state"]) == 2, r
            hardness.setdefault(float(s1), []).append(
                (float(r["hardness"]), float(r["hardness_standard_error"]), float(r["plateau_hardness"]), float(r["plateau_hardness_standard_error"]))
            )
    scatter_c, dof_c = pooled_scatter([[x[0] for x in g] for g in sigma_c.values()])
    scatter_h, dof_h = pooled_scatter([[x[0] for x in g] for g in hardness.values()])
    scatter_p, _ = pooled_scatter([[x[2] for x in g] for g in hardness.values()])
    print(f"fill-to-fill scatter, pooled: sigma_c {100 * scatter_c:.1f} % ({dof_c} degrees of freedom), "
          f"H {100 * scatter_h:.1f} %, plateau H {100 * scatter_p:.1f} % ({dof_h})")
    for s1, fills in sorted(sigma_c.items()):
        print(f"  {s1:7.0f} Pa: sigma_c {', '.join(f'{x[0]:.0f}' for x in fills)} Pa; "
              f"H {', '.join(f'{x[0]:.0f}' for x in hardness.get(s1, []))} Pa; plateau {', '.join(f'{x[2]:.0f}' for x in hardness.get(s1, []))} Pa")

    table = []
    for s1 in sorted(set(sigma_c) & set(hardness)):
        c = summary([x[0] for x in sigma_c[s1]], scatter_c)
        h = summary([x[0] for x in hardness[s1]], scatter_h)
        hp = summary([x[2] for x in hardness[s1]], scatter_p)
        ratio = h[0] / c[0]
        ratio_p = hp[0] / c[0]
        table.append({
            "consolidation_stress_Pa": s1,
            "indentation_fills": len(hardness[s1]),
            "compression_fills": len(sigma_c[s1]),
            "hardness_Pa": h[0],
            "hardness_standard_error_Pa": h[1],
            "plateau_hardness_Pa": hp[0],
            "plateau_hardness_standard_error_Pa": hp[1],
            "unconfined_yield_strength_Pa": c[0],
            "unconfined_yield_strength_standard_error_Pa": c[1],
            "constraint_factor": ratio,
            "constraint_factor_standard_error": ratio * math.hypot(h[1] / h[0], c[1] / c[0]),
            "plateau_constraint_factor": ratio_p,
            "plateau_constraint_factor_standard_error": ratio_p * math.hypot(hp[1] / hp[0], c[1] / c[0]),
            "flow_function": s1 / c[0],
        })
    with open(a.csv, "w", newline="") as f:
        f.write("# The constraint factor C = H / sigma_c of the 004 Ch. 6 material against the consolidation stress sigma_1 (004 Eq. 2.10):\n")
        f.write(f"# H BallIndentation's default test (hardness after unloading; plateau_hardness over h/r {a.window}) on quarter beds of scenes/bed_004_ch6_quarter*.json,\n")
        f.write("# sigma_c UnconfinedCompression's default test on specimens of scenes/uct_004_ch6*.json; standard errors of the means over fills, from the fill-to-fill\n")
        f.write(f"# scatter pooled over the stresses ({100 * scatter_h:.1f} % in H, {100 * scatter_p:.1f} % in the plateau, {100 * scatter_c:.1f} % in sigma_c); the runs: docs/data/constraint_factor_ch6/.\n")
        f.write("# BallIndentation's constraint_factor_source = measured reads the constraint_factor of docs/data/constraint_factor_ch6_seed_window.csv (its default's window).\n")
        f.write("# Written by benches/constraint_factor.py (docs/units/UnconfinedCompression.md).\n")
        w = csv.DictWriter(f, fieldnames=list(table[0]))
        w.writeheader()
        for row in table:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    print(f"wrote {a.csv}")
    for row in table:
        print(f"sigma_1 {row['consolidation_stress_Pa']:7.0f} Pa: H {row['hardness_Pa']:7.0f} +- {row['hardness_standard_error_Pa']:5.0f} Pa "
              f"(plateau {row['plateau_hardness_Pa']:6.0f} +- {row['plateau_hardness_standard_error_Pa']:4.0f}), sigma_c {row['unconfined_yield_strength_Pa']:6.0f} "
              f"+- {row['unconfined_yield_strength_standard_error_Pa']:4.0f} Pa, C {row['constraint_factor']:5.2f} +- {row['constraint_factor_standard_error']:4.2f} "
              f"(plateau {row['plateau_constraint_factor']:5.2f} +- {row['plateau_constraint_factor_standard_error']:4.2f}), ff_c {row['flow_function']:.1f}")

    # The seed's reading (004 Sec. 2.3.5, after Wang et al.): C independent of the consolidation stress.
    # Tested as one weighted mean: chi^2 of the points about it against its degrees of freedom.
    for key in ["constraint_factor", "plateau_constraint_factor"]:
        w = [1 / r[f"{key}_standard_error"] ** 2 for r in table]
        mean = sum(wi * r[key] for wi, r in zip(w, table)) / sum(w)
        chi2 = sum(wi * (r[key] - mean) ** 2 for wi, r in zip(w, table))
        dof = len(table) - 1
        print(f"{key}: a constant C fits as {mean:.2f} +- {sum(w) ** -0.5:.2f}, chi^2 {chi2:.1f} on {dof} degrees of freedom (p = {upper_tail(dof, chi2):.3f})")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = [r["consolidation_stress_Pa"] / 1e3 for r in table]
    fig, ax = plt.subplots(1, 2, figsize=(12, 5))
    for key, label, color in [("hardness", "H, after unloading", "C0"), ("plateau_hardness", f"H, plateau (h/r {a.window})", "C2"), ("unconfined_yield_strength", "sigma_c, unconfined compression", "C3")]:
        ax[0].errorbar(s, [r[f"{key}_Pa"] / 1e3 for r in table], yerr=[r[f"{key}_standard_error_Pa"] / 1e3 for r in table], fmt="o-", color=color, capsize=3, label=label)
    for s1, fills in sigma_c.items():
        if len(fills) > 1:
            ax[0].plot([s1 / 1e3] * len(fills), [x[0] / 1e3 for x in fills], "x", color="C3", alpha=0.6)
    for s1, fills in hardness.items():
        if len(fills) > 1:
            ax[0].plot([s1 / 1e3] * len(fills), [x[0] / 1e3 for x in fills], "x", color="C0", alpha=0.6)
            ax[0].plot([s1 / 1e3] * len(fills), [x[2] / 1e3 for x in fills], "+", color="C2", alpha=0.6)
    ax[0].set(xscale="log", yscale="log", xlabel="sigma_1, consolidation stress [kPa]", ylabel="[kPa]", title="hardness and unconfined yield strength (x, +: single fills)")
    ax[0].legend(fontsize=8)
    ax[1].errorbar(s, [r["constraint_factor"] for r in table], yerr=[r["constraint_factor_standard_error"] for r in table], fmt="o-", color="C0", capsize=3, label="C = H / sigma_c (the unit's measured C)")
    ax[1].errorbar(s, [r["plateau_constraint_factor"] for r in table], yerr=[r["plateau_constraint_factor_standard_error"] for r in table], fmt="s--", color="C2", capsize=3, label="plateau H / sigma_c")
    ax[1].axhline(3.0, color="0.5", ls=":", label="C = 3, the unit's constant (004 Eq. 2.10)")
    ax[1].set(xscale="log", xlabel="sigma_1, consolidation stress [kPa]", ylabel="C [-]", title="constraint factor", ylim=(0, None))
    ax[1].legend(fontsize=8)
    for axis in ax:
        axis.grid(alpha=0.3, which="both")
    fig.suptitle("004 Ch. 6 material: BallIndentation's and UnconfinedCompression's default tests on beds consolidated to sigma_1 (error bars: standard errors)")
    fig.tight_layout()
    fig.savefig(a.plot, dpi=110)
    print(f"wrote {a.plot}")


if __name__ == "__main__":
    main()
