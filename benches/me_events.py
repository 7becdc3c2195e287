"""CVode's work on ParticleWallImpact in Model Exchange: steps and located events per impact for every
piecewise-linear law at three speeds, and the three hard cases of tests/python/test_strict_cvode.py,
under fmpy's CVode as it is and with OMSimulator's minimum step (CVodeSetMinStep 1e-12 s). The error is
ME's restitution against `exact` Co-Simulation.

    .venv/bin/python benches/me_events.py [FMU_DIR]        # default target/fmu

Pass the FMU folder of another build to compare (a failure is printed, not raised)."""

from __future__ import annotations

import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "python"))

from fmpy import extract, read_model_description  # noqa: E402

from fmu_support import StrictCVode, Unit  # noqa: E402
from test_strict_cvode import PIECEWISE_LINEAR, sampled_sine  # noqa: E402

RTOL = 1e-6


def load(folder: Path) -> Unit:
    path = folder / "ParticleWallImpact.fmu"
    return Unit("ParticleWallImpact", path, extract(str(path)), read_model_description(str(path)))


def me_run(unit: Unit, min_step: float, **kwargs):
    """(result or None, CVode steps, events, failure text); a run stops after 20 000 output points."""
    calls = [0]

    def budget(time, recorder):
        calls[0] += 1
        return calls[0] < 20_000

    with StrictCVode(min_step) as cvode:
        try:
            r = unit.simulate("ModelExchange", step_finished=budget, timeout=120, **kwargs)
            return r, cvode.steps, cvode.root_returns, ""
        except Exception as e:  # noqa: BLE001 - a failure is a result here
            text = str(e).split(": ")[-1][:70]
            return None, (cvode.steps if cvode.solvers else 0), cvode.root_returns, text


def main():
    unit = load(Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "target" / "fmu")
    print(f"| law | v [m/s] | min step [s] | CVode steps | events | ME vs exact CS |")
    print("|---|---|---|---|---|---|")
    for law in PIECEWISE_LINEAR:
        for v in (2.0, 3.0, 8.0):
            start = {"initial_velocity": v, "contact_model": law}
            out = ["sphere_velocity"]
            cs = unit.simulate("CoSimulation", start_values={**start, "solver": "exact"}, stop_time=3e-7, output_interval=1e-9, output=out)
            for min_step in (0.0, 1e-12):
                r, steps, events, failure = me_run(unit, min_step, start_values=start, stop_time=3e-7, output_interval=1e-9, relative_tolerance=RTOL, output=out)
                err = f"{abs(r['sphere_velocity'][-1] / cs['sphere_velocity'][-1] - 1):.1e}" if r is not None else f"failed: {failure}"
                print(f"| {law} | {v} | {min_step:g} | {steps} | {events} | {err} |")
    cases = {
        "damped sphere, 20 kHz / 20 nm wall, 0.2 ms": dict(
            start_values={"initial_velocity": 0.0, "gravity": 9.81, "initial_gap": 0.0, "restitution_coefficient": 0.5},
            input=sampled_sine(2e-8, 2e4, 2e-4, 4001), stop_time=2e-4, output_interval=5e-8),
        "sampled 5 MHz / 20 nm wall, 2 us": dict(
            start_values={"gravity": 9.81, "initial_velocity": 0.5, "initial_gap": 4e-8},
            input=sampled_sine(2e-8, 5e6, 2e-6, 2001), stop_time=2e-6, output_interval=4e-9),
    }
    print()
    print("| case | min step [s] | CVode steps | events | reached |")
    print("|---|---|---|---|---|")
    for name, kwargs in cases.items():
        for min_step in (0.0, 1e-12):
            r, steps, events, failure = me_run(unit, min_step, **kwargs)
            reached = f"{r['time'][-1]:.3g} s" if r is not None else f"failed: {failure}"
            print(f"| {name} | {min_step:g} | {steps} | {events} | {reached} |", flush=True)


if __name__ == "__main__":
    main()
