//! The oblique impact by the `adaptive` integrator: Dormand-Prince 5(4) with error control over the normal
//! state and the tangential one, landing on the normal law's branch switches (as `adaptive.rs`) and on the
//! switches between sticking and sliding, which Verlet steps over (docs/benchmarks.md, "Oblique impacts").
//!
//! Between switches the tangential force is smooth in time:
//! - sticking: the spring F_s follows dF_s/dt = -k_t s (the incremental spring of `law::tangential`, as a
//!   differential equation), and F_t = F_s - c_t s with the damping of the Verlet path;
//! - sliding: F_t = sigma mu N, sigma the spring's sign at the switch (no damping, 000 Sec. 2.2).
//!
//! The switches are those of the projected spring of the Verlet path (`TangentialSpring::step`), taken to
//! a vanishing step: sticking ends where |F_s| reaches mu N (indicator mu N - |F_s|); sliding ends where
//! the spring, moved by the slip, would no longer outgrow the limit (indicator -sigma k_t s - d(mu N)/dt),
//! which is where the slip reverses while mu N holds still, and earlier while mu N grows. At the switch to sticking the spring starts at the limit, pulled in by a
//! hysteresis of 1e-9 of it (as the normal indicators' `HYSTERESIS`), so the new indicator starts positive.
//! Rolling friction, a torque that switches with the sign of the spin, is not in it: with rolling friction
//! the oblique impact runs `verlet` (`ImpactOptions::solver`).

use super::adaptive::{A, B4, B5, C};
use super::oblique::{Spin, Tangential};
use super::sphere::{Sphere, State, StepError, WallMotion, MAX_STEPS};
use crate::law::damping;
use crate::law::NormalLaw;
use crate::numeric::first_outside;

/// z, v, W (the normal state), v_t, omega, F_s, W_t (the tangential work, `Spin::work`), x.
const N: usize = 8;
/// The extended state of the adaptive integrator (`N`).
pub(crate) type Y = [f64; N];

/// Model Exchange's continuous states of the oblique impact: z, v, W (the normal and the tangential work
/// in one), v_t, omega, F_s. The same right-hand side as the adaptive integrator's; the host's integrator
/// takes the place of Dormand-Prince and its event indicators that of the switches located here.
pub const ME_STATES: usize = 6;

/// The adaptive integrator's state from Model Exchange's (the tangential work in W, x not carried).
fn from_me(x: &[f64]) -> Y {
    [x[0], x[1], x[2], x[3], x[4], x[5], 0.0, 0.0]
}

/// Whether the contact sticks or slides (with the sign sigma of the sliding force).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Mode {
    /// The spring holds: |F_s| < mu N.
    Stick,
    /// The force is sigma mu N, sigma = +1 or -1.
    Slide(f64),
}

/// The spring's hysteresis at a switch to sticking, relative to the limit.
const SPRING_HYSTERESIS: f64 = 1e-9;

/// The tangential state the adaptive integrator carries between calls.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TangentialMode {
    /// Stick or slide.
    pub mode: Mode,
}

impl Default for TangentialMode {
    fn default() -> TangentialMode {
        TangentialMode { mode: Mode::Stick }
    }
}

/// What the tangential contact does at one state: force on the sphere, the spring's rate, the slip, the
/// limit mu N, and how fast the spring would grow against the limit (sliding goes on while it is > 0).
struct Tangent {
    force: f64,
    spring_rate: f64,
    slip: f64,
    limit: f64,
    excess_rate: f64,
}

