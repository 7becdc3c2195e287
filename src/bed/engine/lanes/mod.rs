//! The pair loop on lanes: four (AVX2) or eight (AVX-512) slots of a part's near list (`engine::near`)
//! at a time, the whole contact
//! (geometry, the normal law, damping, the tangential spring with its Coulomb limit, the rolling load)
//! computed on that many contacts at once, with every branch computed and the right one selected, then
//! each contact's share added to its two bodies in slot order. Every lane does the same IEEE operations in
//! the same order as the scalar contact (`kernel::contact`), so a run gives the same bits as the scalar
//! loop at either width; `tests/bed_isa.rs` steps every law each way and compares the digests.
//!
//! Why: the scalar kernel's one contact is a chain of dependent square roots and divisions the core
//! cannot overlap with the next contact's (docs/benchmarks.md, issue 30). On lanes four or eight chains
//! run in one. The loop and the laws are written once against `simd::Simd`, and compiled per width.
//!
//! A law joins by implementing `LaneLaw` (its evaluation on lanes: `lanes/pasha_simplified.rs`,
//! `lanes/linear.rs`, `lanes/hertz.rs`, `lanes/nan.rs`, `lanes/jkr.rs` for the full and the modified JKR
//! laws). The other laws run once per lane inside the lane loop. A bed whose pairs the lanes do not cover
//! (a tangential model other than the law's own, a load-dependent Pasha stiffness, no fixed ratio of the
//! tangential to the normal damping stiffness) and a force loop with held spheres or recorded dipoles stay
//! on the scalar loop.

#[cfg(target_arch = "x86_64")]
mod hertz;
#[cfg(target_arch = "x86_64")]
mod jkr;
#[cfg(target_arch = "x86_64")]
mod kick;
#[cfg(target_arch = "x86_64")]
mod linear;
#[cfg(target_arch = "x86_64")]
mod nan;
#[cfg(target_arch = "x86_64")]
mod pasha_simplified;
pub mod record;
#[cfg(target_arch = "x86_64")]
pub mod simd;

#[cfg(target_arch = "x86_64")]
pub use kick::kick4;
#[cfg(target_arch = "x86_64")]
pub use x86::*;

/// Parameters of one species pair as the lanes read them: `COMMON` of the contact, then the law's own.
pub const COMMON: usize = 7;
pub const LAW_PARAMS: usize = 8;
pub type LaneRow = [f64; COMMON + LAW_PARAMS];
/// The list slots (or sphere indices) of a block's lanes; four lanes use the first four.
pub type Slots = [usize; 8];

#[cfg(not(target_arch = "x86_64"))]
pub trait LaneLaw {}
#[cfg(not(target_arch = "x86_64"))]
impl<T> LaneLaw for T {}

