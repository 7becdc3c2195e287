"""Saved FMU states through fmpy's low-level API: fmi2GetFMUstate / fmi2SetFMUstate roll back exactly,
serialization round-trips, and a state serialized in one process continues bit-for-bit in another.
Outputs are compared as float.hex strings, so "identical" means bitwise."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2Error

from fmu_support import MessageLog, initialized_model, read_outputs, record_steps, triangle_wall

HERE = Path(__file__).resolve().parent
H = 2.0**-31  # ~0.47 ns: communication steps exact in binary


def impact_case(impact):
    return impact, {"initial_velocity": 3.0}, None


def contact_case(contact):
    # Loading beyond yield and back past pull-off, three times.
    return contact, {}, triangle_wall(peak=4e-8, period=100 * H, low=-1e-8)


@pytest.fixture(params=["impact", "contact"])
def case(request):
    unit = request.getfixturevalue(request.param)
    return (impact_case if request.param == "impact" else contact_case)(unit)


def test_get_and_set_state_rolls_back_exactly(case):
    unit, start, wall = case
    fmu = unit.slave("rollback")
    unit.initialize(fmu, start)
    record_steps(unit, fmu, 0.0, H, 40, wall)  # into the contact (plastic loading)
    t1 = 40 * H
    at_t1 = read_outputs(unit, fmu)
    state = fmu.getFMUstate()
    first = record_steps(unit, fmu, t1, H, 200, wall)
    assert first[-1] != at_t1
    for _ in range(2):  # a state stays valid after it has been set
        fmu.setFMUstate(state)
        assert read_outputs(unit, fmu) == at_t1
        assert record_steps(unit, fmu, t1, H, 200, wall) == first
    fmu.freeFMUstate(state)
    fmu.terminate()
    fmu.freeInstance()


def test_state_restores_history_not_only_positions(impact):
    # A state taken before the contact, set after it: max_overlap and plastic_overlap go back too.
    fmu = impact.slave("history")
    impact.initialize(fmu, {"initial_velocity": 3.0})
    vr = impact.vr
    before = fmu.getFMUstate()
    initial = fmu.getReal([vr["max_overlap"], vr["plastic_overlap"], vr["pull_off_force"]])
    record_steps(impact, fmu, 0.0, H, 300)
    after = fmu.getReal([vr["max_overlap"], vr["plastic_overlap"], vr["pull_off_force"]])
    assert after[0] > 0 and after[1] > initial[1] and after[2] > initial[2]
    fmu.setFMUstate(before)
    assert fmu.getReal([vr["max_overlap"], vr["plastic_overlap"], vr["pull_off_force"]]) == initial
    assert record_steps(impact, fmu, 0.0, H, 300)[-1] == read_outputs(impact, fmu)
    assert fmu.getReal([vr["max_overlap"], vr["plastic_overlap"], vr["pull_off_force"]]) == after
    fmu.freeFMUstate(before)
    fmu.freeInstance()


def test_serialize_and_deserialize_round_trip(case):
    unit, start, wall = case
    fmu = unit.slave("serialize")
    unit.initialize(fmu, start)
    record_steps(unit, fmu, 0.0, H, 40, wall)
    state = fmu.getFMUstate()
    data = fmu.serializeFMUstate(state)
    fmu.freeFMUstate(state)
    assert isinstance(data, bytes) and len(data) > 0
    first = record_steps(unit, fmu, 40 * H, H, 200, wall)
    restored = fmu.deSerializeFMUstate(data)
    assert fmu.serializeFMUstate(restored) == data
    fmu.setFMUstate(restored)
    fmu.freeFMUstate(restored)
    assert record_steps(unit, fmu, 40 * H, H, 200, wall) == first
    fmu.freeInstance()


def test_serialized_state_restores_in_a_fresh_instance(case):
    unit, start, wall = case
    a = unit.slave("a")
    unit.initialize(a, start)
    record_steps(unit, a, 0.0, H, 40, wall)
    state = a.getFMUstate()
    data = a.serializeFMUstate(state)
    a.freeFMUstate(state)
    expected = record_steps(unit, a, 40 * H, H, 200, wall)
    a.freeInstance()
    # Only instantiated: no parameters, no initialization; the state carries them.
    b = unit.slave("b")
    restored = b.deSerializeFMUstate(data)
    b.setFMUstate(restored)
    b.freeFMUstate(restored)
    assert record_steps(unit, b, 40 * H, H, 200, wall) == expected
    b.freeInstance()


def test_a_state_serialized_in_one_process_continues_bit_for_bit_in_another(impact, tmp_path):
    def worker(mode):
        run = subprocess.run(
            [sys.executable, str(HERE / "state_worker.py"), mode, str(impact.unzipdir), str(tmp_path)],
            capture_output=True,
            text=True,
            timeout=120,
            cwd=HERE,
        )
        assert run.returncode == 0, f"{mode} process failed ({run.returncode}):\n{run.stdout}\n{run.stderr}"

    worker("save")
    assert (tmp_path / "state.bin").stat().st_size > 0
    worker("restore")
    expected = json.loads((tmp_path / "expected.json").read_text())
    got = json.loads((tmp_path / "got.json").read_text())
    assert len(got) == len(expected) > 0
    assert got == expected
    # The run went through the contact: it is no trivial free flight.
    states = {row[2] for row in expected}
    assert {"0", "2"} <= states


def test_corrupt_or_foreign_state_is_refused_with_a_message(impact, contact):
    log = MessageLog()
    fmu = impact.slave("victim", log)
    impact.initialize(fmu, {"initial_velocity": 3.0})
    state = fmu.getFMUstate()
    data = bytearray(fmu.serializeFMUstate(state))
    fmu.freeFMUstate(state)
    data[len(data) // 2] ^= 0xFF
    with pytest.raises(FMICallException) as e:
        fmu.deSerializeFMUstate(bytes(data))
    assert e.value.status == fmi2Error
    assert any("checksum" in m for m in log.messages(fmi2Error)), log.messages()

    other = contact.slave("other")
    contact.initialize(other)
    s = other.getFMUstate()
    foreign = other.serializeFMUstate(s)
    other.freeFMUstate(s)
    other.freeInstance()
    log.clear()
    with pytest.raises(FMICallException):
        fmu.deSerializeFMUstate(foreign)
    assert any("ContactElement" in m for m in log.messages(fmi2Error)), log.messages()
    # The instance is unharmed and still steps.
    assert len(record_steps(impact, fmu, 0.0, H, 10)) == 10
    fmu.freeInstance()


# ---------------------------------------------------------------------------------------------------
# Model Exchange


def test_model_exchange_state_rolls_back_and_serializes(impact):
    h = 2.0**-34  # ~0.06 ns
    fmu, driver = initialized_model(impact, {"initial_velocity": 3.0}, "me")
    driver.h = h
    driver.run(0.0, 300)  # ~18 ns: in contact, beyond yield
    t1 = 300 * h
    assert int(read_outputs(impact, fmu)[2]) != 0
    state = fmu.getFMUstate()
    data = fmu.serializeFMUstate(state)
    first = driver.run(t1, 1500)  # through unloading and detachment
    assert {row[2] for row in first} >= {"1", "0"}
    fmu.setFMUstate(state)
    fmu.freeFMUstate(state)
    assert driver.run(t1, 1500) == first
    restored = fmu.deSerializeFMUstate(data)
    fmu.setFMUstate(restored)
    fmu.freeFMUstate(restored)
    assert driver.run(t1, 1500) == first
    fmu.terminate()
    fmu.freeInstance()
