//! A sphere moving along the normal of a wall (the ParticleWallImpact unit). z is the height of the
//! sphere's lowest point (centre minus radius), v its velocity, both positive away from the wall; the
//! wall plane is at w, so the overlap is alpha = w - z and its rate w' - v. Newton: m v' = f - m g, with
//! f the contact force (positive pushes the sphere away) and g the gravity toward the wall.
//!
//! Co-simulation steps use one of three integrators (`Solver`): `exact` (closed-form motion on each branch
//! of a piecewise-linear law, `exact.rs`), `adaptive` (Dormand-Prince 5(4) with event location,
//! `adaptive.rs`) and `verlet` (fixed-step velocity Verlet, what DEM codes do, `verlet.rs`). Within a
//! communication step the wall moves with the velocity input: w(t) = w(t_0) + w'(t_0) (t - t_0). Where
//! the master moves the wall between steps by more than that, the contact walks the jump quasi-statically
//! (`Contact::follow`) before the step.

use super::contact::Contact;

/// The state of the sphere, also Model Exchange's continuous states in this order.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct State {
    /// z: height of the sphere's lowest point [m].
    pub bottom: f64,
    /// v: velocity, positive away from the wall [m/s].
    pub velocity: f64,
    /// W: work done on the contact, the integral of f d alpha [J].
    pub work: f64,
}

impl State {
    /// A state of height `bottom` [m], velocity `velocity` [m/s] and work `work` [J].
    pub fn new(bottom: f64, velocity: f64, work: f64) -> State {
        State { bottom, velocity, work }
    }

    /// [z, v, W], the order of the ME states.
    pub fn to_array(self) -> [f64; 3] {
        [self.bottom, self.velocity, self.work]
    }

    /// A state from [z, v, W], the order of the ME states (the first three entries; panics on fewer).
    pub fn from_slice(x: &[f64]) -> State {
        State { bottom: x[0], velocity: x[1], work: x[2] }
    }
}

impl From<[f64; 3]> for State {
    fn from(a: [f64; 3]) -> State {
        State::from_slice(&a)
    }
}

/// The Runge-Kutta arithmetic of `adaptive` runs over the three components by index.
impl std::ops::Index<usize> for State {
    type Output = f64;
    fn index(&self, i: usize) -> &f64 {
        match i {
            0 => &self.bottom,
            1 => &self.velocity,
            _ => &self.work,
        }
    }
}

impl std::ops::IndexMut<usize> for State {
    fn index_mut(&mut self, i: usize) -> &mut f64 {
        match i {
            0 => &mut self.bottom,
            1 => &mut self.velocity,
            _ => &mut self.work,
        }
    }
}

/// The wall's motion over one communication step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallMotion {
    /// Time at which the wall is at `position` (the start of the step) [s].
    pub t0: f64,
    /// Wall plane w at `t0` [m].
    pub position: f64,
    /// Wall velocity w', constant over the step [m/s].
    pub velocity: f64,
}

impl WallMotion {
    /// Wall plane w at time `t` [s], moving linearly from `t0` [m].
    pub fn at(&self, t: f64) -> f64 {
        self.position + self.velocity * (t - self.t0)
    }
}

/// The integrator of a co-simulation step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Solver {
    /// Closed-form motion on each branch; the piecewise-linear laws only.
    Exact,
    /// Dormand-Prince 5(4) with error control at `Sphere::tolerance`.
    Adaptive,
    /// Fixed-step velocity Verlet with this step [s].
    Verlet {
        /// Fixed step size [s].
        step: f64,
    },
}

