"""ContactElement in shear (issue 33): the wall's tangential displacement drives the law's tangential
spring with its Coulomb limit, as the bed's and the oblique impact's (docs/models.md, "ContactElement in
shear"). At a held overlap the spring is the classic spring-slider: F_t = k_t delta_t up to mu N, then on
the limit, unloading from the point of reversal with the same k_t. Its loop over a shear cycle of
amplitude A takes 4 mu N (A - mu N / k_t) (the area of the parallelogram), in Co-Simulation at any
communication step (the history is exact on a path at constant overlap) and in Model Exchange under
fmpy's CVode to the resolution of its integrator steps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from fmu_support import MessageLog

# Hertz-Mindlin on a rigid wall, so that k_t = 8 G* sqrt(R alpha) and N = f_n in closed form.
HERTZ = {"contact_model": "hertz", "wall_youngs_modulus": 0.0, "friction_coefficient": 0.3, "restitution_coefficient": 1.0}
ALPHA = 1e-8  # the held overlap [m]


def spring_slider(path, k, limit):
    """The spring-slider's force along a displacement path starting unloaded at path[0]."""
    f, out = 0.0, []
    for a, b in zip(path[:1] + path[:-1], path):
        f = min(max(f + k * (b - a), -limit), limit)
        out.append(f)
    return np.array(out)


