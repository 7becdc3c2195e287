"""ContactElement in Co-Simulation: the output at an input (direct feed-through, before fmi2DoStep) is
the value fmi2DoStep gives at the same input, everywhere, including within 1e-12 R* of contact,
separation and re-contact, where the branch follows 000 Eq. 20's inequalities exactly (adhesive on
alpha_fp <= alpha <= alpha_cp, detached below alpha_fp, re-established at alpha_c0)."""

from __future__ import annotations

import numpy as np
import pytest

OUTPUTS = ["force", "overlap", "max_overlap", "plastic_overlap", "pull_off_force"]
H = 1e-3


class Element:
    """A ContactElement slave driven input by input."""

    def __init__(self, contact, start_values=None):
        self.unit = contact
        self.fmu = contact.slave()
        contact.set_start_values(self.fmu, start_values or {})
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        self.fmu.setReal([contact.vr["wall_displacement"], contact.vr["wall_velocity"]], [-1e-8, 1e-8])
        self.fmu.exitInitializationMode()
        self.t = 0.0
        self.last = -1e-8
        self.real_vrs = [contact.vr[n] for n in OUTPUTS]

    def set(self, alpha: float):
        # The rate points along the path, as a master's would.
        rate = 1e-8 if alpha >= self.last else -1e-8
        self.fmu.setReal([self.unit.vr["wall_displacement"], self.unit.vr["wall_velocity"]], [alpha, rate])

    def outputs(self):
        return tuple(self.fmu.getReal(self.real_vrs)) + (self.fmu.getInteger([self.unit.vr["contact_state"]])[0],)

    def feed_through(self, alpha: float):
        """The outputs at this input without stepping (the history is not changed)."""
        self.set(alpha)
        return self.outputs()

    def step(self, alpha: float):
        """Feed-through, then the step at the same input; both output tuples."""
        before = self.feed_through(alpha)
        self.fmu.doStep(self.t, H)
        self.t += H
        self.last = alpha
        return before, self.outputs()

    def save(self):
        return (self.fmu.getFMUstate(), self.t, self.last)

    def restore(self, saved):
        self.fmu.setFMUstate(saved[0])
        self.t, self.last = saved[1], saved[2]

    def state_at(self, alpha: float) -> int:
        return self.feed_through(alpha)[-1]

    def switch(self, lo: float, hi: float) -> float:
        """The overlap in (lo, hi] where the feed-through's contact_state changes, to the last bit."""
        s_lo = self.state_at(lo)
        while True:
            mid = 0.5 * (lo + hi)
            if mid in (lo, hi):
                return hi
            if self.state_at(mid) == s_lo:
                lo = mid
            else:
                hi = mid

    def free(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


def test_feed_through_equals_the_step_on_a_random_path(contact):
    rng = np.random.default_rng(12)
    e = Element(contact)
    alpha, disagreements, states = -1e-8, [], set()
    for _ in range(1500):
        # Mostly steps of all scales about the current point, now and then a jump across the range.
        if rng.random() < 0.1:
            alpha = rng.uniform(-2e-8, 6e-8)
        else:
            alpha += rng.choice([-1, 1]) * 10.0 ** rng.uniform(-20, -8)
        before, after = e.step(alpha)
        states.add(after[-1])
        if before != after:
            disagreements.append((alpha, before, after))
    e.free()
    assert {0, 1, 2, 3} <= states, states
    assert not disagreements, disagreements[:3]


def test_switches_are_the_papers_inequalities_and_feed_through_agrees_next_to_them(contact, cli):
    d = cli.analyze(contact.scene())
    r_star = d["reduced_radius"]
    # Before yield (000 Sec. 2.1): alpha_c0 = 0, alpha_ce (Eq. 8), alpha_fe (Eq. 9).
    alpha_ce = d["alpha_0"] - d["f_ce"] / d["k_el"]
    alpha_fe = alpha_ce - 4.0 / 9.0 * d["f_ce"] / d["k_cl"]
    peak = 0.5 * d["alpha_y"]
    e = Element(contact)
    assert e.state_at(-1e-9) == 0
    # Contact: the branch switches exactly at alpha_c0 = 0 (000 Eq. 20, "cs = 0" on alpha < alpha_c0).
    contact_at = e.switch(-1e-9, peak)
    assert contact_at == 0.0
    e.step(peak)
    # Unloading: elastic -> adhesive at alpha_ce, adhesive -> detached below alpha_fe.
    adhesive_at = e.switch(peak, alpha_fe + 0.5 * (alpha_ce - alpha_fe))
    detach_at = e.switch(alpha_ce - 1e-12, -1e-8)
    assert adhesive_at == pytest.approx(alpha_ce, rel=1e-12, abs=1e-12 * r_star)
    assert detach_at == pytest.approx(alpha_fe, rel=1e-12, abs=1e-12 * r_star)
    assert e.state_at(np.nextafter(detach_at, 1.0)) == 3, "adhesive on alpha_fp <= alpha"
    # Next to each switch, from far in the path's direction down to the last bit: the step gives what the
    # feed-through said, and the branch is the inequality's.
    offsets = [1e-11 * r_star, 1e-12 * r_star, 1e-13 * r_star, 1e-15 * r_star]
    state = e.save()
    for bound, below, above in ((detach_at, 0, 3),):
        for off in offsets + [abs(bound) * 4e-16]:
            for alpha, want in ((bound - off, below), (bound + off, above)):
                e.restore(state)
                before, after = e.step(alpha)
                assert before == after, (alpha, before, after)
                assert after[-1] == want, f"alpha = {alpha:e} m ({(alpha - bound) / r_star:+.1e} R* from the switch): state {after[-1]}"
    # Re-contact after detaching: not before alpha_c0 = 0 (000 Fig. 2(d)).
    e.restore(state)
    e.step(-1e-8)
    recontact_at = e.switch(-1e-8, peak)
    assert recontact_at == 0.0
    for off in offsets:
        for alpha, want in ((-off, 0), (off, 1)):
            saved = e.save()
            before, after = e.step(alpha)
            assert before == after and after[-1] == want, (alpha, before, after)
            e.restore(saved)
            e.fmu.freeFMUstate(saved[0])
    e.fmu.freeFMUstate(state[0])
    e.free()
