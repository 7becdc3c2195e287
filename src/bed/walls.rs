//! Walls: a plane (the die's floor), a cylinder (the die), a sphere (the indenter), the piston (a
//! plane that moves), the mirror planes of a die sector, and the rings of a split die (the shear
//! cell's). Each has a prescribed velocity, set by whoever drives the bed, and measures the force the
//! particles exert on it.

use super::{Vec3, ZERO};

/// The geometry of a wall, placed by the wall's `position`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Shape {
    /// Plane through `position`; particles stay on the side `normal` (unit) points to.
    Plane {
        /// Unit normal, pointing to the particles' side.
        normal: Vec3,
    },
    /// Cylinder of this radius around the vertical axis through `position`; particles stay inside.
    Cylinder {
        /// Inner radius [m].
        radius: f64,
    },
    /// Sphere of this radius centred at `position`; particles stay outside.
    Sphere {
        /// Radius [m].
        radius: f64,
    },
    /// Mirror plane of a die sector through `position` with unit `normal` into the sector: a particle
    /// meets its own mirror image there. The overlap is the pair's, 2 (r - distance); the interaction
    /// is the particle-particle law of the particle with its image (`any::mirror_row`).
    Mirror {
        /// Unit normal, pointing into the sector.
        normal: Vec3,
    },
    /// A ring of a split die (`shear`): the solid between the radii `radius` and `radius + thickness`
    /// around the vertical axis through `position`, from `position.z` up `height`. Particles stay inside;
    /// a sphere meets the ring's inner face, its top or bottom face, or an edge: the nearest point of the
    /// ring's cross-section in the sphere's meridian plane. So a sphere of the upper ring's powder that
    /// the shear has carried over the lower ring's wall rests on that wall's top face (the Jenike cell's
    /// rings: 003 Sec. 5.1, Fig. 13) instead of meeting an infinite cylinder from outside.
    Ring {
        /// Inner radius [m].
        radius: f64,
        /// Height [m].
        height: f64,
        /// Wall thickness [m].
        thickness: f64,
    },
}

/// A wall of the bed: its shape and place, its prescribed velocity and the force the particles exert on it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Wall {
    /// Name (`floor`, `die`, `piston`, `indenter`, `mirror_x`, `mirror_y`).
    pub name: String,
    /// Geometry.
    pub shape: Shape,
    /// A point of the plane, the axis point of the cylinder, the centre of the sphere [m].
    pub position: Vec3,
    /// Prescribed velocity [m/s].
    pub velocity: Vec3,
    /// Force of the particles on the wall during the last step [N].
    pub force: Vec3,
}

/// Where a particle meets a wall: its overlap and the unit normal from the particle's centre towards the
/// wall (the wall's velocity is the wall's own, `Wall::velocity`).
#[derive(Debug, Clone, Copy)]
pub struct WallTouch {
    /// Overlap, positive in contact [m] (for a mirror plane, the pair's overlap with the image).
    pub overlap: f64,
    /// Unit normal from the particle's centre towards the wall.
    pub normal: Vec3,
}

impl Wall {
    /// A plane named `name` through `point` with `normal` (normalised here) pointing to the particles' side; at rest.
    pub fn plane(name: &str, point: Vec3, normal: Vec3) -> Wall {
        let l = normal.norm();
        Wall { name: name.into(), shape: Shape::Plane { normal: normal * (1.0 / l) }, position: point, velocity: ZERO, force: ZERO }
    }

    /// A vertical cylinder named `name` around the axis through `axis_point`, of inner `radius` [m]; at rest.
    pub fn cylinder(name: &str, axis_point: Vec3, radius: f64) -> Wall {
        Wall { name: name.into(), shape: Shape::Cylinder { radius }, position: axis_point, velocity: ZERO, force: ZERO }
    }

    /// A mirror plane named `name` through `point` with `normal` (normalised here) pointing into the sector; at rest.
    pub fn mirror(name: &str, point: Vec3, normal: Vec3) -> Wall {
        let l = normal.norm();
        Wall { name: name.into(), shape: Shape::Mirror { normal: normal * (1.0 / l) }, position: point, velocity: ZERO, force: ZERO }
    }

    /// Whether this is a mirror plane of a die sector.
    pub fn is_mirror(&self) -> bool {
        matches!(self.shape, Shape::Mirror { .. })
    }

    /// A ring named `name` (`Shape::Ring`) around the vertical axis through `base` (the ring's bottom), of
    /// inner `radius`, `height` and `thickness` [m]; at rest.
    pub fn ring(name: &str, base: Vec3, radius: f64, height: f64, thickness: f64) -> Wall {
        Wall { name: name.into(), shape: Shape::Ring { radius, height, thickness }, position: base, velocity: ZERO, force: ZERO }
    }

    /// A sphere named `name` centred at `centre` of `radius` [m] (the indenter); at rest.
    pub fn sphere(name: &str, centre: Vec3, radius: f64) -> Wall {
        Wall { name: name.into(), shape: Shape::Sphere { radius }, position: centre, velocity: ZERO, force: ZERO }
    }

    /// The radius of curvature the contact law sees (the sphere's), or none for flat walls.
    pub fn curvature_radius(&self) -> Option<f64> {
        match self.shape {
            Shape::Sphere { radius } => Some(radius),
            _ => None,
        }
    }

