"""Every law of the table in ParticleWallImpact Model Exchange under a strict CVode (fmpy's CVode with
`CVodeSetMinStep`, 1e-12 s by default: OMSimulator's minimum step) at 0.5, 2, 3 and 8 m/s and relative
tolerances 1e-6 and 1e-8: whether the run reaches its end, CVode's steps and located events per impact,
and the error against Co-Simulation (`exact` for the piecewise-linear laws, `adaptive` at 1e-12 for the
others) in units of rtol, as tests/python/test_strict_cvode.py measures it (`model_exchange_error`: the
rebound velocity relative to the impact speed and the largest overlap; the overlap alone where the sphere
sticks, marked "stuck").

    .venv/bin/python benches/me_all_laws.py [FMU_DIR] [--min-step S] [--laws a,b]   # default target/fmu

Pass the FMU folder of another build to compare; a failure is printed, not raised; the table is Markdown
(docs/benchmarks.md)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "python"))

from fmpy import extract, read_model_description  # noqa: E402

from fmu_support import StrictCVode, Unit  # noqa: E402
from test_strict_cvode import (  # noqa: E402
    ALL_LAWS, IMPACT_OUTPUTS, IMPACT_STOP, SPEEDS, co_simulation_reference, left_the_wall, model_exchange_error,
)


def load(folder: Path) -> Unit:
    path = folder / "ParticleWallImpact.fmu"
    return Unit("ParticleWallImpact", path, extract(str(path)), read_model_description(str(path)))


def me_run(unit: Unit, law: str, v: float, rtol: float, min_step: float):
    """(result or None, CVode steps, located events, failure text)."""
    with StrictCVode(min_step) as cvode:
        try:
            r = unit.simulate("ModelExchange", start_values={"initial_velocity": v, "contact_model": law}, stop_time=IMPACT_STOP,
                              output_interval=1e-9, relative_tolerance=rtol, output=IMPACT_OUTPUTS, timeout=120)
            return r, cvode.steps, cvode.root_returns, ""
        except Exception as e:  # noqa: BLE001 - a failure is a result here
            text = str(e).replace("\n", " ")
            at = text.find("At t")
            return None, (cvode.steps if cvode.solvers else 0), cvode.root_returns, (text[at:at + 60] if at >= 0 else text[-60:])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("fmu_dir", nargs="?", default=str(REPO / "target" / "fmu"))
    p.add_argument("--min-step", type=float, default=1e-12)
    p.add_argument("--laws", default=",".join(ALL_LAWS))
    a = p.parse_args()
    unit = load(Path(a.fmu_dir))
    print(f"min step {a.min_step:g} s; error in units of rtol (model_exchange_error)")
    print("| law | v [m/s] | rtol 1e-6: steps / events / error | rtol 1e-8: steps / events / error |")
    print("|---|---|---|---|")
    worst = 0.0
    for law in a.laws.split(","):
        for v in SPEEDS:
            cs = co_simulation_reference(unit, law, v)
            cells = []
            for rtol in (1e-6, 1e-8):
                me, steps, events, failure = me_run(unit, law, v, rtol, a.min_step)
                if me is None:
                    cells.append(f"failed after {steps} steps, {events} events: {failure}")
                    worst = float("inf")
                else:
                    err = model_exchange_error(me, cs, v) / rtol
                    worst = max(worst, err)
                    cells.append(f"{steps} / {events} / {err:.2g}")
            print(f"| {law} | {v}{'' if left_the_wall(cs) else ' (stuck)'} | {cells[0]} | {cells[1]} |", flush=True)
    print(f"\nworst error: {worst:.3g} x rtol")


if __name__ == "__main__":
    main()
