//! The JKR laws on lanes: the modified JKR of EDEM (`law::jkr_modified`, 004 Sec. 5.1.1, the Ch. 5 beds'
//! law) and the full JKR law (`law::jkr`, 000 App. B). The contact radius is Newton's method on the
//! quartic from the slot's remembered radius (`JkrCurve::contact_radius_from`) with a mask per lane: each
//! lane stops where the scalar loop stops, so the bits are the scalar law's. A lane without a usable
//! guess (a new contact), whose Newton step fails, or that has not settled in eight steps takes the
//! scalar closed form (`JkrCurve::contact_radius`: cube roots and an arc cosine), one lane at a time.
//! Lane parameters: R*, E*, Gamma, b, sqrt(a) at detachment, the detachment overlap of the curve, the
//! overlap where an established contact ends, and 1 for `repulsive` Coulomb limit (else 0).

use super::simd::{Mask, Simd};
use super::x86::{Eval, History, LaneLaw, Lanes};
use super::{Slots, LAW_PARAMS};
use crate::law::jkr::{Jkr, JkrCurve, JkrHistory};
use crate::law::jkr_modified::{JkrFrictionLimit, JkrModified, JkrStiffnessRadius};
use std::f64::consts::PI;

fn params(curve: &JkrCurve, detach_at: f64, repulsive: bool) -> [f64; LAW_PARAMS] {
    let flag = if repulsive { 1.0 } else { 0.0 };
    [curve.radius, curve.youngs_modulus, curve.surface_energy, curve.b, curve.w_detach, curve.alpha_detach, detach_at, flag]
}

/// The contact radius of the lanes in `need` (others give anything), `JkrCurve::contact_radius_from`
/// with the same operations in the same order; `curve(k)` the scalar curve of lane k, read only for the
/// lanes left to the closed form (not on every block).
#[inline(always)]
unsafe fn contact_radius<'a, V: Simd>(p: &[V; LAW_PARAMS], alpha: V, guess: V, need: V::Mask, curve: impl Fn(usize) -> &'a JkrCurve) -> V {
    // SAFETY: the caller runs with the width's instruction set (the trait's contract).
    unsafe {
        let (r, b, wf, alpha_detach) = (p[0], p[3], p[4], p[5]);
        let zero = V::splat(0.0);
        let threshold = wf * wf * V::splat(1.0 + 1e-6);
        // The scalar law's closed form where b = 0, alpha <= alpha_f or the guess is not above a_f.
        let usable = b.ne(zero) & alpha.nle(alpha_detach) & guess.gt(threshold);
        let mut active = need & usable;
        let mut closed_form = need.and_not(usable);
        let mut w = guess.sqrt();
        let mut result = zero;
        for _ in 0..8 {
            if active.bits() == 0 {
                break;
            }
            let df = V::splat(4.0) * w * w * w / r - b;
            let failed = active.and_not(df.gt(zero));
            closed_form = closed_form | failed;
            active = active.and_not(failed);
            let quartic = w * w * w * w / r;
            let step = (quartic - b * w - alpha) / df;
            w = V::select(active, w - step, w);
            let away = df.gt(V::splat(0.4) * w * w * w / r);
            let settled = V::select(away, V::splat(1e-8) * w, V::splat(4.0 * f64::EPSILON) * w);
            let done = active & step.abs().le(settled);
            let m = w.max(wf);
            result = V::select(done, m * m, result);
            active = active.and_not(done);
        }
        closed_form = closed_form | active;
        let lanes = closed_form.bits();
        if lanes != 0 {
            let (a, mut out) = (alpha.to_array(), result.to_array());
            for k in 0..V::N {
                if lanes & (1 << k) != 0 {
                    out.as_mut()[k] = curve(k).contact_radius(a.as_ref()[k]);
                }
            }
            result = V::load(out.as_ref());
        }
        result
    }
}

/// Force and stiffness on the curve at contact radius a (`JkrCurve::force`, `JkrCurve::stiffness`).
#[inline(always)]
unsafe fn on_curve<V: Simd>(p: &[V; LAW_PARAMS], a: V) -> (V, V) {
    // SAFETY: the caller runs with the width's instruction set (the trait's contract).
    unsafe {
        let (r, youngs, gamma, b) = (p[0], p[1], p[2], p[3]);
        let four_e = V::splat(4.0) * youngs;
        let k8 = V::splat(8.0 * PI) * gamma * youngs;
        let a3 = a * a * a;
        let force = four_e * a3 / (V::splat(3.0) * r) - (k8 * a3).sqrt();
        let df_da = four_e * a * a / r - V::splat(1.5) * (k8 * a).sqrt();
        let slope = V::splat(2.0) * a / r - V::splat(0.5) * b / a.sqrt();
        let dalpha_da = slope.max(V::splat(2e-6) * a / r);
        let hertz = V::splat(2.0) * youngs * a;
        let stiffness = V::select(b.eq(V::splat(0.0)), hertz, df_da / dalpha_da);
        (force, stiffness)
    }
}

