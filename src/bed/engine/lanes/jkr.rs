//! The JKR laws on lanes: the modified JKR of EDEM (`law::jkr_modified`, 004 Sec. 5.1.1, the Ch. 5 beds'
//! law) and the full JKR law (`law::jkr`, 000 App. B). The contact radius is Newton's method on the
//! quartic from the slot's remembered radius (`JkrCurve::contact_radius_from`) with a mask per lane: each
//! lane stops where the scalar loop stops, so the bits are the scalar law's. A lane without a usable
//! guess (a new contact), whose Newton step fails, or that has not settled in eight steps takes the
//! scalar closed form (`JkrCurve::contact_radius`: cube roots and an arc cosine), one lane at a time.
//! Lane parameters: R*, E*, Gamma, b, sqrt(a) at detachment, the detachment overlap of the curve, the
//! overlap where an established contact ends, and 1 for `repulsive` Coulomb limit (else 0).

use super::x86::{select, splat, Eval4, History4, LaneLaw, Lanes};
use super::LAW_PARAMS;
use crate::law::jkr::{Jkr, JkrCurve, JkrHistory};
use crate::law::jkr_modified::{JkrFrictionLimit, JkrModified, JkrStiffnessRadius};
use std::arch::x86_64::*;
use std::f64::consts::PI;

fn params(curve: &JkrCurve, detach_at: f64, repulsive: bool) -> [f64; LAW_PARAMS] {
    let flag = if repulsive { 1.0 } else { 0.0 };
    [curve.radius, curve.youngs_modulus, curve.surface_energy, curve.b, curve.w_detach, curve.alpha_detach, detach_at, flag]
}

/// The contact radius of the lanes in `need` (others give anything), `JkrCurve::contact_radius_from`
/// with the same operations in the same order.
#[inline(always)]
unsafe fn contact_radius4(p: &[__m256d; LAW_PARAMS], alpha: __m256d, guess: __m256d, need: __m256d, curves: [&JkrCurve; 4]) -> __m256d {
    // SAFETY: the caller runs with AVX2 (the trait's contract).
    unsafe {
        let (r, b, wf, alpha_detach) = (p[0], p[3], p[4], p[5]);
        let zero = _mm256_setzero_pd();
        let threshold = _mm256_mul_pd(_mm256_mul_pd(wf, wf), splat(1.0 + 1e-6));
        // The scalar law's closed form where b = 0, alpha <= alpha_f or the guess is not above a_f.
        let usable = _mm256_and_pd(
            _mm256_and_pd(_mm256_cmp_pd::<_CMP_NEQ_UQ>(b, zero), _mm256_cmp_pd::<_CMP_NLE_UQ>(alpha, alpha_detach)),
            _mm256_cmp_pd::<_CMP_GT_OQ>(guess, threshold),
        );
        let mut active = _mm256_and_pd(need, usable);
        let mut closed_form = _mm256_andnot_pd(usable, need);
        let mut w = _mm256_sqrt_pd(guess);
        let mut result = zero;
        for _ in 0..8 {
            if _mm256_movemask_pd(active) == 0 {
                break;
            }
            let df = _mm256_sub_pd(_mm256_div_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(splat(4.0), w), w), w), r), b);
            let failed = _mm256_andnot_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(df, zero), active);
            closed_form = _mm256_or_pd(closed_form, failed);
            active = _mm256_andnot_pd(failed, active);
            let quartic = _mm256_div_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(w, w), w), w), r);
            let step = _mm256_div_pd(_mm256_sub_pd(_mm256_sub_pd(quartic, _mm256_mul_pd(b, w)), alpha), df);
            w = select(active, _mm256_sub_pd(w, step), w);
            let away = _mm256_cmp_pd::<_CMP_GT_OQ>(df, _mm256_div_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(splat(0.4), w), w), w), r));
            let settled = select(away, _mm256_mul_pd(splat(1e-8), w), _mm256_mul_pd(splat(4.0 * f64::EPSILON), w));
            let done = _mm256_and_pd(active, _mm256_cmp_pd::<_CMP_LE_OQ>(_mm256_andnot_pd(splat(-0.0), step), settled));
            let m = _mm256_max_pd(w, wf);
            result = select(done, _mm256_mul_pd(m, m), result);
            active = _mm256_andnot_pd(done, active);
        }
        closed_form = _mm256_or_pd(closed_form, active);
        let lanes = _mm256_movemask_pd(closed_form);
        if lanes != 0 {
            let (mut a, mut out) = ([0.0f64; 4], [0.0f64; 4]);
            _mm256_storeu_pd(a.as_mut_ptr(), alpha);
            _mm256_storeu_pd(out.as_mut_ptr(), result);
            for k in 0..4 {
                if lanes & (1 << k) != 0 {
                    out[k] = curves[k].contact_radius(a[k]);
                }
            }
            result = _mm256_loadu_pd(out.as_ptr());
        }
        result
    }
}

