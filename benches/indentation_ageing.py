"""Does a slow indentation read harder because the bed ages during it? Holds BallIndentation's indenter
above the bed for a while (indenter_motion = input, the bed resting under gravity), then drives it in at
a constant speed to max_penetration, and prints the plateau hardness (the unit's output, and the mean
F/A(h) over 0.1 <= h/r <= 0.2 of the 1e-4 s samples, as `powderfmu bed indent --every 1e-4` gives).

    python benches/indentation_ageing.py --age 0.05 --speed 0.07145 --out aged.csv   # about 10 minutes

The FMU is target/fmu/BallIndentation.fmu with its own bed and defaults, except fidelity (full).
"""

import argparse
import json
import time

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--fmu", default="target/fmu/BallIndentation.fmu")
    p.add_argument("--age", type=float, required=True, help="bed time with the indenter held above the bed [s]")
    p.add_argument("--speed", type=float, required=True, help="indentation speed after the wait [m/s]")
    p.add_argument("--above", type=float, default=5e-4, help="height of the held indenter above the first touch [m]")
    p.add_argument("--fidelity", default="full")
    p.add_argument("--out", help="CSV of time_s, depth_m, force_N")
    a = p.parse_args()
    md = read_model_description(a.fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    start = {v.name: v.start for v in md.modelVariables}
    d, h_max = float(start["indenter_diameter"]), float(start["max_penetration"])
    s = FMU2Slave(guid=md.guid, unzipDirectory=extract(a.fmu), modelIdentifier="BallIndentation", instanceName="ageing")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.setString([vr["indenter_motion"], vr["fidelity"]], ["input", a.fidelity])
    s.setReal([vr["indenter_displacement"], vr["indenter_velocity"]], [-a.above, 0.0])
    s.enterInitializationMode()
    s.exitInitializationMode()
    t, started = 0.0, time.time()
    while t < a.age - 1e-12:
        s.doStep(t, 1e-3)
        t += 1e-3
    print(f"held {a.age} s of bed time in {time.time() - started:.0f} s; kinetic energy {s.getReal([vr['kinetic_energy']])[0]:.3e} J", flush=True)
    rows, t0, u, h = [], t, -a.above, 1e-4
    while u < h_max:
        s.setReal([vr["indenter_displacement"], vr["indenter_velocity"]], [u, a.speed])
        s.doStep(t, h)
        t += h
        u = -a.above + a.speed * (t - t0)
        rows.append((t, *s.getReal([vr["penetration_depth"], vr["indenter_force"]])))
    r = np.array(rows)
    area = np.pi * (d * r[:, 1] - r[:, 1] ** 2)
    window = (r[:, 1] / (0.5 * d) >= 0.1) & (r[:, 1] / (0.5 * d) <= 0.2)
    print(json.dumps({
        "age_s": a.age, "speed_m_per_s": a.speed,
        "plateau_hardness_Pa": s.getReal([vr["plateau_hardness"]])[0],
        "plateau_of_1e-4_s_samples_Pa": float(np.mean(r[window, 2] / area[window])),
        "wall_s": round(time.time() - started, 1),
    }))
    if a.out:
        np.savetxt(a.out, r, delimiter=",", header="time_s,depth_m,force_N", comments="")
    s.terminate()
    s.freeInstance()


if __name__ == "__main__":
    main()
