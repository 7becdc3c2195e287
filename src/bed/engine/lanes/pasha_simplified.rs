//! Pasha's simplified law on lanes (`law::pasha_simplified`, `law::pasha::pasha_evaluate`; 004 Secs.
//! 4.1.4-4.1.5): every branch computed, the first that holds selected, in the scalar law's order and with
//! its operations. Lanes: `a` established (a mask), `b` alpha_max. Constant k_e only.

use super::x86::{select, splat, Eval4, History4, LaneLaw, Lanes};
use super::LAW_PARAMS;
use crate::law::pasha::{PashaHistory, PashaStiffnessLaw};
use crate::law::pasha_simplified::PashaSimplified;
use std::arch::x86_64::*;

impl LaneLaw for PashaSimplified {
    const LANES: Lanes = Lanes::Vector;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        (self.stiffness.law == PashaStiffnessLaw::Constant).then_some([self.stiffness.k_e, self.k_p, self.k_cp, self.f_0p, self.f_ce, self.alpha_0, 0.0, 0.0])
    }

    fn load_history(h: &[PashaHistory]) -> History4 {
        let est = |k: usize| if h[k].established { f64::from_bits(u64::MAX) } else { 0.0 };
        // SAFETY: `_mm256_set_pd` needs only AVX, which every caller (the AVX2 lane loop) has.
        unsafe {
            History4 {
                a: _mm256_set_pd(est(3), est(2), est(1), est(0)),
                b: _mm256_set_pd(h[3].alpha_max, h[2].alpha_max, h[1].alpha_max, h[0].alpha_max),
            }
        }
    }

    fn store_history(h: &mut [PashaHistory], v: &History4, mask: i32) {
        let (mut est, mut alpha_max) = ([0.0f64; 4], [0.0f64; 4]);
        // SAFETY: as in `load_history`.
        unsafe {
            _mm256_storeu_pd(est.as_mut_ptr(), v.a);
            _mm256_storeu_pd(alpha_max.as_mut_ptr(), v.b);
        }
        for k in 0..4 {
            if mask & (1 << k) != 0 {
                h[k] = PashaHistory { established: est[k].to_bits() != 0, alpha_max: alpha_max[k] };
            }
        }
    }

    /// The initial history is not established and a detached one rests apart (`rests_apart`): only an
    /// established contact must be visited.
    #[inline(always)]
    unsafe fn must_visit(h: &History4) -> __m256d {
        h.a
    }

    #[inline(always)]
    unsafe fn evaluate4(p: &[__m256d; LAW_PARAMS], alpha: __m256d, h: &History4, _laws: [&Self; 4], _guess: __m256d) -> Eval4 {
        // SAFETY: the caller runs with AVX2 (the trait's contract).
        unsafe {
            let [k_e, k_p, k_cp, f_0p, f_ce, alpha_0, _, _] = *p;
            let (established, alpha_max) = (h.a, h.b);
            let zero = _mm256_setzero_pd();
            let two = splat(2.0);
            // PashaSimplified::points
            let f_max = _mm256_mul_pd(k_p, _mm256_sub_pd(alpha_max, alpha_0));
            let alpha_p = _mm256_sub_pd(alpha_max, _mm256_div_pd(f_max, k_e));
            let alpha_cp = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(k_e, alpha_p), f_0p), _mm256_add_pd(k_e, k_cp));
            let alpha_fp = _mm256_sub_pd(_mm256_mul_pd(two, alpha_cp), alpha_p);
            // pasha_evaluate: apart, adhesive, elastic, plastic, the first that holds
            let recontact = _mm256_max_pd(alpha_fp, zero);
            let apart = _mm256_or_pd(
                _mm256_andnot_pd(established, _mm256_cmp_pd::<_CMP_LT_OQ>(alpha, recontact)),
                _mm256_cmp_pd::<_CMP_LT_OQ>(alpha, alpha_fp),
            );
            let adhesive = _mm256_cmp_pd::<_CMP_LE_OQ>(alpha, alpha_cp);
            let elastic = _mm256_cmp_pd::<_CMP_LE_OQ>(alpha, alpha_max);
            let f_adhesive = _mm256_mul_pd(k_e, _mm256_sub_pd(_mm256_sub_pd(_mm256_mul_pd(two, alpha_cp), alpha_p), alpha));
            let f_elastic = _mm256_mul_pd(k_e, _mm256_sub_pd(alpha, alpha_p));
            let f_plastic = _mm256_mul_pd(k_p, _mm256_sub_pd(alpha, alpha_0));
            let force = select(adhesive, f_adhesive, select(elastic, f_elastic, f_plastic));
            let force = _mm256_andnot_pd(apart, force);
            let stiffness = select(adhesive, _mm256_xor_pd(k_e, splat(-0.0)), select(elastic, k_e, k_p));
            let unloaded = _mm256_or_pd(_mm256_or_pd(apart, adhesive), elastic);
            let new_max = select(unloaded, alpha_max, alpha);
            let in_contact = _mm256_xor_pd(apart, _mm256_cmp_pd::<_CMP_EQ_UQ>(zero, zero));
            Eval4 {
                force,
                stiffness,
                in_contact,
                history: History4 { a: in_contact, b: new_max },
                yielded: _mm256_cmp_pd::<_CMP_GT_OQ>(new_max, zero),
                // 004 Eq. 4.28: F_n + k_cp alpha + f_0p - f_ce
                sliding_normal_force: _mm256_sub_pd(_mm256_add_pd(_mm256_add_pd(force, _mm256_mul_pd(k_cp, alpha)), f_0p), f_ce),
                radius: zero,
                damping_stiffness: stiffness,
                tangential_stiffness: None,
                attraction: _mm256_setzero_pd(),
            }
        }
    }
}