impl Sphere {
    /// The tangential contact at a state; `with_excess`: also the excess rate, which costs two more
    /// evaluations of the law and only the indicators and the mode decisions read (not the stages).
    #[allow(clippy::too_many_arguments)] // the state and what to evaluate
    fn tangent(&self, tg: &Tangential, mode: Mode, alpha: f64, rate: f64, y: &Y, wall_tangential_velocity: f64, with_excess: bool) -> Tangent {
        let spin = Spin { velocity: y[3], angular_velocity: y[4], ..Spin::default() };
        let slip = tg.slip(alpha, &spin, wall_tangential_velocity);
        if tg.friction == 0.0 || !self.contact.accepted.branch.in_contact() {
            return Tangent { force: 0.0, spring_rate: 0.0, slip, limit: 0.0, excess_rate: 0.0 };
        }
        let law = &self.contact.law;
        let limit_at = |a: f64| {
            let (cf, history) = self.contact.state_at(a, rate);
            (tg.friction * law.sliding_normal_force(cf.law, a, &history).max(0.0), cf, history)
        };
        let (limit, _, history) = limit_at(alpha);
        let stiffness = law.evaluate(alpha, &self.contact.accepted.history).stiffness;
        let normal = limit / tg.friction;
        let radius = law.contact_radius(alpha, &history);
        let k_t = tg.stiffness.at(alpha, stiffness, normal, law.mindlin_radius(alpha, &history, radius));
        // The projected spring of the Verlet path slides while the spring, moved by the slip, would
        // outgrow the limit: -sigma k_t s > d(mu N)/dt (sigma the spring's sign, or against the slip for an
        // unloaded spring), with d(mu N)/d alpha by a central difference on the accepted branch.
        let excess_rate = if with_excess {
            // A step relative to the overlap itself: at the first touch (alpha 1e-16 m) a step of the
            // nominal's size (1e-13 m) read the limit far up the branch and said the spring would
            // never catch it.
            let da = 1e-7 * alpha.abs() + 1e-12 * self.contact.alpha_nominal;
            let limit_rate = (limit_at(alpha + da).0 - limit_at(alpha - da).0) / (2.0 * da) * rate;
            let sign = match mode {
                Mode::Slide(sigma) => sigma,
                Mode::Stick if y[5] != 0.0 => y[5].signum(),
                Mode::Stick => -slip.signum(),
            };
            -sign * k_t * slip - limit_rate
        } else {
            f64::NAN
        };
        match mode {
            Mode::Slide(sigma) => Tangent { force: sigma * limit, spring_rate: 0.0, slip, limit, excess_rate },
            Mode::Stick => {
                let d = &self.contact.damping;
                let c_t = damping::coefficient(d.restitution, d.beta_elastic, d.mass, k_t);
                Tangent { force: y[5] - c_t * slip, spring_rate: -k_t * slip, slip, limit, excess_rate }
            }
        }
    }

    fn oblique_rhs(&self, tg: &Tangential, mode: Mode, wall: &WallMotion, w_t: f64, t: f64, y: &Y) -> Y {
        let normal = self.derivatives(wall, t, &State::new(y[0], y[1], y[2]));
        // No motion along the wall, no spin, an unloaded sticking spring and a wall at rest along itself:
        // no slip, so no tangential force, whatever the normal state (Model Exchange's normal impact pays
        // nothing for the tangential states; the general path gives the same values).
        if mode == Mode::Stick && y[3] == 0.0 && y[4] == 0.0 && y[5] == 0.0 && w_t == 0.0 {
            return [normal.bottom, normal.velocity, normal.work, 0.0, 0.0, 0.0, 0.0, 0.0];
        }
        let (alpha, rate) = (wall.at(t) - y[0], wall.velocity - y[1]);
        let tan = self.tangent(tg, mode, alpha, rate, y, w_t, false);
        let lever = tg.lever(alpha);
        // The power the tangential force puts into the motion along the wall and the spin.
        let power = tan.force * (y[3] - lever * y[4]);
        [normal.bottom, normal.velocity, normal.work, tan.force / self.mass, -lever * tan.force / tg.inertia, tan.spring_rate, -power, y[3]]
    }

    /// Model Exchange: the derivatives of the `ME_STATES` states `x` into `dx`; returns the tangential
    /// part of the work's derivative (the power the tangential force takes from the motion) [W].
    #[allow(clippy::too_many_arguments)] // the state and the wall's two motions
    pub fn oblique_me_derivatives(
        &self,
        tg: &Tangential,
        mode: &TangentialMode,
        wall: &WallMotion,
        w_t: f64,
        t: f64,
        x: &[f64],
        dx: &mut [f64],
    ) -> f64 {
        let d = self.oblique_rhs(tg, mode.mode, wall, w_t, t, &from_me(x));
        dx[..ME_STATES].copy_from_slice(&d[..ME_STATES]);
        dx[2] += d[6];
        d[6]
    }

    /// Model Exchange: the tangential event indicator at the states `x`, positive while the mode holds
    /// (sticking: mu N - |F_s|; sliding: how fast the spring would outgrow the limit).
    pub fn oblique_me_indicator(&self, tg: &Tangential, mode: &TangentialMode, wall: &WallMotion, w_t: f64, t: f64, x: &[f64]) -> f64 {
        self.tangential_indicator(tg, mode.mode, wall, w_t, t, &from_me(x))
    }

