//! The `exact` integrator: closed-form motion on each branch of a piecewise-linear law.
//!
//! Within a communication step the wall moves at constant velocity (the `wall_velocity` input; its
//! position is w(t_0) + w'(t_0) (t - t_0)), so the wall is an inertial frame and the overlap x = alpha
//! obeys, on a branch with force f = k x + c + d x' (`Contact::branch_line`),
//! x'' = -q x - 2 a x' + b with q = k/m, a = d/(2m), b = g - c/m:
//! a linear ODE with constant coefficients whose solution is written down (`Segment::at`): an oscillation,
//! a critically or over-damped relaxation, an exponential escape (k < 0) or a parabola (k = 0, free flight).
//! The branch ends where one of the contact's event indicators (linear in x and x') reaches zero.
//! An indicator g(t) is monotone between the zeros of g'(t), which are known in closed form, so each
//! crossing is bracketed on a monotone piece and refined to the last bit of the time. Underdamped
//! motion repeats with a shrinking amplitude about its equilibrium, so if an indicator has not crossed
//! within its first two turning points it never will on this branch.

use super::contact::{BranchLine, Line};
use super::sphere::{Sphere, State, StepError, WallMotion, MAX_STEPS};
use crate::numeric::first_outside;
use std::f64::consts::PI;

/// x'' = -q x - 2 a x' + b for the state y = [x, x'].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// k/m [1/s^2]
    pub q: f64,
    /// d/(2m) [1/s]
    pub a: f64,
    /// g - c/m [m/s^2]
    pub b: f64,
}

/// An indicator this far below zero at the start of a branch means the state is already outside it.
const OUTSIDE: f64 = 1e-9;

impl Segment {
    pub fn new(line: BranchLine, mass: f64, gravity: f64) -> Segment {
        Segment { q: line.stiffness / mass, a: line.damping / (2.0 * mass), b: gravity - line.offset / mass }
    }

    /// e^{-at} C(t) and e^{-at} S(t), with Phi(t) = e^{-at} [C I + S (A + a I)] the propagator of the
    /// homogeneous system y' = A y, A = [[0, 1], [-q, -2a]].
    fn kernel(&self, t: f64) -> (f64, f64) {
        let (a, d) = (self.a, self.a * self.a - self.q);
        if d < 0.0 {
            let mu = (-d).sqrt();
            let e = (-a * t).exp();
            let (s, c) = (mu * t).sin_cos();
            (e * c, e * s / mu)
        } else {
            let mu = d.sqrt();
            if mu * t <= 1.0 {
                let e = (-a * t).exp();
                let s = if mu > 0.0 { (mu * t).sinh() / mu } else { t };
                (e * (mu * t).cosh(), e * s)
            } else {
                // e^{-at} cosh and sinh from the two real exponentials: no overflow for strong damping.
                let (ep, em) = (((mu - a) * t).exp(), (-(mu + a) * t).exp());
                (0.5 * (ep + em), 0.5 * (ep - em) / mu)
            }
        }
    }

    /// Phi(t) applied to [x, v].
    fn homogeneous(&self, t: f64, x: f64, v: f64) -> [f64; 2] {
        let (c, s) = self.kernel(t);
        [c * x + s * (v + self.a * x), c * v - s * (self.q * x + self.a * v)]
    }

    /// The state a time `t` after `y`.
    pub fn at(&self, t: f64, y: [f64; 2]) -> [f64; 2] {
        let (a, b) = (self.a, self.b);
        if self.q != 0.0 {
            let equilibrium = b / self.q;
            let [x, v] = self.homogeneous(t, y[0] - equilibrium, y[1]);
            [equilibrium + x, v]
        } else if a == 0.0 {
            [y[0] + t * (y[1] + 0.5 * b * t), y[1] + b * t]
        } else {
            // No stiffness, damped: the rate relaxes to b / 2a.
            let terminal = b / (2.0 * a);
            let excess = y[1] - terminal;
            [y[0] + terminal * t - excess * (-2.0 * a * t).exp_m1() / (2.0 * a), terminal + excess * (-2.0 * a * t).exp()]
        }
    }

