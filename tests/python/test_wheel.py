"""The Python package as a user outside the repository gets it: a wheel made by tools/wheel.sh, installed
with pip into a fresh virtual environment, used from a folder that is not a clone, with no
POWDERFMU_FMU_DIR: it finds the FMUs it carries, runs the sieve system and a sweep. (pip fetches fmpy
and numpy, from its cache where it has them.)"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def _run(cmd, cwd, env, timeout=600):
    r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    assert r.returncode == 0, f"{cmd} failed:\n{r.stdout}\n{r.stderr}"
    return r.stdout


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    root = tmp_path_factory.mktemp("outside")
    wheel = Path(_run(["bash", str(REPO / "tools" / "wheel.sh"), str(root / "wheels")], REPO, os.environ).strip().splitlines()[-1])
    assert wheel.is_file() and wheel.suffix == ".whl", wheel
    venv = root / "venv"
    _run([sys.executable, "-m", "venv", str(venv)], root, os.environ)
    python = venv / "bin" / "python"
    _run([str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check", str(wheel)], root, os.environ)
    env = {k: v for k, v in os.environ.items() if k not in ("POWDERFMU_FMU_DIR", "PYTHONPATH", "VIRTUAL_ENV")}
    work = root / "work"
    work.mkdir()
    return python, work, env


def test_the_installed_package_finds_the_fmus_it_carries(installed):
    python, work, env = installed
    out = _run([str(python), "-c", "import powderfmu, powderfmu.fmus, json; print(json.dumps([str(powderfmu.fmu_path(u)) for u in powderfmu.fmus.UNITS] + [powderfmu.__file__]))"], work, env)
    *paths, package = json.loads(out)
    site = Path(package).parent
    assert str(REPO) not in package, package
    for p in paths:
        assert Path(p).is_file() and Path(p).parent == site / "fmus", p


def test_the_sieve_and_a_sweep_run_from_outside_the_repository(installed):
    python, work, env = installed
    summary = json.loads(_run([str(python), "-c", "import json; from powderfmu import sieve; print(json.dumps(sieve.run({'particles': 3, 'periods': 2}).summary()))"], work, env))
    assert summary["particles"] == 3 and 0.0 <= summary["detached_fraction"] <= 1.0, summary
    spec = work / "spec.json"
    spec.write_text(json.dumps({"task": "sieve", "base": {"particles": 3, "periods": 2}, "grid": {"frequency": [2e4, 5e4]}}))
    _run([str(python), "-m", "powderfmu.sweep", str(spec), "--serial", "--output", str(work / "out.csv")], work, env)
    rows = [line for line in (work / "out.csv").read_text().splitlines() if line and not line.startswith("#")]
    assert len(rows) == 3 and all(",ok," in r for r in rows[1:]), rows