/// Force and stiffness on the curve at contact radius a (`JkrCurve::force`, `JkrCurve::stiffness`).
#[inline(always)]
unsafe fn on_curve4(p: &[__m256d; LAW_PARAMS], a: __m256d) -> (__m256d, __m256d) {
    // SAFETY: the caller runs with AVX2 (the trait's contract).
    unsafe {
        let (r, youngs, gamma, b) = (p[0], p[1], p[2], p[3]);
        let four_e = _mm256_mul_pd(splat(4.0), youngs);
        let k8 = _mm256_mul_pd(_mm256_mul_pd(splat(8.0 * PI), gamma), youngs);
        let a3 = _mm256_mul_pd(_mm256_mul_pd(a, a), a);
        let force = _mm256_sub_pd(_mm256_div_pd(_mm256_mul_pd(four_e, a3), _mm256_mul_pd(splat(3.0), r)), _mm256_sqrt_pd(_mm256_mul_pd(k8, a3)));
        let df_da = _mm256_sub_pd(
            _mm256_div_pd(_mm256_mul_pd(_mm256_mul_pd(four_e, a), a), r),
            _mm256_mul_pd(splat(1.5), _mm256_sqrt_pd(_mm256_mul_pd(k8, a))),
        );
        let slope = _mm256_sub_pd(_mm256_div_pd(_mm256_mul_pd(splat(2.0), a), r), _mm256_div_pd(_mm256_mul_pd(splat(0.5), b), _mm256_sqrt_pd(a)));
        let dalpha_da = _mm256_max_pd(slope, _mm256_div_pd(_mm256_mul_pd(splat(2e-6), a), r));
        let hertz = _mm256_mul_pd(_mm256_mul_pd(splat(2.0), youngs), a);
        let stiffness = select(_mm256_cmp_pd::<_CMP_EQ_OQ>(b, _mm256_setzero_pd()), hertz, _mm256_div_pd(df_da, dalpha_da));
        (force, stiffness)
    }
}

