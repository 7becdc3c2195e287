"""The two FMUs through fmpy as a user runs them: validation, ME and CS, the physics against the energy
balance and the seeds' tables, a vibrating wall, saved states (also across processes), two instances,
and bad input. Reference values come from `powderfmu analyze` at run time or from the seeds' tables."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from fmu_support import MessageLog, rel, sphere_mass

OUT = ["force", "overlap", "contact_state", "sphere_velocity", "max_overlap", "dissipated_energy", "plastic_overlap"]


def run_impact(unit, v, stop=3e-7, interval=1e-9, fmi_type="CoSimulation", **start):
    return unit.simulate(fmi_type, start_values={"initial_velocity": v, **start}, stop_time=stop, output_interval=interval, output=OUT,
                         relative_tolerance=1e-8 if fmi_type == "ModelExchange" else None)


def rebounds(unit, v, stop=4e-7, **start):
    """True when the sphere leaves the wall, False when it turns back toward it (sticks)."""
    while stop < 1e-4:
        r = run_impact(unit, v, stop=stop, interval=2e-9, **start)
        u = r["sphere_velocity"]
        away = np.nonzero(u > 0)[0]
        if len(away) and np.any(u[away[0]:] < 0):
            return False
        if u[-1] > 0 and r["overlap"][-1] < 0 and r["contact_state"][-1] == 0:
            return True
        stop *= 4
    raise AssertionError(f"impact at {v} m/s undecided after {stop:e} s")


def sticking_velocity(unit, lo, hi, rel_tol=1e-4, **start):
    assert not rebounds(unit, lo, **start) and rebounds(unit, hi, **start)
    while hi - lo > rel_tol * hi:
        mid = 0.5 * (lo + hi)
        if rebounds(unit, mid, **start):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


# --- validation and both interfaces -------------------------------------------------------------------


@pytest.mark.parametrize("name", ["ParticleWallImpact", "ContactElement"])
def test_validate_fmu_finds_no_problem(name, impact_fmu_path, contact_fmu_path):
    path = impact_fmu_path if name == "ParticleWallImpact" else contact_fmu_path
    assert validate_fmu(str(path)) == []


def test_both_units_offer_model_exchange_and_co_simulation(impact, contact):
    for u in (impact, contact):
        assert u.md.modelExchange is not None and u.md.coSimulation is not None
        assert u.md.coSimulation.canHandleVariableCommunicationStepSize


def test_me_under_cvode_agrees_with_cs(impact):
    cs = run_impact(impact, 3.0)
    me = run_impact(impact, 3.0, fmi_type="ModelExchange")
    assert rel(me["sphere_velocity"][-1], cs["sphere_velocity"][-1]) < 1e-4
    assert set(me["contact_state"]) == set(cs["contact_state"]) == {0, 1, 2, 3}


# --- physics ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("v", [2.5, 3.0, 5.0])
def test_undamped_nan_impact_gives_the_energy_balance_restitution(impact, cli, v):
    r = run_impact(impact, v)
    ref = cli.analyze(impact.scene(), velocity=v)
    assert rel(r["sphere_velocity"][-1] / v, ref["restitution"]) < 1e-6
    assert rel(r["max_overlap"][-1], ref["max_overlap"]) < 1e-6
    m = sphere_mass(impact.start("particle_radius"), impact.start("particle_density"))
    lost = 0.5 * m * (v * v - r["sphere_velocity"][-1] ** 2)
    assert rel(r["dissipated_energy"][-1], lost) < 1e-8


# 000 Table 6, e_0 = 1: V_ys [m/s] by radius and yield pressure.
TABLE6 = [(2.45e-6, 30e6, 1.86), (1.72e-6, 30e6, 2.83), (3.445e-6, 25e6, 1.51)]


@pytest.mark.parametrize("radius,p_y,paper", TABLE6)
def test_sticking_velocity_through_the_fmu_reproduces_000_table_6(impact, cli, radius, p_y, paper):
    start = {"particle_radius": radius, "particle_yield_pressure": p_y}
    v_ys = sticking_velocity(impact, 0.5 * paper, 1.5 * paper, **start)
    assert rel(v_ys, paper) < 0.01, f"R = {radius} m, p_y = {p_y} Pa: {v_ys} m/s vs 000 Table 6 {paper} m/s"
    closed_form = cli.analyze(impact.scene(start))["sticking_velocity"]
    assert rel(v_ys, closed_form) < 3e-4


def test_pasha_table_4_2_sticks_below_and_rebounds_above_about_1_6_m_s(impact):
    import json
    from fmu_support import REPO

    scene = json.loads((REPO / "scenes" / "pasha_table_4_2.json").read_text())
    start = {k: v for k, v in scene.items() if k in impact.variables}
    # The scene's wall has no yield pressure; the unit's default wall is silicon's, which the law ignores.
    assert not rebounds(impact, 1.4, **start)
    assert rebounds(impact, 1.7, **start)


def test_a_sphere_on_a_vibrating_wall_bounces_and_stays_above_it(impact):
    t = np.linspace(0, 2e-4, 4001)
    amp, f = 2e-8, 2e4
    w = amp * np.sin(2 * np.pi * f * t)
    wd = amp * 2 * np.pi * f * np.cos(2 * np.pi * f * t)
    signals = np.array(list(zip(t, w, wd)), dtype=[("time", float), ("wall_displacement", float), ("wall_velocity", float)])
    start = {"initial_velocity": 0.0, "gravity": 9.81, "initial_gap": 0.0, "restitution_coefficient": 0.5}
    for fmi_type in ("CoSimulation", "ModelExchange"):
        r = impact.simulate(fmi_type, start_values=start, stop_time=2e-4, output_interval=5e-8, input=signals, output=OUT)
        assert r["time"][-1] == pytest.approx(2e-4), fmi_type
        assert np.all(np.isfinite(r["force"])) and np.all(np.isfinite(r["sphere_velocity"]))
        assert r["max_overlap"][-1] < 5 * amp, fmi_type
        assert {1, 2}.issubset(set(r["contact_state"])), fmi_type
        assert r["dissipated_energy"][-1] > 0, fmi_type  # damped and plastic: the contact takes energy


def test_contact_element_loading_cycle(contact):
    t = np.linspace(0, 2, 2001)
    alpha = 60e-9 * (1 - np.abs(t - 1))
    signals = np.array(list(zip(t, alpha, np.gradient(alpha, t))), dtype=[("time", float), ("wall_displacement", float), ("wall_velocity", float)])
    for fmi_type in ("CoSimulation", "ModelExchange"):
        r = contact.simulate(fmi_type, stop_time=2, output_interval=1e-3, input=signals,
                             output=["force", "overlap", "contact_state", "plastic_overlap", "dissipated_energy", "max_overlap"])
        loading = r["time"] < 0.99
        assert 2 in set(r["contact_state"][loading]), fmi_type
        assert r["plastic_overlap"][-1] > 0 and r["dissipated_energy"][-1] > 0
        assert rel(r["max_overlap"][-1], 60e-9) < 1e-6
        # Continuous while in contact (the law jumps only at contact formation and detachment, 000 Fig. 1).
        touching = (r["contact_state"][1:] > 0) & (r["contact_state"][:-1] > 0)
        assert np.max(np.abs(np.diff(r["force"]))[touching]) < 1e-2 * np.max(r["force"]), fmi_type


# --- saved states, instances ------------------------------------------------------------------------------


def _step(unit, fmu, t, h, n):
    vr = [unit.vr["sphere_velocity"], unit.vr["force"], unit.vr["overlap"]]
    out = []
    for i in range(n):
        fmu.doStep(t + i * h, h)
        out.append(tuple(fmu.getReal(vr)))
    return out


def test_state_rollback_and_serialization_round_trip(impact):
    fmu = impact.slave()
    impact.initialize(fmu, {"initial_velocity": 3.0})
    h = 1e-9
    _step(impact, fmu, 0.0, h, 20)
    state = fmu.getFMUstate()
    first = _step(impact, fmu, 20 * h, h, 80)
    fmu.setFMUstate(state)
    assert _step(impact, fmu, 20 * h, h, 80) == first
    data = fmu.serializeFMUstate(state)
    state2 = fmu.deSerializeFMUstate(data)
    fmu.setFMUstate(state2)
    assert _step(impact, fmu, 20 * h, h, 80) == first
    fmu.freeFMUstate(state)
    fmu.freeFMUstate(state2)
    fmu.terminate()
    fmu.freeInstance()


def test_a_state_serialized_in_one_process_continues_identically_in_another(impact, tmp_path):
    fmu = impact.slave()
    impact.initialize(fmu, {"initial_velocity": 3.0})
    h = 1e-9
    _step(impact, fmu, 0.0, h, 30)
    data = bytes(fmu.serializeFMUstate(fmu.getFMUstate()))
    expected = _step(impact, fmu, 30 * h, h, 50)
    fmu.terminate()
    fmu.freeInstance()
    (tmp_path / "state.bin").write_bytes(data)
    script = textwrap.dedent(f"""
        import sys, json
        sys.path.insert(0, {str(impact.path.parent.parent.parent / 'tests' / 'python')!r})
        from fmpy import extract, read_model_description
        from fmpy.fmi2 import FMU2Slave
        d = extract({str(impact.path)!r})
        md = read_model_description(d)
        fmu = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="other")
        fmu.instantiate()
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode(); fmu.exitInitializationMode()
        data = open({str(tmp_path / 'state.bin')!r}, 'rb').read()
        fmu.setFMUstate(fmu.deSerializeFMUstate(data))
        vr = [v.valueReference for n in ("sphere_velocity", "force", "overlap") for v in md.modelVariables if v.name == n]
        out = []
        for i in range(50):
            fmu.doStep({30 * h!r} + i * {h!r}, {h!r})
            out.append([x.hex() for x in fmu.getReal(vr)])
        print(json.dumps(out))
    """)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    import json

    got = [tuple(float.fromhex(x) for x in row) for row in json.loads(run.stdout)]
    assert got == expected


def test_two_instances_in_one_process_do_not_interfere(impact):
    h = 1e-9
    alone = []
    for start in ({"initial_velocity": 3.0}, {"initial_velocity": 5.0, "contact_model": "thornton_ning"}):
        fmu = impact.slave("alone")
        impact.initialize(fmu, start)
        alone.append(_step(impact, fmu, 0.0, h, 150))
        fmu.terminate()
        fmu.freeInstance()
    a, b = impact.slave("a"), impact.slave("b")
    impact.initialize(a, {"initial_velocity": 3.0})
    impact.initialize(b, {"initial_velocity": 5.0, "contact_model": "thornton_ning"})
    both = ([], [])
    for i in range(150):
        both[0].extend(_step(impact, a, i * h, h, 1))
        both[1].extend(_step(impact, b, i * h, h, 1))
    assert both[0] == alone[0] and both[1] == alone[1]
    for f in (a, b):
        f.terminate()
        f.freeInstance()


# --- bad input ----------------------------------------------------------------------------------------------


def test_nan_parameter_is_refused_with_its_name(impact):
    log = MessageLog()
    fmu = impact.slave(log=log)
    with pytest.raises(FMICallException):
        fmu.setReal([impact.vr["surface_energy"]], [float("nan")])
    assert any("surface_energy" in m for m in log.messages(3))
    fmu.freeInstance()


@pytest.mark.parametrize("name,value,words", [
    ("particle_radius", -1e-6, ["particle_radius", "allowed"]),
    ("particle_poisson_ratio", 0.7, ["particle_poisson_ratio", "allowed"]),
])
def test_negative_or_out_of_range_parameter_fails_initialization_with_a_message(impact, name, value, words):
    log = MessageLog()
    fmu = impact.slave(log=log)
    fmu.setupExperiment(startTime=0.0)
    impact.set_start_values(fmu, {name: value})
    fmu.enterInitializationMode()
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    assert any(all(w in m for w in words) for m in log.messages(3)), log.messages()
    # A failed initialization leaves the instance in the Error state; fmi2Reset brings back the start
    # values and the same instance runs.
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    fmu.reset()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 1e-9)
    fmu.freeInstance()


def test_unknown_contact_model_names_the_choices(impact):
    log = MessageLog()
    fmu = impact.slave(log=log)
    fmu.setupExperiment(startTime=0.0)
    impact.set_start_values(fmu, {"contact_model": "nann"})
    fmu.enterInitializationMode()
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    assert any("contact_model" in m and "thornton_ning" in m for m in log.messages(3))
    fmu.freeInstance()


def test_do_step_before_initialization_and_negative_steps_are_errors(impact):
    log = MessageLog()
    fmu = impact.slave(log=log)
    with pytest.raises(FMICallException):
        fmu.doStep(0.0, 1e-9)
    assert any("fmi2DoStep" in m for m in log.messages(3))
    impact.initialize(fmu)
    log.clear()
    with pytest.raises(FMICallException):
        fmu.doStep(0.0, -1e-9)
    assert any("communicationStepSize" in m for m in log.messages(3))
    fmu.doStep(0.0, 1e-9)
    fmu.freeInstance()


def test_wrong_guid_and_missing_resources_refuse_to_instantiate(impact, tmp_path):
    from fmpy.fmi2 import FMU2Slave

    log = MessageLog()
    with pytest.raises(Exception):
        impact.slave(log=log, guid="{00000000-0000-0000-0000-000000000000}")
    assert any("fmuGUID" in m for m in log.messages(3))
    log.clear()
    # An unzipped FMU without its resources folder: fmpy passes file://.../resources all the same.
    import shutil

    copy = tmp_path / "unzipped"
    shutil.copytree(impact.unzipdir, copy)
    shutil.rmtree(copy / "resources")
    fmu = FMU2Slave(guid=impact.md.guid, unzipDirectory=str(copy), modelIdentifier="ParticleWallImpact", instanceName="x")
    with pytest.raises(Exception):
        fmu.instantiate(callbacks=log.callbacks)
    assert any("fmuResourceLocation" in m and "not a directory" in m for m in log.messages(3))


def test_after_all_errors_a_new_simulation_runs(impact):
    r = run_impact(impact, 3.0)
    assert r["sphere_velocity"][-1] > 0


@pytest.mark.parametrize("which", ["impact", "contact"])
def test_derived_parameters_are_in_the_log_at_initialization(request, cli, which):
    """A parameter left at 0 is derived ("0 means derive it"); the value it became is logged (logEvents)
    at initialization, the same as `powderfmu analyze` gives."""
    from fmpy.fmi2 import FMU2Slave

    unit = request.getfixturevalue(which)
    for given in (None, 400.0):
        log = MessageLog()
        fmu = FMU2Slave(guid=unit.md.guid, unzipDirectory=unit.unzipdir, modelIdentifier=unit.md.coSimulation.modelIdentifier, instanceName="derived")
        fmu.instantiate(callbacks=log.callbacks, loggingOn=True)
        start = {} if given is None else {"elastic_stiffness": given}
        unit.initialize(fmu, start)
        fmu.terminate()
        fmu.freeInstance()
        lines = [r.message for r in log.records if r.category == "logEvents" and r.message.startswith("derived parameters")]
        assert len(lines) == 1, [r.message for r in log.records]
        k_el = float(lines[0].split("k_el = ")[1].split(" N/m")[0])
        expected = cli.analyze(unit.scene(start))["k_el"]
        assert rel(k_el, expected) < 1e-6, (lines[0], expected)
        if given is not None:
            assert rel(k_el, given) < 1e-12
