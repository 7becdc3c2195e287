//! A contact sheared by a prescribed tangential displacement: ContactElement's tangential part.
//!
//! The wall moves along x by delta_t relative to the sphere (`wall_tangential_displacement`); the
//! tangential force on the sphere is the incremental spring of the law's tangential model with its
//! Coulomb limit (`law::tangential`, 004 Eqs. 3.11-3.13, 000 Eq. 23), on the same code path as the bed and
//! the oblique impact (`TangentialSpring::step`, `TangentialStiffness::load`). Since the wall drags the
//! contact point, the spring's force is +k_t d delta_t: positive in the direction the wall moved.
//!
//! The history follows the inputs as the normal history does (`Contact::follow`): from the accepted
//! displacement to the current one as one straight step, taken as a DEM step takes it, with k_t and the
//! limit of the normal state at the step's end (the bed's and the oblique impact's rule). So the spring is
//! exact for a path at constant overlap (pure shear) and for a normal path with the displacement held;
//! where both move within one step the stiffness of its end is used throughout (first order in the step,
//! as in a DEM step); a Coulomb limit that shrank along the normal path takes the spring down with it
//! before the tangential step. The work of the spring, the integral of F_t d delta_t, is taken in closed form along
//! that step (`clamped_integral`).
//!
//! Viscous damping 2 gamma sqrt(m* k_t) times the tangential rate acts while the spring sticks (000
//! Sec. 2.2), as in the oblique impact.

use super::contact::Contact;
use crate::law::damping;
use crate::law::tangential::{SpringLoad, TangentialSpring, TangentialStiffness};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// The tangential force at some inputs, from the accepted spring.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShearForce {
    /// The spring's force on the sphere along x [N].
    pub spring: f64,
    /// The viscous damping force on the sphere along x [N] (0 while sliding).
    pub damping: f64,
    /// The spring is on its Coulomb limit (where a further push in its direction slides).
    pub sliding: bool,
    /// The spring's work from the accepted displacement to these inputs, the integral of F_t d delta_t [J].
    pub work: f64,
}

impl ShearForce {
    /// Spring plus damping [N].
    pub fn total(&self) -> f64 {
        self.spring + self.damping
    }
}

/// What the shear remembers: the part of a saved FMU state.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ShearMemory {
    /// The spring's force at the accepted point [N].
    pub spring: f64,
    /// The displacement at the accepted point [m].
    pub displacement: f64,
    /// Whether the spring was on its limit there.
    pub sliding: bool,
}

/// The tangential contact of ContactElement: its parameters and the accepted spring.
#[derive(Debug, Clone, PartialEq)]
pub struct Shear {
    /// The law's tangential stiffness model.
    pub stiffness: TangentialStiffness,
    /// Sliding friction coefficient mu [-] (0: no tangential force at all).
    pub friction: f64,
    /// The spring's force and the displacement at the accepted point.
    pub accepted: ShearMemory,
}

impl Shear {
    /// An unloaded spring at displacement `displacement` [m].
    pub fn new(stiffness: TangentialStiffness, friction: f64, displacement: f64) -> Shear {
        Shear { stiffness, friction, accepted: ShearMemory { spring: 0.0, displacement, sliding: false } }
    }

    /// The spring's stiffness and Coulomb load at overlap `alpha` on the accepted history of `contact`,
    /// or None out of contact or without friction.
    fn load(&self, contact: &Contact, alpha: f64) -> Option<SpringLoad> {
        if self.friction == 0.0 {
            return None;
        }
        self.stiffness.load(&contact.law, alpha, &contact.accepted.history)
    }

    /// The force at overlap `alpha` [m] (on the normal history of `contact`, already walked there),
    /// displacement `displacement` [m] and tangential rate `rate` [m/s]: the accepted spring stepped to
    /// the displacement. Nothing is changed.
    pub fn at(&self, contact: &Contact, alpha: f64, displacement: f64, rate: f64) -> ShearForce {
        // An unloaded spring that is not moved: no force, whatever the normal state (and no law evaluation
        // for a contact that is never sheared).
        if self.accepted.spring == 0.0 && displacement == self.accepted.displacement && rate == 0.0 && !self.accepted.sliding {
            return ShearForce::default();
        }
        let Some(load) = self.load(contact, alpha) else { return ShearForce::default() };
        let from = self.accepted;
        let d = displacement - from.displacement;
        // The normal path first: a limit that shrank on the way takes the spring down with it.
        let limit = self.friction * load.sliding_normal_force.max(0.0);
        let start = from.spring.clamp(-limit, limit);
        let mut spring = TangentialSpring { force: Vector3::new(start, 0.0, 0.0) };
        // The sphere moves by -d against the wall.
        let (f, slid) = spring.step(Vector3::new(-d, 0.0, 0.0), load.stiffness, self.friction, load.sliding_normal_force);
        // On the limit exactly (the projection's scaling may leave an ulp), so that the accepted spring
        // is still on it at the same input: `sliding` says where the spring is, not what this step did.
        let f = if slid { limit.copysign(f.x) } else { f.x };
        // A zero limit (no normal load) holds an unloaded spring that nothing moves: that is not sliding,
        // unless it slid into that point.
        let sliding = slid || f.abs() >= limit && (limit > 0.0 || from.sliding);
        let work = clamped_integral(start, load.stiffness, limit, d);
        let damping = if sliding {
            0.0
        } else {
            let nd = &contact.damping;
            damping::coefficient(nd.restitution, nd.beta_elastic, nd.mass, load.stiffness) * rate
        };
        ShearForce { spring: f, damping, sliding, work }
    }