    /// Model Exchange: the tangential force on the sphere at the states `x` [N].
    pub fn oblique_me_force(&self, tg: &Tangential, mode: &TangentialMode, wall: &WallMotion, w_t: f64, t: f64, x: &[f64]) -> f64 {
        let (alpha, rate) = (wall.at(t) - x[0], wall.velocity - x[1]);
        self.tangent(tg, mode.mode, alpha, rate, &from_me(x), w_t, false).force
    }

    /// Model Exchange: at an event, after the normal history has accepted the state (`was_in_contact`
    /// before it), the spring and the mode settled as the adaptive integrator settles them; `x[5]` may
    /// change (a restart). `repeat` counts the switches the host has asked for in quick succession
    /// before this one: each widens the spring's pull-in at a switch to sticking tenfold (from 1e-9 of the limit, at
    /// most half of it), so that a host whose integration error of the spring exceeds the hysteresis
    /// (at the first touch, where the spring and its limit are 1e-14 N and the host's absolute
    /// tolerance is set by the impact's force scale) moves on instead of switching forever.
    #[allow(clippy::too_many_arguments)] // the state the decision reads
    pub fn oblique_me_event(
        &self,
        tg: &Tangential,
        mode: &mut TangentialMode,
        wall: &WallMotion,
        w_t: f64,
        t: f64,
        x: &mut [f64],
        was_in_contact: bool,
        repeat: u32,
    ) {
        let mut y = from_me(x);
        let switched = self.tangential_indicator(tg, mode.mode, wall, w_t, t, &y) <= 0.0;
        self.settle_tangential(tg, mode, wall, w_t, t, &mut y, was_in_contact, switched);
        // The host sees a crossing only where an indicator changes sign: a mode whose indicator is not
        // positive where it starts would hold on unwatched. The adaptive integrator settles at every step;
        // here the mode is settled again at once (a contact just formed whose spring outgrew its
        // limit within rounding slides, and sticks again at the limit if it would not outgrow it).
        for _ in 0..2 {
            if self.tangential_indicator(tg, mode.mode, wall, w_t, t, &y) > 0.0 {
                break;
            }
            self.settle_tangential(tg, mode, wall, w_t, t, &mut y, true, true);
        }
        if repeat > 0 && mode.mode == Mode::Stick && y[5] != 0.0 {
            let pull = (SPRING_HYSTERESIS * 10f64.powi(repeat.min(9) as i32)).min(0.5);
            y[5] *= (1.0 - pull) / (1.0 - SPRING_HYSTERESIS);
        }
        x[5] = y[5];
    }

    /// The tangential indicator of a mode at a state: positive while the mode holds.
    fn tangential_indicator(&self, tg: &Tangential, mode: Mode, wall: &WallMotion, w_t: f64, t: f64, y: &Y) -> f64 {
        if tg.friction == 0.0 || !self.contact.accepted.branch.in_contact() {
            return 1.0;
        }
        // An unloaded spring holds whatever the limit (at N = 0 too): it can only leave sticking once it
        // carries a force, which makes the indicator limit - |F_s| at once. So a contact that is never
        // sheared has no tangential events (Model Exchange's normal impact), and costs no evaluation here.
        if mode == Mode::Stick && y[5] == 0.0 {
            return 1.0;
        }
        let (alpha, rate) = (wall.at(t) - y[0], wall.velocity - y[1]);
        let tan = self.tangent(tg, mode, alpha, rate, y, w_t, matches!(mode, Mode::Slide(_)));
        match mode {
            Mode::Stick => tan.limit - y[5].abs(),
            Mode::Slide(_) => tan.excess_rate,
        }
    }

    #[allow(clippy::too_many_arguments)] // one stage of the tableau over the extended state
    fn oblique_dp_step(&self, tg: &Tangential, mode: Mode, wall: &WallMotion, w_t: f64, t: f64, y: &Y, h: f64) -> (Y, Y) {
        let mut k = [[0.0; N]; 7];
        for s in 0..7 {
            let mut ys = *y;
            for (j, kj) in k.iter().enumerate().take(s) {
                for i in 0..N {
                    ys[i] += h * A[s][j] * kj[i];
                }
            }
            k[s] = self.oblique_rhs(tg, mode, wall, w_t, t + C[s] * h, &ys);
        }
        let (mut y5, mut err) = (*y, [0.0; N]);
        for s in 0..7 {
            for i in 0..N {
                y5[i] += h * B5[s] * k[s][i];
                err[i] += h * (B5[s] - B4[s]) * k[s][i];
            }
        }
        (y5, err)
    }

