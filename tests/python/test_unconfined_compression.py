"""UnconfinedCompression through fmpy: the uniaxial tester of 004 Sec. 2.1 on a prepared bed. The shipped
specimen runs once with no arguments (about two minutes on two cores); everything else runs on the suite's
stand-in bed (`quick_bed`, 800 soft cohesive spheres, well under a second per test), where the unit is
held to the command-line tool's `bed compress` on the same bed and to sigma_c's definition recomputed here
from that tool's curve."""

from __future__ import annotations

import subprocess
from pathlib import Path

import fmpy
import numpy as np
import pytest
from fmpy.validation import validate_fmu

from fmu_support import MessageLog, refused

LOADING, DONE = 0, 1


@pytest.fixture(scope="module")
def quick_run(compression):
    return compression.simulate()


def _cli_curve(cli, bed: str, tmp_path: Path, *extra: str) -> tuple[np.ndarray, str]:
    out = tmp_path / "curve.csv"
    run = subprocess.run(
        [str(cli.path), "bed", "compress", bed, "--threads", "1", "--out", str(out), *extra], capture_output=True, text=True, timeout=300
    )
    assert run.returncode == 0, run.stderr
    return np.genfromtxt(out, delimiter=",", names=True), run.stderr + run.stdout


def _largest_window_mean(curve: np.ndarray, window: float, strain_rate: float, reading_start: float) -> tuple[float, float]:
    """sigma_c as docs/units/UnconfinedCompression.md defines it, from a `bed compress` curve: the largest
    mean of the stress over `window` strain (its sample count from the samples' time spacing), over the
    samples after the platen's first contact from `reading_start` on; and the strain at that window's middle."""
    w = max(1, round(window / (strain_rate * (curve["time_s"][1] - curve["time_s"][0]))))
    loaded = curve[np.argmax((curve["strain"] > 0) & (curve["strain"] >= reading_start)) :]
    means = np.convolve(loaded["stress_Pa"], np.ones(w) / w, mode="valid")
    i = int(np.argmax(means))
    return float(means[i]), float(loaded["strain"][i + w // 2])


def test_both_versions_validate_and_offer_co_simulation_only(compression_fmu_path):
    for path in (compression_fmu_path, compression_fmu_path.parent / "fmi3" / compression_fmu_path.name):
        assert validate_fmu(str(path)) == [], path
        md = fmpy.read_model_description(str(path))
        assert md.modelExchange is None and md.coSimulation.canGetAndSetFMUstate


def test_the_default_specimen_runs_with_no_arguments(compression_fmu_path, cli):
    """The shipped specimen (004 Ch. 6's material consolidated to 10 kPa) as a host runs it: no arguments."""
    r = fmpy.simulate_fmu(str(compression_fmu_path))
    last = r[-1]
    assert last["test_state"] == DONE
    assert last["failed"] or last["axial_strain"] >= 0.1, "the test ends by failure or at max_strain"
    sigma_c, error = last["unconfined_yield_strength"], last["unconfined_yield_strength_standard_error"]
    # A cohesive specimen stands under its own weight and is weaker than its consolidation (ff_c > 1).
    assert last["self_weight_stress"] < sigma_c < last["consolidation_stress"]
    assert 0 < error < 0.05 * sigma_c
    assert last["flow_function"] == pytest.approx(last["consolidation_stress"] / sigma_c, rel=1e-12)
    # sigma_c is the largest window mean so far: it never falls.
    assert np.all(np.diff(r["unconfined_yield_strength"]) >= 0)
    # The specimen is the shipped bed as `powderfmu bed info` describes it.
    bed = str(Path(fmpy.extract(str(compression_fmu_path))) / "resources" / "specimen.pfbed")
    info = subprocess.run([str(cli.path), "bed", "info", bed], capture_output=True, text=True, check=True).stdout
    fraction = float(next(line for line in info.splitlines() if line.startswith("solid fraction")).split()[-1])
    assert last["solid_fraction"] == pytest.approx(fraction, abs=1e-4)


def test_the_unit_reads_what_the_command_line_reads_on_the_same_bed(compression, quick_run, cli, tmp_path):
    """The FMU and `bed compress` step the same engine to the same curve: sigma_c to the curve's printed
    digits, recomputed here from the tool's samples by the definition; the stand-in fails before max_strain."""
    last = quick_run[-1]
    window, start = compression.start("window"), compression.start("reading_start")
    curve, text = _cli_curve(cli, compression.defaults["bed_file"], tmp_path, "--window", repr(window), "--reading-start", repr(start))
    sigma_c, at = _largest_window_mean(curve, compression.start("window"), compression.start("strain_rate"), compression.start("reading_start"))
    assert last["unconfined_yield_strength"] == pytest.approx(sigma_c, rel=1e-6)
    assert last["strain_at_failure"] == pytest.approx(at, rel=1e-6)
    assert last["failed"] and "failed" in text
    assert last["test_state"] == DONE and last["axial_strain"] == pytest.approx(curve["strain"][-1], rel=1e-6)
    # Before the platen touches, no stress and no strain.
    first = quick_run[1]
    assert first["axial_stress"] == 0 and first["axial_strain"] == 0 and first["test_state"] == LOADING


def test_the_communication_step_changes_nothing(compression, quick_run):
    fine = compression.simulate(output_interval=3.7e-4)
    for name in ("unconfined_yield_strength", "unconfined_yield_strength_standard_error", "strain_at_failure", "axial_strain"):
        assert fine[-1][name] == quick_run[-1][name], name


def _outputs(compression, fmu):
    names = ["axial_stress", "axial_strain", "unconfined_yield_strength", "kinetic_energy"]
    return fmu.getReal([compression.vr[n] for n in names])


@pytest.mark.parametrize("threads", [1, 2])
def test_a_saved_state_continues_bit_for_bit(compression, threads):
    fmu = compression.slave("saved")
    compression.initialize(fmu, {"threads": threads})
    t, h = 0.0, 5e-4
    for _ in range(12):
        fmu.doStep(t, h)
        t += h
    assert _outputs(compression, fmu)[1] > 0, "saved while the platen loads the specimen"
    state = fmu.getFMUstate()
    serialized = fmu.serializeFMUstate(state)
    ahead = []
    for k in range(10):
        fmu.doStep(t + k * h, h)
        ahead.append(_outputs(compression, fmu))
    for restore in ("state", "serialized"):
        fmu.setFMUstate(state if restore == "state" else fmu.deSerializeFMUstate(serialized))
        again = []
        for k in range(10):
            fmu.doStep(t + k * h, h)
            again.append(_outputs(compression, fmu))
        assert again == ahead, restore
    fmu.freeFMUstate(state)
    fmu.terminate()
    fmu.freeInstance()


def test_bad_input_is_refused_at_initialization_by_name_and_the_host_survives(compression, tmp_path):
    refused(compression, {"strain_rate": 2e3}, "strain_rate")
    refused(compression, {"max_strain": 0.95}, "max_strain")
    refused(compression, {"window": 0.5}, "window")
    # The shipped default's 0.05 % holds 2 samples at the stand-in's step: refused, saying why.
    messages = refused(compression, {"window": 0.0005}, "window")
    assert any("at least 8 samples" in m for m in messages), messages
    refused(compression, {"reading_start": 0.099}, "reading_start")
    refused(compression, {"free_time": 20.0}, "free_time")
    refused(compression, {"threads": 0}, "threads")
    refused(compression, {"time_step": 1e-3}, "time_step")
    refused(compression, {"bed_file": str(tmp_path / "missing.pfbed")}, "bed_file")
    bed = Path(compression.defaults["bed_file"])
    truncated = tmp_path / "truncated.pfbed"
    truncated.write_bytes(bed.read_bytes()[: bed.stat().st_size // 2])
    refused(compression, {"bed_file": str(truncated)}, "bed_file")
    # After all that, a good instance still runs.
    fmu = compression.slave("good")
    compression.initialize(fmu)
    for k in range(10):
        fmu.doStep(k * 1e-3, 1e-3)
    assert _outputs(compression, fmu)[1] > 0
    fmu.terminate()
    fmu.freeInstance()


def test_the_test_reports_its_progress_and_its_end_through_the_logger(compression):
    log = MessageLog()
    fmu = compression.slave("progress", log)
    fmu.setDebugLogging(True, ["logEvents"])
    compression.initialize(fmu)
    t = 0.0
    while t < compression.experiment["stop_time"]:
        fmu.doStep(t, 1e-3)
        t += 1e-3
    messages = log.messages()
    assert any(m.startswith("specimen ") and "sigma_1 = 1.0000e4 Pa" in m for m in messages), messages
    assert any(m.startswith("the test has ended") and "failed" in m and "ff_c" in m for m in messages), messages
    fmu.terminate()
    fmu.freeInstance()


def test_the_fmi3_unit_is_the_fmi2_one_to_the_bit(compression, compression_fmu_path):
    path3 = compression_fmu_path.parent / "fmi3" / compression_fmu_path.name
    r3 = fmpy.simulate_fmu(str(path3), start_values=compression.defaults, stop_time=0.01, output_interval=1e-3)
    r2 = fmpy.simulate_fmu(str(compression_fmu_path), start_values=compression.defaults, stop_time=0.01, output_interval=1e-3)
    for name in ("axial_stress", "axial_strain", "unconfined_yield_strength", "kinetic_energy"):
        assert np.array_equal(r3[name], r2[name]), name
