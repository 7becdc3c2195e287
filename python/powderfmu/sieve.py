"""An ultrasonic sieve keeping its mesh free of a cohesive powder: a system model built from
ParticleWallImpact units.

A plate (the mesh: mass M, spring K, damper C) is driven by a harmonic force at frequency f. N particles of
a log-normal size distribution adhere to it, one ParticleWallImpact instance (Co-Simulation) each, set
down on the plate at rest and settled before the drive starts. The master couples them at a
communication step h that resolves the plate (`steps_per_period` steps per drive period):

- the plate is advanced over the step first, exactly (the linear oscillator's closed form under the
  drive and a constant force), with the particles' contact force of the previous step (Jacobi: each side
  uses the other's values from the step before);
- the particles get the plate's velocity at the step's start and its mean acceleration over the step as
  an input derivative (`fmi2SetRealInputDerivatives`), so the wall they see has a continuous velocity:
  a piecewise-linear wall would kick their stiff contacts at every step (docs/units/ParticleWallImpact.md);
- the force that goes back onto the plate is the impulse each particle received over the step,
  m dv + m g h, divided by h, so the plate gets exactly what the particles got, one step late: the total
  momentum is conserved up to that one step's impulse.

The drive force is the one that keeps the particle-free plate on x(t) = -A s(t) cos(2 pi f t), with s
rising smoothly from 0 to 1 over `ramp_periods`: the plate follows the drive with no transient of its
own, and the particles' load starts without a step (a step would ring the contacts and yield them).
Each compressive half-cycle presses the particles into the plate: a contact that yields there (the
default powder does) gains pull-off force before the tensile half-cycle pulls. A particle is detached at the first step end where it is out of
contact; it is then free and no longer simulated (it flies off under gravity and its momentum is
counted). Quasi-statically a particle detaches when m (A (2 pi f)^2 - g) exceeds its pull-off force.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np
from fmpy import read_model_description
from fmpy.fmi2 import FMU2Slave

from . import scene as scene_mod
from .instance import RefusedStart, cosimulation, description
from .fmus import fmu_path

# The system's own keys, their defaults and allowed ranges (units in the comments and `KEYS_HELP`).
SYSTEM_DEFAULTS: dict[str, Any] = {
    "frequency": 35e3,  # Hz, drive frequency f
    "acceleration": 1e6,  # m/s2, peak acceleration A (2 pi f)^2 of the plate's steady motion (or give amplitude)
    "amplitude": None,  # m, A (instead of acceleration)
    "plate_mass": 1e-8,  # kg, the patch of mesh that carries the simulated particles
    "plate_natural_frequency": 35e3,  # Hz, sqrt(K/M) / 2 pi
    "plate_damping_ratio": 0.05,  # C / (2 sqrt(K M)), in [0, 1)
    "particles": 40,  # N
    "particle_radius": 10e-6,  # m, median radius of the log-normal distribution
    "radius_spread": 1.6,  # geometric standard deviation of the radius (1: one size)
    "particle_weight": 1.0,  # particles on the mesh each simulated one stands for (their force on the plate)
    "seed": 1,  # of the radius sample
    "gravity": 9.81,  # m/s2, toward the plate
    "periods": 10,  # drive periods simulated after settling
    "ramp_periods": 2,  # periods over which the drive's amplitude rises smoothly from 0
    "steps_per_period": 100,  # communication steps per drive period
    "settle_time": 5e-5,  # s, the particles settle on the plate at rest before the drive
}

KEYS_HELP = {
    "frequency": "Hz, > 0",
    "acceleration": "m/s2, > 0 (peak plate acceleration; or give amplitude)",
    "amplitude": "m, > 0 (plate displacement amplitude; or give acceleration)",
    "plate_mass": "kg, > 0",
    "plate_natural_frequency": "Hz, > 0",
    "plate_damping_ratio": "[0, 1)",
    "particles": "integer >= 1",
    "particle_radius": "m, > 0",
    "radius_spread": ">= 1",
    "particle_weight": "> 0",
    "seed": "integer",
    "gravity": "m/s2",
    "periods": "> 0",
    "ramp_periods": ">= 0, at most periods",
    "steps_per_period": "integer >= 8",
    "settle_time": "s, >= 0",
}

# The default powder: the default scene (000 Table 5, ammonium fluorescein on silicon) with damping, so
# that a particle set down on the plate settles: restitution 0.5, and beta = 1 after yield (Nan's 0.1
# would take 20 times longer; the contact yields at first touch, adhesion-induced plasticity).
POWDER_DEFAULTS: dict[str, Any] = {
    "contact_model": "nan",
    "particle_density": 1350.0,
    "particle_youngs_modulus": 1.2e9,
    "particle_poisson_ratio": 0.33,
    "particle_yield_pressure": 30e6,
    "wall_youngs_modulus": 166e9,
    "wall_poisson_ratio": 0.28,
    "wall_yield_pressure": 120e6,
    "surface_energy": 0.24,
    "restitution_coefficient": 0.5,
    "damping_factor_plastic": 1.0,
}

# The master's explicit (Jacobi) coupling hands the plate the particles' force of the step before: with
# the particles riding rigidly on their stiff contacts that is an added mass one step late, stable only
# while the powder is light against the plate. At 0.08 the momentum defect halves with the step; at 0.8
# the detached fraction went from 0.1 to 0.5 as the step halved (docs/system.md).
MAX_MASS_RATIO = 0.25

# Parameters of the unit the system sets itself.
_OWNED = {"particle_radius", "initial_gap", "initial_velocity", "gravity"}


class SpecError(ValueError):
    """A system spec that cannot run; the message names the key and its allowed range."""


def _unit_parameters(fmu: Path) -> dict[str, Any]:
    return {v.name: v for v in read_model_description(str(fmu)).modelVariables if v.causality == "parameter"}


def resolve(spec: Mapping[str, Any], fmu: Path | None = None, check_unit: bool = False) -> tuple[dict[str, Any], dict[str, Any]]:
    """Splits a spec into the system's keys (defaults filled in, checked) and the powder's scene keys
    (checked against the unit's parameters). Raises SpecError naming the key. `check_unit` also asks the
    unit to initialize with them (a sweep checks every task before any runs; `run` meets the unit's
    refusal when it creates the instances)."""
    fmu = fmu or fmu_path("ParticleWallImpact")
    unit = _unit_parameters(fmu)
    system = dict(SYSTEM_DEFAULTS)
    powder = dict(POWDER_DEFAULTS)
    if "amplitude" in spec and spec["amplitude"] is not None:
        if "acceleration" in spec and spec["acceleration"] is not None:
            raise SpecError("give either `acceleration` or `amplitude`, not both")
        system["acceleration"] = None
    for key, value in spec.items():
        if key.startswith("comment"):
            continue
        if key in SYSTEM_DEFAULTS:
            system[key] = value
        elif key in unit and key not in _OWNED:
            powder[key] = value
        else:
            raise SpecError(
                f"unknown key {key!r}: not a system key ({', '.join(SYSTEM_DEFAULTS)}) nor a ParticleWallImpact parameter"
                + (" (the system sets it itself)" if key in _OWNED else "")
            )

    def number(key, low=None, high=None, low_open=True, integer=False):
        v = system[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise SpecError(f"`{key}` = {v!r} must be a finite number ({KEYS_HELP[key]})")
        if integer and v != int(v):
            raise SpecError(f"`{key}` = {v!r} must be an integer ({KEYS_HELP[key]})")
        if low is not None and (v <= low if low_open else v < low):
            raise SpecError(f"`{key}` = {v!r} is out of range ({KEYS_HELP[key]})")
        if high is not None and v >= high:
            raise SpecError(f"`{key}` = {v!r} is out of range ({KEYS_HELP[key]})")
        system[key] = int(v) if integer else float(v)

    number("frequency", 0.0)
    if system["acceleration"] is not None:
        number("acceleration", 0.0)
        system["amplitude"] = system["acceleration"] / (2 * math.pi * system["frequency"]) ** 2
    else:
        number("amplitude", 0.0)
        system["acceleration"] = system["amplitude"] * (2 * math.pi * system["frequency"]) ** 2
    number("plate_mass", 0.0)
    number("plate_natural_frequency", 0.0)
    number("plate_damping_ratio", 0.0, 1.0, low_open=False)
    number("particles", 1, low_open=False, integer=True)
    number("particle_radius", 0.0)
    number("radius_spread", 1.0, low_open=False)
    number("particle_weight", 0.0)
    number("seed", integer=True)
    number("gravity")
    number("periods", 0.0)
    if "ramp_periods" not in spec:
        system["ramp_periods"] = min(SYSTEM_DEFAULTS["ramp_periods"], system["periods"])
    number("ramp_periods", 0.0, low_open=False)
    if system["ramp_periods"] > system["periods"]:
        raise SpecError(f"`ramp_periods` = {system['ramp_periods']} is out of range ({KEYS_HELP['ramp_periods']} = {system['periods']})")
    number("steps_per_period", 8, low_open=False, integer=True)
    number("settle_time", 0.0, low_open=False)
    try:
        powder = scene_mod.start_values(fmu, powder)
    except ValueError as e:
        raise SpecError(str(e)) from None
    r = radii(system)
    density = float(powder.get("particle_density", unit["particle_density"].start))
    ratio = system["particle_weight"] * float((4.0 / 3.0 * math.pi * r**3 * density).sum()) / system["plate_mass"]
    if ratio > MAX_MASS_RATIO:
        raise SpecError(
            f"`plate_mass` = {system['plate_mass']:g} kg carries {ratio:.3g} times its mass of powder (particles x particle_weight); "
            f"the master's explicit coupling needs at most {MAX_MASS_RATIO} (added-mass instability): raise plate_mass or lower particles or particle_weight"
        )
    # The unit checks its own parameters (ranges, combinations) at initialization: for the smallest and
    # the largest particle.
    for radius in {float(r[0]), float(r[-1])} if check_unit else ():
        try:
            p, _ = cosimulation(fmu, "check", {**powder, "particle_radius": radius, "initial_gap": 0.0, "initial_velocity": 0.0, "gravity": system["gravity"]})
        except RefusedStart as e:
            raise SpecError(str(e)) from None
        p.terminate()
        p.freeInstance()
    return system, powder


def radii(system: Mapping[str, Any]) -> np.ndarray:
    """The particles' radii: a log-normal sample (median `particle_radius`, geometric standard deviation
    `radius_spread`) from `seed`, sorted."""
    rng = np.random.default_rng(system["seed"])
    r = system["particle_radius"] * np.exp(math.log(system["radius_spread"]) * rng.standard_normal(system["particles"]))
    return np.sort(r)


class Plate:
    """M x'' + C x' + K x = F(t) + F_c, with F(t) the drive that keeps the particle-free plate on its orbit
    x(t) = -A s(t) cos(w t) (s rises smoothly from 0 to 1 over the ramp, 10 tau^3 - 15 tau^4 + 6 tau^5,
    so that position, velocity and acceleration start at 0: no step in the load that would ring the
    contacts) and F_c the particles' force, constant over a step. Advanced exactly: x is the orbit plus
    F_c / K plus a free damped oscillation."""

    def __init__(self, mass: float, natural_frequency: float, damping_ratio: float, frequency: float, amplitude: float, ramp: float):
        self.m = mass
        self.wp = 2 * math.pi * natural_frequency
        self.zeta = damping_ratio
        self.k = mass * self.wp**2
        self.c = 2 * damping_ratio * mass * self.wp
        self.w = 2 * math.pi * frequency
        self.a = amplitude
        self.ramp = ramp
        self.wd = self.wp * math.sqrt(1 - damping_ratio**2)

    def envelope(self, t: float) -> tuple[float, float, float]:
        """s, s', s'' of the ramp."""
        if self.ramp <= 0 or t >= self.ramp:
            return 1.0, 0.0, 0.0
        u = max(t, 0.0) / self.ramp
        s = u**3 * (10 - 15 * u + 6 * u**2)
        ds = 30 * u**2 * (1 - u) ** 2 / self.ramp
        dds = 60 * u * (1 - u) * (1 - 2 * u) / self.ramp**2
        return s, ds, dds

    def orbit(self, t: float) -> tuple[float, float]:
        """Position and velocity of the particle-free plate."""
        s, ds, _ = self.envelope(t)
        c, sn = math.cos(self.w * t), math.sin(self.w * t)
        return -self.a * s * c, self.a * (s * self.w * sn - ds * c)

    def acceleration(self, t: float) -> float:
        s, ds, dds = self.envelope(t)
        c, sn = math.cos(self.w * t), math.sin(self.w * t)
        return self.a * (s * self.w**2 * c + 2 * ds * self.w * sn - dds * c)

    def drive(self, t: float) -> float:
        """The drive force [N]."""
        x, v = self.orbit(t)
        return self.m * self.acceleration(t) + self.c * v + self.k * x

    def step(self, t: float, x: float, v: float, h: float, force: float) -> tuple[float, float]:
        """The plate's position and velocity at t + h from (x, v) at t under a constant extra force."""
        x0, v0 = self.orbit(t)
        y, yd = x - x0 - force / self.k, v - v0
        zw = self.zeta * self.wp
        e, c, s = math.exp(-zw * h), math.cos(self.wd * h), math.sin(self.wd * h)
        y1 = e * (y * c + (yd + zw * y) / self.wd * s)
        yd1 = e * (yd * c - (self.wp**2 * y + zw * yd) / self.wd * s)
        x1, v1 = self.orbit(t + h)
        return x1 + force / self.k + y1, v1 + yd1


