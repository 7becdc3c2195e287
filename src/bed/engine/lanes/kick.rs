//! The kick on AVX2 lanes: four consecutive spheres at a time, each lane the same IEEE operations in the
//! same order as the scalar `kick_body` (the half kicks, the rolling brake, the drift and the largest
//! squared displacement), so a run gives the same bits either way (`tests/bed_isa.rs`).
//!
//! Why: the scalar kick is a chain per sphere (the spin's square root, the brake's division, then the
//! second half kick on the braked spin) behind a branch on `spin > brake` that a settled bed cannot
//! predict; it took 18.5 % of a step of the seed's test on the shipped quarter bed (`perf record`, one
//! thread). On lanes the branch is a select and four chains run in one (docs/benchmarks.md, issue 30's
//! eleventh round); on AVX-512 the spins of two blocks share one chain of eight (`spin8`, the twentieth
//! round).

use super::record::Record;
use super::simd::transpose;
use crate::bed::engine::partition::Load;
use crate::bed::engine::{Body, Kick, References};
use crate::bed::Vec3;
use std::arch::x86_64::*;

const _: () = assert!(std::mem::size_of::<Vec3>() == 24, "four vectors are twelve consecutive f64");

/// Four consecutive 3-vectors from `v[q]` on as x, y and z lanes: twelve f64 in three loads, shuffled.
#[inline(always)]
unsafe fn load3(v: &[Vec3], q: usize) -> [__m256d; 3] {
    // SAFETY: AVX2 (the caller's); the four vectors are checked in bounds and are twelve consecutive f64.
    unsafe {
        let p = v[q..q + 4].as_ptr() as *const f64;
        let (a, b, c) = (_mm256_loadu_pd(p), _mm256_loadu_pd(p.add(4)), _mm256_loadu_pd(p.add(8)));
        // a = x0 y0 z0 x1, b = y1 z1 x2 y2, c = z2 x3 y3 z3
        let s = _mm256_blend_pd::<0b1100>(a, b); // x0 y0 x2 y2
        let t = _mm256_permute2f128_pd::<0x21>(a, c); // z0 x1 z2 x3
        let u = _mm256_permute2f128_pd::<0x30>(b, c); // y1 z1 y3 z3
        [_mm256_shuffle_pd::<0b1010>(s, t), _mm256_shuffle_pd::<0b0101>(s, u), _mm256_shuffle_pd::<0b1010>(t, u)]
    }
}

/// Four rows of four f64 (the `Load` halves of four spheres) as four lanes: row k's element c in lane k
/// of the c-th.
#[inline(always)]
unsafe fn load4x4(rows: [*const f64; 4]) -> [__m256d; 4] {
    // SAFETY: AVX2 (the caller's); each pointer holds four f64 (the caller's).
    unsafe { transpose(_mm256_loadu_pd(rows[0]), _mm256_loadu_pd(rows[1]), _mm256_loadu_pd(rows[2]), _mm256_loadu_pd(rows[3])) }
}

/// x, y and z lanes back to four consecutive 3-vectors from `v[q]` on: `load3` reversed, three stores
/// (masked stores cost this machine more than the kick's arithmetic).
#[inline(always)]
unsafe fn store3(v: &mut [Vec3], q: usize, c: [__m256d; 3]) {
    // SAFETY: AVX2 (the caller's); the four vectors are checked in bounds and are twelve consecutive f64.
    unsafe {
        let p = v[q..q + 4].as_mut_ptr() as *mut f64;
        let [x, y, z] = c;
        let s = _mm256_shuffle_pd::<0b0000>(x, y); // x0 y0 x2 y2
        let t = _mm256_shuffle_pd::<0b1010>(z, x); // z0 x1 z2 x3
        let u = _mm256_shuffle_pd::<0b1111>(y, z); // y1 z1 y3 z3
        _mm256_storeu_pd(p, _mm256_permute2f128_pd::<0x20>(s, t));
        _mm256_storeu_pd(p.add(4), _mm256_permute2f128_pd::<0x30>(u, s));
        _mm256_storeu_pd(p.add(8), _mm256_permute2f128_pd::<0x31>(t, u));
    }
}

/// What the kick reads of four consecutive spheres, as lanes.
struct Block {
    im: __m256d,
    ii: __m256d,
    r: __m256d,
    f: [__m256d; 3],
    rolling: __m256d,
    t: [__m256d; 3],
    v: [__m256d; 3],
    w: [__m256d; 3],
}

