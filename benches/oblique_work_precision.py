"""Speed against error for oblique impacts: Chung and Ooi's Test 4 sphere (alumina on a rigid plane at
3.9 m/s, Hertz-Mindlin, mu = 0.092) by velocity Verlet at time steps from 0.2 to 0.0002 of the Rayleigh
step and by the adaptive integrator (stick-slip switches located) at tolerances 1e-4 to 1e-10, against
the adaptive one at 1e-12 (the reference). Per setting: the largest error over 89 angles (1-89 deg) in
the tangential restitution and in the spin (relative to the spin's largest value), and the wall time
per impact (89 impacts in one `powderfmu oblique` call, process start included, median of 5).

    python benches/oblique_work_precision.py [--csv docs/data/oblique_work_precision.csv]
"""

import argparse
import csv
import os
import statistics
import subprocess
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.join(HERE, "..")
CLI = os.environ.get("POWDERFMU_CLI", os.path.join(REPO, "target", "release", "powderfmu"))
SCENE = os.path.join(REPO, "scenes", "chung_ooi_alumina.json")
ANGLES = ",".join(str(a) for a in range(1, 90))


def run(fraction, tolerance=None):
    extra = ["--solver", "adaptive", "--tolerance", repr(tolerance)] if tolerance else []
    t0 = time.perf_counter()
    out = subprocess.run([CLI, "oblique", SCENE, "--speed", "3.9", "--angles", ANGLES, "--rayleigh-fraction", repr(fraction)] + extra,
                         capture_output=True, text=True, check=True).stdout
    wall = time.perf_counter() - t0
    rows = list(csv.DictReader(out.splitlines()))
    return wall, [(float(r["tangential_restitution"]), float(r["angular_velocity_out_rad_per_s"])) for r in rows]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--csv")
    a = p.parse_args()
    _, ref = run(0.5, 1e-12)
    w_scale = max(abs(w) for _, w in ref)
    table = []
    settings = [("verlet", f, None) for f in (0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.0002)]
    settings += [("adaptive", 0.5, tol) for tol in (1e-4, 1e-6, 1e-8, 1e-10)]
    for solver, fraction, tol in settings:
        walls = []
        for _ in range(5):
            wall, rows = run(fraction, tol)
            walls.append(wall)
        e_t = max(abs(r[0] - q[0]) for r, q in zip(rows, ref))
        e_w = max(abs(r[1] - q[1]) for r, q in zip(rows, ref)) / w_scale
        table.append({"solver": solver, "rayleigh_fraction": fraction, "tolerance": tol or "", "max_error_tangential_restitution": f"{e_t:.3e}",
                      "max_error_spin_relative": f"{e_w:.3e}", "wall_time_per_impact_s": f"{statistics.median(walls) / 89:.3e}"})
        print(table[-1])
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0]))
            w.writeheader()
            w.writerows(table)


if __name__ == "__main__":
    main()
