//! The scene keys as FMU parameters (DESIGN 3: one vocabulary). Each key of `scene::KEYS` becomes one
//! parameter of the same name: a String for the choices, a Real otherwise. Start values are the default
//! scene (`000` Table 5, an ammonium fluorescein sphere on silicon). A Real whose scene default is
//! derived from other values ("pi R* p_y", "rigid", ...) has start 0, and 0 means "derive it": such a
//! key is left out of the scene the unit builds.

use super::variables::{fmi_unit, Value, Variable};
use crate::error::ParamError;
use crate::scene::{KeyDefault, KeyKind, Scene, KEYS};
use serde_json::{Map, Value as Json};

/// The default scene of the units.
pub const DEFAULT_SCENE: &str = include_str!("../../scenes/ammonium_fluorescein_on_silicon.json");

/// How a key reaches the FMU: its kind in the key table.
pub fn key_kind(name: &str) -> KeyKind {
    KEYS.iter().find(|k| k.name == name).expect("a scene key").kind()
}

/// One FMU parameter per scene key.
pub fn variables() -> Vec<Variable> {
    let scene: Map<String, Json> = serde_json::from_str(DEFAULT_SCENE).expect("the default scene is a JSON object");
    KEYS.iter()
        .map(|key| {
            let given = scene.get(key.name);
            match key.default {
                KeyDefault::Choice { default, .. } => {
                    let start = given.and_then(|v| v.as_str()).unwrap_or(default);
                    Variable::parameter(key.name, Value::String(start.into()), "", key.doc)
                }
                KeyDefault::Number(default) => {
                    let start = given.and_then(|v| v.as_f64()).unwrap_or(default);
                    Variable::parameter(key.name, Value::Real(start), fmi_unit(key.unit), key.doc)
                }
                KeyDefault::Required => {
                    let start = given.and_then(|v| v.as_f64()).expect("a required key is in the default scene");
                    Variable::parameter(key.name, Value::Real(start), fmi_unit(key.unit), key.doc)
                }
                KeyDefault::Derived(how) => {
                    let start = given.and_then(|v| v.as_f64()).unwrap_or(0.0);
                    let doc = format!("{}. 0 = default: {how}", key.doc);
                    Variable::parameter(key.name, Value::Real(start), fmi_unit(key.unit), &doc).with_range(Some(0.0), None)
                }
            }
        })
        .collect()
}

/// The scene of the parameter values `values[vr]` for the variables `vars` (only the scene keys among
/// them are read). Every range check of `Scene` applies, with its message naming the parameter.
pub fn scene(vars: &[Variable], values: &[Value]) -> Result<Scene, ParamError> {
    let mut map = Map::new();
    for (v, value) in vars.iter().zip(values) {
        if !KEYS.iter().any(|k| k.name == v.name) {
            continue;
        }
        let json = match (key_kind(&v.name), value) {
            (KeyKind::Choice, Value::String(s)) => Json::String(s.clone()),
            (KeyKind::Derived, Value::Real(x)) if *x == 0.0 => continue,
            (_, Value::Real(x)) => {
                if !x.is_finite() {
                    return Err(ParamError::Malformed { what: format!("parameter `{}` = {x} is not a finite number", v.name) });
                }
                Json::from(*x)
            }
            _ => continue,
        };
        map.insert(v.name.clone(), json);
    }
    // The wall keys are meaningless against an identical particle: left out while at their start values.
    if map.get("contact_partner").and_then(|p| p.as_str()) == Some("particle") {
        for name in ["wall_youngs_modulus", "wall_poisson_ratio", "wall_yield_pressure"] {
            let default = vars.iter().find(|v| v.name == name).and_then(|v| v.start.clone());
            let now = vars.iter().position(|v| v.name == name).map(|i| values[i].clone());
            if now == default {
                map.remove(name);
            }
        }
    }
    Scene::from_map(&map)
}
