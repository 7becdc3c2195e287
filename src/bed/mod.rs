//! The DEM bed engine (DESIGN 2, 5, 7): a bed of polydisperse adhesive, elasto-plastic spheres in a die,
//! stepped with any normal law of the core, for the ball indentation test of `004` Chs. 5-7.
//!
//! One idea per file:
//! - `particles`: the spheres in structure-of-arrays form;
//! - `psd`: the size distribution of `004` Table 5.1 (the species are its size classes);
//! - `interaction`: the law, damping, tangential and rolling parameters of each pair of species;
//! - `neighbors`: linked cells and the Verlet list with its skin, and the per-contact memory across rebuilds;
//! - `walls`: plane, cylinder (the die), sphere (the indenter) and piston, with motion and reaction force;
//! - `kernel`: the force of one contact (normal law, damping, tangential spring, Coulomb, rolling);
//! - `engine`: the time step (velocity Verlet), the thread pool and the force reduction;
//! - `any`: `AnyEngine`, the engine compiled for the law of a scene (generated from `law_table!`);
//! - `pool`: the engine's own thread pool, joined on drop;
//! - `random`: the seeded random numbers of bed preparation;
//! - `scene`: the bed scene (`BedScene`), read from JSON and checked;
//! - `prepare`: fill, settle, consolidate, unload, relax (`004` Sec. 5.1.3);
//! - `stress`: Bagi's stress tensor (`004` Eqs. 5.1-5.3) in a cylinder or a box;
//! - `indentation`: the ball indentation test on a prepared bed (`004` Sec. 2.3.5, Chs. 5-7);
//! - `file`: the versioned bed file; `export`: VTK/CSV output; `render`: the PNG cross-section;
//! - `lammps`: the LAMMPS data file export for the side-by-side benchmark.

#[macro_use]
mod any;
mod engine;
pub mod export;
pub mod file;
pub mod indentation;
mod interaction;
mod kernel;
pub mod lammps;
mod neighbors;
pub mod particles;
mod pool;
pub mod prepare;
mod psd;
mod random;
pub mod render;
mod scene;
pub mod stress;
pub mod walls;

pub use any::{AnyEngine, BedError};
pub use engine::Engine;
pub use scene::BedScene;

/// A 3-vector [m], [m/s], [N], ...
pub type Vec3 = [f64; 3];

#[inline(always)]
pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
pub(crate) fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
pub(crate) fn scale(a: Vec3, s: f64) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

#[inline(always)]
pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

#[inline(always)]
pub(crate) fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}
