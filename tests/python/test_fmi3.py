"""The FMI 3.0 units through fmpy: every one validates, simulates in Model Exchange and Co-Simulation, and
gives the numbers of its FMI 2.0 twin to the bit; Co-Simulation returns early at contact events, so a
master stepping at 1 ms sees an impact of 0.1 us at the closed form's times; bad input and calls out of
order are refused by name with the unit still usable; saved states continue bit for bit and belong to
their version.

The FMI 3.0 FMUs are target/fmu/fmi3/<Unit>.fmu (`cargo run -p fmu_build`)."""

from __future__ import annotations

import ctypes
import math
import shutil
import tempfile

import fmpy
import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi3 import FMU3Model, FMU3Slave, fmi3LogMessageCallback
from fmpy.validation import validate_fmu

from fmu_support import StrictCVode, fmu_dir

UNITS = ["ParticleWallImpact", "ContactElement", "BallIndentation", "UnconfinedCompression"]


def path3(name: str):
    p = fmu_dir() / "fmi3" / f"{name}.fmu"
    if not p.is_file():
        pytest.fail(f"{p} does not exist: build the FMUs with `cargo run -p fmu_build`", pytrace=False)
    return p


def path2(name: str):
    return fmu_dir() / f"{name}.fmu"


@pytest.fixture(scope="module")
def unzipped():
    """Each FMI 3.0 FMU extracted once: name -> (directory, model description)."""
    dirs = {}
    for name in UNITS:
        d = extract(str(path3(name)), tempfile.mkdtemp(prefix=f"powderfmu-fmi3-{name}-"))
        dirs[name] = (d, read_model_description(d))
    yield dirs
    for d, _ in dirs.values():
        shutil.rmtree(d, ignore_errors=True)


class Log:
    """An fmi3LogMessageCallback that keeps the messages (keep it alive while the instance lives)."""

    def __init__(self):
        self.records = []

        def log(_env, status, category, message):
            self.records.append((int(status), (category or b"").decode(), (message or b"").decode()))

        self.callback = log

    def errors(self):
        return [m for s, _, m in self.records if s >= 3]


def slave(unzipped, name, log, **kw):
    d, md = unzipped[name]
    fmu = FMU3Slave(guid=md.guid, unzipDirectory=d, modelIdentifier=name, instanceName="cs3")
    fmu.instantiate(logMessage=log.callback, **kw)
    return fmu, {v.name: v.valueReference for v in md.modelVariables}


# ---------------------------------------------------------------------------------------------------
# The model descriptions


@pytest.mark.parametrize("name", UNITS)
def test_every_fmi3_fmu_validates_and_has_the_fmi2_variables(name):
    assert validate_fmu(str(path3(name))) == []
    md3 = read_model_description(str(path3(name)))
    md2 = read_model_description(str(path2(name)))
    assert md3.fmiVersion == "3.0" and md2.fmiVersion == "2.0"
    assert md3.guid != md2.guid, "the FMI 3.0 instantiationToken is not the FMI 2.0 GUID"
    fmi3_type = {"Real": "Float64", "Integer": "Int32", "Boolean": "Boolean", "String": "String"}
    v2 = [(v.name, v.valueReference, fmi3_type[v.type], v.causality, v.variability, v.unit, v.start) for v in md2.modelVariables]
    v3 = [(v.name, v.valueReference, v.type, v.causality, v.variability, v.unit, v.start) for v in md3.modelVariables]
    assert v3 == v2, "the same table: names, references, types, units and starts"
    cs = md3.coSimulation
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate and cs.canHandleVariableCommunicationStepSize
    if name == "ParticleWallImpact":
        assert cs.hasEventMode and cs.mightReturnEarlyFromDoStep
        # The normal motion's three and the tangential contact's (issue 33).
        assert len(md3.eventIndicators) == 4 and len(md3.derivatives) == 6
    if name in ("BallIndentation", "UnconfinedCompression"):
        assert md3.modelExchange is None


# ---------------------------------------------------------------------------------------------------
# The same numbers as FMI 2.0


