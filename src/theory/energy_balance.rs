//! Restitution of an undamped normal impact for any rate-independent law, by the work its force does on a
//! quasi-static path: load from first contact until the work equals the kinetic energy, then unload until
//! the contact separates. Each branch segment is integrated by tanh-sinh quadrature, which handles the
//! square-root ends of the JKR curves; segment ends come from the law's own branch intervals.
//!
//! This is the same balance as 000 Eqs. 76-79 and 004 App. II-III, without their closed forms, so it also
//! serves Thornton-Ning, Tomas, JKR and Hertz.

use super::restitution::ImpactOutcome;
use crate::law::{Branch, NormalLaw};
use crate::numeric::{brent, tanh_sinh};

/// Why a quasi-static impact could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BalanceError {
    /// The overlap grew past the limit without stopping the sphere.
    #[error("the sphere was not stopped before an overlap of {overlap:e} m")]
    NoTurningPoint {
        /// The trial overlap that passed the limit of 10 R* [m].
        overlap: f64,
    },
    /// Too many branch switches (a law that chatters between branches).
    #[error("more than 10000 branch segments on one quasi-static path")]
    TooManySegments,
}

const MAX_SEGMENTS: usize = 10_000;

/// The undamped impact of mass `mass` at speed `v` on a law; `length_scale` (R*) sets the search steps
/// and the overlap limit (10 R*).
pub fn impact<L: NormalLaw>(law: &L, mass: f64, v: f64, length_scale: f64) -> Result<ImpactOutcome, BalanceError> {
    let nudge = 1e-13 * length_scale;
    let limit = 10.0 * length_scale;
    // First point where the law has a force on approach.
    let mut h = law.initial_history();
    let mut alpha = law.evaluate(-limit, &h).upper;
    let mut energy = 0.5 * mass * v * v;
    let force = |x: f64, h: &L::History| law.evaluate(x, h).force;

    // Loading: spend the kinetic energy.
    let mut alpha_max = f64::NAN;
    for _ in 0..MAX_SEGMENTS {
        let e = law.evaluate(alpha, &h);
        h = e.history;
        if e.branch == Branch::Separated {
            alpha = e.upper.max(alpha) + nudge;
            continue;
        }
        let end = e.upper;
        let work = |x: f64| tanh_sinh(|y| force(y, &h), alpha, x);
        if end.is_finite() && end > alpha {
            let w = work(end);
            if w < energy {
                energy -= w;
                alpha = end + nudge;
                continue;
            }
            alpha_max = brent(|x| work(x) - energy, alpha, end, 0.0).unwrap_or(end);
            break;
        }
        // Open-ended branch: bracket the turning point by doubling.
        let mut step = length_scale * 1e-6;
        while work(alpha + step) < energy {
            step *= 2.0;
            if alpha + step > limit {
                return Err(BalanceError::NoTurningPoint { overlap: alpha + step });
            }
        }
        alpha_max = brent(|x| work(x) - energy, alpha, alpha + step, 0.0).unwrap_or(alpha + step);
        break;
    }
    if alpha_max.is_nan() {
        return Err(BalanceError::TooManySegments);
    }
    let top = law.evaluate(alpha_max, &h);
    h = top.history;
    let max_force = top.force;

    // Unloading: collect the work the contact gives back until it separates.
    let mut returned = 0.0;
    let mut alpha = alpha_max;
    for _ in 0..MAX_SEGMENTS {
        let e = law.evaluate(alpha, &h);
        h = e.history;
        if e.branch == Branch::Separated {
            return Ok(ImpactOutcome::from_rebound_energy(mass, v, alpha_max, max_force, returned));
        }
        let end = if e.lower.is_finite() && e.lower < alpha { e.lower } else { alpha - nudge };
        returned += tanh_sinh(|y| force(y, &h), end, alpha);
        if returned < 0.0 {
            return Ok(ImpactOutcome::from_rebound_energy(mass, v, alpha_max, max_force, returned));
        }
        alpha = end - nudge;
    }
    Err(BalanceError::TooManySegments)
}

/// The smallest impact speed at which the sphere rebounds, by bisection on `impact` between `lo` (sticks)
/// and `hi` (rebounds); `None` when the bracket does not hold.
pub fn sticking_velocity<L: NormalLaw>(law: &L, mass: f64, length_scale: f64, lo: f64, hi: f64) -> Option<f64> {
    let sticks = |v: f64| impact(law, mass, v, length_scale).map(|o| o.sticks).unwrap_or(true);
    if !sticks(lo) || sticks(hi) {
        return None;
    }
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if sticks(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-12 * hi {
            break;
        }
    }
    Some(0.5 * (lo + hi))
}
