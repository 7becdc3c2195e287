//! A scene: the named parameter values of one contact. The names are the FMU variable names, the keys
//! of the scene JSON the command-line tool reads, and the names in `docs/models.md`. SI units.
//!
//! Each key is defined once, in a typed group (`scene_options!`, `vocabulary`): the common keys here, the
//! shared stiffnesses beside their correlations (`law::params::StiffnessOptions`), each law's own keys
//! beside the law (`LawInfo::Options`). `KEYS` lists them all in that order; the CLI help, the
//! unknown-key check, the FMU parameters and the docs read it.

mod build;

pub use crate::law::params::YieldCorrelation;
pub use crate::law::ModelKind;
pub use crate::vocabulary::{choice_text, given, unknown_choice, Field, Key, KeyDefault, KeyKind, NoOptions, Options, Range};

use crate::error::ParamError;
use crate::law::LawOptions;
use serde_json::{Map, Value};
use std::sync::LazyLock;

/// The names of the laws as one literal (for `concat!`).
macro_rules! model_names {
    ($d:tt; $($variant:ident, $module:ident, $ty:ty, $pl:literal;)*) => {
        $crate::join_names!($($module),*)
    };
}

crate::choice_enum! {
    /// What the particle touches.
    pub enum Partner {
        /// A flat wall of the `wall_*` properties: R* = R, m* = m; rigid without `wall_youngs_modulus`.
        Wall = "wall",
        /// An identical particle: R* = R/2, m* = m/2.
        Particle = "particle",
    }
}

crate::scene_options! {
    /// The validated inputs of one contact: the keys every scene has (the particle, the wall, damping,
    /// friction), then the laws' options. Optional values are `None` when the scene leaves them to a
    /// default that depends on other values (see `crate::law::params`).
    pub struct Scene {
        contact_model: choice(ModelKind::DEFAULT), "-", Range::Names, concat!("normal contact law: ", crate::law_table!(model_names; $));
        contact_partner: choice(Partner::Wall), "-", Range::Names, "wall (a flat of the wall_* properties) or particle (an identical particle: R* = R/2, m* = m/2)";
        particle_radius: required(), "m", Range::ClosedLow(1e-9, 1.0), "sphere radius R";
        particle_density: required(), "kg/m^3", Range::ClosedLow(1.0, 1e5), "solid density rho";
        particle_youngs_modulus: required(), "Pa", Range::ClosedLow(1e3, 1e13), "Young's modulus E of the particle";
        particle_poisson_ratio: required(), "-", Range::Open(-1.0, 0.5), "Poisson ratio nu of the particle, in (-1, 0.5)";
        particle_yield_pressure: derived("none"), "Pa", Range::Open(0.0, 1e13), "limiting contact pressure p_y of the particle (000 Sec. 3.1); or give particle_yield_stress";
        particle_yield_stress: derived("none"), "Pa", Range::Open(0.0, 1e13), "compressive yield stress sigma_y; p_y = C sigma_y by yield_pressure_correlation (000 Eqs. 32-33)";
        yield_pressure_correlation: choice(YieldCorrelation::JacksonGreen), "-", Range::Names, "jackson_green: C = 1.295 exp(0.736 nu) (000 Eq. 32); chang: p_y = (0.454 + 0.41 nu) 2.8 sigma_y (000 Eq. 33)";
        yield_stress_rate_coefficient: number(0.0), "-", Range::ClosedLow(0.0, 1e3), "Y of the strain-rate law sigma_y = sigma_y^s (1 + Y ln(V_i/V_0)) (000 Eq. 34); scales p_y";
        strain_rate: derived("none"), "1/s", Range::Open(0.0, 1e12), "characteristic strain rate V_i of the simulation (000 Eq. 34)";
        reference_strain_rate: derived("none"), "1/s", Range::Open(0.0, 1e12), "quasi-static strain rate V_0 at which the yield stress was measured (000 Eq. 34)";
        wall_youngs_modulus: derived("rigid"), "Pa", Range::ClosedLow(1e3, 1e13), "Young's modulus of the wall; omit for a rigid wall";
        wall_poisson_ratio: number(0.3), "-", Range::Open(-1.0, 0.5), "Poisson ratio of the wall, in (-1, 0.5)";
        wall_yield_pressure: derived("none"), "Pa", Range::Open(0.0, 1e13), "limiting contact pressure of the wall; p_y = min(particle, wall)";
        surface_energy: number(0.0), "J/m^2", Range::ClosedLow(0.0, 1e3), "interface energy Gamma (work of adhesion): f_ce = 1.5 pi Gamma R* (000 Eq. 5)";
        restitution_coefficient: number(1.0), "-", Range::Open(0.0, 1.0 + f64::EPSILON), "elastic restitution e_0 of the viscous damping, in (0, 1] (000 Eq. 26, 004 Eq. 4.25)";
        damping_factor_elastic: number(1.0), "-", Range::ClosedLow(0.0, 1e3), "beta of 000 Eq. 26 before yield";
        damping_factor_plastic: derived("0.1 (nan), 1 (other laws)"), "-", Range::ClosedLow(0.0, 1e3), "beta of 000 Eq. 26 after yield: 0.1 for nan (000 Sec. 2.3); the other laws' papers damp with beta = 1 throughout (004 Eq. 4.25)";
        friction_coefficient: number(0.5), "-", Range::ClosedLow(0.0, 1e3), "sliding friction mu (000 Eq. 23)";
    } nests {
        /// The shared stiffnesses, then each law's own options (`LawInfo::Options`), in table order.
        laws: LawOptions,
    }
}