def _same(r3, r2):
    assert r3.dtype.names == r2.dtype.names and len(r3) == len(r2)
    for n in r3.dtype.names:
        assert np.array_equal(r3[n], r2[n]), n


@pytest.mark.parametrize("kind", ["CoSimulation", "ModelExchange"])
def test_the_default_impact_is_the_fmi2_one_to_the_bit(kind):
    out = ["force", "overlap", "contact_state", "sphere_velocity", "dissipated_energy", "max_overlap"]
    r3 = fmpy.simulate_fmu(str(path3("ParticleWallImpact")), fmi_type=kind, output=out)
    r2 = fmpy.simulate_fmu(str(path2("ParticleWallImpact")), fmi_type=kind, output=out)
    _same(r3, r2)
    # The impact happened: the sphere came back with a restitution coefficient in (0, 1).
    assert r3["max_overlap"][-1] > 0 and 0 < -r3["sphere_velocity"][-1] / -r3["sphere_velocity"][0] < 1


@pytest.mark.parametrize("kind", ["CoSimulation", "ModelExchange"])
def test_the_contact_element_under_a_triangle_wave_is_the_fmi2_one_to_the_bit(kind):
    t = np.linspace(0, 1.0, 11)
    peak = 4e-8
    w = peak * (1 - np.abs(2 * t - 1))
    dw = np.where(t < 0.5, 2 * peak, -2 * peak)
    signal = np.array(list(zip(t, w, dw)), dtype=[("time", float), ("wall_displacement", float), ("wall_velocity", float)])
    out = ["force", "overlap", "contact_state", "plastic_overlap", "dissipated_energy"]
    r3 = fmpy.simulate_fmu(str(path3("ContactElement")), fmi_type=kind, input=signal, output=out, output_interval=1e-2)
    r2 = fmpy.simulate_fmu(str(path2("ContactElement")), fmi_type=kind, input=signal, output=out, output_interval=1e-2)
    _same(r3, r2)
    assert r3["plastic_overlap"].max() > 0, "loaded into plastic"


def test_model_exchange_under_a_strict_cvode_is_the_fmi2_one_to_the_bit():
    """The hard case of the strict-CVode suite (test_strict_cvode.py): a damped sphere on a 20 kHz wall
    sampled 4000 times, CVode with a minimum step of 1e-12 s, through FMI 3.0 and FMI 2.0."""
    amplitude, stop, omega = 2e-8, 2e-4, 2 * np.pi * 2e4
    t = np.linspace(0.0, stop, 4001)
    signal = np.array(list(zip(t, amplitude * np.sin(omega * t), amplitude * omega * np.cos(omega * t))),
                      dtype=[("time", float), ("wall_displacement", float), ("wall_velocity", float)])
    start = {"initial_velocity": 0.0, "gravity": 9.81, "initial_gap": 0.0, "restitution_coefficient": 0.5}
    out = ["force", "overlap", "contact_state", "max_overlap", "dissipated_energy"]
    runs = {}
    for version, path in [(3, path3("ParticleWallImpact")), (2, path2("ParticleWallImpact"))]:
        with StrictCVode() as cvode:
            runs[version] = fmpy.simulate_fmu(str(path), fmi_type="ModelExchange", start_values=start, input=signal, stop_time=stop, output_interval=5e-8, output=out)
            runs[version, "events"] = cvode.root_returns
    _same(runs[3], runs[2])
    assert runs[3]["time"][-1] == pytest.approx(stop) and {1, 2} <= set(runs[3]["contact_state"])
    assert runs[3, "events"] == runs[2, "events"] > 0


def test_the_default_indentation_is_the_fmi2_one_to_the_bit():
    """The first 2 ms of the default test on the shipped bed (29000 spheres)."""
    md = read_model_description(str(path3("BallIndentation")))
    out = [v.name for v in md.modelVariables if v.causality == "output"]
    r3 = fmpy.simulate_fmu(str(path3("BallIndentation")), output=out, stop_time=2e-3)
    r2 = fmpy.simulate_fmu(str(path2("BallIndentation")), output=out, stop_time=2e-3)
    _same(r3, r2)
    assert r3["indenter_force"].max() > 0


