"""Our laws against the peer DEM codes users come from (docs/porting.md), where a peer is installed here
from Debian (`apt-get install lammps`). Skipped, with the reason, where it is not."""

from __future__ import annotations

import csv
import json
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


def lammps_version() -> str:
    """The version line of the installed LAMMPS (its -h banner)."""
    banner = subprocess.run([LMP, "-h"], capture_output=True, text=True, timeout=60).stdout
    return next(line for line in banner.splitlines() if "Simulator" in line).split(" - ", 1)[1].strip()


@pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed (apt-get install lammps); the peer comparison runs where it is")
def test_lammps_wall_modulus_is_the_one_docs_porting_names(tmp_path):
    """docs/porting.md's wall mapping: `fix wall/gran granular hertz/material` builds the wall's E* as
    E/(2(1 - nu)) in LAMMPS 29 Sep 2021 Update 2 (Debian 12's lammps 20220106), not E/(2(1 - nu^2)) as a
    like pair does. One 2.45 um sphere pushed 20 nm into the wall at 1 m/s: F = 4/3 E* sqrt(R) delta^1.5
    at every step in contact gives E* to 1e-9. Another version may differ: then this test says which."""
    radius, E, nu = 2.45e-6, 1.2e9, 0.33
    out = tmp_path / "wall.txt"
    run = subprocess.run(
        [LMP, "-in", str(REPO / "tests/python/peers/lammps_wall.in"), "-log", "none", "-screen", "none", "-var", "z0", repr(radius + 1e-8),
         "-var", "d", repr(2 * radius), "-var", "E", repr(E), "-var", "nu", repr(nu), "-var", "dt", "1e-11", "-var", "v", "1.0",
         "-var", "n", "3000", "-var", "out", str(out)],
        capture_output=True, text=True, timeout=300,
    )
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    z, fz = np.loadtxt(out, comments="#").T
    delta = radius - z
    touching = delta > 1e-9
    e_star = fz[touching] / (4.0 / 3.0 * math.sqrt(radius) * delta[touching] ** 1.5)
    version = lammps_version()
    assert np.ptp(e_star) < 1e-9 * e_star.mean()
    assert e_star.mean() == pytest.approx(E / (2 * (1 - nu)), rel=1e-9), f"LAMMPS {version}: wall E* = {e_star.mean():e} Pa"
    assert version == "29 Sep 2021 - Update 2", f"docs/porting.md names the version measured; this is {version}"


def lammps_sphere_on_plane(*, radius: float, density: float, youngs_modulus: float, poisson_ratio: float, friction: float,
                           v_n: float, v_t: float, spin: float = 0.0, tangential: str = "mindlin/force",
                           rolling_friction: float = 0.0, rolling_stiffness: float = 1e9, dt: float | None = None) -> tuple[float, float, float]:
    """LAMMPS's rebound (v_t, v_n, omega) of an elastic sphere thrown at a rigid plane (`fix wall/gran granular
    hertz/material`, no damping), with a spin about y before [rad/s] and LAMMPS's `rolling sds` (stiffness
    [N/m], no damping, friction mu_r). The time step is 0.01 of the Rayleigh step (000 Eq. 71), ours by
    default, unless given; the run lasts until the sphere has left (three Hertz contact times)."""
    nu, E = poisson_ratio, youngs_modulus
    if dt is None:
        shear = E / (2 * (1 + nu))
        dt = 0.01 * math.pi * radius * math.sqrt(density / shear) / (0.1631 * nu + 0.8766)
    # Our rigid wall's E* = E / (1 - nu^2) through LAMMPS's E / (2 (1 - nu)) (docs/porting.md); its G*
    # = G / (2 - nu) given as LAMMPS's k_t = 8 G*.
    wall_e = 2 * E / (1 + nu)
    k_t = 8 * E / (2 * (1 + nu)) / (2 - nu)
    mass = 4 / 3 * math.pi * radius**3 * density
    contact_time = 2.868 * (mass**2 / ((E / (1 - nu**2)) ** 2 * radius * v_n)) ** 0.2
    gap = v_n * dt
    run = subprocess.run(
        [LMP, "-in", str(REPO / "tests/python/peers/lammps_oblique.in"), "-log", "none", "-var", "tmodel", tangential,
         "-var", "z0", repr(radius + gap), "-var", "d", repr(2 * radius), "-var", "rho", repr(density), "-var", "E", repr(wall_e),
         "-var", "nu", repr(nu), "-var", "kt", repr(k_t), "-var", "mu", repr(friction), "-var", "vt", repr(v_t), "-var", "vn", repr(v_n),
         "-var", "wy", repr(spin), "-var", "dt", repr(dt), "-var", "n", str(int((gap / v_n + 3 * contact_time) / dt)),
         "-var", "kr", repr(rolling_stiffness), "-var", "mur", repr(rolling_friction), "-var", "L", repr(max(1e-2, 10 * radius))],
        capture_output=True, text=True, timeout=300,
    )
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    line = next(l for l in run.stdout.splitlines() if l.startswith("RESULT"))
    vx, vz, wy = (float(x) for x in line.split()[1:])
    return vx, vz, wy


