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
//!   event too. Indicators carry a small hysteresis (docs/architecture.md, "Dynamics and events"), so an event lands just beyond its bound.
//! - Between events, trial evaluations stay on the accepted branch and continue it smoothly past its ends
//!   (`force`); a branch decided from the trial state would be a jump no indicator announces.

use crate::law::damping::NormalDamping;
use crate::law::{AnyHistory, AnyLaw, Branch, Evaluation, NormalLaw};
use crate::numeric::tanh_sinh;
use serde::{Deserialize, Serialize};

/// Indicator hysteresis, in units of the nominal overlap (or nominal rate): an indicator crosses zero
/// this far beyond its bound, so that the state an event is located at lies strictly on the law's other
/// side, and an indicator is never exactly 0 right after the event.
pub const HYSTERESIS: f64 = 1e-10;
/// A state this many ulps from a bound of its branch is on the bound (the rounding of the law's formula
/// for the bound): moving out of it, the branch is the one beyond.
const BOUND_ULPS: f64 = 8.0;
/// How close below the largest overlap an accepted point still counts as being at it (the turning-point
/// indicator watches the rate there), in units of the nominal overlap.
const AT_MAX_OVERLAP: f64 = 2e-9;
/// Model Exchange's lead on a vertical branch end (`NormalLaw::vertical_end`), as a fraction of the
/// zone's width: the lower indicator fires this far above the end, and the rest is crossed in Event Mode
/// by its exact work (`Sphere::accept_crossing`). Measured with benches/me_all_laws.py (docs/models.md).
pub const VERTICAL_END_LEAD: f64 = 1e-2;

/// One contact followed in time: its law, its damping, the accepted state and the indicator scales.
#[derive(Debug, Clone)]
pub struct Contact {
    /// The normal contact law.
    pub law: AnyLaw,
    /// The normal damping model.
    pub damping: NormalDamping,
    /// Overlap scale of indicators and tolerances [m].
    pub alpha_nominal: f64,
    /// Overlap-rate scale of the rate indicators [m/s].
    pub rate_nominal: f64,
    /// The evaluation at the accepted state: its branch, interval and the history accepted (the one place
    /// the contact keeps its history; `history()`).
    pub accepted: Evaluation<AnyHistory>,
    /// The overlap at which `accepted` was evaluated [m].
    pub accepted_alpha: f64,
    /// Largest overlap reached [m] (NEG_INFINITY before any).
    pub max_overlap: f64,
    /// Model Exchange: the lower indicator of a branch that ends in a vertical tangent fires
    /// `VERTICAL_END_LEAD` of its zone early (`vertical_end_ahead`). Off for the Co-Simulation
    /// integrators and ContactElement, whose overlap is an input.
    pub lead_vertical_ends: bool,
}

/// What a contact remembers beyond its parameters: the part of a saved FMU state.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct Memory {
    /// The evaluation at the accepted state (`Contact::accepted`).
    pub accepted: Evaluation<AnyHistory>,
    /// The overlap at which `accepted` was evaluated [m].
    pub accepted_alpha: f64,
    /// Largest overlap reached [m] (NEG_INFINITY before any).
    pub max_overlap: f64,
}

/// An event indicator g = constant + overlap * alpha + rate * (d alpha / dt), positive while the accepted
/// branch holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Constant term (dimensionless).
    pub constant: f64,
    /// [1/m]
    pub overlap: f64,
    /// [s/m]
    pub rate: f64,
}

impl Line {
    /// An indicator that never changes sign.
    pub const INACTIVE: Line = Line { constant: 1.0, overlap: 0.0, rate: 0.0 };

    /// The indicator's value at overlap `alpha` [m] and overlap rate `rate` [m/s].
    pub fn at(&self, alpha: f64, rate: f64) -> f64 {
        self.constant + self.overlap * alpha + self.rate * rate
    }

    /// Whether the indicator depends on overlap or rate (and so can change sign).
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
    /// The branch the force was evaluated on.
    pub branch: Branch,
}

impl ContactForce {
    /// Law force plus damping force [N].
    pub fn total(&self) -> f64 {
        self.law + self.damping
    }
}