def test_a_whole_indentation_test_is_the_fmi2_one_to_the_bit(indentation):
    """The whole test (load, unload, hardness) on the suite's stand-in bed (800 spheres)."""
    out = [v.name for v in indentation.md.modelVariables if v.causality == "output"]
    runs = {}
    for version, path in [(3, path3("BallIndentation")), (2, path2("BallIndentation"))]:
        runs[version] = fmpy.simulate_fmu(str(path), start_values=indentation.defaults, output=out, **indentation.experiment)
    _same(runs[3], runs[2])
    assert runs[3]["test_state"][-1] == 2 and runs[3]["hardness"][-1] > 0, "loaded, unloaded, a hardness"


# ---------------------------------------------------------------------------------------------------
# Early return


def _linear_impact(k=100.0, gap=1e-8, v=1.0):
    """A linear spring without damping: contact at gap / v, separation half a period pi sqrt(m/k) later."""
    md = read_model_description(str(path3("ParticleWallImpact")))
    start = {v_.name: v_.start for v_ in md.modelVariables}
    radius, density = float(start["particle_radius"]), float(start["particle_density"])
    m = 4 / 3 * math.pi * radius**3 * density
    values = {"contact_model": "linear", "elastic_stiffness": k, "restitution_coefficient": 1.0, "initial_gap": gap, "initial_velocity": v}
    return values, gap / v, gap / v + math.pi * math.sqrt(m / k)


@pytest.mark.parametrize("event_mode", [True, False])
def test_a_1_ms_step_returns_early_at_contact_and_separation_at_the_closed_forms_times(event_mode):
    values, t_contact, t_separation = _linear_impact()
    r = fmpy.simulate_fmu(
        str(path3("ParticleWallImpact")),
        start_values=values,
        stop_time=3e-3,
        output_interval=1e-3,
        early_return_allowed=True,
        use_event_mode=event_mode,
        output=["contact_state", "overlap", "sphere_velocity"],
    )
    t, state = r["time"], r["contact_state"]
    formed = t[np.argmax(state == 1)]
    separated = t[np.flatnonzero(state == 1)[-1] + 1]
    assert formed == pytest.approx(t_contact, rel=4e-16, abs=0)
    assert separated == pytest.approx(t_separation, rel=1e-14, abs=0)
    # The sphere leaves at the speed it came with (no damping) and the master's grid goes on at 1 ms.
    assert r["sphere_velocity"][-1] == pytest.approx(1.0, rel=1e-12)
    assert np.allclose(t[-3:], [1e-3, 2e-3, 3e-3], rtol=1e-15, atol=0)


@pytest.mark.parametrize("solver", ["adaptive", "verlet"])
def test_every_integrator_returns_early_at_contact_and_separation(solver):
    """adaptive locates the events as it locates every branch switch; verlet ends the step after the
    fixed step in which the state changed (its own resolution, rayleigh_fraction of the Rayleigh step)."""
    values, t_contact, t_separation = _linear_impact()
    r = fmpy.simulate_fmu(str(path3("ParticleWallImpact")), start_values={**values, "solver": solver}, stop_time=2e-3,
                          output_interval=1e-3, early_return_allowed=True, output=["contact_state"])
    t, state = r["time"], r["contact_state"]
    formed, separated = t[np.argmax(state == 1)], t[np.flatnonzero(state == 1)[-1] + 1]
    tol = 1e-9 if solver == "adaptive" else 0.2 * (t_separation - t_contact)
    assert formed == pytest.approx(t_contact, abs=tol * (1 if solver != "adaptive" else t_contact))
    assert separated == pytest.approx(t_separation, abs=tol * (1 if solver != "adaptive" else t_separation))
    assert list(state[t > 1e-6]) == [0] * int(np.sum(t > 1e-6)), "no event after separation"


