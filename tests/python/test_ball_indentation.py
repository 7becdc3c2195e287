"""BallIndentation through fmpy: the default test with no arguments, what its outputs mean, the
communication step, saved states mid-test, and bad input refused at initialization with the host
surviving."""

import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from fmpy.validation import validate_fmu

from fmu_support import MessageLog, refused

LOADING, UNLOADING, DONE = 0, 1, 2


@pytest.fixture(scope="module")
def default_run(indentation):
    return indentation.simulate()


def test_validates_and_offers_co_simulation_only(indentation):
    assert validate_fmu(str(indentation.path)) == []
    assert indentation.md.modelExchange is None
    assert indentation.md.coSimulation.canGetAndSetFMUstate and indentation.md.coSimulation.canSerializeFMUstate


def test_model_exchange_is_refused_by_name(indentation):
    from fmpy.fmi2 import FMU2Model

    log = MessageLog()
    fmu = FMU2Model(guid=indentation.md.guid, unzipDirectory=indentation.unzipdir, modelIdentifier="BallIndentation", instanceName="me")
    with pytest.raises(Exception):
        fmu.instantiate(callbacks=log.callbacks)
    assert any("Co-Simulation only" in m for m in log.messages()), log.messages()


def test_the_default_test_loads_unloads_and_ends(indentation, default_run):
    r = default_run
    d = indentation.start("indenter_diameter")
    h_max = indentation.start("max_penetration")
    state = r["test_state"]
    assert state[0] == LOADING and state[-1] == DONE
    assert np.all(np.diff(state) >= 0), "loading, then unloading, then done"
    loading = r[state == LOADING]
    # The depth grows at the indentation speed and turns at max_penetration.
    assert r["penetration_depth"].max() == pytest.approx(h_max, rel=1e-3)
    assert r["dimensionless_penetration"].max() == pytest.approx(h_max / (d / 2), rel=1e-3)
    # While loading: A(h) of Eq. 2.9 and hardness F/A.
    deep = loading[loading["penetration_depth"] > 0.25 * h_max]
    h = deep["penetration_depth"]
    assert np.allclose(deep["projected_area"], math.pi * (d * h - h * h), rtol=1e-12)
    assert np.allclose(deep["hardness"], deep["indenter_force"] / deep["projected_area"], rtol=1e-12)
    assert np.all(deep["indenter_force"] > 0) and np.all(deep["indenter_contacts"] > 0)
    # After unloading: h_c is the tangent's, inside the indent, or h_max where the bed let go too fast for
    # one, and the outputs say which; hardness = F_max / A(h_c) with F_max the loading line's force at
    # h_max (force_at_turn, read over the last tenth of the loading), within the force's fluctuation of
    # its largest sample.
    last = r[-1]
    hc = last["contact_depth"]
    # The indenter turns at the engine step that reaches max_penetration (between two output rows).
    turned = h_max
    if last["contact_depth_from_tangent"]:
        assert 0 < hc < turned
    else:
        assert h_max <= hc < h_max * (1 + 1e-3), (float(hc), h_max)
    f_turn = last["force_at_turn"]
    assert last["hardness"] == pytest.approx(f_turn / (math.pi * (d * hc - hc * hc)), rel=1e-12)
    # (The unit samples every 100 engine steps, the output rows here less often: its largest sample may
    # lie above theirs.)
    assert 0.7 * r["indenter_force"].max() < f_turn < 1.1 * r["indenter_force"].max()
    # The force at the turn is A(h_max) times the mean F/A over the last tenth of the loading depth.
    tail = loading[loading["penetration_depth"] >= 0.9 * turned]
    assert len(tail) >= 3
    assert f_turn == pytest.approx(math.pi * (d * turned - turned**2) * np.mean(tail["hardness"]), rel=0.05), "sampled every 100 engine steps by the unit, every output step here"
    # The plateau: the mean of F/A over the loading samples at 0.1 <= h/r <= 0.2, with an error that is a
    # few per cent of it, and the mean of the output rows there within a few of those errors.
    window = loading[(loading["dimensionless_penetration"] >= 0.1) & (loading["dimensionless_penetration"] <= 0.2)]
    mean_rows = np.mean(window["hardness"])
    se = last["plateau_hardness_standard_error"]
    assert last["plateau_samples"] > 10 and 0 < se < 0.1 * last["plateau_hardness"]
    assert abs(last["plateau_hardness"] - mean_rows) < 4 * se, (last["plateau_hardness"], mean_rows, se)
    assert last["depth_origin_offset"] == 0.0, "depth from the first touch by default"
    assert last["unconfined_yield_strength"] == last["hardness"] / indentation.start("constraint_factor")
    assert last["indenter_contacts"] == 0
    # Compression in the dynamic bin under a loaded indenter.
    assert np.mean(deep["hydrostatic_stress"]) > 0 and np.all(deep["deviatoric_stress"] >= 0)


