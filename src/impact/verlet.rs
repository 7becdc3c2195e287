//! The `verlet` integrator: fixed-step velocity Verlet, as DEM codes step (a fraction of the Rayleigh time
//! step, `000` Eq. 71). The damping force of the new position uses the half-step velocity, and the contact
//! history is accepted after every step with no event location: the baseline the other two are measured
//! against. The communication step is cut into equal steps no longer than the chosen one.

use super::sphere::{Sphere, State, StepError, WallMotion, MAX_STEPS};

impl Sphere {
    /// With `stop_at_event`, stops after the first step that changes the contact state and returns its end
    /// (the communication step's end when it is the last).
    pub(super) fn advance_verlet(
        &mut self,
        step: f64,
        wall: &WallMotion,
        t0: f64,
        t_end: f64,
        y: &mut State,
        stop_at_event: bool,
    ) -> Result<Option<f64>, StepError> {
        let Some((n, h)) = steps(step, t0, t_end)? else { return Ok(None) };
        let start_state = self.contact_state();
        let (alpha, rate) = self.overlap(wall, t0, y);
        let mut f = self.contact.law_force(alpha, rate).total();
        let mut alpha = alpha;
        for i in 0..n {
            let t1 = t0 + (i + 1) as f64 * h;
            let v_half = y.velocity + 0.5 * h * (f / self.mass - self.gravity);
            y.bottom += h * v_half;
            let (alpha1, rate1) = (wall.at(t1) - y.bottom, wall.velocity - v_half);
            let f1 = self.contact.law_force(alpha1, rate1).total();
            y.velocity = v_half + 0.5 * h * (f1 / self.mass - self.gravity);
            // Trapezoidal contact work, the accuracy of the scheme.
            y.work += 0.5 * (f + f1) * (alpha1 - alpha);
            if !(y.bottom.is_finite() && y.velocity.is_finite()) {
                return Err(StepError::NotFinite { t: t1 });
            }
            self.contact.accept(alpha1, wall.velocity - y.velocity);
            self.steps += 1;
            f = f1;
            alpha = alpha1;
            if stop_at_event && self.contact_state() != start_state {
                return Ok(Some(if i + 1 == n { t_end } else { t1 }));
            }
        }
        Ok(None)
    }
}

/// The communication step [t0, t_end] cut into n equal steps h no longer than `step`: None for a
/// rounding leftover of a step (no step at all), an error beyond `MAX_STEPS`. Both Verlet paths
/// (`advance_verlet`, `advance_oblique_verlet`) step this way.
pub(super) fn steps(step: f64, t0: f64, t_end: f64) -> Result<Option<(u64, f64)>, StepError> {
    let span = t_end - t0;
    if span <= 4.0 * f64::EPSILON * t_end.abs() {
        return Ok(None);
    }
    let n = (span / step).ceil().max(1.0);
    if n > MAX_STEPS as f64 {
        return Err(StepError::TooManySteps { t: t0, limit: MAX_STEPS });
    }
    Ok(Some((n as u64, span / n)))
}
