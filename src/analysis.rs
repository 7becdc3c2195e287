//! `powderfmu analyze`: the derived parameters and closed-form results of one scene, as named values
//! with units. The keys are listed once in `OUTPUTS`; the CLI help and the docs print that table.

use crate::error::ParamError;
use crate::law::nan::Nan;
use crate::law::nan_params::NanParams;
use crate::law::params::{alpha_y0, f_y0, k_hertz, w_jkr, Effective};
use crate::law::{AnyLaw, NormalLaw};
use crate::scene::Scene;
use crate::theory::energy_balance;
use crate::theory::sticking::{cohesion_yield_number, critical_yield_pressure, sticking_velocities};
use crate::theory::time_step::{critical_time_step, rayleigh_time_step};
use serde_json::{json, Map, Value};

/// One output of `analyze`: key, unit, the law or group it belongs to, and meaning.
pub struct Output {
    /// The value's key in the JSON output and its label in the text output.
    pub name: &'static str,
    /// The value's unit as printed ("-" for a pure number or a yes/no flag).
    pub unit: &'static str,
    /// The section the value belongs to.
    pub group: Group,
    /// What the value is, with its source equation.
    pub doc: &'static str,
}

/// Which law or part of the analysis a value belongs to: the text output's sections.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// The pair of surfaces, whatever the law.
    Pair,
    /// Nan's law (000 Secs. 2-4) for these materials, whatever the active law.
    Nan,
    /// Thornton and Ning's yield (000 Eqs. 30-31).
    ThorntonNing,
    /// JKR (000 Eq. 37, 73; App. B), which needs no yield pressure.
    Jkr,
    /// The active law (`contact_model`).
    Active,
    /// Time steps.
    TimeStep,
    /// With --velocity: one undamped impact of the active law.
    Impact,
}

impl Group {
    /// The section's heading in the text output; `model` is the active law's scene name, used in the
    /// `Active` and `Impact` headings.
    pub fn title(self, model: &str) -> String {
        match self {
            Group::Pair => "the pair (000 Sec. 3, whatever the law)".into(),
            Group::Nan => "Nan's law for these materials (000 Secs. 2-4)".into(),
            Group::ThorntonNing => "Thornton-Ning yield (000 Eqs. 30-31)".into(),
            Group::Jkr => "JKR (000 Eqs. 37, 73)".into(),
            Group::Active => format!("the active law, {model}"),
            Group::TimeStep => "time steps".into(),
            Group::Impact => format!("one undamped impact of {model} (energy balance)"),
        }
    }
}

