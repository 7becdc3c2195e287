"""The cost of a Co-Simulation step of ParticleWallImpact through FMI 3.0 against FMI 2.0, side by side in
one process: fmpy's own calls (doStep and one get, as a master makes them) and the bare C functions
through ctypes (fmi2DoStep with 4 arguments, fmi3DoStep with 8). Medians of 5 runs of 3000 (fmpy) and
20000 (ctypes) steps of 1e-10 s on the default impact, one instance of each version alive at once.

    python benches/fmi3_overhead.py [--fmu-dir target/fmu]
"""

import argparse
import ctypes
import os
import statistics
import time

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def instances(fmu_dir):
    d2 = extract(os.path.join(fmu_dir, "ParticleWallImpact.fmu"))
    d3 = extract(os.path.join(fmu_dir, "fmi3", "ParticleWallImpact.fmu"))
    md2, md3 = read_model_description(d2), read_model_description(d3)
    f2 = FMU2Slave(guid=md2.guid, unzipDirectory=d2, modelIdentifier="ParticleWallImpact", instanceName="fmi2")
    f2.instantiate()
    f2.setupExperiment(startTime=0.0)
    f2.enterInitializationMode()
    f2.exitInitializationMode()
    f3 = FMU3Slave(guid=md3.guid, unzipDirectory=d3, modelIdentifier="ParticleWallImpact", instanceName="fmi3")
    f3.instantiate()
    f3.enterInitializationMode()
    f3.exitInitializationMode()
    force2 = next(v.valueReference for v in md2.modelVariables if v.name == "force")
    force3 = next(v.valueReference for v in md3.modelVariables if v.name == "force")
    return f2, f3, force2, force3


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--fmu-dir", default=os.path.join(ROOT, "target", "fmu"))
    a = p.parse_args()
    f2, f3, force2, force3 = instances(a.fmu_dir)
    h = 1e-10
    # The bare C calls: fmi2DoStep(c, t, h, flag) and fmi3DoStep(c, t, h, flag, 4 outputs).
    s2 = ctypes.CDLL(f2.dll._name).fmi2DoStep
    s2.argtypes, s2.restype = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_int], ctypes.c_int
    s3 = ctypes.CDLL(f3.dll._name).fmi3DoStep
    s3.argtypes, s3.restype = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_bool] + [ctypes.c_void_p] * 4, ctypes.c_int
    flags = [ctypes.c_bool() for _ in range(3)]
    last = ctypes.c_double()
    outs = [ctypes.addressof(x) for x in flags] + [ctypes.addressof(last)]
    results = {"fmpy 2.0": [], "fmpy 3.0": [], "C 2.0": [], "C 3.0": []}
    t2 = t3 = 0.0
    for _ in range(5):
        n = 3000
        t0 = time.perf_counter()
        for _ in range(n):
            f2.doStep(t2, h)
            f2.getReal([force2])
            t2 += h
        results["fmpy 2.0"].append((time.perf_counter() - t0) / n)
        t0 = time.perf_counter()
        for _ in range(n):
            f3.doStep(t3, h)
            f3.getFloat64([force3])
            t3 += h
        results["fmpy 3.0"].append((time.perf_counter() - t0) / n)
        n = 20000
        t0 = time.perf_counter()
        for _ in range(n):
            assert s2(f2.component, t2, h, 1) == 0
            t2 += h
        results["C 2.0"].append((time.perf_counter() - t0) / n)
        t0 = time.perf_counter()
        for _ in range(n):
            assert s3(f3.component, t3, h, True, *outs) == 0
            t3 += h
        results["C 3.0"].append((time.perf_counter() - t0) / n)
    print("| calls | FMI 2.0 [us per step] | FMI 3.0 [us per step] | 3.0 / 2.0 |")
    print("|---|---:|---:|---:|")
    for what in ("fmpy", "C"):
        m2, m3 = statistics.median(results[f"{what} 2.0"]), statistics.median(results[f"{what} 3.0"])
        label = "fmpy doStep + one get" if what == "fmpy" else "bare doStep through ctypes"
        print(f"| {label} | {m2 * 1e6:.2f} | {m3 * 1e6:.2f} | {m3 / m2:.2f} |")


if __name__ == "__main__":
    main()
