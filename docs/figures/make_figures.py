#!/usr/bin/env python3
"""Draws the figures of docs/models.md from the command-line tool's CSV output.

    bash docs/figures/make_figures.sh

force_overlap.png: force-overlap loops of every law on 004 Tables 4.1-4.2 (load, unload to detachment,
reload further, unload). restitution.png: restitution of undamped impacts against impact velocity by
energy balance, same scene."""
import io
import json
import pathlib
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
BIN = ROOT / "target" / "release" / "powderfmu"
SCENE = json.loads((ROOT / "scenes" / "pasha_table_4_2.json").read_text())
OUT = ROOT / "docs" / "figures"
R = SCENE["particle_radius"]

LINEAR = ["nan", "pasha", "pasha_simplified", "luding", "walton_braun", "linear"]
NONLINEAR = ["thornton_ning", "tomas", "jkr", "jkr_modified", "hertz"]


def run(model, *args):
    scene = dict(SCENE, contact_model=model)
    if model == "nan":
        # The Nan law with its own correlations (000 Sec. 3: k_el = pi R* p_y, k_p = k_el), not with
        # Pasha's stiffnesses read off Thornton-Ning's curves: its k_e grows from k_el (Eq. 46).
        scene.pop("elastic_stiffness")
        scene.pop("plastic_stiffness")
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(scene, f)
    out = subprocess.run([str(BIN), args[0], f.name, *args[1:]], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{model}: {out.stderr}")
    return out.stdout


def table(text, cols):
    data = np.genfromtxt(io.StringIO(text), delimiter=",", names=True, dtype=None, encoding=None, comments="#")
    return [np.asarray(data[c], dtype=float) for c in cols]


def loops():
    path = ",".join(f"{x * R:e}" for x in (0.02, -0.002, 0.035, -0.004))
    limits = {"linear laws": (-22, 22), "nonlinear laws": (-7, 22)}
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, group, title in ((axes[0], LINEAR, "linear laws"), (axes[1], NONLINEAR, "nonlinear laws")):
        for model in group:
            a, f = table(run(model, "curve", "--path", path, "--points", "1500"), ["overlap_m", "force_N"])
            ax.plot(a * 1e9, f * 1e6, label=model, lw=1.2)
        ax.axhline(0, color="0.6", lw=0.6)
        ax.set_xlim(-12, 90)
        ax.set_ylim(*limits[title])
        ax.set_xlabel("overlap alpha [nm]")
        ax.set_ylabel("normal force f [uN]")
        ax.set_title(f"{title}: load 2 % R, unload, reload 3.5 % R, unload", fontsize=10)
        ax.legend(fontsize=8)
    fig.suptitle("Force-overlap loops, 004 Tables 4.1-4.2 (R = 2.45 um ammonium fluorescein on silicon)")
    fig.tight_layout()
    fig.savefig(OUT / "force_overlap.png", dpi=110)


def restitution():
    v = np.geomspace(0.3, 40, 60)
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for model in ["thornton_ning", "nan", "pasha", "pasha_simplified", "luding", "tomas", "jkr"]:
        text = run(model, "restitution", "--velocities", ",".join(f"{x:g}" for x in v))
        vi, e = table(text, ["impact_velocity_m_per_s", "restitution"])
        style = dict(color="k", lw=2.2) if model == "thornton_ning" else dict(lw=1.2)
        label = "nan (000 Sec. 3 correlations)" if model == "nan" else model
        ax.plot(vi, e, label=label, **style)
    ax.set_xscale("log")
    ax.set_xlabel("impact velocity [m/s]")
    ax.set_ylabel("coefficient of restitution [-]")
    ax.set_title("Undamped impacts by energy balance, 004 Tables 4.1-4.2")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(OUT / "restitution.png", dpi=110)


if __name__ == "__main__":
    if not BIN.exists():
        sys.exit("build the tool first: cargo build --release")
    loops()
    restitution()
    print(f"wrote {OUT / 'force_overlap.png'} and {OUT / 'restitution.png'}")