    /// The longest span one closed-form evaluation may cover: where the motion grows exponentially
    /// (negative stiffness, an adhesive line), e^30 of growth, so nothing overflows; else unbounded.
    pub fn safe_span(&self) -> f64 {
        let d = self.a * self.a - self.q;
        let growth = if d > 0.0 { d.sqrt() - self.a } else { 0.0 };
        if growth > 0.0 {
            30.0 / growth
        } else {
            f64::INFINITY
        }
    }

    /// y' at the state y.
    pub fn rate(&self, y: [f64; 2]) -> [f64; 2] {
        [y[1], -self.q * y[0] - 2.0 * self.a * y[1] + self.b]
    }

    /// The first (up to three) times in (0, horizon) where the indicator `line` turns (its derivative
    /// changes sign), in increasing order. `eta` is y' at t = 0.
    fn turning_times(&self, line: &Line, eta: [f64; 2], horizon: f64) -> ([f64; 3], usize) {
        // g'(t) = line . Phi(t) eta = e^{-at} (P C(t) + Q S(t)).
        let p = line.overlap * eta[0] + line.rate * eta[1];
        let q = line.overlap * (eta[1] + self.a * eta[0]) - line.rate * (self.q * eta[0] + self.a * eta[1]);
        let mut out = [0.0; 3];
        let mut n = 0;
        let d = self.a * self.a - self.q;
        if p == 0.0 && q == 0.0 {
            return (out, 0);
        }
        if d < 0.0 {
            // P cos(mu t) + (Q/mu) sin(mu t) = R cos(mu t - phi): zeros at mu t = phi + pi/2 + n pi.
            let mu = (-d).sqrt();
            let phi = (q / mu).atan2(p);
            let first = (phi + 0.5 * PI).rem_euclid(PI);
            for k in 0..3 {
                let t = (first + k as f64 * PI) / mu;
                if t > 0.0 && t < horizon {
                    out[n] = t;
                    n += 1;
                }
            }
        } else {
            // P cosh(mu t) + Q sinh(mu t)/mu = 0: tanh(mu t) = -P mu / Q, at most one zero.
            let mu = d.sqrt();
            let t = if q == 0.0 {
                f64::NAN
            } else if mu == 0.0 {
                -p / q
            } else {
                let s = -p * mu / q;
                if s.abs() < 1.0 {
                    s.atanh() / mu
                } else {
                    f64::NAN
                }
            };
            if t > 0.0 && t < horizon {
                out[0] = t;
                n = 1;
            }
        }
        (out, n)
    }

    /// The earliest time in [0, horizon] at which one of `lines` leaves the branch (goes below zero), and
    /// which line it is. Time 0 when the start is already outside or on a bound moving out.
    pub fn first_crossing(&self, y0: [f64; 2], lines: &[Line; 3], horizon: f64) -> Option<(f64, usize)> {
        let eta = self.rate(y0);
        let mut best: Option<(f64, usize)> = None;
        for (i, line) in lines.iter().enumerate() {
            if !line.is_active() {
                continue;
            }
            let g = |t: f64| {
                let y = self.at(t, y0);
                line.at(y[0], y[1])
            };
            let g0 = line.at(y0[0], y0[1]);
            let slope0 = line.overlap * eta[0] + line.rate * eta[1];
            // Outside a bound already, or on it moving out: an event now. A rate indicator below zero is a
            // turning point already passed (as for `adaptive`, only a change from + to - is an event).
            if line.overlap != 0.0 && (g0 < -OUTSIDE || (g0 <= 0.0 && slope0 < 0.0)) {
                return Some((0.0, i));
            }
            let limit = best.map_or(horizon, |b| b.0);
            let (turns, n) = self.turning_times(line, eta, limit);
            let (mut lo, mut g_lo) = (0.0, g0);
            // From an extreme on, two turning points cover a whole period and the later extremes lie
            // closer to the equilibrium, so nothing crosses after them. A start at or above zero counts as
            // an extreme (g only moves away from zero on the first piece, or it crosses there); a start
            // below zero (a rate indicator just past its turning point) needs one turning point more.
            let needed = if g0 >= 0.0 { 2 } else { 3 };
            let mut ends = [limit; 4];
            ends[..n].copy_from_slice(&turns[..n]);
            let pieces = if n >= needed { needed } else { n + 1 };
            for &tb in &ends[..pieces] {
                let g_b = g(tb);
                if g_lo >= 0.0 && g_b < 0.0 {
                    let t = first_outside(g, |v| v >= 0.0, (lo, g_lo), (tb, g_b), |lo, hi| hi - lo <= 2.0 * f64::EPSILON * hi);
                    if best.is_none_or(|b| t < b.0) {
                        best = Some((t, i));
                    }
                    break;
                }
                lo = tb;
                g_lo = g_b;
            }
        }
        best
    }
}

