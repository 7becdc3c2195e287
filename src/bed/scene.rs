//! The bed scene: materials, size distribution, die and preparation protocol, as one JSON object.
//! Defaults are the indentation set-up of `004` Sec. 5.1.3 (Tables 5.1-5.3): glass beads of mean
//! diameter 1 mm, Hertz with the modified JKR adhesion and Mindlin's tangential law (004 Sec. 5.1.1),
//! in a steel die of 39 mm, consolidated at 1/s to 10 kPa.
//!
//! The modified JKR's friction is limited by the repulsive part of its force, as in EDEM
//! (`jkr_friction_limit` = `repulsive`).
//!
//! `particle_particle` holds scene keys of the contact-law core (`Scene`): the law and its parameters
//! between particles. `particle_wall` holds the keys that differ against the die, the floor and the
//! piston (Table 5.3's second column); every other key is taken from `particle_particle`.
//! `indenter_material` says which of the two the indenter is made of: 004 Sec. 5.1.3's indenter is
//! "a cohesionless spherical indenter made of Material 1" (the particles' material), 004 Sec. 6.1's is
//! one of the "non-cohesive elastic geometries" with the walls' interaction (Table 6.3).

use super::psd::SizeDistribution;
use crate::error::ParamError;
use crate::scene::{ModelKind, Scene};
use crate::vocabulary::{Options, Range};
use serde_json::{json, Map, Value};

crate::choice_enum! {
    /// What the indenter is made of.
    pub enum IndenterMaterial {
        /// The particles' material (004 Sec. 5.1.3: "a cohesionless spherical indenter made of Material
        /// 1"): `particle_particle`'s keys with the interface energy 0, and `rolling_friction`.
        Particle = "particle",
        /// A geometry like the die (004 Sec. 6.1, Table 6.3): `particle_wall`'s keys and `wall_rolling_friction`.
        Wall = "wall",
    }
}

/// A bed scene, read and checked (`from_json`): the contact laws, the spheres, the die and the preparation.
#[derive(Debug, Clone, PartialEq)]
pub struct BedScene {
    /// Scene keys of the particle-particle law, the defaults with the user's laid over them.
    pub particle_particle: Map<String, Value>,
    /// `particle_particle` with the `particle_wall` keys laid over it.
    pub particle_wall: Map<String, Value>,
    /// The contact law of every contact in the bed (`contact_model`).
    pub model: ModelKind,
    /// The particles' density [kg/m^3], Young's modulus [Pa] and Poisson ratio, as `particle_particle` gives them.
    pub density: f64,
    /// The particles' Young's modulus [Pa].
    pub youngs_modulus: f64,
    /// The particles' Poisson ratio [-].
    pub poisson_ratio: f64,
    /// Particle-particle rolling friction coefficient mu_r [-] (004 Table 5.3: 0.1).
    pub rolling_friction: f64,
    /// Particle-wall rolling friction coefficient [-] (004 Table 5.3: 0).
    pub wall_rolling_friction: f64,
    /// What the indenter of a test is made of (`indenter_pair`, `indenter_rolling_friction`).
    pub indenter_material: IndenterMaterial,
    /// The spheres' diameters and their number fractions.
    pub size_distribution: SizeDistribution,
    /// Number of spheres in the simulated part of the die (the sector's with `die_sector`).
    pub particle_count: usize,
    /// Inner diameter of the die [m].
    pub die_diameter: f64,
    /// Height of the die [m]: the loose fill must fit in it.
    pub die_height: f64,
    /// The part of the die simulated: 1 (whole), 0.5 (half: y >= 0, mirror plane y = 0) or 0.25 (a
    /// quarter: x, y >= 0, mirror planes x = 0 and y = 0). The mirror planes stand for the spheres'
    /// images, so every output is the whole die's.
    pub die_sector: f64,
    /// Gravitational acceleration, downward [m/s^2].
    pub gravity: f64,
    /// Fixed step [s], or None to derive it from `rayleigh_fraction`.
    pub time_step: Option<f64>,
    /// Time step, when `time_step` is None, as a fraction of the stability limit (`any::stability_limit`:
    /// the Rayleigh time of the smallest sphere, 000 Eq. 71, or less for stiff springs) [-].
    pub rayleigh_fraction: f64,
    /// Verlet skin [m], or None for `DEFAULT_SKIN` (0.025) of the mean diameter. A speed setting only:
    /// what a contact remembers does not depend on it.
    pub skin: Option<f64>,
    /// Forgetting distance [m]: a contact whose surfaces are farther apart forgets its memory (the
    /// plastic history of Pasha's and Nan's laws), or None for `DEFAULT_FORGETTING_DISTANCE` (0.025) of
    /// the mean diameter.
    pub forgetting_distance: Option<f64>,
    /// Solid fraction of the loose random fill.
    pub fill_solid_fraction: f64,
    /// Settling ends when the kinetic energy falls below this fraction of sum(m g d_mean).
    pub settle_energy_ratio: f64,
    /// Piston stress to consolidate to [Pa] (004 Sec. 5.1.3: 10 kPa).
    pub consolidation_stress: f64,
    /// Piston strain rate, loading and unloading [1/s] (004 Sec. 5.1.3: 1/s).
    pub strain_rate: f64,
    /// Seed of the random fill.
    pub seed: u64,
    /// Threads the engine runs on (force loop and kick).
    pub threads: usize,
}