/// Spheres q..q+4 of the slices (`kick_lanes`'s).
///
/// # Safety
/// AVX2 (the caller's).
#[inline(always)]
unsafe fn read(q: usize, v: &[Vec3], w: &[Vec3], inv_mass: &[f64], inv_inertia: &[f64], radius: &[f64], load: &[Load]) -> Block {
    // SAFETY: AVX2 (the caller's); every slice access is checked.
    unsafe {
        let l = &load[q..q + 4];
        // A Load is eight f64: [force, rolling] then [torque, pad].
        let lower: [*const f64; 4] = std::array::from_fn(|k| &l[k] as *const _ as *const f64);
        let [fx, fy, fz, rolling] = load4x4(lower);
        let [tx, ty, tz, _] = load4x4(lower.map(|p| p.wrapping_add(4)));
        Block {
            im: _mm256_loadu_pd(inv_mass[q..q + 4].as_ptr()),
            ii: _mm256_loadu_pd(inv_inertia[q..q + 4].as_ptr()),
            r: _mm256_loadu_pd(radius[q..q + 4].as_ptr()),
            f: [fx, fy, fz],
            rolling,
            t: [tx, ty, tz],
            v: load3(v, q),
            w: load3(w, q),
        }
    }
}

/// The spin's half kicks of one block on four lanes: w += T/I h, then the rolling brake (the scalar
/// `kick_body`'s operations, in its order).
///
/// # Safety
/// AVX2 (the caller's).
#[inline(always)]
unsafe fn spin4(b: &mut Block, h: f64, halves: usize) {
    // SAFETY: AVX2 (the caller's).
    unsafe {
        let (zero, one, hv) = (_mm256_setzero_pd(), _mm256_set1_pd(1.0), _mm256_set1_pd(h));
        let rolls = _mm256_cmp_pd::<_CMP_GT_OQ>(b.rolling, zero);
        // ((rolling r) ii) h, as the scalar brake.
        let brake = _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(b.rolling, b.r), b.ii), hv);
        let [mut wx, mut wy, mut wz] = b.w;
        let [tx, ty, tz] = b.t;
        for _ in 0..halves {
            wx = _mm256_add_pd(wx, _mm256_mul_pd(_mm256_mul_pd(tx, b.ii), hv));
            wy = _mm256_add_pd(wy, _mm256_mul_pd(_mm256_mul_pd(ty, b.ii), hv));
            wz = _mm256_add_pd(wz, _mm256_mul_pd(_mm256_mul_pd(tz, b.ii), hv));
            if _mm256_movemask_pd(rolls) != 0 {
                // nalgebra's norm: sqrt((x x + y y) + z z).
                let spin = _mm256_sqrt_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(wx, wx), _mm256_mul_pd(wy, wy)), _mm256_mul_pd(wz, wz)));
                let stops = _mm256_cmp_pd::<_CMP_GT_OQ>(spin, brake);
                let keep = _mm256_and_pd(_mm256_sub_pd(one, _mm256_div_pd(brake, spin)), stops);
                wx = _mm256_blendv_pd(wx, _mm256_mul_pd(wx, keep), rolls);
                wy = _mm256_blendv_pd(wy, _mm256_mul_pd(wy, keep), rolls);
                wz = _mm256_blendv_pd(wz, _mm256_mul_pd(wz, keep), rolls);
            }
        }
        b.w = [wx, wy, wz];
    }
}

