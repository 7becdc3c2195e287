"""The detachment threshold of one never-yielding particle against the drive frequency, through the
contact's natural frequency: the system's bisection (powderfmu.sieve.detachment_threshold) against the
quasi-static closed form f_ce/m + g (000 Eq. 5) and a linear base-excited oscillator at the contact's
elastic frequency, a* = (f_ce/m + g) sqrt((1 - r^2)^2 + (2 zeta r)^2), r = f/f_c.

    python benches/sieve_threshold.py [--out docs/data/sieve/threshold.csv] [--plot docs/figures/sieve_threshold.png]
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from powderfmu import sieve
from powderfmu.fmus import repository

REPO = repository()
# 10 um particles of the default powder, made hard enough never to yield (p_y = 1e8 Pa, above the
# critical 3.2e7 Pa of 000 Eq. 80 at this size, and above every compressive half-cycle's load here).
POWDER = {"particle_yield_pressure": 1e8, "wall_yield_pressure": 1.2e8}
RADIUS = 10e-6


def analyze(keys: dict) -> dict:
    scene = {**sieve.POWDER_DEFAULTS, **keys, "particle_radius": RADIUS}
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(scene, f)
    out = subprocess.run([str(REPO / "target" / "release" / "powderfmu"), "analyze", "--json", f.name], capture_output=True, text=True, check=True)
    flat = {}

    def walk(d):
        for k, v in d.items():
            if isinstance(v, dict):
                walk(v)
            else:
                flat.setdefault(k, v)

    walk(json.loads(out.stdout))
    return flat


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(REPO / "docs/data/sieve/threshold.csv"))
    ap.add_argument("--plot", default=str(REPO / "docs/figures/sieve_threshold.png"))
    ap.add_argument("--points", type=int, default=15)
    args = ap.parse_args()
    a = analyze(POWDER)
    m, k_el = a["effective_mass"], a["k_el"]
    f_c = math.sqrt(k_el / m) / (2 * math.pi)
    e = sieve.POWDER_DEFAULTS["restitution_coefficient"]
    zeta = -math.log(e) / math.sqrt(math.pi**2 + math.log(e) ** 2)
    spec = {**POWDER, "radius_spread": 1.0, "particle_radius": RADIUS, "plate_mass": 1.0, "periods": 10}
    quasi_static = a["f_ce"] / m + sieve.SYSTEM_DEFAULTS["gravity"]
    print(f"particle R = {RADIUS:g} m, m = {m:.4e} kg, k_el = {k_el:.4e} N/m: f_c = {f_c:.4e} Hz, zeta = {zeta:.3f}; quasi-static threshold {quasi_static:.4e} m/s2")
    rows = []
    for f in np.logspace(3, math.log10(8 * f_c), args.points):
        started = time.perf_counter()
        thr = sieve.detachment_threshold({**spec, "frequency": float(f)}, rel_tol=2e-3)
        r = f / f_c
        sdof = quasi_static * math.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2)
        rows.append({"frequency": f, "f_over_fc": r, "threshold": thr, "quasi_static": quasi_static, "oscillator": sdof, "seconds": time.perf_counter() - started})
        print(f"  f = {f:10.4e} Hz (f/f_c {r:7.4f}): threshold {thr:.4e} m/s2 = {thr / quasi_static:6.3f} x quasi-static; oscillator {sdof / quasi_static:6.3f}", flush=True)
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    with open(args.out, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fr = np.array([r["f_over_fc"] for r in rows])
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        ax.loglog(fr, [r["threshold"] for r in rows], "o-", label="system (CS, bisection)")
        x = np.logspace(math.log10(fr.min()), math.log10(fr.max()), 400)
        ax.loglog(x, quasi_static * np.sqrt((1 - x * x) ** 2 + (2 * zeta * x) ** 2), "--", label=f"linear oscillator at f_c, zeta = {zeta:.2f}")
        ax.axhline(quasi_static, color="k", lw=0.8, label="quasi-static f_ce/m + g")
        ax.set_xlabel("drive frequency / contact frequency f/f_c  [-]")
        ax.set_ylabel("detachment threshold, peak plate acceleration [m/s$^2$]")
        ax.set_title(f"one 10 um particle (never yields), f_c = {f_c / 1e6:.2f} MHz")
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=130)
        print(f"wrote {args.out} and {args.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