crate::scene_options! {
    /// The bed scene's keys that take a number or a name, each declared once: read, range-checked and
    /// listed in the help (`powderfmu bed prepare --help`) from here. `to_json` writes them back; a test
    /// holds it to this list.
    pub struct BedKeys {
        rolling_friction: number(0.1), "-", Range::ClosedLow(0.0, 10.0), "particle-particle rolling friction coefficient mu_r (004 Table 5.3: 0.1)";
        wall_rolling_friction: number(0.0), "-", Range::ClosedLow(0.0, 10.0), "particle-wall rolling friction coefficient (004 Table 5.3: 0)";
        indenter_material: choice(IndenterMaterial::Particle), "-", Range::Names, "particle: the particles' material and friction without cohesion (004 Sec. 5.1.3); wall: the walls' contact (004 Table 6.3)";
        size_scale: number(1.0), "-", Range::Open(1e-4, 1e4), "factor on every diameter of size_distribution";
        particle_count: number(16000.0), "-", Range::ClosedLow(2.0, 1e7), "number of spheres, a whole number (004 Sec. 5.1.3: 16000); the sector's with die_sector";
        die_diameter: number(0.039), "m", Range::Open(0.0, 100.0), "inner diameter of the die (004 Sec. 5.1.3: 39 mm)";
        die_height: number(0.06), "m", Range::Open(0.0, 100.0), "height of the die: the loose fill must fit in it";
        die_sector: number(1.0), "-", Range::OpenClosed(0.0, 1.0), "part of the die simulated, with mirror planes for the rest: 1, 0.5 or 0.25";
        gravity: number(9.81), "m/s^2", Range::ClosedLow(0.0, 1e6), "gravitational acceleration, downward";
        time_step: number(0.0), "s", Range::ClosedLow(0.0, 1.0), "fixed time step; 0 derives rayleigh_fraction x the Rayleigh time of the smallest sphere";
        rayleigh_fraction: number(0.2), "-", Range::OpenClosed(0.0, 1.0), "time step as a fraction of the Rayleigh time (000 Eq. 71)";
        skin: number(0.0), "m", Range::ClosedLow(0.0, 1.0), "Verlet list skin, a speed setting; 0 derives 0.025 of the mean diameter (at least twice the adhesive necks' reach)";
        forgetting_distance: number(0.0), "m", Range::ClosedLow(0.0, 1.0), "a contact whose surfaces are farther apart forgets its memory (Pasha's and Nan's plastic history); 0 derives 0.025 of the mean diameter (at least twice the necks' reach)";
        fill_solid_fraction: number(0.3), "-", Range::Open(0.0, 0.5), "solid fraction of the loose random fill";
        settle_energy_ratio: number(1e-6), "-", Range::Open(0.0, 1.0), "settled when the kinetic energy < this x sum(m g d_mean)";
        consolidation_stress: number(10e3), "Pa", Range::Open(0.0, 1e9), "piston stress to consolidate to (004 Sec. 5.1.3: 10 kPa)";
        strain_rate: number(1.0), "1/s", Range::Open(0.0, 1e4), "piston strain rate, loading and unloading (004 Sec. 5.1.3: 1/s)";
        seed: number(1.0), "-", Range::ClosedLow(0.0, 1e15), "seed of the random fill, a whole number";
        threads: number(1.0), "-", Range::ClosedLow(1.0, 257.0), "threads of the force loop, a whole number";
    }
}

