"""One particle of the sieve in Model Exchange: ParticleWallImpact's ME interface integrated by fmpy's
CVode (the solver fmpy's simulate_fmu uses), the plate's motion prescribed (its particle-free orbit,
one-way: right when the powder is light against the plate) and set as inputs at every evaluation, the
way a Modelica tool feeds a connected input. Events (branch switches, pull-off, detachment) are handled
in fmi2NewDiscreteStates. For comparing Co-Simulation with Model Exchange on the same cases."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from fmpy.fmi2 import FMU2Model
from fmpy.sundials import CVodeSolver

from . import sieve
from .instance import Messages, description, extracted, set_values
from .fmus import fmu_path


@dataclass
class MeResult:
    detach_time: float  # s after the drive started, at the communication point CS would see it; nan: stayed
    detach_event_time: float  # s after the drive started, the event at which the contact ended
    pull_off_force: float  # N, after settling
    mass: float  # kg
    radius: float  # m
    steps: int  # CVode steps
    events: int
    wall_time: float  # s


class _NoInput:
    """fmpy's CVodeSolver calls input.apply(t) in the root function; the inputs are set in set_time."""

    def apply(self, *_args, **_kwargs):
        pass


def run_particle(spec: Mapping[str, Any], relative_tolerance: float = 1e-8, fmu: Path | None = None) -> MeResult:
    """The first particle of `spec` (radius: the sample's first, i.e. `particle_radius` with
    radius_spread 1) on the prescribed plate, in Model Exchange."""
    fmu = Path(fmu or fmu_path("ParticleWallImpact"))
    system, powder = sieve.resolve({**spec, "particles": 1}, fmu)
    radius = float(sieve.radii(system)[0])
    md = description(fmu)
    v = {x.name: x for x in md.modelVariables}
    vr_x, vr_v = v["wall_displacement"].valueReference, v["wall_velocity"].valueReference
    started = time.perf_counter()
    log = Messages()
    p = FMU2Model(guid=md.guid, unzipDirectory=extracted(fmu), modelIdentifier=md.modelExchange.modelIdentifier, instanceName="me")
    p.instantiate(callbacks=log.callbacks)
    try:
        p.setupExperiment(startTime=0.0)
        set_values(p, v, {**powder, "particle_radius": radius, "initial_gap": 0.0, "initial_velocity": 0.0, "gravity": system["gravity"]})
        p.enterInitializationMode()
        p.exitInitializationMode()
        _event_iteration(p)
        p.enterContinuousTimeMode()

        settle = system["settle_time"]
        period = 1.0 / system["frequency"]
        plate = sieve.Plate(1.0, system["plate_natural_frequency"], system["plate_damping_ratio"], system["frequency"], system["amplitude"], system["ramp_periods"] * period)
        x_start = plate.orbit(0.0)[0]

        def wall(t: float) -> tuple[float, float]:
            if t <= settle:
                return 0.0, 0.0
            x, vel = plate.orbit(t - settle)
            return x - x_start, vel

        def set_time(t):
            p.setTime(t)
            p.setReal([vr_x, vr_v], list(wall(t)))

        solver = CVodeSolver(
            nx=md.numberOfContinuousStates,
            nz=md.numberOfEventIndicators,
            get_x=p.getContinuousStates,
            set_x=p.setContinuousStates,
            get_dx=p.getDerivatives,
            get_z=p.getEventIndicators,
            get_nominals=p.getNominalsOfContinuousStates,
            set_time=set_time,
            input=_NoInput(),
            startTime=0.0,
            maxStep=min(settle, period) / 20 if settle > 0 else period / 20,
            relativeTolerance=relative_tolerance,
            maxNumSteps=1_000_000,
        )
        t, stop = 0.0, settle + system["periods"] * period
        pull_off, detach, detach_event, steps, events = math.nan, math.nan, math.nan, 0, 0
        vr_state, vr_pull = v["contact_state"].valueReference, v["pull_off_force"].valueReference
        # Output points: the end of settling, then the CS communication points (detachment is read there
        # too, so both interfaces report it on the same grid).
        h = period / system["steps_per_period"]
        grid = [settle] + [settle + (n + 1) * h for n in range(round(system["periods"] * system["steps_per_period"]))]
        for t_next in grid:
            while t < t_next and not math.isclose(t, t_next, rel_tol=0, abs_tol=1e-15 * t_next):
                state_event, _roots, t = solver.step(t, t_next)
                steps += 1
                set_time(t)
                if state_event:
                    events += 1
                    p.enterEventMode()
                    _event_iteration(p)
                    p.enterContinuousTimeMode()
                    solver.reset(t)
                    if t > settle and math.isnan(detach_event) and p.getInteger([vr_state])[0] == 0:
                        detach_event = t - settle
            if t_next == settle:
                pull_off = p.getReal([vr_pull])[0]
            elif p.getInteger([vr_state])[0] == 0:
                detach = t - settle
                break
        p.terminate()
    except Exception as e:  # noqa: BLE001 - re-raised with the unit's message
        raise RuntimeError(f"Model Exchange run failed: {log.errors() or e}") from None
    finally:
        p.freeInstance()
    density = float(powder.get("particle_density", sieve.POWDER_DEFAULTS["particle_density"]))
    return MeResult(detach, detach_event, pull_off, 4.0 / 3.0 * math.pi * radius**3 * density, radius, steps, events, time.perf_counter() - started)


def _event_iteration(p: FMU2Model) -> None:
    while True:
        needed, terminate, *_ = p.newDiscreteStates()
        if terminate:
            raise RuntimeError("the unit asked to terminate")
        if not needed:
            return


def detachment_threshold(spec: Mapping[str, Any], rel_tol: float = 1e-3, relative_tolerance: float = 1e-8) -> float:
    """As sieve.detachment_threshold, in Model Exchange."""
    spec = {k: v for k, v in spec.items() if k != "amplitude"}
    r = sieve.run({**spec, "particles": 1, "acceleration": 1.0, "periods": 0.01, "ramp_periods": 0})
    quasi_static = float(r.quasi_static_threshold[0])

    def detaches(a: float) -> bool:
        return not math.isnan(run_particle({**spec, "acceleration": a}, relative_tolerance).detach_time)

    lo, hi = quasi_static / 4, quasi_static
    while not detaches(hi):
        lo, hi = hi, 2 * hi
        if hi > 1e3 * quasi_static:
            raise RuntimeError(f"no detachment up to {hi:.3e} m/s2")
    while hi / lo - 1 > rel_tol:
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if detaches(mid) else (mid, hi)
    return math.sqrt(lo * hi)
