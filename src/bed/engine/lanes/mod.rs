//! The pair loop on AVX2 lanes: four list slots at a time, the whole contact (geometry, the normal law,
//! damping, the tangential spring with its Coulomb limit, the rolling load) computed on four contacts at
//! once, with every branch computed and the right one selected, then each contact's share added to its
//! two bodies in slot order. Every lane does the same IEEE operations in the same order as the scalar
//! contact (`kernel::contact`), so a run gives the same bits as the scalar loop; `tests/bed_isa.rs` steps
//! every law both ways and compares the digests.
//!
//! Why: the scalar kernel's one contact is a chain of dependent square roots and divisions the core
//! cannot overlap with the next contact's (docs/benchmarks.md, issue 30). On lanes four chains run in one.
//!
//! A law joins by implementing `LaneLaw` (its evaluation on lanes: `lanes/pasha_simplified.rs`,
//! `lanes/linear.rs`, `lanes/hertz.rs`, `lanes/jkr.rs` for the full and the modified JKR laws). The other
//! laws, a bed whose pairs the lanes do not cover (a tangential model other than the law's own, a
//! load-dependent Pasha stiffness, no fixed ratio of the tangential to the normal damping stiffness), and
//! a force loop with held spheres or recorded dipoles stay on the scalar loop.

#[cfg(target_arch = "x86_64")]
mod hertz;
#[cfg(target_arch = "x86_64")]
mod jkr;
#[cfg(target_arch = "x86_64")]
mod kick;
#[cfg(target_arch = "x86_64")]
mod linear;
#[cfg(target_arch = "x86_64")]
mod pasha_simplified;

#[cfg(target_arch = "x86_64")]
pub use kick::kick4;
#[cfg(target_arch = "x86_64")]
pub use x86::*;

/// Parameters of one species pair as the lanes read them: `COMMON` of the contact, then the law's own.
pub const COMMON: usize = 7;
pub const LAW_PARAMS: usize = 8;
pub type LaneRow = [f64; COMMON + LAW_PARAMS];

#[cfg(not(target_arch = "x86_64"))]
pub trait LaneLaw {}
#[cfg(not(target_arch = "x86_64"))]
impl<T> LaneLaw for T {}

