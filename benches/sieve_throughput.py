"""Throughput of the sieve system and its sweeps: tasks per second serially (in this process), on a
LocalCluster of 1 and of 2 workers (the same 16 tasks, cluster start included and not), and the cost
of one system run against its number of particles. Medians of --repeat runs, measured side by side.

    python benches/sieve_throughput.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

from powderfmu import sieve, sweep

SPEC = {"task": "sieve", "base": {"particles": 40, "periods": 10}, "grid": {"frequency": [2e4, 5e4, 1e5, 2e5], "acceleration": [5e5, 1e6, 2e6, 5e6]}}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    sieve.run({"particles": 1})  # the FMU extracted, imports warm
    n_tasks = len(sweep.points(SPEC))
    print(f"sweep of {n_tasks} tasks (40 particles, 10 periods of 100 steps each; cluster start included)")
    print("| runner | wall time [s] | tasks/s | vs serial |")
    print("|---|---:|---:|---:|")
    serial_rate = None
    for label, kw in (("serial (no Dask)", {"serial": True}), ("LocalCluster, 1 worker", {"workers": 1}), ("LocalCluster, 2 workers", {"workers": 2})):
        times = []
        for _ in range(args.repeat):
            with tempfile.TemporaryDirectory() as d:
                started = time.perf_counter()
                counts = sweep.run(SPEC, Path(d) / "s.csv", progress=False, **kw)
                times.append(time.perf_counter() - started)
                assert counts["ran"] == n_tasks
        t = statistics.median(times)
        rate = n_tasks / t
        serial_rate = serial_rate or rate
        print(f"| {label} | {t:.2f} | {rate:.1f} | {rate / serial_rate:.2f}x |", flush=True)
    print()
    print("one system run against its number of particles (20 kHz, 1e6 m/s2, 4 periods of 100 steps)")
    print("| particles | wall time [s] | fmi2DoStep calls | us per particle-step |")
    print("|---:|---:|---:|---:|")
    for n in (1, 4, 16, 64, 256):
        times, steps = [], 0
        for _ in range(args.repeat):
            r = sieve.run({"particles": n, "periods": 4, "frequency": 2e4, "acceleration": 1e6, "plate_mass": 1e-6})
            times.append(r.wall_time)
            steps = r.particle_steps
        t = statistics.median(times)
        print(f"| {n} | {t:.3f} | {steps} | {1e6 * t / max(steps, 1):.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