/// Every scene key, in the order the help prints them: the common ones, the shared stiffnesses, then
/// each law's own in the order of the law table.
pub static KEYS: LazyLock<Vec<Key>> = LazyLock::new(|| {
    let mut keys = Vec::new();
    Scene::keys(&mut keys);
    keys
});

impl Scene {
    /// A scene with the required particle values and every other key at its default.
    pub fn new(model: ModelKind, radius: f64, density: f64, youngs_modulus: f64, poisson_ratio: f64) -> Scene {
        Scene {
            contact_model: model,
            particle_radius: radius,
            particle_density: density,
            particle_youngs_modulus: youngs_modulus,
            particle_poisson_ratio: poisson_ratio,
            ..Scene::defaults()
        }
    }

    /// Reads a scene from JSON text: an object whose keys are in `KEYS`.
    pub fn from_json(text: &str) -> Result<Scene, ParamError> {
        let value: Value = serde_json::from_str(text).map_err(|e| ParamError::Malformed { what: format!("not valid JSON: {e}") })?;
        let map = value.as_object().ok_or_else(|| ParamError::Malformed { what: "the top level must be a JSON object of parameter names".into() })?;
        Scene::from_map(map)
    }

    /// Reads a scene from a JSON object.
    pub fn from_map(map: &Map<String, Value>) -> Result<Scene, ParamError> {
        for k in map.keys() {
            if !KEYS.iter().any(|key| key.name == k) {
                return Err(ParamError::UnknownKey { name: k.clone(), hint: nearest_key_hint(k) });
            }
        }
        for key in KEYS.iter().filter(|k| k.kind() == KeyKind::Required) {
            if given(map, key.name).is_none() {
                return Err(ParamError::Missing {
                    name: key.name,
                    why: "every scene gives the particle's radius, density, Young's modulus and Poisson ratio".into(),
                });
            }
        }
        let mut s = Scene::defaults();
        s.read(map)?;
        if s.contact_partner == Partner::Particle {
            for name in ["wall_youngs_modulus", "wall_poisson_ratio", "wall_yield_pressure"] {
                if map.contains_key(name) {
                    return Err(ParamError::Inconsistent {
                        name: KEYS.iter().find(|k| k.name == name).map(|k| k.name).unwrap_or("contact_partner"),
                        why: "given, but contact_partner is particle (an identical particle); remove it or set contact_partner to wall".into(),
                    });
                }
            }
        }
        s.validate()?;
        Ok(s)
    }

    /// Every value in its key's range, and the checks across keys. Cross-checks that need derived values
    /// live in `law::params` and in each law's constructor.
    pub fn validate(&self) -> Result<(), ParamError> {
        // The ranges are physical, wide enough for every powder and every wall, narrow enough that no
        // value makes the dynamics degenerate (a mass of 1e-130 kg oscillates 1e60 times in a nanosecond).
        self.check()?;
        let stiffness = &self.laws.stiffness;
        if stiffness.unloading_stiffness_reference.is_some() != stiffness.unloading_overlap_reference.is_some() {
            return Err(ParamError::Inconsistent {
                name: "unloading_stiffness_reference",
                why: "give both unloading_stiffness_reference (k_e0) and unloading_overlap_reference (alpha_max0), or neither".into(),
            });
        }
        if stiffness.unloading_stiffness_reference.is_some() && stiffness.elastic_stiffness.is_some() {
            return Err(ParamError::Inconsistent {
                name: "elastic_stiffness",
                why: "give either elastic_stiffness or the measured unloading line (unloading_stiffness_reference, unloading_overlap_reference), not both".into(),
            });
        }
        if self.yield_stress_rate_coefficient > 0.0 && (self.strain_rate.is_none() || self.reference_strain_rate.is_none()) {
            return Err(ParamError::Missing {
                name: "strain_rate",
                why: "yield_stress_rate_coefficient > 0 needs strain_rate and reference_strain_rate (000 Eq. 34)".into(),
            });
        }
        Ok(())
    }

