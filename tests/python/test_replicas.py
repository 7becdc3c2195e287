"""BallIndentation's and UnconfinedCompression's `replicas`: the same test on several independently
prepared beds, side by side. The outputs are the means over the beds and
`plateau_hardness_standard_error_over_beds` (`unconfined_yield_strength_standard_error_over_specimens`)
their spread; each bed steps as it would alone, so the replicas' outputs are the mean of the single runs."""

import json
from pathlib import Path
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


def _continues_bit_for_bit(fmu, vrs, h: float, before: int, after: int, loaded=None):
    """Steps `before` steps of `h`, saves the state (serialized), steps `after` more, restores and steps them
    again: the outputs `vrs` are the same to the bit. `loaded(outputs)` checks the state saved is mid-test."""
    t = 0.0
    for _ in range(before):
        fmu.doStep(t, h)
        t += h
    if loaded is not None:
        loaded(fmu.getReal(vrs))
    serialized = fmu.serializeFMUstate(fmu.getFMUstate())
    runs = []
    for restore in (False, True):
        if restore:
            fmu.setFMUstate(fmu.deSerializeFMUstate(serialized))
        outputs = []
        for k in range(after):
            fmu.doStep(t + k * h, h)
            outputs.append(fmu.getReal(vrs))
        runs.append(outputs)
    assert runs[1] == runs[0]
    fmu.terminate()
    fmu.freeInstance()


def test_a_saved_state_of_replicas_continues_bit_for_bit(indentation, quick_bed, second_bed):
    fmu = indentation.slave("replicas-saved")
    indentation.initialize(fmu, {"bed_file": f"{quick_bed['bed_file']};{second_bed}", "replicas": 2, "threads": 2})
    names = ["indenter_force", "plateau_hardness", "plateau_hardness_standard_error_over_beds", "kinetic_energy"]
    _continues_bit_for_bit(fmu, [indentation.vr[n] for n in names], 1e-3, 6, 6)


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
    # A replica must be a fill of the first bed's scene: the shipped quarter is another powder and die.
    quarter = Path(shipped_indentation.unzipdir) / "resources" / "bed_quarter.pfbed"
    messages = _refused(indentation, {"replicas": 2, "bed_file": f"{quick_bed['bed_file']};{quarter}"})
    assert any("replica 2 of 2" in m and "another scene than replica 1" in m and "differs" in m for m in messages), messages


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


# UnconfinedCompression on the stand-in bed and its second fill (both fail at about 2 % strain).


@pytest.fixture(scope="module")
def single_compressions(compression, quick_bed, second_bed):
    """Each specimen alone (one thread, the `compression` fixture's)."""
    return [compression.simulate(start_values={"bed_file": b}) for b in (quick_bed["bed_file"], second_bed)]


def test_the_compression_replicas_outputs_are_the_means_of_the_single_runs(compression, quick_bed, second_bed, single_compressions):
    a, b = single_compressions
    assert a["unconfined_yield_strength"][-1] != b["unconfined_yield_strength"][-1], "two specimens, two readings"
    both = compression.simulate(start_values={"bed_file": f"{quick_bed['bed_file']};{second_bed}", "replicas": 2})
    for name in ("axial_stress", "axial_strain", "kinetic_energy", "solid_fraction", "specimen_height", "consolidation_stress", "self_weight_stress"):
        assert np.allclose(both[name], 0.5 * (a[name] + b[name]), rtol=1e-12, atol=0), name
    # Done when both are; sigma_c, its strain and failure once both have a window.
    assert np.array_equal(both["test_state"], np.minimum(a["test_state"], b["test_state"]))
    ready = (a["unconfined_yield_strength"] > 0) & (b["unconfined_yield_strength"] > 0)
    assert ready.any() and np.all(both["unconfined_yield_strength"][~ready] == 0)
    mean = 0.5 * (a["unconfined_yield_strength"] + b["unconfined_yield_strength"])
    assert np.allclose(both["unconfined_yield_strength"][ready], mean[ready], rtol=1e-12, atol=0)
    assert np.allclose(both["strain_at_failure"][ready], 0.5 * (a["strain_at_failure"] + b["strain_at_failure"])[ready], rtol=1e-12, atol=0)
    assert np.array_equal(both["failed"][ready], (a["failed"] & b["failed"])[ready])
    assert both["failed"][-1]
    # The specimens' own errors combine as independent; the spread of two gives |a - b| / 2.
    se = np.sqrt(a["unconfined_yield_strength_standard_error"] ** 2 + b["unconfined_yield_strength_standard_error"] ** 2) / 2
    assert np.allclose(both["unconfined_yield_strength_standard_error"][ready], se[ready], rtol=1e-12, atol=0)
    spread = np.abs(a["unconfined_yield_strength"] - b["unconfined_yield_strength"]) / 2
    assert np.allclose(both["unconfined_yield_strength_standard_error_over_specimens"][ready], spread[ready], rtol=1e-9, atol=1e-9)
    assert both["unconfined_yield_strength_standard_error_over_specimens"][-1] > both["unconfined_yield_strength_standard_error"][-1] > 0
    ff = 0.5 * (a["consolidation_stress"][-1] + b["consolidation_stress"][-1]) / both["unconfined_yield_strength"][-1]
    assert both["flow_function"][-1] == pytest.approx(ff, rel=1e-12)
    # One specimen has no spread to measure.
    assert np.all(a["unconfined_yield_strength_standard_error_over_specimens"] == 0)


