//! A scene: the named parameter values of one contact. The names are the FMU variable names, the keys
//! of the scene JSON the command-line tool reads, and the names in `docs/models.md`. SI units.
//!
//! `KEYS` is the one table of every key: its unit, default and meaning. The CLI help, the unknown-key
//! check and the docs all read it.

use crate::error::{check_closed_low, check_open, ParamError};
use serde_json::{Map, Value};
use std::sync::LazyLock;

/// The names of the laws as one literal (for `concat!`).
macro_rules! model_names {
    ($d:tt; $($variant:ident, $name:literal, $ty:ty, $pl:literal;)*) => {
        $crate::join_names!($($name),*)
    };
}

/// What kind of value a key takes, and so how it reaches an FMU (`units::scene_params`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyKind {
    /// One of a set of names (a String parameter).
    Choice,
    /// A number every scene must give.
    Required,
    /// A number with a fixed default (`default` is that number).
    Number,
    /// A number whose default is derived from other keys (an FMU's Real parameter uses 0 for "derive").
    Derived,
}

/// One scene key: name, unit, kind, default (as text) and what it means (with its seed reference).
#[derive(Debug, Clone, Copy)]
pub struct Key {
    pub name: &'static str,
    pub unit: &'static str,
    pub kind: KeyKind,
    /// The default as the help prints it (a number, a name, or how it is derived).
    pub default: &'static str,
    pub doc: &'static str,
}

/// The keys every scene has: the particle, the wall, damping, friction and the stiffnesses the laws share.
const COMMON_KEYS: &[Key] = &[
    Key { name: "contact_model", unit: "-", kind: KeyKind::Choice, default: "nan", doc: concat!("normal contact law: ", crate::law_table!(model_names; $)) },
    Key { name: "contact_partner", unit: "-", kind: KeyKind::Choice, default: "wall", doc: "wall (a flat of the wall_* properties) or particle (an identical particle: R* = R/2, m* = m/2)" },
    Key { name: "particle_radius", unit: "m", kind: KeyKind::Required, default: "required", doc: "sphere radius R" },
    Key { name: "particle_density", unit: "kg/m^3", kind: KeyKind::Required, default: "required", doc: "solid density rho" },
    Key { name: "particle_youngs_modulus", unit: "Pa", kind: KeyKind::Required, default: "required", doc: "Young's modulus E of the particle" },
    Key { name: "particle_poisson_ratio", unit: "-", kind: KeyKind::Required, default: "required", doc: "Poisson ratio nu of the particle, in (-1, 0.5)" },
    Key { name: "particle_yield_pressure", unit: "Pa", kind: KeyKind::Derived, default: "none", doc: "limiting contact pressure p_y of the particle (000 Sec. 3.1); or give particle_yield_stress" },
    Key { name: "particle_yield_stress", unit: "Pa", kind: KeyKind::Derived, default: "none", doc: "compressive yield stress sigma_y; p_y = C sigma_y by yield_pressure_correlation (000 Eqs. 32-33)" },
    Key { name: "yield_pressure_correlation", unit: "-", kind: KeyKind::Choice, default: "jackson_green", doc: "jackson_green: C = 1.295 exp(0.736 nu) (000 Eq. 32); chang: p_y = (0.454 + 0.41 nu) 2.8 sigma_y (000 Eq. 33)" },
    Key { name: "yield_stress_rate_coefficient", unit: "-", kind: KeyKind::Number, default: "0", doc: "Y of the strain-rate law sigma_y = sigma_y^s (1 + Y ln(V_i/V_0)) (000 Eq. 34); scales p_y" },
    Key { name: "strain_rate", unit: "1/s", kind: KeyKind::Derived, default: "none", doc: "characteristic strain rate V_i of the simulation (000 Eq. 34)" },
    Key { name: "reference_strain_rate", unit: "1/s", kind: KeyKind::Derived, default: "none", doc: "quasi-static strain rate V_0 at which the yield stress was measured (000 Eq. 34)" },
    Key { name: "wall_youngs_modulus", unit: "Pa", kind: KeyKind::Derived, default: "rigid", doc: "Young's modulus of the wall; omit for a rigid wall" },
    Key { name: "wall_poisson_ratio", unit: "-", kind: KeyKind::Number, default: "0.3", doc: "Poisson ratio of the wall, in (-1, 0.5)" },
    Key { name: "wall_yield_pressure", unit: "Pa", kind: KeyKind::Derived, default: "none", doc: "limiting contact pressure of the wall; p_y = min(particle, wall)" },
    Key { name: "surface_energy", unit: "J/m^2", kind: KeyKind::Number, default: "0", doc: "interface energy Gamma (work of adhesion): f_ce = 1.5 pi Gamma R* (000 Eq. 5)" },
    Key { name: "restitution_coefficient", unit: "-", kind: KeyKind::Number, default: "1", doc: "elastic restitution e_0 of the viscous damping, in (0, 1] (000 Eq. 26, 004 Eq. 4.25)" },
    Key { name: "damping_factor_elastic", unit: "-", kind: KeyKind::Number, default: "1", doc: "beta of 000 Eq. 26 before yield" },
    Key { name: "damping_factor_plastic", unit: "-", kind: KeyKind::Derived, default: "0.1 (nan), 1 (other laws)", doc: "beta of 000 Eq. 26 after yield: 0.1 for nan (000 Sec. 2.3); the other laws' papers damp with beta = 1 throughout (004 Eq. 4.25)" },
    Key { name: "friction_coefficient", unit: "-", kind: KeyKind::Number, default: "0.5", doc: "sliding friction mu (000 Eq. 23)" },
    Key { name: "elastic_stiffness", unit: "N/m", kind: KeyKind::Derived, default: "pi R* p_y", doc: "k_el, elastic stiffness before yield (nan); constant k_e (pasha, pasha_simplified); unloading k_e (walton_braun). Default 000 Eq. 52" },
    Key { name: "unloading_stiffness_reference", unit: "N/m", kind: KeyKind::Derived, default: "none", doc: "k_e0 of a measured unloading line; with unloading_overlap_reference gives k_el by 000 Eqs. 45 and 29 (or 49)" },
    Key { name: "unloading_overlap_reference", unit: "m", kind: KeyKind::Derived, default: "none", doc: "alpha_max0, the overlap at which the measured unloading line with k_e0 starts (000 Eq. 43)" },
    Key { name: "plastic_stiffness", unit: "N/m", kind: KeyKind::Derived, default: "elastic_stiffness", doc: "k_p, plastic loading stiffness (000 Eq. 18, 004 Eq. 4.3); must not exceed k_el" },
];

