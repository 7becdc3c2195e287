"""Fixtures of the fmpy suite.

The FMUs are read from $POWDERFMU_FMU_DIR (default <repo>/target/fmu), built by `cargo run -p fmu_build`;
the command-line tool from $POWDERFMU_CLI (default <repo>/target/release/powderfmu), built by
`cargo build --release --bin powderfmu`. A missing file fails the test that needs it with a message
saying how to build it.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from fmpy import extract, read_model_description  # noqa: E402

from fmu_support import Cli, Unit, cli_path, fmu_dir  # noqa: E402


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


@pytest.fixture(scope="session")
def indentation(indentation_fmu_path, _unzip_root) -> Unit:
    """BallIndentation, extracted once."""
    return _unit("BallIndentation", indentation_fmu_path, _unzip_root)


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
