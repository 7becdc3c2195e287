//! Hertz's law on lanes (`law::hertz`, 004 Eq. 3.14): 4/3 E* sqrt(R*) alpha^(3/2) for alpha > 0, with its
//! contact radius a = sqrt(R* alpha) for Mindlin's tangential stiffness. No history.

use super::x86::{splat, Eval4, History4, LaneLaw, Lanes};
use super::LAW_PARAMS;
use crate::law::hertz::Hertz;
use std::arch::x86_64::*;

impl LaneLaw for Hertz {
    const LANES: Lanes = Lanes::Vector;
    const MINDLIN: bool = true;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        Some([self.radius, self.youngs_modulus, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    }

    #[inline(always)]
    unsafe fn evaluate4(p: &[__m256d; LAW_PARAMS], alpha: __m256d, h: &History4, _laws: [&Self; 4], _guess: __m256d) -> Eval4 {
        // SAFETY: the caller runs with AVX2 (the trait's contract).
        unsafe {
            let (radius, youngs) = (p[0], p[1]);
            // `alpha <= 0` separates (force and stiffness 0); its negation (true for NaN, as the scalar
            // `else`) touches.
            let in_contact = _mm256_cmp_pd::<_CMP_NLE_UQ>(alpha, _mm256_setzero_pd());
            let root = _mm256_sqrt_pd(_mm256_mul_pd(radius, alpha));
            let force = _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(splat(4.0 / 3.0), youngs), root), alpha);
            let force = _mm256_and_pd(force, in_contact);
            let two_e = _mm256_mul_pd(splat(2.0), youngs);
            let stiffness = _mm256_and_pd(_mm256_mul_pd(two_e, root), in_contact); // 000 Eq. 41
            Eval4 {
                force,
                stiffness,
                in_contact,
                history: *h,
                yielded: _mm256_setzero_pd(),
                sliding_normal_force: force,
                // Hertz::evaluate_with_radius: a = 2 E* a / (2 E*)
                radius: _mm256_div_pd(stiffness, two_e),
                damping_stiffness: stiffness,
                tangential_stiffness: None,
                attraction: _mm256_setzero_pd(),
            }
        }
    }
}
