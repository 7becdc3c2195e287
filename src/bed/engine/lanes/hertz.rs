//! Hertz's law on lanes (`law::hertz`, 004 Eq. 3.14): 4/3 E* sqrt(R*) alpha^(3/2) for alpha > 0, with its
//! contact radius a = sqrt(R* alpha) for Mindlin's tangential stiffness. No history.

use super::simd::Simd;
use super::x86::{Eval, History, LaneLaw, Lanes};
use super::LAW_PARAMS;
use crate::law::hertz::Hertz;

impl LaneLaw for Hertz {
    const LANES: Lanes = Lanes::Vector;
    const MINDLIN: bool = true;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        Some([self.radius, self.youngs_modulus, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    }

    #[inline(always)]
    unsafe fn evaluate_lanes<'l, V: Simd>(p: &[V; LAW_PARAMS], alpha: V, h: &History<V>, _law: &dyn Fn(usize) -> &'l Self, _guess: V) -> Eval<V> {
        // SAFETY: the caller runs with the width's instruction set (the trait's contract).
        unsafe {
            let (radius, youngs, zero) = (p[0], p[1], V::splat(0.0));
            // `alpha <= 0` separates (force and stiffness 0); its negation (true for NaN, as the scalar
            // `else`) touches.
            let in_contact = alpha.nle(zero);
            let root = (radius * alpha).sqrt();
            let force = (V::splat(4.0 / 3.0) * youngs * root * alpha).keep(in_contact);
            let two_e = V::splat(2.0) * youngs;
            let stiffness = (two_e * root).keep(in_contact); // 000 Eq. 41
            let none = V::mask_from_fn(|_| false);
            Eval {
                force,
                stiffness,
                in_contact,
                history: *h,
                yielded: none,
                sliding_normal_force: force,
                // Hertz::evaluate_with_radius: a = 2 E* a / (2 E*)
                radius: stiffness / two_e,
                damping_stiffness: stiffness,
                tangential_stiffness: None,
                attraction: none,
            }
        }
    }
}
