"""Worker of test_state.py, run in a process of its own: `save` initializes a unit, steps it, writes its
serialized FMU state and the outputs of further steps; `restore` instantiates the unit afresh (no
parameters set, not initialized), reads that state, sets it and steps the same way, writing its outputs.

    python state_worker.py save|restore UNZIPDIR WORKDIR
"""

import json
import sys
from pathlib import Path

from fmpy import read_model_description

from fmu_support import Unit, record_steps, triangle_wall

H = 2.0**-31  # ~0.47 ns, exact in binary
BEFORE, AFTER = 40, 160
START = {"initial_velocity": 3.0, "particle_radius": 1.72e-6, "surface_energy": 0.3}


def wall():
    # The wall moves too, so the inputs are part of the state.
    return triangle_wall(peak=2e-9, period=64 * H, low=-2e-9)


def main(mode: str, unzipdir: str, workdir: str):
    work = Path(workdir)
    md = read_model_description(unzipdir)
    unit = Unit(name=md.modelName, path=Path(unzipdir), unzipdir=unzipdir, md=md)
    fmu = unit.slave(f"worker-{mode}")
    if mode == "save":
        unit.initialize(fmu, START)
        record_steps(unit, fmu, 0.0, H, BEFORE, wall())
        state = fmu.getFMUstate()
        (work / "state.bin").write_bytes(fmu.serializeFMUstate(state))
        fmu.freeFMUstate(state)
        rows = record_steps(unit, fmu, BEFORE * H, H, AFTER, wall())
        (work / "expected.json").write_text(json.dumps(rows))
    elif mode == "restore":
        state = fmu.deSerializeFMUstate((work / "state.bin").read_bytes())
        fmu.setFMUstate(state)
        fmu.freeFMUstate(state)
        rows = record_steps(unit, fmu, BEFORE * H, H, AFTER, wall())
        (work / "got.json").write_text(json.dumps(rows))
        expected = json.loads((work / "expected.json").read_text())
        if rows != expected:
            print("restored run differs from the saving process", file=sys.stderr)
            sys.exit(2)
    else:
        raise SystemExit(f"unknown mode {mode}")
    fmu.terminate()
    fmu.freeInstance()


if __name__ == "__main__":
    main(*sys.argv[1:])
