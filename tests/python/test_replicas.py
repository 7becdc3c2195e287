"""BallIndentation's `replicas`: the same test on several independently prepared beds, side by side. The
outputs are the means over the beds and `plateau_hardness_standard_error_over_beds` their spread; each
bed steps as it would alone, so the replicas' outputs are the mean of the single runs."""

import json
import subprocess

import numpy as np
import pytest

from conftest import REPO
from fmu_support import MessageLog

DONE = 2
# The stand-in's test, short: to h/r 0.2 and out again.
SHORT = {"stop_time": 0.02}


@pytest.fixture(scope="module")
def second_bed(cli, quick_bed, tmp_path_factory):
    """The stand-in bed prepared again with fill seed 2: another bed of the same powder."""
    scene = json.loads((REPO / "scenes" / "bed_indentation_quick.json").read_text())
    scene["seed"] = 2
    folder = tmp_path_factory.mktemp("replica")
    (folder / "quick_seed2.json").write_text(json.dumps(scene))
    bed = folder / "quick_seed2.pfbed"
    run = subprocess.run([str(cli.path), "bed", "prepare", str(folder / "quick_seed2.json"), "-o", str(bed)], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    return str(bed)


@pytest.fixture(scope="module")
def single_runs(indentation, quick_bed, second_bed):
    """Each bed alone, on two threads (a run is the same to the bit for a given thread count)."""
    return [indentation.simulate(start_values={"bed_file": b, "threads": 2}, **SHORT) for b in (quick_bed["bed_file"], second_bed)]


def test_the_replicas_outputs_are_the_means_of_the_single_runs(indentation, quick_bed, second_bed, single_runs):
    a, b = single_runs
    assert a["plateau_hardness"][-1] != b["plateau_hardness"][-1], "two beds, two readings"
    both = indentation.simulate(start_values={"bed_file": f"{quick_bed['bed_file']};{second_bed}", "replicas": 2, "threads": 2}, **SHORT)
    assert both["test_state"][-1] == DONE
    for name in ("indenter_force", "penetration_depth", "hardness", "hydrostatic_stress", "kinetic_energy", "contact_depth", "force_at_turn", "plateau_hardness"):
        assert np.allclose(both[name], 0.5 * (a[name] + b[name]), rtol=1e-12, atol=0), name
    # The done state waits for the slower bed.
    assert np.array_equal(both["test_state"], np.minimum(a["test_state"], b["test_state"]))
    assert np.array_equal(both["plateau_samples"], a["plateau_samples"] + b["plateau_samples"])
    # The runs' own errors combine as independent; the spread of two beds gives |a - b| / 2.
    se = np.sqrt(a["plateau_hardness_standard_error"] ** 2 + b["plateau_hardness_standard_error"] ** 2) / 2
    assert np.allclose(both["plateau_hardness_standard_error"], se, rtol=1e-12, atol=0)
    spread = np.abs(a["plateau_hardness"] - b["plateau_hardness"]) / 2
    assert np.allclose(both["plateau_hardness_standard_error_over_beds"], spread, rtol=1e-9, atol=1e-9)
    assert both["plateau_hardness_standard_error_over_beds"][-1] > 0
    # One bed has no spread to measure.
    assert np.all(a["plateau_hardness_standard_error_over_beds"] == 0)


def test_a_saved_state_of_replicas_continues_bit_for_bit(indentation, quick_bed, second_bed):
    fmu = indentation.slave("replicas-saved")
    indentation.initialize(fmu, {"bed_file": f"{quick_bed['bed_file']};{second_bed}", "replicas": 2, "threads": 2})
    names = ["indenter_force", "plateau_hardness", "plateau_hardness_standard_error_over_beds", "kinetic_energy"]
    vrs = [indentation.vr[n] for n in names]
    t, h = 0.0, 1e-3
    for _ in range(6):
        fmu.doStep(t, h)
        t += h
    serialized = fmu.serializeFMUstate(fmu.getFMUstate())
    ahead = []
    for k in range(6):
        fmu.doStep(t + k * h, h)
        ahead.append(fmu.getReal(vrs))
    fmu.setFMUstate(fmu.deSerializeFMUstate(serialized))
    again = []
    for k in range(6):
        fmu.doStep(t + k * h, h)
        again.append(fmu.getReal(vrs))
    assert again == ahead
    fmu.terminate()
    fmu.freeInstance()


def _refused(unit, start_values):
    log = MessageLog()
    fmu = unit.slave("bad-replicas", log)
    fmu.setupExperiment(startTime=0.0)
    unit.set_start_values(fmu, {**unit.defaults, **start_values})
    fmu.enterInitializationMode()
    with pytest.raises(Exception):
        fmu.exitInitializationMode()
    fmu.freeInstance()
    return log.messages()


def test_replicas_the_beds_cannot_give_are_refused_by_name(indentation, shipped_indentation, quick_bed):
    messages = _refused(indentation, {"replicas": 2})
    assert any("`replicas` = 2" in m and "lists 1 bed" in m for m in messages), messages
    messages = _refused(indentation, {"replicas": 0})
    assert any("`replicas` = 0" in m and "[1, 64]" in m for m in messages), messages
    messages = _refused(shipped_indentation, {"replicas": 4})
    assert any("`replicas` = 4" in m and "allowed [1, 3]" in m for m in messages), messages
    messages = _refused(shipped_indentation, {"replicas": 2, "fidelity": "full"})
    assert any("`replicas` = 2" in m and "allowed [1, 1]" in m for m in messages), messages


def test_the_fmu_ships_three_quarter_beds(shipped_indentation):
    """replicas = 3 on the FMU's own quarter beds: three different beds of the shipped scene load and step (the whole test is docs/indentation.md's, too long for the suite)."""
    log = MessageLog()
    from fmpy.fmi2 import FMU2Slave

    u = shipped_indentation
    fmu = FMU2Slave(guid=u.md.guid, unzipDirectory=u.unzipdir, modelIdentifier="BallIndentation", instanceName="three")
    fmu.instantiate(callbacks=log.callbacks, loggingOn=True)
    u.initialize(fmu, {"replicas": 3, "threads": 2})
    fmu.doStep(0.0, 1e-3)
    depth, force = fmu.getReal([u.vr["penetration_depth"], u.vr["indenter_force"]])
    fmu.terminate()
    fmu.freeInstance()
    beds = [r.message for r in log.records if r.category == "logEvents" and r.message.startswith("replica ")]
    assert len(beds) == 3, beds
    assert [m.split(":")[0] for m in beds] == ["replica 1 of 3", "replica 2 of 3", "replica 3 of 3"]
    assert all("7250 spheres" in m and "each on 2 engine thread(s)" in m for m in beds), beds
    touches = {m.split("first touch at z = ")[1].split(" ")[0] for m in beds}
    assert len(touches) == 3, f"three different beds: {touches}"
    assert depth > 0 and force > 0
