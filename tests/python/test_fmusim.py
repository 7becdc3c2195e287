"""The units in fmusim, the command-line simulator of the Modelica Association's Reference-FMUs (release
v0.0.39, the last that ships it), FMI 2.0 and 3.0. fmusim restarts CVode after an event only when the
unit reports valuesOfContinuousStatesChanged, applies inputs at their samples as events, and compares
times with an absolute tolerance of 1e-5 s (so the runs here last 1e-4 s with 2e-5 s output points, and
the impact happens inside the first). docs/hosts.md says what it is; these tests run where `fmusim`
is on PATH (or $FMUSIM names it) and are skipped elsewhere."""

from __future__ import annotations

import csv
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from fmu_support import fmu_dir
from masters import held_input_cs
from test_strict_cvode import sampled_sine

FMUSIM = os.environ.get("FMUSIM") or shutil.which("fmusim")
pytestmark = pytest.mark.skipif(FMUSIM is None, reason="fmusim (Reference-FMUs v0.0.39, docs/hosts.md) is not on PATH and $FMUSIM is not set")
RTOL = 1e-8


def fmu(name: str, fmi: str) -> Path:
    return (fmu_dir() / name if fmi == "2" else fmu_dir() / "fmi3" / name).with_suffix(".fmu")


def fmusim(path: Path, tmp_path: Path, *args: str, outputs: list[str]) -> tuple[dict[str, np.ndarray], subprocess.CompletedProcess]:
    out = tmp_path / f"out_{len(list(tmp_path.iterdir()))}.csv"
    cmd = [FMUSIM, *args, "--output-file", str(out)]
    for name in outputs:
        cmd += ["--output-variable", name]
    done = subprocess.run([*cmd, str(path)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, (cmd, done.stdout[-2000:], done.stderr[-2000:])
    with out.open() as f:
        rows = list(csv.reader(f))
    columns = {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}
    return columns, done


def impact_args(interface: str, v: float) -> list[str]:
    return ["--interface-type", interface, "--solver", "cvode", "--tolerance", str(RTOL), "--stop-time", "1e-4", "--output-interval", "2e-5",
            "--start-value", "initial_velocity", str(v), "--start-value", "gravity", "0"]


@pytest.mark.parametrize("fmi", ["2", "3"])
def test_impact_model_exchange_agrees_with_co_simulation(tmp_path, fmi):
    """Before the units reported valuesOfContinuousStatesChanged, fmusim went on with CVode's step across
    each event on the old branch: the rebound was 32 % off at 2 m/s. Now within 10 rtol in energy."""
    path = fmu("ParticleWallImpact", fmi)
    for v in (2.0, 3.0, 5.0, 10.0):
        me, _ = fmusim(path, tmp_path, *impact_args("me", v), outputs=["sphere_velocity", "contact_state"])
        cs, _ = fmusim(path, tmp_path, *impact_args("cs", v), outputs=["sphere_velocity", "contact_state"])
        assert me["time"][-1] == pytest.approx(1e-4) and me["contact_state"][-1] == 0
        v_me, v_cs = me["sphere_velocity"][-1], cs["sphere_velocity"][-1]
        assert v_cs > 0
        assert abs(v_me**2 - v_cs**2) / v**2 < 10 * RTOL, (fmi, v, v_me, v_cs)


def test_co_simulation_with_early_return(tmp_path):
    """FMI 3.0 Co-Simulation with Event Mode and early return: the steps end at the contact events and
    the rebound is the one of plain steps."""
    path = fmu("ParticleWallImpact", "3")
    args = impact_args("cs", 3.0)
    plain, _ = fmusim(path, tmp_path, *args, outputs=["sphere_velocity"])
    early, _ = fmusim(path, tmp_path, *args, "--early-return-allowed", "--event-mode-used", outputs=["sphere_velocity", "contact_state"])
    # fmusim records a row at each early return: the contact's events inside the first output interval.
    assert len(early["time"]) > len(plain["time"])
    assert early["sphere_velocity"][-1] == pytest.approx(plain["sphere_velocity"][-1], rel=1e-12)


@pytest.mark.parametrize("fmi", ["2", "3"])
def test_contact_element_held_inputs_as_input_events(contact, tmp_path, fmi):
    """A sampled sine through contact, yield, pull-off and re-contact, each sample held until the next
    (two CSV rows at each sample time: fmusim's discrete change of a continuous input, an event). The
    forces before each event and the work equal Co-Simulation stepped over the same held inputs."""
    s = sampled_sine(4e-8, 1.0, 2.0, 201)
    table = tmp_path / "held.csv"
    with table.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time", "wall_displacement", "wall_velocity"])
        for k in range(s.size):
            if k > 0:
                w.writerow([repr(float(s["time"][k])), repr(float(s["wall_displacement"][k - 1])), repr(float(s["wall_velocity"][k - 1]))])
            w.writerow([repr(float(s["time"][k])), repr(float(s["wall_displacement"][k])), repr(float(s["wall_velocity"][k]))])
    outputs = ["force", "dissipated_energy", "contact_state"]
    me, _ = fmusim(fmu("ContactElement", fmi), tmp_path, "--interface-type", "me", "--solver", "cvode", "--tolerance", str(RTOL), "--stop-time", "2",
                   "--output-interval", "0.01", "--input-file", str(table), outputs=outputs)
    cs = held_input_cs(contact, {}, s, ["wall_displacement", "wall_velocity"], outputs)
    assert {0, 1, 2, 3} <= set(cs["contact_state"].astype(int))
    # The first row at each sample time is recorded before the event that sets the next sample.
    first = {}
    for i, t in enumerate(me["time"]):
        first.setdefault(round(t, 9), i)
    rows = [first[round(t, 9)] for t in s["time"][1:]]
    peak = np.max(np.abs(cs["force"]))
    assert np.max(np.abs(me["force"][rows] - cs["force"])) <= 1e-12 * peak
    assert abs(me["dissipated_energy"][-1] / cs["dissipated_energy"][-1] - 1) < 10 * RTOL


def test_the_default_experiment_is_below_fmusims_time_resolution(tmp_path):
    """What a user meets: ParticleWallImpact's default experiment (2e-7 s, an impact of 50 ns) is below
    fmusim's absolute time tolerance of 1e-5 s, so fmusim records the start and stops, with exit code 0
    (docs/units/ParticleWallImpact.md)."""
    out, _ = fmusim(fmu("ParticleWallImpact", "2"), tmp_path, "--interface-type", "me", "--solver", "cvode", outputs=["sphere_velocity"])
    assert list(out["time"]) == [0.0]


@pytest.mark.parametrize("fmi", ["2", "3"])
def test_state_files_despite_fmusims_free(tmp_path, fmi):
    """fmusim's --final-fmu-state-file and --initial-fmu-state-file free the state by passing the state
    itself, not its address. The units recognise it, free it with a logged warning and succeed, so the
    saved run ends normally and a run restored from the file goes on from the saved time (0.25 s: the
    start time at which the Reference-FMUs crash there)."""
    path, state = fmu("ParticleWallImpact", fmi), tmp_path / "state.bin"
    args = ["--interface-type", "cs", "--output-interval", "2e-5", "--start-value", "gravity", "0"]
    first, done = fmusim(path, tmp_path, *args, "--start-time", "0.25", "--stop-time", "0.2501", "--final-fmu-state-file", str(state),
                         "--logging-on", outputs=["sphere_velocity"])
    assert state.stat().st_size > 0
    assert "the FMU state itself, not the address" in done.stdout + done.stderr
    whole, _ = fmusim(path, tmp_path, *args, "--start-time", "0.25", "--stop-time", "0.2503", outputs=["sphere_velocity"])
    # The state carries the parameters: fmusim sets start values after restoring it, where a fixed
    # parameter is refused by name, so none are given.
    resumed, _ = fmusim(path, tmp_path, "--interface-type", "cs", "--output-interval", "2e-5", "--start-time", "0.2501", "--stop-time", "0.2503",
                        "--initial-fmu-state-file", str(state), outputs=["sphere_velocity"])
    assert resumed["time"][0] == pytest.approx(0.2501) and resumed["time"][-1] == pytest.approx(0.2503)
    # fmusim's step sizes from 0.2501 round differently from those of the whole run (start + n interval).
    assert resumed["sphere_velocity"][-1] == pytest.approx(whole["sphere_velocity"][-1], rel=1e-6)