@dataclass
class Result:
    """One run of the system. Times in s from the start of the drive; forces in N; masses in kg."""

    system: dict[str, Any]
    powder: dict[str, Any]
    radius: np.ndarray  # m
    mass: np.ndarray  # kg
    pull_off_force: np.ndarray  # N, of each contact after settling (the unit's pull_off_force)
    detach_time: np.ndarray  # s after the drive started; nan: stayed
    time: np.ndarray  # s, the communication points of the drive
    plate_position: np.ndarray  # m
    plate_velocity: np.ndarray  # m/s
    plate_force: np.ndarray  # N, the particles' force on the plate over each step (the step that ends at time[i])
    momentum_defect: float  # kg m/s, plate's received impulse + particles' contact impulse (0 up to one step's)
    wall_time: float  # s
    particle_steps: int  # fmi2DoStep calls
    events: list[str] = field(default_factory=list)

    @property
    def detached(self) -> np.ndarray:
        return ~np.isnan(self.detach_time)

    @property
    def detached_mass_fraction(self) -> float:
        return float(self.mass[self.detached].sum() / self.mass.sum())

    @property
    def detached_fraction(self) -> float:
        return float(self.detached.mean())

    @property
    def quasi_static_threshold(self) -> np.ndarray:
        """Per particle, the plate acceleration [m/s2] at which it detaches quasi-statically:
        pull-off force / m + g."""
        return self.pull_off_force / self.mass + self.system["gravity"]

    def summary(self) -> dict[str, Any]:
        """One row of numbers (a sweep's output)."""
        s = self.system
        d = self.detach_time[self.detached]
        return {
            "frequency": s["frequency"],
            "acceleration": s["acceleration"],
            "amplitude": s["amplitude"],
            "particles": s["particles"],
            "particle_radius": s["particle_radius"],
            "detached_fraction": self.detached_fraction,
            "detached_mass_fraction": self.detached_mass_fraction,
            "first_detachment": float(d.min()) if d.size else math.nan,
            "smallest_detached_radius": float(self.radius[self.detached].min()) if d.size else math.nan,
            "largest_attached_radius": float(self.radius[~self.detached].max()) if (~self.detached).any() else math.nan,
            "quasi_static_detached_fraction": float((self.quasi_static_threshold < s["acceleration"]).mean()),
            "plate_amplitude": float(np.abs(self.plate_position).max()),
            "momentum_defect": float(self.momentum_defect),
            "wall_time": self.wall_time,
        }


