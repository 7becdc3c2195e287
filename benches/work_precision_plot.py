"""Figures and tables of the work-precision study, from the CSV files `cargo bench --bench work_precision`
and `benches/fmpy_cost.py` write to docs/figures/.

Writes docs/figures/work_precision.png and docs/figures/fidelity.png, and replaces the generated part of
docs/benchmarks.md between its `work-precision` markers.

Usage: python benches/work_precision_plot.py
"""

import csv
import math
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIG = os.path.join(ROOT, "docs", "figures")
DOC = os.path.join(ROOT, "docs", "benchmarks.md")
BEGIN, END = "<!-- work-precision:begin -->", "<!-- work-precision:end -->"
FLOOR = 1e-17  # errors of exactly zero are drawn here
TARGET = 1e-6  # the error at which costs are compared
COLORS = {"exact": "tab:red", "adaptive": "tab:blue", "verlet": "tab:gray"}
STYLES = {"below": ":", "near": "--", "far": "-"}


def number(s):
    try:
        x = float(s)
    except ValueError:
        return math.nan
    return x


def load(name):
    with open(os.path.join(FIG, name), newline="") as f:
        return list(csv.DictReader(f))


def error(row):
    """The error that matters for a case: the rebound for impacts that rebound, the maximum overlap for
    impacts that stick (no rebound to compare)."""
    e = number(row["rebound_rel_error"])
    return e if not math.isnan(e) else number(row["max_overlap_rel_error"])


def work_precision_figure(rows):
    laws = list(dict.fromkeys(r["law"] for r in rows))
    cols = 4
    fig, axes = plt.subplots(math.ceil(len(laws) / cols), cols, figsize=(16, 3.4 * math.ceil(len(laws) / cols)), sharex=True, sharey=True)
    for ax, law in zip(axes.flat, laws):
        for case, style in STYLES.items():
            for solver, color in COLORS.items():
                pts = [(number(r["ns_per_impact"]), max(error(r), FLOOR)) for r in rows if r["law"] == law and r["case"] == case and r["solver"] == solver]
                pts = [p for p in pts if not math.isnan(p[0]) and not math.isnan(p[1])]
                if not pts:
                    continue
                xs, ys = zip(*sorted(pts))
                marker = "*" if solver == "exact" else "o"
                ax.loglog(xs, ys, style, color=color, marker=marker, ms=9 if solver == "exact" else 3, lw=1)
        ax.axhline(TARGET, color="k", lw=0.5, alpha=0.4)
        ax.set_title(law, fontsize=10)
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes.flat[len(laws):]:
        ax.axis("off")
    for ax in axes[-1]:
        ax.set_xlabel("native cost per impact [ns]")
    for ax in axes[:, 0]:
        ax.set_ylabel("relative error")
    handles = [plt.Line2D([], [], color=c, marker="*" if s == "exact" else "o", label=s) for s, c in COLORS.items()]
    handles += [plt.Line2D([], [], color="k", ls=st, label=f"{c} sticking" + (" (error of max overlap)" if c == "below" else "")) for c, st in STYLES.items()]
    fig.legend(handles=handles, loc="upper center", ncol=6, fontsize=9, bbox_to_anchor=(0.5, 0.945))
    fig.suptitle("Work-precision of one sphere-wall impact, 000 Table 5 (R = 2.45 um): error of the rebound velocity (of the maximum overlap where the sphere sticks) against cost; exact = closed form per branch, adaptive = Dormand-Prince over tolerances 1e-4..1e-11, verlet = fixed step over 0.3..1e-5 of the Rayleigh step", fontsize=10, wrap=True)
    fig.tight_layout(rect=(0, 0, 1, 0.91))
    fig.savefig(os.path.join(FIG, "work_precision.png"), dpi=110)


def fidelity_figure(curves, summary):
    fig, ax = plt.subplots(figsize=(8, 5))
    for law in dict.fromkeys(r["law"] for r in curves):
        pts = [(number(r["impact_velocity_m_s"]), number(r["restitution"])) for r in curves if r["law"] == law]
        xs, ys = zip(*pts)
        tn = law == "thornton_ning"
        ax.semilogx(xs, ys, "k-" if tn else "-", lw=2.5 if tn else 1.2, label=law)
    ax.set_xlabel("impact velocity [m/s]")
    ax.set_ylabel("coefficient of restitution [-]")
    ax.set_title("004 Table 4.1 (ammonium fluorescein on silicon, R = 2.45 um): each linear law from its own correlations, against Thornton-Ning", fontsize=9, wrap=True)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(FIG, "fidelity.png"), dpi=110)


def cheapest(rows, law, case, solver, target):
    """The cheapest run of a solver from which on every costlier run has an error of at most `target`
    (Verlet's error is not monotone in the step: a lucky cancellation does not count); (ns, error) or None."""
    runs = sorted((number(r["ns_per_impact"]), error(r)) for r in rows if r["law"] == law and r["case"] == case and r["solver"] == solver)
    runs = [p for p in runs if not math.isnan(p[0])]
    for i, p in enumerate(runs):
        if all(e <= target for _, e in runs[i:]):
            return p
    return None


