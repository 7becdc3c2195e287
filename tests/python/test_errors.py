"""Bad input through FMI: the call returns fmi2Error (fmpy raises FMICallException), the logger gets a
message naming the problem, Python does not crash, and simulations run normally afterwards."""

from __future__ import annotations

import math
import pathlib

import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2CoSimulation, fmi2Error, fmi2False, fmi2ModelExchange

from fmu_support import MessageLog

ERROR = fmi2Error


def error_messages(log: MessageLog) -> list[str]:
    return [r.message for r in log.records if r.status == ERROR and r.category == "logStatusError"]


def assert_error(call, log: MessageLog, *words: str):
    """`call` fails with fmi2Error and one error message contains every word."""
    log.clear()
    with pytest.raises(FMICallException) as e:
        call()
    assert e.value.status == ERROR
    messages = error_messages(log)
    assert any(all(w in m for w in words) for m in messages), f"no error message with {words}: {log.records}"


def simulation_still_works(impact, cli):
    """A fresh default simulation after the error gives the energy-balance rebound."""
    r = impact.simulate(start_values={"initial_velocity": 3.0}, stop_time=2e-7, output_interval=1e-8)
    ref = cli.analyze(impact.scene(), velocity=3.0)
    assert r["contact_state"][-1] == 0
    assert r["sphere_velocity"][-1] == pytest.approx(ref["rebound_velocity"], rel=1e-6)


@pytest.fixture
def log():
    return MessageLog()


@pytest.mark.parametrize("name", ["particle_radius", "surface_energy", "initial_velocity"])
@pytest.mark.parametrize("value", [math.nan, math.inf])
def test_non_finite_parameter_is_refused_by_set_real(impact, cli, log, name, value):
    fmu = impact.slave("nan", log)
    assert_error(lambda: fmu.setReal([impact.vr[name]], [value]), log, "fmi2SetReal", f"`{name}`", "not a finite number")
    # The bad value was not taken: the instance initializes and runs with the start value.
    impact.initialize(fmu, {"initial_velocity": 3.0})
    assert fmu.getReal([impact.vr[name]]) == [3.0 if name == "initial_velocity" else impact.start(name)]
    fmu.freeInstance()
    simulation_still_works(impact, cli)


def test_non_finite_input_is_refused(impact, contact, log):
    for unit in (impact, contact):
        fmu = unit.slave("input", log)
        unit.initialize(fmu)
        assert_error(lambda: fmu.setReal([unit.vr["wall_displacement"]], [math.nan]), log, "`wall_displacement`")
        fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-9)
        fmu.freeInstance()


def test_negative_radius_fails_initialization_naming_it(impact, cli, log):
    fmu = impact.slave("radius", log)
    fmu.setupExperiment(startTime=0.0)
    fmu.setReal([impact.vr["particle_radius"]], [-1e-6])  # stored; checked when the unit initializes
    fmu.enterInitializationMode()
    assert_error(fmu.exitInitializationMode, log, "fmi2ExitInitializationMode", "`particle_radius`", "-1e-6")
    # fmi2Reset returns to the start values; the same instance then runs.
    fmu.reset()
    impact.initialize(fmu, {"initial_velocity": 3.0})
    assert fmu.getReal([impact.vr["particle_radius"]]) == [impact.start("particle_radius")]
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=2e-7)
    assert fmu.getReal([impact.vr["sphere_velocity"]])[0] == pytest.approx(
        cli.analyze(impact.scene(), velocity=3.0)["rebound_velocity"], rel=1e-6
    )
    fmu.freeInstance()
    simulation_still_works(impact, cli)


def test_negative_radius_in_model_exchange_and_contact_element(impact, contact, log):
    for unit, make in ((impact, impact.model), (contact, contact.slave)):
        fmu = make("radius", log)
        fmu.setupExperiment(startTime=0.0)
        fmu.setReal([unit.vr["particle_radius"]], [-2e-6])
        fmu.enterInitializationMode()
        assert_error(fmu.exitInitializationMode, log, "`particle_radius`")
        fmu.freeInstance()


def test_unknown_contact_model_fails_initialization_naming_it(impact, cli, log):
    fmu = impact.slave("model", log)
    fmu.setupExperiment(startTime=0.0)
    fmu.setString([impact.vr["contact_model"]], ["bogus"])
    fmu.enterInitializationMode()
    assert_error(fmu.exitInitializationMode, log, "`contact_model`", "bogus")
    # The message lists what is allowed.
    assert all(law in error_messages(log)[0] for law in ("nan", "pasha_simplified", "thornton_ning", "walton_braun"))
    fmu.freeInstance()
    simulation_still_works(impact, cli)


