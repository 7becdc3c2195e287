#!/usr/bin/env python3
"""The figure of docs/indentation.md's "The stiff 45 mm die's 30 mm bed": the seed's 13 mm indenter's hardness
over its window (h/r 0.35-0.5) against the bed's height, every stiff Ch. 5 bed run with EDEM's friction limit
(004 Sec. 5.2, Fig. 5.12: about 8 kPa on the 13 mm bed in the 39 mm die, about 6 kPa on the 20, 30 and 50 mm
beds in the 45 mm die).

One marker per fill (a prepared bed), its height as `bed prepare` printed it (quoted in docs/indentation.md
beside each CSV); per height of the 45 mm die, the fills' mean with the standard error of the quarter beds'
pooled bed-to-bed scatter over the number of fills. The seed's two levels are drawn at its nominal heights
with half a kilopascal of reading error (its figures are missing; the levels are its prose's).

    .venv/bin/python benches/plot_ch5_bed_height.py [OUT.png]
"""

import math
import statistics
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from indentation_rate import load, summary  # noqa: E402  (the window mean of every indentation bench)

REPO = Path(__file__).resolve().parent.parent
WINDOW = (0.35, 0.5)
# (CSV under docs/data, bed height [mm] as prepared, group)
FILLS = [
    ("ch5_quarter45_13mm_edem_friction.csv", 14.63, "45 mm die, quarter"),
    ("ch5_quarter45_13mm_edem_friction_seed2.csv", 14.65, "45 mm die, quarter"),
    ("ch5_quarter45_20mm_edem_friction.csv", 22.36, "45 mm die, quarter"),
    ("ch5_quarter45_20mm_edem_friction_seed2.csv", 22.38, "45 mm die, quarter"),
    ("ch5_quarter45_20mm_edem_friction_seed3.csv", 22.36, "45 mm die, quarter"),
    ("ch5_quarter45_30mm_edem_friction.csv", 31.99, "45 mm die, quarter"),
    ("ch5_quarter39_13mm_edem_friction.csv", 14.69, "39 mm die, quarter"),
    ("ch5_quarter39_13mm_edem_friction_seed2.csv", 14.71, "39 mm die, quarter"),
    ("ch5_whole39_13mm_edem_friction.csv", 14.49, "39 mm die, whole"),
    ("ch5_whole39_seed2_13mm_edem_friction.csv", 14.49, "39 mm die, whole"),
]
STYLE = {"45 mm die, quarter": ("tab:blue", "o"), "39 mm die, quarter": ("tab:orange", "s"), "39 mm die, whole": ("tab:green", "D")}
# 004 Sec. 5.2 (Fig. 5.12), its prose: (nominal height [mm], kPa)
SEED = [(13.0, 8.0), (20.0, 6.0), (30.0, 6.0), (50.0, 6.0)]
SEED_READING_ERROR = 0.5  # kPa, assumed: levels stated as "about"


def readings():
    out = []
    for name, height, group in FILLS:
        path = REPO / "docs" / "data" / name
        if not path.exists():
            sys.exit(f"{path}: missing (docs/indentation.md says how it was run)")
        out.append((height, summary(load(path), WINDOW)["plateau"] / 1e3, group))
    return out


def pooled_sd(values_by_group):
    """The bed-to-bed standard deviation pooled over the groups of fills of one bed (n - 1 each)."""
    squares = sum(sum((v - statistics.fmean(vs)) ** 2 for v in vs) for vs in values_by_group if len(vs) > 1)
    dof = sum(len(vs) - 1 for vs in values_by_group if len(vs) > 1)
    return math.sqrt(squares / dof), dof


def main(out):
    rows = readings()
    quarters = {}
    for height, kpa, group in rows:
        if "quarter" in group:
            quarters.setdefault((group, round(height)), []).append(kpa)
    sd, dof = pooled_sd(list(quarters.values()))
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for nominal, level in SEED:
        ax.errorbar(nominal, level, yerr=SEED_READING_ERROR, fmt="_", ms=18, color="black", capsize=0, lw=1.0)
    ax.plot([], [], "_", color="black", ms=12, label="004 Fig. 5.12 as its prose states (+-0.5 kPa assumed)")
    for group, (colour, marker) in STYLE.items():
        xs = [h for h, _, g in rows if g == group]
        ys = [k for _, k, g in rows if g == group]
        ax.plot(xs, ys, marker, color=colour, mfc="none", label=f"{group}, one fill each")
    for (group, height), values in sorted(quarters.items()):
        if group.startswith("45"):
            mean = statistics.fmean(values)
            hs = [h for h, _, g in rows if g == group and round(h) == height]
            ax.errorbar(statistics.fmean(hs) + 0.6, mean, yerr=sd / math.sqrt(len(values)), fmt="o", color="tab:blue", capsize=3)
            print(f"45 mm die, {height} mm: {len(values)} fill(s), mean {mean:.2f} +- {sd / math.sqrt(len(values)):.2f} kPa")
    ax.plot([], [], "o", color="tab:blue", label=f"45 mm die: mean of the fills +- pooled SE ({sd:.2f} kPa SD, {dof} dof)")
    ax.set_xlabel("bed height [mm] (as prepared; the seed's at its nominal heights)")
    ax.set_ylabel(f"F / A(h) over h/r {WINDOW[0]}-{WINDOW[1]} [kPa]")
    ax.set_xlim(10.0, 53.0)
    ax.set_ylim(4.0, 11.0)
    ax.text(50.0, 6.8, "50 mm bed:\nnot run stiff", ha="center", fontsize=8)
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title("stiff Ch. 5 beds (E = 55 GPa, EDEM's friction limit), 13 mm indenter at 13 mm/s", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"pooled bed-to-bed SD of the quarters {sd:.3f} kPa over {dof} degrees of freedom; wrote {out}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "docs" / "figures" / "ch5_bed_height.png")