def test_an_oblique_step_returns_early_at_contact_stick_slip_and_separation():
    """The oblique adaptive integrator (a tangential velocity at the start) returns early where the contact
    state or `sliding` changes: contact and separation at the closed form's times (the normal motion does
    not depend on the tangential), a switch between them, and the rebound that the run without early
    return gives."""
    values, t_contact, t_separation = _linear_impact()
    values |= {"initial_tangential_velocity": 0.3}
    out = ["contact_state", "sliding", "tangential_velocity", "angular_velocity", "sphere_velocity"]
    runs = [fmpy.simulate_fmu(str(path3("ParticleWallImpact")), start_values=values, stop_time=3e-3, output_interval=1e-3,
                              early_return_allowed=early, output=out) for early in (True, False)]
    r = runs[0]
    t, state, sliding = r["time"], r["contact_state"], r["sliding"]
    assert t[np.argmax(state == 1)] == pytest.approx(t_contact, rel=1e-9)
    assert t[np.flatnonzero(state == 1)[-1] + 1] == pytest.approx(t_separation, rel=1e-9)
    switches = t[1:][sliding[1:] != sliding[:-1]]
    assert len(switches) >= 1 and all(t_contact < ts < t_separation + 1e-15 for ts in switches), switches
    for name in ("tangential_velocity", "angular_velocity", "sphere_velocity"):
        assert r[name][-1] == pytest.approx(runs[1][name][-1], rel=1e-9)
    assert r["angular_velocity"][-1] > 0, "the wall's friction spins the sphere forward"


def test_an_event_at_the_step_end_asks_for_event_mode_without_an_early_return(unzipped):
    """A master whose communication point is the contact time itself: the step completes (no early
    return) and, with Event Mode, is asked to handle the event there."""
    values, _, _ = _linear_impact()

    def started():
        fmu, vr = slave(unzipped, "ParticleWallImpact", Log(), eventModeUsed=True, earlyReturnAllowed=True)
        for name, value in values.items():
            if isinstance(value, str):
                fmu.setString([vr[name]], [value])
            else:
                fmu.setFloat64([vr[name]], [value])
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        fmu.updateDiscreteStates()
        fmu.enterStepMode()
        return fmu, vr

    fmu, vr = started()
    event, _, early, t_contact = fmu.doStep(0.0, 1e-3)
    assert early and event
    fmu.terminate()
    fmu.freeInstance()
    # A second run whose step ends exactly there.
    fmu, vr = started()
    event, _, early, t_last = fmu.doStep(0.0, t_contact)
    assert event and not early and t_last == t_contact
    assert fmu.getInt32([vr["contact_state"]]) == [1]
    fmu.terminate()
    fmu.freeInstance()


def test_without_early_return_a_1_ms_step_sees_no_contact():
    values, _, _ = _linear_impact()
    r = fmpy.simulate_fmu(str(path3("ParticleWallImpact")), start_values=values, stop_time=2e-3, output_interval=1e-3, output=["contact_state", "sphere_velocity"])
    assert list(r["time"]) == pytest.approx([0, 1e-3, 2e-3])
    assert np.all(r["contact_state"] == 0), "the whole impact fell inside one step"
    assert r["sphere_velocity"][-1] == pytest.approx(1.0, rel=1e-12), "but its effect is there"


def test_early_return_and_event_mode_through_the_c_calls(unzipped):
    log = Log()
    fmu, vr = slave(unzipped, "ParticleWallImpact", log, eventModeUsed=True, earlyReturnAllowed=True)
    values, t_contact, _ = _linear_impact()
    for name, value in values.items():
        if isinstance(value, str):
            fmu.setString([vr[name]], [value])
        else:
            fmu.setFloat64([vr[name]], [value])
    fmu.enterInitializationMode(startTime=0.0)
    fmu.exitInitializationMode()
    # With eventModeUsed the instance starts in Event Mode, as Model Exchange does.
    fmu.updateDiscreteStates()
    fmu.enterStepMode()
    event, terminate, early, t_last = fmu.doStep(0.0, 1e-3)
    assert early and event and not terminate
    assert t_last == pytest.approx(t_contact, rel=4e-16, abs=0)
    assert fmu.getInt32([vr["contact_state"]]) == [1]
    assert fmu.getFloat64([vr["time"]]) == [t_last]
    # A step from anywhere but lastSuccessfulTime is refused; the instance stays where it is.
    with pytest.raises(Exception):
        fmu.doStep(1e-3, 1e-3)
    assert any("is not the unit's time" in m for m in log.errors())
    fmu.enterEventMode()
    fmu.updateDiscreteStates()
    fmu.enterStepMode()
    event, _, early, t2 = fmu.doStep(t_last, 1e-3 - t_last)
    assert early and t2 > t_last
    fmu.terminate()
    fmu.freeInstance()


