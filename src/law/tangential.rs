//! Tangential force: an incremental spring with a Coulomb limit shifted by the law's adhesion.
//!
//! Stiffness models:
//! - `Ratio`: k_t = 4 G*/E* |k_n| with k_n the normal branch stiffness (000 Eq. 22; the linear laws,
//!   004 Eq. 4.26 and 003 Sec. 3.4);
//! - `Mindlin`: k_t = 8 G* sqrt(R* alpha) (Mindlin's no-slip solution, 004 Eq. 3.25; Hertz, JKR,
//!   Thornton-Ning);
//! - `Tomas`: k_t = 4 G* r_K with r_K = [3 R* (F_N + F_H) / (2 E*_Tomas)]^(1/3) (003 Eqs. 8-9).
//! The sliding limit is mu max(N, 0) where N is the law's `sliding_normal_force` (000 Eq. 23,
//! 004 Eqs. 4.27-4.28, 3.49, 3.75, 003 Eq. 10). When sliding, the spring is rescaled onto the limit and
//! no tangential damping acts (000 Sec. 2.2).

use crate::scene::ModelKind;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialStiffness {
    Ratio { ratio: f64 },
    Mindlin { shear_modulus: f64, radius: f64 },
    Tomas { shear_modulus: f64, radius: f64, youngs_modulus: f64 },
}

impl TangentialStiffness {
    /// The model each law uses.
    pub fn for_model(model: ModelKind, shear_modulus: f64, youngs_modulus: f64, radius: f64) -> TangentialStiffness {
        match model {
            ModelKind::Hertz | ModelKind::Jkr | ModelKind::JkrModified | ModelKind::ThorntonNing => {
                TangentialStiffness::Mindlin { shear_modulus, radius }
            }
            ModelKind::Tomas => TangentialStiffness::Tomas { shear_modulus, radius, youngs_modulus },
            _ => TangentialStiffness::Ratio { ratio: 4.0 * shear_modulus / youngs_modulus },
        }
    }

    /// k_t [N/m] for a normal state: overlap, branch stiffness and the load F_N + F_H (Tomas).
    pub fn at(&self, alpha: f64, normal_stiffness: f64, adhesive_load: f64) -> f64 {
        match *self {
            TangentialStiffness::Ratio { ratio } => ratio * normal_stiffness.abs(),
            TangentialStiffness::Mindlin { shear_modulus, radius } => 8.0 * shear_modulus * (radius * alpha.max(0.0)).sqrt(),
            TangentialStiffness::Tomas { shear_modulus, radius, youngs_modulus } => {
                let r_k = (3.0 * radius * adhesive_load.max(0.0) / (4.0 * youngs_modulus)).cbrt();
                4.0 * shear_modulus * r_k
            }
        }
    }
}

/// The elastic tangential displacement of one contact (the spring's state).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentialSpring {
    /// Elastic tangential displacement [m].
    pub xi: [f64; 3],
}

impl TangentialSpring {
    /// Adds a tangential displacement increment and returns the tangential force [N] with the spring
    /// projected back onto the Coulomb limit `mu max(normal, 0)` when it slides; `true` when sliding.
    pub fn step(&mut self, increment: [f64; 3], k_t: f64, mu: f64, sliding_normal_force: f64) -> ([f64; 3], bool) {
        for i in 0..3 {
            self.xi[i] += increment[i];
        }
        let limit = mu * sliding_normal_force.max(0.0);
        let trial = [-k_t * self.xi[0], -k_t * self.xi[1], -k_t * self.xi[2]];
        let norm = (trial[0] * trial[0] + trial[1] * trial[1] + trial[2] * trial[2]).sqrt();
        if norm <= limit || norm == 0.0 {
            return (trial, false);
        }
        let scale = limit / norm;
        let force = [trial[0] * scale, trial[1] * scale, trial[2] * scale];
        for i in 0..3 {
            self.xi[i] *= scale;
        }
        (force, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spring_sticks_then_slides_at_the_coulomb_limit() {
        let mut s = TangentialSpring::default();
        let (f, sliding) = s.step([1e-9, 0.0, 0.0], 1000.0, 0.5, 1e-5);
        assert!(!sliding);
        assert!((f[0] + 1e-6).abs() < 1e-18);
        let (f, sliding) = s.step([1e-7, 0.0, 0.0], 1000.0, 0.5, 1e-5);
        assert!(sliding);
        assert!((f[0] + 0.5e-5).abs() < 1e-18);
        // After sliding the spring holds exactly the limit: reversing unloads elastically from there.
        let (f, sliding) = s.step([-1e-9, 0.0, 0.0], 1000.0, 0.5, 1e-5);
        assert!(!sliding);
        assert!((f[0] + 0.5e-5 - 1e-6).abs() < 1e-15);
    }

    #[test]
    fn no_normal_load_means_no_tangential_force() {
        let mut s = TangentialSpring::default();
        let (f, sliding) = s.step([1e-9, 1e-9, 0.0], 1000.0, 0.5, -1.0);
        assert!(sliding);
        assert_eq!(f, [0.0, 0.0, 0.0]);
    }

    #[test]
    fn ratio_is_000_eq_22() {
        let t = TangentialStiffness::for_model(ModelKind::Nan, 1.0, 2.5, 1e-6);
        assert_eq!(t.at(1e-9, -300.0, 0.0), 4.0 * 1.0 / 2.5 * 300.0);
    }
}
