"""The ball indentation test as a sweep task: one BallIndentation run (Co-Simulation, through fmpy) with
the given parameters, summarised by its hardness readings. Keys: any BallIndentation parameter
(`bed_file`, `friction_coefficient`, `surface_energy`, `indentation_speed`, ...), plus `stop_time` [s]
and `output_interval` [s] of the run (default: the unit's DefaultExperiment)."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any, Mapping

from fmpy import read_model_description, simulate_fmu

from . import scene as scene_mod
from .fmus import fmu_path
from .instance import cosimulation

OWN_KEYS = ("stop_time", "output_interval")
SUMMARY_KEYS = (
    "plateau_hardness",
    "plateau_hardness_standard_error",
    "hardness",
    "hardness_standard_error",
    "unconfined_yield_strength",
    "unconfined_yield_strength_standard_error",
    "force_at_turn",
    "contact_depth",
    "max_force",
    "max_depth",
    "test_state",
    "wall_time",
)


def resolve(inputs: Mapping[str, Any], fmu: Path | None = None, check_unit: bool = False) -> tuple[dict[str, Any], dict[str, Any]]:
    """(run settings, start values) of a task, checked: unknown keys and non-positive times are errors;
    `check_unit` also initializes the unit with them (loading the bed), as a sweep does before any task."""
    fmu = fmu or fmu_path("BallIndentation")
    md = read_model_description(str(fmu))
    settings = {"stop_time": float(md.defaultExperiment.stopTime), "output_interval": float(md.defaultExperiment.stepSize)}
    params = {}
    for key, value in inputs.items():
        if key in OWN_KEYS:
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value > 0):
                raise ValueError(f"`{key}` = {value!r} must be a positive number of seconds")
            settings[key] = float(value)
        else:
            params[key] = value
    start = scene_mod.start_values(fmu, params)
    if check_unit:
        # The unit checks its parameters (ranges, the bed file and its scene) at initialization.
        p, _ = cosimulation(fmu, "check", start)
        p.terminate()
        p.freeInstance()
    return settings, start


def run(inputs: Mapping[str, Any], fmu: Path | None = None) -> dict[str, Any]:
    fmu = fmu or fmu_path("BallIndentation")
    settings, start = resolve(inputs, fmu)
    started = time.perf_counter()
    r = simulate_fmu(
        str(fmu), fmi_type="CoSimulation", start_values=start, stop_time=settings["stop_time"], output_interval=settings["output_interval"]
    )
    last = r[-1]
    return {
        "plateau_hardness": float(last["plateau_hardness"]),
        "plateau_hardness_standard_error": float(last["plateau_hardness_standard_error"]),
        "hardness": float(last["hardness"]),
        "hardness_standard_error": float(last["hardness_standard_error"]),
        "force_at_turn": float(last["force_at_turn"]),
        "contact_depth": float(last["contact_depth"]),
        "unconfined_yield_strength": float(last["unconfined_yield_strength"]),
        "unconfined_yield_strength_standard_error": float(last["unconfined_yield_strength_standard_error"]),
        "max_force": float(max(r["indenter_force"])),
        "max_depth": float(max(r["penetration_depth"])),
        "test_state": int(last["test_state"]),
        "wall_time": time.perf_counter() - started,
    }
