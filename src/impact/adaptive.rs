//! The `adaptive` integrator: an embedded Runge-Kutta pair (Dormand-Prince 5(4)) with error control that
//! lands on every branch switch of the law. A step that changes the sign of an event indicator of
//! `Contact` is shortened by regula falsi (Illinois) until the switch is bracketed to 1e-13 of the step,
//! and the history is accepted there. Works for every law; the nonlinear ones (Hertz, JKR, Thornton-Ning,
//! Tomas) need it.

use super::sphere::{Sphere, State, StepError, WallMotion, MAX_STEPS};
use crate::numeric::first_outside;

// Dormand-Prince 5(4) coefficients (Hairer, Norsett & Wanner, Table II.5.2).
pub(super) const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
pub(super) const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
    [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
    [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
];
pub(super) const B5: [f64; 7] = [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0, 0.0];
pub(super) const B4: [f64; 7] = [5179.0 / 57600.0, 0.0, 7571.0 / 16695.0, 393.0 / 640.0, -92097.0 / 339200.0, 187.0 / 2100.0, 1.0 / 40.0];

impl Sphere {
    /// One Dormand-Prince step: the 5th-order solution and the error estimate.
    fn dp_step(&self, wall: &WallMotion, t: f64, y: &State, h: f64) -> (State, State) {
        let mut k = [State::default(); 7];
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
        let mut err = State::default();
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
        let scale_z = tol * (self.contact.alpha_nominal + y0.bottom.abs().max(y1.bottom.abs()));
        let scale_v = tol * (self.contact.rate_nominal + y0.velocity.abs().max(y1.velocity.abs()));
        let ez = err.bottom / scale_z;
        let ev = err.velocity / scale_v;
        ((ez * ez + ev * ev) / 2.0).sqrt()
    }

    /// Advances the state from `t` to `t_end` with the wall moving as `wall`, landing on branch switches.
    /// With `stop_at_event`, stops at the first located switch after `t` that changes the contact state and
    /// returns its time.
    pub(super) fn advance_adaptive(
        &mut self,
        wall: &WallMotion,
        t: f64,
        t_end: f64,
        y: &mut State,
        stop_at_event: bool,
    ) -> Result<Option<f64>, StepError> {
        let (t_start, mut start_state) = (t, self.contact_state());
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
            if !y1.to_array().iter().all(|x| x.is_finite()) {
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
            if any_crossed && t == t_start {
                start_state = self.contact_state();
            } else if stop_at_event && any_crossed && self.contact_state() != start_state {
                return Ok(Some(t));
            }
            // The shortened last step of a communication step says nothing about the step size the
            // dynamics allows: it is not kept for the next call.
            if !any_crossed && !last {
                self.last_step = h_try;
                h = h_try * (0.9 * e.max(1e-10).powf(-0.2)).min(5.0);
            }
        }
        Ok(None)
    }

    /// The smallest step in (0, h] after which one of the `crossed` indicators has changed sign, to 1e-13 h.
    fn locate(&self, wall: &WallMotion, t: f64, y: &State, h: f64, crossed: &[bool; 3]) -> f64 {
        let g = |tau: f64| -> f64 {
            let (y_tau, _) = self.dp_step(wall, t, y, tau);
            let z = self.indicators(wall, t + tau, &y_tau);
            (0..3).filter(|&i| crossed[i]).map(|i| z[i]).fold(f64::INFINITY, f64::min)
        };
        let (g_lo, g_hi) = (g(0.0), g(h));
        first_outside(g, |v| v > 0.0, (0.0, g_lo), (h, g_hi), |lo, hi| hi - lo <= 1e-13 * h)
    }

    fn initial_step(&self, y: &State) -> f64 {
        let speed = y.velocity.abs().max(self.contact.rate_nominal);
        1e-2 * self.contact.alpha_nominal / speed
    }
}
