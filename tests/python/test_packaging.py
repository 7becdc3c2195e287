"""The packaging tool's promises: the same inputs give byte-identical .fmu files.

The suite's FMUs (built by `cargo run -p fmu_build`) are packaged a second time from the same built
library (`--skip-build`) into a temporary folder; every archive must be identical byte for byte, so a
user can compare a downloaded FMU with one built from the same commit by its hash.
"""

from __future__ import annotations

import hashlib
import os
import subprocess
import zipfile

import pytest

from fmu_support import REPO, fmu_dir

UNITS = ["ParticleWallImpact", "ContactElement", "BallIndentation", "UnconfinedCompression"]


def sha256(path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@pytest.fixture(scope="module")
def second_build(tmp_path_factory):
    out = tmp_path_factory.mktemp("fmu_again")
    env = dict(os.environ)
    # The packaging tool tests/run_all.sh ran ($POWDERFMU_FMU_BUILD), or cargo's.
    tool = [os.environ["POWDERFMU_FMU_BUILD"]] if os.environ.get("POWDERFMU_FMU_BUILD") else ["cargo", "run", "--locked", "--quiet", "-p", "fmu_build", "--"]
    run = subprocess.run(
        tool + ["--skip-build", "--out", str(out)],
        cwd=REPO, env=env, capture_output=True, text=True, timeout=1800,
    )
    assert run.returncode == 0, run.stderr
    return out


# Each unit's FMI 2.0 archive and its FMI 3.0 one (fmi3/), with the folder of its Linux binary.
ARCHIVES = [(f"{u}.fmu", f"binaries/linux64/{u}.so") for u in UNITS] + [(f"fmi3/{u}.fmu", f"binaries/x86_64-linux/{u}.so") for u in UNITS]


@pytest.mark.parametrize("archive", [a for a, _ in ARCHIVES])
def test_two_builds_give_byte_identical_fmus(second_build, archive):
    first = fmu_dir() / archive
    again = second_build / archive
    assert first.is_file() and again.is_file()
    assert sha256(first) == sha256(again), f"{archive} differs between two packagings of the same build"


@pytest.mark.parametrize("archive,binary", ARCHIVES)
def test_archives_have_fixed_times_and_sorted_entries(archive, binary):
    with zipfile.ZipFile(fmu_dir() / archive) as z:
        names = z.namelist()
        assert names == sorted(names)
        assert "modelDescription.xml" in names
        assert binary in names
        for info in z.infolist():
            assert info.date_time == (1980, 1, 1, 0, 0, 0), (info.filename, info.date_time)
            assert (info.external_attr >> 16) & 0o777 == 0o644, info.filename
        assert z.testzip() is None