/// The evaluation of the lanes in contact at contact radius a, with the Coulomb limit's normal force
/// `pull_off` (F_n + 2 f_c, 004 Eq. 3.49) or, where the last parameter is set, `repulsive`
/// (`JkrCurve::repulsive_part`).
#[inline(always)]
unsafe fn evaluation(p: &[__m256d; LAW_PARAMS], in_contact: __m256d, a: __m256d, history: History4) -> Eval4 {
    // SAFETY: the caller runs with AVX2 (the trait's contract).
    unsafe {
        let (r, youngs, gamma, b) = (p[0], p[1], p[2], p[3]);
        let (force, stiffness) = on_curve4(p, a);
        let (force, stiffness, a) = (_mm256_and_pd(force, in_contact), _mm256_and_pd(stiffness, in_contact), _mm256_and_pd(a, in_contact));
        let f_c = _mm256_mul_pd(_mm256_mul_pd(splat(1.5 * PI), gamma), r);
        let pull_off = _mm256_add_pd(force, _mm256_mul_pd(splat(2.0), f_c));
        let two_e = _mm256_mul_pd(splat(2.0), youngs);
        let repulsive_lanes = _mm256_cmp_pd::<_CMP_NEQ_UQ>(p[7], _mm256_setzero_pd());
        let sliding_normal_force = if _mm256_movemask_pd(repulsive_lanes) != 0 {
            let k = _mm256_div_pd(_mm256_mul_pd(splat(4.0), youngs), _mm256_mul_pd(splat(3.0), r));
            let c = _mm256_mul_pd(two_e, b);
            let root = _mm256_sqrt_pd(_mm256_max_pd(
                _mm256_add_pd(_mm256_mul_pd(c, c), _mm256_mul_pd(_mm256_mul_pd(splat(4.0), k), force)),
                _mm256_setzero_pd(),
            ));
            let x = _mm256_div_pd(_mm256_add_pd(c, root), _mm256_mul_pd(splat(2.0), k));
            select(repulsive_lanes, _mm256_mul_pd(_mm256_mul_pd(k, x), x), pull_off)
        } else {
            pull_off
        };
        let damping_stiffness = _mm256_mul_pd(two_e, a);
        Eval4 {
            force,
            stiffness,
            in_contact,
            history,
            yielded: _mm256_setzero_pd(),
            sliding_normal_force,
            radius: a,
            damping_stiffness,
            tangential_stiffness: None,
            attraction: _mm256_setzero_pd(),
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
    unsafe fn evaluate4(p: &[__m256d; LAW_PARAMS], alpha: __m256d, h: &History4, laws: [&Self; 4], guess: __m256d) -> Eval4 {
        // SAFETY: the caller runs with AVX2 (the trait's contract).
        unsafe {
            // `alpha <= 0` separates; its negation (true for NaN, as the scalar `else`) touches.
            let in_contact = _mm256_cmp_pd::<_CMP_NLE_UQ>(alpha, _mm256_setzero_pd());
            let a = contact_radius4(p, alpha, guess, in_contact, laws.map(|l| &l.curve));
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

    /// Lane `a`: established (a mask).
    fn load_history(h: &[JkrHistory]) -> History4 {
        let est = |k: usize| if h[k].established { f64::from_bits(u64::MAX) } else { 0.0 };
        // SAFETY: `_mm256_set_pd` needs only AVX, which every caller (the AVX2 lane loop) has.
        unsafe { History4 { a: _mm256_set_pd(est(3), est(2), est(1), est(0)), b: _mm256_setzero_pd() } }
    }

    fn store_history(h: &mut [JkrHistory], v: &History4, mask: i32) {
        let mut est = [0.0f64; 4];
        // SAFETY: as in `load_history`.
        unsafe { _mm256_storeu_pd(est.as_mut_ptr(), v.a) };
        for k in 0..4 {
            if mask & (1 << k) != 0 {
                h[k] = JkrHistory { established: est[k].to_bits() != 0 };
            }
        }
    }

    /// The initial history is not established, and an established contact holds at negative overlap
    /// down to its end: only an established contact must be visited.
    #[inline(always)]
    unsafe fn must_visit(h: &History4) -> __m256d {
        h.a
    }

    #[inline(always)]
    unsafe fn evaluate4(p: &[__m256d; LAW_PARAMS], alpha: __m256d, h: &History4, laws: [&Self; 4], guess: __m256d) -> Eval4 {
        // SAFETY: the caller runs with AVX2 (the trait's contract).
        unsafe {
            let zero = _mm256_setzero_pd();
            // `Jkr::separated`: (!established && alpha < 0) || alpha < detach_at.
            let separated = _mm256_or_pd(_mm256_andnot_pd(h.a, _mm256_cmp_pd::<_CMP_LT_OQ>(alpha, zero)), _mm256_cmp_pd::<_CMP_LT_OQ>(alpha, p[6]));
            let in_contact = _mm256_xor_pd(separated, _mm256_cmp_pd::<_CMP_EQ_UQ>(zero, zero));
            let a = contact_radius4(p, alpha, guess, in_contact, laws.map(|l| &l.curve));
            evaluation(p, in_contact, a, History4 { a: in_contact, b: zero })
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
            "particle_poisson_ratio": 0.25, "surface_energy": 0.5, "friction_coefficient": 0.15}) else { unreachable!() };
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