/// Every number `analyze` prints.
pub const OUTPUTS: &[Output] = &[
    Output { name: "reduced_radius", unit: "m", group: Group::Pair, doc: "R* (R for a wall, R/2 for an identical particle)" },
    Output { name: "effective_mass", unit: "kg", group: Group::Pair, doc: "m* (m for a wall)" },
    Output { name: "effective_modulus", unit: "Pa", group: Group::Pair, doc: "E*, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 (004 Eq. 3.15)" },
    Output { name: "effective_shear_modulus", unit: "Pa", group: Group::Pair, doc: "G*, 1/G* = (2-nu1)/G1 + (2-nu2)/G2" },
    Output { name: "yield_pressure", unit: "Pa", group: Group::Pair, doc: "p_y = min(p_y1, p_y2) after 000 Eqs. 32-34" },
    Output { name: "f_ce", unit: "N", group: Group::Pair, doc: "JKR pull-off force 1.5 pi Gamma R* (000 Eq. 5)" },
    Output { name: "f_0", unit: "N", group: Group::Pair, doc: "8/9 f_ce, the drop at first contact (000 Eq. 4)" },
    Output { name: "k_el", unit: "N/m", group: Group::Nan, doc: "elastic stiffness before yield (000 Eq. 52, 45 or given)" },
    Output { name: "k_cl", unit: "N/m", group: Group::Nan, doc: "adhesive stiffness before yield (000 Eq. 36 or 38)" },
    Output { name: "k_p", unit: "N/m", group: Group::Nan, doc: "plastic stiffness" },
    Output { name: "f_y", unit: "N", group: Group::Nan, doc: "yield force (000 Eq. 28)" },
    Output { name: "alpha_y", unit: "m", group: Group::Nan, doc: "yield overlap (000 Eq. 29)" },
    Output { name: "alpha_0", unit: "m", group: Group::Nan, doc: "zero-force overlap before yield f_0/k_el (000 Eq. 6)" },
    Output { name: "f_y0", unit: "N", group: Group::ThorntonNing, doc: "Thornton-Ning yield force (000 Eq. 30)" },
    Output { name: "alpha_y0", unit: "m", group: Group::ThorntonNing, doc: "Thornton-Ning yield overlap (000 Eq. 31)" },
    Output { name: "hertz_stiffness_at_yield", unit: "N/m", group: Group::Nan, doc: "2 E* sqrt(R* alpha_y) (000 Eq. 41; Table 3's k_H)" },
    Output { name: "w_jkr", unit: "J", group: Group::Jkr, doc: "JKR adhesion work 7.09 (Gamma^5 R*^4/E*^2)^(1/3) (000 Eq. 37): the displacement-controlled reading (contact ending at -5/9 f_c), whatever jkr_detachment is" },
    Output { name: "jkr_sticking_velocity", unit: "m/s", group: Group::Jkr, doc: "V_s = (2 W_JKR / m*)^(1/2) (000 Eq. 73): the displacement-controlled reading, whatever jkr_detachment is; needs no yield pressure" },
    Output { name: "yield_velocity", unit: "m/s", group: Group::Nan, doc: "V_y0, yield velocity without cohesion (000 Eq. 74)" },
    Output { name: "adhesive_yield_velocity", unit: "m/s", group: Group::Nan, doc: "V_y (000 Eq. 75); null when f_y < f_0 (adhesion-induced plasticity)" },
    Output { name: "sticking_velocity", unit: "m/s", group: Group::Active, doc: "the active law's sticking velocity, undamped: the smallest impact speed at which the sphere rebounds (nan: 000 Eqs. 77-79; other laws: bisection on the energy balance to 1e-12); 0 if it never sticks" },
    Output { name: "nan_sticking_velocity", unit: "m/s", group: Group::Nan, doc: "V_ys of the Nan law for these materials, whatever the active law (000 Eqs. 77-79)" },
    Output { name: "critical_yield_pressure", unit: "Pa", group: Group::Nan, doc: "p_y below which f_y < f_0 with k_el by Eq. 52 (000 Eq. 80)" },
    Output { name: "cohesion_yield_number", unit: "-", group: Group::Nan, doc: "CY = p_y^3 R* / (E*^2 Gamma) (000 Eq. 81)" },
    Output { name: "rayleigh_time_step", unit: "s", group: Group::TimeStep, doc: "Rayleigh time step of the particle (000 Eq. 71)" },
    Output { name: "critical_time_step", unit: "s", group: Group::TimeStep, doc: "2 sqrt(m*/k_el) (000 Eq. 68)" },
    Output { name: "pull_off_force_fresh", unit: "N", group: Group::Active, doc: "the active law's pull-off force before any loading" },
    Output { name: "adhesion_induced_plasticity", unit: "-", group: Group::Nan, doc: "f_y < f_0: the contact yields at first touch, from adhesion alone (000 Sec. 4)" },
    Output { name: "yields_at_sticking", unit: "-", group: Group::Nan, doc: "whether an impact at the sticking velocity yields (000 Sec. 4)" },
    Output { name: "impact_velocity", unit: "m/s", group: Group::Impact, doc: "with --velocity: the impact speed asked for" },
    Output { name: "max_overlap", unit: "m", group: Group::Impact, doc: "with --velocity: largest overlap of the undamped impact (active law)" },
    Output { name: "max_force", unit: "N", group: Group::Impact, doc: "with --velocity: largest force of the undamped impact (active law)" },
    Output { name: "rebound_velocity", unit: "m/s", group: Group::Impact, doc: "with --velocity: rebound speed by energy balance (active law), 0 if it sticks" },
    Output { name: "restitution", unit: "-", group: Group::Impact, doc: "with --velocity: rebound / impact velocity (active law)" },
    Output { name: "sticks", unit: "-", group: Group::Impact, doc: "with --velocity: whether the sphere sticks" },
];

