"""Oblique impacts through FMI (ParticleWallImpact in Co-Simulation): the unit against the command-line
tool's `oblique` on Chung and Ooi's Test 4 sphere, the belt's sign conventions, the outputs after the
rebound, and Model Exchange against the adaptive Co-Simulation (docs/models.md, "Oblique
impacts")."""

from __future__ import annotations

import csv
import io
import json
import math
import subprocess

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from fmu_support import REPO, MessageLog

# The scene's rigid wall: the unit's default wall is 000 Table 5's silicon, so its modulus is set to 0
# (0 = rigid).
ALUMINA = json.loads((REPO / "scenes/chung_ooi_alumina.json").read_text()) | {"wall_youngs_modulus": 0.0}
SPEED, MU, RADIUS = 3.9, 0.092, 2.5e-3


def cli_oblique(cli, angle: float, *extra: str) -> dict:
    out = subprocess.run([str(cli.path), "oblique", str(REPO / "scenes/chung_ooi_alumina.json"), "--speed", str(SPEED),
                          "--angles", repr(angle), *extra], capture_output=True, text=True, check=True).stdout
    return {k: v if k in ("slid_throughout", "sticks", "mechanism") else float(v) for k, v in next(csv.DictReader(io.StringIO(out))).items()}


def unit_oblique(impact, angle: float, **start) -> dict:
    v_n, v_t = SPEED * math.cos(math.radians(angle)), SPEED * math.sin(math.radians(angle))
    r = impact.simulate(start_values={**ALUMINA, "initial_velocity": v_n, "initial_tangential_velocity": v_t, "initial_gap": 1e-9, **start},
                        stop_time=2e-5, output_interval=1e-7)
    return {name: r[name][-1] for name in r.dtype.names} | {"contact_state_max": int(r["contact_state"].max())}


@pytest.mark.parametrize("angle", [10.0, 20.0, 45.0])
def test_the_adaptive_unit_rebounds_as_the_command_line_tool(impact, cli, angle):
    """The unit's oblique adaptive integrator (solver adaptive, tolerance 1e-10) against the tool's at 1e-12:
    the rebound velocities and spin to 1e-6, the rebound angle of the centre, the energy taken."""
    ref = cli_oblique(cli, angle, "--solver", "adaptive", "--tolerance", "1e-12", "--rayleigh-fraction", "0.5")
    out = unit_oblique(impact, angle, solver="adaptive", tolerance=1e-10)
    assert out["contact_state_max"] > 0 and out["contact_state"] == 0
    assert out["sphere_velocity"] == pytest.approx(ref["normal_velocity_out_m_per_s"], rel=1e-6)
    assert out["tangential_velocity"] == pytest.approx(ref["tangential_velocity_out_m_per_s"], rel=1e-6)
    assert out["angular_velocity"] == pytest.approx(ref["angular_velocity_out_rad_per_s"], rel=1e-6)
    assert out["rebound_angle"] == pytest.approx(math.atan2(out["tangential_velocity"], out["sphere_velocity"]), rel=1e-12)
    assert out["dissipated_energy"] == pytest.approx(ref["kinetic_energy_lost_J"], rel=1e-5)
    assert out["tangential_force"] == 0.0 and not out["sliding"]


def test_the_verlet_unit_is_the_command_line_tools_verlet(impact, cli):
    """solver verlet at 0.01 of the Rayleigh step: the tool's Verlet to its own step error (1e-3 of the
    rebound, docs/benchmarks.md), since the unit cuts its communication steps into equal steps."""
    ref = cli_oblique(cli, 30.0)
    out = unit_oblique(impact, 30.0, solver="verlet", rayleigh_fraction=0.01)
    assert out["tangential_velocity"] == pytest.approx(ref["tangential_velocity_out_m_per_s"], rel=2e-3)
    assert out["angular_velocity"] == pytest.approx(ref["angular_velocity_out_rad_per_s"], rel=2e-3)


def test_a_belt_drags_the_sphere_forward_and_spins_it_backward(impact):
    """A sphere dropped straight onto a belt moving at +2 m/s along x, sliding throughout: the belt's
    friction gives it mu (1 + e) v_n of tangential velocity along +x, and a spin of -5/2 of that over R
    (its bottom is dragged forward), within the lever's alpha / 2R."""
    v_n = 1.0
    from fmpy.fmi2 import FMU2Slave

    fmu_log = MessageLog()
    fmu = FMU2Slave(guid=impact.md.guid, unzipDirectory=impact.unzipdir, modelIdentifier=impact.md.coSimulation.modelIdentifier, instanceName="belt")
    fmu.instantiate(callbacks=fmu_log.callbacks, loggingOn=True)
    impact.initialize(fmu, {**ALUMINA, "initial_velocity": v_n, "initial_gap": 1e-9, "solver": "adaptive"})
    vr = impact.vr
    fmu.setReal([vr["wall_tangential_velocity"]], [2.0])
    t, h = 0.0, 1e-7
    while t < 2e-5:
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        t += h
    v, v_t, w = fmu.getReal([vr["sphere_velocity"], vr["tangential_velocity"], vr["angular_velocity"]])
    fmu.freeInstance()
    e_n = v / v_n
    assert v_t == pytest.approx(MU * (1 + e_n) * v_n, rel=1e-6)
    assert -w * RADIUS / (2.5 * v_t) == pytest.approx(1.0, abs=2e-3)
    assert w < 0
    events = [r.message for r in fmu_log.records if r.category == "logEvents"]
    assert any("tangential motion and spin by the oblique adaptive integrator" in m for m in events), events