#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::{LaneRow, COMMON, LAW_PARAMS};
    use crate::bed::engine::partition::{Load, Sink};
    use crate::bed::interaction::{BedLaw, Interaction};
    use crate::bed::Vec3;
    use crate::law::tangential::TangentialStiffness;
    use crate::law::NormalLaw;
    use std::arch::x86_64::*;

    /// A law's history on four lanes: up to two f64 lanes (their meaning is the law's).
    #[derive(Clone, Copy)]
    pub struct History4 {
        pub a: __m256d,
        pub b: __m256d,
    }

    /// The law's answer on four lanes (`NormalLaw::evaluate` with `has_yielded` and
    /// `sliding_normal_force`); masks are all ones or all zeros per lane.
    pub struct Eval4 {
        pub force: __m256d,
        /// The branch stiffness k_n [N/m] (the damping's and the tangential spring's).
        pub stiffness: __m256d,
        pub in_contact: __m256d,
        pub history: History4,
        pub yielded: __m256d,
        pub sliding_normal_force: __m256d,
        /// The contact radius the slot remembers (the Hertz-based laws'; 0 for the others) [m].
        pub radius: __m256d,
        /// k_n of the viscous damping (`NormalLaw::damping_stiffness`) [N/m].
        pub damping_stiffness: __m256d,
        /// k_t where the law gives it (per lane), else the pair loop forms it from the table [N/m].
        pub tangential_stiffness: Option<__m256d>,
        /// Lanes out of contact that still carry a normal force (Tomas' attraction).
        pub attraction: __m256d,
    }

    /// How a law runs on lanes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum Lanes {
        /// Its whole evaluation on lanes (`LaneLaw::evaluate4`).
        Vector,
        /// The law's own scalar evaluation once per lane, the rest of the contact on lanes.
        PerLane,
    }

    /// A normal law the pair loop can run on lanes. By default the law itself is evaluated once per lane
    /// (`Lanes::PerLane`); a law with its evaluation on lanes says `Lanes::Vector` and gives the rest.
    pub trait LaneLaw: NormalLaw + Sized {
        const LANES: Lanes = Lanes::PerLane;
        /// Mindlin's tangential stiffness 8 G* a on the law's contact radius (004 Eq. 3.25), else the
        /// fixed ratio 4 G*/E* |k_n| (000 Eq. 22).
        const MINDLIN: bool = false;

        /// The law's parameters for the lanes, or None where this pair's law has a form the lanes do not
        /// cover.
        fn lane_params(&self) -> Option<[f64; LAW_PARAMS]> {
            None
        }

        // The three history functions below default to a law without history (`()`: nothing to load or
        // store, never a reason to visit a pair at rest apart), as the linear spring and Hertz are; a
        // `Lanes::Vector` law with a history overrides all three. `Lanes::PerLane` laws never call them.

        /// The histories of four consecutive slots.
        fn load_history(_h: &[Self::History]) -> History4 {
            // SAFETY: `_mm256_setzero_pd` needs only AVX, which every caller (the AVX2 lane loop) has.
            unsafe { History4 { a: _mm256_setzero_pd(), b: _mm256_setzero_pd() } }
        }

        /// Writes the lanes whose bit `mask` sets (bit k: slot k) back to four consecutive slots.
        fn store_history(_h: &mut [Self::History], _v: &History4, _mask: i32) {}

        /// Lanes whose history forbids skipping the pair while it is beyond reach with no spring: neither
        /// the initial history nor one the law `rests_apart` with.
        ///
        /// # Safety
        /// AVX2 must be available.
        #[inline(always)]
        unsafe fn must_visit(_h: &History4) -> __m256d {
            // SAFETY: the caller runs with AVX2 (the trait's contract).
            unsafe { _mm256_setzero_pd() }
        }

        /// The law on four lanes: `p` its `lane_params`, `laws` the four pairs' laws (for what is left to the
        /// scalar law, such as a closed form without a guess), `guess` the slots' remembered contact radii.
        ///
        /// # Safety
        /// AVX2 must be available.
        unsafe fn evaluate4(_p: &[__m256d; LAW_PARAMS], _alpha: __m256d, _h: &History4, _laws: [&Self; 4], _guess: __m256d) -> Eval4 {
            unreachable!("no lanes for this law")
        }
    }

    /// The lane table of a bed's species pairs, or None when some pair is outside what the lanes cover.
    pub fn table<L: BedLaw>(pairs: &[Interaction<L>], out: &mut Vec<LaneRow>) -> bool {
        out.clear();
        let vector = L::LANES == Lanes::Vector;
        for it in pairs {
            // k_t = this factor times |k_n| (ratio) or the contact radius (Mindlin: 8 G*, as the scalar
            // `TangentialStiffness::at` multiplies it); a law evaluated per lane gives k_t itself.
            let k_t_factor = match (it.tangential, L::MINDLIN) {
                _ if !vector => 0.0,
                (TangentialStiffness::Ratio { ratio }, false) => ratio,
                (TangentialStiffness::Mindlin { shear_modulus, .. }, true) => 8.0 * shear_modulus,
                _ => return false,
            };
            let law = if vector { it.law.lane_params() } else { Some([0.0; LAW_PARAMS]) };
            let (Some(q), Some(law)) = (it.tangential_root_ratio, law) else {
                return false;
            };
            let mut row = [0.0; COMMON + LAW_PARAMS];
            row[..COMMON].copy_from_slice(&[it.reach, it.damping_elastic, it.damping_plastic, k_t_factor, q, it.friction, it.rolling_friction]);
            row[COMMON..].copy_from_slice(&law);
            out.push(row);
        }
        true
    }

    #[inline(always)]
    pub unsafe fn splat(x: f64) -> __m256d {
        unsafe { _mm256_set1_pd(x) }
    }

    /// `a` where `mask`, else `b`.
    #[inline(always)]
    pub unsafe fn select(mask: __m256d, a: __m256d, b: __m256d) -> __m256d {
        unsafe { _mm256_blendv_pd(b, a, mask) }
    }

    /// Four 3-vectors as x, y and z lanes (masked loads: nothing read past the vector).
    #[inline(always)]
    unsafe fn gather3(v: &[Vec3], idx: [usize; 4]) -> [__m256d; 3] {
        unsafe {
            let three = _mm256_set_epi64x(0, -1, -1, -1);
            // The mask reads the vector's three f64 and nothing beyond.
            let row = |k: usize| _mm256_maskload_pd(v[idx[k]].as_ptr(), three);
            let (r0, r1, r2, r3) = (row(0), row(1), row(2), row(3));
            let t0 = _mm256_unpacklo_pd(r0, r1); // x0 x1 z0 z1
            let t1 = _mm256_unpackhi_pd(r0, r1); // y0 y1 0 0
            let t2 = _mm256_unpacklo_pd(r2, r3);
            let t3 = _mm256_unpackhi_pd(r2, r3);
            [_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_permute2f128_pd(t1, t3, 0x20), _mm256_permute2f128_pd(t0, t2, 0x31)]
        }
    }

    /// Lanes a, b, c, d to four rows [a_k, b_k, c_k, d_k].
    #[inline(always)]
    pub(super) unsafe fn transpose(a: __m256d, b: __m256d, c: __m256d, d: __m256d) -> [__m256d; 4] {
        unsafe {
            let t0 = _mm256_unpacklo_pd(a, b);
            let t1 = _mm256_unpackhi_pd(a, b);
            let t2 = _mm256_unpacklo_pd(c, d);
            let t3 = _mm256_unpackhi_pd(c, d);
            [
                _mm256_permute2f128_pd(t0, t2, 0x20),
                _mm256_permute2f128_pd(t1, t3, 0x20),
                _mm256_permute2f128_pd(t0, t2, 0x31),
                _mm256_permute2f128_pd(t1, t3, 0x31),
            ]
        }
    }

    #[inline(always)]
    unsafe fn dot3(a: [__m256d; 3], b: [__m256d; 3]) -> __m256d {
        unsafe { _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a[0], b[0]), _mm256_mul_pd(a[1], b[1])), _mm256_mul_pd(a[2], b[2])) }
    }

    /// Adds `row` to a `Load`'s first four f64 (force and rolling load) or its last four (torque and pad).
    #[inline(always)]
    unsafe fn add4(load: &mut Load, upper: bool, row: __m256d) {
        let p = (load as *mut Load as *mut f64).wrapping_add(if upper { 4 } else { 0 });
        // A Load is eight f64 (asserted in `partition`), so both halves are inside it.
        unsafe { _mm256_storeu_pd(p, _mm256_add_pd(_mm256_loadu_pd(p), row)) }
    }

    /// What the lane loop reads of the engine.
    pub struct LaneInput<'a, L: BedLaw> {
        pub position: &'a [Vec3],
        pub velocity: &'a [Vec3],
        pub spin: &'a [Vec3],
        pub radius: &'a [f64],
        pub species: &'a [u16],
        pub species_count: usize,
        pub owner: &'a [u32],
        pub partner: &'a [u32],
        pub table: &'a [LaneRow],
        /// The species pairs' interactions (`Engine::pairs`), for the laws evaluated per lane.
        pub pairs: &'a [Interaction<L>],
        pub dt: f64,
        /// The forgetting distance [m] (`Engine::forget`).
        pub forget: f64,
    }

    /// The law of a `Lanes::PerLane` law evaluated once per visited lane (bit k of `visit` set), as
    /// `kernel::contact` does: its history written where it changed, and everything the rest of the
    /// contact needs packed into lanes.
    #[inline(always)]
    unsafe fn per_lane<L: BedLaw>(its: [&Interaction<L>; 4], alpha: __m256d, history: &mut [L::History], guess: &[f64], visit: i32) -> Eval4 {
        unsafe {
            let yes = f64::from_bits(u64::MAX);
            let mut a = [0.0f64; 4];
            _mm256_storeu_pd(a.as_mut_ptr(), alpha);
            let mut v = [[0.0f64; 4]; 9];
            for k in 0..4 {
                if visit & (1 << k) == 0 {
                    continue;
                }
                let (it, h) = (its[k], &mut history[k]);
                let (ev, k_damp, radius) = it.law.evaluate_near(a[k], h, guess[k]);
                if ev.history != *h {
                    *h = ev.history;
                }
                v[6][k] = radius.unwrap_or(0.0);
                if !ev.branch.in_contact() {
                    if ev.force != 0.0 {
                        v[8][k] = yes;
                        v[0][k] = ev.force;
                    }
                    continue;
                }
                let sliding = it.law.sliding_normal_force(ev.force, a[k], &ev.history);
                v[0][k] = ev.force;
                v[1][k] = ev.stiffness;
                v[2][k] = yes;
                v[3][k] = if it.law.has_yielded(&ev.history) { yes } else { 0.0 };
                v[4][k] = sliding;
                v[5][k] = k_damp;
                v[7][k] = it.tangential.at(a[k], ev.stiffness, sliding, it.law.mindlin_radius(a[k], &ev.history, radius));
            }
            let lane = |q: usize| _mm256_loadu_pd(v[q].as_ptr());
            let zero = _mm256_setzero_pd();
            Eval4 {
                force: lane(0),
                stiffness: lane(1),
                in_contact: lane(2),
                history: History4 { a: zero, b: zero },
                yielded: lane(3),
                sliding_normal_force: lane(4),
                damping_stiffness: lane(5),
                radius: lane(6),
                tangential_stiffness: Some(lane(7)),
                attraction: lane(8),
            }
        }
    }

    /// Slots [first, first + 4 blocks) of a part, four at a time; returns the first slot not done (the
    /// part's last 0-3 slots go to the scalar loop). `slot0` is the part's first slot (its memory slices
    /// start there).
    ///
    /// # Safety
    /// AVX2 must be available.
    #[target_feature(enable = "avx2")]
    #[allow(clippy::too_many_arguments)] // one call per part: its slots, its memory and its sink
    pub unsafe fn pairs<L: BedLaw>(
        e: &LaneInput<L>,
        first: usize,
        last: usize,
        slot0: usize,
        normal: &mut [L::History],
        spring: &mut [Vec3],
        radius_memory: &mut [f64],
        sink: &mut Sink,
    ) -> usize {
        // SAFETY: the caller runs this with AVX2 (the lane helpers and the law's lane functions need it);
        // every slice access is checked, and the raw loads and stores stay inside their vectors and records.
        unsafe {
            let n = e.position.len();
            let zero = _mm256_setzero_pd();
            let neg_zero = splat(-0.0);
            let (one, half) = (splat(1.0), splat(0.5));
            let dt = splat(e.dt);
            let forget = splat(e.forget);
            // The partner's share: force and its sign flipped (a - b is a + (-b) to the bit), rolling load added.
            let flip = _mm256_set_pd(0.0, -0.0, -0.0, -0.0);
            let base = sink.base;
            let mut slot = first;
            while slot + 4 <= last {
                let ii: [usize; 4] = std::array::from_fn(|k| e.owner[slot + k] as usize);
                let jj: [usize; 4] = std::array::from_fn(|k| e.partner[slot + k] as usize);
                assert!(ii.iter().chain(&jj).all(|&p| p < n));
                let m = slot - slot0;
                let pair: [usize; 4] = std::array::from_fn(|k| e.species[ii[k]] as usize * e.species_count + e.species[jj[k]] as usize);
                let rows: [&LaneRow; 4] = std::array::from_fn(|k| &e.table[pair[k]]);
                let param = |q: usize| _mm256_set_pd(rows[3][q], rows[2][q], rows[1][q], rows[0][q]);
                let xi = gather3(e.position, ii);
                let xj = gather3(e.position, jj);
                let d = [_mm256_sub_pd(xj[0], xi[0]), _mm256_sub_pd(xj[1], xi[1]), _mm256_sub_pd(xj[2], xi[2])];
                let dist2 = dot3(d, d);
                let ri = _mm256_set_pd(e.radius[ii[3]], e.radius[ii[2]], e.radius[ii[1]], e.radius[ii[0]]);
                let rj = _mm256_set_pd(e.radius[jj[3]], e.radius[jj[2]], e.radius[jj[1]], e.radius[jj[0]]);
                let sum_r = _mm256_add_pd(ri, rj);
                let range = _mm256_add_pd(sum_r, param(0));
                // Beyond the forgetting distance a contact forgets (as the scalar loop's `pair`), before its
                // memory is read; such lanes are then skipped below (apart, nothing remembered).
                let far = _mm256_add_pd(sum_r, forget);
                let beyond = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_GE_OQ>(dist2, _mm256_mul_pd(far, far)));
                if beyond != 0 {
                    for k in (0..4).filter(|k| beyond & (1 << k) != 0) {
                        let initial = e.pairs[pair[k]].initial;
                        super::super::force_loop::forget(&mut normal[m + k], &mut spring[m + k], &mut radius_memory[m + k], initial);
                    }
                }
                let mem = &mut spring[m..m + 4];
                let s0 = [
                    _mm256_set_pd(mem[3].x, mem[2].x, mem[1].x, mem[0].x),
                    _mm256_set_pd(mem[3].y, mem[2].y, mem[1].y, mem[0].y),
                    _mm256_set_pd(mem[3].z, mem[2].z, mem[1].z, mem[0].z),
                ];
                let vector = L::LANES == Lanes::Vector;
                let interactions = || -> [&Interaction<L>; 4] { std::array::from_fn(|k| &e.pairs[pair[k]]) };
                let (h, must_visit) = if vector {
                    let h = L::load_history(&normal[m..m + 4]);
                    (h, L::must_visit(&h))
                } else {
                    let its = interactions();
                    let yes = f64::from_bits(u64::MAX);
                    let must: [f64; 4] = std::array::from_fn(|k| {
                        let h = &normal[m + k];
                        if *h == its[k].initial || its[k].law.rests_apart(h) {
                            0.0
                        } else {
                            yes
                        }
                    });
                    (History4 { a: zero, b: zero }, _mm256_loadu_pd(must.as_ptr()))
                };
                // The scalar loop skips a pair that is apart (dist2 >= range^2), has no spring and whose
                // history allows it; the lanes visit the rest.
                let within = _mm256_cmp_pd::<_CMP_NGE_UQ>(dist2, _mm256_mul_pd(range, range));
                let has_spring = _mm256_or_pd(
                    _mm256_or_pd(_mm256_cmp_pd::<_CMP_NEQ_UQ>(s0[0], zero), _mm256_cmp_pd::<_CMP_NEQ_UQ>(s0[1], zero)),
                    _mm256_cmp_pd::<_CMP_NEQ_UQ>(s0[2], zero),
                );
                let visit = _mm256_or_pd(_mm256_or_pd(within, has_spring), must_visit);
                let visit_bits = _mm256_movemask_pd(visit);
                if visit_bits == 0 {
                    slot += 4;
                    continue;
                }
                let dist = _mm256_sqrt_pd(dist2);
                let inv = _mm256_div_pd(one, dist);
                let nrm = [_mm256_mul_pd(d[0], inv), _mm256_mul_pd(d[1], inv), _mm256_mul_pd(d[2], inv)];
                let alpha = _mm256_sub_pd(sum_r, dist);
                let half_alpha = _mm256_mul_pd(half, alpha);
                let (li, lj) = (_mm256_sub_pd(ri, half_alpha), _mm256_sub_pd(rj, half_alpha));
                // The surface velocity of i relative to j (kernel::surface_velocity).
                let vi = gather3(e.velocity, ii);
                let vj = gather3(e.velocity, jj);
                let wi = gather3(e.spin, ii);
                let wj = gather3(e.spin, jj);
                let w: [__m256d; 3] = std::array::from_fn(|c| _mm256_add_pd(_mm256_mul_pd(wi[c], li), _mm256_mul_pd(wj[c], lj)));
                let v = [
                    _mm256_add_pd(_mm256_sub_pd(vi[0], vj[0]), _mm256_sub_pd(_mm256_mul_pd(w[1], nrm[2]), _mm256_mul_pd(w[2], nrm[1]))),
                    _mm256_add_pd(_mm256_sub_pd(vi[1], vj[1]), _mm256_sub_pd(_mm256_mul_pd(w[2], nrm[0]), _mm256_mul_pd(w[0], nrm[2]))),
                    _mm256_add_pd(_mm256_sub_pd(vi[2], vj[2]), _mm256_sub_pd(_mm256_mul_pd(w[0], nrm[1]), _mm256_mul_pd(w[1], nrm[0]))),
                ];
                // The law (kernel::contact from here on).
                let ev = if vector {
                    let law_params: [__m256d; LAW_PARAMS] = std::array::from_fn(|q| param(COMMON + q));
                    let laws: [&L; 4] = std::array::from_fn(|k| &e.pairs[pair[k]].law);
                    let guess = _mm256_loadu_pd(radius_memory[m..m + 4].as_ptr());
                    let ev = L::evaluate4(&law_params, alpha, &h, laws, guess);
                    L::store_history(&mut normal[m..m + 4], &ev.history, visit_bits);
                    ev
                } else {
                    per_lane(interactions(), alpha, &mut normal[m..m + 4], &radius_memory[m..m + 4], visit_bits)
                };
                let touch = _mm256_and_pd(visit, ev.in_contact);
                let approach = dot3(v, nrm);
                let abs_k = _mm256_andnot_pd(neg_zero, ev.stiffness);
                let root_k = _mm256_sqrt_pd(_mm256_andnot_pd(neg_zero, ev.damping_stiffness));
                let damping = select(ev.yielded, param(2), param(1));
                let f_n = _mm256_add_pd(ev.force, _mm256_mul_pd(_mm256_mul_pd(damping, root_k), approach));
                let minus_f_n = _mm256_xor_pd(f_n, neg_zero);
                // The tangential spring, kept in the tangent plane of the turned contact with its magnitude.
                let v_t: [__m256d; 3] = std::array::from_fn(|c| _mm256_sub_pd(v[c], _mm256_mul_pd(nrm[c], approach)));
                let along = dot3(s0, nrm);
                let mut s_t: [__m256d; 3] = std::array::from_fn(|c| _mm256_sub_pd(s0[c], _mm256_mul_pd(nrm[c], along)));
                let t2 = dot3(s_t, s_t);
                let turned = _mm256_and_pd(_mm256_cmp_pd::<_CMP_NEQ_UQ>(along, zero), _mm256_cmp_pd::<_CMP_GT_OQ>(t2, zero));
                if _mm256_movemask_pd(turned) != 0 {
                    let x = _mm256_div_pd(_mm256_mul_pd(along, along), t2);
                    let small = _mm256_cmp_pd::<_CMP_LT_OQ>(x, splat(1e-4));
                    let series = _mm256_add_pd(one, _mm256_mul_pd(x, _mm256_sub_pd(half, _mm256_mul_pd(splat(0.125), x))));
                    let factor = if _mm256_movemask_pd(_mm256_andnot_pd(small, turned)) != 0 {
                        select(small, series, _mm256_sqrt_pd(_mm256_add_pd(one, x)))
                    } else {
                        series
                    };
                    s_t = std::array::from_fn(|c| select(turned, _mm256_mul_pd(s_t[c], factor), s_t[c]));
                }
                // TangentialSpring::step with k_t (000 Eq. 22, or Mindlin's 004 Eq. 3.25) and the limit mu max(N, 0).
                let k_t = match ev.tangential_stiffness {
                    Some(k_t) => k_t,
                    None => _mm256_mul_pd(param(3), if L::MINDLIN { ev.radius } else { abs_k }),
                };
                let mu = param(5);
                let mut f_s: [__m256d; 3] = std::array::from_fn(|c| _mm256_sub_pd(s_t[c], _mm256_mul_pd(_mm256_mul_pd(v_t[c], dt), k_t)));
                let limit = _mm256_mul_pd(mu, _mm256_max_pd(ev.sliding_normal_force, zero));
                let norm2 = dot3(f_s, f_s);
                let sliding = _mm256_cmp_pd::<_CMP_NLE_UQ>(norm2, _mm256_mul_pd(limit, limit));
                if _mm256_movemask_pd(sliding) != 0 {
                    let norm = _mm256_sqrt_pd(norm2);
                    let scale = _mm256_and_pd(_mm256_div_pd(limit, norm), _mm256_cmp_pd::<_CMP_GT_OQ>(norm, zero));
                    f_s = std::array::from_fn(|c| select(sliding, _mm256_mul_pd(f_s[c], scale), f_s[c]));
                }
                let root_kt = _mm256_mul_pd(param(4), root_k);
                let c_t = _mm256_mul_pd(param(1), root_kt);
                let tangential: [__m256d; 3] = std::array::from_fn(|c| select(sliding, f_s[c], _mm256_sub_pd(f_s[c], _mm256_mul_pd(v_t[c], c_t))));
                // No friction: no tangential force, and the spring as it was. None out of contact either.
                let rubs = _mm256_cmp_pd::<_CMP_GT_OQ>(mu, zero);
                let tangential: [__m256d; 3] = std::array::from_fn(|c| _mm256_and_pd(tangential[c], _mm256_and_pd(rubs, touch)));
                // The memory: a visited lane in contact keeps the new spring (where it rubs), one out of
                // contact forgets it; a lane not visited keeps its own.
                let new_s: [__m256d; 3] = std::array::from_fn(|c| select(visit, _mm256_and_pd(select(rubs, f_s[c], s0[c]), ev.in_contact), s0[c]));
                let mut out = [[0.0f64; 4]; 4];
                for c in 0..3 {
                    _mm256_storeu_pd(out[c].as_mut_ptr(), new_s[c]);
                }
                _mm256_storeu_pd(out[3].as_mut_ptr(), ev.radius);
                for k in 0..4 {
                    if visit_bits & (1 << k) != 0 {
                        mem[k] = Vec3::new(out[0][k], out[1][k], out[2][k]);
                        radius_memory[m + k] = out[3][k];
                    }
                }
                // Each contact's share of its two bodies; lanes not touching add +0.0, which changes no sum (a
                // sum that starts at +0.0 is never -0.0).
                // A lane out of contact that attracts (Tomas) gives the normal force alone, and no rolling load.
                let attracts = _mm256_and_pd(visit, ev.attraction);
                let minus_f = _mm256_xor_pd(ev.force, neg_zero);
                let acts = _mm256_or_pd(touch, attracts);
                let force: [__m256d; 3] = std::array::from_fn(|c| {
                    let f = select(attracts, _mm256_mul_pd(nrm[c], minus_f), _mm256_add_pd(_mm256_mul_pd(nrm[c], minus_f_n), tangential[c]));
                    _mm256_and_pd(f, acts)
                });
                let turn = [
                    _mm256_sub_pd(_mm256_mul_pd(nrm[1], tangential[2]), _mm256_mul_pd(nrm[2], tangential[1])),
                    _mm256_sub_pd(_mm256_mul_pd(nrm[2], tangential[0]), _mm256_mul_pd(nrm[0], tangential[2])),
                    _mm256_sub_pd(_mm256_mul_pd(nrm[0], tangential[1]), _mm256_mul_pd(nrm[1], tangential[0])),
                ];
                let (li, lj) = (_mm256_and_pd(li, acts), _mm256_and_pd(lj, acts));
                let rolling = _mm256_and_pd(_mm256_mul_pd(param(6), _mm256_andnot_pd(neg_zero, ev.force)), touch);
                let share = transpose(force[0], force[1], force[2], rolling);
                let torque_i = transpose(_mm256_mul_pd(turn[0], li), _mm256_mul_pd(turn[1], li), _mm256_mul_pd(turn[2], li), zero);
                let torque_j = transpose(_mm256_mul_pd(turn[0], lj), _mm256_mul_pd(turn[1], lj), _mm256_mul_pd(turn[2], lj), zero);
                for k in 0..4 {
                    let a = &mut sink.load[ii[k] - base];
                    add4(a, false, share[k]);
                    add4(a, true, torque_i[k]);
                    let b = &mut sink.load[jj[k] - base];
                    add4(b, false, _mm256_xor_pd(share[k], flip));
                    add4(b, true, torque_j[k]);
                }
                slot += 4;
            }
            slot
        }
    }
}