/// `spin4` of two blocks on eight lanes: the same operations per lane, so the same bits, with half the
/// square roots and divisions in flight. Why: with rolling friction the brake's square root and
/// division are half the kick (8.4 % of a step without it, 16.5 % with 0.01, the shipped quarter under
/// the simplified Pasha law, `perf record` one thread), and waiting on them is where its samples sit.
///
/// # Safety
/// AVX-512 F (the caller's).
#[inline(always)]
unsafe fn spin8(a: &mut Block, b: &mut Block, h: f64, halves: usize) {
    // SAFETY: AVX-512 F (the caller's).
    unsafe {
        let join = |x: __m256d, y: __m256d| _mm512_insertf64x4::<1>(_mm512_castpd256_pd512(x), y);
        let (zero, one, hv) = (_mm512_setzero_pd(), _mm512_set1_pd(1.0), _mm512_set1_pd(h));
        let (rolling, r, ii) = (join(a.rolling, b.rolling), join(a.r, b.r), join(a.ii, b.ii));
        let rolls = _mm512_cmp_pd_mask::<_CMP_GT_OQ>(rolling, zero);
        let brake = _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(rolling, r), ii), hv);
        let (mut wx, mut wy, mut wz) = (join(a.w[0], b.w[0]), join(a.w[1], b.w[1]), join(a.w[2], b.w[2]));
        let (tx, ty, tz) = (join(a.t[0], b.t[0]), join(a.t[1], b.t[1]), join(a.t[2], b.t[2]));
        for _ in 0..halves {
            wx = _mm512_add_pd(wx, _mm512_mul_pd(_mm512_mul_pd(tx, ii), hv));
            wy = _mm512_add_pd(wy, _mm512_mul_pd(_mm512_mul_pd(ty, ii), hv));
            wz = _mm512_add_pd(wz, _mm512_mul_pd(_mm512_mul_pd(tz, ii), hv));
            if rolls != 0 {
                let spin = _mm512_sqrt_pd(_mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(wx, wx), _mm512_mul_pd(wy, wy)), _mm512_mul_pd(wz, wz)));
                let stops = _mm512_cmp_pd_mask::<_CMP_GT_OQ>(spin, brake);
                // 0 where the brake stops the spin (+0.0, as the AVX2 `and`), else 1 - brake/spin.
                let keep = _mm512_maskz_sub_pd(stops, one, _mm512_div_pd(brake, spin));
                wx = _mm512_mask_mul_pd(wx, rolls, wx, keep);
                wy = _mm512_mask_mul_pd(wy, rolls, wy, keep);
                wz = _mm512_mask_mul_pd(wz, rolls, wz, keep);
            }
        }
        let low = |x: __m512d| _mm512_castpd512_pd256(x);
        let high = |x: __m512d| _mm512_extractf64x4_pd::<1>(x);
        a.w = [low(wx), low(wy), low(wz)];
        b.w = [high(wx), high(wy), high(wz)];
    }
}

/// `kick_body` (the same arguments) for the first 4 m spheres of the slices `v`, `w`, `x` (spheres
/// `base` on), none held and every one with a list reference position; returns the largest squared
/// displacements from the two references (with a drift, `dt` > 0; infinite from a near reference that
/// lacks the spheres), else 0. The caller kicks the last 0-3.
/// With a drift and `records` (one per sphere of the slices, else empty) it also writes the spheres'
/// records for the pair loop (`record::Record`) from the lanes it holds.
///
/// # Safety
/// AVX2 must be available.
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)] // as `kick_body`
pub unsafe fn kick4(
    base: usize,
    v: &mut [Vec3],
    w: &mut [Vec3],
    x: &mut [Vec3],
    body: Body,
    load: &[Load],
    refs: References,
    kick: Kick,
    records: &mut [Record],
) -> (f64, f64) {
    // SAFETY: AVX2 (the contract).
    unsafe { kick_lanes::<false>(base, v, w, x, body, load, refs, kick, records) }
}

/// `kick4` with the spin of two blocks at a time on eight lanes (`spin8`): the same bits.
///
/// # Safety
/// AVX2 and AVX-512 F must be available.
#[target_feature(enable = "avx2,avx512f")]
#[allow(clippy::too_many_arguments)] // as `kick_body`
pub unsafe fn kick8(
    base: usize,
    v: &mut [Vec3],
    w: &mut [Vec3],
    x: &mut [Vec3],
    body: Body,
    load: &[Load],
    refs: References,
    kick: Kick,
    records: &mut [Record],
) -> (f64, f64) {
    // SAFETY: AVX2 and AVX-512 F (the contract).
    unsafe { kick_lanes::<true>(base, v, w, x, body, load, refs, kick, records) }
}