    fn oblique_error_norm(&self, tg: &Tangential, y0: &Y, y1: &Y, err: &Y) -> f64 {
        let tol = self.tolerance;
        let v_scale = self.contact.rate_nominal;
        let scale = |i: usize, base: f64| tol * (base + y0[i].abs().max(y1[i].abs()));
        let parts = [
            err[0] / scale(0, self.contact.alpha_nominal),
            err[1] / scale(1, v_scale),
            err[3] / scale(3, v_scale),
            err[4] * tg.radius / (tol * (v_scale + tg.radius * y0[4].abs().max(y1[4].abs()))),
        ];
        (parts.iter().map(|p| p * p).sum::<f64>() / parts.len() as f64).sqrt()
    }

    /// The mode that holds at an accepted state: at a located switch (`switched`) the other mode; a
    /// sticking spring on or over the limit slides in its own direction; a sliding spring that would no
    /// longer outgrow the limit sticks there, less the hysteresis; a contact just formed (`formed`) slides
    /// at once if its spring outgrows the limit from zero (Maw, Barber and Fawcett's initial sliding,
    /// Psi_1 > 1). The checks besides the located switch catch a state a step started on.
    #[allow(clippy::too_many_arguments)] // the state the decision reads
    fn settle_mode(&self, tg: &Tangential, mode: &mut TangentialMode, alpha: f64, rate: f64, x: &mut Y, w_t: f64, formed: bool, switched: bool) {
        if tg.friction == 0.0 {
            return;
        }
        let tan = self.tangent(tg, mode.mode, alpha, rate, x, w_t, true);
        match mode.mode {
            // (A contact formed without slip has nothing to slide with.)
            Mode::Stick if switched || (x[5] != 0.0 && tan.limit - x[5].abs() <= 0.0) || (formed && tan.slip != 0.0 && tan.excess_rate > 0.0) => {
                let sigma = if x[5] != 0.0 { x[5].signum() } else { -tan.slip.signum() };
                mode.mode = Mode::Slide(sigma);
            }
            Mode::Slide(sigma) if switched || tan.excess_rate <= 0.0 => {
                x[5] = sigma * tan.limit * (1.0 - SPRING_HYSTERESIS);
                mode.mode = Mode::Stick;
            }
            _ => {}
        }
    }

    /// After the normal history has accepted the state `x` at `t` (an accepted step here, an event in Model
    /// Exchange): the spring unloads out of contact and starts unloaded in a contact just formed; in
    /// contact the mode that holds is settled (`settle_mode`; `switched`: the tangential indicator was
    /// the one that crossed).
    #[allow(clippy::too_many_arguments)] // the state the decision reads
    pub(crate) fn settle_tangential(
        &self,
        tg: &Tangential,
        mode: &mut TangentialMode,
        wall: &WallMotion,
        w_t: f64,
        t: f64,
        x: &mut Y,
        was_in_contact: bool,
        switched: bool,
    ) {
        let (alpha, rate) = (wall.at(t) - x[0], wall.velocity - x[1]);
        if !self.contact.accepted.branch.in_contact() {
            x[5] = 0.0;
            mode.mode = Mode::Stick;
            return;
        }
        if !was_in_contact {
            x[5] = 0.0;
            mode.mode = Mode::Stick;
        }
        self.settle_mode(tg, mode, alpha, rate, x, w_t, !was_in_contact, was_in_contact && switched);
    }