SUMMARY_KEYS = (
    "frequency",
    "acceleration",
    "amplitude",
    "particles",
    "particle_radius",
    "detached_fraction",
    "detached_mass_fraction",
    "first_detachment",
    "smallest_detached_radius",
    "largest_attached_radius",
    "quasi_static_detached_fraction",
    "plate_amplitude",
    "momentum_defect",
    "wall_time",
)


def _step(p: FMU2Slave, t: float, h: float) -> None:
    try:
        p.doStep(currentCommunicationPoint=t, communicationStepSize=h)
    except Exception as e:  # noqa: BLE001 - re-raised with the unit's message
        raise RuntimeError(f"{p.instanceName}: fmi2DoStep at t = {t:.6e} s failed: {p._powderfmu_log.errors() or e}") from None


def run(spec: Mapping[str, Any] | None = None, fmu: Path | None = None, progress: bool = False) -> Result:
    """Runs the system of `spec` (system keys and ParticleWallImpact parameters; missing keys take their
    defaults) and returns its Result; `progress` prints a line every 5 % of the steps."""
    fmu = Path(fmu or fmu_path("ParticleWallImpact"))
    system, powder = resolve(spec or {}, fmu)
    started = time.perf_counter()
    variables = {v.name: v for v in description(fmu).modelVariables}
    vr = {n: variables[n].valueReference for n in ("wall_displacement", "wall_velocity", "sphere_velocity", "contact_state", "pull_off_force", "particle_density")}

    r = radii(system)
    g = system["gravity"]
    instances: list[FMU2Slave] = []
    try:
        for i, radius in enumerate(r):
            p, _ = cosimulation(fmu, f"particle{i}", {**powder, "particle_radius": float(radius), "initial_gap": 0.0, "initial_velocity": 0.0, "gravity": g})
            instances.append(p)
        density = instances[0].getReal([vr["particle_density"]])[0]
        mass = 4.0 / 3.0 * math.pi * r**3 * density
        # Settling on the plate at rest; one step of the exact integrator.
        settle = system["settle_time"]
        if settle > 0:
            for p in instances:
                _step(p, 0.0, settle)
        pull_off = np.array([p.getReal([vr["pull_off_force"]])[0] for p in instances])
        velocity = np.array([p.getReal([vr["sphere_velocity"]])[0] for p in instances])
        attached = np.array([p.getInteger([vr["contact_state"]])[0] != 0 for p in instances])
        if not attached.all():
            raise RuntimeError(f"{int((~attached).sum())} particle(s) did not stay on the plate while settling (settle_time {settle} s)")

        period = 1.0 / system["frequency"]
        plate = Plate(
            system["plate_mass"], system["plate_natural_frequency"], system["plate_damping_ratio"], system["frequency"], system["amplitude"], system["ramp_periods"] * period
        )
        h = period / system["steps_per_period"]
        n_steps = max(1, round(system["periods"] * system["steps_per_period"]))
        weight = system["particle_weight"]
        x, v = plate.orbit(0.0)
        times = np.arange(n_steps + 1) * h
        xs, vs, fs = np.empty(n_steps + 1), np.empty(n_steps + 1), np.zeros(n_steps + 1)
        xs[0], vs[0] = x, v
        detach = np.full(len(r), np.nan)
        # The particles' force of the previous step [N]. Their settled weight (1e-5 of the drive's load at
        # 1e6 m/s2) is in the plate's static equilibrium and left out of the first step.
        force_on_plate = 0.0
        plate_impulse = 0.0  # what the plate received from the particles [N s]
        particle_impulse = 0.0  # what the particles received from their contacts [N s]
        steps = 0
        live = list(range(len(r)))
        for n in range(n_steps):
            t = n * h
            x1, v1 = plate.step(t, x, v, h, force_on_plate)
            plate_impulse += force_on_plate * h
            a_mean = (v1 - v) / h
            impulse = 0.0
            still = []
            for i in live:
                p = instances[i]
                p.setReal([vr["wall_velocity"]], [v])
                p.setRealInputDerivatives([vr["wall_velocity"]], [1], [a_mean])
                _step(p, settle + t, h)
                steps += 1
                v_new = p.getReal([vr["sphere_velocity"]])[0]
                j = mass[i] * (v_new - velocity[i]) + mass[i] * g * h
                velocity[i] = v_new
                impulse += j
                if p.getInteger([vr["contact_state"]])[0] == 0:
                    detach[i] = t + h
                else:
                    still.append(i)
            live = still
            particle_impulse += weight * impulse
            force_on_plate = -weight * impulse / h
            x, v = x1, v1
            xs[n + 1], vs[n + 1], fs[n + 1] = x, v, force_on_plate
            if progress and (n + 1) % max(1, n_steps // 20) == 0:
                print(f"  t = {t + h:.4e} s  {len(r) - len(live)}/{len(r)} detached", flush=True)
            if not live:
                # Every particle has left: the plate goes on alone, on its orbit plus what is left of the
                # particles' last push.
                for m in range(n + 1, n_steps):
                    x, v = plate.step(m * h, x, v, h, force_on_plate if m == n + 1 else 0.0)
                    if m == n + 1:
                        plate_impulse += force_on_plate * h
                    xs[m + 1], vs[m + 1] = x, v
                force_on_plate = 0.0
                break
        for p in instances:
            p.terminate()
    finally:
        for p in instances:
            try:
                p.freeInstance()
            except Exception:  # noqa: BLE001 - freeing what could be freed; the first error is the one raised
                pass
    return Result(
        system=system,
        powder=powder,
        radius=r,
        mass=mass,
        pull_off_force=pull_off,
        detach_time=detach,
        time=times,
        plate_position=xs,
        plate_velocity=vs,
        plate_force=fs,
        momentum_defect=plate_impulse + particle_impulse,
        wall_time=time.perf_counter() - started,
        particle_steps=steps,
    )


def detachment_threshold(spec: Mapping[str, Any], rel_tol: float = 1e-3, fmu: Path | None = None) -> float:
    """The smallest peak plate acceleration [m/s2] that detaches the (first) particle of a one-particle
    spec, by bisection on `acceleration` between a quarter and four times the quasi-static threshold."""
    spec = {**spec, "particles": 1}
    spec.pop("amplitude", None)

    def detaches(a: float) -> bool:
        return bool(run({**spec, "acceleration": a}, fmu).detached[0])

    quasi_static = float(run({**spec, "acceleration": 1.0}, fmu).quasi_static_threshold[0])
    lo, hi = quasi_static / 4, quasi_static
    while not detaches(hi):
        lo, hi = hi, 2 * hi
        if hi > 1e3 * quasi_static:
            raise RuntimeError(f"no detachment up to {hi:.3e} m/s2 (quasi-static threshold {quasi_static:.3e})")
    if detaches(lo):
        raise RuntimeError(f"detached at {lo:.3e} m/s2, a quarter of the quasi-static threshold {quasi_static:.3e}")
    while hi / lo - 1 > rel_tol:
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if detaches(mid) else (mid, hi)
    return math.sqrt(lo * hi)


def main(argv=None) -> int:
    """python -m powderfmu.sieve [SPEC.json] [--set KEY=VALUE ...] [--check-step] [--plot FILE]"""
    import argparse
    import json
    import sys

    ap = argparse.ArgumentParser(prog="python -m powderfmu.sieve", description="Runs the ultrasonic sieve system once and prints which particles detach, when, and the plate's motion.")
    ap.add_argument("spec", nargs="?", help="JSON object of system keys and ParticleWallImpact parameters (default: the defaults)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="one key (a number or a string), after the spec's")
    ap.add_argument("--check-step", action="store_true", help="run again at half the communication step and report the differences")
    ap.add_argument("--plot", help="write the plate's motion and the detachments to this image")
    args = ap.parse_args(argv)
    spec: dict[str, Any] = {}
    try:
        if args.spec:
            spec = scene_mod.load(args.spec)
        for item in args.set:
            key, sep, value = item.partition("=")
            if not sep:
                raise SpecError(f"--set {item!r}: give KEY=VALUE")
            try:
                spec[key] = json.loads(value)
            except json.JSONDecodeError:
                spec[key] = value
        r = run(spec)
    except (SpecError, ValueError) as e:
        print(f"powderfmu.sieve: {e}", file=sys.stderr)
        return 2
    s = r.system
    print(
        f"plate: {s['plate_mass']:g} kg, natural frequency {s['plate_natural_frequency']:g} Hz, damping ratio {s['plate_damping_ratio']:g}; "
        f"drive {s['frequency']:g} Hz, amplitude {s['amplitude']:.4e} m, peak acceleration {s['acceleration']:.4e} m/s2"
    )
    print(f"{s['particles']} particles (median radius {s['particle_radius']:g} m, spread {s['radius_spread']:g}); {s['periods']:g} periods of {s['steps_per_period']} steps; {r.wall_time:.2f} s")
    print(f"{'radius [m]':>12} {'mass [kg]':>11} {'pull-off [N]':>12} {'q-s threshold [m/s2]':>21} {'detached at [s]':>16}")
    for i in range(len(r.radius)):
        t = "stayed" if math.isnan(r.detach_time[i]) else f"{r.detach_time[i]:.6e}"
        print(f"{r.radius[i]:12.4e} {r.mass[i]:11.4e} {r.pull_off_force[i]:12.4e} {r.quasi_static_threshold[i]:21.4e} {t:>16}")
    print(
        f"detached: {r.detached.sum()} of {len(r.radius)} particles, mass fraction {r.detached_mass_fraction:.4f} "
        f"(quasi-statically expected: {(r.quasi_static_threshold < s['acceleration']).sum()}); plate amplitude {np.abs(r.plate_position).max():.4e} m; "
        f"momentum defect {r.momentum_defect:.3e} N s"
    )
    if args.check_step:
        fine = run({**spec, "steps_per_period": 2 * s["steps_per_period"]})
        both = ~np.isnan(r.detach_time) & ~np.isnan(fine.detach_time)
        dt = float(np.abs(r.detach_time[both] - fine.detach_time[both]).max()) if both.any() else 0.0
        print(
            f"half the step ({2 * s['steps_per_period']} per period): {int((r.detached != fine.detached).sum())} particle(s) change side, "
            f"detachment times move by at most {dt:.3e} s (one step: {1 / s['frequency'] / s['steps_per_period']:.3e} s), "
            f"plate amplitude by {abs(np.abs(fine.plate_position).max() / np.abs(r.plate_position).max() - 1):.2e} relative"
        )
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
        a1.plot(r.time * 1e3, r.plate_position * 1e6)
        a1.set_ylabel("plate position [um]")
        a1.set_title(f"sieve at {s['frequency']:g} Hz, {s['acceleration']:.3g} m/s2: detached mass fraction {r.detached_mass_fraction:.2f}")
        d = r.detached
        a2.semilogy(r.detach_time[d] * 1e3, r.radius[d] * 1e6, "v", color="C3", label="detached (time, radius)")
        a2.semilogy(np.full((~d).sum(), r.time[-1] * 1e3), r.radius[~d] * 1e6, "o", color="C2", mfc="none", label="stayed")
        a2.set_xlabel("time after the drive started [ms]")
        a2.set_ylabel("particle radius [um]")
        a2.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
