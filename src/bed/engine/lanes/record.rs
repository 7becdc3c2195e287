//! A sphere as the pair loop reads it: position, radius, velocity, species and spin in one 128-byte
//! record, packed from the engine's arrays before each force loop on lanes (`pack`).
//!
//! Why: a lane reads eight values of each of its two spheres. From the engine's arrays (position,
//! velocity, spin, radius, species) that is five cache lines per sphere and three shuffled 3-vector
//! gathers; from a record it is two lines, one aligned 512-bit load and one 256-bit load, transposed
//! eight lanes at a time (docs/benchmarks.md, issue 30's seventeenth round).

use crate::bed::particles::Particles;

/// [x, y, z, r, vx, vy, vz, species, wx, wy, wz, 0, 0, 0, 0, 0]: SI units, the species as an f64 (exact).
#[derive(Clone, Copy, Default, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Record(pub [f64; 16]);

/// Writes the records of spheres `first..first + out.len()`.
pub fn pack(p: &Particles, first: usize, out: &mut [Record]) {
    let n = out.len();
    let (x, v, w) = (&p.position[first..first + n], &p.velocity[first..first + n], &p.angular_velocity[first..first + n]);
    let (r, s) = (&p.radius[first..first + n], &p.species[first..first + n]);
    for (k, rec) in out.iter_mut().enumerate() {
        let (x, v, w) = (x[k], v[k], w[k]);
        rec.0 = [x.x, x.y, x.z, r[k], v.x, v.y, v.z, f64::from(s[k]), w.x, w.y, w.z, 0.0, 0.0, 0.0, 0.0, 0.0];
    }
}
