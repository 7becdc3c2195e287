//! A sphere moving along the normal of a wall (the ParticleWallImpact unit). z is the height of the
//! sphere's lowest point (centre minus radius), v its velocity, both positive away from the wall; the
//! wall plane is at w, so the overlap is alpha = w - z and its rate w' - v. Newton: m v' = f - m g, with
//! f the contact force (positive pushes the sphere away) and g the gravity toward the wall.
//!
//! Co-simulation steps use an embedded Runge-Kutta pair (Dormand-Prince 5(4)) with error control, and land
//! on every branch switch of the law: a step that changes the sign of an event indicator of `Contact` is
//! shortened by regula falsi (Illinois) until the switch is bracketed to 1e-13 of the step, and the history
//! is accepted there. Within a communication step the wall moves with the velocity input:
//! w(t) = w(t_0) + w'(t_0) (t - t_0).

use super::contact::Contact;

/// The state of the sphere: [z, v, W] with W the work done on the contact (the integral of f d alpha).
pub type State = [f64; 3];

/// The wall's motion over one communication step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    pub t0: f64,
    pub position: f64,
    pub velocity: f64,
}

impl Wall {
    pub fn at(&self, t: f64) -> f64 {
        self.position + self.velocity * (t - self.t0)
    }
}

#[derive(Debug, Clone)]
pub struct Sphere {
    pub mass: f64,
    /// Gravity toward the wall [m/s^2].
    pub gravity: f64,
    pub contact: Contact,
    /// Relative tolerance of the integrator; absolute tolerances are it times the nominal overlap and rate.
    pub tolerance: f64,
    /// Last step size the controller chose [s] (0 before the first step).
    pub last_step: f64,
    /// Counters for the logs and benchmarks.
    pub steps: u64,
    pub events: u64,
}

/// Why a step could not be completed.
#[derive(Debug, Clone, PartialEq)]
pub enum StepError {
    /// The state or force became non-finite.
    NotFinite { t: f64 },
    /// The step size fell below the resolution of time.
    StepTooSmall { t: f64 },
    /// More steps than allowed in one communication step.
    TooManySteps { t: f64, limit: u64 },
}

impl std::fmt::Display for StepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepError::NotFinite { t } => write!(f, "the sphere's state became non-finite at t = {t:e} s"),
            StepError::StepTooSmall { t } => write!(f, "the integrator's step size fell below the resolution of time at t = {t:e} s"),
            StepError::TooManySteps { t, limit } => {
                write!(f, "more than {limit} integrator steps in one communication step (at t = {t:e} s); use shorter communication steps")
            }
        }
    }
}

const MAX_STEPS: u64 = 10_000_000;