    /// Dormand-Prince over [t0, t_end] for the oblique impact, landing on the normal law's branch switches
    /// and the stick-slip switches; the tangential state in `spin`, the spring in `tangential.spring`, the
    /// mode in `mode`. No rolling friction (module docs). With `stop_at_event` it stops at the first
    /// located change of the contact state or of sticking and sliding (FMI 3.0 early return) and returns
    /// its time.
    #[allow(clippy::too_many_arguments)] // the normal and the tangential state, the wall's two motions
    pub fn advance_oblique_adaptive(
        &mut self,
        tangential: &mut Tangential,
        mode: &mut TangentialMode,
        wall: &WallMotion,
        w_t: f64,
        t0: f64,
        t_end: f64,
        y: &mut State,
        spin: &mut Spin,
        stop_at_event: bool,
    ) -> Result<Option<f64>, StepError> {
        let (state0, sliding0) = (self.contact_state(), matches!(mode.mode, Mode::Slide(_)));
        let mut event = None;
        let mut x: Y = [y.bottom, y.velocity, y.work, spin.velocity, spin.angular_velocity, tangential.spring.force.x, spin.work, spin.position];
        let mut t = t0;
        let mut h =
            if self.last_step > 0.0 { self.last_step } else { 1e-2 * self.contact.alpha_nominal / y.velocity.abs().max(self.contact.rate_nominal) };
        let mut steps = 0u64;
        while t < t_end {
            if t_end - t <= 4.0 * f64::EPSILON * t_end.abs() {
                break;
            }
            steps += 1;
            if steps > MAX_STEPS {
                return Err(StepError::TooManySteps { t, limit: MAX_STEPS });
            }
            let last = h >= t_end - t;
            let h_try = if last { t_end - t } else { h };
            if h_try <= f64::EPSILON * t.abs() * 4.0 && !last {
                return Err(StepError::StepTooSmall { t });
            }
            let (x1, err) = self.oblique_dp_step(tangential, mode.mode, wall, w_t, t, &x, h_try);
            if !x1.iter().all(|v| v.is_finite()) {
                if h_try < 1e-300 {
                    return Err(StepError::NotFinite { t });
                }
                h = h_try * 0.1;
                continue;
            }
            let e = self.oblique_error_norm(tangential, &x, &x1, &err);
            if e > 1.0 {
                h = h_try * (0.9 * e.powf(-0.2)).max(0.1);
                continue;
            }
            // Accepted by error control. Did a normal branch or the tangential mode switch inside?
            let indicators = |tau: f64, z: &Y| -> [f64; 4] {
                let s = State::new(z[0], z[1], z[2]);
                let g = self.indicators(wall, t + tau, &s);
                [g[0], g[1], g[2], self.tangential_indicator(tangential, mode.mode, wall, w_t, t + tau, z)]
            };
            let (g0, g1) = (indicators(0.0, &x), indicators(h_try, &x1));
            let crossed: [bool; 4] = std::array::from_fn(|i| g0[i] > 0.0 && g1[i] <= 0.0);
            let any = crossed.contains(&true);
            let (t_new, x_new) = if !any {
                (if last { t_end } else { t + h_try }, x1)
            } else {
                let g = |tau: f64| -> f64 {
                    let (z, _) = self.oblique_dp_step(tangential, mode.mode, wall, w_t, t, &x, tau);
                    let v = indicators(tau, &z);
                    (0..4).filter(|&i| crossed[i]).map(|i| v[i]).fold(f64::INFINITY, f64::min)
                };
                let (g_lo, g_hi) = (g(0.0), g(h_try));
                let tau = first_outside(g, |v| v > 0.0, (0.0, g_lo), (h_try, g_hi), |lo, hi| hi - lo <= 1e-13 * h_try);
                let (z, _) = self.oblique_dp_step(tangential, mode.mode, wall, w_t, t, &x, tau);
                self.events += 1;
                (t + tau, z)
            };
            self.steps += 1;
            x = x_new;
            t = t_new;
            let was_in_contact = self.contact.accepted.branch.in_contact();
            let s = State::new(x[0], x[1], x[2]);
            self.accept(wall, t, &s);
            self.settle_tangential(tangential, mode, wall, w_t, t, &mut x, was_in_contact, any && crossed[3]);
            if stop_at_event && t < t_end && (self.contact_state() != state0 || matches!(mode.mode, Mode::Slide(_)) != sliding0) {
                event = Some(t);
                break;
            }
            if !any && !last {
                self.last_step = h_try;
                h = h_try * (0.9 * e.max(1e-10).powf(-0.2)).min(5.0);
            }
        }
        (y.bottom, y.velocity, y.work) = (x[0], x[1], x[2]);
        spin.velocity = x[3];
        spin.angular_velocity = x[4];
        spin.work = x[6];
        spin.position = x[7];
        tangential.spring.force.x = x[5];
        tangential.sliding = matches!(mode.mode, Mode::Slide(_));
        let t_stop = event.unwrap_or(t_end);
        let (alpha, rate) = (wall.at(t_stop) - y.bottom, wall.velocity - y.velocity);
        tangential.force = self.tangent(tangential, mode.mode, alpha, rate, &x, w_t, false).force;
        Ok(event)
    }
}
