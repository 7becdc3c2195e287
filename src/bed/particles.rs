//! The spheres of a bed in structure-of-arrays form: each quantity is one contiguous vector, so the
//! force loop streams only what it reads.

use super::Vec3;
use std::f64::consts::PI;

/// The spheres of a bed, one entry per sphere in each array (all of the same length).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Particles {
    /// Centre position [m].
    pub position: Vec<Vec3>,
    /// Velocity [m/s].
    pub velocity: Vec<Vec3>,
    /// Angular velocity [rad/s].
    pub angular_velocity: Vec<Vec3>,
    /// Radius [m].
    pub radius: Vec<f64>,
    /// Mass [kg].
    pub mass: Vec<f64>,
    /// 1 / mass [1/kg].
    pub inv_mass: Vec<f64>,
    /// 1 / moment of inertia 2/5 m R^2 [1/(kg m^2)].
    pub inv_inertia: Vec<f64>,
    /// Species: the size class of the distribution, which selects the interaction of each pair.
    pub species: Vec<u16>,
    /// Held in place (a shortcut of the indentation, `Engine::hold`): not moved, and pairs of two held
    /// spheres are not computed.
    pub held: Vec<bool>,
}

impl Particles {
    /// Number of spheres.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// Whether there are no spheres.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Adds a sphere at rest.
    pub fn push(&mut self, position: Vec3, radius: f64, density: f64, species: u16) {
        let mass = 4.0 / 3.0 * PI * radius.powi(3) * density;
        self.position.push(position);
        self.velocity.push(super::ZERO);
        self.angular_velocity.push(super::ZERO);
        self.radius.push(radius);
        self.mass.push(mass);
        self.inv_mass.push(1.0 / mass);
        self.inv_inertia.push(1.0 / (0.4 * mass * radius * radius));
        self.species.push(species);
        self.held.push(false);
    }

    /// Reorders every array by `order` (new index k holds old particle `order[k]`).
    pub fn permute(&mut self, order: &[usize]) {
        fn apply<T: Copy>(v: &mut Vec<T>, order: &[usize]) {
            *v = order.iter().map(|&k| v[k]).collect();
        }
        apply(&mut self.position, order);
        apply(&mut self.velocity, order);
        apply(&mut self.angular_velocity, order);
        apply(&mut self.radius, order);
        apply(&mut self.mass, order);
        apply(&mut self.inv_mass, order);
        apply(&mut self.inv_inertia, order);
        apply(&mut self.held, order);
        apply(&mut self.species, order);
    }

    /// Total kinetic energy, translational plus rotational [J].
    pub fn kinetic_energy(&self) -> f64 {
        let mut e = 0.0;
        for k in 0..self.len() {
            let v = self.velocity[k];
            let w = self.angular_velocity[k];
            e += 0.5 * self.mass[k] * v.norm_squared() + 0.5 / self.inv_inertia[k] * w.norm_squared();
        }
        e
    }

    /// Total momentum [kg m/s].
    pub fn momentum(&self) -> Vec3 {
        let mut p = super::ZERO;
        for k in 0..self.len() {
            p += self.velocity[k] * self.mass[k];
        }
        p
    }

    /// Bytes held by the arrays.
    pub fn memory_bytes(&self) -> usize {
        fn bytes<T>(v: &Vec<T>) -> usize {
            v.capacity() * std::mem::size_of::<T>()
        }
        bytes(&self.position)
            + bytes(&self.velocity)
            + bytes(&self.angular_velocity)
            + bytes(&self.radius)
            + bytes(&self.mass)
            + bytes(&self.inv_mass)
            + bytes(&self.inv_inertia)
            + bytes(&self.species)
    }
}
