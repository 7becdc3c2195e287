"""The win64 binaries of the FMUs, run as a Windows host runs them: `fmu_check` (fmu_build/check, a small
FMI 2.0 importer that unzips the .fmu, reads modelDescription.xml and loads binaries/<platform>/) is
built for x86_64-pc-windows-gnu and run under wine on every unit, in Co-Simulation and, where offered,
Model Exchange; a state serialized by the Linux binary is restored by the Windows one.

Needs what tests/run_all.sh installs: the Rust target x86_64-pc-windows-gnu, mingw-w64 and wine. Set
POWDERFMU_SKIP_WINDOWS=1 to skip these tests on a machine without them (the skip says so).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
import zipfile
from pathlib import Path

import fmpy
import pytest

from fmu_support import REPO, fmu_dir

UNITS = ["ParticleWallImpact", "ContactElement", "BallIndentation", "UnconfinedCompression"]
# The DEM units: Co-Simulation only, and bit for bit across platforms (see below).
BEDS = ("BallIndentation", "UnconfinedCompression")
TARGET = "x86_64-pc-windows-gnu"

pytestmark = pytest.mark.skipif(
    os.environ.get("POWDERFMU_SKIP_WINDOWS") == "1", reason="POWDERFMU_SKIP_WINDOWS=1: the Windows toolchain (mingw-w64, wine) is not installed here"
)


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=1200, **kw)
    assert r.returncode == 0, f"{' '.join(map(str, cmd))} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}"
    return r.stdout


@pytest.fixture(scope="module")
def checkers(tmp_path_factory):
    """fmu_check for Linux and for Windows (with the test-only bcryptprimitives shim beside it)."""
    for tool in ("x86_64-w64-mingw32-gcc", "wine"):
        assert shutil.which(tool), f"{tool} is missing: apt-get install gcc-mingw-w64-x86-64 wine (tests/run_all.sh does)"
    run(["cargo", "build", "--quiet", "--release", "-p", "fmu_check"], cwd=REPO)
    run(["cargo", "build", "--quiet", "--release", "-p", "fmu_check", "--target", TARGET], cwd=REPO)
    win = tmp_path_factory.mktemp("win")
    shutil.copy(REPO / "target" / TARGET / "release" / "fmu_check.exe", win / "fmu_check.exe")
    run(["x86_64-w64-mingw32-gcc", "-shared", "-O2", "-o", str(win / "bcryptprimitives.dll"), str(REPO / "tests" / "windows" / "bcryptprimitives.c"), "-ladvapi32"])
    env = dict(os.environ, WINEDEBUG="-all", WINEPREFIX=str(tmp_path_factory.mktemp("wineprefix")))
    return REPO / "target" / "release" / "fmu_check", win / "fmu_check.exe", env


def finals(text: str) -> dict[str, dict[str, float]]:
    """{'CS final': {name: value}, 'ME final': {...}} from fmu_check's lines."""
    out = {}
    for line in text.splitlines():
        m = re.match(r"(CS final|CS saved|CS restored|ME final|CS3 final|CS3 saved|CS3 restored)(?: \((\d+) (?:events|early returns)\))? (.*)", line)
        if m:
            values = dict(kv.split("=") for kv in m.group(3).split())
            out[m.group(1)] = {k: float(v) for k, v in values.items()}
            if m.group(2):
                out[m.group(1)]["events"] = float(m.group(2))
    return out


def close(a: dict, b: dict, rel: float) -> list[str]:
    assert a.keys() == b.keys()
    return [f"{k}: {a[k]!r} vs {b[k]!r}" for k in a if abs(a[k] - b[k]) > rel * max(abs(a[k]), abs(b[k]), 1e-300)]


@pytest.mark.parametrize("unit", UNITS)
def test_every_fmu_carries_both_platforms(unit):
    with zipfile.ZipFile(fmu_dir() / f"{unit}.fmu") as z:
        names = z.namelist()
    assert f"binaries/linux64/{unit}.so" in names
    assert f"binaries/win64/{unit}.dll" in names


