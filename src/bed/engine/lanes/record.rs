//! A sphere as the pair loop reads it: position, radius, velocity and spin in one 128-byte
//! record, written by the step's drifting kick (`lanes::kick4`, `pack` for the spheres it leaves to the
//! scalar kick) or packed from the engine's arrays before a force loop without one.
//!
//! Why: a lane reads eight values of each of its two spheres. From the engine's arrays (position,
//! velocity, spin, radius) that is four cache lines per sphere and three shuffled 3-vector gathers;
//! from a record it is two lines, one aligned 512-bit load and one 256-bit load, transposed
//! eight lanes at a time (docs/benchmarks.md, issue 30's seventeenth round).

use crate::bed::Vec3;

/// [x, y, z, r, vx, vy, vz, 0, wx, wy, wz, 0, 0, 0, 0, 0], SI units. The species stays in its array: read
/// from there the pair loop ran 5-12 % faster than with the species as an f64 here (the conversions back
/// to a table index; issue 30's seventeenth round).
#[derive(Clone, Copy, Default, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Record(pub [f64; 16]);

/// Writes one record per entry of `out` from the spheres' positions `x`, velocities `v`, spins `w` and
/// radii `r` (each at least as long as `out`).
pub fn pack(x: &[Vec3], v: &[Vec3], w: &[Vec3], r: &[f64], out: &mut [Record]) {
    let n = out.len();
    let (x, v, w, r) = (&x[..n], &v[..n], &w[..n], &r[..n]);
    for (k, rec) in out.iter_mut().enumerate() {
        let (x, v, w) = (x[k], v[k], w[k]);
        rec.0 = [x.x, x.y, x.z, r[k], v.x, v.y, v.z, 0.0, w.x, w.y, w.z, 0.0, 0.0, 0.0, 0.0, 0.0];
    }
}
