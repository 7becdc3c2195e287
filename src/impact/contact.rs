//! One contact followed in time: the law, its damping, and the history accepted so far. Both units and
//! every integrator share this bookkeeping:
//!
//! - Trial evaluations (Runge-Kutta stages, CVode's right-hand sides) use the accepted history and never
//!   change it.
//! - `accept` moves the history to the current overlap: at events and at accepted steps only.
//! - The branch interval of the accepted state gives two event indicators, positive inside the branch; a
//!   third is the overlap rate, so that every turning point (the largest overlap) is landed on.
//!   A bound that moves with the overlap (plastic loading, where alpha_max follows alpha) is watched through
//!   the sign of the overlap rate instead, so the turning point, where the history must be taken, is an
//!   event too. Indicators carry a small hysteresis (DESIGN 6), and an accepted state at a branch point is
//!   nudged in the direction of motion, so the branch just entered is the one the motion goes into.

use crate::law::damping::NormalDamping;
use crate::law::{AnyHistory, AnyLaw, Branch, Evaluation, NormalLaw};
use crate::numeric::tanh_sinh;
use serde::{Deserialize, Serialize};

/// Indicator hysteresis, in units of the nominal overlap (or nominal rate).
pub const HYSTERESIS: f64 = 1e-10;
/// The nudge into the branch the motion enters, in units of the nominal overlap.
pub const NUDGE: f64 = 1e-9;

#[derive(Debug, Clone)]
pub struct Contact {
    pub law: AnyLaw,
    pub damping: NormalDamping,
    /// Overlap scale of indicators and tolerances [m].
    pub alpha_nominal: f64,
    /// Overlap-rate scale of the rate indicators [m/s].
    pub rate_nominal: f64,
    pub history: AnyHistory,
    /// The evaluation at the accepted state (its branch and interval).
    pub accepted: Evaluation<AnyHistory>,
    /// The overlap at which `accepted` was evaluated [m].
    pub accepted_alpha: f64,
    /// Largest overlap reached [m] (NEG_INFINITY before any).
    pub max_overlap: f64,
}

/// What a contact remembers beyond its parameters: the part of a saved FMU state.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct Memory {
    pub history: AnyHistory,
    pub accepted: Evaluation<AnyHistory>,
    pub accepted_alpha: f64,
    pub max_overlap: f64,
}

/// An event indicator g = constant + overlap * alpha + rate * (d alpha / dt), positive while the accepted
/// branch holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    pub constant: f64,
    /// [1/m]
    pub overlap: f64,
    /// [s/m]
    pub rate: f64,
}

impl Line {
    /// An indicator that never changes sign.
    pub const INACTIVE: Line = Line { constant: 1.0, overlap: 0.0, rate: 0.0 };

    pub fn at(&self, alpha: f64, rate: f64) -> f64 {
        self.constant + self.overlap * alpha + self.rate * rate
    }

    pub fn is_active(&self) -> bool {
        self.overlap != 0.0 || self.rate != 0.0
    }
}

/// A branch of a piecewise-linear law with linear damping: f = stiffness alpha + offset + damping rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchLine {
    /// [N/m]
    pub stiffness: f64,
    /// [N]
    pub offset: f64,
    /// [N s/m]
    pub damping: f64,
}

/// Force of one trial evaluation.
#[derive(Debug, Clone, Copy)]
pub struct ContactForce {
    /// Elastic-plastic-adhesive force of the law [N].
    pub law: f64,
    /// Viscous damping force [N].
    pub damping: f64,
    pub branch: Branch,
}

impl ContactForce {
    pub fn total(&self) -> f64 {
        self.law + self.damping
    }
}

impl Contact {
    pub fn new(law: AnyLaw, damping: NormalDamping, alpha_nominal: f64, rate_nominal: f64) -> Contact {
        let history = law.initial_history();
        // A placeholder until the unit accepts its initial state.
        let accepted = Evaluation::separated(f64::INFINITY, history);
        Contact { law, damping, alpha_nominal, rate_nominal, history, accepted, accepted_alpha: f64::NAN, max_overlap: f64::NEG_INFINITY }
    }

    pub fn memory(&self) -> Memory {
        Memory { history: self.history, accepted: self.accepted, accepted_alpha: self.accepted_alpha, max_overlap: self.max_overlap }
    }