    /// Overlap and normal for a particle at `x` of radius `r`.
    #[inline(always)]
    pub fn touch(&self, x: Vec3, r: f64) -> WallTouch {
        let d = x - self.position;
        match self.shape {
            Shape::Plane { normal } => WallTouch { overlap: r - d.dot(&normal), normal: -normal },
            Shape::Mirror { normal } => WallTouch { overlap: 2.0 * (r - d.dot(&normal)), normal: -normal },
            Shape::Cylinder { radius } => {
                let rho = d.xy().norm();
                let n = if rho > 0.0 { Vec3::new(d.x / rho, d.y / rho, 0.0) } else { Vec3::x() };
                WallTouch { overlap: r - (radius - rho), normal: n }
            }
            Shape::Ring { radius, height, thickness } => {
                let rho = d.xy().norm();
                let out = if rho > 0.0 { Vec3::new(d.x / rho, d.y / rho, 0.0) } else { Vec3::x() };
                // The nearest point of the cross-section [radius, radius + thickness] x [0, height].
                let (q_rho, q_z) = (rho.clamp(radius, radius + thickness), d.z.clamp(0.0, height));
                let (g_rho, g_z) = (q_rho - rho, q_z - d.z);
                let dist = (g_rho * g_rho + g_z * g_z).sqrt();
                if dist == 0.0 {
                    // A centre inside the ring's solid: pushed back through the inner face.
                    WallTouch { overlap: r + (rho - radius), normal: out }
                } else {
                    WallTouch { overlap: r - dist, normal: Vec3::new(out.x * g_rho / dist, out.y * g_rho / dist, g_z / dist) }
                }
            }
            Shape::Sphere { radius } => {
                let dist = d.norm();
                let n = if dist > 0.0 { d * (-1.0 / dist) } else { Vec3::new(0.0, 0.0, -1.0) };
                WallTouch { overlap: r + radius - dist, normal: n }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlaps_and_normals() {
        let floor = Wall::plane("floor", ZERO, Vec3::z());
        let t = floor.touch(Vec3::new(0.3, 0.0, 0.9e-3), 1e-3);
        assert!((t.overlap - 0.1e-3).abs() < 1e-15);
        assert_eq!(t.normal, -Vec3::z());
        let die = Wall::cylinder("die", ZERO, 0.02);
        let t = die.touch(Vec3::new(0.0, 0.0195, 0.01), 1e-3);
        assert!((t.overlap - 0.5e-3).abs() < 1e-15);
        assert!((t.normal[1] - 1.0).abs() < 1e-15);
        let ball = Wall::sphere("ball", Vec3::new(0.0, 0.0, 0.01), 5e-3);
        let t = ball.touch(Vec3::new(0.0, 0.0, 0.01 - 5.5e-3), 1e-3);
        assert!((t.overlap - 0.5e-3).abs() < 1e-15);
        assert_eq!(t.normal, Vec3::z());
        // A sphere 0.9 r from a mirror plane overlaps its image by 2 x 0.1 r.
        let m = Wall::mirror("mirror_x", ZERO, Vec3::x());
        let t = m.touch(Vec3::new(0.9e-3, 0.004, 0.01), 1e-3);
        assert!((t.overlap - 0.2e-3).abs() < 1e-15);
        assert_eq!(t.normal, -Vec3::x());
    }

    #[test]
    fn a_ring_is_its_cylinder_inside_and_a_solid_at_its_faces_and_edges() {
        let (radius, height, thickness, r) = (0.01, 0.005, 0.002, 1e-3);
        let ring = Wall::ring("upper_ring", Vec3::new(0.0, 0.0, 0.002), radius, height, thickness);
        let die = Wall::cylinder("die", ZERO, radius);
        // Within its height: the die's cylinder, to the bit.
        for x in [Vec3::new(0.0095, 0.0, 0.004), Vec3::new(-0.003, 0.0093, 0.0069)] {
            let (a, b) = (ring.touch(x, r), die.touch(x, r));
            assert_eq!((a.overlap, a.normal), (b.overlap, b.normal));
        }
        // Below it, beside the inner face: no contact; a sphere resting on its top face at (0.0105, 0).
        assert!(ring.touch(Vec3::new(0.0095, 0.0, 0.0005), r).overlap < 0.0);
        let t = ring.touch(Vec3::new(0.0105, 0.0, 0.007 + 0.9e-3), r);
        assert!((t.overlap - 0.1e-3).abs() < 1e-15, "{t:?}");
        assert_eq!(t.normal, -Vec3::z());
        // Under its bottom face, and at its inner lower edge (45 degrees).
        let t = ring.touch(Vec3::new(0.0, 0.011, 0.002 - 0.5e-3), r);
        assert!((t.overlap - 0.5e-3).abs() < 1e-15 && t.normal == Vec3::z(), "{t:?}");
        let s = 0.5e-3;
        let t = ring.touch(Vec3::new(radius - s, 0.0, 0.002 - s), r);
        assert!((t.overlap - (r - s * 2f64.sqrt())).abs() < 1e-15, "{t:?}");
        assert!((t.normal - Vec3::new(1.0, 0.0, 1.0) / 2f64.sqrt()).norm() < 1e-15);
        // A centre inside the solid is pushed back through the inner face.
        let t = ring.touch(Vec3::new(0.0, -0.0102, 0.004), r);
        assert!((t.overlap - 1.2e-3).abs() < 1e-15 && (t.normal + Vec3::y()).norm() < 1e-15, "{t:?}");
    }
}
