//! The DEM bed engine (docs/architecture.md; docs/bed.md): a bed of polydisperse adhesive, elasto-plastic spheres in a die,
//! stepped with any normal law of the core, for the ball indentation test of `004` Chs. 5-7.
//!
//! One idea per file:
//! - `particles`: the spheres in structure-of-arrays form;
//! - `psd`: the size distribution of `004` Table 5.1 (the species are its size classes);
//! - `interaction`: the law, damping, tangential and rolling parameters of each pair of species;
//! - `neighbors`: linked cells and the Verlet list with its skin, and the per-contact memory across rebuilds;
//! - `walls`: plane, cylinder (the die), sphere (the indenter), piston, mirror planes and a split die's rings, with motion and reaction force;
//! - `kernel`: the force of one contact (normal law, damping, tangential spring, Coulomb, rolling);
//! - `engine`: the time step (velocity Verlet), its threads and the force reduction;
//! - `any`: `AnyEngine`, the engine compiled for the law of a scene (generated from `law_table!`);
//! - `team`: the engine's threads, part k of each phase on thread k, joined on drop;
//! - `random`: the seeded random numbers of bed preparation;
//! - `scene`: the bed scene (`BedScene`), read from JSON and checked;
//! - `prepare`: fill, settle, consolidate, unload, relax (`004` Sec. 5.1.3);
//! - `stress`: Bagi's stress tensor (`004` Eqs. 5.1-5.3) in a cylinder or a box;
//! - `indentation`: the ball indentation test on a prepared bed (`004` Sec. 2.3.5, Chs. 5-7);
//! - `compression`: the unconfined compression test on a prepared bed (`004` Sec. 2.1): sigma_c and ff_c;
//! - `shear`: the translational (Jenike) shear cell on a prepared bed (`003` Sec. 5.1): the yield locus;
//! - `shear_state`: the file of the shear cell at the preshear's end, for shears without the preshear again;
//! - `yield_locus`: the straight yield locus and its Mohr circles (sigma_c, sigma_1; `004` Sec. 2.2);
//! - `series`: the mean of an autocorrelated series with its standard error;
//! - `file`: the versioned bed file; `export`: VTK/CSV output; `render`: the PNG cross-section;
//! - `lammps`: the LAMMPS data file export for the side-by-side benchmark.

#[macro_use]
mod any;
pub mod compression;
pub mod constraint_factor;
mod engine;
pub mod export;
pub mod file;
pub mod indentation;
mod interaction;
mod kernel;
pub mod lammps;
mod neighbors;
pub mod particles;
pub mod prepare;
mod psd;
mod random;
pub mod render;
pub mod replicas;
mod scene;
pub mod series;
pub mod shear;
pub mod shear_state;
pub mod stress;
mod team;
pub mod walls;
pub mod yield_locus;

pub use any::{AnyEngine, BedError};
pub use engine::{Engine, Isa};
pub use scene::{
    first_difference as scene_difference, keys_help as scene_keys_help, replica_difference, BedKeys, BedScene, IndenterMaterial, STRUCTURED_KEYS,
};

/// A 3-vector [m], [m/s], [N], ...: nalgebra's, so the geometry reads as vector algebra (`x - wall.position`,
/// `d.dot(&normal)`, `n * lever`, Bagi's `n F^T`). The engine still stores them structure-of-arrays
/// (`particles`: one `Vec` per quantity), and a bed file holds each as three f64, as before nalgebra.
pub type Vec3 = nalgebra::Vector3<f64>;

/// The zero vector, for the many places a force, a velocity or a spring starts from nothing.
pub const ZERO: Vec3 = Vec3::new(0.0, 0.0, 0.0);

/// A 3x3 tensor: a particle's sum of contact dipoles |x_c - x_p| n F^T (004 Eq. 5.1), a stress [Pa].
pub type Tensor = nalgebra::Matrix3<f64>;

// Component-wise operations for the body of `kernel::contact` and the pair loop of
// `engine/force_loop.rs`, kept by hand for speed: with nalgebra's operators there, 300 Hertz steps of
// the 10^4-sphere bench bed executed 6.84e9 instructions (valgrind callgrind), against 6.54e9 with these
// (6.57e9 before nalgebra), and one side-by-side timing ran 8.5 % slower (median of 7; a second, noisier
// one showed no difference). What those two call keeps nalgebra, as measured in the 6.54e9:
// `TangentialSpring::step`, `Sink::add_contact`'s Bagi outer product (its accumulation is written out
// since issue 30, with the same rounding) and `Wall::touch`. The helpers round as nalgebra does, ((a0 b0 + a1 b1) + a2 b2): either way a bed steps
// to the same bits.

#[inline(always)]
pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

#[inline(always)]
pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(a.x - b.x, a.y - b.y, a.z - b.z)
}

#[inline(always)]
pub(crate) fn add(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(a.x + b.x, a.y + b.y, a.z + b.z)
}

#[inline(always)]
pub(crate) fn scale(a: Vec3, s: f64) -> Vec3 {
    Vec3::new(a.x * s, a.y * s, a.z * s)
}

#[inline(always)]
pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
}