def lammps_oblique(theta_deg: float, tangential: str, spin: float = 0.0, rolling_friction: float = 0.0, rolling_stiffness: float = 1e9) -> tuple[float, float, float]:
    """LAMMPS's rebound (v_t, v_n, omega) of Chung and Ooi's Test 4 sphere (alumina, 3.9 m/s) at one
    incident angle, with a spin about y before [rad/s] and LAMMPS's `rolling sds`."""
    speed = 3.9
    return lammps_sphere_on_plane(radius=2.5e-3, density=4000.0, youngs_modulus=3.8e11, poisson_ratio=0.23, friction=0.092,
                                  v_n=speed * math.cos(math.radians(theta_deg)), v_t=speed * math.sin(math.radians(theta_deg)),
                                  spin=spin, tangential=tangential, rolling_friction=rolling_friction,
                                  rolling_stiffness=rolling_stiffness, dt=1.3806e-8)


@pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed (apt-get install lammps); the peer comparison runs where it is")
@pytest.mark.parametrize("theta", [10.0, 30.0, 60.0])
def test_oblique_impacts_are_lammps_granular_mindlin_force(theta, cli):
    """Chung and Ooi's Test 4 (alumina on a rigid plane at 3.9 m/s) at an angle in the micro-slip regime
    (10 deg) and two of gross sliding, against LAMMPS's `tangential mindlin/force` (the incremental force
    spring, ours): the rebound velocities and spin agree to 1e-3, the time-step error of both (ours at a
    tenth of the step moves by up to 1.7e-4 at 10 deg), with LAMMPS's lever R (`--lever radius`). With
    our default lever R - alpha/2 the spin differs from LAMMPS's by alpha/2R in gross sliding (4e-4 at
    60 deg) and by 0.4 % at 10 deg, where the spin is smaller; asserted below so that a change shows."""
    vx, vz, wy = lammps_oblique(theta, "mindlin/force")

    def ours(lever: str) -> dict:
        out = subprocess.run([str(cli.path), "oblique", str(REPO / "scenes/chung_ooi_alumina.json"), "--speed", "3.9",
                              "--angles", repr(theta), "--lever", lever], capture_output=True, text=True, check=True).stdout
        return next(csv.DictReader(out.splitlines()))

    o = ours("radius")
    assert float(o["tangential_velocity_out_m_per_s"]) == pytest.approx(vx, rel=1e-3)
    assert float(o["normal_velocity_out_m_per_s"]) == pytest.approx(vz, rel=1e-5)
    assert float(o["angular_velocity_out_rad_per_s"]) == pytest.approx(wy, rel=1e-3)
    mid = ours("mid-overlap")
    spin_gap = abs(float(mid["angular_velocity_out_rad_per_s"]) / wy - 1)
    assert spin_gap < (5e-3 if theta < 28.3 else float(mid["max_overlap_m"]) / 2.5e-3), f"mid-overlap lever: spin {spin_gap:.2e} from LAMMPS's"


@pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed (apt-get install lammps); the peer comparison runs where it is")
@pytest.mark.parametrize("spin", [-1500.0, 400.0, 1500.0])
def test_oblique_impacts_with_spin_are_lammps_and_share_its_sign(spin, cli):
    """The same sphere at 30 deg with a spin before the impact, backspin and topspin (positive rolls
    toward +x, LAMMPS's omegay with the same axes): a sign convention that differed would turn these
    rebounds around. Rebound velocities and spin to 1e-3 with LAMMPS's lever."""
    vx, vz, wy = lammps_oblique(30.0, "mindlin/force", spin)
    out = subprocess.run([str(cli.path), "oblique", str(REPO / "scenes/chung_ooi_alumina.json"), "--speed", "3.9", "--angles", "30",
                          "--angular-velocity", repr(spin), "--lever", "radius"], capture_output=True, text=True, check=True).stdout
    o = next(csv.DictReader(out.splitlines()))
    assert float(o["tangential_velocity_out_m_per_s"]) == pytest.approx(vx, rel=1e-3, abs=1e-4)
    assert float(o["normal_velocity_out_m_per_s"]) == pytest.approx(vz, rel=1e-5)
    assert float(o["angular_velocity_out_rad_per_s"]) == pytest.approx(wy, rel=1e-3, abs=0.05)