impl Contact {
    /// A contact that has not yet accepted a state, with indicator scales `alpha_nominal` [m] and
    /// `rate_nominal` [m/s]; the unit then accepts its initial state. The vertical-end lead is off.
    pub fn new(law: AnyLaw, damping: NormalDamping, alpha_nominal: f64, rate_nominal: f64) -> Contact {
        // A placeholder until the unit accepts its initial state.
        let accepted = Evaluation::separated(f64::INFINITY, law.initial_history());
        Contact {
            law,
            damping,
            alpha_nominal,
            rate_nominal,
            accepted,
            accepted_alpha: f64::NAN,
            max_overlap: f64::NEG_INFINITY,
            lead_vertical_ends: false,
        }
    }

    /// The history accepted so far.
    pub fn history(&self) -> &AnyHistory {
        &self.accepted.history
    }

    /// What the contact remembers, for a saved FMU state (`remember` takes it back).
    pub fn memory(&self) -> Memory {
        Memory { accepted: self.accepted, accepted_alpha: self.accepted_alpha, max_overlap: self.max_overlap }
    }

    /// Takes back a saved memory; refuses one of another law, and one no contact of these parameters
    /// can have been in (a corrupted state whose checksum was repaired): overlaps beyond a thousand
    /// radii, or a force a thousand times the force of crushing the sphere to half its radius.
    pub fn remember(&mut self, m: Memory) -> Result<(), String> {
        // The indicator scale is a thousandth of R* (units::contact_parts::build).
        let radius = 1e3 * self.alpha_nominal;
        if std::mem::discriminant(&m.accepted.history) != std::mem::discriminant(&self.law.initial_history()) {
            return Err("the saved state belongs to another contact_model than the parameters".into());
        }
        let fresh = self.law.initial_history();
        let crush = self.law.evaluate(0.5 * radius, &fresh).force.abs().max(self.law.evaluate(0.0, &fresh).force.abs());
        let force_limit = 1e3 * crush.max(f64::MIN_POSITIVE);
        let overlap_limit = 1e3 * radius;
        let force = self.law.evaluate(m.accepted_alpha, &m.accepted.history).force;
        let pull_off = self.law.pull_off_force(&m.accepted.history);
        let plastic = self.law.plastic_overlap(&m.accepted.history);
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
        self.accepted = m.accepted;
        self.accepted_alpha = m.accepted_alpha;
        self.max_overlap = m.max_overlap;
        Ok(())
    }

    /// Force at overlap `alpha` and overlap rate `rate` on the accepted branch (a trial: nothing kept).
    ///
    /// Between events the right-hand side must not switch on the trial state (FMI 2.0 Sec. 3.1; docs/architecture.md, "Dynamics and events"):
    /// a solver evaluates states past a bound before it locates the event there, and a jump no indicator
    /// announces makes CVode fail its error test. So where the law puts `alpha` on another branch than the
    /// accepted one, the accepted branch goes on as its tangent at the bound it crossed (the exact line for
    /// the piecewise-linear laws); branch, history and discrete outputs change only in `accept`.
    pub fn force(&self, alpha: f64, rate: f64) -> ContactForce {
        self.state_at(alpha, rate).0
    }

    /// `force`, and the history the accepted branch has at `alpha` (growing with plastic loading): what
    /// the units report as pull-off force and plastic overlap between events.
    pub fn state_at(&self, alpha: f64, rate: f64) -> (ContactForce, AnyHistory) {
        let (e, law_force, at) = self.on_accepted_branch(alpha);
        (self.with_damping(&e, law_force, at, rate), e.history)
    }

    /// Force at overlap `alpha` with the law's own branch there and the accepted history, as a DEM force
    /// loop evaluates it (the `verlet` baseline): the branch may differ from the accepted one.
    pub fn law_force(&self, alpha: f64, rate: f64) -> ContactForce {
        let e = self.law.evaluate(alpha, &self.accepted.history);
        self.with_damping(&e, e.force, alpha, rate)
    }

    /// The damping force of 000 Eqs. 24-26 on the branch of `e` (evaluated at overlap `at`).
    fn with_damping(&self, e: &Evaluation<AnyHistory>, law_force: f64, at: f64, rate: f64) -> ContactForce {
        let damping = if e.branch.in_contact() {
            let k = self.law.damping_stiffness(at, &e.history, e.stiffness);
            self.damping.force(k, self.law.has_yielded(&e.history), rate)
        } else {
            0.0
        };
        ContactForce { law: law_force, damping, branch: e.branch }
    }

