//! The linear spring on lanes (`law::linear`, 004 Eq. 3.9): k_n alpha for alpha > 0. No history.

use super::simd::Simd;
use super::x86::{Eval, History, LaneLaw, Lanes};
use super::LAW_PARAMS;
use crate::law::linear::Linear;

impl LaneLaw for Linear {
    const LANES: Lanes = Lanes::Vector;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        Some([self.stiffness, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    }

    #[inline(always)]
    unsafe fn evaluate_lanes<'l, V: Simd>(p: &[V; LAW_PARAMS], alpha: V, h: &History<V>, _law: &dyn Fn(usize) -> &'l Self, _guess: V) -> Eval<V> {
        // SAFETY: the caller runs with the width's instruction set (the trait's contract).
        unsafe {
            let (k, zero) = (p[0], V::splat(0.0));
            // `alpha <= 0` separates; its negation (true for NaN, as the scalar `else`) touches.
            let in_contact = alpha.nle(zero);
            let force = (k * alpha).keep(in_contact);
            let none = V::mask_from_fn(|_| false);
            Eval {
                force,
                stiffness: k,
                in_contact,
                history: *h,
                yielded: none,
                sliding_normal_force: force,
                radius: zero,
                damping_stiffness: k,
                tangential_stiffness: None,
                attraction: none,
            }
        }
    }
}
