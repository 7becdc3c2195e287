"""Fixtures of the fmpy suite.

The FMUs are read from $POWDERFMU_FMU_DIR (default <repo>/target/fmu), built by `cargo run -p fmu_build`;
the command-line tool from $POWDERFMU_CLI (default <repo>/target/release/powderfmu), built by
`cargo build --release --bin powderfmu`. A missing file fails the test that needs it with a message
saying how to build it.
"""

from __future__ import annotations

import dataclasses
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from fmpy import extract, read_model_description  # noqa: E402

from fmu_support import REPO, Cli, Unit, cli_path, fmu_dir  # noqa: E402


def _fmu_path(name: str) -> Path:
    path = fmu_dir() / f"{name}.fmu"
    if not path.is_file():
        pytest.fail(
            f"{path} does not exist: build the FMUs with `cargo run -p fmu_build` in the repository root "
            f"(or point POWDERFMU_FMU_DIR at the folder that holds {name}.fmu)",
            pytrace=False,
        )
    return path


@pytest.fixture(scope="session")
def impact_fmu_path() -> Path:
    """Path of ParticleWallImpact.fmu."""
    return _fmu_path("ParticleWallImpact")


@pytest.fixture(scope="session")
def contact_fmu_path() -> Path:
    """Path of ContactElement.fmu."""
    return _fmu_path("ContactElement")


@pytest.fixture(scope="session")
def indentation_fmu_path() -> Path:
    """Path of BallIndentation.fmu."""
    return _fmu_path("BallIndentation")


@pytest.fixture(scope="session")
def _unzip_root():
    root = tempfile.mkdtemp(prefix="powderfmu-fmpy-")
    yield Path(root)
    shutil.rmtree(root, ignore_errors=True)


def _unit(name: str, path: Path, root: Path) -> Unit:
    unzipdir = extract(str(path), unzipdir=str(root / name))
    return Unit(name=name, path=path, unzipdir=unzipdir, md=read_model_description(unzipdir))


@pytest.fixture(scope="session")
def impact(impact_fmu_path, _unzip_root) -> Unit:
    """ParticleWallImpact, extracted once."""
    return _unit("ParticleWallImpact", impact_fmu_path, _unzip_root)


@pytest.fixture(scope="session")
def contact(contact_fmu_path, _unzip_root) -> Unit:
    """ContactElement, extracted once."""
    return _unit("ContactElement", contact_fmu_path, _unzip_root)


# The indentation tests run on a stand-in bed: the shipped bed (29000 spheres) takes about a minute per
# test, so only `test_default_bed.py` runs it. The stand-in's test: a 4 mm indenter in its 7 mm die to h/r =
# 0.2, read over h/r 0.1-0.2 (the unit's default window, 0.35-0.5, would take this shallow bed 2.5 times
# as deep), one thread, and the bed's own time step.
QUICK_TEST = {"indenter_diameter": 0.004, "max_penetration": 0.0004, "indentation_speed": 0.05, "threads": 1, "time_step": 0.0,
              "plateau_start": 0.1, "plateau_end": 0.2}
QUICK_EXPERIMENT = {"stop_time": 0.03, "output_interval": 2e-4}


@pytest.fixture(scope="session")
def quick_bed(cli, tmp_path_factory) -> dict:
    """The stand-in bed `scenes/bed_indentation_quick.json` (800 soft spheres in a 7 mm die), prepared
    once per session with `powderfmu bed prepare`, as the start values that load it (`powderfmu bed
    params`: bed_file and its contact parameters)."""
    bed = tmp_path_factory.mktemp("beds") / "quick.pfbed"
    for cmd in (
        [str(cli.path), "bed", "prepare", str(REPO / "scenes" / "bed_indentation_quick.json"), "-o", str(bed)],
        [str(cli.path), "bed", "params", str(bed)],
    ):
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        assert run.returncode == 0, f"{' '.join(cmd)} failed ({run.returncode}): {run.stderr}"
    return json.loads(run.stdout)


@pytest.fixture(scope="session")
def shipped_indentation(indentation_fmu_path, _unzip_root) -> Unit:
    """BallIndentation as shipped, extracted once: the seed's bed and the unit's own defaults."""
    return _unit("BallIndentation", indentation_fmu_path, _unzip_root)


@pytest.fixture(scope="session")
def indentation(shipped_indentation, quick_bed) -> Unit:
    """BallIndentation with the start values and experiment of the stand-in bed. The same extraction as
    `shipped_indentation`: extracting again would overwrite the loaded library in place (a crash later)."""
    return dataclasses.replace(shipped_indentation, defaults={**quick_bed, **QUICK_TEST}, experiment=dict(QUICK_EXPERIMENT))


@pytest.fixture(scope="session")
def compression_fmu_path() -> Path:
    """Path of UnconfinedCompression.fmu."""
    return _fmu_path("UnconfinedCompression")


@pytest.fixture(scope="session")
def shipped_compression(compression_fmu_path, _unzip_root) -> Unit:
    """UnconfinedCompression as shipped, extracted once: the Ch. 6 specimen and the unit's own defaults."""
    return _unit("UnconfinedCompression", compression_fmu_path, _unzip_root)


@pytest.fixture(scope="session")
def compression(shipped_compression, quick_bed) -> Unit:
    """UnconfinedCompression on the stand-in bed (800 soft cohesive spheres, 10 kPa; it fails at about 2 %
    strain in about 10000 engine steps), one thread, a window of 0.5 % strain (the default 0.05 % holds 2
    samples at this soft bed's step, and is refused). The same extraction as `shipped_compression`."""
    return dataclasses.replace(
        shipped_compression,
        defaults={"bed_file": quick_bed["bed_file"], "threads": 1, "window": 0.005},
        experiment={"stop_time": 0.05, "output_interval": 5e-4},
    )


@pytest.fixture(scope="session")
def cli() -> Cli:
    """`powderfmu analyze` for energy-balance and closed-form reference values."""
    path = cli_path()
    if not path.is_file():
        pytest.fail(
            f"{path} does not exist: build the command-line tool with `cargo build --release --bin powderfmu` "
            "in the repository root (or point POWDERFMU_CLI at it)",
            pytrace=False,
        )
    return Cli(path)