    /// The accepted branch at `alpha`: the law's evaluation where the law agrees, else the tangent
    /// continued from the end of the accepted interval on `alpha`'s side. Returns the evaluation that
    /// stands for the branch, the law force and the overlap at which that evaluation was made.
    fn on_accepted_branch(&self, alpha: f64) -> (Evaluation<AnyHistory>, f64, f64) {
        let a = &self.accepted;
        let e = self.law.evaluate(alpha, &self.accepted.history);
        if e.branch == a.branch || !self.accepted_alpha.is_finite() {
            return (e, e.force, alpha);
        }
        // The end of the accepted interval toward alpha (a moving bound is the accepted point itself).
        let end = if alpha > self.accepted_alpha { a.upper } else { a.lower };
        let mut candidates = [end, f64::NAN];
        if end.is_finite() {
            // The law's inequality may put the end itself on the other side: one ulp inside then.
            candidates[1] = if alpha > self.accepted_alpha { next_down(end) } else { next_up(end) };
        }
        let on_end = candidates
            .into_iter()
            .filter(|b| b.is_finite())
            .map(|b| (b, self.law.evaluate(b, &self.accepted.history)))
            .find(|(_, eb)| eb.branch == a.branch);
        let (b, eb) = on_end.unwrap_or((self.accepted_alpha, *a));
        // A vertical tangent (JKR at detachment) continues flat.
        let k = if eb.stiffness.is_finite() { eb.stiffness } else { 0.0 };
        (Evaluation { stiffness: k, ..eb }, eb.force + k * (alpha - b), b)
    }

    /// The contact as it is after walking from the accepted overlap to `alpha` (a copy; this one is not
    /// changed): what `follow` and `accept` would make of these inputs, and the law's work on the way
    /// [J]. Co-Simulation's outputs at new inputs use it, so that they are the values the next step
    /// starts from.
    pub fn walked_to(&self, alpha: f64, rate: f64) -> (Contact, f64) {
        let mut c = self.clone();
        let work = c.follow(alpha);
        c.accept(alpha, rate);
        (c, work)
    }

    /// Takes the state at `alpha`, moving with `rate`, into the history. Returns the branch before and after.
    ///
    /// The branch is the law's own at `alpha`, with its inequalities exactly as the paper writes them
    /// (000 Eq. 20: adhesive on alpha_fp <= alpha <= alpha_cp, detached below alpha_fp). Only where
    /// `alpha` is a point at which the branch ends in the direction of motion (the largest overlap, where
    /// plastic loading goes on; a bound reached by `follow`) is the branch the one just beyond, a few ulps
    /// further.
    pub fn accept(&mut self, alpha: f64, rate: f64) -> (Branch, Branch) {
        let before = self.accepted.branch;
        // First the history at alpha itself (a turning point of plastic loading keeps its alpha_max), then
        // the branch the motion goes into.
        let here = self.law.evaluate(alpha, &self.accepted.history);
        let dir = direction(rate);
        let mut point = alpha;
        let mut into = self.law.evaluate(alpha, &here.history);
        // The bound of the branch in the direction of motion, how far it lies ahead of `x` (<= 0: on or
        // behind it), and the next double in that direction.
        let bound = |e: &Evaluation<AnyHistory>| if dir > 0.0 { e.upper } else { e.lower };
        let ahead = |b: f64, x: f64| (b - x) * dir;
        let beyond = |x: f64| if dir > 0.0 { next_up(x) } else { next_down(x) };
        // On the bound within the rounding of the law's own formula for it (a few ulps), moving out of it:
        // step out by ulps until the law's own inequality (rounded as it computes it) agrees.
        let b = bound(&into);
        if dir != 0.0 && b.is_finite() && ahead(b, alpha) <= BOUND_ULPS * f64::EPSILON * alpha.abs().max(b.abs()) {
            for _ in 0..BOUND_ULPS as usize {
                let b = bound(&into);
                point = beyond(if ahead(b, point) > 0.0 { b } else { point });
                into = self.law.evaluate(point, &here.history);
                if ahead(bound(&into), point) > 0.0 {
                    break;
                }
            }
        }
        // The history is the one at alpha itself; the point beyond only names the branch and its bounds.
        // So accepting the same point twice changes nothing.
        into.history = here.history;
        self.accepted = into;
        self.accepted_alpha = point;
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
        } else if let Some((end, lead)) = self.vertical_end_ahead() {
            Line { constant: -(end + lead) * a, overlap: a, rate: 0.0 }
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
        let turning = if self.accepted_alpha >= self.max_overlap - AT_MAX_OVERLAP * self.alpha_nominal {
            Line { constant: 0.0, overlap: 0.0, rate: r }
        } else if self.max_overlap.is_finite() {
            Line { constant: self.max_overlap * a, overlap: -a, rate: 0.0 }
        } else {
            Line::INACTIVE
        };
        [lower, upper, turning]
    }