/// Defines `ModelKind` from the rows of `law_table!`.
macro_rules! define_model_kind {
    ($d:tt; $($variant:ident, $name:literal, $ty:ty, $pl:literal;)*) => {
        /// The normal contact laws a scene can name: the rows of `law_table!` (`src/law/table.rs`), in its
        /// order.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum ModelKind {
            $($variant,)*
        }

        impl ModelKind {
            /// Every law, in the table's order.
            pub const ALL: [ModelKind; [$($name),*].len()] = [$(ModelKind::$variant),*];

            /// The scene name (`contact_model`).
            pub fn name(self) -> &'static str {
                match self {
                    $(ModelKind::$variant => $name,)*
                }
            }

            /// Whether every branch is a straight line for a fixed history (the laws the `exact`
            /// integrator solves in closed form).
            pub fn is_piecewise_linear(self) -> bool {
                match self {
                    $(ModelKind::$variant => $pl,)*
                }
            }
        }
    };
}

crate::law_table!(define_model_kind; $);

impl ModelKind {
    /// The default law: the first line of the table.
    pub const DEFAULT: ModelKind = ModelKind::ALL[0];

    /// The scene names of the piecewise-linear laws, comma-separated.
    pub fn piecewise_linear_names() -> String {
        ModelKind::ALL.iter().filter(|m| m.is_piecewise_linear()).map(|m| m.name()).collect::<Vec<_>>().join(", ")
    }