/// Zero-length branch switches in a row before the state is declared stuck.
const MAX_STALLS: u32 = 16;

impl Sphere {
    /// Advances by closed-form segments from branch switch to branch switch. The contact work is the
    /// energy the sphere lost in the wall's frame: W = m g (x_1 - x_0) - m (x_1'^2 - x_0'^2) / 2.
    /// With `stop_at_event`, stops at the first branch switch after `t` that changes the contact state and
    /// returns its time (switches at `t` itself are where the step starts: a master returning there would
    /// make no progress).
    pub(super) fn advance_exact(
        &mut self,
        wall: &WallMotion,
        t: f64,
        t_end: f64,
        y: &mut State,
        stop_at_event: bool,
    ) -> Result<Option<f64>, StepError> {
        let t_start = t;
        let u = wall.velocity;
        let mut t = t;
        let mut x = [wall.at(t) - y.bottom, u - y.velocity];
        // The branch the motion goes into now: the master may have turned the wall around.
        self.contact.accept(x[0], x[1]);
        let mut start_state = self.contact_state();
        let mut event = None;
        let (mut segments, mut stalls) = (0u64, 0u32);
        // A rounding leftover of the communication step is no step at all.
        while t_end - t > 4.0 * f64::EPSILON * t_end.abs() {
            segments += 1;
            if segments > MAX_STEPS {
                return Err(StepError::TooManySteps { t, limit: MAX_STEPS });
            }
            let segment = Segment::new(self.contact.branch_line(), self.mass, self.gravity);
            let span = segment.safe_span();
            let rest = t_end - t;
            let horizon = rest.min(span);
            let crossing = segment.first_crossing(x, &self.contact.indicator_lines(), horizon);
            let tau = crossing.map_or(horizon, |c| c.0);
            let x1 = segment.at(tau, x);
            if !(x1[0].is_finite() && x1[1].is_finite()) {
                return Err(StepError::NotFinite { t });
            }
            y.work += self.mass * (self.gravity * (x1[0] - x[0]) - 0.5 * (x1[1] * x1[1] - x[1] * x[1]));
            x = x1;
            self.steps += 1;
            if crossing.is_some() {
                let before = t;
                t += tau;
                self.events += 1;
                // No progress: a switch at tau 0, or at a tau too small to move the time.
                stalls = if t == before { stalls + 1 } else { 0 };
                if stalls > MAX_STALLS {
                    return Err(StepError::NoProgress { t });
                }
            } else if horizon == rest {
                t = t_end;
            } else {
                t += horizon;
            }
            self.contact.accept(x[0], x[1]);
            if crossing.is_some() && t == t_start {
                start_state = self.contact_state();
            } else if stop_at_event && crossing.is_some() && self.contact_state() != start_state {
                event = Some(t);
                break;
            }
        }
        y.bottom = wall.at(t) - x[0];
        y.velocity = u - x[1];
        Ok(event)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reference by many tiny RK4 steps.
    fn rk4(s: &Segment, t: f64, y0: [f64; 2]) -> [f64; 2] {
        let n = 20_000;
        let h = t / n as f64;
        let mut y = y0;
        for _ in 0..n {
            let k1 = s.rate(y);
            let k2 = s.rate([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
            let k3 = s.rate([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
            let k4 = s.rate([y[0] + h * k3[0], y[1] + h * k3[1]]);
            for i in 0..2 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        y
    }

    #[test]
    fn closed_form_matches_integration_in_every_regime() {
        let cases = [
            Segment { q: 4.0, a: 0.0, b: 1.0 },        // undamped
            Segment { q: 4.0, a: 0.5, b: -1.0 },       // underdamped
            Segment { q: 4.0, a: 2.0, b: 1.0 },        // critical
            Segment { q: 4.0, a: 2.0 + 1e-9, b: 1.0 }, // just overdamped
            Segment { q: 4.0, a: 7.0, b: 1.0 },        // overdamped
            Segment { q: -3.0, a: 0.0, b: 0.5 },       // negative stiffness: escape
            Segment { q: -3.0, a: 1.0, b: 0.5 },
            Segment { q: 0.0, a: 0.0, b: -9.81 }, // free flight
            Segment { q: 0.0, a: 1.5, b: -9.81 }, // damped, no stiffness
        ];
        for s in cases {
            for t in [0.1, 1.0, 3.0] {
                let y = s.at(t, [0.3, -0.7]);
                let r = rk4(&s, t, [0.3, -0.7]);
                for i in 0..2 {
                    assert!((y[i] - r[i]).abs() < 1e-10 * (1.0 + r[i].abs()), "{s:?} t {t}: {y:?} vs {r:?}");
                }
            }
        }
    }

    #[test]
    fn crossing_of_an_oscillation_is_the_analytic_time() {
        // x = cos(2t) from x = 1 at rest: x = 0.5 first at t = pi/6, x' = 0 again at t = pi/2.
        let s = Segment { q: 4.0, a: 0.0, b: 0.0 };
        let lower = Line { constant: -0.5, overlap: 1.0, rate: 0.0 };
        let lines = [lower, Line::INACTIVE, Line::INACTIVE];
        let (t, i) = s.first_crossing([1.0, 0.0], &lines, 10.0).unwrap();
        assert_eq!(i, 0);
        assert!((t - PI / 6.0).abs() < 4.0 * f64::EPSILON, "{t}");
        // A bound the oscillation never reaches is never crossed, however long the horizon.
        let far = [Line { constant: 1.5, overlap: 1.0, rate: 0.0 }, Line::INACTIVE, Line::INACTIVE];
        assert!(s.first_crossing([1.0, 0.0], &far, 1e6).is_none());
        // The rate turns from negative to positive at t = pi/2.
        let rate = [Line { constant: 0.0, overlap: 0.0, rate: -1.0 }, Line::INACTIVE, Line::INACTIVE];
        let (t, _) = s.first_crossing([1.0, -1e-300], &rate, 10.0).unwrap();
        assert!((t - PI / 2.0).abs() < 4.0 * f64::EPSILON, "{t}");
    }

    #[test]
    fn a_start_outside_or_leaving_is_an_event_now() {
        let s = Segment { q: 4.0, a: 0.0, b: 0.0 };
        let lower = [Line { constant: -0.5, overlap: 1.0, rate: 0.0 }, Line::INACTIVE, Line::INACTIVE];
        assert_eq!(s.first_crossing([0.4, 1.0], &lower, 1.0), Some((0.0, 0)));
        assert_eq!(s.first_crossing([0.5, -1.0], &lower, 1.0), Some((0.0, 0)));
        // On the bound and moving in: no event until it comes back, x = sin(2t + pi/4) / sqrt(2) = 0.5 at pi/4.
        let (t, _) = s.first_crossing([0.5, 1.0], &lower, 10.0).unwrap();
        assert!((t - PI / 4.0).abs() < 4.0 * f64::EPSILON, "{t}");
    }

    #[test]
    fn damped_oscillation_inside_a_wide_branch_never_crosses() {
        let s = Segment { q: 1e12, a: 1e4, b: 0.0 };
        let lines = [Line { constant: 2.0, overlap: 1.0, rate: 0.0 }, Line { constant: 2.0, overlap: -1.0, rate: 0.0 }, Line::INACTIVE];
        assert!(s.first_crossing([1.0, 0.0], &lines, 1.0).is_none());
    }
}
