"""The package's own tests: where it finds the FMUs, and the sweep's task registry. No FMU is run here
(tests/python runs them; tests/python/test_wheel.py installs a wheel and runs it outside the repository)."""

from __future__ import annotations

import importlib

import pytest

from powderfmu import fmus, sweep


@pytest.fixture
def no_env(monkeypatch):
    monkeypatch.delenv("POWDERFMU_FMU_DIR", raising=False)


def _fake(folder, unit="ParticleWallImpact"):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{unit}.fmu").write_bytes(b"PK")
    return folder / f"{unit}.fmu"


def test_a_named_folder_comes_first_then_the_environment_then_the_package(tmp_path, monkeypatch, no_env):
    given = _fake(tmp_path / "given")
    env = _fake(tmp_path / "env")
    packaged = _fake(tmp_path / "packaged")
    monkeypatch.setattr(fmus, "PACKAGED", packaged.parent)
    monkeypatch.setenv("POWDERFMU_FMU_DIR", str(env.parent))
    assert fmus.fmu_path("ParticleWallImpact", directory=given.parent) == given
    assert fmus.fmu_path("ParticleWallImpact") == env
    monkeypatch.delenv("POWDERFMU_FMU_DIR")
    assert fmus.fmu_path("ParticleWallImpact") == packaged


def test_a_missing_fmu_is_named_and_nothing_is_built(tmp_path, monkeypatch, no_env):
    with pytest.raises(fmus.FmuNotFound, match="the folder given"):
        fmus.fmu_path("ContactElement", directory=tmp_path)
    monkeypatch.setenv("POWDERFMU_FMU_DIR", str(tmp_path))
    with pytest.raises(fmus.FmuNotFound, match="POWDERFMU_FMU_DIR"):
        fmus.fmu_path("ContactElement")
    monkeypatch.delenv("POWDERFMU_FMU_DIR")
    # Outside any clone and with no FMUs in the package: refused with what to do, no cargo started.
    monkeypatch.setattr(fmus, "PACKAGED", tmp_path / "none")
    monkeypatch.setattr(fmus, "repository", lambda: None)
    monkeypatch.setattr(fmus.subprocess, "run", lambda *a, **k: pytest.fail("a lookup started a build"))
    with pytest.raises(fmus.FmuNotFound, match="POWDERFMU_FMU_DIR"):
        fmus.fmu_path("BallIndentation")
    with pytest.raises(ValueError, match="not one of"):
        fmus.fmu_path("Hopper")


def test_every_task_names_a_unit_and_a_module_that_runs_it():
    assert set(sweep.TASKS) == {"sieve", "indentation", "compression"}
    for name, task in sweep.TASKS.items():
        assert task.unit in fmus.UNITS, name
        code = importlib.import_module(f"powderfmu.{task.module}")
        assert callable(code.resolve) and callable(code.run), name
        assert len(task.summary_keys()) > 0 and all(isinstance(k, str) for k in task.summary_keys()), name
    with pytest.raises(sweep.SweepError, match="not one of sieve, indentation, compression"):
        sweep.check({"task": "hopper", "grid": {"frequency": [1.0]}})
