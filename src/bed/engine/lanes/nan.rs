//! Nan's law on lanes (`law::nan`, 000 Eqs. 17-19 with the history of Eqs. 10-14): the branches of
//! `Nan::evaluate` computed on every lane and the first that holds selected, with its operations. The
//! history's branch points are loaded with it; a lane that loads plastically (alpha > alpha_max, Eq. 10)
//! gets its new points from the scalar `Nan::points_after_yield`, which only such a lane pays for.

use super::simd::{Mask, Simd};
use super::x86::{Eval, History, LaneLaw, Lanes};
use super::{Slots, LAW_PARAMS};
use crate::law::nan::{Nan, NanHistory, NanPoints};

/// A history's branch points in the order of `History::points`.
fn to_lanes(p: &NanPoints) -> [f64; 7] {
    [p.k_e, p.k_c, p.alpha_p, p.f_cp, p.alpha_c0, p.alpha_cp, p.alpha_fp]
}

impl LaneLaw for Nan {
    const LANES: Lanes = Lanes::Vector;

    fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
        Some([self.p.f_y, self.p.k_p, self.p.alpha_y, 0.0, 0.0, 0.0, 0.0, 0.0])
    }

    #[inline(always)]
    unsafe fn load_history<V: Simd>(h: &[NanHistory], at: &Slots) -> History<V> {
        // SAFETY: the caller's (the trait's contract); each slot checked, and alpha_max and the seven
        // points are eight consecutive f64 of it (`NanHistory`'s layout, asserted there).
        unsafe {
            // One row of eight per slot, transposed (`Simd::load_rows`), not eight fields gathered lane by
            // lane (64 scalar loads and their inserts per block on eight lanes): 1.05x on the bench bed
            // at eight lanes, 1.01x at four (issue 30's twenty-first round).
            // Each pointer is taken from the whole history (its provenance covers the row's 64 bytes).
            let rows: [*const f64; 8] = std::array::from_fn(|k| {
                let slot: *const NanHistory = &h[at[k.min(V::N - 1)]];
                std::ptr::addr_of!((*slot).alpha_max)
            });
            let [value, p @ ..] = V::load_rows(&rows);
            History { established: V::mask_from_fn(|k| h[at[k]].established), value, points: p }
        }
    }

    #[inline(always)]
    fn store_history<V: Simd>(h: &mut [NanHistory], at: &Slots, v: &History<V>, mask: u32) {
        let est = v.established.bits();
        let rows: [*mut f64; 8] = std::array::from_fn(|k| {
            if k < V::N && mask & (1 << k) != 0 {
                let slot: *mut NanHistory = &mut h[at[k]];
                // SAFETY: `slot` points to a live history; the field's address keeps its provenance.
                unsafe { std::ptr::addr_of_mut!((*slot).alpha_max) }
            } else {
                std::ptr::null_mut()
            }
        });
        let [a, b, c, d, e, f, g] = v.points;
        // SAFETY: the lanes of `mask` point into their slots (checked above), eight consecutive f64 each.
        unsafe { V::store_rows(&rows, &[v.value, a, b, c, d, e, f, g], mask) };
        for k in (0..V::N).filter(|k| mask & (1 << k) != 0) {
            h[at[k]].established = est & (1 << k) != 0;
        }
    }

    /// Visited unless the history is the initial one: not established and alpha_max = alpha_y. The points
    /// follow alpha_max (set with it on the plastic branch, where alpha_max only grows beyond alpha_y, and
    /// kept by the other branches), so equal alpha_max means equal points, and this is the scalar loop's
    /// `history == initial` test.
    #[inline(always)]
    unsafe fn must_visit<V: Simd>(h: &History<V>, param: impl Fn(usize) -> V) -> V::Mask {
        h.established | h.value.ne(param(2))
    }

    #[inline(always)]
    unsafe fn evaluate_lanes<'l, V: Simd>(p: &[V; LAW_PARAMS], alpha: V, h: &History<V>, law: &dyn Fn(usize) -> &'l Self, _guess: V) -> Eval<V> {
        // SAFETY: the caller runs with the width's instruction set (the trait's contract).
        unsafe {
            let [f_y, k_p, alpha_y, ..] = *p;
            let [k_e, k_c, alpha_p, f_cp, alpha_c0, alpha_cp, alpha_fp] = h.points;
            let alpha_max = h.value;
            // Nan::evaluate: separated, adhesive (Eq. 19), elastic (Eq. 17), plastic (Eq. 18), the first
            // that holds.
            let apart = alpha.lt(alpha_c0).and_not(h.established) | alpha.lt(alpha_fp);
            let adhesive = alpha.le(alpha_cp);
            let elastic = alpha.le(alpha_max);
            let f_adhesive = -f_cp + k_c * (alpha_cp - alpha);
            let f_elastic = k_e * (alpha - alpha_p);
            let f_plastic = f_y + k_p * (alpha - alpha_y);
            let force = V::select(adhesive, f_adhesive, V::select(elastic, f_elastic, f_plastic)).unless(apart);
            let stiffness = V::select(adhesive, -k_c, V::select(elastic, k_e, k_p)).unless(apart);
            let plastic = !(apart | adhesive | elastic);
            let new_max = V::select(plastic, alpha, alpha_max);
            let plastic_bits = plastic.bits();
            let points = if plastic_bits == 0 {
                h.points
            } else {
                let a = alpha.to_array();
                let mut lanes = [a; 7];
                for (lane, x) in lanes.iter_mut().zip(&h.points) {
                    *lane = x.to_array();
                }
                for k in (0..V::N).filter(|k| plastic_bits & (1 << k) != 0) {
                    for (lane, value) in lanes.iter_mut().zip(to_lanes(&law(k).points_after_yield(a.as_ref()[k]))) {
                        lane.as_mut()[k] = value;
                    }
                }
                let mut points = h.points;
                for (x, lane) in points.iter_mut().zip(&lanes) {
                    *x = V::load(lane.as_ref());
                }
                points
            };
            let in_contact = !apart;
            Eval {
                force,
                stiffness,
                in_contact,
                history: History { established: in_contact, value: new_max, points },
                yielded: new_max.gt(alpha_y),
                // 000 Eq. 23: mu f, no adhesion shift.
                sliding_normal_force: force,
                radius: V::splat(0.0),
                damping_stiffness: stiffness,
                tangential_stiffness: None,
                attraction: V::mask_from_fn(|_| false),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::simd::{F64x4, Mask, Simd};
    use super::super::x86::ORDER;
    use super::super::x86::{History, LaneLaw};
    use super::super::LAW_PARAMS;
    use crate::bed::interaction::{ContactTemplate, Interaction};
    use crate::law::nan::Nan;
    use crate::law::{Branch, NormalLaw};
    use serde_json::{json, Value};

    /// Four contacts of 000 Table 5's material driven through loading past yield, unloading into the
    /// adhesive branch, detachment, re-establishment and a second plastic loading, each lane on its own
    /// path: at every step the lanes give the scalar law's force, stiffness, contact state and history to
    /// the bit, and every branch is met.
    #[test]
    fn the_lanes_follow_the_scalar_law_through_every_branch() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("no AVX2 on this CPU: the lanes are not run");
            return;
        }
        let Value::Object(map) = json!({"contact_model": "nan", "particle_youngs_modulus": 1.2e9, "particle_poisson_ratio": 0.33,
            "particle_yield_pressure": 25e6, "surface_energy": 0.24})
        else {
            unreachable!()
        };
        let (r, rho) = (2.45e-6, 1350.0);
        let m = rho * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
        let base = ContactTemplate::particle(&map, r, rho).unwrap();
        let it = Interaction::<Nan>::particle_pair(&base, r, m, r, m, 0.0).unwrap();
        let law = &it.law;
        let (alpha_y, alpha_fe) = (law.p.alpha_y, law.initial_history().points.alpha_fp);
        // Lane k: up to (3 + k) alpha_y, down past detachment to 1.5 alpha_fe, up to (6 + 2k) alpha_y, and
        // back out; 400 points per leg.
        let legs = |k: usize| [0.0, (3 + k) as f64 * alpha_y, 1.5 * alpha_fe, (6 + 2 * k) as f64 * alpha_y, 2.0 * alpha_fe];
        let p: [f64; LAW_PARAMS] = law.lane_params().unwrap();
        let mut lanes = [law.initial_history(); 4];
        let mut scalar = lanes;
        let mut met = [false; 5]; // separated after contact, adhesive, elastic, plastic, re-established
        for leg in 0..4 {
            for i in 1..=400 {
                let alpha: [f64; 4] = std::array::from_fn(|k| {
                    let (a, b) = (legs(k)[leg], legs(k)[leg + 1]);
                    a + (b - a) * i as f64 / 400.0
                });
                // SAFETY: AVX2 is there (checked above).
                let ev = unsafe {
                    let pv: [F64x4; LAW_PARAMS] = std::array::from_fn(|q| F64x4::splat(p[q]));
                    let h: History<F64x4> = Nan::load_history(&lanes, &ORDER);
                    Nan::evaluate_lanes(&pv, F64x4::load(&alpha), &h, &|_| law, F64x4::splat(0.0))
                };
                Nan::store_history(&mut lanes, &ORDER, &ev.history, 0b1111);
                let (force, stiffness, in_contact) = (ev.force.to_array(), ev.stiffness.to_array(), ev.in_contact.bits());
                for k in 0..4 {
                    let s = law.evaluate(alpha[k], &scalar[k]);
                    let was = scalar[k].established;
                    met[0] |= was && s.branch == Branch::Separated;
                    met[1] |= s.branch == Branch::Adhesive;
                    met[2] |= s.branch == Branch::Elastic;
                    met[3] |= s.branch == Branch::Plastic;
                    met[4] |= !was && s.history.established && scalar[k].alpha_max > alpha_y;
                    scalar[k] = s.history;
                    let at = format!("lane {k}, leg {leg}, point {i}, alpha {:e} m, {:?}", alpha[k], s.branch);
                    assert_eq!(force[k].to_bits(), s.force.to_bits(), "force, {at}");
                    assert_eq!(stiffness[k].to_bits(), s.stiffness.to_bits(), "stiffness, {at}");
                    assert_eq!(in_contact & (1 << k) != 0, s.branch.in_contact(), "contact, {at}");
                    assert_eq!(format!("{:?}", lanes[k]), format!("{:?}", scalar[k]), "history, {at}");
                }
            }
        }
        assert_eq!(met, [true; 5], "branches met: detached, adhesive, elastic, plastic, re-established");
    }
}