/// The analysis as text for people: each value with its unit beside it, in sections by the law it
/// belongs to (`Group`), then the notes. `analyze --json` prints the same values as JSON.
pub fn to_text(v: &Value) -> String {
    let model = v["contact_model"].as_str().unwrap_or("?");
    let mut out = format!("contact_model: {model}\n");
    for group in [Group::Pair, Group::Active, Group::Nan, Group::ThorntonNing, Group::Jkr, Group::TimeStep, Group::Impact] {
        let rows: Vec<&Output> = OUTPUTS.iter().filter(|o| o.group == group && v.get(o.name).is_some()).collect();
        if rows.is_empty() {
            continue;
        }
        out += &format!("\n{}\n", group.title(model));
        for o in rows {
            let value = match &v[o.name] {
                Value::Number(n) if o.unit == "-" => format!("{:.5e}", n.as_f64().unwrap_or(f64::NAN)),
                Value::Number(n) => format!("{:.5e} {}", n.as_f64().unwrap_or(f64::NAN), o.unit),
                Value::Bool(b) => (if *b { "yes" } else { "no" }).to_string(),
                Value::Null => "none".to_string(),
                other => other.to_string(),
            };
            out += &format!("  {:<28} {:<20} {}\n", o.name, value, o.doc);
        }
    }
    if let Some(notes) = v["notes"].as_array() {
        out += "\nnotes\n";
        for n in notes {
            out += &format!("  - {}\n", n.as_str().unwrap_or_default());
        }
    }
    out
}

/// The largest impact speed searched for a sticking velocity [m/s].
const MAX_STICKING_SEARCH: f64 = 1e4;

/// The smallest undamped impact speed at which the sphere rebounds, by the energy balance: the first
/// doubling from 1 mm/s that rebounds, then bisection to 1e-12 below it (`energy_balance::sticking_velocity`).
/// 0 when it rebounds even at 1 mm/s from a law without adhesion.
fn active_sticking_velocity(law: &AnyLaw, mass: f64, radius: f64) -> Option<f64> {
    let sticks = |v: f64| energy_balance::impact(law, mass, v, radius).map(|o| o.sticks).unwrap_or(true);
    let mut lo = 1e-3;
    if !sticks(lo) {
        return (law.pull_off_force(&law.initial_history()) == 0.0).then_some(0.0);
    }
    while lo < MAX_STICKING_SEARCH {
        let hi = 2.0 * lo;
        if !sticks(hi) {
            return energy_balance::sticking_velocity(law, mass, radius, lo, hi);
        }
        lo = hi;
    }
    None
}

/// Analyses a scene: derived parameters, closed-form results, and, with `velocity`, one undamped impact
/// of the active law by energy balance. The keys of the answer are `powderfmu analyze --help`'s.
///
/// 000 Table 5's ammonium fluorescein particle on silicon (`scenes/ammonium_fluorescein_on_silicon.json`,
/// Gamma = 0.24 J/m^2 as docs/models.md, "Reading the seeds", reads it): 000 Table 6's V_s = 0.66 m/s
/// and V_ys = 1.86 m/s.
/// ```
/// let scene = powderfmu::Scene::from_json(
///     r#"{"contact_model": "nan", "particle_radius": 2.45e-6, "particle_density": 1350,
///         "particle_youngs_modulus": 1.2e9, "particle_poisson_ratio": 0.33, "particle_yield_pressure": 30e6,
///         "wall_youngs_modulus": 166e9, "wall_poisson_ratio": 0.28, "wall_yield_pressure": 120e6,
///         "surface_energy": 0.24}"#,
/// )?;
/// let report = powderfmu::analysis::analyze(&scene, None)?;
/// let (v_s, v_ys) = (report["jkr_sticking_velocity"].as_f64().unwrap(), report["sticking_velocity"].as_f64().unwrap());
/// assert!((v_s - 0.66).abs() < 0.01 && (v_ys - 1.86).abs() < 0.01, "{v_s} m/s, {v_ys} m/s");
/// # Ok::<(), powderfmu::ParamError>(())
/// ```
pub fn analyze(scene: &Scene, velocity: Option<f64>) -> Result<Value, ParamError> {
    analyze_with(scene, velocity, true)
}

