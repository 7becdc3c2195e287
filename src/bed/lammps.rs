//! Export of a bed to a LAMMPS data file (`atom_style sphere`: id type diameter density x y z, and
//! velocities), for the side-by-side benchmark `benches/vs_lammps.sh`.

use super::any::AnyEngine;
use std::fmt::Write;

/// The bed's spheres as a LAMMPS data file: one atom type, the particle `density` [kg/m^3], positions
/// [m] and velocities [m/s], angular velocities [rad/s], in a box around the spheres with a margin.
pub fn data_file(engine: &AnyEngine, density: f64) -> String {
    let p = engine.particles();
    let n = p.len();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for (x, r) in p.position.iter().zip(&p.radius) {
        for c in 0..3 {
            lo[c] = lo[c].min(x[c] - r);
            hi[c] = hi[c].max(x[c] + r);
        }
    }
    // A margin of a few millimetres so no sphere starts on the box boundary; the die fits inside.
    let m = 2e-3;
    let mut s = String::with_capacity(n * 100);
    let _ = writeln!(s, "LAMMPS data file: powderfmu bed\n\n{n} atoms\n1 atom types\n");
    let _ = writeln!(
        s,
        "{:e} {:e} xlo xhi\n{:e} {:e} ylo yhi\n{:e} {:e} zlo zhi\n",
        lo[0] - m,
        hi[0] + m,
        lo[1] - m,
        hi[1] + m,
        lo[2].min(0.0) - m,
        hi[2] + 4.0 * m
    );
    let _ = writeln!(s, "Atoms # sphere\n");
    for k in 0..n {
        let x = p.position[k];
        let _ = writeln!(s, "{} 1 {:.17e} {density} {:.17e} {:.17e} {:.17e}", k + 1, 2.0 * p.radius[k], x[0], x[1], x[2]);
    }
    let _ = writeln!(s, "\nVelocities\n");
    for k in 0..n {
        let (v, w) = (p.velocity[k], p.angular_velocity[k]);
        let _ = writeln!(s, "{} {:e} {:e} {:e} {:e} {:e} {:e}", k + 1, v[0], v[1], v[2], w[0], w[1], w[2]);
    }
    s
}
