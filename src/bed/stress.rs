//! Bagi's stress tensor in a measurement volume (`004` Eq. 5.1):
//! sigma_ij = -1/V sum_p sum_c |x^c - x^p| n_i F_j over the particles p whose centre is in the volume
//! and their contacts c, with n the unit vector from the centre to the contact and F the contact force
//! on p. With F = -f n for a compressed contact this makes compression positive. The hydrostatic and
//! deviatoric stresses are 004 Eqs. 5.2 and 5.3.

use super::any::AnyEngine;
use super::{Tensor, Vec3};

/// A measurement volume: what it holds and how big it is.
pub trait Volume {
    /// Its volume [m^3].
    fn volume(&self) -> f64;
    /// Whether the point `x` [m] lies inside it (a particle counts when its centre does).
    fn contains(&self, x: Vec3) -> bool;
}

/// A vertical cylinder about the die axis between two heights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Region {
    /// Radius about the die axis [m].
    pub radius: f64,
    /// Lower height, included [m].
    pub z_low: f64,
    /// Upper height, excluded [m].
    pub z_high: f64,
}

impl Volume for Region {
    fn volume(&self) -> f64 {
        std::f64::consts::PI * self.radius * self.radius * (self.z_high - self.z_low)
    }

    fn contains(&self, x: Vec3) -> bool {
        x.xy().norm_squared() <= self.radius * self.radius && x.z >= self.z_low && x.z < self.z_high
    }
}

/// An axis-aligned box centred on the die axis (the dynamic bin under the indenter, 004 Sec. 5.2,
/// Fig. 5.18).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cuboid {
    /// Widths in x and y [m].
    pub width_x: f64,
    /// Width in y [m].
    pub width_y: f64,
    /// Lower height, included [m].
    pub z_low: f64,
    /// Upper height, excluded [m].
    pub z_high: f64,
}

impl Volume for Cuboid {
    fn volume(&self) -> f64 {
        self.width_x * self.width_y * (self.z_high - self.z_low)
    }

    fn contains(&self, x: Vec3) -> bool {
        2.0 * x.x.abs() <= self.width_x && 2.0 * x.y.abs() <= self.width_y && x.z >= self.z_low && x.z < self.z_high
    }
}

/// Stress tensor [Pa]; `get(i, j)` is sigma_ij with 0, 1, 2 for x, y, z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stress(pub Tensor);

impl Stress {
    /// The whole die's stress from a sector bed's: a volume about the die axis holds only the sector's
    /// share of the spheres (their mirror images the rest), with the same stress.
    pub fn of_whole_die(self, die_sector: f64) -> Stress {
        Stress(self.0 / die_sector)
    }

    /// Component sigma_ij [Pa], with 0, 1, 2 for x, y, z.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.0[(i, j)]
    }

    /// 004 Eq. 5.2.
    pub fn hydrostatic(&self) -> f64 {
        // Summed as before nalgebra (its trace starts from +0 and would turn an empty bin's -0 into +0).
        (self.get(0, 0) + self.get(1, 1) + self.get(2, 2)) / 3.0
    }

    /// 004 Eq. 5.3.
    pub fn deviatoric(&self) -> f64 {
        let (xx, yy, zz) = (self.get(0, 0), self.get(1, 1), self.get(2, 2));
        (((xx - yy).powi(2) + (xx - zz).powi(2) + (yy - zz).powi(2)) / 6.0).sqrt()
    }
}

/// Bagi's stress in `region` for the forces of the bed's current state (one extra force evaluation
/// that leaves the state unchanged, `Engine::measure_dipoles`).
pub fn bagi(engine: &mut AnyEngine, region: &impl Volume) -> Stress {
    // The dipoles through AnyEngine's own method: called here, generic over the region, the force loop
    // of every law was compiled again in each crate that calls `bagi` (tests/bed.rs: 55 s of the build).
    let dip = engine.measure_dipoles();
    let mut s = Tensor::zeros();
    for (k, x) in engine.particles().position.iter().enumerate() {
        if region.contains(*x) {
            s += dip[k];
        }
    }
    Stress(-s / region.volume())
}