    pub fn parse(s: &str) -> Result<ModelKind, ParamError> {
        ModelKind::ALL.iter().copied().find(|m| m.name() == s).ok_or_else(|| ParamError::UnknownChoice {
            name: "contact_model".into(),
            value: s.into(),
            allowed: ModelKind::ALL.iter().map(|m| m.name()).collect::<Vec<_>>().join(", "),
        })
    }
}

/// Every scene key, in the order the help prints them: the common ones, then each law's own
/// (`LawInfo::KEYS`, declared beside the law) in the order of the law table.
pub static KEYS: LazyLock<Vec<Key>> = LazyLock::new(|| {
    let mut keys = COMMON_KEYS.to_vec();
    keys.extend(ModelKind::ALL.iter().flat_map(|m| m.own_keys().iter().copied()));
    keys
});

/// What the particle touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Partner {
    Wall,
    Particle,
}

/// Correlation from yield stress to limiting contact pressure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum YieldCorrelation {
    /// 000 Eq. 32: p_y = 1.295 exp(0.736 nu) sigma_y.
    JacksonGreen,
    /// 000 Eq. 33: p_y = (0.454 + 0.41 nu) 2.8 sigma_y.
    Chang,
}

/// How k_e grows after yield in the Nan law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnloadingStiffnessLaw {
    /// 000 Eqs. 42-46.
    Sqrt,
    /// 000 Eqs. 47-49.
    SqrtPlusPlastic,
}

/// How the maximum pull-off force grows after yield in the Nan law (000 Table 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PullOffLaw {
    /// 000 Eq. 59.
    Energy,
    /// 000 Eq. 61.
    Pasha,
    /// 000 Eq. 64.
    Curvature,
    /// 000 Eq. 67.
    WorkRatio,
}

/// Which form of the k_cl correlation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdhesiveStiffnessLaw {
    /// 000 Eq. 36 with Eq. 37.
    Exact,
    /// 000 Eq. 38.
    Approximate,
}

/// Constant or load-dependent unloading stiffness in the Pasha laws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PashaStiffnessLaw {
    Constant,
    /// 004 Eq. 4.23.
    LoadDependent,
}

/// The validated inputs of one contact. Optional values are `None` when the scene leaves them to
/// a default that depends on other values (see `crate::law::params`).
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub contact_model: ModelKind,
    pub contact_partner: Partner,
    pub particle_radius: f64,
    pub particle_density: f64,
    pub particle_youngs_modulus: f64,
    pub particle_poisson_ratio: f64,
    pub particle_yield_pressure: Option<f64>,
    pub particle_yield_stress: Option<f64>,
    pub yield_pressure_correlation: YieldCorrelation,
    pub yield_stress_rate_coefficient: f64,
    pub strain_rate: Option<f64>,
    pub reference_strain_rate: Option<f64>,
    pub wall_youngs_modulus: Option<f64>,
    pub wall_poisson_ratio: f64,
    pub wall_yield_pressure: Option<f64>,
    pub surface_energy: f64,
    pub restitution_coefficient: f64,
    pub damping_factor_elastic: f64,
    pub damping_factor_plastic: Option<f64>,
    pub friction_coefficient: f64,
    pub elastic_stiffness: Option<f64>,
    pub unloading_stiffness_reference: Option<f64>,
    pub unloading_overlap_reference: Option<f64>,
    pub plastic_stiffness: Option<f64>,
    pub unloading_stiffness_law: UnloadingStiffnessLaw,
    pub pull_off_law: PullOffLaw,
    pub adhesive_stiffness_law: AdhesiveStiffnessLaw,
    pub pasha_stiffness_law: PashaStiffnessLaw,
    pub pasha_max_elastic_stiffness: Option<f64>,
    pub pasha_pull_off_stiffness: f64,
    pub pasha_pull_off_intercept: Option<f64>,
    pub luding_loading_stiffness: Option<f64>,
    pub luding_max_unloading_stiffness: Option<f64>,
    pub luding_adhesion_stiffness: f64,
    pub luding_plasticity_depth: f64,
    pub luding_contact_adhesion_force: Option<f64>,
    pub tomas_yield_strength: Option<f64>,
    pub tomas_area_coefficient: f64,
    pub tomas_repulsion_coefficient: f64,
    pub tomas_contact_adhesion_force: Option<f64>,
    pub tomas_separation: f64,
    pub linear_stiffness: Option<f64>,
    pub walton_braun_stiffening_slope: f64,
}