/// The derived parameters in one line, `name = value unit`, for the units' log at initialization: what
/// every "0 = derive it" parameter became. Closed forms only (no energy-balance search).
pub fn derived_line(scene: &Scene) -> Result<String, ParamError> {
    let v = analyze_with(scene, None, false)?;
    let items: Vec<String> = OUTPUTS
        .iter()
        .filter(|o| matches!(o.group, Group::Pair | Group::Nan | Group::ThorntonNing | Group::Jkr | Group::TimeStep))
        .filter_map(|o| {
            v.get(o.name).and_then(Value::as_f64).map(|x| {
                if o.unit == "-" {
                    format!("{} = {x:.6e}", o.name)
                } else {
                    format!("{} = {x:.6e} {}", o.name, o.unit)
                }
            })
        })
        .collect();
    Ok(format!("derived parameters ({}; Nan's law for these materials, 000 Sec. 3): {}", scene.contact_model.name(), items.join(", ")))
}

fn analyze_with(scene: &Scene, velocity: Option<f64>, search_active: bool) -> Result<Value, ParamError> {
    let law = AnyLaw::from_scene(scene)?;
    let eff = Effective::from_scene(scene)?;
    let mut out = Map::new();
    let mut notes: Vec<String> = Vec::new();
    out.insert("contact_model".into(), json!(scene.contact_model.name()));
    out.insert("reduced_radius".into(), json!(eff.radius));
    out.insert("effective_mass".into(), json!(eff.mass));
    out.insert("effective_modulus".into(), json!(eff.youngs_modulus));
    out.insert("effective_shear_modulus".into(), json!(eff.shear_modulus));
    out.insert("yield_pressure".into(), json!(eff.yield_pressure));
    out.insert("f_ce".into(), json!(eff.f_ce()));
    out.insert("f_0".into(), json!(8.0 / 9.0 * eff.f_ce()));
    out.insert(
        "rayleigh_time_step".into(),
        json!(rayleigh_time_step(scene.particle_radius, scene.particle_density, scene.particle_shear_modulus(), scene.particle_poisson_ratio)),
    );
    out.insert("pull_off_force_fresh".into(), json!(law.pull_off_force(&law.initial_history())));
    // The JKR quantities need no yield pressure (000 Eqs. 37, 73; W_0 = W_JKR).
    if eff.surface_energy > 0.0 {
        let w = w_jkr(eff.surface_energy, eff.radius, eff.youngs_modulus);
        out.insert("w_jkr".into(), json!(w));
        out.insert("jkr_sticking_velocity".into(), json!((2.0 * w / eff.mass).sqrt()));
    }
    let nan_sticking = match NanParams::from_pair(&eff, &scene.laws.stiffness, &scene.laws.nan) {
        Ok(p) => {
            let nan = Nan::new(p);
            let v = sticking_velocities(&nan, eff.mass);
            let (r, e) = (p.radius, p.youngs_modulus);
            out.insert("k_el".into(), json!(p.k_el));
            out.insert("k_cl".into(), json!(p.k_cl));
            out.insert("k_p".into(), json!(p.k_p));
            out.insert("f_y".into(), json!(p.f_y));
            out.insert("alpha_y".into(), json!(p.alpha_y));
            out.insert("alpha_0".into(), json!(p.alpha_0));
            out.insert("f_y0".into(), json!(f_y0(r, e, p.yield_pressure)));
            out.insert("alpha_y0".into(), json!(alpha_y0(r, e, p.yield_pressure)));
            out.insert("hertz_stiffness_at_yield".into(), json!(k_hertz(e, r, p.alpha_y)));
            out.insert("yield_velocity".into(), json!(v.yield_velocity));
            out.insert("adhesive_yield_velocity".into(), json!(v.adhesive_yield_velocity));
            out.insert("nan_sticking_velocity".into(), json!(v.sticking_velocity));
            if v.sticking_velocity.is_none() {
                notes.push("sticking_velocity is undefined: 000 Eq. 78 has no root with pull_off_law pasha (Eq. 61 drops f_cp to 0 at yield)".into());
            }
            out.insert("adhesion_induced_plasticity".into(), json!(p.f_y < p.f_0));
            out.insert("yields_at_sticking".into(), json!(v.yields_at_sticking));
            out.insert("critical_time_step".into(), json!(critical_time_step(eff.mass, p.k_el)));
            if p.surface_energy > 0.0 {
                out.insert("critical_yield_pressure".into(), json!(critical_yield_pressure(p.surface_energy, e, r)));
                out.insert("cohesion_yield_number".into(), json!(cohesion_yield_number(p.yield_pressure, r, e, p.surface_energy)));
            } else {
                notes.push("surface_energy is 0: no adhesion, so no critical yield pressure and CY is infinite".into());
            }
            if scene.contact_model.name() != "nan" {
                notes.push("k_el .. adhesive_yield_velocity and nan_sticking_velocity are the Nan law's (000 Sec. 3-4) for these materials".into());
            }
            v.sticking_velocity
        }
        Err(err) => {
            notes.push(format!("Nan law parameters not derived: {err}"));
            None
        }
    };
    // The active law's sticking velocity: the Nan law's closed form, else the energy balance.
    let sticking = if matches!(law, AnyLaw::Nan(_)) {
        nan_sticking
    } else if search_active {
        active_sticking_velocity(&law, eff.mass, eff.radius)
    } else {
        None
    };
    if sticking.is_none() && search_active {
        notes.push(format!(
            "sticking_velocity of {} not found: the sphere sticks at every speed up to {MAX_STICKING_SEARCH} m/s, or 000 Eq. 78 has no root",
            scene.contact_model.name()
        ));
    }
    out.insert("sticking_velocity".into(), json!(sticking));
    if let AnyLaw::Jkr(jkr) = &law {
        if jkr.detachment == crate::law::jkr::JkrDetachment::Force && eff.surface_energy > 0.0 {
            notes.push(
                "sticking_velocity is jkr_detachment = force's (the contact ends at -f_c, LAMMPS's reading); w_jkr and jkr_sticking_velocity are 000 Eqs. 37 and 73, the displacement reading (-5/9 f_c)".into(),
            );
        }
    }
    if let Some(v) = velocity {
        let o = energy_balance::impact(&law, eff.mass, v, eff.radius)
            .map_err(|e| ParamError::Inconsistent { name: "impact_velocity", why: e.to_string() })?;
        out.insert("impact_velocity".into(), json!(v));
        out.insert("max_overlap".into(), json!(o.max_overlap));
        out.insert("max_force".into(), json!(o.max_force));
        out.insert("rebound_velocity".into(), json!(o.rebound_velocity));
        out.insert("restitution".into(), json!(o.restitution));
        out.insert("sticks".into(), json!(o.sticks));
    }
    let units: Map<String, Value> = OUTPUTS.iter().filter(|o| out.contains_key(o.name)).map(|o| (o.name.to_string(), json!(o.unit))).collect();
    out.insert("units".into(), Value::Object(units));
    if !notes.is_empty() {
        out.insert("notes".into(), json!(notes));
    }
    Ok(Value::Object(out))
}
