//! Viscous normal and tangential damping (`000` Eqs. 24-26, `004` Eq. 4.25).
//!
//! f_nd = 2 gamma sqrt(m* k_n) V_n with gamma = -beta ln e_0 / sqrt(pi^2 + ln^2 e_0). For the Nan law
//! beta = 1 before yield and a smaller beta (default 0.1) after yield (000 Sec. 2.3). 004 Eq. 4.25 is the
//! same with beta = 1 throughout, and that is the default of every other law (Pasha's and Luding's
//! contacts count as yielded from first contact, so a 0.1 would all but switch their damping off).
//! k_n is the law's damping stiffness (`NormalLaw::damping_stiffness`): the branch stiffness, its
//! magnitude on the adhesive branches (000 Sec. 2.2 names k_c there), and 2 E* a for the JKR curves.

/// gamma of 000 Eq. 26.
pub fn gamma(restitution: f64, beta: f64) -> f64 {
    if restitution >= 1.0 {
        return 0.0;
    }
    let l = restitution.ln();
    -beta * l / (PI2 + l * l).sqrt()
}

const PI2: f64 = std::f64::consts::PI * std::f64::consts::PI;

/// The damping coefficient 2 gamma sqrt(m* |k_n|) [N s/m] (000 Eqs. 24-25).
pub fn coefficient(restitution: f64, beta: f64, mass: f64, stiffness: f64) -> f64 {
    2.0 * gamma(restitution, beta) * (mass * stiffness.abs()).sqrt()
}

/// 004 Eq. 4.25: beta_v = sqrt(4 ln^2(e) m* k_n / (ln^2(e) + pi^2)).
pub fn coefficient_pasha(restitution: f64, mass: f64, stiffness: f64) -> f64 {
    let l2 = restitution.ln().powi(2);
    (4.0 * l2 * mass * stiffness.abs() / (l2 + PI2)).sqrt()
}

/// The normal damping of one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalDamping {
    /// Restitution coefficient e_0 of 000 Eq. 26 (1 or more: no damping) [-].
    pub restitution: f64,
    /// Damping factor beta of 000 Eq. 26 before yield [-].
    pub beta_elastic: f64,
    /// Damping factor beta of 000 Eq. 26 after yield (`NormalLaw::has_yielded`) [-].
    pub beta_plastic: f64,
    /// m* [kg].
    pub mass: f64,
}

impl NormalDamping {
    /// Damping force [N], positive repulsive, for an approach rate d alpha/dt [m/s].
    pub fn force(&self, stiffness: f64, yielded: bool, approach_rate: f64) -> f64 {
        self.coefficient(stiffness, yielded) * approach_rate
    }

    /// The damping coefficient of a branch of stiffness `stiffness` [N s/m].
    pub fn coefficient(&self, stiffness: f64, yielded: bool) -> f64 {
        let beta = if yielded { self.beta_plastic } else { self.beta_elastic };
        coefficient(self.restitution, beta, self.mass, stiffness)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{ModelKind, Scene};

    #[test]
    fn plastic_beta_defaults_to_0_1_for_nan_only() {
        let mut s = Scene::new(ModelKind::Nan, 1e-6, 1000.0, 1e9, 0.3);
        assert_eq!(NormalDamping::from_scene(&s, 1.0).beta_plastic, 0.1);
        s.contact_model = ModelKind::Pasha;
        assert_eq!(NormalDamping::from_scene(&s, 1.0).beta_plastic, 1.0);
        s.damping_factor_plastic = Some(0.3);
        assert_eq!(NormalDamping::from_scene(&s, 1.0).beta_plastic, 0.3);
    }

    #[test]
    fn pasha_eq_4_25_is_nan_eq_24_with_beta_one() {
        for e in [0.1, 0.5, 0.93] {
            let a = coefficient(e, 1.0, 2e-12, 300.0);
            let b = coefficient_pasha(e, 2e-12, 300.0);
            assert!((a / b - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn linear_oscillator_with_this_damping_restitutes_e0() {
        // Damped linear spring: e = exp(-zeta pi / sqrt(1 - zeta^2)) with zeta = gamma (000 Eq. 26).
        for e0 in [0.3, 0.81, 0.95] {
            let z = gamma(e0, 1.0);
            let e = (-z * std::f64::consts::PI / (1.0 - z * z).sqrt()).exp();
            assert!((e - e0).abs() < 1e-12, "{e} vs {e0}");
        }
    }
}
