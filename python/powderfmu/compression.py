"""The unconfined compression test as a sweep task: one UnconfinedCompression run (Co-Simulation, through
fmpy) with the given parameters, summarised by its readings. Keys: any UnconfinedCompression parameter
(`bed_file`, `strain_rate`, `max_strain`, `window`, ...), plus `stop_time` [s] and `output_interval` [s]
of the run (default: the unit's DefaultExperiment). A flow function is a sweep over `bed_file`: beds
consolidated to several sigma_1 (`powderfmu bed prepare` with `consolidation_stress` changed)."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any, Mapping

from fmpy import simulate_fmu

from . import indentation
from .fmus import fmu_path

SUMMARY_KEYS = (
    "unconfined_yield_strength",
    "unconfined_yield_strength_standard_error",
    "strain_at_failure",
    "failed",
    "flow_function",
    "consolidation_stress",
    "solid_fraction",
    "self_weight_stress",
    "axial_strain",
    "test_state",
    "wall_time",
)


def resolve(inputs: Mapping[str, Any], fmu: Path | None = None, check_unit: bool = False) -> tuple[dict[str, Any], dict[str, Any]]:
    """(run settings, start values) of a task, checked as `indentation.resolve` checks its own (the same
    rules: unknown keys and non-positive times are errors; `check_unit` initializes the unit, loading the bed)."""
    return indentation.resolve(inputs, fmu or fmu_path("UnconfinedCompression"), check_unit)


def run(inputs: Mapping[str, Any], fmu: Path | None = None) -> dict[str, Any]:
    fmu = fmu or fmu_path("UnconfinedCompression")
    settings, start = resolve(inputs, fmu)
    started = time.perf_counter()
    r = simulate_fmu(
        str(fmu), fmi_type="CoSimulation", start_values=start, stop_time=settings["stop_time"], output_interval=settings["output_interval"]
    )
    last = r[-1]
    row: dict[str, Any] = {k: float(last[k]) for k in SUMMARY_KEYS if k not in ("failed", "test_state", "wall_time")}
    row["failed"] = bool(last["failed"])
    row["test_state"] = int(last["test_state"])
    row["wall_time"] = time.perf_counter() - started
    return {k: row[k] for k in SUMMARY_KEYS}