/// The bed scene's keys that hold structures (read by hand in `from_map`): name, unit, meaning.
pub const STRUCTURED_KEYS: [(&str, &str, &str); 4] = [
    ("particle_particle", "-", "scene keys of the particle-particle law (004 Tables 5.2-5.3, column 1; `powderfmu analyze --help` lists them)"),
    ("particle_wall", "-", "scene keys that differ against the die, floor and piston (004 Table 5.3, column 2)"),
    ("size_distribution", "m, -", "{\"diameters\": [...], \"frequencies\": [...]} by number; default 004 Table 5.1"),
    ("comment", "-", "free text, ignored"),
];

/// Every bed scene key's name: the structured ones, then `BedKeys`.
fn bed_key_names() -> impl Iterator<Item = &'static str> {
    STRUCTURED_KEYS.iter().map(|k| k.0).chain(BedKeys::OWN_KEYS.iter().map(|k| k.name))
}

/// The bed scene's keys as the help lists them: name, unit, default, what is allowed, meaning.
pub fn keys_help() -> String {
    let mut s = String::from("BED SCENE KEYS\n\n");
    for (name, unit, doc) in STRUCTURED_KEYS {
        s += &format!("  {name:<24} [{unit}] {doc}\n");
    }
    for k in BedKeys::OWN_KEYS {
        s += &format!("  {:<24} [{}] default {}, allowed {}\n      {}\n", k.name, k.unit, k.default_text(), k.allowed_text(), k.doc);
    }
    s
}

/// A whole number, or an error naming the key.
fn whole(name: &'static str, x: f64) -> Result<f64, ParamError> {
    if x.fract() == 0.0 {
        Ok(x)
    } else {
        Err(ParamError::OutOfRange { name, value: x, allowed: "a whole number".into() })
    }
}

impl Default for BedScene {
    fn default() -> BedScene {
        BedScene::from_json("{}").expect("the default bed scene is valid")
    }
}

impl BedScene {
    /// Reads a bed scene from JSON text: an object of bed scene keys, unknown keys refused, the rest defaulted.
    pub fn from_json(text: &str) -> Result<BedScene, ParamError> {
        let value: Value = serde_json::from_str(text).map_err(|e| ParamError::Malformed { what: format!("not valid JSON: {e}") })?;
        let map = value.as_object().ok_or_else(|| ParamError::Malformed { what: "the top level of a bed scene must be a JSON object".into() })?;
        BedScene::from_map(map)
    }