impl Solver {
    /// The solver names of the `solver` parameter.
    pub const NAMES: [&'static str; 4] = ["auto", "exact", "adaptive", "verlet"];
}

/// A sphere moving along a wall normal, with its contact, integrator and counters.
#[derive(Debug, Clone)]
pub struct Sphere {
    /// Mass of the sphere [kg].
    pub mass: f64,
    /// Gravity toward the wall [m/s^2].
    pub gravity: f64,
    /// The contact with the wall.
    pub contact: Contact,
    /// The integrator of co-simulation steps.
    pub solver: Solver,
    /// Relative tolerance of the integrator; absolute tolerances are it times the nominal overlap and rate.
    pub tolerance: f64,
    /// Last step size the controller chose [s] (0 before the first step).
    pub last_step: f64,
    /// Counters for the logs and benchmarks: integrator steps (closed-form segments for `exact`) and
    /// branch events.
    pub steps: u64,
    /// Number of branch events.
    pub events: u64,
}

/// Why a step could not be completed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StepError {
    /// The state or force became non-finite.
    #[error("the sphere's state became non-finite at t = {t:e} s")]
    NotFinite {
        /// Time at which it happened [s].
        t: f64,
    },
    /// The step size fell below the resolution of time.
    #[error("the integrator's step size fell below the resolution of time at t = {t:e} s")]
    StepTooSmall {
        /// Time at which it happened [s].
        t: f64,
    },
    /// More steps than allowed in one communication step.
    #[error("more than {limit} integrator steps in one communication step (at t = {t:e} s); use shorter communication steps")]
    TooManySteps {
        /// Time at which the limit was reached [s].
        t: f64,
        /// The largest number of integrator steps allowed in one communication step.
        limit: u64,
    },
    /// The law switched branches without the state moving (branch intervals that do not meet).
    #[error("the contact switched branches repeatedly without moving at t = {t:e} s")]
    NoProgress {
        /// Time at which it happened [s].
        t: f64,
    },
}

pub(super) const MAX_STEPS: u64 = 10_000_000;

impl Sphere {
    /// A sphere of mass `mass` [kg] under gravity `gravity` toward the wall [m/s^2], with the step and
    /// event counters at 0.
    pub fn new(mass: f64, gravity: f64, contact: Contact, solver: Solver, tolerance: f64) -> Sphere {
        Sphere { mass, gravity, contact, solver, tolerance, last_step: 0.0, steps: 0, events: 0 }
    }

    /// Advances the state from `t` to `t_end` with the wall moving as `wall`.
    pub fn advance(&mut self, wall: &WallMotion, t: f64, t_end: f64, y: &mut State) -> Result<(), StepError> {
        self.advance_until(wall, t, t_end, y, false).map(|_| ())
    }

    /// Advances from `t` toward `t_end`, stopping at the first change of the contact state (the
    /// integer output: formation, the elastic-plastic switches, pull-off, detachment) on the way. Returns
    /// the time of that event, or None when the state reached `t_end` without one. `exact` and `adaptive`
    /// locate the event as they locate every branch switch; `verlet` at the end of its fixed step.
    pub fn advance_to_event(&mut self, wall: &WallMotion, t: f64, t_end: f64, y: &mut State) -> Result<Option<f64>, StepError> {
        self.advance_until(wall, t, t_end, y, true)
    }

    /// Advances from `t` [s] toward `t_end` [s] with the chosen solver, after walking a wall jump the
    /// master made between steps. With `stop_at_event` it stops at the first change of the contact state
    /// and returns its time (`advance_to_event`); else it runs to `t_end` (`advance`).
    pub fn advance_until(&mut self, wall: &WallMotion, t: f64, t_end: f64, y: &mut State, stop_at_event: bool) -> Result<Option<f64>, StepError> {
        self.follow_jump(wall, t, y);
        match self.solver {
            Solver::Exact => self.advance_exact(wall, t, t_end, y, stop_at_event),
            Solver::Adaptive => self.advance_adaptive(wall, t, t_end, y, stop_at_event),
            Solver::Verlet { step } => self.advance_verlet(step, wall, t, t_end, y, stop_at_event),
        }
    }

    /// The integer contact state of the accepted branch (the `contact_state` output).
    pub fn contact_state(&self) -> i32 {
        self.contact.accepted.branch.contact_state()
    }