def _instance_with_callback(unzipped, early_return, on_event):
    """A ParticleWallImpact CS instance (the linear impact) whose intermediate-update callback is
    `on_event(fmu, vr, time) -> bool` (True: end the step here)."""
    log = Log()
    d, md = unzipped["ParticleWallImpact"]
    fmu = FMU3Slave(guid=md.guid, unzipDirectory=d, modelIdentifier="ParticleWallImpact", instanceName="iu")
    vr = {v.name: v.valueReference for v in md.modelVariables}

    def callback(_env, t, set_requested, get_allowed, step_finished, can_return_early, early_requested, early_time):
        assert get_allowed and not set_requested and step_finished
        assert bool(can_return_early) == early_return
        if on_event(fmu, vr, t):
            early_requested[0] = True
            early_time[0] = t

    fmu.instantiate(logMessage=log.callback, earlyReturnAllowed=early_return, intermediateUpdate=callback)
    values, t_contact, t_separation = _linear_impact()
    for name, value in values.items():
        if isinstance(value, str):
            fmu.setString([vr[name]], [value])
        else:
            fmu.setFloat64([vr[name]], [value])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    return fmu, vr, log, t_contact, t_separation


def test_intermediate_updates_tell_the_master_of_each_event_inside_a_1_ms_step(unzipped):
    seen = []

    def on_event(fmu, vr, t):
        # Intermediate Update Mode: the outputs at the event can be read, the parameters cannot.
        seen.append((t, fmu.getInt32([vr["contact_state"]])[0]))
        try:
            fmu.getFloat64([vr["particle_radius"]])
            seen.append("a parameter was readable")
        except Exception:
            pass
        try:
            fmu.doStep(t, 1e-3)
            seen.append("doStep inside the callback was accepted")
        except Exception:
            pass
        return False

    fmu, vr, log, t_contact, t_separation = _instance_with_callback(unzipped, False, on_event)
    _, _, early, t_last = fmu.doStep(0.0, 1e-3)
    assert not early and t_last == pytest.approx(1e-3, rel=1e-15), "the step went to its end"
    assert [x for x in seen if isinstance(x, str)] == [], seen
    events = [x for x in seen if not isinstance(x, str)]
    assert [state for _, state in events] == [1, 0], "contact, then separation"
    assert events[0][0] == pytest.approx(t_contact, rel=4e-16, abs=0)
    assert events[1][0] == pytest.approx(t_separation, rel=1e-14, abs=0)
    assert any("Intermediate Update Mode only the outputs" in m for m in log.errors())
    assert any("fmi3DoStep must not be called in Intermediate Update Mode" in m for m in log.errors())
    assert fmu.getFloat64([vr["sphere_velocity"]]) == pytest.approx([1.0], rel=1e-12)
    fmu.terminate()
    fmu.freeInstance()


def test_an_intermediate_update_can_end_the_step_at_its_event(unzipped):
    # End the step at the second event (separation), not at the first.
    fmu, vr, log, t_contact, t_separation = _instance_with_callback(unzipped, True, lambda fmu, vr, t: t > 2 * t_contact)
    _, _, early, t_last = fmu.doStep(0.0, 1e-3)
    assert early and t_last == pytest.approx(t_separation, rel=1e-14, abs=0)
    assert fmu.getInt32([vr["contact_state"]]) == [0]
    # The next step goes on from there.
    _, _, early, t_last = fmu.doStep(t_last, 1e-3 - t_last)
    assert not early and t_last == pytest.approx(1e-3)
    fmu.terminate()
    fmu.freeInstance()


# ---------------------------------------------------------------------------------------------------
# Bad input, calls out of order, saved states


