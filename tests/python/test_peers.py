"""Our laws against the peer DEM codes users come from (docs/porting.md), where a peer is installed here
from Debian (`apt-get install lammps`). Skipped, with the reason, where it is not: CI does not install
them, so these never sit in its critical path."""

from __future__ import annotations

import csv
import math
import shutil
import subprocess

import numpy as np
import pytest

from fmu_support import REPO

LMP = shutil.which("lmp")


@pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed (apt-get install lammps); the peer comparison runs where it is")
def test_jkr_force_detachment_is_lammps_granular_jkr(tmp_path, cli):
    """Two 2.45 um spheres (000 Table 5 materials) pushed 20 nm into JKR contact and pulled apart at 1 m/s
    under LAMMPS (pair granular jkr, its gamma = our Gamma / 2), against `powderfmu curve` on the same
    path with jkr_detachment = force: the forces agree to 1e-9 f_c and the contact ends at the same
    overlap to one LAMMPS step."""
    radius, gamma, dt, v = 2.45e-6, 0.24, 1e-11, 1.0
    d, n_in, n = 2 * radius, 2200, 6200
    out = tmp_path / "force.txt"
    run = subprocess.run(
        [LMP, "-in", str(REPO / "tests/python/peers/lammps_jkr.in"), "-log", "none", "-screen", "none",
         "-var", "x0", repr(d + 2e-9), "-var", "d", repr(d), "-var", "E", "1.2e9", "-var", "nu", "0.33",
         "-var", "gamma", repr(gamma / 2), "-var", "dt", repr(dt), "-var", "v", repr(v), "-var", "n_in", str(n_in),
         "-var", "n", str(n), "-var", "out", str(out)],
        capture_output=True, text=True, timeout=300,
    )
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    lammps = np.loadtxt(out, comments="#")
    alpha, force = d - lammps[:, 0], lammps[:, 1]

    scene = tmp_path / "scene.json"
    scene.write_text(
        '{"contact_model": "jkr", "jkr_detachment": "force", "contact_partner": "particle", "particle_radius": 2.45e-6, '
        '"particle_density": 1350, "particle_youngs_modulus": 1.2e9, "particle_poisson_ratio": 0.33, "surface_energy": 0.24}'
    )
    ours = subprocess.run([str(cli.path), "curve", str(scene), "--path", "2e-8,-2e-8", "--start", "-2e-9", "--points", "200000"],
                          capture_output=True, text=True, check=True).stdout.splitlines()
    rows = list(csv.DictReader(ours))
    oa = np.array([float(r["overlap_m"]) for r in rows])
    of = np.array([float(r["force_N"]) for r in rows])
    state = np.array([int(r["contact_state"]) for r in rows])
    f_c = 1.5 * math.pi * gamma * radius / 2  # R* = R/2

    turn, i_turn = int(np.argmax(oa)), int(np.argmax(alpha))
    assert alpha[i_turn] == pytest.approx(oa[turn], rel=1e-9)
    # In: from first touch (the force drops to -8/9 f_c in both) to 20 nm.
    a_in, f_in = alpha[: i_turn + 1], force[: i_turn + 1]
    touching = a_in > 1e-11
    assert np.max(np.abs(np.interp(a_in[touching], oa[: turn + 1], of[: turn + 1]) - f_in[touching])) < 1e-9 * f_c
    # Out: down to the force minimum -f_c, where both end the contact.
    oa2, of2, in_contact = oa[turn:][::-1], of[turn:][::-1], state[turn:][::-1] != 0
    our_end = oa2[in_contact].min()
    a_out, f_out = alpha[i_turn:], force[i_turn:]
    lammps_end = a_out[f_out != 0].min()
    assert abs(lammps_end - our_end) <= v * dt, f"LAMMPS ends at {lammps_end:e} m, ours at {our_end:e} m"
    on = (f_out != 0) & (a_out > our_end + 2 * v * dt)
    assert np.max(np.abs(np.interp(a_out[on], oa2[in_contact], of2[in_contact]) - f_out[on])) < 1e-9 * f_c
    assert f_out[f_out != 0].min() == pytest.approx(-f_c, rel=1e-6), "LAMMPS ends at the pull-off force"