    /// Takes back a saved memory; refuses one of another law, and one no contact of these parameters
    /// can have been in (a corrupted state whose checksum was repaired): overlaps beyond a thousand
    /// radii, or a force a thousand times the force of crushing the sphere to half its radius.
    pub fn remember(&mut self, m: Memory) -> Result<(), String> {
        // The indicator scale is a thousandth of R* (units::contact_parts::build).
        let radius = 1e3 * self.alpha_nominal;
        if std::mem::discriminant(&m.history) != std::mem::discriminant(&self.law.initial_history()) {
            return Err("the saved state belongs to another contact_model than the parameters".into());
        }
        let fresh = self.law.initial_history();
        let crush = self.law.evaluate(0.5 * radius, &fresh).force.abs().max(self.law.evaluate(0.0, &fresh).force.abs());
        let force_limit = 1e3 * crush.max(f64::MIN_POSITIVE);
        let overlap_limit = 1e3 * radius;
        let force = self.law.evaluate(m.accepted_alpha, &m.history).force;
        let pull_off = self.law.pull_off_force(&m.history);
        let plastic = self.law.plastic_overlap(&m.history);
        let plausible = m.accepted_alpha.is_finite()
            && pull_off.is_finite()
            && pull_off.abs() <= force_limit
            && plastic.is_finite()
            && plastic.abs() <= overlap_limit
            && m.accepted_alpha.abs() <= overlap_limit
            && m.max_overlap <= overlap_limit
            && !m.max_overlap.is_nan()
            && force.is_finite()
            && force.abs() <= force_limit
            && m.accepted.force.is_finite()
            && m.accepted.force.abs() <= force_limit;
        if !plausible {
            return Err(format!(
                "the saved contact is not one these parameters allow (overlap {:e} m, force {force:e} N; limits {overlap_limit:e} m, {force_limit:e} N)",
                m.accepted_alpha
            ));
        }
        self.history = m.history;
        self.accepted = m.accepted;
        self.accepted_alpha = m.accepted_alpha;
        self.max_overlap = m.max_overlap;
        Ok(())
    }

    /// Force at overlap `alpha` and overlap rate `rate` with the accepted history (a trial: nothing kept).
    ///
    /// At the accepted point itself (within the nudge) the branch is the one the motion goes into: the
    /// law evaluated exactly at a branch point answers for the branch behind it (the elastic end of the
    /// line at alpha_max, where plastic loading goes on), and its damping there differs. Every step that
    /// starts at an accepted point would then see a jump in the damping force, and an error-controlled
    /// integrator would shrink its steps to nothing. There the accepted branch is extended linearly.
    pub fn force(&self, alpha: f64, rate: f64) -> ContactForce {
        let e = self.law.evaluate(alpha, &self.history);
        let a = &self.accepted;
        let at_accepted = (alpha - self.accepted_alpha).abs() <= 2.0 * NUDGE * self.alpha_nominal;
        let (e, law_force) = if at_accepted && e.branch != a.branch && a.stiffness.is_finite() {
            (*a, a.force + a.stiffness * (alpha - self.accepted_alpha))
        } else {
            (e, e.force)
        };
        let damping = if e.branch.in_contact() {
            let k = self.law.damping_stiffness(alpha, &e.history, e.stiffness);
            self.damping.force(k, self.law.has_yielded(&e.history), rate)
        } else {
            0.0
        };
        ContactForce { law: law_force, damping, branch: e.branch }
    }

    /// The branch at `alpha`: the trial branch, except at the accepted point itself, where it is the branch
    /// the motion goes into (plastic loading rather than the elastic end of the line just accepted).
    pub fn branch_at(&self, alpha: f64, rate: f64) -> Branch {
        if (alpha - self.accepted_alpha).abs() <= 2.0 * NUDGE * self.alpha_nominal {
            self.accepted.branch
        } else {
            self.force(alpha, rate).branch
        }
    }

    /// Takes the state at `alpha`, moving with `rate`, into the history. Returns the branch before and after.
    pub fn accept(&mut self, alpha: f64, rate: f64) -> (Branch, Branch) {
        let before = self.accepted.branch;
        // First the history at alpha itself (a turning point of plastic loading keeps its alpha_max), then
        // the branch the motion goes into.
        let here = self.law.evaluate(alpha, &self.history);
        let step = NUDGE * self.alpha_nominal * direction(rate);
        let mut into = if step == 0.0 { here } else { self.law.evaluate(alpha + step, &here.history) };
        let into_point = alpha + step;
        // The history is the one at alpha itself; the nudged evaluation only names the branch and its
        // bounds. So accepting the same point twice changes nothing.
        into.history = here.history;
        self.history = here.history;
        self.accepted = into;
        self.accepted_alpha = into_point;
        if alpha > self.max_overlap {
            self.max_overlap = alpha;
        }
        (before, into.branch)
    }

