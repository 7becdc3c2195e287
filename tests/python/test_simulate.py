"""Both units run under fmpy in Model Exchange (CVode) and Co-Simulation, and the two interfaces agree."""

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from fmu_support import wall_input

INTERFACES = ["CoSimulation", "ModelExchange"]


def all_finite(result):
    return all(np.all(np.isfinite(result[name])) for name in result.dtype.names)


@pytest.mark.parametrize("fmi_type", INTERFACES)
def test_particle_wall_impact_runs_its_default_experiment(impact, fmi_type):
    r = impact.simulate(fmi_type, start_values={"initial_velocity": 3.0})
    stop = impact.md.defaultExperiment.stopTime
    assert r["time"][-1] == pytest.approx(float(stop), rel=1e-12)
    assert all_finite(r)
    # The sphere starts at -initial_velocity, hits the wall (yields) and flies off.
    assert r["sphere_velocity"][0] == -3.0
    assert r["max_overlap"][-1] > 0
    assert 2 in set(r["contact_state"])
    assert r["contact_state"][-1] == 0 and r["sphere_velocity"][-1] > 0 and r["overlap"][-1] < 0


@pytest.mark.parametrize("fmi_type", INTERFACES)
def test_contact_element_runs_a_ramp(contact, fmi_type):
    signals = wall_input([0.0, 1.0], [-1e-8, 4e-8])
    r = contact.simulate(fmi_type, input=signals, stop_time=1.0, output_interval=2.0**-6)
    assert r["time"][-1] == 1.0
    assert all_finite(r)
    assert r["contact_state"][0] == 0 and r["force"][0] == 0.0
    assert r["contact_state"][-1] == 2 and r["force"][-1] > 0
    assert np.all(np.diff(r["max_overlap"]) >= 0)


def test_model_exchange_and_co_simulation_give_the_same_restitution(impact):
    v = 3.0
    cs = impact.simulate("CoSimulation", start_values={"initial_velocity": v}, stop_time=2e-7, output_interval=1e-9)
    me = impact.simulate(
        "ModelExchange", start_values={"initial_velocity": v}, stop_time=2e-7, output_interval=1e-9, relative_tolerance=1e-8
    )
    for r in (cs, me):
        assert r["contact_state"][-1] == 0 and r["sphere_velocity"][-1] > 0
    e_cs = cs["sphere_velocity"][-1] / v
    e_me = me["sphere_velocity"][-1] / v
    assert e_me == pytest.approx(e_cs, rel=1e-4)
    assert me["max_overlap"][-1] == pytest.approx(cs["max_overlap"][-1], rel=1e-4)
    assert me["plastic_overlap"][-1] == pytest.approx(cs["plastic_overlap"][-1], rel=1e-4)
    assert me["dissipated_energy"][-1] == pytest.approx(cs["dissipated_energy"][-1], rel=1e-3)


def test_contact_element_interfaces_agree_on_a_loading_cycle(contact):
    signals = wall_input([0.0, 1.0, 2.0], [-1e-8, 5e-8, -1e-8])
    runs = {t: contact.simulate(t, input=signals, stop_time=2.0, output_interval=2.0**-6) for t in INTERFACES}
    cs, me = runs["CoSimulation"], runs["ModelExchange"]
    # The law's history is exact in both; the work is a state that CVode integrates in ME (fmpy sets the
    # inputs only where it evaluates event indicators, so ME is good to a fraction of a percent here).
    assert me["max_overlap"][-1] == cs["max_overlap"][-1] == pytest.approx(5e-8, rel=1e-12)
    assert me["plastic_overlap"][-1] == pytest.approx(cs["plastic_overlap"][-1], rel=1e-12)
    assert me["pull_off_force"][-1] == pytest.approx(cs["pull_off_force"][-1], rel=1e-12)
    assert cs["dissipated_energy"][-1] > 0
    assert me["dissipated_energy"][-1] == pytest.approx(cs["dissipated_energy"][-1], rel=0.02)


def test_co_simulation_takes_variable_communication_steps(impact):
    # The wall rests (all inputs 0), but the input table has a time point every 5 ns, so fmpy, the unit
    # declaring canHandleVariableCommunicationStepSize, steps to 4, 5, 8, 10, 12, 15, ... ns.
    knots = np.arange(0.0, 3e-7 + 1e-12, 5e-9)
    signals = wall_input(knots, np.zeros_like(knots))
    # Below the sticking velocity (1.86 m/s) the sphere stays on the wall, above it it leaves. A rounding
    # leftover of one step used to become the next step's size and fail the step after it.
    for v, leaves in ((0.5, False), (3.0, True)):
        r = impact.simulate(start_values={"initial_velocity": v}, input=signals, stop_time=3e-7, output_interval=4e-9)
        assert r["time"][-1] == pytest.approx(3e-7)
        assert (r["contact_state"][-1] == 0 and r["sphere_velocity"][-1] > 0) == leaves
