//! Tangential force: an incremental spring (dF_t = -k_t d delta_t, 004 Eqs. 3.11-3.13) with a Coulomb limit
//! shifted by the law's adhesion. Incremental, so a change of k_t with the normal branch changes the
//! slope of the tangential response, never its value.
//!
//! Stiffness models:
//! - `Ratio`: k_t = 4 G*/E* |k_n| with k_n the normal branch stiffness (000 Eq. 22; the linear laws,
//!   004 Eq. 4.26 and 003 Sec. 3.4);
//! - `Mindlin`: k_t = 8 G* a with a the law's contact radius (Mindlin's no-slip solution, 004 Eq. 3.25,
//!   where a = sqrt(R* alpha) for Hertz; for JKR and Thornton-Ning the JKR contact radius, as the
//!   tangential models built on JKR use it, 004 Secs. 3.4.3.2-3.4.4.2);
//! - `Tomas`: k_t = 4 G* r_K with r_K = [3 R* (F_N + F_H) / (2 E*_Tomas)]^(1/3) (003 Eqs. 8-9).
//!
//! The sliding limit is mu max(N, 0) where N is the law's `sliding_normal_force` (000 Eq. 23,
//! 004 Eqs. 4.27-4.28, 3.49, 3.75, 003 Eq. 10). When sliding, the force is scaled back onto the limit
//! and no tangential damping acts (000 Sec. 2.2).

use super::NormalLaw;
use crate::numeric::cbrt;
use nalgebra::Vector3;

/// Which stiffness model a law uses (`LawInfo::TANGENTIAL`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TangentialModel {
    Ratio,
    Mindlin,
    Tomas,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialStiffness {
    Ratio { ratio: f64 },
    Mindlin { shear_modulus: f64, radius: f64 },
    Tomas { shear_modulus: f64, radius: f64, youngs_modulus: f64 },
}

impl TangentialStiffness {
    /// The stiffness of a model with these pair properties.
    pub fn for_model(model: TangentialModel, shear_modulus: f64, youngs_modulus: f64, radius: f64) -> TangentialStiffness {
        match model {
            TangentialModel::Mindlin => TangentialStiffness::Mindlin { shear_modulus, radius },
            TangentialModel::Tomas => TangentialStiffness::Tomas { shear_modulus, radius, youngs_modulus },
            TangentialModel::Ratio => TangentialStiffness::Ratio { ratio: 4.0 * shear_modulus / youngs_modulus },
        }
    }

    /// k_t [N/m] for a normal state: overlap, branch stiffness, the load F_N + F_H (Tomas) and the law's
    /// contact radius where it has one (`NormalLaw::contact_radius`).
    #[inline]
    pub fn at(&self, alpha: f64, normal_stiffness: f64, adhesive_load: f64, contact_radius: Option<f64>) -> f64 {
        match *self {
            TangentialStiffness::Ratio { ratio } => ratio * normal_stiffness.abs(),
            TangentialStiffness::Mindlin { shear_modulus, radius } => {
                8.0 * shear_modulus * contact_radius.unwrap_or_else(|| (radius * alpha.max(0.0)).sqrt())
            }
            TangentialStiffness::Tomas { shear_modulus, radius, youngs_modulus } => {
                let r_k = cbrt(3.0 * radius * adhesive_load.max(0.0) / (4.0 * youngs_modulus));
                4.0 * shear_modulus * r_k
            }
        }
    }
}

/// What the tangential spring needs of the normal state: its stiffness and the normal load of its Coulomb
/// limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringLoad {
    /// k_t [N/m].
    pub stiffness: f64,
    /// The law's sliding normal load N; the limit is mu max(N, 0) [N].
    pub sliding_normal_force: f64,
}

impl TangentialStiffness {
    /// k_t and the Coulomb load of the law `law` at overlap `alpha` [m] from the accepted history, or None
    /// out of contact (where the spring unloads). The one place the units' tangential contacts (the
    /// oblique impact, ContactElement's shear) read the normal state.
    pub fn load<L: NormalLaw>(&self, law: &L, alpha: f64, history: &L::History) -> Option<SpringLoad> {
        let (ev, _, radius) = law.evaluate_with_radius(alpha, history);
        if !ev.branch.in_contact() {
            return None;
        }
        let normal = law.sliding_normal_force(ev.force, alpha, &ev.history);
        let stiffness = self.at(alpha, ev.stiffness, normal, law.mindlin_radius(alpha, &ev.history, radius));
        Some(SpringLoad { stiffness, sliding_normal_force: normal })
    }
}