    /// The event indicators at `alpha`, `rate`: the lower and upper bound of the accepted branch (positive
    /// while it holds), and the overlap rate, whose sign change is a turning point (the largest overlap),
    /// or, below the largest overlap so far, the distance to it.
    /// Each active indicator carries the hysteresis.
    pub fn indicators(&self, alpha: f64, rate: f64) -> [f64; 3] {
        self.indicator_lines().map(|l| if l.is_active() { l.at(alpha, rate) + HYSTERESIS } else { l.at(alpha, rate) })
    }

    /// The event indicators as linear functions of overlap and rate, without hysteresis (the `exact`
    /// integrator solves for their zeros in closed form).
    pub fn indicator_lines(&self) -> [Line; 3] {
        let e = &self.accepted;
        let (a, r) = (1.0 / self.alpha_nominal, 1.0 / self.rate_nominal);
        let lower = if e.lower == self.accepted_alpha {
            Line { constant: 0.0, overlap: 0.0, rate: r }
        } else if e.lower.is_finite() {
            Line { constant: -e.lower * a, overlap: a, rate: 0.0 }
        } else {
            Line::INACTIVE
        };
        let upper = if e.upper == self.accepted_alpha {
            Line { constant: 0.0, overlap: 0.0, rate: -r }
        } else if e.upper.is_finite() {
            Line { constant: e.upper * a, overlap: -a, rate: 0.0 }
        } else {
            Line::INACTIVE
        };
        // Turning points matter where the overlap is the largest so far (max_overlap, and the end of
        // plastic loading); elsewhere (a sphere oscillating in its adhesive well, at rest under gravity)
        // watching the rate would only make events. There the indicator watches max_overlap itself, so
        // that a deeper peak (a second impact on a branch without a bound there) is landed on too.
        let turning = if self.accepted_alpha >= self.max_overlap - 2.0 * NUDGE * self.alpha_nominal {
            Line { constant: 0.0, overlap: 0.0, rate: r }
        } else if self.max_overlap.is_finite() {
            Line { constant: self.max_overlap * a, overlap: -a, rate: 0.0 }
        } else {
            Line::INACTIVE
        };
        [lower, upper, turning]
    }

    /// The accepted branch as a straight line with linear damping: force = stiffness alpha + offset +
    /// damping rate. Exact for the piecewise-linear laws (`AnyLaw::is_piecewise_linear`); for the others it
    /// is the tangent at the accepted point.
    pub fn branch_line(&self) -> BranchLine {
        let alpha = self.accepted_alpha;
        let e = self.law.evaluate(alpha, &self.history);
        let damping = if e.branch.in_contact() {
            let k = self.law.damping_stiffness(alpha, &e.history, e.stiffness);
            self.damping.coefficient(k, self.law.has_yielded(&e.history))
        } else {
            0.0
        };
        BranchLine { stiffness: e.stiffness, offset: e.force - e.stiffness * alpha, damping }
    }

    /// Follows a straight overlap path from the accepted overlap to `to`, accepting the history at every
    /// branch point on the way; returns the work of the law's force along it, the integral of f d alpha [J].
    /// A monotone path cannot turn, so stopping at each branch point is the exact history.
    pub fn follow(&mut self, to: f64) -> f64 {
        let mut at = self.accepted_alpha;
        if !at.is_finite() {
            self.accept(to, 0.0);
            return 0.0;
        }
        let dir = direction(to - at);
        if dir == 0.0 {
            return 0.0;
        }
        let mut work = 0.0;
        for _ in 0..10_000 {
            let e = self.accepted;
            let bound = if dir > 0.0 { e.upper } else { e.lower };
            let moving = bound == self.accepted_alpha;
            let end = if moving || !bound.is_finite() || (bound - to) * dir >= 0.0 { to } else { bound };
            if (end - at) * dir > 0.0 {
                let h = self.history;
                work += tanh_sinh(|x| self.law.evaluate(x, &h).force, at, end);
            }
            self.accept(end, dir);
            at = end;
            if end == to {
                break;
            }
        }
        work
    }
}

/// +1, -1 or 0: the sign of a rate, for the nudge.
fn direction(rate: f64) -> f64 {
    if rate > 0.0 {
        1.0
    } else if rate < 0.0 {
        -1.0
    } else {
        0.0
    }
}
