"""The physics through the FMUs: undamped Nan impacts against the energy balance of `powderfmu analyze`,
sticking velocities found by bisection on initial_velocity against 000 Table 6 and 004 Table 4.2, a
sphere on a vibrating wall, and the ContactElement through a loading-unloading cycle.

The only numbers written here are the published ones; every other reference comes from the CLI at run
time or from the units' own start values."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from fmu_support import REPO, power_of_two_below, rel, sphere_mass, wall_input

# ---------------------------------------------------------------------------------------------------
# Impacts


def impact_run(impact, cli, start: dict, v: float, periods: float = 50.0):
    """A CS impact at v long enough for the sphere to come off the wall: the approach (gap / v) plus
    `periods` times 2 sqrt(m/k_el) (000 Eq. 68), a few contact durations. Coarse output: only the end
    state matters."""
    ref = cli.analyze(impact.scene(start))
    gap = start.get("initial_gap", impact.start("initial_gap"))
    stop = gap / v + periods * ref["critical_time_step"]
    return impact.simulate(start_values={**start, "initial_velocity": v}, stop_time=stop, output_interval=stop / 20)


def rebounds(impact, cli, start: dict, v: float) -> bool:
    """True when the sphere has left the wall for good, False when it stays stuck.

    Undamped, a stuck sphere does not come to rest: it oscillates in its adhesive well, its velocity
    changing sign, so the sign of the final velocity alone says nothing. A rebounded sphere is out of
    contact (contact_state 0) and flies away at constant positive velocity (no gravity)."""
    r = impact_run(impact, cli, start, v)
    tail = r[-5:]
    if np.all(tail["contact_state"] == 0):
        assert np.all(tail["sphere_velocity"] > 0), f"out of contact but not moving away at {v} m/s: {tail}"
        assert np.all(tail["sphere_velocity"] == tail["sphere_velocity"][-1]), "free flight must keep its velocity"
        return True
    assert np.all(tail["contact_state"] != 0), f"undecided at {v} m/s (leaves and returns?): {r['contact_state']}"
    assert r["max_overlap"][-1] > 0
    return False


def sticking_velocity(impact, cli, start: dict, lo: float = 0.5, hi: float = 10.0, iterations: int = 24) -> float:
    """Bisection on initial_velocity between a speed that sticks and one that rebounds."""
    assert not rebounds(impact, cli, start, lo), f"{lo} m/s should stick"
    assert rebounds(impact, cli, start, hi), f"{hi} m/s should rebound"
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        if rebounds(impact, cli, start, mid):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("v", [2.5, 3.0, 5.0])
def test_undamped_nan_impact_matches_the_energy_balance(impact, cli, v):
    assert impact.start("restitution_coefficient") == 1.0  # the default scene (000 Table 5) is undamped
    ref = cli.analyze(impact.scene(), velocity=v)
    assert not ref["sticks"]
    r = impact_run(impact, cli, {}, v)
    assert r["sphere_velocity"][0] == -v
    assert r["contact_state"][-1] == 0
    v_out = r["sphere_velocity"][-1]
    assert v_out / v == pytest.approx(ref["restitution"], rel=1e-6)
    assert v_out == pytest.approx(ref["rebound_velocity"], rel=1e-6)
    assert r["max_overlap"][-1] == pytest.approx(ref["max_overlap"], rel=1e-6)
    # After the sphere has left, dissipated_energy is the kinetic energy the contact took.
    m = sphere_mass(impact.start("particle_radius"), impact.start("particle_density"))
    assert m == pytest.approx(ref["effective_mass"], rel=1e-12)
    assert r["dissipated_energy"][-1] == pytest.approx(0.5 * m * (v * v - v_out * v_out), rel=1e-8)


# 000 Table 6, e_0 = 1: plastic adhesive sticking velocity V_ys [m/s] of ammonium fluorescein on silicon
# (Table 5 materials) for a particle radius and a limiting contact pressure p_y.
TABLE_6 = [
    (2.45e-6, 30e6, 1.86),
    (1.72e-6, 30e6, 2.83),
    (3.445e-6, 25e6, 1.51),
    (1.29e-6, 25e6, 4.76),
]


@pytest.mark.parametrize("radius, p_y, paper", TABLE_6)
def test_sticking_velocity_through_the_fmu_reproduces_000_table_6(impact, cli, radius, p_y, paper):
    start = {"particle_radius": radius, "particle_yield_pressure": p_y}
    v_ys = sticking_velocity(impact, cli, start)
    # Table 6 prints two or three significant digits.
    assert rel(v_ys, paper) < 0.01, f"V_ys {v_ys} vs 000 Table 6 {paper}"
    closed_form = cli.analyze(impact.scene(start))["sticking_velocity"]
    assert rel(v_ys, closed_form) < 1e-5, f"V_ys {v_ys} vs 000 Eqs. 77-79 {closed_form}"


def pasha_table_4_2(impact) -> dict:
    scene = json.loads((REPO / "scenes" / "pasha_table_4_2.json").read_text())
    unknown = set(scene) - set(impact.variables)
    assert not unknown, f"scene keys that are not parameters of the FMU: {unknown}"
    return scene


def test_pasha_simplified_sticks_at_1_4_and_rebounds_at_1_7_m_s(impact, cli):
    # 004 Table 4.2 with the simplified Pasha law: sticking below ~1.6 m/s (read off a simulation plot).
    start = pasha_table_4_2(impact)
    assert start["contact_model"] == "pasha_simplified"
    assert not rebounds(impact, cli, start, 1.4)
    assert rebounds(impact, cli, start, 1.7)
    ref = cli.analyze(impact.scene(start), velocity=1.7)
    r = impact_run(impact, cli, start, 1.7)
    assert r["sphere_velocity"][-1] == pytest.approx(ref["rebound_velocity"], rel=1e-6)


def test_pasha_simplified_sticking_velocity_matches_the_energy_balance(impact, cli):
    start = pasha_table_4_2(impact)
    lo, hi = 1.0, 3.0
    v_s = sticking_velocity(impact, cli, start, lo, hi)
    assert 1.4 < v_s < 1.7
    energy_balance = cli.restitution_sticking_velocity(impact.scene(start), [lo, hi])
    assert rel(v_s, energy_balance) < 1e-5, f"{v_s} vs energy balance {energy_balance}"


# ---------------------------------------------------------------------------------------------------
# A vibrating wall


def test_sphere_on_a_vibrating_wall(impact, cli):
    """A damped sphere (e_0 = 0.5) under gravity lands on a wall vibrating at about 5 MHz with 20 nm
    amplitude (wall speed up to ~0.67 m/s), for 8 periods, in CS and ME."""
    amplitude, v0 = 2e-8, 0.5
    # The wall: a sine sampled on a grid exact in binary, linear in between, wall_velocity the exact
    # slope. (A binary grid keeps fmpy's communication steps free of rounding; see the xfail in
    # test_simulate.py for what rounding does to CS.)
    dt = power_of_two_below(1e-9)
    per_period, periods = 215, 8
    t = np.arange(per_period * periods + 1) * dt
    omega = 2 * math.pi / (per_period * dt)
    signals = wall_input(t, amplitude * np.sin(omega * t))
    v_wall = np.max(np.abs(signals["wall_velocity"]))
    start = {"gravity": 9.81, "initial_velocity": v0, "initial_gap": 2 * amplitude, "restitution_coefficient": 0.5}
    runs = {}
    for fmi_type in ("CoSimulation", "ModelExchange"):
        r = impact.simulate(fmi_type, start_values=start, input=signals, stop_time=t[-1], output_interval=4 * dt)
        assert r["time"][-1] == t[-1]
        for name in r.dtype.names:
            assert np.all(np.isfinite(r[name])), f"{fmi_type}: {name} not finite"
        assert r["max_overlap"][-1] > 0 and {1, 2} <= set(r["contact_state"])
        # History is consistent: the overlap never exceeds the largest overlap, which only grows.
        assert np.all(np.diff(r["max_overlap"]) >= 0)
        assert np.all(r["overlap"] <= r["max_overlap"][-1] * (1 + 1e-12))
        # The sphere never sinks into the wall deeper than one undamped impact at the largest relative
        # speed (its own plus twice the wall's), nor moves faster than that.
        v_bound = v0 + 2 * v_wall
        deepest = cli.analyze(impact.scene(start), velocity=v_bound)["max_overlap"]
        assert r["max_overlap"][-1] < deepest
        assert np.max(np.abs(r["sphere_velocity"])) < v_bound
        # The wall is below the sphere's centre by about a radius: the sphere is neither through the
        # wall nor lost (it came to the wall at 0.5 m/s).
        gap = r["sphere_position"] - signals_at(signals, r["time"]) - impact.start("particle_radius")
        assert np.min(gap) > -r["max_overlap"][-1] * (1 + 1e-6)
        runs[fmi_type] = r
    cs, me = runs["CoSimulation"], runs["ModelExchange"]
    assert me["max_overlap"][-1] == pytest.approx(cs["max_overlap"][-1], rel=0.01)
    assert me["plastic_overlap"][-1] == pytest.approx(cs["plastic_overlap"][-1], rel=0.01)


def signals_at(signals, times):
    """The wall displacement of an input table at the given times (linear interpolation)."""
    return np.interp(times, signals["time"], signals["wall_displacement"])


# ---------------------------------------------------------------------------------------------------
# ContactElement


def test_contact_element_loading_unloading_cycle(contact, cli):
    """Overlap -10 nm -> 50 nm -> -10 nm (beyond yield at ~13 nm, back past pull-off and detachment),
    default scene (000 Table 5, nan law), quasi-static, CS."""
    ref = cli.analyze(contact.scene())
    k_el, alpha_y, f_y, f_0, f_ce = (ref[k] for k in ("k_el", "alpha_y", "f_y", "f_0", "f_ce"))
    peak = 5e-8
    signals = wall_input([0.0, 1.0, 2.0], [-1e-8, peak, -1e-8])
    r = contact.simulate("CoSimulation", input=signals, stop_time=2.0, output_interval=2.0**-7)
    alpha, f, state = r["overlap"], r["force"], r["contact_state"]
    top = int(np.argmax(alpha))
    assert alpha[top] == pytest.approx(peak, rel=1e-12)
    # At the peak itself the wall already moves back (wall_velocity < 0): the branch entered is elastic.
    load, unload = slice(0, top), slice(top, None)

    # Loading: separated, elastic (the line from -f_0 at first contact, 000 Eq. 17), plastic beyond yield.
    assert set(state[load][alpha[load] < 0]) == {0}
    elastic = (alpha[load] > 0) & (alpha[load] < alpha_y)
    assert elastic.any() and set(state[load][elastic]) == {1}
    assert np.allclose(f[load][elastic], k_el * alpha[load][elastic] - f_0, rtol=0, atol=1e-9 * f_0)
    assert set(state[load][alpha[load] > alpha_y * (1 + 1e-9)]) == {2}
    # 000 Eq. 18: f = f_y + k_p (alpha - alpha_y), k_p = k_el by default.
    plastic = alpha[load] > alpha_y * (1 + 1e-9)
    assert np.allclose(f[load][plastic], f_y + k_el * (alpha[load][plastic] - alpha_y), rtol=1e-9, atol=0)

    # Unloading: elastic, then adhesive beyond the pull-off point, then detached for good.
    order = [s for i, s in enumerate(state[unload]) if i == 0 or s != state[unload][i - 1]]
    assert order == [1, 3, 0], f"branches while unloading: {order}"
    assert state[-1] == 0 and f[-1] == 0.0

    # Residual plastic overlap (000 Eqs. 16, 46): alpha_p = (1 - k_p/k_e) alpha_max + (k_p alpha_y - f_y)/k_e,
    # k_e = k_el sqrt(alpha_max/alpha_y).
    k_e = k_el * math.sqrt(peak / alpha_y)
    alpha_p = (1 - k_el / k_e) * peak + (k_el * alpha_y - f_y) / k_e
    assert r["plastic_overlap"][-1] > 0
    assert r["plastic_overlap"][-1] == pytest.approx(alpha_p, rel=1e-9)
    assert r["plastic_overlap"][-1] > r["plastic_overlap"][0]
    assert r["max_overlap"][-1] == pytest.approx(peak, rel=1e-12)
    # Plastic flattening strengthens the contact: the pull-off force grows beyond f_ce.
    assert r["pull_off_force"][0] == pytest.approx(f_ce, rel=1e-12)
    assert r["pull_off_force"][-1] > f_ce

    # Energy: positive after the cycle and equal to the loop integral of the law along the same path.
    curve = cli.curve(contact.scene(), [-1e-8, peak, -1e-8], points=20000)
    loop = np.sum(0.5 * (curve["force_N"][1:] + curve["force_N"][:-1]) * np.diff(curve["overlap_m"]))
    assert r["dissipated_energy"][-1] > 0
    assert r["dissipated_energy"][-1] == pytest.approx(loop, rel=1e-4)

    # Continuity: in contact, the force changes by no more than the stiffest branch allows (the law
    # jumps only at contact formation and at detachment, 000 Fig. 1).
    both = (state[1:] != 0) & (state[:-1] != 0)
    jump = np.abs(np.diff(f))[both]
    allowed = k_e * np.abs(np.diff(alpha))[both]
    assert both.sum() > 100
    assert np.all(jump <= allowed * (1 + 1e-9) + 1e-18), f"largest excess {np.max(jump - allowed)} N"


def test_jkr_force_detachment_through_the_fmu_sticks_at_0_703_of_the_displacement_reading(impact, cli):
    """jkr_detachment (docs/models.md, JKR): the contact ended at the force minimum -f_c (LAMMPS's
    reading) keeps 0.494 of W_JKR; through the FMU (CS, adaptive) each reading sticks at its own energy
    balance, and their ratio is 0.703."""
    velocities = {}
    for reading in ("displacement", "force"):
        start = {"contact_model": "jkr", "jkr_detachment": reading}
        lo, hi = 0.2, 1.0
        velocities[reading] = sticking_velocity(impact, cli, start, lo, hi, iterations=30)
        balance = cli.restitution_sticking_velocity(impact.scene(start), [lo, hi])
        assert rel(velocities[reading], balance) < 1e-5, f"{reading}: {velocities[reading]} vs energy balance {balance}"
    assert velocities["force"] / velocities["displacement"] == pytest.approx(0.703, abs=5e-4)
    # The displacement reading is 000 Eq. 73's V_s.
    assert rel(velocities["displacement"], cli.analyze(impact.scene({"contact_model": "jkr"}))["jkr_sticking_velocity"]) < 2e-3


@pytest.mark.parametrize("variant", ["pasha", "mercurydpm"])
@pytest.mark.parametrize("v", [5.0, 8.0, 15.0, 20.0])
def test_each_luding_reading_rebounds_through_the_fmu_as_its_energy_balance(impact, cli, variant, v):
    """luding_variant (docs/models.md, Luding): 004 Table 4.2's Luding values, impacts at 5 m/s (below
    alpha*: the readings agree, both stick), 8 m/s (beyond: 004's reading, loading on k_1, sticks up to
    13.75 m/s; the peers', on k_2hat, rebounds above 5.52 m/s), 15 and 20 m/s; the CS exact integrator
    against the closed form of each reading."""
    start = {**pasha_table_4_2(impact), "contact_model": "luding", "luding_variant": variant}
    ref = cli.analyze(impact.scene(start), velocity=v)
    r = impact_run(impact, cli, start, v)
    assert ref["sticks"] == (v < {"pasha": 13.75, "mercurydpm": 5.52}[variant])
    if ref["sticks"]:
        assert r["contact_state"][-1] != 0
    else:
        assert r["contact_state"][-1] == 0
        assert r["sphere_velocity"][-1] == pytest.approx(ref["rebound_velocity"], rel=1e-8)
    assert r["max_overlap"][-1] == pytest.approx(ref["max_overlap"], rel=1e-8)


def test_the_peers_luding_reading_has_no_contact_adhesion_by_default_through_the_fmu(impact, cli):
    """With luding_variant = mercurydpm the start value 0 of luding_contact_adhesion_force ("derive it")
    gives f_0 = 0, the peers' law (docs/porting.md): the FMU's rebound at 8 m/s is the energy balance with
    an explicit f_0 = 0 (0.7237 on Table 4.2's values, sphere on a wall)."""
    start = {**pasha_table_4_2(impact), "contact_model": "luding", "luding_variant": "mercurydpm", "luding_contact_adhesion_force": 0.0}
    scene = {**impact.scene(start), "luding_contact_adhesion_force": 0.0}
    ref = cli.analyze(scene, velocity=8.0)
    assert ref["restitution"] == pytest.approx(0.7237, abs=1e-4)
    r = impact_run(impact, cli, start, 8.0)
    assert r["sphere_velocity"][-1] == pytest.approx(ref["rebound_velocity"], rel=1e-8)