/// The tangential spring of one contact: its current force.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentialSpring {
    /// Tangential force [N].
    pub force: Vector3<f64>,
}

impl TangentialSpring {
    /// Adds a tangential displacement increment with the current stiffness (dF = -k_t d delta) and returns
    /// the force [N], projected back onto the Coulomb limit `mu max(normal, 0)`; `true` when it slides.
    #[inline]
    pub fn step(&mut self, increment: Vector3<f64>, k_t: f64, mu: f64, sliding_normal_force: f64) -> (Vector3<f64>, bool) {
        self.force -= increment * k_t;
        let limit = mu * sliding_normal_force.max(0.0);
        // Compared squared: a sticking contact (the common case in a bed at rest) needs no square root.
        let norm2 = self.force.norm_squared();
        if norm2 <= limit * limit {
            return (self.force, false);
        }
        let norm = norm2.sqrt();
        let scale = if norm > 0.0 { limit / norm } else { 0.0 };
        self.force *= scale;
        (self.force, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::ModelKind;

    #[test]
    fn spring_sticks_then_slides_at_the_coulomb_limit() {
        let mut s = TangentialSpring::default();
        let (f, sliding) = s.step(Vector3::new(1e-9, 0.0, 0.0), 1000.0, 0.5, 1e-5);
        assert!(!sliding);
        assert!((f[0] + 1e-6).abs() < 1e-18);
        let (f, sliding) = s.step(Vector3::new(1e-7, 0.0, 0.0), 1000.0, 0.5, 1e-5);
        assert!(sliding);
        assert!((f[0] + 0.5e-5).abs() < 1e-18);
        // After sliding the spring holds exactly the limit: reversing unloads elastically from there.
        let (f, sliding) = s.step(Vector3::new(-1e-9, 0.0, 0.0), 1000.0, 0.5, 1e-5);
        assert!(!sliding);
        assert!((f[0] + 0.5e-5 - 1e-6).abs() < 1e-15);
    }

    #[test]
    fn no_normal_load_means_no_tangential_force() {
        let mut s = TangentialSpring::default();
        let (f, sliding) = s.step(Vector3::new(1e-9, 1e-9, 0.0), 1000.0, 0.5, -1.0);
        assert!(sliding);
        assert_eq!(f, Vector3::zeros());
    }

    #[test]
    fn ratio_is_000_eq_22() {
        let t = TangentialStiffness::for_model(ModelKind::Nan.tangential_model(), 1.0, 2.5, 1e-6);
        assert_eq!(t.at(1e-9, -300.0, 0.0, None), 4.0 * 1.0 / 2.5 * 300.0);
    }

    #[test]
    fn a_change_of_stiffness_changes_the_slope_not_the_force() {
        let mut s = TangentialSpring::default();
        let (f1, _) = s.step(Vector3::new(1e-9, 0.0, 0.0), 1000.0, 0.5, 1.0);
        // The normal branch changes and k_t drops to a tenth: no jump, the next increment is softer.
        let (f2, _) = s.step(Vector3::new(0.0, 0.0, 0.0), 100.0, 0.5, 1.0);
        assert_eq!(f1, f2);
        let (f3, _) = s.step(Vector3::new(1e-9, 0.0, 0.0), 100.0, 0.5, 1.0);
        assert!((f3[0] - f2[0] + 1e-7).abs() < 1e-20);
    }

    #[test]
    fn mindlin_uses_the_law_contact_radius_where_given() {
        let t = TangentialStiffness::for_model(ModelKind::Jkr.tangential_model(), 2.0, 5.0, 1e-6);
        // Hertz radius sqrt(R alpha) without one; the JKR radius (nonzero at alpha <= 0) with one.
        assert_eq!(t.at(1e-10, 0.0, 0.0, None), 8.0 * 2.0 * (1e-6f64 * 1e-10).sqrt());
        assert_eq!(t.at(-1e-10, 0.0, 0.0, Some(3e-8)), 8.0 * 2.0 * 3e-8);
    }
}