def test_the_communication_step_changes_nothing(indentation, default_run):
    fine = indentation.simulate(output_interval=float(indentation.md.defaultExperiment.stepSize) / 2.7)
    assert fine["test_state"][-1] == DONE
    assert fine[-1]["hardness"] == default_run[-1]["hardness"]
    assert fine[-1]["contact_depth"] == default_run[-1]["contact_depth"]


def _outputs(indentation, fmu):
    names = ["indenter_force", "penetration_depth", "hardness", "hydrostatic_stress", "kinetic_energy"]
    return fmu.getReal([indentation.vr[n] for n in names])


@pytest.mark.parametrize("threads", [1, 2])
def test_a_saved_state_continues_bit_for_bit(indentation, threads):
    """On two threads too: a restored bed rebuilds its Verlet list where the running one last built it, so
    its partition over threads, and each sphere's sum of forces, is the running one's."""
    fmu = indentation.slave("saved")
    indentation.initialize(fmu, {"threads": threads})
    t, h = 0.0, 2e-4
    for _ in range(20):
        fmu.doStep(t, h)
        t += h
    state = fmu.getFMUstate()
    serialized = fmu.serializeFMUstate(state)
    ahead = []
    for k in range(10):
        fmu.doStep(t + k * h, h)
        ahead.append(_outputs(indentation, fmu))
    for restore in ("state", "serialized"):
        if restore == "state":
            fmu.setFMUstate(state)
        else:
            fmu.setFMUstate(fmu.deSerializeFMUstate(serialized))
        again = []
        for k in range(10):
            fmu.doStep(t + k * h, h)
            again.append(_outputs(indentation, fmu))
        assert again == ahead, restore
    fmu.freeFMUstate(state)
    fmu.terminate()
    fmu.freeInstance()


