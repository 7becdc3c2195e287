"""Where the .fmu files are, in this order: a folder the caller names; $POWDERFMU_FMU_DIR; the FMUs the
installed package carries (a wheel made by `tools/wheel.sh`); the `target/fmu` folder of the powderfmu
repository this package or the current directory sits in. Nothing is built unless the caller asks
(`build=True`, in a clone of the repository)."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

UNITS = ("ParticleWallImpact", "ContactElement", "BallIndentation", "UnconfinedCompression")

#: The FMUs a wheel carries, beside this module.
PACKAGED = Path(__file__).resolve().parent / "fmus"


class FmuNotFound(RuntimeError):
    pass


def repository() -> Path | None:
    """The powderfmu repository holding this package or the current directory, if any."""
    for start in (Path(__file__).resolve().parent, Path.cwd().resolve()):
        for d in (start, *start.parents):
            if (d / "fmu_build" / "Cargo.toml").is_file() and (d / "Cargo.toml").is_file():
                return d
    return None


def fmu_path(unit: str = "ParticleWallImpact", directory: str | os.PathLike[str] | None = None, build: bool = False) -> Path:
    """The path of a unit's FMI 2.0 .fmu (see the module's text for where it is looked for). `build`: in a
    clone of the repository, build the FMUs (linux64) with cargo when they are missing."""
    if unit not in UNITS:
        raise ValueError(f"unit {unit!r} is not one of {', '.join(UNITS)}")
    name = f"{unit}.fmu"
    for folder, why in ((directory, "the folder given"), (os.environ.get("POWDERFMU_FMU_DIR"), "POWDERFMU_FMU_DIR is set")):
        if folder is not None:
            path = Path(folder) / name
            if not path.is_file():
                raise FmuNotFound(f"{path} does not exist ({why}; build the FMUs with `cargo run -p fmu_build` in a clone of powderfmu)")
            return path
    if (PACKAGED / name).is_file():
        return PACKAGED / name
    repo = repository()
    if repo is None:
        raise FmuNotFound(
            f"{name} not found: this installation carries no FMUs. Install a wheel made by tools/wheel.sh, pass "
            "the folder that holds the .fmu files, or set POWDERFMU_FMU_DIR to it"
        )
    path = repo / "target" / "fmu" / name
    if not path.is_file():
        if not build:
            raise FmuNotFound(f"{path} does not exist; build it with `cargo run -p fmu_build` in {repo}")
        print(f"powderfmu: building the FMUs in {repo} (cargo run -p fmu_build -- --linux-only)", flush=True)
        subprocess.run(["cargo", "run", "--quiet", "--release", "-p", "fmu_build", "--", "--linux-only"], cwd=repo, check=True, stdin=subprocess.DEVNULL)
    return path
