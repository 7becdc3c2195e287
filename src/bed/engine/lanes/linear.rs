//! The linear spring on lanes (`law::linear`, 004 Eq. 3.9): k_n alpha for alpha > 0. No history.

use super::x86::{Eval4, History4, LaneLaw, Lanes};
use super::LAW_PARAMS;
use crate::law::linear::Linear;
use std::arch::x86_64::*;

impl LaneLaw for Linear {
    const LANES: Lanes = Lanes::Vector;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        Some([self.stiffness, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    }

    #[inline(always)]
    unsafe fn evaluate4(p: &[__m256d; LAW_PARAMS], alpha: __m256d, h: &History4, _laws: [&Self; 4], _guess: __m256d) -> Eval4 {
        // SAFETY: the caller runs with AVX2 (the trait's contract).
        unsafe {
            let k = p[0];
            // `alpha <= 0` separates; its negation (true for NaN, as the scalar `else`) touches.
            let in_contact = _mm256_cmp_pd::<_CMP_NLE_UQ>(alpha, _mm256_setzero_pd());
            let force = _mm256_and_pd(_mm256_mul_pd(k, alpha), in_contact);
            Eval4 {
                force,
                stiffness: k,
                in_contact,
                history: *h,
                yielded: _mm256_setzero_pd(),
                sliding_normal_force: force,
                radius: _mm256_setzero_pd(),
                damping_stiffness: k,
                tangential_stiffness: None,
                attraction: _mm256_setzero_pd(),
            }
        }
    }
}