/// `kick4` and `kick8`: with EIGHT the spins of two blocks at a time on eight lanes, the last block
/// alone on four.
///
/// # Safety
/// AVX2 must be available, and AVX-512 F with EIGHT.
#[inline(always)]
#[allow(clippy::too_many_arguments)] // as `kick_body`
unsafe fn kick_lanes<const EIGHT: bool>(
    base: usize,
    v: &mut [Vec3],
    w: &mut [Vec3],
    x: &mut [Vec3],
    body: Body,
    load: &[Load],
    refs: References,
    kick: Kick,
    records: &mut [Record],
) -> (f64, f64) {
    let Kick { g, h, halves, dt } = kick;
    let end = base + v.len() / 4 * 4;
    let (inv_mass, inv_inertia, radius) = (&body.inv_mass[base..end], &body.inv_inertia[base..end], &body.radius[base..end]);
    let (load, reference) = (&load[base..end], &refs.list[base..end]);
    let near = refs.near.get(base..end);
    // SAFETY: AVX2 is available, and AVX-512 F with EIGHT (the contract); every slice access below is
    // checked.
    unsafe {
        let n = v.len() / 4 * 4;
        assert!(w.len() >= n && x.len() >= n);
        let write = !records.is_empty() && dt != 0.0;
        assert!(!write || records.len() >= n);
        let zero = _mm256_setzero_pd();
        let (gx, gy, gz, hv, dtv) = (_mm256_set1_pd(g.x), _mm256_set1_pd(g.y), _mm256_set1_pd(g.z), _mm256_set1_pd(h), _mm256_set1_pd(dt));
        let (mut moved, mut moved_near) = (zero, zero);
        let lanes = Lanes { g: [gx, gy, gz], hv, dtv, zero, halves, dt, write };
        let mut q = 0;
        while q < n {
            if EIGHT && q + 8 <= n {
                let mut a = read(q, v, w, inv_mass, inv_inertia, radius, load);
                let mut b = read(q + 4, v, w, inv_mass, inv_inertia, radius, load);
                spin8(&mut a, &mut b, h, halves);
                finish(&lanes, q, &a, [v, w, x], reference, near, records, [&mut moved, &mut moved_near]);
                finish(&lanes, q + 4, &b, [v, w, x], reference, near, records, [&mut moved, &mut moved_near]);
                q += 8;
            } else {
                let mut a = read(q, v, w, inv_mass, inv_inertia, radius, load);
                spin4(&mut a, h, halves);
                finish(&lanes, q, &a, [v, w, x], reference, near, records, [&mut moved, &mut moved_near]);
                q += 4;
            }
        }
        let largest = |v: __m256d| {
            let mut m = [0.0f64; 4];
            _mm256_storeu_pd(m.as_mut_ptr(), v);
            m.into_iter().fold(0.0, f64::max)
        };
        let moved_near = if near.is_some() || dt == 0.0 { largest(moved_near) } else { f64::INFINITY };
        (largest(moved), moved_near)
    }
}

/// The kick's constants as lanes.
struct Lanes {
    g: [__m256d; 3],
    hv: __m256d,
    dtv: __m256d,
    zero: __m256d,
    halves: usize,
    dt: f64,
    write: bool,
}

/// The rest of a block's kick once its spin is done: the half kicks of v, the stores of v and w, the
/// drift, the largest squared displacements from the two references and the records.
///
/// # Safety
/// AVX2 (the caller's).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn finish(
    c: &Lanes,
    q: usize,
    b: &Block,
    [v, w, x]: [&mut [Vec3]; 3],
    reference: &[Vec3],
    near: Option<&[Vec3]>,
    records: &mut [Record],
    [moved, moved_near]: [&mut __m256d; 2],
) {
    // SAFETY: AVX2 (the caller's); every slice access is checked.
    unsafe {
        let [mut vx, mut vy, mut vz] = b.v;
        let [fx, fy, fz] = b.f;
        let [gx, gy, gz] = c.g;
        for _ in 0..c.halves {
            vx = _mm256_add_pd(vx, _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(fx, b.im), gx), c.hv));
            vy = _mm256_add_pd(vy, _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(fy, b.im), gy), c.hv));
            vz = _mm256_add_pd(vz, _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(fz, b.im), gz), c.hv));
        }
        let [wx, wy, wz] = b.w;
        store3(v, q, [vx, vy, vz]);
        store3(w, q, b.w);
        if c.dt == 0.0 {
            return;
        }
        let [mut xx, mut xy, mut xz] = load3(x, q);
        xx = _mm256_add_pd(xx, _mm256_mul_pd(vx, c.dtv));
        xy = _mm256_add_pd(xy, _mm256_mul_pd(vy, c.dtv));
        xz = _mm256_add_pd(xz, _mm256_mul_pd(vz, c.dtv));
        store3(x, q, [xx, xy, xz]);
        let [rx, ry, rz] = load3(reference, q);
        let (dx, dy, dz) = (_mm256_sub_pd(xx, rx), _mm256_sub_pd(xy, ry), _mm256_sub_pd(xz, rz));
        let d2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
        // max(d2, moved) keeps `moved` where d2 is NaN, as the scalar f64::max does.
        *moved = _mm256_max_pd(d2, *moved);
        if let Some(near) = near {
            let [rx, ry, rz] = load3(near, q);
            let (dx, dy, dz) = (_mm256_sub_pd(xx, rx), _mm256_sub_pd(xy, ry), _mm256_sub_pd(xz, rz));
            let d2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
            *moved_near = _mm256_max_pd(d2, *moved_near);
        }
        if c.write {
            let rows = [transpose(xx, xy, xz, b.r), transpose(vx, vy, vz, c.zero), transpose(wx, wy, wz, c.zero)];
            for (k, rec) in records[q..q + 4].iter_mut().enumerate() {
                for (c, row) in rows.iter().enumerate() {
                    _mm256_storeu_pd(rec.0[4 * c..4 * c + 4].as_mut_ptr(), row[k]);
                }
            }
        }
    }
}