/// The evaluation of the lanes in contact at contact radius a, with the Coulomb limit's normal force
/// `pull_off` (F_n + 2 f_c, 004 Eq. 3.49) or, where the last parameter is set, `repulsive`
/// (`JkrCurve::repulsive_part`).
#[inline(always)]
unsafe fn evaluation<V: Simd>(p: &[V; LAW_PARAMS], in_contact: V::Mask, a: V, history: History<V>) -> Eval<V> {
    // SAFETY: the caller runs with the width's instruction set (the trait's contract).
    unsafe {
        let (r, youngs, gamma, b) = (p[0], p[1], p[2], p[3]);
        let zero = V::splat(0.0);
        let (force, stiffness) = on_curve(p, a);
        let (force, stiffness, a) = (force.keep(in_contact), stiffness.keep(in_contact), a.keep(in_contact));
        let f_c = V::splat(1.5 * PI) * gamma * r;
        let pull_off = force + V::splat(2.0) * f_c;
        let two_e = V::splat(2.0) * youngs;
        let repulsive_lanes = p[7].ne(zero);
        let sliding_normal_force = if repulsive_lanes.bits() != 0 {
            let k = V::splat(4.0) * youngs / (V::splat(3.0) * r);
            let c = two_e * b;
            let root = (c * c + V::splat(4.0) * k * force).max(zero).sqrt();
            let x = (c + root) / (V::splat(2.0) * k);
            V::select(repulsive_lanes, k * x * x, pull_off)
        } else {
            pull_off
        };
        let none = V::mask_from_fn(|_| false);
        Eval {
            force,
            stiffness,
            in_contact,
            history,
            yielded: none,
            sliding_normal_force,
            radius: a,
            damping_stiffness: two_e * a,
            tangential_stiffness: None,
            attraction: none,
        }
    }
}

impl LaneLaw for JkrModified {
    const LANES: Lanes = Lanes::Vector;
    const MINDLIN: bool = true;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        // Hertz's stiffness radius is not on the lanes: the pair loop is then the scalar one.
        (self.stiffness_radius == JkrStiffnessRadius::Contact).then(|| params(&self.curve, 0.0, self.friction_limit == JkrFrictionLimit::Repulsive))
    }

    #[inline(always)]
    unsafe fn evaluate_lanes<'l, V: Simd>(p: &[V; LAW_PARAMS], alpha: V, h: &History<V>, law: &dyn Fn(usize) -> &'l Self, guess: V) -> Eval<V> {
        // SAFETY: the caller runs with the width's instruction set (the trait's contract).
        unsafe {
            // `alpha <= 0` separates; its negation (true for NaN, as the scalar `else`) touches.
            let in_contact = alpha.nle(V::splat(0.0));
            let a = contact_radius(p, alpha, guess, in_contact, |k| &law(k).curve);
            evaluation(p, in_contact, a, *h)
        }
    }
}

impl LaneLaw for Jkr {
    const LANES: Lanes = Lanes::Vector;
    const MINDLIN: bool = true;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        Some(params(&self.curve, self.detach_overlap(), false))
    }

    /// Lanes `established`.
    #[inline(always)]
    unsafe fn load_history<V: Simd>(h: &[JkrHistory], at: &Slots) -> History<V> {
        // SAFETY: the caller's (the trait's contract).
        unsafe { History { established: V::mask_from_fn(|k| h[at[k]].established), ..History::none() } }
    }

    #[inline(always)]
    fn store_history<V: Simd>(h: &mut [JkrHistory], at: &Slots, v: &History<V>, mask: u32) {
        let est = v.established.bits();
        for k in (0..V::N).filter(|k| mask & (1 << k) != 0) {
            h[at[k]] = JkrHistory { established: est & (1 << k) != 0 };
        }
    }

    /// The initial history is not established, and an established contact holds at negative overlap
    /// down to its end: only an established contact must be visited.
    #[inline(always)]
    unsafe fn must_visit<V: Simd>(h: &History<V>, _param: impl Fn(usize) -> V) -> V::Mask {
        h.established
    }

    #[inline(always)]
    unsafe fn evaluate_lanes<'l, V: Simd>(p: &[V; LAW_PARAMS], alpha: V, h: &History<V>, law: &dyn Fn(usize) -> &'l Self, guess: V) -> Eval<V> {
        // SAFETY: the caller runs with the width's instruction set (the trait's contract).
        unsafe {
            let zero = V::splat(0.0);
            // `Jkr::separated`: (!established && alpha < 0) || alpha < detach_at.
            let separated = alpha.lt(zero).and_not(h.established) | alpha.lt(p[6]);
            let in_contact = !separated;
            let a = contact_radius(p, alpha, guess, in_contact, |k| &law(k).curve);
            evaluation(p, in_contact, a, History { established: in_contact, ..History::none() })
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::bed::interaction::{ContactTemplate, Interaction};
    use crate::law::jkr_modified::JkrModified;
    use serde_json::{json, Value};

    #[test]
    fn hertz_stiffness_radius_leaves_the_lanes_and_keeps_the_tangential_ratio_4_g_over_e() {
        // 004 Tables 5.1-5.3's glass beads.
        let Value::Object(mut map) = json!({"contact_model": "jkr_modified", "particle_youngs_modulus": 55e9,
            "particle_poisson_ratio": 0.25, "surface_energy": 0.5, "friction_coefficient": 0.15})
        else {
            unreachable!()
        };
        let (r, rho) = (5e-4, 2500.0);
        let m = rho * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
        for (name, on_lanes) in [("contact", true), ("hertz", false)] {
            map.insert("jkr_stiffness_radius".into(), name.into());
            let base = ContactTemplate::particle(&map, r, rho).unwrap();
            let it = Interaction::<JkrModified>::particle_pair(&base, r, m, r, m, 0.1).unwrap();
            let mut rows = Vec::new();
            assert_eq!(super::super::table(std::slice::from_ref(&it), &mut rows), on_lanes, "{name}");
            // k_t / k_n = 8 G* r / (2 E* r) whichever radius r is: the tangential damping's ratio stays.
            let (g, e) = (base.effective.shear_modulus, base.effective.youngs_modulus);
            let q = it.tangential_root_ratio.expect("a constant ratio");
            assert!((q * q / (4.0 * g / e) - 1.0).abs() < 1e-12, "{name}: {q}");
        }
    }
}