    /// Reads a bed scene from a JSON object of bed scene keys: the two contact maps over their defaults and
    /// checked at a representative radius, every other key range-checked.
    pub fn from_map(map: &Map<String, Value>) -> Result<BedScene, ParamError> {
        for k in map.keys() {
            if !bed_key_names().any(|known| known == k) {
                let hint = match crate::vocabulary::nearest_name(k, bed_key_names()) {
                    Some(name) => format!(" (did you mean `{name}`?)"),
                    None => "; run `powderfmu bed prepare --help` for the list of bed scene keys".into(),
                };
                return Err(ParamError::UnknownKey { name: k.clone(), hint });
            }
        }
        let object = |name: &'static str| -> Result<Map<String, Value>, ParamError> {
            match map.get(name) {
                None | Some(Value::Null) => Ok(Map::new()),
                Some(Value::Object(m)) => Ok(m.clone()),
                Some(other) => Err(ParamError::Malformed { what: format!("`{name}` must be an object of scene keys, got {other}") }),
            }
        };
        // 004 Tables 5.2-5.3 and Sec. 5.1.1. The interface energy: Table 5.3's 0.5 J/m^2 is EDEM's
        // surface energy gamma, whose JKR force -4 (pi gamma E*)^(1/2) a^(3/2) is 004 Eq. 3.41's with
        // Gamma = 2 gamma (docs/models.md, "The seed's Ch. 5 material"; measured in docs/indentation.md).
        let mut pp = json!({
            "contact_model": "jkr_modified",
            "particle_density": 2456.0,
            "particle_youngs_modulus": 55e9,
            "particle_poisson_ratio": 0.25,
            "surface_energy": 1.0,
            "restitution_coefficient": 0.5,
            "friction_coefficient": 0.15,
        })
        .as_object()
        .cloned()
        .unwrap_or_default();
        let user_pp = object("particle_particle")?;
        for (k, v) in &user_pp {
            if k == "particle_radius" || k == "contact_partner" {
                return Err(ParamError::Inconsistent {
                    name: "particle_particle",
                    why: format!("`{k}` is set by the bed (radii come from size_distribution, partners from the pair)"),
                });
            }
            pp.insert(k.clone(), v.clone());
        }
        // The modified JKR as EDEM implements it: the friction limited by the repulsive part of the force
        // (docs/models.md, "The friction limit of the modified JKR contacts"; measured in
        // docs/indentation.md, "EDEM's friction limit").
        if pp.get("contact_model") == Some(&Value::from("jkr_modified")) {
            pp.entry("jkr_friction_limit").or_insert_with(|| Value::from("repulsive"));
        }
        let mut pw = pp.clone();
        for (k, v) in json!({
            "wall_youngs_modulus": 182e9,
            "wall_poisson_ratio": 0.3,
            "surface_energy": 0.0,
            "restitution_coefficient": 0.3,
            "friction_coefficient": 0.0,
        })
        .as_object()
        .cloned()
        .unwrap_or_default()
        {
            pw.insert(k, v);
        }
        for (k, v) in object("particle_wall")? {
            if k == "contact_model" && Some(&v) != pp.get("contact_model") {
                return Err(ParamError::Inconsistent {
                    name: "particle_wall",
                    why: "the bed steps one law: give contact_model in particle_particle only".into(),
                });
            }
            pw.insert(k, v);
        }
        // Check both maps now, at a representative radius, so errors name the key early.
        let probe = |m: &Map<String, Value>, partner: &str| -> Result<Scene, ParamError> {
            let mut m = m.clone();
            m.insert("particle_radius".into(), Value::from(0.5e-3));
            m.insert("contact_partner".into(), Value::from(partner));
            Scene::from_map(&m)
        };
        let scene_pp = probe(&pp, "particle")?;
        probe(&pw, "wall")?;
        let mut keys = BedKeys::defaults();
        keys.read(map)?;
        keys.check()?;
        let scale = keys.size_scale;
        let size_distribution = match map.get("size_distribution") {
            None | Some(Value::Null) => SizeDistribution::table_5_1(scale),
            Some(Value::Object(d)) => {
                let list = |k: &str| -> Result<Vec<f64>, ParamError> {
                    d.get(k)
                        .and_then(Value::as_array)
                        .map(|a| a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect())
                        .ok_or_else(|| ParamError::Malformed { what: format!("size_distribution needs a number list `{k}`") })
                };
                let dia = list("diameters")?.iter().map(|d| d * scale).collect();
                SizeDistribution::new(dia, list("frequencies")?)?
            }
            Some(other) => return Err(ParamError::Malformed { what: format!("`size_distribution` must be an object, got {other}") }),
        };
        let count = whole("particle_count", keys.particle_count)?;
        if ![1.0, 0.5, 0.25].contains(&keys.die_sector) {
            return Err(ParamError::OutOfRange {
                name: "die_sector",
                value: keys.die_sector,
                allowed: "1 (the whole die), 0.5 (half) or 0.25 (a quarter)".into(),
            });
        }
        let threads = whole("threads", keys.threads)?;
        let seed = whole("seed", keys.seed)?;
        Ok(BedScene {
            model: scene_pp.contact_model,
            density: scene_pp.particle_density,
            youngs_modulus: scene_pp.particle_youngs_modulus,
            poisson_ratio: scene_pp.particle_poisson_ratio,
            particle_particle: pp,
            particle_wall: pw,
            rolling_friction: keys.rolling_friction,
            wall_rolling_friction: keys.wall_rolling_friction,
            indenter_material: keys.indenter_material,
            size_distribution,
            particle_count: count as usize,
            die_diameter: keys.die_diameter,
            die_height: keys.die_height,
            die_sector: keys.die_sector,
            gravity: keys.gravity,
            time_step: (keys.time_step > 0.0).then_some(keys.time_step),
            rayleigh_fraction: keys.rayleigh_fraction,
            skin: (keys.skin > 0.0).then_some(keys.skin),
            forgetting_distance: (keys.forgetting_distance > 0.0).then_some(keys.forgetting_distance),
            fill_solid_fraction: keys.fill_solid_fraction,
            settle_energy_ratio: keys.settle_energy_ratio,
            consolidation_stress: keys.consolidation_stress,
            strain_rate: keys.strain_rate,
            seed: seed as u64,
            threads: threads as usize,
        })
    }

    /// The scene as JSON again (stored in bed files so a bed says how it was made).
    pub fn to_json(&self) -> Value {
        let d = &self.size_distribution;
        json!({
            "particle_particle": self.particle_particle,
            "particle_wall": self.particle_wall,
            "rolling_friction": self.rolling_friction,
            "wall_rolling_friction": self.wall_rolling_friction,
            "indenter_material": self.indenter_material.name(),
            "size_distribution": {"diameters": d.diameters, "frequencies": d.fractions},
            "particle_count": self.particle_count,
            "die_diameter": self.die_diameter,
            "die_height": self.die_height,
            "die_sector": self.die_sector,
            "gravity": self.gravity,
            "time_step": self.time_step.unwrap_or(0.0),
            "rayleigh_fraction": self.rayleigh_fraction,
            "skin": self.skin.unwrap_or(0.0),
            "forgetting_distance": self.forgetting_distance.unwrap_or(0.0),
            "fill_solid_fraction": self.fill_solid_fraction,
            "settle_energy_ratio": self.settle_energy_ratio,
            "consolidation_stress": self.consolidation_stress,
            "strain_rate": self.strain_rate,
            "seed": self.seed,
            "threads": self.threads,
        })
    }

    /// A scene stored in a bed file. Beds written before `indenter_material` existed were indented with
    /// the walls' contact: they keep it. Beds written before `jkr_friction_limit` existed were prepared
    /// with 004 Eq. 3.49's limit: they keep it (a bed must be tested with the law it was packed with).
    pub fn from_stored_json(text: &str) -> Result<BedScene, ParamError> {
        let mut value: Value = serde_json::from_str(text).map_err(|e| ParamError::Malformed { what: format!("not valid JSON: {e}") })?;
        if let Some(map) = value.as_object_mut() {
            map.entry("indenter_material").or_insert_with(|| Value::from(IndenterMaterial::Wall.name()));
            for pair in ["particle_particle", "particle_wall"] {
                if let Some(Value::Object(keys)) = map.get_mut(pair) {
                    if keys.get("contact_model") == Some(&Value::from("jkr_modified")) {
                        keys.entry("jkr_friction_limit").or_insert_with(|| Value::from("pull_off"));
                    }
                }
            }
        }
        let map = value.as_object().ok_or_else(|| ParamError::Malformed { what: "the top level of a bed scene must be a JSON object".into() })?;
        BedScene::from_map(map)
    }

    /// The particle-indenter scene keys. Made of the particles' material: `particle_particle` with the
    /// particles' Young's modulus and Poisson ratio as the wall's and no interface energy (004 Sec.
    /// 5.1.3); a yield pressure of the wall is not set, so the indenter does not yield (it is elastic in
    /// both of the seed's set-ups). Otherwise the walls' keys (004 Table 6.3).
    pub fn indenter_pair(&self) -> Map<String, Value> {
        match self.indenter_material {
            IndenterMaterial::Wall => self.particle_wall.clone(),
            IndenterMaterial::Particle => {
                let mut pair = self.particle_particle.clone();
                pair.insert("wall_youngs_modulus".into(), Value::from(self.youngs_modulus));
                pair.insert("wall_poisson_ratio".into(), Value::from(self.poisson_ratio));
                pair.insert("surface_energy".into(), Value::from(0.0));
                pair
            }
        }
    }

    /// The rolling friction coefficient against the indenter: `rolling_friction` when it is made of the
    /// particles' material, `wall_rolling_friction` otherwise.
    pub fn indenter_rolling_friction(&self) -> f64 {
        match self.indenter_material {
            IndenterMaterial::Particle => self.rolling_friction,
            IndenterMaterial::Wall => self.wall_rolling_friction,
        }
    }

    /// The cross-section of the die the bed fills: the sector's share of pi D^2 / 4 [m^2].
    pub fn sector_area(&self) -> f64 {
        self.die_sector * std::f64::consts::PI * 0.25 * self.die_diameter * self.die_diameter
    }

    /// Radius [m] and mass [kg] of each species (size class).
    pub fn species(&self) -> Vec<(f64, f64)> {
        self.size_distribution.diameters.iter().map(|d| (0.5 * d, std::f64::consts::PI / 6.0 * d.powi(3) * self.density)).collect()
    }

    /// The Rayleigh time of the smallest sphere (000 Eq. 71) [s]: the stability limit of the step.
    pub fn rayleigh_time(&self) -> f64 {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        crate::theory::time_step::rayleigh_time_step(0.5 * self.size_distribution.min_diameter(), self.density, e / (2.0 * (1.0 + nu)), nu)
    }
}

