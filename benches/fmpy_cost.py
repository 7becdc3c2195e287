"""End-to-end cost of one impact through fmpy.simulate_fmu: ParticleWallImpact on the default scene
(000 Table 5, Nan, undamped, 3 m/s) and with Thornton-Ning, in Co-Simulation with each solver and in
Model Exchange under fmpy's CVode. Median wall time of 5 runs each (after one warm-up), side by side
in one process; the restitution of each run against the closed form shows what the time buys.

Usage: python benches/fmpy_cost.py [--fmu-dir target/fmu] [--out docs/figures/fmpy_cost.csv]
"""

import argparse
import csv
import os
import statistics
import time

from fmpy import extract, simulate_fmu

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
V = 3.0
STOP = 3e-7
INTERVAL = 1e-9

RUNS = [
    # label, law, fmi_type, start values beyond the law, relative tolerance (ME)
    ("CS exact", "nan", "CoSimulation", {"solver": "exact"}, None),
    ("CS adaptive 1e-10", "nan", "CoSimulation", {"solver": "adaptive", "tolerance": 1e-10}, None),
    ("CS adaptive 1e-6", "nan", "CoSimulation", {"solver": "adaptive", "tolerance": 1e-6}, None),
    ("CS verlet 0.2 t_R", "nan", "CoSimulation", {"solver": "verlet", "rayleigh_fraction": 0.2}, None),
    ("CS verlet 0.001 t_R", "nan", "CoSimulation", {"solver": "verlet", "rayleigh_fraction": 0.001}, None),
    ("ME CVode rtol 1e-8", "nan", "ModelExchange", {}, 1e-8),
    ("ME CVode rtol 1e-6", "nan", "ModelExchange", {}, 1e-6),
    ("CS adaptive 1e-10", "thornton_ning", "CoSimulation", {"solver": "adaptive", "tolerance": 1e-10}, None),
    ("ME CVode rtol 1e-8", "thornton_ning", "ModelExchange", {}, 1e-8),
]


def run(unzipdir, fmu, law, fmi_type, start, rtol):
    values = {"initial_velocity": V, "contact_model": law, **start}
    t = time.perf_counter()
    r = simulate_fmu(
        unzipdir,
        fmi_type=fmi_type,
        stop_time=STOP,
        output_interval=INTERVAL,
        start_values=values,
        relative_tolerance=rtol,
        output=["sphere_velocity"],
    )
    return time.perf_counter() - t, r["sphere_velocity"][-1] / V


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu-dir", default=os.path.join(ROOT, "target", "fmu"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "figures", "fmpy_cost.csv"))
    a = ap.parse_args()
    fmu = os.path.join(a.fmu_dir, "ParticleWallImpact.fmu")
    unzipdir = extract(fmu)
    rows = []
    for label, law, fmi_type, start, rtol in RUNS:
        run(unzipdir, fmu, law, fmi_type, start, rtol)
        samples = [run(unzipdir, fmu, law, fmi_type, start, rtol) for _ in range(5)]
        ms = statistics.median(s[0] for s in samples) * 1e3
        e = samples[0][1]
        rows.append({"law": law, "run": label, "median_ms": f"{ms:.2f}", "restitution": f"{e:.10f}"})
        print(f"fmpy_cost: {law:14s} {label:22s} {ms:8.2f} ms  restitution {e:.10f}", flush=True)
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["law", "run", "median_ms", "restitution"])
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