class Sheared:
    """A ContactElement slave held at overlap ALPHA and driven along a tangential path step by step."""

    def __init__(self, contact, start_values, alpha=ALPHA):
        self.unit = contact
        self.fmu = contact.slave()
        contact.set_start_values(self.fmu, start_values)
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        self.set(alpha, 0.0)
        self.fmu.exitInitializationMode()
        self.t = 0.0

    def set(self, alpha, delta, rate=0.0):
        vr = self.unit.vr
        self.fmu.setReal([vr["wall_displacement"], vr["wall_velocity"], vr["wall_tangential_displacement"], vr["wall_tangential_velocity"]],
                         [alpha, 0.0, delta, rate])

    def read(self):
        vr = self.unit.vr
        f_t, f_n, work = self.fmu.getReal([vr["tangential_force"], vr["force"], vr["dissipated_energy"]])
        return f_t, f_n, work, self.fmu.getBoolean([vr["sliding"]])[0]

    def step(self, delta, alpha=ALPHA):
        self.set(alpha, delta)
        before = self.read()
        self.fmu.doStep(self.t, 1e-3)
        self.t += 1e-3
        after = self.read()
        assert after == before, "the output at an input is the value the step gives there (feed-through)"
        return after

    def free(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


def hertz_constants(contact, start_values):
    """k_t = 8 G* a and mu N = mu 4/3 E* sqrt(R) alpha^(3/2) of the element's rigid-wall Hertz contact."""
    s = {n: contact.start(n) for n in ("particle_radius", "particle_youngs_modulus", "particle_poisson_ratio")} | start_values
    r, e, nu = s["particle_radius"], s["particle_youngs_modulus"], s["particle_poisson_ratio"]
    e_star, g_star = e / (1 - nu * nu), e / (2 * (1 + nu)) / (2 - nu)
    a = math.sqrt(r * ALPHA)
    return 8 * g_star * a, start_values["friction_coefficient"] * 4 / 3 * e_star * math.sqrt(r) * ALPHA**1.5


def test_hertz_mindlin_sticks_at_8_g_a_and_slides_at_mu_f_n(contact):
    k, limit = hertz_constants(contact, HERTZ)
    e = Sheared(contact, HERTZ)
    try:
        d1 = 0.1 * limit / k
        f_t, f_n, _, sliding = e.step(d1)
        assert f_t == pytest.approx(k * d1, rel=1e-12) and not sliding
        assert f_n == pytest.approx(limit / HERTZ["friction_coefficient"], rel=1e-12)
        f_t, _, _, sliding = e.step(3 * limit / k)
        assert f_t == pytest.approx(limit, rel=1e-12) and sliding
        # Reversal: unloads at once from the limit with k_t (the point reached is the history).
        f_t, _, _, sliding = e.step(3 * limit / k - d1)
        assert f_t == pytest.approx(limit - k * d1, rel=1e-12) and not sliding
    finally:
        e.free()


@pytest.mark.parametrize("points_per_quarter", [3, 40, 1000])
def test_a_shear_cycle_dissipates_the_spring_sliders_loop_at_any_step(contact, points_per_quarter):
    """0 -> A -> -A -> A at the held overlap, A = 3 mu N / k_t: the force at every point is the
    spring-slider's and the work over the closed loop (-A -> A -> -A ... here A -> -A -> A) is
    4 mu N (A - mu N / k_t), whatever the communication step."""
    k, limit = hertz_constants(contact, HERTZ)
    amp = 3 * limit / k
    q = np.linspace(0, amp, points_per_quarter + 1)[1:]
    path = list(q) + list(amp - 2 * np.linspace(0, amp, 2 * points_per_quarter + 1)[1:]) + list(-amp + 2 * np.linspace(0, amp, 2 * points_per_quarter + 1)[1:])
    e = Sheared(contact, HERTZ)
    try:
        rows = [e.step(d) for d in path]
    finally:
        e.free()
    f_t = np.array([r[0] for r in rows])
    assert f_t == pytest.approx(spring_slider([0.0] + path, k, limit)[1:], rel=1e-11, abs=1e-12 * limit)
    work_at_a = rows[points_per_quarter - 1][2]
    loop = rows[-1][2] - work_at_a
    assert loop == pytest.approx(4 * limit * (amp - limit / k), rel=1e-11)
    assert {r[3] for r in rows} == {True, False}


def test_nan_law_loop_is_the_spring_sliders_of_its_own_k_t_and_limit(contact):
    """Nan's linear law (k_t = 4 G*/E* k_n, the limit shifted by the adhesion, 000 Eqs. 22-23) at a held
    overlap on its loading branch: the loop closes with the stiffness and limit the element shows."""
    sv = {"contact_model": "nan", "friction_coefficient": 0.5, "restitution_coefficient": 1.0}
    e = Sheared(contact, sv, alpha=4e-8)
    try:
        d0 = 1e-12
        k = e.step(d0, alpha=4e-8)[0] / d0
        top = e.step(1e-6, alpha=4e-8)
        limit = top[0]
        assert k > 0 and limit > 0 and limit < k * 1e-6 and top[3]
        # A closed loop between 1e-6 - 2 A and 1e-6 (on the limit at both ends).
        amp = 4 * limit / k
        rows = [e.step(d, alpha=4e-8) for d in (1e-6 - 2 * amp, 1e-6)]
    finally:
        e.free()
    assert [r[0] for r in rows] == pytest.approx([-limit, limit], rel=1e-12)
    assert rows[1][2] - top[2] == pytest.approx(4 * limit * (amp - limit / k), rel=1e-10)


def test_unloading_the_normal_load_takes_a_sliding_spring_down_with_its_limit(contact):
    k, limit = hertz_constants(contact, HERTZ)
    e = Sheared(contact, HERTZ)
    try:
        e.step(3 * limit / k)
        for alpha in np.linspace(ALPHA, 0.2 * ALPHA, 9):
            f_t, f_n, _, _ = e.step(3 * limit / k, alpha=alpha)
            assert abs(f_t) <= HERTZ["friction_coefficient"] * f_n * (1 + 1e-12)
        assert f_t == pytest.approx(HERTZ["friction_coefficient"] * f_n, rel=1e-12)
        # Out of contact the spring is gone; back in contact it starts unloaded.
        assert e.step(3 * limit / k, alpha=-1e-9)[0] == 0.0
        f_t, *_ = e.step(3 * limit / k + 1e-12, alpha=ALPHA)
        assert f_t == pytest.approx(k * 1e-12, rel=1e-9)
    finally:
        e.free()


def test_without_tangential_inputs_the_normal_outputs_are_those_without_friction(contact):
    """The tangential spring never changes the normal contact: along a loading-unloading path with the
    tangential inputs at 0, friction 0.5 and 0 give the same normal outputs to the bit, and no
    tangential force."""
    outs = []
    for mu in (0.0, 0.5):
        e = Sheared(contact, {"contact_model": "nan", "friction_coefficient": mu}, alpha=0.0)
        rows = []
        for alpha in list(np.linspace(0, 5e-9, 7)) + list(np.linspace(5e-9, -1e-9, 7)):
            e.set(alpha, 0.0)
            e.fmu.doStep(e.t, 1e-3)
            e.t += 1e-3
            rows.append(e.read())
        e.free()
        outs.append(rows)
    assert [r[1:3] for r in outs[0]] == [r[1:3] for r in outs[1]]
    assert all(r[0] == 0.0 and not r[3] for r in outs[1])


def test_a_saved_state_resumes_the_spring(contact):
    k, limit = hertz_constants(contact, HERTZ)
    e = Sheared(contact, HERTZ)
    try:
        e.step(2 * limit / k)
        saved, t = e.fmu.getFMUstate(), e.t
        after = [e.step(d) for d in (limit / k, 0.0)]
        e.fmu.setFMUstate(saved)
        e.t = t
        again = [e.step(d) for d in (limit / k, 0.0)]
        assert again == after
        assert after[0][0] == pytest.approx(0.0, abs=1e-12 * limit)  # limit - k (2L/k - L/k) = 0
        e.fmu.freeFMUstate(saved)
    finally:
        e.free()


def test_a_tangential_input_that_is_not_finite_is_refused_by_name(contact):
    """The glue refuses it at fmi2SetReal, naming the input; the element goes on with the last value."""
    log = MessageLog()
    fmu = contact.slave("nan", log)
    try:
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        with pytest.raises(FMICallException):
            fmu.setReal([contact.vr["wall_tangential_displacement"]], [float("nan")])
        assert any("`wall_tangential_displacement`" in r.message and "not a finite number" in r.message for r in log.records)
        fmu.exitInitializationMode()
        fmu.doStep(0.0, 1e-3)
        assert fmu.getReal([contact.vr["tangential_force"]]) == [0.0]
    finally:
        fmu.freeInstance()


def test_model_exchange_follows_a_sinusoidal_shear_to_its_integrator_steps(contact):
    """fmpy's CVode in Model Exchange, delta_t = A sin(2 pi t / T) at the held overlap: the force is the
    spring-slider's along the input path; the sliding spring keeps the point it reaches at every completed
    integrator step, so a reversal is placed within one of them (where a sine's top is flat)."""
    k, limit = hertz_constants(contact, HERTZ)
    amp, period = 3 * limit / k, 1.0
    t = np.linspace(0, 1.5 * period, 3001)
    delta = amp * np.sin(2 * np.pi * t / period)
    signal = np.zeros(len(t), dtype=[("time", float), ("wall_displacement", float), ("wall_tangential_displacement", float),
                                      ("wall_tangential_velocity", float)])
    signal["time"], signal["wall_displacement"], signal["wall_tangential_displacement"] = t, ALPHA, delta
    signal["wall_tangential_velocity"] = amp * 2 * np.pi / period * np.cos(2 * np.pi * t / period)
    r = contact.simulate("ModelExchange", start_values=HERTZ, stop_time=1.5 * period, output_interval=period / 500, input=signal)
    expected = spring_slider(list(np.interp(r["time"], t, delta)), k, limit)
    assert np.max(np.abs(r["tangential_force"] - expected)) < 1e-6 * limit
    assert r["sliding"].any() and not r["sliding"].all()
