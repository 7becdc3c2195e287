//! The force of one contact, the same for particle-particle and particle-wall pairs:
//! - normal: the law at overlap alpha with the contact's history, plus viscous damping
//!   2 gamma sqrt(m* k_n) d alpha/dt (000 Eqs. 24-26);
//! - tangential: an incremental spring k_t with the Coulomb limit mu N (000 Eqs. 22-23,
//!   `law::tangential`), kept in the tangent plane as the contact turns, with viscous damping while it
//!   sticks;
//! - rolling: the load mu_r |f_n| of EDEM's constant directional torque model (004 Table 5.3), summed
//!   per particle and applied against its spin by the integrator.
//!
//! The vector arithmetic of `contact` is the hand-written `dot`, `sub`, `scale`, `cross` of `bed/mod.rs`,
//! not nalgebra's operators: this is the hot path, and there they cost 4 % more instructions (measured
//! in `bed/mod.rs`; the tangential spring's own update keeps nalgebra at no cost).

use super::interaction::{BedLaw, Interaction};
use super::{cross, dot, scale, sub, Vec3, ZERO};
use crate::law::tangential::TangentialSpring;

/// What a contact gives the two bodies.
#[derive(Debug, Clone, Copy, Default)]
pub struct PairForce {
    /// Force on the first body [N] (the partner gets the opposite).
    pub force: Vec3,
    /// Tangential force on the first body [N], for the torques.
    pub tangential: Vec3,
    /// mu_r |f_n| [N]: the rolling load.
    pub rolling_load: f64,
}

/// One contact. `normal` points from the first body's centre to the partner; `relative_velocity` is
/// the velocity of the first body's surface relative to the partner's surface at the contact point;
/// `radius_guess` keeps the contact radius for the next step's solve (the JKR laws).
/// Returns `None` when the pair carries no force (its history and spring are updated all the same).
#[inline(always)]
#[allow(clippy::too_many_arguments)] // the force loop's one call per contact, inlined: the pair, its state and its memory
pub fn contact<L: BedLaw>(
    it: &Interaction<L>,
    alpha: f64,
    normal: Vec3,
    relative_velocity: Vec3,
    history: &mut L::History,
    spring: &mut Vec3,
    radius_guess: &mut f64,
    dt: f64,
) -> Option<PairForce> {
    let law = &it.law;
    let (ev, k_damp, radius) = law.evaluate_near(alpha, history, *radius_guess);
    // Most contacts keep their history from step to step: skip the store (Nan's is 72 bytes).
    if ev.history != *history {
        *history = ev.history;
    }
    *radius_guess = radius.unwrap_or(0.0);
    if !ev.branch.in_contact() {
        *spring = ZERO;
        if ev.force == 0.0 {
            return None;
        }
        // The Tomas attraction outside contact: a normal force only.
        return Some(PairForce { force: scale(normal, -ev.force), tangential: ZERO, rolling_load: 0.0 });
    }
    let approach = dot(relative_velocity, normal);
    let yielded = law.has_yielded(&ev.history);
    let root_k = k_damp.abs().sqrt();
    let f_n = ev.force + (if yielded { it.damping_plastic } else { it.damping_elastic }) * root_k * approach;
    let mut force = scale(normal, -f_n);
    let mut tangential = ZERO;
    if it.friction > 0.0 {
        let v_t = sub(relative_velocity, scale(normal, approach));
        // Keep the stored spring in the tangent plane of the turned contact, with its magnitude. (Only
        // removing the normal component, as LAMMPS' gran/hooke/history does, loses a little of the
        // spring at every step a contact turns: a bed at rest then creeps, tests/bed.rs.)
        let s = *spring;
        let along = dot(s, normal);
        let mut s_t = sub(s, scale(normal, along));
        if along != 0.0 {
            let t2 = dot(s_t, s_t);
            if t2 > 0.0 {
                // sqrt(1 + x), x = along^2 / t2: a contact turns little in a step, and for x < 1e-4 three
                // terms of the series are exact to rounding without a square root.
                let x = along * along / t2;
                let factor = if x < 1e-4 { 1.0 + x * (0.5 - 0.125 * x) } else { (1.0 + x).sqrt() };
                s_t = scale(s_t, factor);
            }
        }
        let normal_load = law.sliding_normal_force(ev.force, alpha, &ev.history);
        let k_t = it.tangential.at(alpha, ev.stiffness, normal_load, law.mindlin_radius(alpha, &ev.history, radius));
        let mut ts = TangentialSpring { force: s_t };
        let (f_s, sliding) = ts.step(scale(v_t, dt), k_t, it.friction, normal_load);
        *spring = f_s;
        tangential = if sliding {
            f_s
        } else {
            // 2 gamma sqrt(m* k_t): where k_t / k_n is fixed for the pair (every law but Tomas), from the
            // square root of k_n already taken for the normal damping.
            let root_kt = match it.tangential_root_ratio {
                Some(q) => q * root_k,
                None => k_t.sqrt(),
            };
            sub(f_s, scale(v_t, it.damping_elastic * root_kt))
        };
        force = super::add(force, tangential);
    }
    Some(PairForce { force, tangential, rolling_load: it.rolling_friction * ev.force.abs() })
}

/// The velocity of body 1's surface relative to body 2's at a contact along `normal` (1 -> 2), with
/// levers l1, l2 from the centres to the contact point.
#[inline(always)]
pub fn surface_velocity(v1: Vec3, w1: Vec3, l1: f64, v2: Vec3, w2: Vec3, l2: f64, normal: Vec3) -> Vec3 {
    // v1 + w1 x (l1 n) - (v2 + w2 x (-l2 n))
    let w = Vec3::new(w1[0] * l1 + w2[0] * l2, w1[1] * l1 + w2[1] * l2, w1[2] * l1 + w2[2] * l2);
    super::add(sub(v1, v2), cross(w, normal))
}
