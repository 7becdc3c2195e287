//! The kick on AVX2 lanes: four consecutive spheres at a time, each lane the same IEEE operations in the
//! same order as the scalar `kick_body` (the half kicks, the rolling brake, the drift and the largest
//! squared displacement), so a run gives the same bits either way (`tests/bed_isa.rs`).
//!
//! Why: the scalar kick is a chain per sphere (the spin's square root, the brake's division, then the
//! second half kick on the braked spin) behind a branch on `spin > brake` that a settled bed cannot
//! predict; it took 18.5 % of a step of the seed's test on the shipped quarter bed (`perf record`, one
//! thread). On lanes the branch is a select and four chains run in one (docs/benchmarks.md, issue 30's
//! eleventh round).

use super::record::Record;
use super::simd::{load4x4, transpose};
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
    let Kick { g, h, halves, dt } = kick;
    let end = base + v.len() / 4 * 4;
    let (inv_mass, inv_inertia, radius) = (&body.inv_mass[base..end], &body.inv_inertia[base..end], &body.radius[base..end]);
    let (load, reference) = (&load[base..end], &refs.list[base..end]);
    let near = refs.near.get(base..end);
    // SAFETY: AVX2 is available (the contract); every slice access below is checked.
    unsafe {
        let n = v.len() / 4 * 4;
        assert!(w.len() >= n && x.len() >= n);
        let write = !records.is_empty() && dt != 0.0;
        assert!(!write || records.len() >= n);
        let (zero, one) = (_mm256_setzero_pd(), _mm256_set1_pd(1.0));
        let (gx, gy, gz, hv, dtv) = (_mm256_set1_pd(g.x), _mm256_set1_pd(g.y), _mm256_set1_pd(g.z), _mm256_set1_pd(h), _mm256_set1_pd(dt));
        let (mut moved, mut moved_near) = (zero, zero);
        let mut q = 0;
        while q < n {
            let im = _mm256_loadu_pd(inv_mass[q..q + 4].as_ptr());
            let ii = _mm256_loadu_pd(inv_inertia[q..q + 4].as_ptr());
            let r = _mm256_loadu_pd(radius[q..q + 4].as_ptr());
            let l = &load[q..q + 4];
            // A Load is eight f64: [force, rolling] then [torque, pad].
            let lower: [*const f64; 4] = std::array::from_fn(|k| &l[k] as *const _ as *const f64);
            let [fx, fy, fz, rolling] = load4x4(lower);
            let [tx, ty, tz, _] = load4x4(lower.map(|p| p.wrapping_add(4)));
            let [mut vx, mut vy, mut vz] = load3(v, q);
            let [mut wx, mut wy, mut wz] = load3(w, q);
            let rolls = _mm256_cmp_pd::<_CMP_GT_OQ>(rolling, zero);
            // ((rolling r) ii) h, as the scalar brake.
            let brake = _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(rolling, r), ii), hv);
            for _ in 0..halves {
                vx = _mm256_add_pd(vx, _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(fx, im), gx), hv));
                vy = _mm256_add_pd(vy, _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(fy, im), gy), hv));
                vz = _mm256_add_pd(vz, _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(fz, im), gz), hv));
                wx = _mm256_add_pd(wx, _mm256_mul_pd(_mm256_mul_pd(tx, ii), hv));
                wy = _mm256_add_pd(wy, _mm256_mul_pd(_mm256_mul_pd(ty, ii), hv));
                wz = _mm256_add_pd(wz, _mm256_mul_pd(_mm256_mul_pd(tz, ii), hv));
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
            store3(v, q, [vx, vy, vz]);
            store3(w, q, [wx, wy, wz]);
            if dt != 0.0 {
                let [mut xx, mut xy, mut xz] = load3(x, q);
                xx = _mm256_add_pd(xx, _mm256_mul_pd(vx, dtv));
                xy = _mm256_add_pd(xy, _mm256_mul_pd(vy, dtv));
                xz = _mm256_add_pd(xz, _mm256_mul_pd(vz, dtv));
                store3(x, q, [xx, xy, xz]);
                let [rx, ry, rz] = load3(reference, q);
                let (dx, dy, dz) = (_mm256_sub_pd(xx, rx), _mm256_sub_pd(xy, ry), _mm256_sub_pd(xz, rz));
                let d2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
                // max(d2, moved) keeps `moved` where d2 is NaN, as the scalar f64::max does.
                moved = _mm256_max_pd(d2, moved);
                if let Some(near) = near {
                    let [rx, ry, rz] = load3(near, q);
                    let (dx, dy, dz) = (_mm256_sub_pd(xx, rx), _mm256_sub_pd(xy, ry), _mm256_sub_pd(xz, rz));
                    let d2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
                    moved_near = _mm256_max_pd(d2, moved_near);
                }
                if write {
                    let rows = [transpose(xx, xy, xz, r), transpose(vx, vy, vz, zero), transpose(wx, wy, wz, zero)];
                    for (k, rec) in records[q..q + 4].iter_mut().enumerate() {
                        for (c, row) in rows.iter().enumerate() {
                            _mm256_storeu_pd(rec.0[4 * c..4 * c + 4].as_mut_ptr(), row[k]);
                        }
                    }
                }
            }
            q += 4;
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