    /// The particle's shear modulus G = E / (2 (1 + nu)) [Pa].
    pub fn particle_shear_modulus(&self) -> f64 {
        self.particle_youngs_modulus / (2.0 * (1.0 + self.particle_poisson_ratio))
    }

    /// The particle's mass m = 4/3 pi R^3 rho [kg].
    pub fn particle_mass(&self) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * self.particle_radius.powi(3) * self.particle_density
    }
}

/// " (did you mean `x`?)" for the closest known key, or where to find the keys.
fn nearest_key_hint(unknown: &str) -> String {
    crate::vocabulary::nearest_name(unknown, KEYS.iter().map(|k| k.name))
        .map(|name| format!(" (did you mean `{name}`?)"))
        .unwrap_or_else(|| "; run `powderfmu analyze --help` for the list of keys".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    const REQUIRED: &str = r#""particle_radius":1e-6,"particle_density":1000,"particle_youngs_modulus":1e9,"particle_poisson_ratio":0.3"#;

    #[test]
    fn keys_are_unique() {
        let mut names: Vec<_> = KEYS.iter().map(|k| k.name).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), KEYS.len());
    }

    #[test]
    fn each_default_lies_in_its_range() {
        for k in KEYS.iter() {
            match k.default {
                KeyDefault::Number(x) => assert!(k.check(x).is_ok(), "{}: default {x} is outside its range", k.name),
                KeyDefault::Choice { default, allowed } => {
                    assert!(allowed.contains(&default), "{}: default {default} is not one of {allowed:?}", k.name);
                    assert_eq!(k.range, Range::Names, "{}", k.name);
                }
                KeyDefault::Required | KeyDefault::Derived(_) => assert_ne!(k.range, Range::Names, "{}", k.name),
            }
        }
    }

    #[test]
    fn every_key_reaches_its_field() {
        let default = Scene::from_json(&format!("{{{REQUIRED}}}")).unwrap();
        // A value each key accepts that differs from its default (choices: a second option).
        let value = |key: &Key| -> String {
            match key.name {
                "contact_model" => r#""hertz""#.into(),
                "contact_partner" => r#""particle""#.into(),
                "yield_pressure_correlation" => r#""chang""#.into(),
                "unloading_stiffness_law" => r#""sqrt_plus_plastic""#.into(),
                "pull_off_law" => r#""curvature""#.into(),
                "adhesive_stiffness_law" => r#""approximate""#.into(),
                "pasha_stiffness_law" => r#""load_dependent""#.into(),
                "jkr_detachment" => r#""force""#.into(),
                "jkr_friction_limit" => r#""repulsive""#.into(),
                "jkr_stiffness_radius" => r#""hertz""#.into(),
                "luding_variant" => r#""mercurydpm""#.into(),
                "particle_poisson_ratio" | "wall_poisson_ratio" => "0.25".into(),
                "restitution_coefficient" | "tomas_area_coefficient" => "0.9".into(),
                "tomas_repulsion_coefficient" => "0.2".into(),
                "luding_plasticity_depth" => "0.1".into(),
                "tomas_separation" => "5e-10".into(),
                _ => match key.unit {
                    "Pa" => "1e8",
                    "N/m" => "100",
                    "m" => "1e-9",
                    "N" => "1e-6",
                    _ => "0.45",
                }
                .into(),
            }
        };
        for key in KEYS.iter().filter(|k| !REQUIRED.contains(&format!("\"{}\"", k.name))) {
            let mut extra = format!(r#","{}":{}"#, key.name, value(key));
            match key.name {
                "unloading_stiffness_reference" => extra += r#","unloading_overlap_reference":1e-9"#,
                "unloading_overlap_reference" => extra += r#","unloading_stiffness_reference":100"#,
                "yield_stress_rate_coefficient" => extra = r#","yield_stress_rate_coefficient":0.5,"strain_rate":1,"reference_strain_rate":1"#.into(),
                _ => {}
            }
            let scene = Scene::from_json(&format!("{{{REQUIRED}{extra}}}")).unwrap_or_else(|e| panic!("{}: {e}", key.name));
            assert_ne!(scene, default, "key `{}` changed nothing in the scene", key.name);
        }
    }

    #[test]
    fn unknown_key_suggests_the_nearest() {
        let err = Scene::from_json(
            r#"{"particle_radius":1e-6,"particle_density":1000,"particle_youngs_modulus":1e9,"particle_poisson_ratio":0.3,"surface_enrgy":0.1}"#,
        )
        .unwrap_err();
        assert!(err.to_string().contains("did you mean `surface_energy`"), "{err}");
    }
}
