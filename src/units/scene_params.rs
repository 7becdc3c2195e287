//! The scene keys as FMU parameters (docs/architecture.md, "One vocabulary": one vocabulary). Each key of `scene::KEYS` becomes one
//! parameter of the same name: a String for the choices, a Real otherwise. Start values are the default
//! scene (`000` Table 5, an ammonium fluorescein sphere on silicon). A Real whose scene default is
//! derived from other values ("pi R* p_y", "rigid", ...) has start 0, and 0 means "derive it": such a
//! key is left out of the scene the unit builds.

use super::variables::{fmi_unit, Value, Variable};
use crate::error::ParamError;
use crate::scene::{Key, KeyDefault, KeyKind, Scene, KEYS};
use serde_json::{Map, Value as Json};

/// The default scene of the units.
pub const DEFAULT_SCENE: &str = include_str!("../../scenes/ammonium_fluorescein_on_silicon.json");

/// One FMU parameter per scene key.
pub fn variables() -> Vec<Variable> {
    let scene: Map<String, Json> = serde_json::from_str(DEFAULT_SCENE).expect("the default scene is a JSON object");
    KEYS.iter().map(|key| parameter(key, key.name, scene.get(key.name))).collect()
}

/// The FMU parameter of a scene key, named `name`, starting at `given` (else at the key's default; a
/// derived Real at 0, "derive").
fn parameter(key: &Key, name: &str, given: Option<&Json>) -> Variable {
    match key.default {
        KeyDefault::Choice { default, .. } => {
            let start = given.and_then(|v| v.as_str()).unwrap_or(default);
            Variable::parameter(name, Value::String(start.into()), "", key.doc)
        }
        KeyDefault::Number(default) => {
            let start = given.and_then(|v| v.as_f64()).unwrap_or(default);
            Variable::parameter(name, Value::Real(start), fmi_unit(key.unit), key.doc)
        }
        KeyDefault::Required => {
            let start = given.and_then(|v| v.as_f64()).expect("a required key is given");
            Variable::parameter(name, Value::Real(start), fmi_unit(key.unit), key.doc)
        }
        KeyDefault::Derived(how) => {
            let start = given.and_then(|v| v.as_f64()).unwrap_or(0.0);
            let doc = format!("{}. 0 = default: {how}", key.doc);
            Variable::parameter(name, Value::Real(start), fmi_unit(key.unit), &doc).with_range(Some(0.0), None)
        }
    }
}

/// The parameters `{group}.{key}` of the scene keys `keep` accepts, starting at the values of `map`
/// (a contact of a bed scene: `particle_particle`, `particle_wall`).
pub fn group_variables(group: &str, map: &Map<String, Json>, keep: impl Fn(&Key) -> bool) -> Vec<Variable> {
    KEYS.iter().filter(|k| keep(k)).map(|key| parameter(key, &format!("{group}.{}", key.name), map.get(key.name))).collect()
}

/// The scene keys of the parameters `{group}.{key}` as a JSON object (a derived Real at 0 is left out:
/// "derive").
pub fn group_map(group: &str, vars: &[Variable], values: &[Value]) -> Result<Map<String, Json>, ParamError> {
    let prefix = format!("{group}.");
    let mut map = Map::new();
    for (v, value) in vars.iter().zip(values) {
        let Some(name) = v.name.strip_prefix(&prefix) else { continue };
        let Some(key) = KEYS.iter().find(|k| k.name == name) else { continue };
        if let Some(json) = json_of(key, &v.name, value)? {
            map.insert(key.name.into(), json);
        }
    }
    Ok(map)
}

/// A parameter's value as the scene JSON has it: none for a derived Real at 0.
fn json_of(key: &Key, parameter: &str, value: &Value) -> Result<Option<Json>, ParamError> {
    Ok(match (key.kind(), value) {
        (KeyKind::Choice, Value::String(s)) => Some(Json::String(s.clone())),
        (KeyKind::Derived, Value::Real(x)) if *x == 0.0 => None,
        (_, Value::Real(x)) => {
            if !x.is_finite() {
                return Err(ParamError::Malformed { what: format!("parameter `{parameter}` = {x} is not a finite number") });
            }
            Some(Json::from(*x))
        }
        _ => None,
    })
}

/// The scene of the parameter values `values[vr]` for the variables `vars` (only the scene keys among
/// them are read). Every range check of `Scene` applies, with its message naming the parameter.
pub fn scene(vars: &[Variable], values: &[Value]) -> Result<Scene, ParamError> {
    let mut map = Map::new();
    for (v, value) in vars.iter().zip(values) {
        let Some(key) = KEYS.iter().find(|k| k.name == v.name) else { continue };
        if let Some(json) = json_of(key, &v.name, value)? {
            map.insert(v.name.clone(), json);
        }
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
