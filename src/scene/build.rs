//! The laws of a scene: the scene composes the laws' options and the material of one contact, and builds
//! from them what the laws take (their typed pair properties, `law::Effective`), the law and its damping.
//! These live here, above the laws, so that no law knows the scene (docs/architecture.md, "Layers").

use super::{Partner, Scene};
use crate::error::ParamError;
use crate::law::damping::NormalDamping;
use crate::law::params::{strain_rate_factor, yield_pressure_from_stress, Effective};
use crate::law::AnyLaw;

impl AnyLaw {
    /// Builds the scene's law with its parameters derived and checked.
    ///
    /// A Hertzian sphere against a rigid wall, evaluated at 1 um of overlap (004 Eq. 3.14):
    /// ```
    /// use powderfmu::{AnyLaw, NormalLaw, Scene};
    ///
    /// let scene = Scene::from_json(
    ///     r#"{"contact_model": "hertz", "particle_radius": 1e-3, "particle_density": 2500,
    ///         "particle_youngs_modulus": 1e9, "particle_poisson_ratio": 0.3}"#,
    /// )?;
    /// let law = AnyLaw::from_scene(&scene)?;
    /// let at = law.evaluate(1e-6, &law.initial_history());
    /// // 4/3 E* sqrt(R*) alpha^(3/2), E* = E / (1 - nu^2) against a rigid wall, R* = R.
    /// let hertz = 4.0 / 3.0 * 1e9 / (1.0 - 0.09) * 1e-3_f64.sqrt() * 1e-6_f64.powf(1.5);
    /// assert!((at.force - hertz).abs() < 1e-12 * hertz);
    /// # Ok::<(), powderfmu::ParamError>(())
    /// ```
    pub fn from_scene(s: &Scene) -> Result<AnyLaw, ParamError> {
        AnyLaw::from_pair(s.contact_model, &Effective::from_scene(s)?, &s.laws)
    }
}

impl NormalDamping {
    /// The damping of a scene: beta after yield defaults to 0.1 for nan and 1 for the other laws.
    pub fn from_scene(s: &Scene, mass: f64) -> NormalDamping {
        let default_plastic = s.contact_model.plastic_damping_factor().unwrap_or(s.damping_factor_elastic);
        NormalDamping {
            restitution: s.restitution_coefficient,
            beta_elastic: s.damping_factor_elastic,
            beta_plastic: s.damping_factor_plastic.unwrap_or(default_plastic),
            mass,
        }
    }
}

impl Effective {
    /// The effective pair properties of a scene, after validating it: R*, m*, E* and G* against a wall
    /// (rigid when it has no modulus) or an identical particle; Gamma; p_y, the smaller of the two
    /// surfaces' yield pressures (given, or from a yield stress by 000 Eq. 32 or 33), times the
    /// strain-rate factor of 000 Eq. 34 when its coefficient is positive.
    pub fn from_scene(s: &Scene) -> Result<Effective, ParamError> {
        s.validate()?;
        let (r, m) = (s.particle_radius, s.particle_mass());
        let (e1, nu1, g1) = (s.particle_youngs_modulus, s.particle_poisson_ratio, s.particle_shear_modulus());
        let (radius, mass, inv_e2, inv_g2) = match s.contact_partner {
            Partner::Wall => match s.wall_youngs_modulus {
                Some(e2) => {
                    let nu2 = s.wall_poisson_ratio;
                    let g2 = e2 / (2.0 * (1.0 + nu2));
                    (r, m, (1.0 - nu2 * nu2) / e2, (2.0 - nu2) / g2)
                }
                None => (r, m, 0.0, 0.0),
            },
            Partner::Particle => (r / 2.0, m / 2.0, (1.0 - nu1 * nu1) / e1, (2.0 - nu1) / g1),
        };
        let youngs_modulus = 1.0 / ((1.0 - nu1 * nu1) / e1 + inv_e2);
        let shear_modulus = 1.0 / ((2.0 - nu1) / g1 + inv_g2);
        let particle_py = match (s.particle_yield_pressure, s.particle_yield_stress) {
            (Some(_), Some(_)) => {
                return Err(ParamError::Inconsistent {
                    name: "particle_yield_stress",
                    why: "give particle_yield_pressure or particle_yield_stress, not both".into(),
                })
            }
            (Some(p), None) => Some(p),
            (None, Some(sigma)) => Some(yield_pressure_from_stress(sigma, nu1, s.yield_pressure_correlation)),
            (None, None) => None,
        };
        let wall_py = if s.contact_partner == Partner::Particle { particle_py } else { s.wall_yield_pressure };
        let mut yield_pressure = match (particle_py, wall_py) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        if s.yield_stress_rate_coefficient > 0.0 {
            let factor = strain_rate_factor(s.yield_stress_rate_coefficient, s.strain_rate.unwrap_or(1.0), s.reference_strain_rate.unwrap_or(1.0));
            if !(factor > 0.0) {
                return Err(ParamError::Inconsistent {
                    name: "yield_stress_rate_coefficient",
                    why: format!("1 + Y ln(V_i/V_0) = {factor:.4} must be positive (000 Eq. 34): raise strain_rate or lower the coefficient"),
                });
            }
            yield_pressure = yield_pressure.map(|p| p * factor);
        }
        Ok(Effective { radius, mass, youngs_modulus, shear_modulus, surface_energy: s.surface_energy, yield_pressure })
    }
}