@pytest.mark.parametrize("unit", UNITS)
def test_the_fmi3_fmu_carries_the_same_windows_binary_with_every_fmi3_export(unit):
    """The FMI 3.0 archive's x86_64-windows DLL is the win64 one the wine runs below check, and its
    export table names the 75 functions of fmi3Functions.h (the PE export table, read with mingw's objdump)."""
    with zipfile.ZipFile(fmu_dir() / f"{unit}.fmu") as z2, zipfile.ZipFile(fmu_dir() / "fmi3" / f"{unit}.fmu") as z3:
        dll2 = z2.read(f"binaries/win64/{unit}.dll")
        dll3 = z3.read(f"binaries/x86_64-windows/{unit}.dll")
        assert f"binaries/x86_64-linux/{unit}.so" in z3.namelist()
    assert dll3 == dll2
    objdump = shutil.which("x86_64-w64-mingw32-objdump")
    if objdump is None:
        pytest.skip("x86_64-w64-mingw32-objdump (Debian's binutils-mingw-w64-x86-64) is not installed")
    header = (Path(fmpy.__file__).parent / "c-code" / "fmi3Functions.h").read_text()
    standard = set(re.findall(r"^FMI3_Export fmi3\w+TYPE\s+(fmi3\w+);", header, re.M))
    assert len(standard) == 75
    with tempfile.NamedTemporaryFile(suffix=".dll") as f:
        f.write(dll3)
        f.flush()
        table = subprocess.run([objdump, "-p", f.name], capture_output=True, text=True, check=True).stdout
    exported = set(re.findall(r"\b(fmi3\w+)\b", table))
    assert standard <= exported, sorted(standard - exported)


@pytest.mark.parametrize("unit", UNITS)
def test_the_win64_binary_runs_under_wine_as_the_linux64_one(checkers, unit, tmp_path):
    linux, windows, env = checkers
    fmu = fmu_dir() / f"{unit}.fmu"
    state = tmp_path / "linux.state"
    native = run([str(linux), str(fmu), "--state-out", str(state)])
    wine = run(["wine", str(windows), str(fmu)], env=env)
    assert "win64" in wine and "binaries/win64" in wine.replace("\\", "/"), wine
    n, w = finals(native), finals(wine)
    kinds = ["CS final", "ME final"] if unit not in BEDS else ["CS final"]
    for kind in kinds:
        assert kind in n and kind in w, f"{kind} missing:\n{native}\n{wine}"
        # The same code on both platforms; the C libraries' exp, sin and cos may round differently in the
        # last bit, which the smooth single-contact units keep at that level. The DEM bed would turn one
        # bit into another trajectory, so its only libm call (cbrt) is the pure-Rust one (numeric::cbrt):
        # the DEM units must repeat bit for bit.
        rel = 0.0 if unit in BEDS else 1e-12
        assert not close(n[kind], w[kind], rel), f"{unit} {kind}: " + "; ".join(close(n[kind], w[kind], rel))


@pytest.mark.parametrize("unit", UNITS)
def test_a_state_saved_on_linux_restores_on_windows(checkers, unit, tmp_path):
    linux, windows, env = checkers
    fmu = fmu_dir() / f"{unit}.fmu"
    state = tmp_path / "linux.state"
    native = finals(run([str(linux), str(fmu), "--state-out", str(state)]))
    restored = finals(run(["wine", str(windows), str(fmu), "--state-in", str(state)], env=env))
    assert restored["CS restored"] == native["CS saved"], "the state reads back to the same outputs"
    rel = 0.0 if unit in BEDS else 1e-12
    assert not close(native["CS final"], restored["CS final"], rel), "; ".join(close(native["CS final"], restored["CS final"], rel))


@pytest.mark.parametrize("unit", UNITS)
def test_the_fmi3_windows_binary_runs_under_wine_as_the_linux_one_with_early_return(checkers, unit, tmp_path):
    """fmu_check's FMI 3.0 run (Co-Simulation with early return at contact events), natively and under
    wine, and a state saved by the Linux binary restored by the Windows one."""
    linux, windows, env = checkers
    fmu = fmu_dir() / "fmi3" / f"{unit}.fmu"
    state = tmp_path / "linux3.state"
    native = run([str(linux), str(fmu), "--state-out", str(state)])
    wine = run(["wine", str(windows), str(fmu)], env=env)
    restored = finals(run(["wine", str(windows), str(fmu), "--state-in", str(state)], env=env))
    assert "binaries/x86_64-windows" in wine.replace("\\", "/"), wine
    n, w = finals(native), finals(wine)
    assert "CS3 final" in n and "CS3 final" in w, f"{native}\n{wine}"
    rel = 0.0 if unit in BEDS else 1e-12
    assert not close(n["CS3 final"], w["CS3 final"], rel), "; ".join(close(n["CS3 final"], w["CS3 final"], rel))
    assert n["CS3 final"]["events"] == w["CS3 final"]["events"], "the same early returns"
    if unit == "ParticleWallImpact":
        assert n["CS3 final"]["events"] >= 2, "the impact's contact and separation at least"
    assert restored["CS3 restored"] == n["CS3 saved"]
    # The restored run starts halfway, after the impact's early returns: its count is its own.
    without = lambda d: {k: v for k, v in d.items() if k != "events"}  # noqa: E731
    assert not close(without(n["CS3 final"]), without(restored["CS3 final"]), rel)