impl Scene {
    /// A scene with the required particle values and every other key at its default.
    pub fn new(model: ModelKind, radius: f64, density: f64, youngs_modulus: f64, poisson_ratio: f64) -> Scene {
        Scene {
            contact_model: model,
            contact_partner: Partner::Wall,
            particle_radius: radius,
            particle_density: density,
            particle_youngs_modulus: youngs_modulus,
            particle_poisson_ratio: poisson_ratio,
            particle_yield_pressure: None,
            particle_yield_stress: None,
            yield_pressure_correlation: YieldCorrelation::JacksonGreen,
            yield_stress_rate_coefficient: 0.0,
            strain_rate: None,
            reference_strain_rate: None,
            wall_youngs_modulus: None,
            wall_poisson_ratio: 0.3,
            wall_yield_pressure: None,
            surface_energy: 0.0,
            restitution_coefficient: 1.0,
            damping_factor_elastic: 1.0,
            damping_factor_plastic: None,
            friction_coefficient: 0.5,
            elastic_stiffness: None,
            unloading_stiffness_reference: None,
            unloading_overlap_reference: None,
            plastic_stiffness: None,
            unloading_stiffness_law: UnloadingStiffnessLaw::Sqrt,
            pull_off_law: PullOffLaw::Energy,
            adhesive_stiffness_law: AdhesiveStiffnessLaw::Exact,
            pasha_stiffness_law: PashaStiffnessLaw::Constant,
            pasha_max_elastic_stiffness: None,
            pasha_pull_off_stiffness: 0.0,
            pasha_pull_off_intercept: None,
            luding_loading_stiffness: None,
            luding_max_unloading_stiffness: None,
            luding_adhesion_stiffness: 0.0,
            luding_plasticity_depth: 0.05,
            luding_contact_adhesion_force: None,
            tomas_yield_strength: None,
            tomas_area_coefficient: 0.834,
            tomas_repulsion_coefficient: 0.152,
            tomas_contact_adhesion_force: None,
            tomas_separation: 4e-10,
            linear_stiffness: None,
            walton_braun_stiffening_slope: 0.0,
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
        let num = |name: &'static str| -> Result<Option<f64>, ParamError> {
            match map.get(name) {
                None | Some(Value::Null) => Ok(None),
                Some(Value::Number(n)) => Ok(n.as_f64()),
                Some(other) => Err(ParamError::Malformed { what: format!("`{name}` must be a number, got {other}") }),
            }
        };
        let text = |name: &'static str| -> Result<Option<String>, ParamError> {
            match map.get(name) {
                None | Some(Value::Null) => Ok(None),
                Some(Value::String(s)) => Ok(Some(s.clone())),
                Some(other) => Err(ParamError::Malformed { what: format!("`{name}` must be a string, got {other}") }),
            }
        };
        let required = |name: &'static str| -> Result<f64, ParamError> {
            num(name)?.ok_or_else(|| ParamError::Missing {
                name,
                why: "every scene gives the particle's radius, density, Young's modulus and Poisson ratio".into(),
            })
        };
        let model = match text("contact_model")? {
            Some(s) => ModelKind::parse(&s)?,
            None => ModelKind::DEFAULT,
        };
        let mut s = Scene::new(
            model,
            required("particle_radius")?,
            required("particle_density")?,
            required("particle_youngs_modulus")?,
            required("particle_poisson_ratio")?,
        );
        if let Some(p) = text("contact_partner")? {
            s.contact_partner = choice("contact_partner", &p, &[("wall", Partner::Wall), ("particle", Partner::Particle)])?;
        }
        if let Some(c) = text("yield_pressure_correlation")? {
            s.yield_pressure_correlation =
                choice("yield_pressure_correlation", &c, &[("jackson_green", YieldCorrelation::JacksonGreen), ("chang", YieldCorrelation::Chang)])?;
        }
        if let Some(c) = text("unloading_stiffness_law")? {
            s.unloading_stiffness_law = choice(
                "unloading_stiffness_law",
                &c,
                &[("sqrt", UnloadingStiffnessLaw::Sqrt), ("sqrt_plus_plastic", UnloadingStiffnessLaw::SqrtPlusPlastic)],
            )?;
        }
        if let Some(c) = text("pull_off_law")? {
            s.pull_off_law = choice(
                "pull_off_law",
                &c,
                &[
                    ("energy", PullOffLaw::Energy),
                    ("pasha", PullOffLaw::Pasha),
                    ("curvature", PullOffLaw::Curvature),
                    ("work_ratio", PullOffLaw::WorkRatio),
                ],
            )?;
        }
        if let Some(c) = text("adhesive_stiffness_law")? {
            s.adhesive_stiffness_law =
                choice("adhesive_stiffness_law", &c, &[("exact", AdhesiveStiffnessLaw::Exact), ("approximate", AdhesiveStiffnessLaw::Approximate)])?;
        }
        if let Some(c) = text("pasha_stiffness_law")? {
            s.pasha_stiffness_law = choice(
                "pasha_stiffness_law",
                &c,
                &[("constant", PashaStiffnessLaw::Constant), ("load_dependent", PashaStiffnessLaw::LoadDependent)],
            )?;
        }
        s.particle_yield_pressure = num("particle_yield_pressure")?;
        s.particle_yield_stress = num("particle_yield_stress")?;
        if let Some(v) = num("yield_stress_rate_coefficient")? {
            s.yield_stress_rate_coefficient = v;
        }
        s.strain_rate = num("strain_rate")?;
        s.reference_strain_rate = num("reference_strain_rate")?;
        s.wall_youngs_modulus = num("wall_youngs_modulus")?;
        if let Some(v) = num("wall_poisson_ratio")? {
            s.wall_poisson_ratio = v;
        }
        s.wall_yield_pressure = num("wall_yield_pressure")?;
        let set = |slot: &mut f64, name: &'static str| -> Result<(), ParamError> {
            if let Some(v) = num(name)? {
                *slot = v;
            }
            Ok(())
        };
        set(&mut s.surface_energy, "surface_energy")?;
        set(&mut s.restitution_coefficient, "restitution_coefficient")?;
        set(&mut s.damping_factor_elastic, "damping_factor_elastic")?;
        s.damping_factor_plastic = num("damping_factor_plastic")?;
        set(&mut s.friction_coefficient, "friction_coefficient")?;
        s.elastic_stiffness = num("elastic_stiffness")?;
        s.unloading_stiffness_reference = num("unloading_stiffness_reference")?;
        s.unloading_overlap_reference = num("unloading_overlap_reference")?;
        s.plastic_stiffness = num("plastic_stiffness")?;
        s.pasha_max_elastic_stiffness = num("pasha_max_elastic_stiffness")?;
        set(&mut s.pasha_pull_off_stiffness, "pasha_pull_off_stiffness")?;
        s.pasha_pull_off_intercept = num("pasha_pull_off_intercept")?;
        s.luding_loading_stiffness = num("luding_loading_stiffness")?;
        s.luding_max_unloading_stiffness = num("luding_max_unloading_stiffness")?;
        set(&mut s.luding_adhesion_stiffness, "luding_adhesion_stiffness")?;
        set(&mut s.luding_plasticity_depth, "luding_plasticity_depth")?;
        s.luding_contact_adhesion_force = num("luding_contact_adhesion_force")?;
        s.tomas_yield_strength = num("tomas_yield_strength")?;
        set(&mut s.tomas_area_coefficient, "tomas_area_coefficient")?;
        set(&mut s.tomas_repulsion_coefficient, "tomas_repulsion_coefficient")?;
        s.tomas_contact_adhesion_force = num("tomas_contact_adhesion_force")?;
        set(&mut s.tomas_separation, "tomas_separation")?;
        s.linear_stiffness = num("linear_stiffness")?;
        set(&mut s.walton_braun_stiffening_slope, "walton_braun_stiffening_slope")?;
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

    /// Range checks on every value given. Cross-checks that need derived values live in `law::params`.
    pub fn validate(&self) -> Result<(), ParamError> {
        // Physical ranges, wide enough for every powder and every wall, narrow enough that no value
        // makes the dynamics degenerate (a mass of 1e-130 kg oscillates 1e60 times in a nanosecond).
        check_closed_low("particle_radius", self.particle_radius, 1e-9, 1.0, "m")?;
        check_closed_low("particle_density", self.particle_density, 1.0, 1e5, "kg/m^3")?;
        check_closed_low("particle_youngs_modulus", self.particle_youngs_modulus, 1e3, 1e13, "Pa")?;
        check_open("particle_poisson_ratio", self.particle_poisson_ratio, -1.0, 0.5, "")?;
        opt_below("particle_yield_pressure", self.particle_yield_pressure, 1e13, "Pa")?;
        opt_below("particle_yield_stress", self.particle_yield_stress, 1e13, "Pa")?;
        check_closed_low("yield_stress_rate_coefficient", self.yield_stress_rate_coefficient, 0.0, 1e3, "")?;
        opt_below("strain_rate", self.strain_rate, 1e12, "1/s")?;
        opt_below("reference_strain_rate", self.reference_strain_rate, 1e12, "1/s")?;
        if let Some(v) = self.wall_youngs_modulus {
            check_closed_low("wall_youngs_modulus", v, 1e3, 1e13, "Pa")?;
        }
        check_open("wall_poisson_ratio", self.wall_poisson_ratio, -1.0, 0.5, "")?;
        opt_below("wall_yield_pressure", self.wall_yield_pressure, 1e13, "Pa")?;
        check_closed_low("surface_energy", self.surface_energy, 0.0, 1e3, "J/m^2")?;
        check_open("restitution_coefficient", self.restitution_coefficient, 0.0, 1.0 + f64::EPSILON, "")?;
        check_closed_low("damping_factor_elastic", self.damping_factor_elastic, 0.0, 1e3, "")?;
        if let Some(v) = self.damping_factor_plastic {
            check_closed_low("damping_factor_plastic", v, 0.0, 1e3, "")?;
        }
        check_closed_low("friction_coefficient", self.friction_coefficient, 0.0, 1e3, "")?;
        opt_below("elastic_stiffness", self.elastic_stiffness, 1e12, "N/m")?;
        opt_below("unloading_stiffness_reference", self.unloading_stiffness_reference, 1e12, "N/m")?;
        opt_below("unloading_overlap_reference", self.unloading_overlap_reference, 1.0, "m")?;
        opt_below("plastic_stiffness", self.plastic_stiffness, 1e12, "N/m")?;
        opt_below("pasha_max_elastic_stiffness", self.pasha_max_elastic_stiffness, 1e12, "N/m")?;
        check_closed_low("pasha_pull_off_stiffness", self.pasha_pull_off_stiffness, 0.0, 1e12, "N/m")?;
        if let Some(v) = self.pasha_pull_off_intercept {
            check_closed_low("pasha_pull_off_intercept", v, 0.0, 1e6, "N")?;
        }
        opt_below("luding_loading_stiffness", self.luding_loading_stiffness, 1e12, "N/m")?;
        opt_below("luding_max_unloading_stiffness", self.luding_max_unloading_stiffness, 1e12, "N/m")?;
        check_closed_low("luding_adhesion_stiffness", self.luding_adhesion_stiffness, 0.0, 1e12, "N/m")?;
        check_open("luding_plasticity_depth", self.luding_plasticity_depth, 0.0, 0.5, "")?;
        if let Some(v) = self.luding_contact_adhesion_force {
            check_closed_low("luding_contact_adhesion_force", v, 0.0, 1e6, "N")?;
        }
        opt_below("tomas_yield_strength", self.tomas_yield_strength, 1e13, "Pa")?;
        check_closed_low("tomas_area_coefficient", self.tomas_area_coefficient, 2.0 / 3.0, 1.0 + f64::EPSILON, "")?;
        check_closed_low(
            "tomas_repulsion_coefficient",
            self.tomas_repulsion_coefficient,
            0.0,
            self.tomas_area_coefficient,
            "(below tomas_area_coefficient)",
        )?;
        if let Some(v) = self.tomas_contact_adhesion_force {
            check_closed_low("tomas_contact_adhesion_force", v, 0.0, 1e6, "N")?;
        }
        check_open("tomas_separation", self.tomas_separation, 0.0, 1.0, "m")?;
        opt_below("linear_stiffness", self.linear_stiffness, 1e12, "N/m")?;
        check_closed_low("walton_braun_stiffening_slope", self.walton_braun_stiffening_slope, 0.0, 1e12, "1/m")?;
        if self.unloading_stiffness_reference.is_some() != self.unloading_overlap_reference.is_some() {
            return Err(ParamError::Inconsistent {
                name: "unloading_stiffness_reference",
                why: "give both unloading_stiffness_reference (k_e0) and unloading_overlap_reference (alpha_max0), or neither".into(),
            });
        }
        if self.unloading_stiffness_reference.is_some() && self.elastic_stiffness.is_some() {
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
}

/// An optional value in (0, max): positive, and below where the dynamics would degenerate.
fn opt_below(name: &'static str, v: Option<f64>, max: f64, unit: &str) -> Result<(), ParamError> {
    match v {
        Some(x) => check_open(name, x, 0.0, max, unit).map(|_| ()),
        None => Ok(()),
    }
}

fn choice<T: Copy>(name: &'static str, value: &str, options: &[(&str, T)]) -> Result<T, ParamError> {
    options.iter().find(|(k, _)| *k == value).map(|(_, v)| *v).ok_or_else(|| ParamError::UnknownChoice {
        name: name.into(),
        value: value.into(),
        allowed: options.iter().map(|(k, _)| *k).collect::<Vec<_>>().join(", "),
    })
}

/// " (did you mean `x`?)" for the closest known key, or "" when nothing is close.
fn nearest_key_hint(unknown: &str) -> String {
    let best = KEYS.iter().map(|k| (edit_distance(unknown, k.name), k.name)).min();
    match best {
        Some((d, name)) if d <= 3.max(unknown.len() / 4) => format!(" (did you mean `{name}`?)"),
        _ => "; run `powderfmu analyze --help` for the list of keys".into(),
    }
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != *cb)).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    const REQUIRED: &str = r#""particle_radius":1e-6,"particle_density":1000,"particle_youngs_modulus":1e9,"particle_poisson_ratio":0.3"#;

    #[test]
    fn every_scene_field_has_a_key_and_keys_are_unique() {
        let mut names: Vec<_> = KEYS.iter().map(|k| k.name).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), KEYS.len());
        // The fields of `Scene`, read off its Debug form: each is a key of the table.
        let debug = format!("{:?}", Scene::from_json(&format!("{{{REQUIRED}}}")).unwrap());
        let fields: Vec<&str> = debug.split(['{', ',']).skip(1).filter_map(|part| part.split(':').next()).map(str::trim).collect();
        assert_eq!(fields.len(), KEYS.len(), "{fields:?}");
        for f in fields {
            assert!(KEYS.iter().any(|k| k.name == f), "Scene field `{f}` has no key in KEYS");
        }
    }

    #[test]
    fn each_key_kind_agrees_with_its_default() {
        for k in KEYS.iter() {
            match k.kind {
                KeyKind::Number => assert!(k.default.parse::<f64>().is_ok(), "{}: default `{}` is not a number", k.name, k.default),
                KeyKind::Required => assert_eq!(k.default, "required", "{}", k.name),
                KeyKind::Choice => assert_eq!(k.unit, "-", "{}", k.name),
                KeyKind::Derived => assert!(k.default.parse::<f64>().is_err(), "{}: a number default is not derived", k.name),
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