// Dormand-Prince 5(4) coefficients (Hairer, Norsett & Wanner, Table II.5.2).
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
    [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
    [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
];
const B5: [f64; 7] = [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0, 0.0];
const B4: [f64; 7] = [5179.0 / 57600.0, 0.0, 7571.0 / 16695.0, 393.0 / 640.0, -92097.0 / 339200.0, 187.0 / 2100.0, 1.0 / 40.0];

impl Sphere {
    /// Overlap and overlap rate of a state at time t.
    pub fn overlap(&self, wall: &Wall, t: f64, y: &State) -> (f64, f64) {
        (wall.at(t) - y[0], wall.velocity - y[1])
    }

    /// dy/dt with the accepted history.
    pub fn derivatives(&self, wall: &Wall, t: f64, y: &State) -> State {
        let (alpha, rate) = self.overlap(wall, t, y);
        let f = self.contact.force(alpha, rate).total();
        [y[1], f / self.mass - self.gravity, f * rate]
    }

    /// The event indicators at a state.
    pub fn indicators(&self, wall: &Wall, t: f64, y: &State) -> [f64; 3] {
        let (alpha, rate) = self.overlap(wall, t, y);
        self.contact.indicators(alpha, rate)
    }

    /// Accepts a state into the contact history; returns whether the branch changed.
    pub fn accept(&mut self, wall: &Wall, t: f64, y: &State) -> bool {
        let (alpha, rate) = self.overlap(wall, t, y);
        let (before, after) = self.contact.accept(alpha, rate);
        before != after
    }

    /// One Dormand-Prince step: the 5th-order solution and the error estimate.
    fn dp_step(&self, wall: &Wall, t: f64, y: &State, h: f64) -> (State, State) {
        let mut k = [[0.0; 3]; 7];
        for s in 0..7 {
            let mut ys = *y;
            for (j, kj) in k.iter().enumerate().take(s) {
                for i in 0..3 {
                    ys[i] += h * A[s][j] * kj[i];
                }
            }
            k[s] = self.derivatives(wall, t + C[s] * h, &ys);
        }
        let mut y5 = *y;
        let mut err = [0.0; 3];
        for s in 0..7 {
            for i in 0..3 {
                y5[i] += h * B5[s] * k[s][i];
                err[i] += h * (B5[s] - B4[s]) * k[s][i];
            }
        }
        (y5, err)
    }

    fn error_norm(&self, y0: &State, y1: &State, err: &State) -> f64 {
        let tol = self.tolerance;
        let scale_z = tol * (self.contact.alpha_nominal + y0[0].abs().max(y1[0].abs()));
        let scale_v = tol * (self.contact.rate_nominal + y0[1].abs().max(y1[1].abs()));
        let ez = err[0] / scale_z;
        let ev = err[1] / scale_v;
        ((ez * ez + ev * ev) / 2.0).sqrt()
    }

    /// Advances the state from `t` to `t_end` with the wall moving as `wall`, landing on branch switches.
    pub fn advance(&mut self, wall: &Wall, t: f64, t_end: f64, y: &mut State) -> Result<(), StepError> {
        let mut t = t;
        let mut h = if self.last_step > 0.0 { self.last_step } else { self.initial_step(y) };
        let mut steps = 0u64;
        while t < t_end {
            // A rounding leftover of the communication step is no step at all.
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
            let (y1, err) = self.dp_step(wall, t, y, h_try);
            if !y1.iter().all(|x| x.is_finite()) {
                if h_try < 1e-300 {
                    return Err(StepError::NotFinite { t });
                }
                h = h_try * 0.1;
                continue;
            }
            let e = self.error_norm(y, &y1, &err);
            if e > 1.0 {
                h = h_try * (0.9 * e.powf(-0.2)).max(0.1);
                continue;
            }
            // Accepted by error control. Did the branch change inside the step?
            let g0 = self.indicators(wall, t, y);
            let g1 = self.indicators(wall, t + h_try, &y1);
            let crossed: [bool; 3] = std::array::from_fn(|i| g0[i] > 0.0 && g1[i] <= 0.0);
            let any_crossed = crossed.contains(&true);
            let (t_new, y_new) = if !any_crossed {
                (if last { t_end } else { t + h_try }, y1)
            } else {
                let tau = self.locate(wall, t, y, h_try, &crossed);
                let (y_tau, _) = self.dp_step(wall, t, y, tau);
                self.events += 1;
                (t + tau, y_tau)
            };
            self.steps += 1;
            *y = y_new;
            t = t_new;
            self.accept(wall, t, y);
            // The shortened last step of a communication step says nothing about the step size the
            // dynamics allows: it is not kept for the next call.
            if !any_crossed && !last {
                self.last_step = h_try;
                h = h_try * (0.9 * e.max(1e-10).powf(-0.2)).min(5.0);
            }
        }
        Ok(())
    }

    /// The smallest step in (0, h] after which one of the `crossed` indicators has changed sign, to 1e-13 h.
    fn locate(&self, wall: &Wall, t: f64, y: &State, h: f64, crossed: &[bool; 3]) -> f64 {
        let g = |tau: f64| -> f64 {
            let (y_tau, _) = self.dp_step(wall, t, y, tau);
            let z = self.indicators(wall, t + tau, &y_tau);
            (0..3).filter(|&i| crossed[i]).map(|i| z[i]).fold(f64::INFINITY, f64::min)
        };
        let (mut lo, mut hi) = (0.0, h);
        let (mut g_lo, mut g_hi) = (g(0.0), g(h));
        let mut side = 0i8;
        for _ in 0..200 {
            if hi - lo <= 1e-13 * h {
                break;
            }
            let mut tau = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
            if !(tau > lo && tau < hi) {
                tau = 0.5 * (lo + hi);
            }
            let g_tau = g(tau);
            if g_tau > 0.0 {
                lo = tau;
                g_lo = g_tau;
                if side == 1 {
                    g_hi *= 0.5;
                }
                side = 1;
            } else {
                hi = tau;
                g_hi = g_tau;
                if side == -1 {
                    g_lo *= 0.5;
                }
                side = -1;
            }
        }
        hi
    }

    fn initial_step(&self, y: &State) -> f64 {
        let speed = y[1].abs().max(self.contact.rate_nominal);
        1e-2 * self.contact.alpha_nominal / speed
    }
}