def test_a_saved_state_of_compression_replicas_continues_bit_for_bit(compression, quick_bed, second_bed):
    fmu = compression.slave("replicas-saved")
    compression.initialize(fmu, {"bed_file": f"{quick_bed['bed_file']};{second_bed}", "replicas": 2})
    names = ["axial_stress", "axial_strain", "unconfined_yield_strength", "unconfined_yield_strength_standard_error_over_specimens", "kinetic_energy"]

    def loaded(outputs):
        assert outputs[1] > 0, "saved while the platen loads the specimens"

    _continues_bit_for_bit(fmu, [compression.vr[n] for n in names], 5e-4, 12, 10, loaded)


def test_compression_replicas_the_specimens_cannot_give_are_refused_by_name(compression, shipped_compression):
    messages = _refused(compression, {"replicas": 2})
    assert any("`replicas` = 2" in m and "lists 1 bed" in m for m in messages), messages
    messages = _refused(compression, {"replicas": 65})
    assert any("`replicas` = 65" in m and "[1, 64]" in m for m in messages), messages
    messages = _refused(shipped_compression, {"replicas": 4})
    assert any("`replicas` = 4" in m and "allowed [1, 3]" in m for m in messages), messages
    specimen = Path(shipped_compression.unzipdir) / "resources" / "specimen.pfbed"
    messages = _refused(compression, {"replicas": 2, "bed_file": f"{compression.defaults['bed_file']};{specimen}"})
    assert any("replica 2 of 2" in m and "another scene than replica 1" in m and "differs" in m for m in messages), messages


def test_the_fmu_ships_three_specimens(shipped_compression, cli):
    """replicas = 3 on the FMU's own specimens: the shipped specimen's scene in three fills load, each
    as `powderfmu bed info` describes it (the whole test is docs/units/UnconfinedCompression.md's)."""
    log = MessageLog()
    from fmpy.fmi2 import FMU2Slave

    u = shipped_compression
    fmu = FMU2Slave(guid=u.md.guid, unzipDirectory=u.unzipdir, modelIdentifier="UnconfinedCompression", instanceName="three")
    fmu.instantiate(callbacks=log.callbacks, loggingOn=True)
    u.initialize(fmu, {"replicas": 3, "threads": 2})
    fmu.doStep(0.0, 1e-3)
    fraction, sigma_1 = fmu.getReal([u.vr["solid_fraction"], u.vr["consolidation_stress"]])
    fmu.terminate()
    fmu.freeInstance()
    specimens = [r.message for r in log.records if r.category == "logEvents" and r.message.startswith("replica ")]
    assert [m.split(":")[0] for m in specimens] == ["replica 1 of 3", "replica 2 of 3", "replica 3 of 3"], specimens
    assert all("4000 spheres" in m for m in specimens), specimens
    fractions = []
    for name in ("specimen.pfbed", "specimen_2.pfbed", "specimen_3.pfbed"):
        info = subprocess.run([str(cli.path), "bed", "info", str(Path(u.unzipdir) / "resources" / name)], capture_output=True, text=True, check=True).stdout
        fractions.append(float(next(line for line in info.splitlines() if line.startswith("solid fraction")).split()[-1]))
    assert len(set(fractions)) == 3, f"three different fills: {fractions}"
    assert fraction == pytest.approx(np.mean(fractions), abs=1e-4) and sigma_1 == 10e3