    /// Model Exchange's vertical branch end below the accepted point, when the lead is on: the end and
    /// the lead above it [m]. None once the accepted point lies in the lead (a crossing refused for want
    /// of energy, `Sphere::accept_crossing`): the indicator then watches the end itself.
    pub fn vertical_end_ahead(&self) -> Option<(f64, f64)> {
        if !self.lead_vertical_ends {
            return None;
        }
        let e = &self.accepted;
        let width = self.law.vertical_end(e.branch, &e.history)?;
        let lead = VERTICAL_END_LEAD * width;
        (e.lower.is_finite() && lead > 0.0 && self.accepted_alpha > e.lower + lead).then_some((e.lower, lead))
    }

    /// The accepted branch as a straight line with linear damping: force = stiffness alpha + offset +
    /// damping rate. Exact for the piecewise-linear laws (`AnyLaw::is_piecewise_linear`); for the others it
    /// is the tangent at the accepted point.
    pub fn branch_line(&self) -> BranchLine {
        let alpha = self.accepted_alpha;
        let e = self.law.evaluate(alpha, &self.accepted.history);
        let damping = if e.branch.in_contact() {
            let k = self.law.damping_stiffness(alpha, &e.history, e.stiffness);
            self.damping.coefficient(k, self.law.has_yielded(&e.history))
        } else {
            0.0
        };
        BranchLine { stiffness: e.stiffness, offset: e.force - e.stiffness * alpha, damping }
    }

    /// Between events, at a completed integrator step: where the accepted branch's lower bound is the
    /// accepted point itself (plastic loading, whose history grows with the overlap) and the overlap has
    /// moved on along that branch, the history takes the point reached, as a delay buffer would (FMI 2.0
    /// Sec. 3.2.2). The branch, its force and the indicators do not change; only the largest overlap is
    /// kept. A master that holds sampled inputs lets the overlap jump up and back between two events,
    /// and the peak it jumped to is then the peak of the history, as in Co-Simulation's walk. Returns the
    /// law's work along the way [J] (0 where nothing is kept).
    pub fn keep_growth(&mut self, alpha: f64) -> f64 {
        let e = &self.accepted;
        let growing = e.branch.in_contact() && e.lower == self.accepted_alpha && alpha > self.accepted_alpha && alpha < e.upper;
        if !growing || self.law.evaluate(alpha, &e.history).branch != e.branch {
            return 0.0;
        }
        self.follow(alpha)
    }

    /// Walks to `end`, a bound at which the accepted branch ends, and over it, taking the history the
    /// law gives beyond it (`accept` keeps the history of the bound itself, which for a contact that ends
    /// still says it is established). Returns the law's work on the way [J].
    pub fn cross(&mut self, end: f64) -> f64 {
        let work = self.follow(end);
        let beyond = self.law.evaluate(self.accepted_alpha, &self.accepted.history);
        if beyond.branch == self.accepted.branch {
            self.accepted.history = beyond.history;
        }
        work
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
                let h = self.accepted.history;
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

/// The next larger double (for finite x). `f64::next_up` is std from Rust 1.86; the crate builds on 1.80.
pub fn next_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

/// The next smaller double (for finite x).
pub fn next_down(x: f64) -> f64 {
    -next_up(-x)
}

/// +1, -1 or 0: the sign of a rate, the direction of motion.
fn direction(rate: f64) -> f64 {
    if rate > 0.0 {
        1.0
    } else if rate < 0.0 {
        -1.0
    } else {
        0.0
    }
}