YADE = shutil.which("yade")
TURNS = [4.0e-8, 1.5e-8, 2.0e-8, 1.2e-7, -1e-9]


@pytest.mark.skipif(YADE is None, reason="Yade is not installed (apt-get install yade); the peer comparison runs where it is")
def test_luding_mercurydpm_reading_is_yades_luding_law(tmp_path, cli):
    """Two 2.45 um spheres under Yade's Law2_ScGeom_LudingPhys_Basic (004 Table 4.2's k_1 210, k_2hat 1500,
    k_c 20 N/m, phi_f 0.02; no f_0, no damping) moved along a path into contact below alpha*, back onto the
    adhesion limit, reloaded, on past alpha* and out, against `powderfmu curve` on the same path: the
    mercurydpm reading follows Yade to within one Yade step's change of force on every leg (at the kinks)
    and to 1e-5 of the peak force in the median of the reloading leg (Yade applies Singh's Eq. 9 one step
    late); 004's reading (pasha) departs on reloading and beyond alpha*."""
    args = {"radius": 2.45e-6, "density": 1350, "k1": 210.0, "kp": 1500.0, "kc": 20.0, "phi_f": 0.02, "dt": 1e-9, "v": 0.01, "turns": TURNS}
    (tmp_path / "args.json").write_text(json.dumps(args))
    out = tmp_path / "yade.txt"
    run = subprocess.run([YADE, "-n", "-x", str(REPO / "tests/python/peers/yade_luding.py"), str(tmp_path / "args.json"), str(out)],
                         capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    yade = np.loadtxt(out)
    ya, yf, leg = yade[:, 0], yade[:, 1], yade[:, 2].astype(int)
    peak = np.abs(yf).max()
    one_step = args["kp"] * args["v"] * args["dt"] / peak  # the largest force change of one Yade step, relative

    def ours(variant):
        scene = tmp_path / f"{variant}.json"
        scene.write_text(json.dumps({
            "contact_model": "luding", "luding_variant": variant, "contact_partner": "particle", "particle_radius": 2.45e-6,
            "particle_density": 1350, "particle_youngs_modulus": 1.2e9, "particle_poisson_ratio": 0.3, "luding_loading_stiffness": 210,
            "luding_max_unloading_stiffness": 1500, "luding_adhesion_stiffness": 20, "luding_plasticity_depth": 0.02,
            "luding_contact_adhesion_force": 0}))
        text = subprocess.run([str(cli.path), "curve", str(scene), "--path", ",".join(map(repr, TURNS)), "--start", repr(TURNS[-1]),
                               "--points", "20000"], capture_output=True, text=True, check=True).stdout.splitlines()
        rows = list(csv.DictReader(text))
        return np.array([float(r["overlap_m"]) for r in rows]), np.array([float(r["force_N"]) for r in rows])

    def per_leg(variant):
        oa, of = ours(variant)
        n = len(oa) // len(TURNS)
        worst, median = [], []
        for k in range(len(TURNS)):
            xa, xf = oa[k * n:(k + 1) * n], of[k * n:(k + 1) * n]
            if xa[0] > xa[-1]:
                xa, xf = xa[::-1], xf[::-1]
            q, qf = ya[leg == k], yf[leg == k]
            inside = (q > max(xa.min(), 0.0) + 3e-11) & (q < xa.max() - 3e-11)
            d = np.abs(np.interp(q[inside], xa, xf) - qf[inside]) / peak
            worst.append(d.max())
            median.append(np.median(d))
        return np.array(worst), np.array(median)

    worst, median = per_leg("mercurydpm")
    print(f"\nmercurydpm against Yade, per leg (of the peak force): max {worst}, median {median}")
    assert np.all(worst <= 1.01 * one_step), (worst, one_step)
    assert median[2] < 1e-5
    worst_p, median_p = per_leg("pasha")
    print(f"pasha against Yade: max {worst_p}")
    assert worst_p[0] < 1e-12, "before any reloading the readings are one law"
    assert median_p[2] > 1e-3 and worst_p[3] > 0.5


@pytest.mark.skipif(YADE is None, reason="Yade is not installed (apt-get install yade); the peer comparison runs where it is")
@pytest.mark.parametrize("v", [3.5, 8.0, 13.0, 20.0])
def test_luding_impacts_in_yade_rebound_as_the_mercurydpm_readings_energy_balance(tmp_path, cli, v):
    """Head-on impacts of two 2.45 um spheres at 3.5-20 m/s under Yade's Luding law (004 Table 4.2's
    values, no f_0, no damping): the restitution is the energy balance of `luding_variant = mercurydpm`
    to 1e-5 (Yade's time step), where 004's reading keeps 0.2655 beyond alpha* (0.873 against 0.266 at
    8 m/s)."""
    args = {"radius": 2.45e-6, "density": 1350, "k1": 210.0, "kp": 1500.0, "kc": 20.0, "phi_f": 0.02, "dt": 1e-11, "v": v}
    (tmp_path / "args.json").write_text(json.dumps(args))
    out = tmp_path / "impact.json"
    run = subprocess.run([YADE, "-n", "-x", str(REPO / "tests/python/peers/yade_luding_impact.py"), str(tmp_path / "args.json"), str(out)],
                         capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    yade = json.loads(out.read_text())
    e = {}
    for variant in ("mercurydpm", "pasha"):
        e[variant] = cli.analyze({
            "contact_model": "luding", "luding_variant": variant, "contact_partner": "particle", "particle_radius": 2.45e-6,
            "particle_density": 1350, "particle_youngs_modulus": 1.2e9, "particle_poisson_ratio": 0.3, "luding_loading_stiffness": 210,
            "luding_max_unloading_stiffness": 1500, "luding_adhesion_stiffness": 20, "luding_plasticity_depth": 0.02,
            "luding_contact_adhesion_force": 0}, velocity=v)
    assert yade["restitution"] == pytest.approx(e["mercurydpm"]["restitution"], abs=1e-5)
    assert yade["max_overlap"] == pytest.approx(e["mercurydpm"]["max_overlap"], rel=1e-4)
    if v > 5:
        assert e["pasha"]["restitution"] == pytest.approx(0.2655, abs=1e-4)


@pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed (apt-get install lammps); the peer comparison runs where it is")
@pytest.mark.parametrize("theta,spin", [(10.0, 3000.0), (30.0, 1500.0), (45.0, -1500.0)])
def test_rolling_friction_is_lammps_rolling_sds_on_its_slider(theta, spin, cli):
    """Rolling friction mu_r = 0.02 on spinning spheres (Chung and Ooi's Test 4 sphere), against LAMMPS's
    `rolling sds` with a stiff spring (k_roll = 1e9 N/m, no damping): its rolling force reaches the slider
    mu_r f_n within a step and then acts as ours, EDEM's constant torque mu_r f_n R against the spin. The
    spin after to 1e-3 (measured 4e-8 to 1.3e-4), the velocities as without rolling. With a soft spring
    (k_roll = 1e5 N/m) LAMMPS's torque builds up over the contact instead and the spin differs by 5-10 %
    (measured 859 against 794 rad/s at 30 deg): the models agree where the spring is stiff, which is the
    case this test fixes."""
    vx, vz, wy = lammps_oblique(theta, "mindlin/force", spin, rolling_friction=0.02)
    out = subprocess.run([str(cli.path), "oblique", str(REPO / "scenes/chung_ooi_alumina.json"), "--speed", "3.9", "--angles", repr(theta),
                          "--angular-velocity", repr(spin), "--lever", "radius", "--rolling-friction", "0.02"], capture_output=True, text=True, check=True).stdout
    o = next(csv.DictReader(out.splitlines()))
    assert float(o["tangential_velocity_out_m_per_s"]) == pytest.approx(vx, rel=1e-3, abs=1e-4)
    assert float(o["normal_velocity_out_m_per_s"]) == pytest.approx(vz, rel=1e-5)
    assert float(o["angular_velocity_out_rad_per_s"]) == pytest.approx(wy, rel=1e-3)
    # The rolling resistance is what is compared: it takes 5-12 % of the spin here.
    _, _, free = lammps_oblique(theta, "mindlin/force", spin)
    assert abs(wy / free - 1) > 0.04, (wy, free)


def _ours_on_plane(cli, scene_file: str, v_n: float, v_t: float, spin: float, scene_path=None) -> tuple[float, float, float]:
    """`powderfmu oblique` (adaptive, converged; LAMMPS's lever R): rebound (v_t, v_n, omega)."""
    path = scene_path or (REPO / "scenes" / scene_file)
    out = subprocess.run([str(cli.path), "oblique", str(path), "--speed", repr(math.hypot(v_n, v_t)),
                          "--angles", repr(math.degrees(math.atan2(v_t, v_n))), "--angular-velocity", repr(spin),
                          "--lever", "radius", "--solver", "adaptive"], capture_output=True, text=True, check=True).stdout
    o = next(csv.DictReader(out.splitlines()))
    return float(o["tangential_velocity_out_m_per_s"]), float(o["normal_velocity_out_m_per_s"]), float(o["angular_velocity_out_rad_per_s"])


def lammps_for_scene(s: dict, v_n: float, v_t: float, spin: float) -> tuple[float, float, float]:
    """`lammps_sphere_on_plane` for a scene's sphere (scene keys), at 0.001 of its Rayleigh step."""
    nu, E, rho, R = s["particle_poisson_ratio"], s["particle_youngs_modulus"], s["particle_density"], s["particle_radius"]
    rayleigh = math.pi * R * math.sqrt(rho / (E / (2 * (1 + nu)))) / (0.1631 * nu + 0.8766)
    return lammps_sphere_on_plane(radius=R, density=rho, youngs_modulus=E, poisson_ratio=nu, friction=s["friction_coefficient"],
                                  v_n=v_n, v_t=v_t, spin=spin, dt=1e-3 * rayleigh)


@pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed (apt-get install lammps); the peer comparison runs where it is")
@pytest.mark.parametrize("material,angle", [("steel", 12.0), ("steel", 36.0), ("polyethylene", 54.0)])
def test_chung_ooi_test_5_is_lammps_in_micro_slip(material, angle, cli):
    """Chung and Ooi's Test 5 (v_n = 5 m/s, the tangential velocity swept, elastic) in micro-slip, where
    no closed form holds: the normalised spin R omega' / (mu V_cn) (scale 5) of our converged adaptive
    integrator and LAMMPS's `tangential mindlin/force` at 0.001 of the Rayleigh step agree to 2e-3
    (LAMMPS's time-step error: at 0.01 of the step it is 2 % low at 10 deg; benches/chung_ooi_5_6.py)."""
    s = json.loads((REPO / f"scenes/chung_ooi_{material}.json").read_text())
    mu, R, v_n = s["friction_coefficient"], s["particle_radius"], 5.0
    v_t = v_n * math.tan(math.radians(angle))
    vx, vz, wy = lammps_for_scene(s, v_n, v_t, 0.0)
    ox, oz, ow = _ours_on_plane(cli, f"chung_ooi_{material}.json", v_n, v_t, 0.0)
    assert abs(R * (ow - wy) / (mu * v_n)) < 2e-3, (ow, wy)
    assert abs((ox - R * ow) - (vx - R * wy)) / (mu * v_n) < 2e-3, (ox, ow, vx, wy)
    assert oz == pytest.approx(vz, rel=1e-5)


@pytest.mark.skipif(LMP is None, reason="LAMMPS is not installed (apt-get install lammps); the peer comparison runs where it is")
@pytest.mark.parametrize("material,angle", [("aluminium_alloy", 12.0), ("nylon", 42.0), ("aluminium_alloy", 60.0)])
def test_chung_ooi_test_6_elastic_twin_is_lammps(material, angle, cli, tmp_path):
    """Chung and Ooi's Test 6 (v_n = 0.2 m/s, spin only, swept) without its damping (LAMMPS's damping models
    are not ours): the contact point's restitution beta = -V_st' / V_st agrees with LAMMPS at 0.001 of the
    Rayleigh step to 2e-3, where the spin alone drives the contact (a path Test 4 does not take)."""
    s = json.loads((REPO / f"scenes/chung_ooi_{material}.json").read_text()) | {"restitution_coefficient": 1.0}
    path = tmp_path / "elastic.json"
    path.write_text(json.dumps(s))
    R, v_n = s["particle_radius"], 0.2
    v_st = v_n * math.tan(math.radians(angle))
    vx, vz, wy = lammps_for_scene(s, v_n, 0.0, -v_st / R)
    ox, oz, ow = _ours_on_plane(cli, "", v_n, 0.0, -v_st / R, scene_path=path)
    beta_lammps, beta_ours = -(vx - R * wy) / v_st, -(ox - R * ow) / v_st
    assert abs(beta_ours - beta_lammps) < 2e-3, (beta_ours, beta_lammps)
    assert oz == pytest.approx(vz, rel=1e-5)