def best(rows, law, case, solver):
    pts = [(error(r), number(r["ns_per_impact"])) for r in rows if r["law"] == law and r["case"] == case and r["solver"] == solver and not math.isnan(error(r))]
    return min(pts) if pts else None


def fmt_ns(ns):
    return f"{ns / 1e3:.1f} us" if ns < 1e6 else f"{ns / 1e6:.1f} ms"


def tables(rows, summary, fmpy_rows):
    out = []
    out.append("### Cost at equal error: rebound velocity to 1e-6 (maximum overlap where the sphere sticks)\n")
    out.append("Cheapest run of each solver from which on every costlier run has an error of at most 1e-6, native, one impact from just before contact to just after separation in one communication step; `exact` at its own error. Ratio: verlet's cost over exact's (over adaptive's for the nonlinear laws).\n")
    out.append("| law | case | v [m/s] | exact: error, cost | adaptive at 1e-6 | verlet at 1e-6 | verlet / best |")
    out.append("|---|---|---:|---|---|---|---:|")
    for law in dict.fromkeys(r["law"] for r in rows):
        for case in ("below", "near", "far"):
            sel = [r for r in rows if r["law"] == law and r["case"] == case]
            if not sel:
                continue
            v = number(sel[0]["impact_velocity_m_s"])
            ex = cheapest(rows, law, case, "exact", math.inf)
            ad = cheapest(rows, law, case, "adaptive", TARGET)
            ve = cheapest(rows, law, case, "verlet", TARGET)
            ex_s = f"{ex[1]:.0e}, {fmt_ns(ex[0])}" if ex else "-"
            ad_s = fmt_ns(ad[0]) if ad else "not reached"
            finest = max((number(r["ns_per_impact"]) for r in sel if r["solver"] == "verlet"), default=None)
            if ve:
                ve_s = fmt_ns(ve[0])
            else:
                b = best(rows, law, case, "verlet")
                ve_s = f"not for every finer step (best run {b[0]:.0e} at {fmt_ns(b[1])})" if b else "-"
            base = ex[0] if ex else (ad[0] if ad else None)
            if ve and base:
                ratio = f"{ve[0] / base:.0f}"
            elif base and finest:
                # A stable 1e-6 needs a step finer than the finest tried: more than its cost.
                ratio = f"> {finest / base:.0f}"
            else:
                ratio = "-"
            out.append(f"| {law} | {case} | {v:.3g} | {ex_s} | {ad_s} | {ve_s} | {ratio} |")
    out.append("")
    out.append("### Fidelity: each linear law against Thornton-Ning on 004 Table 4.1\n")
    out.append("Undamped restitution from each law's closed form (the energy balance for Thornton-Ning) over 0.1-10 m/s, each law with the stiffnesses its own correlations give from the material data; cost of one force evaluation through `AnyLaw` (median, this run; `cargo bench --bench laws` has the concrete-law figures).\n")
    out.append("| law | sticking velocity [m/s] | RMS restitution difference to Thornton-Ning | ns / force evaluation |")
    out.append("|---|---:|---:|---:|")
    for r in summary:
        vs = r["sticking_velocity_m_s"]
        vs = vs if vs == "none" else f"{number(vs):.3f}"
        out.append(f"| {r['law']} | {vs} | {number(r['rms_restitution_difference_vs_thornton_ning']):.3f} | {number(r['ns_per_force_evaluation']):.1f} |")
    out.append("")
    if fmpy_rows:
        out.append("### End to end through fmpy.simulate_fmu\n")
        out.append("One impact at 3 m/s, 300 output points (`benches/fmpy_cost.py`), median of 5 runs; fmpy's own work dominates.\n")
        out.append("| law | run | median [ms] | restitution |")
        out.append("|---|---|---:|---:|")
        for r in fmpy_rows:
            out.append(f"| {r['law']} | {r['run']} | {r['median_ms']} | {r['restitution']} |")
        out.append("")
    return "\n".join(out)


def main():
    rows = load("work_precision.csv")
    curves = load("fidelity_curves.csv")
    summary = load("fidelity.csv")
    fmpy_path = os.path.join(FIG, "fmpy_cost.csv")
    fmpy_rows = load("fmpy_cost.csv") if os.path.exists(fmpy_path) else []
    work_precision_figure(rows)
    fidelity_figure(curves, summary)
    text = open(DOC).read()
    generated = f"{BEGIN}\n{tables(rows, summary, fmpy_rows)}\n{END}"
    if BEGIN in text:
        text = re.sub(re.escape(BEGIN) + ".*?" + re.escape(END), lambda _: generated, text, flags=re.S)
    else:
        text += "\n" + generated + "\n"
    with open(DOC, "w") as f:
        f.write(text)
    print("work_precision_plot: wrote docs/figures/work_precision.png, docs/figures/fidelity.png and the tables of docs/benchmarks.md")


if __name__ == "__main__":
    main()
