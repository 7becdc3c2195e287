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


@pytest.mark.xfail(
    strict=False,
    raises=AssertionError,
    reason="FMU bug (ME): when wall_velocity is not exactly d(wall_displacement)/dt (fmpy interpolates each input "
    "linearly), events at a turning point repeat every ~2e-16 s and the simulation stalls (Zeno): the rate "
    "indicator (from wall_velocity) says unloading while the overlap (from wall_displacement) still grows",
)
def test_model_exchange_tolerates_slightly_inconsistent_wall_inputs(impact):
    # A wall vibrating at 5 MHz, 20 nm, sampled 200 times a period: position and velocity each exact at
    # the samples and interpolated linearly in between, so they disagree by up to ~1 % of the speed.
    amplitude, omega = 2e-8, 2 * np.pi * 5e6
    stop = 2e-6
    t = np.linspace(0.0, stop, 2001)
    signals = np.zeros(t.size, dtype=[("time", np.float64), ("wall_displacement", np.float64), ("wall_velocity", np.float64)])
    signals["time"] = t
    signals["wall_displacement"] = amplitude * np.sin(omega * t)
    signals["wall_velocity"] = amplitude * omega * np.cos(omega * t)
    steps = [0]

    def budget(time, recorder):
        steps[0] += 1
        return steps[0] < 10_000  # the same wall given consistently (wall_input) takes ~2 000 steps

    start = {"gravity": 9.81, "initial_velocity": 0.5, "initial_gap": 2 * amplitude}
    r = impact.simulate("ModelExchange", start_values=start, input=signals, stop_time=stop, output_interval=stop / 500, step_finished=budget)
    assert r["time"][-1] == pytest.approx(stop), f"stalled at t = {r['time'][-1]:e} s after {steps[0]} steps"
