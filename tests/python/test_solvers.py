"""The Co-Simulation integrators of ParticleWallImpact through fmpy (`solver`: exact, adaptive, verlet,
auto) and Model Exchange under fmpy's CVode against them, on the default scene (000 Table 5, Nan,
undamped, 3 m/s): the restitution each gives against the closed form, and the errors for bad choices."""

from __future__ import annotations

import pytest
from fmpy.fmi1 import FMICallException

from fmu_support import MessageLog

V = 3.0
STOP = 2e-7


def restitution(impact, fmi_type="CoSimulation", rtol=None, **start):
    r = impact.simulate(
        fmi_type,
        start_values={"initial_velocity": V, **start},
        stop_time=STOP,
        output_interval=1e-9,
        relative_tolerance=rtol,
        output=["sphere_velocity", "contact_state"],
    )
    assert r["contact_state"][-1] == 0, "the sphere must have left the wall"
    return r["sphere_velocity"][-1] / V


@pytest.fixture(scope="module")
def closed_form(impact, cli):
    return cli.analyze(impact.scene(), velocity=V)["restitution"]


def test_exact_is_the_closed_form_and_auto_chooses_it_for_nan(impact, closed_form):
    exact = restitution(impact, solver="exact")
    assert exact == pytest.approx(closed_form, rel=1e-9)
    assert restitution(impact) == exact, "auto must pick exact for the Nan law"


def test_adaptive_converges_to_exact_and_verlet_is_the_coarse_baseline(impact, closed_form):
    exact = restitution(impact, solver="exact")
    loose, tight = (abs(restitution(impact, solver="adaptive", tolerance=t) - exact) for t in (1e-5, 1e-10))
    assert tight < 1e-8 and tight < loose
    # Verlet at a DEM code's step (0.2 of the Rayleigh time) is off in the third digit; a step 200 times
    # shorter is closer but still above the adaptive solver at its default tolerance.
    coarse, fine = (abs(restitution(impact, solver="verlet", rayleigh_fraction=f) - exact) for f in (0.2, 0.001))
    assert 1e-3 < coarse / exact < 0.1
    assert fine < coarse and fine > tight


@pytest.mark.parametrize("rtol", [1e-6, 1e-8])
def test_model_exchange_agrees_with_cs_exact_to_the_solver_tolerance(impact, rtol):
    """CVode's error is global, about 10-100 times its local relative tolerance."""
    exact = restitution(impact, solver="exact")
    me = restitution(impact, "ModelExchange", rtol=rtol)
    assert abs(me - exact) < 100 * rtol * exact, f"ME {me} vs CS exact {exact} at rtol {rtol}"


def test_model_exchange_converges_as_its_tolerance_tightens(impact):
    exact = restitution(impact, solver="exact")
    errors = [abs(restitution(impact, "ModelExchange", rtol=rtol) - exact) for rtol in (1e-5, 1e-7, 1e-9)]
    assert errors[0] > errors[1] > errors[2], errors


def test_auto_chooses_adaptive_for_a_nonlinear_law(impact):
    auto = restitution(impact, contact_model="thornton_ning")
    assert auto == restitution(impact, contact_model="thornton_ning", solver="adaptive")


def _init_error(impact, log, values, *words):
    fmu = impact.slave("solver", log)
    fmu.setupExperiment(startTime=0.0)
    impact.set_start_values(fmu, values)
    fmu.enterInitializationMode()
    log.clear()
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    messages = [r.message for r in log.records]
    assert any(all(w in m for w in words) for m in messages), f"no message with {words}: {messages}"
    fmu.freeInstance()


def test_bad_solver_choices_are_refused_naming_the_parameter(impact):
    log = MessageLog()
    _init_error(impact, log, {"solver": "exact", "contact_model": "thornton_ning"}, "`solver`", "piecewise-linear", "thornton_ning")
    _init_error(impact, log, {"solver": "rk4"}, "`solver`", "rk4", "auto, exact, adaptive, verlet")
    _init_error(impact, log, {"solver": "verlet", "rayleigh_fraction": 0.0}, "`rayleigh_fraction`", "(0, 1]")
    # Above the declared maximum the setter itself refuses.
    fmu = impact.slave("fraction", log)
    log.clear()
    with pytest.raises(FMICallException):
        fmu.setReal([impact.vr["rayleigh_fraction"]], [2.0])
    assert any("rayleigh_fraction" in r.message for r in log.records), log.records
    fmu.freeInstance()
    # The unit is still usable afterwards.
    assert restitution(impact, solver="verlet", rayleigh_fraction=0.01) > 0
