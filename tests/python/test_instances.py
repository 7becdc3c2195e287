"""Several instances in one process: each keeps its own parameters, state and log, whatever the others do."""

import pytest
from fmpy.fmi1 import FMICallException

from fmu_support import MessageLog, initialized_model, record_steps, triangle_wall

H = 2.0**-31  # ~0.47 ns, exact in binary
N = 300

A = {"initial_velocity": 3.0}
B = {"initial_velocity": 5.0, "particle_radius": 1.72e-6, "contact_model": "thornton_ning", "restitution_coefficient": 0.8}


def alone(unit, start, n=N, wall=None):
    fmu = unit.slave("alone")
    unit.initialize(fmu, start)
    rows = record_steps(unit, fmu, 0.0, H, n, wall)
    fmu.terminate()
    fmu.freeInstance()
    return rows


def test_two_instances_with_different_parameters_stepped_interleaved(impact):
    ref_a, ref_b = alone(impact, A), alone(impact, B)
    assert ref_a != ref_b
    a, b = impact.slave("a"), impact.slave("b")
    impact.initialize(a, A)
    impact.initialize(b, B)
    got_a, got_b = [], []
    for i in range(N):
        got_a += record_steps(impact, a, i * H, H, 1)
        got_b += record_steps(impact, b, i * H, H, 1)
    assert got_a == ref_a
    assert got_b == ref_b
    for fmu in (a, b):
        fmu.terminate()
        fmu.freeInstance()


def test_both_units_and_both_interfaces_interleaved(impact, contact):
    wall = triangle_wall(peak=4e-8, period=100 * H, low=-1e-8)
    ref_impact, ref_contact = alone(impact, B), alone(contact, {}, wall=wall)
    me_alone, driver = initialized_model(impact, A, "me-alone")
    driver.h = H / 8
    ref_me = driver.run(0.0, N)
    me_alone.freeInstance()

    cs_impact, cs_contact = impact.slave("cs-impact"), contact.slave("cs-contact")
    impact.initialize(cs_impact, B)
    contact.initialize(cs_contact)
    me, driver = initialized_model(impact, A, "me")
    driver.h = H / 8
    got = ([], [], [])
    for i in range(N):
        got[0].extend(record_steps(impact, cs_impact, i * H, H, 1))
        got[1].extend(driver.run(i * H / 8, 1))
        got[2].extend(record_steps(contact, cs_contact, i * H, H, 1, wall))
    assert got[0] == ref_impact
    assert got[1] == ref_me
    assert got[2] == ref_contact
    for fmu in (cs_impact, cs_contact, me):
        fmu.freeInstance()


def test_an_error_in_one_instance_leaves_the_other_alone(impact):
    ref = alone(impact, A)
    log_a, log_b = MessageLog(), MessageLog()
    a, b = impact.slave("good", log_a), impact.slave("bad", log_b)
    impact.initialize(a, A)
    got = record_steps(impact, a, 0.0, H, N // 2)
    with pytest.raises(FMICallException):
        b.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)  # not initialized
    got += record_steps(impact, a, (N // 2) * H, H, N - N // 2)
    assert got == ref
    assert log_a.messages(3) == []
    assert [r.instance for r in log_b.records] == ["bad"] and "fmi2DoStep" in log_b.records[0].message
    for fmu in (a, b):
        fmu.freeInstance()