#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::simd::{F64x4, F64x8, Mask, Share, Simd, Spheres};
    use super::{LaneRow, Slots, COMMON, LAW_PARAMS};
    use crate::bed::engine::near::Near;
    use crate::bed::engine::partition::Sink;
    use crate::bed::interaction::{BedLaw, Interaction};
    use crate::bed::Vec3;
    use crate::law::tangential::TangentialStiffness;
    use crate::law::NormalLaw;

    /// A law's history on lanes: a mask, a value and the values that follow from it (their meaning is
    /// the law's; a law that uses fewer leaves the rest at zero, and the compiler drops them).
    #[derive(Clone, Copy)]
    pub struct History<V: Simd> {
        pub established: V::Mask,
        pub value: V,
        /// Nan's branch points (`NanPoints`, computed from alpha_max and kept in the history).
        pub points: [V; 7],
    }

    impl<V: Simd> History<V> {
        /// A history with nothing in it (the laws without one).
        ///
        /// # Safety
        /// The CPU runs the width's instruction set.
        #[inline(always)]
        pub unsafe fn none() -> History<V> {
            // SAFETY: the caller's.
            unsafe { History { established: V::mask_from_fn(|_| false), value: V::splat(0.0), points: [V::splat(0.0); 7] } }
        }
    }

    /// The law's answer on lanes (`NormalLaw::evaluate` with `has_yielded` and `sliding_normal_force`).
    pub struct Eval<V: Simd> {
        pub force: V,
        /// The branch stiffness k_n [N/m] (the damping's and the tangential spring's).
        pub stiffness: V,
        pub in_contact: V::Mask,
        pub history: History<V>,
        pub yielded: V::Mask,
        pub sliding_normal_force: V,
        /// The contact radius the slot remembers (the Hertz-based laws'; 0 for the others) [m].
        pub radius: V,
        /// k_n of the viscous damping (`NormalLaw::damping_stiffness`) [N/m].
        pub damping_stiffness: V,
        /// k_t where the law gives it (per lane), else the pair loop forms it from the table [N/m].
        pub tangential_stiffness: Option<V>,
        /// Lanes out of contact that still carry a normal force (Tomas' attraction).
        pub attraction: V::Mask,
    }

    /// How a law runs on lanes.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum Lanes {
        /// Its whole evaluation on lanes (`LaneLaw::evaluate_lanes`).
        Vector,
        /// The law's own scalar evaluation once per lane, the rest of the contact on lanes.
        PerLane,
    }

    /// A normal law the pair loop can run on lanes. By default the law itself is evaluated once per lane
    /// (`Lanes::PerLane`); a law with its evaluation on lanes says `Lanes::Vector` and gives the rest.
    /// The lane functions are generic over the width (`Simd`) and are called only inside the pair loop,
    /// which runs where the CPU has the width's instruction set.
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

        /// The histories of slots `at[0]`, ..., `at[V::N - 1]` of `h`.
        ///
        /// # Safety
        /// The CPU runs the width's instruction set.
        #[inline(always)]
        unsafe fn load_history<V: Simd>(_h: &[Self::History], _at: &Slots) -> History<V> {
            // SAFETY: the caller's.
            unsafe { History::none() }
        }

        /// Writes the lanes whose bit `mask` sets (bit k: lane k) back to their slots `at[k]`.
        #[inline(always)]
        fn store_history<V: Simd>(_h: &mut [Self::History], _at: &Slots, _v: &History<V>, _mask: u32) {}

        /// Lanes whose history forbids skipping the pair while it is beyond reach with no spring: neither
        /// the initial history nor one the law `rests_apart` with. `param(q)` reads the law's lane
        /// parameter q (a table gather, so only a law that needs it calls it).
        ///
        /// # Safety
        /// The CPU runs the width's instruction set.
        #[inline(always)]
        unsafe fn must_visit<V: Simd>(_h: &History<V>, _param: impl Fn(usize) -> V) -> V::Mask {
            // SAFETY: the caller's.
            unsafe { V::mask_from_fn(|_| false) }
        }

        /// The law on lanes: `p` its `lane_params`, `law(k)` lane k's pair's law (for what is left to the scalar
        /// law, such as a closed form without a guess), `guess` the slots' remembered contact radii.
        ///
        /// # Safety
        /// The CPU runs the width's instruction set.
        unsafe fn evaluate_lanes<'l, V: Simd>(
            _p: &[V; LAW_PARAMS],
            _alpha: V,
            _h: &History<V>,
            _law: &dyn Fn(usize) -> &'l Self,
            _guess: V,
        ) -> Eval<V> {
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
    fn dot3<V: Simd>(a: [V; 3], b: [V; 3]) -> V {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    /// What the lane loop reads of the engine.
    pub struct LaneInput<'a, L: BedLaw> {
        /// The spheres (`Simd::gather_sphere` reads the arrays on four lanes, the records on eight).
        pub spheres: Spheres<'a>,
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
    /// `kernel::contact` does: lane k's history (`history[at[k]]`) written where it changed, and
    /// everything the rest of the contact needs packed into lanes.
    #[inline(always)]
    unsafe fn per_lane<L: BedLaw, V: Simd>(
        its: &[&Interaction<L>],
        alpha: V,
        history: &mut [L::History],
        at: &Slots,
        guess: &[f64],
        visit: u32,
    ) -> Eval<V> {
        let a = alpha.to_array();
        let a = a.as_ref();
        let (mut v, mut flags) = ([V::Array::default(); 6], [[false; 8]; 3]);
        for k in 0..V::N {
            if visit & (1 << k) == 0 {
                continue;
            }
            let (it, h) = (its[k], &mut history[at[k]]);
            let (ev, k_damp, radius) = it.law.evaluate_near(a[k], h, guess[k]);
            if ev.history != *h {
                *h = ev.history;
            }
            v[4].as_mut()[k] = radius.unwrap_or(0.0);
            if !ev.branch.in_contact() {
                if ev.force != 0.0 {
                    flags[2][k] = true;
                    v[0].as_mut()[k] = ev.force;
                }
                continue;
            }
            let sliding = it.law.sliding_normal_force(ev.force, a[k], &ev.history);
            v[0].as_mut()[k] = ev.force;
            v[1].as_mut()[k] = ev.stiffness;
            flags[0][k] = true;
            flags[1][k] = it.law.has_yielded(&ev.history);
            v[2].as_mut()[k] = sliding;
            v[3].as_mut()[k] = k_damp;
            v[5].as_mut()[k] = it.tangential.at(a[k], ev.stiffness, sliding, it.law.mindlin_radius(a[k], &ev.history, radius));
        }
        // SAFETY: the caller runs with the width's instruction set.
        unsafe {
            let lane = |q: usize| V::load(v[q].as_ref());
            let mask = |q: usize| V::mask_from_fn(|k| flags[q][k]);
            Eval {
                force: lane(0),
                stiffness: lane(1),
                in_contact: mask(0),
                history: History::none(),
                yielded: mask(1),
                sliding_normal_force: lane(2),
                damping_stiffness: lane(3),
                radius: lane(4),
                tangential_stiffness: Some(lane(5)),
                attraction: mask(2),
            }
        }
    }

    /// Slots [first, last) of a part, four at a time on AVX2; returns the first slot not done (the
    /// part's last 0-3 slots go to the scalar loop). `slot0` is the part's first slot (its memory slices
    /// start there).
    ///
    /// # Safety
    /// AVX2 must be available.
    #[target_feature(enable = "avx2")]
    #[allow(clippy::too_many_arguments)] // one call per part: its slots, its memory and its sink
    pub unsafe fn pairs_avx2<L: BedLaw>(
        e: &LaneInput<L>,
        first: usize,
        last: usize,
        slot0: usize,
        normal: &mut [L::History],
        spring: &mut [Vec3],
        radius_memory: &mut [f64],
        sink: &mut Sink,
    ) -> usize {
        // SAFETY: AVX2 (this function's contract).
        unsafe { pairs_one_pass::<L, F64x4>(e, first, last, slot0, normal, spring, radius_memory, sink) }
    }

    /// `pairs_avx2` eight at a time on AVX-512; the part's last 0-7 slots go to the scalar loop.
    ///
    /// # Safety
    /// AVX-512 F and DQ must be available.
    #[target_feature(enable = "avx2,avx512f,avx512dq")]
    #[allow(clippy::too_many_arguments)] // as `pairs_avx2`
    pub unsafe fn pairs_avx512<L: BedLaw>(
        e: &LaneInput<L>,
        first: usize,
        last: usize,
        slot0: usize,
        normal: &mut [L::History],
        spring: &mut [Vec3],
        radius_memory: &mut [f64],
        sink: &mut Sink,
    ) -> usize {
        // SAFETY: AVX-512 F and DQ (this function's contract).
        unsafe { pairs_one_pass::<L, F64x8>(e, first, last, slot0, normal, spring, radius_memory, sink) }
    }

    /// The walk over every slot of a part (where its near list holds most of them, `engine::near`): each
    /// block of `V::N` consecutive slots read and its contacts computed at once. Its kernel is
    /// `contacts`' (the same operations in the same order, `tests/bed_isa.rs` holds both to the scalar
    /// loop's bits), kept written out here because Hertz ran 4 % slower at eight lanes when this loop
    /// called `contacts` (issue 30's eighteenth round). Its first part (forgetting, the lanes to visit)
    /// is `near_pairs`' with the memory read in place instead of by index.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    unsafe fn pairs_one_pass<L: BedLaw, V: Simd>(
        e: &LaneInput<L>,
        first: usize,
        last: usize,
        slot0: usize,
        normal: &mut [L::History],
        spring: &mut [Vec3],
        radius_memory: &mut [f64],
        sink: &mut Sink,
    ) -> usize {
        // SAFETY: the caller runs this with the width's instruction set (the lane helpers and the law's
        // lane functions need it); the unchecked reads of sphere data and table rows use indices checked
        // against their arrays once per block (below), every other slice access is checked, and the raw
        // loads and stores stay inside their vectors and records.
        unsafe {
            let sp = &e.spheres;
            let n = sp.position.len();
            assert!(sp.velocity.len() == n && sp.spin.len() == n && sp.radius.len() == n && sp.species.len() == n);
            assert!(!V::RECORDS || sp.records.len() == n, "the records are packed for this step's spheres");
            // Each block checks its 2w indices against n once, and the table row of each lane once, and
            // reads without a bounds test per access (the index work was 29 % of the linear loop's samples, issue 30's fourteenth round; without the tests
            // the seed's test ran 1.23x faster, its fifteenth).
            assert!(last <= e.owner.len() && last <= e.partner.len());
            let w = V::N;
            let zero = V::splat(0.0);
            let (one, half) = (V::splat(1.0), V::splat(0.5));
            let dt = V::splat(e.dt);
            let forget = V::splat(e.forget);
            let mut slot = first;
            let (mut ii, mut jj, mut pair) = ([0usize; 8], [0usize; 8], [0usize; 8]);
            while slot + w <= last {
                for k in 0..w {
                    ii[k] = *e.owner.get_unchecked(slot + k) as usize;
                    jj[k] = *e.partner.get_unchecked(slot + k) as usize;
                }
                assert!(ii[..w].iter().chain(&jj[..w]).all(|&p| p < n));
                let m = slot - slot0;
                // Both spheres of each lane (on eight lanes from their records: two cache lines each, not
                // one per array).
                let si = V::gather_sphere(sp, &ii);
                let sj = V::gather_sphere(sp, &jj);
                for k in 0..w {
                    pair[k] = *sp.species.get_unchecked(ii[k]) as usize * e.species_count + *sp.species.get_unchecked(jj[k]) as usize;
                }
                assert!(pair[..w].iter().all(|&p| p < e.table.len()));
                let param = |q: usize| V::from_fn(|k| e.table.get_unchecked(pair[k])[q]);
                let xi = [si[0], si[1], si[2]];
                let xj = [sj[0], sj[1], sj[2]];
                let d = [xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]];
                let dist2 = dot3(d, d);
                let (ri, rj) = (si[3], sj[3]);
                let sum_r = ri + rj;
                let range = sum_r + param(0);
                // Beyond the forgetting distance a contact forgets (as the scalar loop's `pair`), before its
                // memory is read; such lanes are then skipped below (apart, nothing remembered).
                let far = sum_r + forget;
                let beyond = dist2.ge(far * far).bits();
                if beyond != 0 {
                    for k in (0..w).filter(|k| beyond & (1 << k) != 0) {
                        let initial = e.pairs[pair[k]].initial;
                        super::super::force_loop::forget(&mut normal[m + k], &mut spring[m + k], &mut radius_memory[m + k], initial);
                    }
                }
                let mem = &mut spring[m..m + w];
                let s0 = [V::from_fn(|k| mem[k].x), V::from_fn(|k| mem[k].y), V::from_fn(|k| mem[k].z)];
                let vector = L::LANES == Lanes::Vector;
                let interactions = |k: usize| &e.pairs[pair[k]];
                let (h, must_visit) = if vector {
                    let h = L::load_history::<V>(&normal[m..m + w], &ORDER);
                    (h, L::must_visit(&h, |q| param(COMMON + q)))
                } else {
                    let must = V::mask_from_fn(|k| {
                        let (h, it) = (&normal[m + k], interactions(k));
                        !(*h == it.initial || it.law.rests_apart(h))
                    });
                    (History::none(), must)
                };
                // The scalar loop skips a pair that is apart (dist2 >= range^2), has no spring and whose
                // history allows it; the lanes visit the rest.
                let within = dist2.nge(range * range);
                let has_spring = s0[0].ne(zero) | s0[1].ne(zero) | s0[2].ne(zero);
                let visit = within | has_spring | must_visit;
                let visit_bits = visit.bits();
                if visit_bits == 0 {
                    slot += w;
                    continue;
                }
                let dist = dist2.sqrt();
                let inv = one / dist;
                let nrm = [d[0] * inv, d[1] * inv, d[2] * inv];
                let alpha = sum_r - dist;
                let half_alpha = half * alpha;
                let (li, lj) = (ri - half_alpha, rj - half_alpha);
                // The surface velocity of i relative to j (kernel::surface_velocity).
                let (vi, vj) = ([si[4], si[5], si[6]], [sj[4], sj[5], sj[6]]);
                let (wi, wj) = ([si[7], si[8], si[9]], [sj[7], sj[8], sj[9]]);
                let om: [V; 3] = std::array::from_fn(|c| wi[c] * li + wj[c] * lj);
                let v = [
                    (vi[0] - vj[0]) + (om[1] * nrm[2] - om[2] * nrm[1]),
                    (vi[1] - vj[1]) + (om[2] * nrm[0] - om[0] * nrm[2]),
                    (vi[2] - vj[2]) + (om[0] * nrm[1] - om[1] * nrm[0]),
                ];
                // The law (kernel::contact from here on).
                let ev = if vector {
                    // A loop, not `array::from_fn`: its closure is not inlined and would call the vector
                    // loads out of line (30 % slower at eight lanes, issue 30's fourteenth round).
                    let mut law_params = [zero; LAW_PARAMS];
                    for (q, p) in law_params.iter_mut().enumerate() {
                        *p = param(COMMON + q);
                    }
                    let guess = V::load(&radius_memory[m..m + w]);
                    let ev = L::evaluate_lanes(&law_params, alpha, &h, &|k| &e.pairs[pair[k]].law, guess);
                    L::store_history(&mut normal[m..m + w], &ORDER, &ev.history, visit_bits);
                    ev
                } else {
                    let its: [&Interaction<L>; 8] = std::array::from_fn(interactions);
                    per_lane(&its[..w], alpha, &mut normal[m..m + w], &ORDER, &radius_memory[m..m + w], visit_bits)
                };
                let touch = visit & ev.in_contact;
                let approach = dot3(v, nrm);
                let abs_k = ev.stiffness.abs();
                let root_k = ev.damping_stiffness.abs().sqrt();
                let damping = V::select(ev.yielded, param(2), param(1));
                let f_n = ev.force + damping * root_k * approach;
                let minus_f_n = -f_n;
                // The tangential spring, kept in the tangent plane of the turned contact with its magnitude.
                let v_t: [V; 3] = std::array::from_fn(|c| v[c] - nrm[c] * approach);
                let along = dot3(s0, nrm);
                let mut s_t: [V; 3] = std::array::from_fn(|c| s0[c] - nrm[c] * along);
                let t2 = dot3(s_t, s_t);
                let turned = along.ne(zero) & t2.gt(zero);
                if turned.bits() != 0 {
                    let x = along * along / t2;
                    let small = x.lt(V::splat(1e-4));
                    let series = one + x * (half - V::splat(0.125) * x);
                    let factor = if turned.and_not(small).bits() != 0 { V::select(small, series, (one + x).sqrt()) } else { series };
                    s_t = std::array::from_fn(|c| V::select(turned, s_t[c] * factor, s_t[c]));
                }
                // TangentialSpring::step with k_t (000 Eq. 22, or Mindlin's 004 Eq. 3.25) and the limit mu max(N, 0).
                let k_t = match ev.tangential_stiffness {
                    Some(k_t) => k_t,
                    None => param(3) * if L::MINDLIN { ev.radius } else { abs_k },
                };
                let mu = param(5);
                let mut f_s: [V; 3] = std::array::from_fn(|c| s_t[c] - v_t[c] * dt * k_t);
                let limit = mu * ev.sliding_normal_force.max(zero);
                let norm2 = dot3(f_s, f_s);
                let sliding = norm2.nle(limit * limit);
                if sliding.bits() != 0 {
                    let norm = norm2.sqrt();
                    let scale = (limit / norm).keep(norm.gt(zero));
                    f_s = std::array::from_fn(|c| V::select(sliding, f_s[c] * scale, f_s[c]));
                }
                let root_kt = param(4) * root_k;
                let c_t = param(1) * root_kt;
                let tangential: [V; 3] = std::array::from_fn(|c| V::select(sliding, f_s[c], f_s[c] - v_t[c] * c_t));
                // No friction: no tangential force, and the spring as it was. None out of contact either.
                let rubs = mu.gt(zero);
                let tangential: [V; 3] = std::array::from_fn(|c| tangential[c].keep(rubs & touch));
                // The memory: a visited lane in contact keeps the new spring (where it rubs), one out of
                // contact forgets it; a lane not visited keeps its own.
                let new_s: [V::Array; 3] =
                    std::array::from_fn(|c| V::select(visit, V::select(rubs, f_s[c], s0[c]).keep(ev.in_contact), s0[c]).to_array());
                let new_radius = ev.radius.to_array();
                for k in 0..w {
                    if visit_bits & (1 << k) != 0 {
                        mem[k] = Vec3::new(new_s[0].as_ref()[k], new_s[1].as_ref()[k], new_s[2].as_ref()[k]);
                        radius_memory[m + k] = new_radius.as_ref()[k];
                    }
                }
                // Each contact's share of its two bodies; lanes not touching add +0.0, which changes no sum (a
                // sum that starts at +0.0 is never -0.0).
                // A lane out of contact that attracts (Tomas) gives the normal force alone, and no rolling load.
                let attracts = visit & ev.attraction;
                let minus_f = -ev.force;
                let acts = touch | attracts;
                let force: [V; 3] = std::array::from_fn(|c| V::select(attracts, nrm[c] * minus_f, nrm[c] * minus_f_n + tangential[c]).keep(acts));
                let turn = [
                    nrm[1] * tangential[2] - nrm[2] * tangential[1],
                    nrm[2] * tangential[0] - nrm[0] * tangential[2],
                    nrm[0] * tangential[1] - nrm[1] * tangential[0],
                ];
                let (li, lj) = (li.keep(acts), lj.keep(acts));
                let rolling = (param(6) * ev.force.abs()).keep(touch);
                let torque_i = [turn[0] * li, turn[1] * li, turn[2] * li];
                let torque_j = [turn[0] * lj, turn[1] * lj, turn[2] * lj];
                V::add_shares(&mut sink.rows(), &ii[..w], &jj[..w], Share { force, rolling, torque_i, torque_j });
                slot += w;
            }
            slot
        }
    }

    /// The near list of a part (`engine::near`), four entries at a time on AVX2. `normal`, `spring` and
    /// `radius_memory` are the part's memory slices (the entries' slots index them).
    ///
    /// # Safety
    /// AVX2 must be available.
    #[target_feature(enable = "avx2")]
    pub unsafe fn near_avx2<L: BedLaw>(
        e: &LaneInput<L>,
        near: &Near,
        normal: &mut [L::History],
        spring: &mut [Vec3],
        radius_memory: &mut [f64],
        sink: &mut Sink,
    ) {
        // SAFETY: AVX2 (this function's contract).
        unsafe { near_pairs::<L, F64x4>(e, near, normal, spring, radius_memory, sink) }
    }

    /// `near_avx2` eight at a time on AVX-512.
    ///
    /// # Safety
    /// AVX-512 F and DQ must be available.
    #[target_feature(enable = "avx2,avx512f,avx512dq")]
    pub unsafe fn near_avx512<L: BedLaw>(
        e: &LaneInput<L>,
        near: &Near,
        normal: &mut [L::History],
        spring: &mut [Vec3],
        radius_memory: &mut [f64],
        sink: &mut Sink,
    ) {
        // SAFETY: AVX-512 F and DQ (this function's contract).
        unsafe { near_pairs::<L, F64x8>(e, near, normal, spring, radius_memory, sink) }
    }

    /// The pair loop at width `V` over a part's near list, inlined into the function that enables the
    /// width's instructions: `V::N` entries a block; the last block's spare lanes repeat its last entry
    /// and are not visited (they write nothing and add +0.0; a law may still evaluate them, which costs
    /// time, not bits). Each entry forgets beyond the forgetting distance and is visited within reach,
    /// with a spring, or with a history that forbids skipping, as the scalar loop's `pair`. The entries
    /// keep slot order, so each body's sum is the scalar loop's, added in its order.
    #[inline(always)]
    unsafe fn near_pairs<L: BedLaw, V: Simd>(
        e: &LaneInput<L>,
        near: &Near,
        normal: &mut [L::History],
        spring: &mut [Vec3],
        radius_memory: &mut [f64],
        sink: &mut Sink,
    ) {
        // SAFETY: the caller runs this with the width's instruction set (the lane helpers and the law's
        // lane functions need it); the unchecked reads of sphere data and table rows use indices checked
        // against their arrays once per block (below), every other slice access is checked, and the raw
        // loads and stores stay inside their vectors and records.
        unsafe {
            let sp = &e.spheres;
            let n = sp.position.len();
            assert!(sp.velocity.len() == n && sp.spin.len() == n && sp.radius.len() == n && sp.species.len() == n);
            assert!(!V::RECORDS || sp.records.len() == n, "the records are packed for this step's spheres");
            let count = near.len();
            assert!(near.i.len() == count && near.j.len() == count && near.pair.len() == count);
            let w = V::N;
            let zero = V::splat(0.0);
            let forget = V::splat(e.forget);
            let mut c = 0;
            while c < count {
                let valid = (count - c).min(w);
                let entry = |k: usize| c + k.min(valid - 1);
                let ii: Slots = std::array::from_fn(|k| *near.i.get_unchecked(entry(k)) as usize);
                let jj: Slots = std::array::from_fn(|k| *near.j.get_unchecked(entry(k)) as usize);
                let pair: Slots = std::array::from_fn(|k| *near.pair.get_unchecked(entry(k)) as usize);
                let mm: Slots = std::array::from_fn(|k| *near.slot.get_unchecked(entry(k)) as usize);
                // Each block checks its indices once and reads without a bounds test per access (the
                // index work was 29 % of the linear loop's samples, issue 30's fourteenth round).
                assert!(ii[..w].iter().chain(&jj[..w]).all(|&p| p < n));
                assert!(pair[..w].iter().all(|&p| p < e.table.len()));
                let lanes = V::mask_from_fn(|k| k < valid);
                let si = V::gather_sphere(sp, &ii);
                let sj = V::gather_sphere(sp, &jj);
                let d = [sj[0] - si[0], sj[1] - si[1], sj[2] - si[2]];
                let dist2 = dot3(d, d);
                let sum_r = si[3] + sj[3];
                let range = sum_r + V::from_fn(|k| e.table.get_unchecked(pair[k])[0]);
                // Beyond the forgetting distance a contact forgets (as the scalar loop's `pair`), before its
                // memory is read; such lanes are then skipped (apart, nothing remembered).
                let far = sum_r + forget;
                let beyond = (dist2.ge(far * far) & lanes).bits();
                if beyond != 0 {
                    for k in (0..w).filter(|k| beyond & (1 << k) != 0) {
                        let initial = e.pairs[pair[k]].initial;
                        super::super::force_loop::forget(&mut normal[mm[k]], &mut spring[mm[k]], &mut radius_memory[mm[k]], initial);
                    }
                }
                let s0 = [V::from_fn(|k| spring[mm[k]].x), V::from_fn(|k| spring[mm[k]].y), V::from_fn(|k| spring[mm[k]].z)];
                let (h, must_visit) = if L::LANES == Lanes::Vector {
                    let h = L::load_history::<V>(normal, &mm);
                    (h, L::must_visit(&h, |q| V::from_fn(|k| e.table.get_unchecked(pair[k])[COMMON + q])))
                } else {
                    let must = V::mask_from_fn(|k| {
                        let (h, it) = (&normal[mm[k]], &e.pairs[pair[k]]);
                        !(*h == it.initial || it.law.rests_apart(h))
                    });
                    (History::none(), must)
                };
                // The scalar loop skips a pair that is apart (dist2 >= range^2), has no spring and whose
                // history allows it; the lanes visit the rest.
                let within = dist2.nge(range * range);
                let has_spring = s0[0].ne(zero) | s0[1].ne(zero) | s0[2].ne(zero);
                let visit = (within | has_spring | must_visit) & lanes;
                if visit.bits() != 0 {
                    let block = Block { ii, jj, pair, mm, si, sj, s0, h, visit };
                    contacts::<L, V>(e, block, normal, spring, radius_memory, sink);
                }
                c += w;
            }
        }
    }

    /// Lane k's slot in a block of consecutive slots.
    pub(super) const ORDER: Slots = [0, 1, 2, 3, 4, 5, 6, 7];

    /// A block of lanes for the contact: the two spheres, the species pair and the memory slot (relative to
    /// the part's first) of each lane, what is read of them, and the lanes to visit.
    struct Block<V: Simd> {
        ii: Slots,
        jj: Slots,
        pair: Slots,
        mm: Slots,
        si: [V; 10],
        sj: [V; 10],
        /// The tangential springs.
        s0: [V; 3],
        h: History<V>,
        visit: V::Mask,
    }

    /// The contacts of a block's visited lanes (`kernel::contact` from the distance on): their memory
    /// written, their shares added to the sink in lane order.
    ///
    /// # Safety
    /// The width's instruction set; every `ii[k]`, `jj[k]` below the spheres' count (and their records
    /// packed on eight lanes) and every `pair[k]` below the table's length, for all eight entries.
    #[inline(always)]
    unsafe fn contacts<L: BedLaw, V: Simd>(
        e: &LaneInput<L>,
        b: Block<V>,
        normal: &mut [L::History],
        spring: &mut [Vec3],
        radius_memory: &mut [f64],
        sink: &mut Sink,
    ) {
        // SAFETY: as `near_pairs` (the block's spheres and pairs were checked there).
        unsafe {
            let w = V::N;
            let Block { ii, jj, pair, mm, si, sj, s0, h, visit } = b;
            let visit_bits = visit.bits();
            let zero = V::splat(0.0);
            let (one, half) = (V::splat(1.0), V::splat(0.5));
            let dt = V::splat(e.dt);
            let param = |q: usize| V::from_fn(|k| e.table.get_unchecked(pair[k])[q]);
            let xi = [si[0], si[1], si[2]];
            let xj = [sj[0], sj[1], sj[2]];
            let d = [xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]];
            let dist2 = dot3(d, d);
            let (ri, rj) = (si[3], sj[3]);
            let sum_r = ri + rj;
            let vector = L::LANES == Lanes::Vector;
            let interactions = |k: usize| &e.pairs[pair[k]];
            let dist = dist2.sqrt();
            let inv = one / dist;
            let nrm = [d[0] * inv, d[1] * inv, d[2] * inv];
            let alpha = sum_r - dist;
            let half_alpha = half * alpha;
            let (li, lj) = (ri - half_alpha, rj - half_alpha);
            // The surface velocity of i relative to j (kernel::surface_velocity).
            let (vi, vj) = ([si[4], si[5], si[6]], [sj[4], sj[5], sj[6]]);
            let (wi, wj) = ([si[7], si[8], si[9]], [sj[7], sj[8], sj[9]]);
            let om: [V; 3] = std::array::from_fn(|c| wi[c] * li + wj[c] * lj);
            let v = [
                (vi[0] - vj[0]) + (om[1] * nrm[2] - om[2] * nrm[1]),
                (vi[1] - vj[1]) + (om[2] * nrm[0] - om[0] * nrm[2]),
                (vi[2] - vj[2]) + (om[0] * nrm[1] - om[1] * nrm[0]),
            ];
            let guess_lanes: [f64; 8] = std::array::from_fn(|k| radius_memory[mm[k.min(w - 1)]]);
            // The law (kernel::contact from here on).
            let ev = if vector {
                // A loop, not `array::from_fn`: its closure is not inlined and would call the vector
                // loads out of line (30 % slower at eight lanes, issue 30's fourteenth round).
                let mut law_params = [zero; LAW_PARAMS];
                for (q, p) in law_params.iter_mut().enumerate() {
                    *p = param(COMMON + q);
                }
                let guess = V::load(&guess_lanes[..w]);
                let ev = L::evaluate_lanes(&law_params, alpha, &h, &|k| &e.pairs[pair[k]].law, guess);
                L::store_history(normal, &mm, &ev.history, visit_bits);
                ev
            } else {
                let its: [&Interaction<L>; 8] = std::array::from_fn(interactions);
                per_lane(&its[..w], alpha, normal, &mm, &guess_lanes[..w], visit_bits)
            };
            let touch = visit & ev.in_contact;
            let approach = dot3(v, nrm);
            let abs_k = ev.stiffness.abs();
            let root_k = ev.damping_stiffness.abs().sqrt();
            let damping = V::select(ev.yielded, param(2), param(1));
            let f_n = ev.force + damping * root_k * approach;
            let minus_f_n = -f_n;
            // The tangential spring, kept in the tangent plane of the turned contact with its magnitude.
            let v_t: [V; 3] = std::array::from_fn(|c| v[c] - nrm[c] * approach);
            let along = dot3(s0, nrm);
            let mut s_t: [V; 3] = std::array::from_fn(|c| s0[c] - nrm[c] * along);
            let t2 = dot3(s_t, s_t);
            let turned = along.ne(zero) & t2.gt(zero);
            if turned.bits() != 0 {
                let x = along * along / t2;
                let small = x.lt(V::splat(1e-4));
                let series = one + x * (half - V::splat(0.125) * x);
                let factor = if turned.and_not(small).bits() != 0 { V::select(small, series, (one + x).sqrt()) } else { series };
                s_t = std::array::from_fn(|c| V::select(turned, s_t[c] * factor, s_t[c]));
            }
            // TangentialSpring::step with k_t (000 Eq. 22, or Mindlin's 004 Eq. 3.25) and the limit mu max(N, 0).
            let k_t = match ev.tangential_stiffness {
                Some(k_t) => k_t,
                None => param(3) * if L::MINDLIN { ev.radius } else { abs_k },
            };
            let mu = param(5);
            let mut f_s: [V; 3] = std::array::from_fn(|c| s_t[c] - v_t[c] * dt * k_t);
            let limit = mu * ev.sliding_normal_force.max(zero);
            let norm2 = dot3(f_s, f_s);
            let sliding = norm2.nle(limit * limit);
            if sliding.bits() != 0 {
                let norm = norm2.sqrt();
                let scale = (limit / norm).keep(norm.gt(zero));
                f_s = std::array::from_fn(|c| V::select(sliding, f_s[c] * scale, f_s[c]));
            }
            let root_kt = param(4) * root_k;
            let c_t = param(1) * root_kt;
            let tangential: [V; 3] = std::array::from_fn(|c| V::select(sliding, f_s[c], f_s[c] - v_t[c] * c_t));
            // No friction: no tangential force, and the spring as it was. None out of contact either.
            let rubs = mu.gt(zero);
            let tangential: [V; 3] = std::array::from_fn(|c| tangential[c].keep(rubs & touch));
            // The memory: a visited lane in contact keeps the new spring (where it rubs), one out of
            // contact forgets it; a lane not visited writes nothing.
            let new_s: [V::Array; 3] = std::array::from_fn(|c| V::select(rubs, f_s[c], s0[c]).keep(ev.in_contact).to_array());
            let new_radius = ev.radius.to_array();
            for k in (0..w).filter(|k| visit_bits & (1 << k) != 0) {
                spring[mm[k]] = Vec3::new(new_s[0].as_ref()[k], new_s[1].as_ref()[k], new_s[2].as_ref()[k]);
                radius_memory[mm[k]] = new_radius.as_ref()[k];
            }
            // Each contact's share of its two bodies; lanes not touching add +0.0, which changes no sum (a
            // sum that starts at +0.0 is never -0.0).
            // A lane out of contact that attracts (Tomas) gives the normal force alone, and no rolling load.
            let attracts = visit & ev.attraction;
            let minus_f = -ev.force;
            let acts = touch | attracts;
            let force: [V; 3] = std::array::from_fn(|c| V::select(attracts, nrm[c] * minus_f, nrm[c] * minus_f_n + tangential[c]).keep(acts));
            let turn = [
                nrm[1] * tangential[2] - nrm[2] * tangential[1],
                nrm[2] * tangential[0] - nrm[0] * tangential[2],
                nrm[0] * tangential[1] - nrm[1] * tangential[0],
            ];
            let (li, lj) = (li.keep(acts), lj.keep(acts));
            let rolling = (param(6) * ev.force.abs()).keep(touch);
            let torque_i = [turn[0] * li, turn[1] * li, turn[2] * li];
            let torque_j = [turn[0] * lj, turn[1] * lj, turn[2] * lj];
            V::add_shares(&mut sink.rows(), &ii[..w], &jj[..w], Share { force, rolling, torque_i, torque_j });
        }
    }
}