def test_do_step_before_initialization(impact, cli, log):
    fmu = impact.slave("early", log)
    assert_error(lambda: fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-9), log, "fmi2DoStep")
    fmu.freeInstance()
    simulation_still_works(impact, cli)


@pytest.mark.parametrize("h", [-1e-9, 0.0])
def test_non_positive_step_size(impact, cli, log, h):
    fmu = impact.slave("step", log)
    impact.initialize(fmu, {"initial_velocity": 3.0})
    assert_error(lambda: fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=h), log, "communicationStepSize")
    fmu.freeInstance()
    simulation_still_works(impact, cli)


def test_do_step_from_the_wrong_time(impact, log):
    fmu = impact.slave("time", log)
    impact.initialize(fmu, {"initial_velocity": 3.0})
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-9)
    assert_error(lambda: fmu.doStep(currentCommunicationPoint=5e-9, communicationStepSize=1e-9), log, "currentCommunicationPoint")
    fmu.freeInstance()


def test_setting_an_output_or_unknown_reference(impact, log):
    fmu = impact.slave("refs", log)
    assert_error(lambda: fmu.setReal([impact.vr["force"]], [1.0]), log, "`force`")
    assert_error(lambda: fmu.setReal([99999], [1.0]), log, "99999")
    assert_error(lambda: fmu.setReal([impact.vr["contact_model"]], [1.0]), log, "`contact_model`")
    fmu.freeInstance()


def test_wrong_guid_fails_to_instantiate(impact, cli, log):
    wrong = "{00000000-0000-0000-0000-000000000000}"
    with pytest.raises(Exception, match="instantiate"):
        impact.slave("guid", log, guid=wrong)
    messages = error_messages(log)
    assert any("fmuGUID" in m and wrong in m for m in messages), log.records
    simulation_still_works(impact, cli)


@pytest.mark.parametrize("kind", [fmi2ModelExchange, fmi2CoSimulation])
def test_missing_resource_folder_fails_to_instantiate(impact, cli, log, tmp_path, kind):
    missing = pathlib.Path(tmp_path, "no", "resources")
    fmu = impact.model("probe") if kind == fmi2ModelExchange else impact.slave("probe")  # only for fmi2Instantiate
    component = fmu.fmi2Instantiate(
        b"resources", kind, impact.md.guid.encode(), missing.as_uri().encode(), log.callbacks, fmi2False, fmi2False
    )
    assert component is None
    messages = error_messages(log)
    assert any("fmuResourceLocation" in m and str(missing) in m for m in messages), log.records
    fmu.freeInstance()
    simulation_still_works(impact, cli)


def test_non_finite_time_in_model_exchange(impact, log):
    fmu = impact.model("me", log)
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    assert_error(lambda: fmu.setTime(math.nan), log, "fmi2SetTime")
    fmu.freeInstance()


def test_out_of_sequence_call_changes_nothing(impact, log):
    fmu = impact.slave("sequence", log)
    impact.initialize(fmu, {"initial_velocity": 3.0})
    assert_error(lambda: fmu.setupExperiment(startTime=0.0), log, "fmi2SetupExperiment", "must not be called in Step Complete")
    assert_error(fmu.enterInitializationMode, log, "fmi2EnterInitializationMode", "Step Complete")
    # Refused calls left the instance as it was: the impact runs on.
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=2e-7)
    assert fmu.getReal([impact.vr["sphere_velocity"]])[0] > 0
    fmu.freeInstance()


def test_fixed_parameter_after_initialization_is_refused(impact, log):
    fmu = impact.slave("fixed", log)
    impact.initialize(fmu)
    assert_error(lambda: fmu.setReal([impact.vr["particle_radius"]], [1e-6]), log, "`particle_radius`", "fixed")
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-9)
    fmu.freeInstance()


def test_failed_step_enters_the_error_state_and_a_saved_state_recovers(impact, log):
    """A step that cannot be computed (Verlet at 1e-12 of the Rayleigh step over 1 ms needs more than
    the 1e7 steps allowed) fails; the instance is in the Error state; a state saved before restores it."""
    fmu = impact.slave("recover", log)
    impact.initialize(fmu, {"initial_velocity": 3.0, "solver": "verlet", "rayleigh_fraction": 1e-12})
    saved = fmu.getFMUstate()
    assert_error(lambda: fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3), log, "fmi2DoStep", "Error state")
    assert_error(lambda: fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-9), log, "must not be called in Error")
    # Getters still answer in the Error state; the saved state brings the instance back.
    assert math.isfinite(fmu.getReal([impact.vr["sphere_velocity"]])[0])
    fmu.setFMUstate(saved)
    fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-14)  # 7e5 Verlet steps: allowed
    fmu.freeFMUstate(saved)
    fmu.freeInstance()
