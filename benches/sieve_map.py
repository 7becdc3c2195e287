"""The map users want: the detached fraction of the default powder over drive frequency and peak plate
acceleration, and the critical particle size against acceleration with the closed-form lines; both
sweeps run on dask.distributed (`powderfmu.sweep`), resumable.

    python benches/sieve_map.py [--workers 2] [--plot docs/figures/sieve_map.png]
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from powderfmu import sieve, sweep
from powderfmu.fmus import repository

REPO = repository()
DATA = REPO / "docs" / "data" / "sieve"


def column(rows, key):
    return np.array([float(r[key]) if r[key] not in ("", "nan") else math.nan for r in rows])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--plot", default=str(REPO / "docs/figures/sieve_map.png"))
    args = ap.parse_args()
    for name in ("map", "critical"):
        spec = sweep.load_spec(DATA / f"{name}_spec.json")
        counts = sweep.run(spec, DATA / f"{name}.csv", workers=args.workers)
        print(f"{name}: {counts['tasks']} tasks, {counts['ran']} ran, {counts['skipped']} already done, {counts['failed']} failed, {counts['wall_time']:.1f} s")

    _, rows = sweep.read(DATA / "map.csv")
    f, a, frac = column(rows, "frequency"), column(rows, "acceleration"), column(rows, "detached_mass_fraction")
    fs, accs = np.unique(f), np.unique(a)
    grid = np.full((len(accs), len(fs)), np.nan)
    for fi, ai, x in zip(f, a, frac):
        grid[np.searchsorted(accs, ai), np.searchsorted(fs, fi)] = x

    _, crows = sweep.read(DATA / "critical.csv")
    ca = column(crows, "acceleration")
    attached, detached = column(crows, "largest_attached_radius"), column(crows, "smallest_detached_radius")
    base = sweep.load_spec(DATA / "critical_spec.json")["base"]
    # The settled contacts' own pull-off forces (the unit's pull_off_force after settling) give each
    # particle's quasi-static threshold F_po/m + g; the closed form for a never-yielded contact is f_ce.
    settled = sieve.run({**base, "acceleration": 1.0, "periods": 0.01, "ramp_periods": 0})
    gamma, rho, g = settled.powder["surface_energy"], settled.powder["particle_density"], settled.system["gravity"]
    x = np.logspace(math.log10(ca.min()), math.log10(ca.max()), 200)
    r_fce = np.sqrt(9 * gamma / (8 * rho * np.maximum(x - g, 1e-30)))
    thr = settled.quasi_static_threshold  # falls with the radius
    order = np.argsort(thr)
    r_settled = np.interp(np.log(x), np.log(thr[order]), settled.radius[order], left=np.nan, right=np.nan)

    print("detached mass fraction (rows: acceleration [m/s2], columns: frequency [Hz])")
    print(" " * 9 + "".join(f"{x:9.0e}" for x in fs))
    for i, ai in enumerate(accs):
        print(f"{ai:9.0e}" + "".join(f"{grid[i, j]:9.2f}" for j in range(len(fs))))

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm  # noqa: F401 - log axes below

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11.5, 4.6))
    def edges(v):
        lv = np.log(v)
        mid = (lv[1:] + lv[:-1]) / 2
        return np.exp(np.concatenate([[lv[0] - (mid[0] - lv[0])], mid, [lv[-1] + (lv[-1] - mid[-1])]]))

    mesh = ax1.pcolormesh(edges(fs), edges(accs), grid, shading="flat", cmap="viridis", vmin=0, vmax=1)
    ax1.set_xscale("log")
    ax1.set_yscale("log")
    ax1.set_xlabel("drive frequency f [Hz]")
    ax1.set_ylabel("peak plate acceleration A (2 pi f)$^2$ [m/s$^2$]")
    ax1.set_title("detached mass fraction, default powder (median R 10 um)")
    fig.colorbar(mesh, ax=ax1, label="detached mass fraction [-]")
    ax2.loglog(x, r_fce * 1e6, "k--", label="closed form, never-yielded contact: f_ce/m + g = a")
    ax2.loglog(x, r_settled * 1e6, "C1-", label="closed form with each settled contact's pull-off force")
    ok = ~np.isnan(detached)
    ax2.loglog(ca[ok], detached[ok] * 1e6, "v", color="C3", label="smallest detached particle (system, 20 kHz)")
    ok = ~np.isnan(attached)
    ax2.loglog(ca[ok], attached[ok] * 1e6, "^", color="C2", label="largest particle that stayed")
    ax2.set_xlabel("peak plate acceleration a [m/s$^2$]")
    ax2.set_ylabel("particle radius [um]")
    ax2.set_title("critical particle size: larger ones leave")
    ax2.legend(fontsize=7)
    ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=130)
    print(f"wrote {args.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