    /// A wall the master moved between steps: the contact walks from the accepted overlap to the new one
    /// along a straight path (the sphere cannot move in no time), adding that path's work.
    pub fn follow_jump(&mut self, wall: &WallMotion, t: f64, y: &mut State) {
        let (alpha, rate) = self.overlap(wall, t, y);
        if self.jumped(wall, t, y) {
            y.work += self.contact.follow(alpha);
            self.contact.accept(alpha, rate);
        }
    }

    /// Whether the overlap at this state differs from the accepted one by more than the rounding of the
    /// absolute positions it is made of (a wall the master moved between steps).
    pub fn jumped(&self, wall: &WallMotion, t: f64, y: &State) -> bool {
        let (alpha, _) = self.overlap(wall, t, y);
        let from = self.contact.accepted_alpha;
        let resolution = 8.0 * f64::EPSILON * (wall.at(t).abs() + y.bottom.abs());
        from.is_finite() && (alpha - from).abs() > resolution
    }

    /// Overlap and overlap rate of a state at time t.
    pub fn overlap(&self, wall: &WallMotion, t: f64, y: &State) -> (f64, f64) {
        (wall.at(t) - y.bottom, wall.velocity - y.velocity)
    }

    /// dy/dt on the accepted branch and its continuation (`Contact::force`).
    pub fn derivatives(&self, wall: &WallMotion, t: f64, y: &State) -> State {
        let (alpha, rate) = self.overlap(wall, t, y);
        let f = self.contact.force(alpha, rate).total();
        State { bottom: y.velocity, velocity: f / self.mass - self.gravity, work: f * rate }
    }

    /// The event indicators at a state.
    pub fn indicators(&self, wall: &WallMotion, t: f64, y: &State) -> [f64; 3] {
        let (alpha, rate) = self.overlap(wall, t, y);
        self.contact.indicators(alpha, rate)
    }

    /// Accepts a state into the contact history; returns whether the branch changed.
    pub fn accept(&mut self, wall: &WallMotion, t: f64, y: &State) -> bool {
        let (alpha, rate) = self.overlap(wall, t, y);
        let (before, after) = self.contact.accept(alpha, rate);
        before != after
    }

    /// Model Exchange's event: `accept`, except in the lead above a vertical branch end
    /// (`Contact::vertical_end_ahead`), which the sphere crosses here, in no time, by the exact work of
    /// the law along it (`Contact::follow`) and of the damping force of the event's rate: the contact
    /// ends and the sphere leaves with the speed it would have at the end, from where it is. The time it
    /// saves is lead / speed (1e-13 s for the default JKR impact at 3 m/s); the rebound speed is
    /// unchanged. Refused, the state is accepted where it is (it turns inside the lead) and the indicator
    /// then watches the end itself. Returns whether the branch changed and whether `y` did.
    ///
    /// Why: the force there goes as f_d + c sqrt(alpha - alpha_d) (000 App. B), so the solution's higher
    /// derivatives are unbounded at the end, and a BDF solver with a minimum step (OMSimulator, 1e-12 s)
    /// fails its error test on the step that reaches it.
    pub fn accept_crossing(&mut self, wall: &WallMotion, t: f64, y: &mut State) -> (bool, bool) {
        let (alpha, rate) = self.overlap(wall, t, y);
        let before = self.contact.accepted.branch;
        if let Some((end, lead)) = self.contact.vertical_end_ahead() {
            if rate < 0.0 && alpha <= end + lead * (1.0 + 1e-6) {
                let mut crossed = self.contact.clone();
                crossed.accept(alpha, rate);
                let law_work = crossed.cross(end);
                let damping_work = self.contact.force(alpha, rate).damping * (end - alpha);
                let kinetic = 0.5 * self.mass * rate * rate - law_work - damping_work;
                if kinetic > 0.0 && !crossed.accepted.branch.in_contact() {
                    // The history is the one beyond the end; the state stays where it is.
                    crossed.accept(alpha, rate);
                    self.contact = crossed;
                    y.velocity = wall.velocity + (2.0 * kinetic / self.mass).sqrt();
                    y.work += law_work + damping_work;
                    return (true, true);
                }
            }
        }
        self.contact.accept(alpha, rate);
        (before != self.contact.accepted.branch, false)
    }
}
