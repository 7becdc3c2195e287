"""The units inside a system model: the ultrasonic sieve of `powderfmu.sieve` (a vibrated plate and N
ParticleWallImpact instances, two-way coupled) and its sweeps on Dask (`powderfmu.sweep`)."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from fmu_support import REPO, rel

sieve = pytest.importorskip("powderfmu.sieve", reason="the powderfmu package is installed by tools/venv.sh")
from powderfmu import sweep  # noqa: E402

# A powder that never yields (yield pressures far above the Nan law's critical 5e7 Pa): its contact keeps
# the fresh pull-off force f_ce = 1.5 pi Gamma R (000 Eq. 5) through settling and the compressive
# half-cycles, the case of the closed form.
NEVER_YIELDS = {"particle_yield_pressure": 1e10, "wall_yield_pressure": 1e10}


def one_particle(acceleration: float, frequency: float = 1e3, **keys) -> sieve.Result:
    spec = {"particles": 1, "radius_spread": 1.0, "acceleration": acceleration, "frequency": frequency, "periods": 4, "plate_mass": 1.0}
    return sieve.run({**spec, **NEVER_YIELDS, **keys})


def threshold(frequency: float, guess: float, rel_tol: float = 1e-3, **keys) -> float:
    """The smallest peak plate acceleration that detaches the particle, by bisection."""
    lo, hi = guess / 4, guess * 4
    assert not one_particle(lo, frequency, **keys).detached[0] and one_particle(hi, frequency, **keys).detached[0]
    while hi / lo - 1 > rel_tol:
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if one_particle(mid, frequency, **keys).detached[0] else (mid, hi)
    return math.sqrt(lo * hi)


def test_the_low_frequency_threshold_is_the_closed_form():
    """At 1 kHz (far below the contact's ~1 MHz) the particle detaches when m (A w^2 - g) exceeds f_ce."""
    r = one_particle(1e3)
    radius, mass = r.radius[0], r.mass[0]
    f_ce = 1.5 * math.pi * r.powder["surface_energy"] * radius
    assert rel(r.pull_off_force[0], f_ce) < 1e-9, "the settled contact keeps the fresh pull-off force"
    closed_form = f_ce / mass + r.system["gravity"]
    measured = threshold(1e3, closed_form)
    print(f"\nthreshold at 1 kHz: {measured:.6e} m/s2, closed form f_ce/m + g = {closed_form:.6e} m/s2 ({measured / closed_form - 1:+.2%})")
    assert rel(measured, closed_form) < 0.02


def test_a_particle_below_the_threshold_stays_and_one_above_leaves_in_the_first_tensile_half_cycle():
    closed_form = one_particle(1e3).quasi_static_threshold[0]
    assert not one_particle(0.97 * closed_form).detached[0]
    r = one_particle(1.03 * closed_form)
    # Detached near the first peak of the tensile half-cycle after the ramp's build-up (the plate at its
    # highest point, w t = pi mod 2 pi).
    t = r.detach_time[0] * r.system["frequency"]
    assert r.detached[0] and 0.0 < t < r.system["periods"] and abs((t % 1.0) - 0.5) < 0.1, t


def test_two_way_coupling_conserves_momentum_to_the_masters_step():
    """The plate gets the particles' impulse of each step one step late: plate impulse + particle momenta
    differ by that last step's impulse, which halves with the step."""
    spec = {"particles": 20, "plate_mass": 2e-9, "acceleration": 5e5, "frequency": 2e4, "periods": 3}
    coarse, fine = sieve.run({**spec, "steps_per_period": 50}), sieve.run({**spec, "steps_per_period": 100})
    for r in (coarse, fine):
        h = 1.0 / r.system["frequency"] / r.system["steps_per_period"]
        exchanged = np.abs(r.plate_force).sum() * h
        last = abs(r.plate_force[-1]) * h
        assert abs(r.momentum_defect) <= 1.0001 * last + 1e-12 * exchanged, (r.momentum_defect, last)
        assert last < 0.05 * exchanged
    assert 0.4 < abs(fine.momentum_defect) / abs(coarse.momentum_defect) < 0.6
    # The coupling is two-way: the powder's load changes the plate's motion.
    alone = sieve.run({**spec, "steps_per_period": 100, "particle_weight": 1e-9})
    assert rel(np.abs(fine.plate_position).max(), np.abs(alone.plate_position).max()) > 1e-3


def test_halving_the_step_moves_the_detachment_by_less_than_a_step():
    spec = {"particles": 20, "acceleration": 1.5e6, "frequency": 2e4, "periods": 4}
    a, b = sieve.run({**spec, "steps_per_period": 100}), sieve.run({**spec, "steps_per_period": 200})
    assert (a.detached == b.detached).all()
    h = 1.0 / 2e4 / 100
    assert np.nanmax(np.abs(a.detach_time - b.detach_time)) <= h


GRID = {"task": "sieve", "base": {"particles": 6, "periods": 3}, "grid": {"frequency": [2e4, 5e4], "acceleration": [8e5, 2e6]}}


def rows_by_task(path) -> dict[str, dict[str, str]]:
    _, rows = sweep.read(path)
    return {r["task_id"]: {k: v for k, v in r.items() if k != "wall_time"} for r in rows}


def test_a_sweep_on_a_two_worker_local_cluster_gives_the_serial_numbers_bit_for_bit(tmp_path):
    serial = sweep.run(GRID, tmp_path / "serial.csv", serial=True, progress=False)
    dask = sweep.run(GRID, tmp_path / "dask.csv", workers=2, progress=False)
    assert serial["ran"] == dask["ran"] == 4 and serial["failed"] == dask["failed"] == 0
    a, b = rows_by_task(tmp_path / "serial.csv"), rows_by_task(tmp_path / "dask.csv")
    assert a == b
    assert {r["status"] for r in a.values()} == {"ok"}
    spec, _ = sweep.read(tmp_path / "dask.csv")
    assert spec == GRID
    header = (tmp_path / "dask.csv").read_text().splitlines()[:4]
    assert header[2].startswith("# versions: ") and "fmpy" in header[2] and "dask" in header[2]
    assert header[3].startswith("# fmu: ParticleWallImpact.fmu guid {")


def test_a_sweep_on_an_existing_scheduler_gives_the_serial_numbers(tmp_path):
    from distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        counts = sweep.run(GRID, tmp_path / "remote.csv", scheduler=cluster.scheduler_address, progress=False)
    assert counts["ran"] == 4
    sweep.run(GRID, tmp_path / "serial.csv", serial=True, progress=False)
    assert rows_by_task(tmp_path / "remote.csv") == rows_by_task(tmp_path / "serial.csv")


def test_an_interrupted_sweep_resumes_without_redoing_finished_tasks(tmp_path):
    out = tmp_path / "sweep.csv"
    calls = []

    def interrupted(task, inputs):
        if len(calls) == 2:
            raise KeyboardInterrupt
        calls.append(inputs)
        return sweep.run_task(task, inputs)

    with pytest.raises(KeyboardInterrupt):
        sweep.run(GRID, out, serial=True, progress=False, task_runner=interrupted)
    assert len(rows_by_task(out)) == 2
    resumed = sweep.run(GRID, out, serial=True, progress=False)
    assert resumed["skipped"] == 2 and resumed["ran"] == 2
    whole = sweep.run(GRID, tmp_path / "whole.csv", serial=True, progress=False)
    assert whole["ran"] == 4
    assert rows_by_task(out) == rows_by_task(tmp_path / "whole.csv")
    # Nothing left to do: a third call runs nothing.
    assert sweep.run(GRID, out, serial=True, progress=False)["ran"] == 0
    # Another spec into the same file is refused.
    with pytest.raises(sweep.SweepError, match="another sweep"):
        sweep.run({**GRID, "base": {"particles": 7}}, out, serial=True, progress=False)


def test_a_sweep_command_stopped_with_ctrl_c_resumes_where_it_was(tmp_path):
    """The command on a LocalCluster, interrupted (SIGINT) once some rows are in the file, run again."""
    import signal
    import time

    spec = {**GRID, "base": {"particles": 40, "periods": 10}, "grid": {"frequency": [2e4, 3e4, 4e4, 5e4], "acceleration": [1e6, 2e6, 3e6, 4e6]}}
    path = tmp_path / "spec.json"
    path.write_text(json.dumps(spec))
    out = tmp_path / "spec.csv"
    cmd = [sys.executable, "-m", "powderfmu.sweep", str(path), "--workers", "2", "--quiet"]
    # Ctrl-C's default action in the command, even when this suite runs as a background job (a shell
    # starts those with SIGINT ignored, and Python then never raises KeyboardInterrupt).
    first = subprocess.Popen(cmd, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and first.poll() is None:
        if out.exists() and sum(1 for line in out.read_text().splitlines() if line.endswith(",ok,")) >= 3:
            break
        time.sleep(0.05)
    first.send_signal(signal.SIGINT)
    first.communicate(timeout=60)
    done_before = sum(1 for line in out.read_text().splitlines() if line.endswith(",ok,"))
    assert 3 <= done_before < 16, f"interrupted after {done_before} tasks"
    again = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert f"{16 - done_before} ran, {done_before} already done, 0 failed" in again.stdout, again.stdout
    rows = rows_by_task(out)
    assert len(rows) == 16 and {r["status"] for r in rows.values()} == {"ok"}


def test_a_torn_line_and_a_task_that_failed_then_ran_leave_one_complete_row_each(tmp_path):
    out = tmp_path / "s.csv"

    def fails_once(task, inputs):
        if inputs["acceleration"] == 2e6 and inputs["frequency"] == 5e4 and not (tmp_path / "ran").exists():
            raise RuntimeError("not yet")
        return sweep.run_task(task, inputs)

    sweep.run(GRID, out, serial=True, progress=False, task_runner=fails_once)
    (tmp_path / "ran").touch()
    with out.open("a") as f:
        f.write("deadbeefdeadbeef,50000.0,20")  # a row torn by a kill
    assert sweep.run(GRID, out, serial=True, progress=False, task_runner=fails_once)["ran"] == 1
    _, rows = sweep.read(out)
    assert len(rows) == 4 and {r["status"] for r in rows} == {"ok"}
    assert all(None not in r.values() for r in rows)
    # Rebuilding the FMU (another GUID) and resuming into the same file is refused.
    text = out.read_text().replace("# fmu: ParticleWallImpact.fmu guid {", "# fmu: ParticleWallImpact.fmu guid {0")
    out.write_text(text)
    with pytest.raises(sweep.SweepError, match="another build of the FMU"):
        sweep.run(GRID, out, serial=True, progress=False)


def test_a_failed_task_is_retried_once_then_reported_with_its_inputs(tmp_path, capsys):
    attempts = []

    def flaky(task, inputs):
        if inputs["acceleration"] == 2e6 and inputs["frequency"] == 5e4:
            attempts.append(inputs)
            raise RuntimeError("the plate broke")
        return sweep.run_task(task, inputs)

    counts = sweep.run(GRID, tmp_path / "s.csv", serial=True, progress=False, task_runner=flaky)
    assert counts["failed"] == 1 and counts["ran"] == 3 and len(attempts) == 2
    rows = rows_by_task(tmp_path / "s.csv")
    failed = [r for r in rows.values() if r["status"] == "failed"]
    assert len(failed) == 1 and "the plate broke" in failed[0]["error"] and failed[0]["frequency"] == "50000.0"
    assert '"frequency": 50000.0' in capsys.readouterr().err
    # A resume runs the failed task again (and only it).
    assert sweep.run(GRID, tmp_path / "s.csv", serial=True, progress=False)["ran"] == 1


def test_on_the_cluster_too_a_failed_task_is_retried_once_and_reported(tmp_path):
    attempts = tmp_path / "attempts.txt"

    def flaky(task, inputs):
        if inputs["acceleration"] == 2e6 and inputs["frequency"] == 5e4:
            with open(attempts, "a") as f:
                f.write("x\n")
            raise RuntimeError("the plate broke")
        return sweep.run_task(task, inputs)

    counts = sweep.run(GRID, tmp_path / "s.csv", workers=2, progress=False, task_runner=flaky)
    assert counts["failed"] == 1 and counts["ran"] == 3
    assert attempts.read_text().count("x") == 2, "one run and one retry"
    failed = [r for r in rows_by_task(tmp_path / "s.csv").values() if r["status"] == "failed"]
    assert len(failed) == 1 and "the plate broke" in failed[0]["error"]


@pytest.mark.parametrize(
    "spec, words",
    [
        ({**GRID, "base": {"particles": 6, "frequncy": 1e3}}, ["frequncy", "unknown key"]),
        ({"task": "sieve", "grid": {}}, ["grid", "empty"]),
        ({"task": "sieve", "grid": {"frequency": []}}, ["grid.frequency", "non-empty"]),
        ({"task": "sieve", "grid": {"frequency": [1e3, -5e3]}}, ["frequency", "-5000", "> 0"]),
        ({"task": "sieve", "grid": {"frequency": [1e3, 1e3]}}, ["grid.frequency", "twice"]),
        ({"task": "sieve", "grid": {"surface_energy": [-1.0]}}, ["surface_energy"]),
        ({"task": "hopper", "grid": {"frequency": [1e3]}}, ["task", "hopper"]),
        ({"task": "sieve", "sample": {"count": 0, "ranges": {"frequency": [1e3, 1e4]}}}, ["sample.count"]),
    ],
)
def test_a_bad_spec_is_refused_before_any_task_starts(tmp_path, spec, words):
    def never(task, inputs):
        raise AssertionError("a task ran")

    with pytest.raises(sweep.SweepError) as e:
        sweep.run(spec, tmp_path / "s.csv", serial=True, progress=False, task_runner=never)
    for w in words:
        assert w in str(e.value), str(e.value)
    assert not (tmp_path / "s.csv").exists()


def test_the_sweep_command_line(tmp_path):
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps({**GRID, "grid": {"frequency": [2e4], "acceleration": [2e6]}}))
    ok = subprocess.run([sys.executable, "-m", "powderfmu.sweep", str(spec), "--serial", "--quiet"], capture_output=True, text=True, cwd=tmp_path)
    assert ok.returncode == 0, ok.stderr
    assert "1 tasks: 1 ran" in ok.stdout and (tmp_path / "spec.csv").exists()
    spec.write_text(json.dumps({"grid": {"frequency": [-1.0]}}))
    bad = subprocess.run([sys.executable, "-m", "powderfmu.sweep", str(spec), "--serial"], capture_output=True, text=True, cwd=tmp_path)
    assert bad.returncode == 2 and "frequency" in bad.stderr and "Traceback" not in bad.stderr


@pytest.mark.parametrize("frequency", [1e5, 2.5e6])
def test_model_exchange_and_co_simulation_agree_on_the_threshold_and_the_detachment(frequency):
    """One 10 um particle of the default powder on the prescribed plate: Co-Simulation (exact integrator,
    the plate's acceleration as an input derivative) against Model Exchange under fmpy's CVode with the
    inputs set at every evaluation; at 2.5 MHz the drive is at 0.7 of the contact's natural frequency."""
    from powderfmu import me

    spec = {"particle_radius": 10e-6, "radius_spread": 1.0, "plate_mass": 1.0, "periods": 6, "frequency": frequency}
    cs, model_exchange = sieve.detachment_threshold(spec, rel_tol=1e-3), me.detachment_threshold(spec, rel_tol=1e-3)
    print(f"\n{frequency:.1e} Hz: threshold CS {cs:.5e}, ME {model_exchange:.5e} m/s2")
    assert rel(model_exchange, cs) < 3e-3
    above = {**spec, "acceleration": 1.2 * cs}
    t_cs, m = sieve.run({**above, "particles": 1}).detach_time[0], me.run_particle(above)
    h = 1.0 / frequency / 100
    assert t_cs == pytest.approx(m.detach_time, rel=1e-12)
    assert t_cs - h < m.detach_event_time <= t_cs, "CS reports the detachment at the end of the step it happened in"


def test_the_sweep_runs_the_indentation_units_parameter_studies(tmp_path, quick_bed):
    """The indentation task: one BallIndentation run per task on the suite's stand-in bed, here the
    indenter's friction and surface energy against the powder, loading to h/r = 0.1."""
    from conftest import QUICK_TEST

    spec = {
        "task": "indentation",
        "base": {**quick_bed, **QUICK_TEST, "max_penetration": 0.0002, "stop_time": 0.01, "output_interval": 5e-4},
        "grid": {"particle_indenter.friction_coefficient": [0.0, 0.5], "particle_indenter.surface_energy": [0.0, 0.5]},
    }
    counts = sweep.run(spec, tmp_path / "ind.csv", serial=True, progress=False)
    assert counts["ran"] == 4 and counts["failed"] == 0
    _, rows = sweep.read(tmp_path / "ind.csv")
    force = {(r["particle_indenter.friction_coefficient"], r["particle_indenter.surface_energy"]): float(r["max_force"]) for r in rows}
    assert all(f > 0 for f in force.values())
    assert len(set(force.values())) == 4, "each parameter changes the test"
    assert all(float(r["plateau_hardness"]) > 0 and int(r["test_state"]) == 2 for r in rows), rows
    bad = {**spec, "grid": {"particle_indenter.friction_coefficient": [-1.0]}}
    with pytest.raises(sweep.SweepError, match="friction"):
        sweep.check(bad)


def test_the_sweep_runs_the_compression_units_parameter_studies(tmp_path, quick_bed):
    """The compression task: one UnconfinedCompression run per task on the suite's stand-in bed, here the
    strain rate and the window of sigma_c; a bad value is refused by name before any task runs."""
    spec = {
        "task": "compression",
        "base": {"bed_file": quick_bed["bed_file"], "threads": 1, "stop_time": 0.1, "output_interval": 1e-3},
        "grid": {"strain_rate": [1.0, 0.5], "window": [0.005, 0.01]},
    }
    counts = sweep.run(spec, tmp_path / "uct.csv", serial=True, progress=False)
    assert counts["ran"] == 4 and counts["failed"] == 0
    _, rows = sweep.read(tmp_path / "uct.csv")
    strength = {(float(r["strain_rate"]), float(r["window"])): float(r["unconfined_yield_strength"]) for r in rows}
    assert all(s > 0 for s in strength.values()) and len(set(strength.values())) == 4, strength
    for r in rows:
        sigma_1, sigma_c = float(r["consolidation_stress"]), float(r["unconfined_yield_strength"])
        assert float(r["flow_function"]) == pytest.approx(sigma_1 / sigma_c, rel=1e-12)
        assert r["failed"] == "True" and int(r["test_state"]) == 1, r
    with pytest.raises(sweep.SweepError, match="strain_rate"):
        sweep.check({**spec, "grid": {"strain_rate": [2e3]}})


def test_a_scene_file_becomes_start_values_and_a_misspelt_key_is_named(tmp_path):
    from powderfmu import fmu_path, start_values

    fmu = fmu_path("ParticleWallImpact")
    values = start_values(fmu, REPO / "scenes" / "ammonium_fluorescein_on_silicon.json")
    assert values["contact_model"] == "nan" and values["particle_radius"] == 2.45e-6 and values["surface_energy"] == 0.24
    r = sieve.run({"particles": 1, "periods": 0.5, "ramp_periods": 0.5, **{k: v for k, v in values.items() if k != "particle_radius"}})
    assert r.powder["surface_energy"] == 0.24
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"surface_enrgy": 0.3}))
    with pytest.raises(ValueError, match="'surface_enrgy' is not a parameter of ParticleWallImpact.*did you mean 'surface_energy'"):
        start_values(fmu, bad)
    with pytest.raises(ValueError, match="surface_energy.*must be a number"):
        start_values(fmu, {"surface_energy": "much"})
    with pytest.raises(ValueError, match="does not exist"):
        start_values(fmu, tmp_path / "missing.json")