def test_bad_input_is_refused_by_name_and_the_unit_stays_usable(unzipped):
    log = Log()
    fmu, vr = slave(unzipped, "ParticleWallImpact", log)
    fmu.setFloat64([vr["particle_radius"]], [-1.0])
    fmu.enterInitializationMode()
    with pytest.raises(Exception):
        fmu.exitInitializationMode()
    assert any("particle_radius" in m for m in log.errors()), log.records
    fmu.reset()
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 1e-8)
    assert fmu.getFloat64([vr["time"]]) == [1e-8]
    # A type the units do not have is refused with the variable's real type.
    with pytest.raises(Exception):
        fmu.getInt64([vr["force"]])
    assert any("`force`, a Float64 variable, not Int64" in m for m in log.errors())
    # A non-finite input is refused and changes nothing.
    before = fmu.getFloat64([vr["wall_velocity"]])
    with pytest.raises(Exception):
        fmu.setFloat64([vr["wall_velocity"]], [math.nan])
    assert fmu.getFloat64([vr["wall_velocity"]]) == before
    fmu.terminate()
    fmu.freeInstance()


def test_calls_out_of_order_are_refused_by_name(unzipped):
    log = Log()
    fmu, vr = slave(unzipped, "ContactElement", log)
    with pytest.raises(Exception):
        fmu.doStep(0.0, 1e-3)
    assert any("fmi3DoStep must not be called in Instantiated" in m for m in log.errors()), log.records
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    # ContactElement has no events inside a step: no Event Mode in Co-Simulation.
    with pytest.raises(Exception):
        fmu.enterEventMode()
    assert any("hasEventMode is false" in m for m in log.errors())
    fmu.doStep(0.0, 1e-3)
    fmu.terminate()
    fmu.freeInstance()


def test_an_instance_made_with_the_fmi2_guid_is_refused(unzipped):
    d, _ = unzipped["ContactElement"]
    guid2 = read_model_description(str(path2("ContactElement"))).guid
    log = Log()
    fmu = FMU3Slave(guid=guid2, unzipDirectory=d, modelIdentifier="ContactElement", instanceName="wrong")
    with pytest.raises(Exception):
        fmu.instantiate(logMessage=log.callback)
    assert any("is the GUID of the FMI 2.0 ContactElement" in m for m in log.errors()), log.records


def test_a_saved_state_continues_bit_for_bit(unzipped):
    log = Log()
    fmu, vr = slave(unzipped, "ParticleWallImpact", log)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    h = 1e-9
    for i in range(20):
        fmu.doStep(i * h, h)
    state = fmu.getFMUState()
    blob = fmu.serializeFMUState(state)
    outs = [vr[n] for n in ["force", "overlap", "sphere_velocity", "dissipated_energy"]]
    first = []
    for i in range(20, 60):
        fmu.doStep(i * h, h)
        first.append(fmu.getFloat64(outs))
    restored = fmu.deserializeFMUState(blob)
    fmu.setFMUState(restored)
    again = []
    for i in range(20, 60):
        fmu.doStep(i * h, h)
        again.append(fmu.getFloat64(outs))
    assert again == first
    fmu.freeFMUState(state)
    fmu.freeFMUState(restored)
    fmu.terminate()
    fmu.freeInstance()


def test_model_exchange_by_hand_reports_its_sizes_and_events(unzipped):
    d, md = unzipped["ParticleWallImpact"]
    log = Log()
    fmu = FMU3Model(guid=md.guid, unzipDirectory=d, modelIdentifier="ParticleWallImpact", instanceName="me3")
    fmu.instantiate(logMessage=log.callback)
    assert fmu.getNumberOfContinuousStates() == 6 and fmu.getNumberOfEventIndicators() == 4
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.updateDiscreteStates()
    fmu.enterContinuousTimeMode()
    z = (ctypes.c_double * 4)()
    fmu.getEventIndicators(z, 4)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    names = ["event_indicator_lower", "event_indicator_upper", "event_indicator_rate", "event_indicator_stick_slip"]
    assert fmu.getFloat64([vr[n] for n in names]) == list(z), "the indicators are the variables ModelStructure names"
    fmu.terminate()
    fmu.freeInstance()
