//! Pasha's simplified law on lanes (`law::pasha_simplified`, `law::pasha::pasha_evaluate`; 004 Secs.
//! 4.1.4-4.1.5): every branch computed, the first that holds selected, in the scalar law's order and with
//! its operations. History lanes: `established` and alpha_max. Constant k_e only.

use super::simd::{Mask, Simd};
use super::x86::{Eval, History, LaneLaw, Lanes};
use super::{Slots, LAW_PARAMS};
use crate::law::pasha::{PashaHistory, PashaStiffnessLaw};
use crate::law::pasha_simplified::PashaSimplified;

impl LaneLaw for PashaSimplified {
    const LANES: Lanes = Lanes::Vector;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        (self.stiffness.law == PashaStiffnessLaw::Constant).then_some([
            self.stiffness.k_e,
            self.k_p,
            self.k_cp,
            self.f_0p,
            self.f_ce,
            self.alpha_0,
            0.0,
            0.0,
        ])
    }

    #[inline(always)]
    unsafe fn load_history<V: Simd>(h: &[PashaHistory], at: &Slots) -> History<V> {
        // SAFETY: the caller's (the trait's contract).
        unsafe { History { established: V::mask_from_fn(|k| h[at[k]].established), value: V::from_fn(|k| h[at[k]].alpha_max), ..History::none() } }
    }

    #[inline(always)]
    fn store_history<V: Simd>(h: &mut [PashaHistory], at: &Slots, v: &History<V>, mask: u32) {
        let (est, alpha_max) = (v.established.bits(), v.value.to_array());
        for k in (0..V::N).filter(|k| mask & (1 << k) != 0) {
            h[at[k]] = PashaHistory { established: est & (1 << k) != 0, alpha_max: alpha_max.as_ref()[k] };
        }
    }

    /// The initial history is not established and a detached one rests apart (`rests_apart`): only an
    /// established contact must be visited.
    #[inline(always)]
    unsafe fn must_visit<V: Simd>(h: &History<V>, _param: impl Fn(usize) -> V) -> V::Mask {
        h.established
    }

    #[inline(always)]
    unsafe fn evaluate_lanes<'l, V: Simd>(p: &[V; LAW_PARAMS], alpha: V, h: &History<V>, _law: &dyn Fn(usize) -> &'l Self, _guess: V) -> Eval<V> {
        // SAFETY: the caller runs with the width's instruction set (the trait's contract).
        unsafe {
            let [k_e, k_p, k_cp, f_0p, f_ce, alpha_0, _, _] = *p;
            let (established, alpha_max) = (h.established, h.value);
            let zero = V::splat(0.0);
            let two = V::splat(2.0);
            // PashaSimplified::points
            let f_max = k_p * (alpha_max - alpha_0);
            let alpha_p = alpha_max - f_max / k_e;
            let alpha_cp = (k_e * alpha_p - f_0p) / (k_e + k_cp);
            let alpha_fp = two * alpha_cp - alpha_p;
            // pasha_evaluate: apart, adhesive, elastic, plastic, the first that holds
            let recontact = alpha_fp.max(zero);
            let apart = alpha.lt(recontact).and_not(established) | alpha.lt(alpha_fp);
            let adhesive = alpha.le(alpha_cp);
            let elastic = alpha.le(alpha_max);
            let f_adhesive = k_e * (two * alpha_cp - alpha_p - alpha);
            let f_elastic = k_e * (alpha - alpha_p);
            let f_plastic = k_p * (alpha - alpha_0);
            let force = V::select(adhesive, f_adhesive, V::select(elastic, f_elastic, f_plastic)).unless(apart);
            let stiffness = V::select(adhesive, -k_e, V::select(elastic, k_e, k_p));
            let unloaded = apart | adhesive | elastic;
            let new_max = V::select(unloaded, alpha_max, alpha);
            let in_contact = !apart;
            Eval {
                force,
                stiffness,
                in_contact,
                history: History { established: in_contact, value: new_max, ..*h },
                yielded: new_max.gt(zero),
                // 004 Eq. 4.28: F_n + k_cp alpha + f_0p - f_ce
                sliding_normal_force: force + k_cp * alpha + f_0p - f_ce,
                radius: zero,
                damping_stiffness: stiffness,
                tangential_stiffness: None,
                attraction: V::mask_from_fn(|_| false),
            }
        }
    }
}