/// The path of the first key whose values differ between two scenes as JSON (`BedScene::to_json`), keys
/// in `ignored` left out at every level; numbers compare by value (2 and 2.0 are one). For the checks
/// that a bed was made with a given scene (`fmu_build`) and that replicas are fills of one scene.
pub fn first_difference(at: &str, a: &Value, b: &Value, ignored: &[&str]) -> Option<String> {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).filter(|k| !ignored.contains(&k.as_str())).collect();
            keys.sort();
            keys.dedup();
            keys.into_iter().find_map(|k| {
                let path = if at.is_empty() { k.clone() } else { format!("{at}.{k}") };
                match (x.get(k), y.get(k)) {
                    (Some(u), Some(v)) => first_difference(&path, u, v, ignored),
                    _ => Some(path),
                }
            })
        }
        _ if a == b => None,
        (Value::Number(x), Value::Number(y)) if x.as_f64() == y.as_f64() => None,
        _ => Some(at.to_string()),
    }
}

/// The first key in which a replica's scene differs from the first bed's, or None where the two are fills
/// of one scene: only the fill `seed` may differ (and `threads` and `comment`, which change no bed).
pub fn replica_difference(first: &BedScene, other: &BedScene) -> Option<String> {
    first_difference("", &first.to_json(), &other.to_json(), &["threads", "comment", "seed"])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_difference_is_named_by_its_path() {
        let ignored = ["threads", "comment"];
        let a = json!({"threads": 1, "particle_particle": {"surface_energy": 2.0, "friction_coefficient": 0.15}});
        let b = json!({"threads": 2, "particle_particle": {"surface_energy": 2, "friction_coefficient": 0.3}});
        assert_eq!(first_difference("", &a, &b, &ignored).as_deref(), Some("particle_particle.friction_coefficient"));
        assert_eq!(first_difference("", &a, &a, &ignored), None);
        let c = json!({"particle_particle": {"surface_energy": 2.0, "friction_coefficient": 0.15}, "particle_count": 5});
        assert_eq!(first_difference("", &a, &c, &ignored).as_deref(), Some("particle_count"));
    }

    #[test]
    fn replicas_may_differ_in_their_fill_seed_only() {
        let first = BedScene::default();
        let other = BedScene { seed: first.seed + 1, threads: first.threads + 1, ..first.clone() };
        assert_eq!(replica_difference(&first, &other), None);
        let stronger = BedScene { consolidation_stress: 2.0 * first.consolidation_stress, ..other };
        assert_eq!(replica_difference(&first, &stronger).as_deref(), Some("consolidation_stress"));
    }

    #[test]
    fn to_json_writes_every_declared_key_and_reads_back_the_same_scene() {
        let given = r#"{"particle_count": 500, "die_sector": 0.25, "time_step": 1e-7, "seed": 7, "threads": 2,
            "indenter_material": "wall", "rolling_friction": 0.05, "size_scale": 2, "comment": "a test"}"#;
        for scene in [BedScene::default(), BedScene::from_json(given).unwrap()] {
            let json = scene.to_json();
            let map = json.as_object().unwrap();
            // Every declared key is written, except the two that leave no value of their own: the comment,
            // and size_scale, which is applied to the written diameters.
            for name in bed_key_names().filter(|n| !["comment", "size_scale"].contains(n)) {
                assert!(map.contains_key(name), "to_json leaves out `{name}`");
            }
            for k in map.keys() {
                assert!(bed_key_names().any(|n| n == k), "to_json writes `{k}`, which is not a declared key");
            }
            assert_eq!(BedScene::from_json(&json.to_string()).unwrap(), scene);
        }
    }

    #[test]
    fn a_bad_bed_key_is_named_with_its_range_or_the_nearest_key() {
        let err = |text: &str| BedScene::from_json(text).unwrap_err().to_string();
        let e = err(r#"{"consolidation_stres": 1e4}"#);
        assert!(e.contains("did you mean `consolidation_stress`"), "{e}");
        let e = err(r#"{"gravity": -1}"#);
        assert!(e.contains("gravity") && e.contains("[0, 1e6) m/s^2"), "{e}");
        let e = err(r#"{"particle_count": 100.5}"#);
        assert!(e.contains("particle_count") && e.contains("whole number"), "{e}");
        let e = err(r#"{"rayleigh_fraction": 1.5}"#);
        assert!(e.contains("rayleigh_fraction") && e.contains("(0, 1]"), "{e}");
        assert!(BedScene::from_json(r#"{"rayleigh_fraction": 1}"#).is_ok());
        let e = err(r#"{"threads": "two"}"#);
        assert!(e.contains("threads") && e.contains("must be a number"), "{e}");
        assert!(keys_help().contains("consolidation_stress") && keys_help().contains("(0, 1e9) Pa"));
    }
}
