"""Where the .fmu files are: $POWDERFMU_FMU_DIR, else `target/fmu` of the powderfmu repository this
package sits in (or the current directory's), built there with `cargo run -p fmu_build` when missing."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

UNITS = ("ParticleWallImpact", "ContactElement", "BallIndentation")


class FmuNotFound(RuntimeError):
    pass


def repository() -> Path | None:
    """The powderfmu repository holding this package or the current directory, if any."""
    for start in (Path(__file__).resolve().parent, Path.cwd().resolve()):
        for d in (start, *start.parents):
            if (d / "fmu_build" / "Cargo.toml").is_file() and (d / "Cargo.toml").is_file():
                return d
    return None


def fmu_path(unit: str = "ParticleWallImpact", build: bool = True) -> Path:
    """The path of a unit's .fmu; builds the FMUs (linux64 only) in the repository when they are missing."""
    if unit not in UNITS:
        raise ValueError(f"unit {unit!r} is not one of {', '.join(UNITS)}")
    if "POWDERFMU_FMU_DIR" in os.environ:
        path = Path(os.environ["POWDERFMU_FMU_DIR"]) / f"{unit}.fmu"
        if not path.is_file():
            raise FmuNotFound(f"{path} does not exist (POWDERFMU_FMU_DIR is set; build the FMUs with `cargo run -p fmu_build`)")
        return path
    repo = repository()
    if repo is None:
        raise FmuNotFound(
            f"{unit}.fmu not found: set POWDERFMU_FMU_DIR to the folder that holds the .fmu files, "
            "or run from a clone of the powderfmu repository"
        )
    path = repo / "target" / "fmu" / f"{unit}.fmu"
    if not path.is_file():
        if not build:
            raise FmuNotFound(f"{path} does not exist; build it with `cargo run -p fmu_build` in {repo}")
        print(f"powderfmu: building the FMUs in {repo} (cargo run -p fmu_build -- --linux-only)", flush=True)
        subprocess.run(["cargo", "run", "--quiet", "--release", "-p", "fmu_build", "--", "--linux-only"], cwd=repo, check=True, stdin=subprocess.DEVNULL)
    return path
