//! Bed snapshots for ParaView and spreadsheets: legacy VTK polydata (points with radius, velocity,
//! species and coordination; show them with ParaView's "Point Gaussian" representation scaled by
//! radius) and CSV with a header naming every column and its unit.

use super::any::AnyEngine;
use std::fmt::Write;

/// Legacy ASCII VTK of the spheres.
pub fn vtk(engine: &AnyEngine) -> String {
    with_engine!(engine, e => {
        let p = &e.particles;
        let z = e.coordination();
        let n = p.len();
        let mut s = String::with_capacity(n * 120);
        let _ = writeln!(s, "# vtk DataFile Version 3.0\npowderfmu bed, t = {:e} s\nASCII\nDATASET POLYDATA\nPOINTS {n} double", e.time);
        for x in &p.position {
            let _ = writeln!(s, "{:e} {:e} {:e}", x[0], x[1], x[2]);
        }
        let _ = writeln!(s, "VERTICES {n} {}", 2 * n);
        for k in 0..n {
            let _ = writeln!(s, "1 {k}");
        }
        let _ = writeln!(s, "POINT_DATA {n}\nSCALARS radius double 1\nLOOKUP_TABLE default");
        for r in &p.radius {
            let _ = writeln!(s, "{r:e}");
        }
        let _ = writeln!(s, "SCALARS species int 1\nLOOKUP_TABLE default");
        for sp in &p.species {
            let _ = writeln!(s, "{sp}");
        }
        let _ = writeln!(s, "SCALARS coordination int 1\nLOOKUP_TABLE default");
        for c in &z {
            let _ = writeln!(s, "{c}");
        }
        let _ = writeln!(s, "VECTORS velocity double");
        for v in &p.velocity {
            let _ = writeln!(s, "{:e} {:e} {:e}", v[0], v[1], v[2]);
        }
        s
    })
}

/// CSV of the spheres.
pub fn csv(engine: &AnyEngine) -> String {
    with_engine!(engine, e => {
        let p = &e.particles;
        let z = e.coordination();
        let mut s = String::from("x [m],y [m],z [m],radius [m],vx [m/s],vy [m/s],vz [m/s],species,coordination\n");
        for k in 0..p.len() {
            let (x, v) = (p.position[k], p.velocity[k]);
            let _ = writeln!(s, "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{}", x[0], x[1], x[2], p.radius[k], v[0], v[1], v[2], p.species[k], z[k]);
        }
        s
    })
}
