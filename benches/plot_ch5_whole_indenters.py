#!/usr/bin/env python3
"""The figure of docs/indentation.md's "The seed's 16 and 19 mm indenters on the stiff whole die": F/A(h)
against h/r for the 13, 16 and 19 mm indenters on the first stiff whole 39 mm die (004 Sec. 5.2, Figs. 5.3-5.4)
and the 13 mm indenter on the second (fill seed 2), with the seed's window shaded and its "about 8 kPa" drawn.

Reads docs/data/ch5_whole39_<D>mm_edem_friction.csv and ch5_whole39_seed2_13mm_edem_friction.csv
(`powderfmu bed indent ... --every 1e-3 --out`) and writes docs/figures/ch5_whole39_indenters.png.

    .venv/bin/python benches/plot_ch5_whole_indenters.py [OUT.png]
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from indentation_rate import load, summary  # noqa: E402  (the window mean of every indentation bench)
from plot_indentation_window import binned  # noqa: E402  (F/A(h) in bins of 0.01 h/r)

REPO = Path(__file__).resolve().parent.parent
# (CSV under docs/data, label, colour, line style)
CURVES = [
    ("ch5_whole39_13mm_edem_friction.csv", "13 mm indenter, first die", "tab:blue", "-"),
    ("ch5_whole39_16mm_edem_friction.csv", "16 mm indenter, first die", "tab:orange", "-"),
    ("ch5_whole39_19mm_edem_friction.csv", "19 mm indenter, first die", "tab:green", "-"),
    ("ch5_whole39_seed2_13mm_edem_friction.csv", "13 mm indenter, second die (fill seed 2)", "tab:purple", "--"),
]
SEED = 8.0  # kPa: 004 Sec. 5.2, "stabilises around 8 kPa" after h/r 0.35-0.4 for 13-19 mm
WINDOW = (0.35, 0.5)


def main(out):
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    ax.axvspan(*WINDOW, color="0.92", zorder=0)
    ax.axhline(SEED, color="black", lw=1.0, ls="--", label="004 Sec. 5.2: about 8 kPa (13-19 mm)")
    for name, label, colour, style in CURVES:
        path = REPO / "docs" / "data" / name
        if not path.exists():
            sys.exit(f"{path}: missing (docs/indentation.md says how it was run)")
        rows = load(path)
        x, y = binned(rows)
        level = summary(rows, WINDOW)["plateau"] / 1e3
        ax.plot(x, y, color=colour, lw=1.0, ls=style, label=f"{label}: {level:.2f} kPa over h/r {WINDOW[0]}-{WINDOW[1]}")
    ax.set_xlabel("h / r [-] (depth from the first touch)")
    ax.set_ylabel("F / A(h) [kPa] (mean over bins of 0.01 h/r)")
    ax.set_xlim(0.0, 0.5)
    ax.set_ylim(0.0, 14.0)
    ax.text(sum(WINDOW) / 2, 13.2, "seed's window", ha="center", fontsize=9)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title("stiff whole 39 mm dies (16000 spheres, E = 55 GPa, EDEM's friction limit), 13 mm/s", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "docs" / "figures" / "ch5_whole39_indenters.png")