    /// Takes the spring at these inputs into the history (`at`); returns the spring's work on the way [J].
    pub fn accept(&mut self, contact: &Contact, alpha: f64, displacement: f64) -> f64 {
        let f = self.at(contact, alpha, displacement, 0.0);
        self.accepted = ShearMemory { spring: f.spring, displacement, sliding: f.sliding };
        f.work
    }

    /// Between events, at a completed integrator step: a sliding spring keeps the point reached, so that
    /// a reversal unloads from there (as `Contact::keep_growth` keeps plastic loading). A sticking spring
    /// keeps its accepted point: its force is a function of the displacement alone. Returns the work [J].
    pub fn keep_sliding(&mut self, contact: &Contact, alpha: f64, displacement: f64) -> f64 {
        let f = self.at(contact, alpha, displacement, 0.0);
        if f.sliding && (f.spring != self.accepted.spring || displacement != self.accepted.displacement) {
            self.accept(contact, alpha, displacement)
        } else {
            0.0
        }
    }
}

/// The integral over s from 0 to `d` of clamp(f0 + k s, -limit, limit) [J]: the work of a spring of
/// stiffness `k` [N/m] starting at `f0` [N] under a Coulomb limit `limit` [N] along a displacement `d`
/// [m], as `TangentialSpring::step` would give it at every point of the way (a force beyond a limit
/// that has shrunk is on the limit at once).
pub fn clamped_integral(f0: f64, k: f64, limit: f64, d: f64) -> f64 {
    let clamp = |f: f64| f.clamp(-limit, limit);
    if d == 0.0 {
        return 0.0;
    }
    if k == 0.0 {
        return clamp(f0) * d;
    }
    let (a, b) = if d > 0.0 { (0.0, d) } else { (d, 0.0) };
    // Where f0 + k s meets -limit and +limit, inside (a, b): the pieces' ends.
    let mut cuts = vec![a];
    for s in [(-limit - f0) / k, (limit - f0) / k] {
        if s > a && s < b {
            cuts.push(s);
        }
    }
    cuts.push(b);
    cuts.sort_by(f64::total_cmp);
    let mut sum = 0.0;
    for w in cuts.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let (g_lo, g_hi) = (f0 + k * lo, f0 + k * hi);
        let mid = 0.5 * (g_lo + g_hi);
        // On each piece the clamp is either the line itself or one of the limits.
        sum += if mid.abs() <= limit { mid * (hi - lo) } else { clamp(mid) * (hi - lo) };
    }
    if d > 0.0 {
        sum
    } else {
        -sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The integral by the midpoint rule on a fine grid.
    fn numeric(f0: f64, k: f64, limit: f64, d: f64) -> f64 {
        let n = 200_000;
        let h = d / n as f64;
        (0..n).map(|i| (f0 + k * (i as f64 + 0.5) * h).clamp(-limit, limit) * h).sum()
    }

    #[test]
    fn the_clamped_integral_is_the_numeric_one() {
        for &(f0, k, limit, d) in &[
            (0.0, 1e3, 1.0, 5e-4),
            (0.0, 1e3, 1.0, 5e-3),
            (0.5, 1e3, 1.0, -5e-3),
            (-0.9, 2e3, 1.0, 2e-3),
            (2.0, 1e3, 1.0, 1e-3),
            (2.0, 1e3, 1.0, -4e-3),
            (0.3, 0.0, 1.0, 1e-3),
            (0.3, 1e3, 0.0, 1e-3),
        ] {
            let exact = clamped_integral(f0, k, limit, d);
            let num = numeric(f0, k, limit, d);
            assert!((exact - num).abs() <= 1e-8 * num.abs().max(1e-9), "{f0} {k} {limit} {d}: {exact} vs {num}");
        }
    }

    #[test]
    fn sticking_stores_k_d_squared_over_2() {
        assert_eq!(clamped_integral(0.0, 1e3, 10.0, 2e-3), 0.5 * 1e3 * 4e-6);
    }
}