def test_bad_input_is_refused_at_initialization_and_the_host_survives(indentation, tmp_path):
    refused(indentation, {"indenter_diameter": 0.01}, "indenter_diameter")
    refused(indentation, {"max_penetration": 0.05}, "max_penetration")
    refused(indentation, {"bed_file": str(tmp_path / "missing.pfbed")}, "bed_file")
    bed = Path(indentation.unzipdir) / "resources" / "bed.pfbed"
    truncated = tmp_path / "truncated.pfbed"
    truncated.write_bytes(bed.read_bytes()[: bed.stat().st_size // 2])
    refused(indentation, {"bed_file": str(truncated)}, "bed_file")
    refused(indentation, {"indenter_motion": "input"}, "indenter_velocity", {"indenter_displacement": 0.0, "indenter_velocity": -0.01})
    refused(indentation, {"indenter_motion": "input"}, "indenter_displacement", {"indenter_displacement": 1e-4, "indenter_velocity": 0.01})
    refused(indentation, {"indenter_motion": "sideways"}, "indenter_motion")
    refused(indentation, {"fidelity": "medium"}, "fidelity")
    refused(indentation, {"time_step": 1e-3}, "time_step")
    refused(indentation, {"depth_origin": "surface"}, "depth_origin")
    refused(indentation, {"plateau_start": 0.2, "plateau_end": 0.1}, "plateau_end")
    # A bed prepared with other materials is another powder: the difference is named, for a changed
    # parameter and for another bed (the shipped one, under the stand-in's parameters).
    messages = refused(indentation, {"particle_particle.surface_energy": 2.0}, "bed_file")
    assert any("particle_particle.surface_energy" in m for m in messages), messages
    messages = refused(indentation, {"bed_file": str(bed)}, "bed_file")
    assert any("was prepared with particle_particle." in m for m in messages), messages
    # After all that, a good instance still runs.
    fmu = indentation.slave("good")
    indentation.initialize(fmu)
    fmu.doStep(0.0, 1e-3)
    assert fmu.getReal([indentation.vr["penetration_depth"]])[0] > 0
    fmu.terminate()
    fmu.freeInstance()


def test_input_motion_follows_a_host_signal(indentation):
    speed = indentation.start("indentation_speed")
    h_max = indentation.start("max_penetration")
    t_turn = h_max / speed
    t = np.linspace(0, 2 * t_turn, 201)
    depth = np.where(t < t_turn, speed * t, h_max - speed * (t - t_turn))
    rate = np.where(t < t_turn, speed, -speed)
    signal = np.array(list(zip(t, depth, rate)), dtype=[("time", float), ("indenter_displacement", float), ("indenter_velocity", float)])
    r = indentation.simulate(start_values={"indenter_motion": "input"}, input=signal, stop_time=2 * t_turn)
    i = np.argmin(np.abs(r["time"] - t_turn))
    assert r["penetration_depth"][i] == pytest.approx(h_max, rel=0.02)
    assert r["indenter_force"][i] > 0
    assert UNLOADING in r["test_state"]


def test_the_indenter_has_its_own_contact(indentation, default_run):
    """The particle-indenter keys are free (004 Secs. 6.2.1, 6.2.3 vary them); the bed's stay the bed's."""
    rough = indentation.simulate(start_values={"particle_indenter.friction_coefficient": 0.5})
    assert rough["test_state"][-1] == DONE
    assert rough["indenter_force"].max() != default_run["indenter_force"].max()
    assert indentation.start("particle_indenter.friction_coefficient") == indentation.start("particle_wall.friction_coefficient")


def test_the_test_reports_its_progress_through_the_logger(indentation):
    from fmpy.fmi2 import FMU2Slave

    log = MessageLog()
    fmu = FMU2Slave(guid=indentation.md.guid, unzipDirectory=indentation.unzipdir, modelIdentifier="BallIndentation", instanceName="news")
    fmu.instantiate(callbacks=log.callbacks, loggingOn=True)
    indentation.initialize(fmu)
    t, h = 0.0, 1e-3
    while fmu.getInteger([indentation.vr["test_state"]])[0] != DONE and t < 1.0:
        fmu.doStep(t, h)
        t += h
    fmu.terminate()
    fmu.freeInstance()
    events = [r.message for r in log.records if r.category == "logEvents"]
    assert any(m.startswith("bed ") and "spheres" in m for m in events), events
    assert any(m.startswith("unloading from h_max") for m in events), events
    assert any(m.startswith("the indenter has left the bed") for m in events), events


def test_the_engine_threads_end_with_the_instance(indentation):
    """threads = 2 starts the bed engine's helper thread; fmi2FreeInstance joins it (Linux: /proc/self/task)."""
    import os

    before = len(os.listdir("/proc/self/task"))
    fmu = indentation.slave("threads")
    indentation.initialize(fmu, {"threads": 2})
    fmu.doStep(0.0, 2e-3)
    assert fmu.getReal([indentation.vr["penetration_depth"]])[0] > 0
    during = len(os.listdir("/proc/self/task"))
    fmu.terminate()
    fmu.freeInstance()
    # The helper has been joined when fmi2FreeInstance returns; the kernel reaps the thread a moment later.
    import time

    start = time.monotonic()
    while len(os.listdir("/proc/self/task")) != before and time.monotonic() - start < 1.0:
        time.sleep(0.001)
    after = len(os.listdir("/proc/self/task"))
    assert during == before + 1, "two threads: the caller's and one helper"
    assert after == before, f"{after - before} threads left after fmi2FreeInstance"


def test_the_depth_from_the_mean_surface_is_the_depth_from_the_first_touch_less_the_offset(indentation, default_run):
    """depth_origin = mean_surface: the bed's mean surface under the footprint lies below the first touch
    by depth_origin_offset (less than a sphere); the indenter starts at the first touch as before, so the
    same motion gives the same forces, every depth that much smaller (until the turn, which comes at
    max_penetration below the mean surface)."""
    r = indentation.simulate(start_values={"depth_origin": "mean_surface"}, stop_time=0.004)
    offset = r["depth_origin_offset"][0]
    assert 0 < offset < 1e-3, offset
    assert np.all(r["depth_origin_offset"] == offset)
    n = len(r)
    assert np.allclose(r["penetration_depth"], default_run["penetration_depth"][:n] - offset, rtol=0, atol=1e-15)
    assert np.array_equal(r["indenter_force"], default_run["indenter_force"][:n])


def _table_c_at_10_kpa():
    """C and its standard error at 10 kPa from the committed table (docs/data/constraint_factor_ch6_seed_window.csv)."""
    import csv

    from fmu_support import REPO

    with open(REPO / "docs" / "data" / "constraint_factor_ch6_seed_window.csv") as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    row = next(r for r in rows if float(r["consolidation_stress_Pa"]) == 1e4)
    return float(row["constraint_factor"]), float(row["constraint_factor_standard_error"])


def test_a_measured_constraint_factor_divides_the_yield_strength_with_its_error(shipped_indentation):
    """`constraint_factor_source` = measured on the seed's material (the shipped quarter bed, consolidated
    to 10 kPa): the unit divides by the table's C(10 kPa) and adds its error; the constant stays exact."""
    c, c_error = _table_c_at_10_kpa()
    u = shipped_indentation
    read = ["hardness", "hardness_standard_error", "unconfined_yield_strength", "unconfined_yield_strength_standard_error", "constraint_factor_used", "constraint_factor_used_standard_error"]
    got = {}
    for source in ["measured", "constant"]:
        fmu = u.slave(source)
        u.initialize(fmu, {"constraint_factor_source": source})
        t, h = 0.0, 1e-3
        for _ in range(3):  # 3 ms of loading (0.21 mm at the default speed): the indenter is in the bed
            fmu.doStep(t, h)
            t += h
        got[source] = dict(zip(read, fmu.getReal([u.vr[n] for n in read])))
        fmu.terminate()
        fmu.freeInstance()
    m, k = got["measured"], got["constant"]
    assert m["hardness"] > 0 and m["hardness"] == k["hardness"], "the same test either way"
    assert m["constraint_factor_used"] == pytest.approx(c, rel=1e-12) and m["constraint_factor_used_standard_error"] == pytest.approx(c_error, rel=1e-12)
    assert m["unconfined_yield_strength"] == pytest.approx(m["hardness"] / c, rel=1e-12)
    # While loading the hardness is one sample (its error 0): the yield strength's error is C's alone.
    assert m["hardness_standard_error"] == 0.0
    assert m["unconfined_yield_strength_standard_error"] == pytest.approx(m["unconfined_yield_strength"] * c_error / c, rel=1e-12)
    assert (k["constraint_factor_used"], k["constraint_factor_used_standard_error"]) == (3.0, 0.0)
    assert k["unconfined_yield_strength"] == pytest.approx(k["hardness"] / 3.0, rel=1e-15) and k["unconfined_yield_strength_standard_error"] == 0.0


def test_a_measured_constraint_factor_is_refused_for_another_material_or_source(indentation):
    # The suite's stand-in bed is another powder than the one C was measured on: refused, by name.
    messages = refused(indentation, {"constraint_factor_source": "measured"}, "constraint_factor_source")
    assert any("004 Ch. 6 material" in m and "differs from it in particle_particle." in m for m in messages), messages
    messages = refused(indentation, {"constraint_factor_source": "table"}, "constraint_factor_source")
    assert any("allowed constant, measured" in m for m in messages), messages