@pytest.mark.parametrize("angle", [5.0, 20.0, 45.0])
def test_model_exchange_rebounds_as_the_adaptive_co_simulation(impact, cli, angle):
    """fmpy's CVode in Model Exchange on Chung and Ooi's Test 4 sphere: the stick-slip switches are events
    (event_indicator_stick_slip), so the rebound is the oblique adaptive integrator's to CVode's
    tolerance (sticking then sliding at 5 deg, micro-slip at 20 deg, gross sliding at 45 deg)."""
    ref = cli_oblique(cli, angle, "--solver", "adaptive", "--tolerance", "1e-12", "--rayleigh-fraction", "0.5")
    v_n, v_t = SPEED * math.cos(math.radians(angle)), SPEED * math.sin(math.radians(angle))
    r = impact.simulate("ModelExchange", start_values={**ALUMINA, "initial_velocity": v_n, "initial_tangential_velocity": v_t, "initial_gap": 1e-9},
                        stop_time=2e-5, output_interval=1e-7, relative_tolerance=1e-8)
    assert r["contact_state"].max() > 0 and r["contact_state"][-1] == 0
    assert r["sphere_velocity"][-1] == pytest.approx(ref["normal_velocity_out_m_per_s"], rel=1e-5)
    assert r["tangential_velocity"][-1] == pytest.approx(ref["tangential_velocity_out_m_per_s"], rel=1e-5)
    assert r["angular_velocity"][-1] == pytest.approx(ref["angular_velocity_out_rad_per_s"], rel=1e-5)
    # The work is a state whose absolute tolerance is rtol times the approach's kinetic energy, a
    # thousand times the work: to 2e-4 at rtol 1e-8 (5 deg).
    assert r["dissipated_energy"][-1] == pytest.approx(ref["kinetic_energy_lost_J"], rel=1e-3)
    assert r["rebound_angle"][-1] == pytest.approx(math.atan2(r["tangential_velocity"][-1], r["sphere_velocity"][-1]), rel=1e-12)
    # Where the tool says the contact slid throughout, the unit slid at every output point in contact.
    # (At the output points: fmpy also records the rows before and after each event.)
    on_grid = np.isclose(r["time"] / 1e-7, np.round(r["time"] / 1e-7), rtol=0, atol=1e-6)
    in_contact = (r["contact_state"] > 0) & on_grid
    if ref["slid_throughout"] == "true":
        assert r["sliding"][in_contact].all()
    else:
        assert not r["sliding"][in_contact].all()


def test_model_exchange_on_a_belt_gives_the_gross_sliding_closed_form(impact):
    """The belt of the Co-Simulation test above, in Model Exchange: v_t = mu (1 + e_n) v_n."""
    v_n = 1.0
    signal = np.zeros(2, dtype=[("time", float), ("wall_tangential_velocity", float)])
    signal["time"], signal["wall_tangential_velocity"] = [0.0, 2e-5], 2.0
    r = impact.simulate("ModelExchange", start_values={**ALUMINA, "initial_velocity": v_n, "initial_gap": 1e-9},
                        stop_time=2e-5, output_interval=1e-7, relative_tolerance=1e-8, input=signal)
    e_n = r["sphere_velocity"][-1] / v_n
    assert r["tangential_velocity"][-1] == pytest.approx(MU * (1 + e_n) * v_n, rel=1e-6)
    assert -r["angular_velocity"][-1] * RADIUS / (2.5 * r["tangential_velocity"][-1]) == pytest.approx(1.0, abs=2e-3)


def test_model_exchange_refuses_a_rolling_friction_by_name(impact):
    log = MessageLog()
    fmu = impact.model("me", log)
    with pytest.raises(FMICallException):
        fmu.setReal([impact.vr["rolling_friction"]], [0.1])
    assert any("`rolling_friction`" in r.message and "Co-Simulation" in r.message for r in log.records), log.records
    # Zero is taken, and the normal impact runs.
    fmu.setReal([impact.vr["rolling_friction"]], [0.0])
    fmu.freeInstance()
    r = impact.simulate(fmi_type="ModelExchange", start_values={"initial_velocity": 3.0}, stop_time=2e-7, output_interval=1e-8)
    assert r["contact_state"][-1] == 0 and r["tangential_velocity"][-1] == 0.0


def test_rolling_friction_needs_verlet_and_is_refused_by_name_otherwise(impact):
    log = MessageLog()
    fmu = impact.slave("rolling", log)
    fmu.setupExperiment(startTime=0.0)
    impact.set_start_values(fmu, {"rolling_friction": 0.1, "solver": "adaptive"})
    fmu.enterInitializationMode()
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    assert any("`rolling_friction`" in r.message and "verlet" in r.message for r in log.records), log.records
    fmu.freeInstance()
