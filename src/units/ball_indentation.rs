//! BallIndentation (Co-Simulation): a small bed of cohesive powder, pre-consolidated in a die, indented by
//! a sphere (`004` Sec. 2.3.5, Chs. 5-7). The bed is a prepared bed file (`powderfmu bed prepare`); the
//! test, its readings and their definitions are `bed::indentation`.
//!
//! With `indenter_motion` = prescribed (the default) the indenter loads at `indentation_speed` to
//! `max_penetration` and unloads at the same speed until it leaves the bed, so that a simulation with no
//! inputs runs the whole test. With `input` it follows `indenter_displacement` (depth below its first touch
//! of the bed surface, positive into the bed) and `indenter_velocity`: over a communication step it moves at
//! constant speed from where it is to displacement + velocity x step.

use super::scene_params;
use super::variables::{Value, VarType, Variable};
use super::{Model, UnitError, UnitInfo};
use crate::bed::indentation::{DepthOrigin, Indentation, Motion, Setup, TestState, FAST, SEED_WINDOW};
use crate::bed::replicas::{check_replica, over_beds, Replicas};
use crate::bed::{constraint_factor, file};
use crate::bed::{BedError, BedScene};
use crate::scene::{Key, KeyDefault, KEYS};
use serde_json::{Map, Value as Json};
use std::path::{Path, PathBuf};

/// The FMI modelIdentifier of the unit.
pub const MODEL_IDENTIFIER: &str = "BallIndentation";

/// The bed in the FMU's resources folder.
pub const RESOURCE_BED: &str = "bed.pfbed";

/// The scene of the bed the FMU ships; the contact parameters start at its values.
pub const DEFAULT_BED_SCENE: &str = include_str!("../../scenes/bed_004_ch6.json");

/// The bed the FMU ships, prepared once from `DEFAULT_BED_SCENE` (repository path; `fmu_build` refuses
/// it if made with another scene).
pub const SHIPPED_BED: &str = "beds/bed_004_ch6.pfbed";

/// The quarter of the same bed's die (`die_sector` 0.25, mirror planes) that `fidelity = quarter` runs:
/// its resource name, its scene and the repository path it is prepared to.
pub const RESOURCE_QUARTER_BED: &str = "bed_quarter.pfbed";
/// The scene of the quarter bed (`RESOURCE_QUARTER_BED`).
pub const QUARTER_BED_SCENE: &str = include_str!("../../scenes/bed_004_ch6_quarter.json");
/// The repository path the quarter bed is prepared to.
pub const SHIPPED_QUARTER_BED: &str = "beds/bed_004_ch6_quarter.pfbed";

/// The quarter beds `replicas` runs on beside the first: prepared as it is from its scene with other fill
/// seeds (resource name, scene, repository path).
pub const QUARTER_REPLICAS: [(&str, &str, &str); 2] = [
    ("bed_quarter_2.pfbed", include_str!("../../scenes/bed_004_ch6_quarter_seed2.json"), "beds/bed_004_ch6_quarter_seed2.pfbed"),
    ("bed_quarter_3.pfbed", include_str!("../../scenes/bed_004_ch6_quarter_seed3.json"), "beds/bed_004_ch6_quarter_seed3.pfbed"),
];

/// The default speed [m/s]: gamma* = (v/H)(d/g)^(1/2) = 0.04 on the shipped bed (`004` Eq. 7.1; H =
/// 18.0 mm, d = 1.0 mm), run on its quarter (`fidelity = quarter`) to h/r 0.5 and read in the seed's
/// window (`SEED_WINDOW`): the test in 104-116 s on two cores (AVX2). Chosen from the measured curve in
/// docs/indentation.md: in the seed's window the three quarter beds read the same level at gamma* 0.01,
/// 0.02 and 0.04 (6719, 6767 and 6631 Pa) and 14 % less at 0.08, and 0.04 is the fastest of them.
pub const DEFAULT_SPEED: f64 = 0.07144;

/// The default depth [m] the indenter turns at: h/r = 0.5 for the 16 mm indenter, the end of the seed's
/// window.
pub const DEFAULT_MAX_PENETRATION: f64 = 0.004;

/// The default time step [s]: half the shipped bed's stability limit 2 sqrt(m*/k) = 5.0e-7 s (its
/// smallest sphere on the 8 MN/m die wall, 000 Eq. 68), 2.5 times its own step (docs/indentation.md
/// measures what that changes).
pub const DEFAULT_TIME_STEP: f64 = 2.5e-7;

/// The three contacts whose scene keys are parameters `{contact}.{key}`: the bed's two, which must agree
/// with the bed file, and the indenter's, free.
const CONTACTS: [&str; 3] = ["particle_particle", "particle_wall", "particle_indenter"];

/// Which scene keys a contact's parameters hold: the bed sets every radius and the partner; the
/// particle's own material (and the one law the bed steps) come from particle_particle.
fn contact_key(contact: &str, key: &Key) -> bool {
    let bed_sets = ["contact_partner", "particle_radius"];
    let particle_only = ["contact_model", "particle_density", "particle_youngs_modulus", "particle_poisson_ratio"];
    !bed_sets.contains(&key.name) && (contact == "particle_particle" || !particle_only.contains(&key.name))
}

/// A bed's scene keys of one of the three contacts (the indenter's as `BedScene::indenter_pair`).
fn contact_map(bed: &BedScene, contact: &str) -> Map<String, Json> {
    match contact {
        "particle_particle" => bed.particle_particle.clone(),
        "particle_wall" => bed.particle_wall.clone(),
        _ => bed.indenter_pair(),
    }
}

/// The unit's variables: its own, then the scene keys of the three contacts, starting at the shipped bed's.
fn variables() -> Vec<Variable> {
    let bed = BedScene::from_json(DEFAULT_BED_SCENE).expect("the shipped bed scene is valid");
    let mut vars = own_variables();
    for contact in CONTACTS {
        let map = contact_map(&bed, contact);
        vars.extend(scene_params::group_variables(contact, &map, |k| contact_key(contact, k)));
    }
    vars
}

/// The value a bed's contact map gives a key, as the parameters hold it: a choice or a number (its
/// default when absent), or none for a derived value left to derive.
fn resolved(key: &Key, map: &Map<String, Json>) -> Option<Json> {
    // Numbers compare as numbers (JSON's 0 and 0.0 are one value).
    let given = map.get(key.name).filter(|v| !v.is_null()).map(|v| v.as_f64().map_or_else(|| v.clone(), Json::from));
    match (key.default, given.as_ref()) {
        (KeyDefault::Derived(_), Some(v)) if v.as_f64() == Some(0.0) => None,
        (_, Some(v)) => Some(v.clone()),
        (KeyDefault::Number(x), None) => Some(Json::from(x)),
        (KeyDefault::Choice { default, .. }, None) => Some(Json::from(default)),
        (KeyDefault::Required | KeyDefault::Derived(_), None) => None,
    }
}

/// The first of a contact's keys whose values differ between two maps, as the parameters hold them
/// (`resolved`: 0 and 0.0 are one value, an absent key its default).
fn first_difference(contact: &str, a: &Map<String, Json>, b: &Map<String, Json>) -> Option<&'static Key> {
    KEYS.iter().filter(|k| contact_key(contact, k)).find(|key| resolved(key, a) != resolved(key, b))
}

/// The contact parameters that make the unit accept a bed made with `bed`, as start values for an
/// importer (`powderfmu bed params`): its two contacts, and the particle-indenter contact the bed's
/// `indenter_material` gives (as `powderfmu bed indent` takes it); a derived key left to derive is 0.
pub fn parameters_of_bed(bed: &BedScene) -> Map<String, Json> {
    let mut out = Map::new();
    for contact in CONTACTS {
        let map = contact_map(bed, contact);
        for key in KEYS.iter().filter(|k| contact_key(contact, k)) {
            out.insert(format!("{contact}.{}", key.name), resolved(key, &map).unwrap_or_else(|| Json::from(0.0)));
        }
    }
    out
}

variable_table! {
    indenter_displacement: Variable::input("indenter_displacement", "m", "with indenter_motion = input: depth of the indenter's lowest point below the depth origin (depth_origin), positive into the bed; at the start at most -depth_origin_offset (the indenter starts at or above its first touch of the bed)"),
    indenter_velocity: Variable::input("indenter_velocity", "m/s", "with indenter_motion = input: rate of indenter_displacement, positive into the bed"),
    indenter_force: Variable::output("indenter_force", VarType::Real, "N", "force of the bed on the indenter, positive resisting the indentation"),
    penetration_depth: Variable::output("penetration_depth", VarType::Real, "m", "h, depth of the indenter's lowest point below the depth origin (depth_origin: its first touch of the bed, or the bed's mean surface under its footprint)"),
    dimensionless_penetration: Variable::output("dimensionless_penetration", VarType::Real, "", "h / r with r the indenter's radius (004 Eq. 5.5)"),
    projected_area: Variable::output("projected_area", VarType::Real, "m2", "A(h) = pi (d h - h^2) (004 Eq. 2.9)"),
    hardness: Variable::output("hardness", VarType::Real, "Pa", "while loading F / A(h); after the turn F_max / A(h_c) (004 Sec. 2.3.5), F_max = force_at_turn (the loading curve's force at h_max, not its largest sample) and h_c = contact_depth"),
    hardness_standard_error: Variable::output("hardness_standard_error", VarType::Real, "Pa", "after the turn, the standard error of hardness from the fluctuations of the force it reads: A(h_max) / A(h_c) times the error of the mean F/A(h) behind force_at_turn, sqrt(sigma^2 min(1, tau / m)) over its m samples, with the variance sigma^2 and the correlation time tau of F/A(h) over the loading's deeper half (the estimator of plateau_hardness_standard_error): the last tenth of the depth holds less than one correlation time, so its own scatter would understate the error; 0 while loading (hardness is then one sample) and where fewer than 8 samples lie in the last tenth of the loading depth. It holds neither the uncertainty of contact_depth nor the bed-to-bed scatter; with replicas, the beds' own errors combined as independent"),
    unconfined_yield_strength: Variable::output("unconfined_yield_strength", VarType::Real, "Pa", "hardness / C (004 Eq. 2.10), C the constraint_factor_used"),
    unconfined_yield_strength_standard_error: Variable::output("unconfined_yield_strength_standard_error", VarType::Real, "Pa", "from hardness_standard_error / C and C's own standard error, added in quadrature (a constant constraint_factor taken as exact; a measured C's error is common to the replicas' beds)"),
    constraint_factor_used: Variable::output("constraint_factor_used", VarType::Real, "", "C the unconfined_yield_strength is divided by: constraint_factor, or with constraint_factor_source = measured the C(sigma_1) measured for the 004 Ch. 6 material at the bed's consolidation stress (the mean over the replicas' beds)"),
    constraint_factor_used_standard_error: Variable::output("constraint_factor_used_standard_error", VarType::Real, "", "the standard error of constraint_factor_used: 0 for the constant, the measured table's for C(sigma_1) (its fill-to-fill scatter, docs/data/constraint_factor_ch6_seed_window.csv)"),
    hydrostatic_stress: Variable::output("hydrostatic_stress", VarType::Real, "Pa", "Bagi's hydrostatic stress in the dynamic bin under the indenter (004 Eqs. 5.1-5.2, Sec. 5.2), compression positive"),
    deviatoric_stress: Variable::output("deviatoric_stress", VarType::Real, "Pa", "Bagi's deviatoric stress in the dynamic bin under the indenter (004 Eq. 5.3)"),
    indenter_contacts: Variable::output("indenter_contacts", VarType::Integer, "", "spheres touching the indenter (on a quarter bed, with their mirror images: four per sphere)"),
    kinetic_energy: Variable::output("kinetic_energy", VarType::Real, "J", "kinetic energy of the bed's spheres, translation and rotation"),
    test_state: Variable::output("test_state", VarType::Integer, "", "0 loading, 1 unloading, 2 done (the indenter has left the bed)"),
    contact_depth: Variable::output("contact_depth", VarType::Real, "m", "h_c, where the tangent to the initial unloading curve (its upper quarter) meets zero force (004 Sec. 2.3.5); h_max (the deepest so far) until the tangent is known, and for good where the bed lets go of the indenter too fast for one (see contact_depth_from_tangent)"),
    contact_depth_from_tangent: Variable::output("contact_depth_from_tangent", VarType::Boolean, "", "true once contact_depth is the tangent's h_c; false while it is h_max (before unloading, or where the unloading curve gave no tangent: a vertical one, h_c = h_max)"),
    force_at_turn: Variable::output("force_at_turn", VarType::Real, "N", "F_max of the hardness: A(h_max) times the mean of F/A(h) over the loading samples in the last tenth of the loading depth (h_max the deepest so far): a local reading of the fluctuating force at the turn, not its largest sample"),
    plateau_hardness: Variable::output("plateau_hardness", VarType::Real, "Pa", "mean of F/A(h) over the loading samples (every 100 engine steps) at plateau_start <= h/r <= plateau_end, where it levels off (004 Figs. 5.2-5.3, 5.19); 0 until the indenter reaches plateau_start"),
    plateau_hardness_standard_error: Variable::output("plateau_hardness_standard_error", VarType::Real, "Pa", "standard error of plateau_hardness from this run's fluctuations: sqrt(sigma^2 tau / n), sigma^2 the samples' variance and tau their integrated autocorrelation time in samples (Sokal's window); 0 below 8 samples. It holds neither the bed-to-bed scatter nor, below about 50 correlation times of samples, a reliable error of itself (docs/indentation.md)"),
    plateau_samples: Variable::output("plateau_samples", VarType::Integer, "", "n, the samples behind plateau_hardness (over every replica)"),
    plateau_hardness_standard_error_over_beds: Variable::output("plateau_hardness_standard_error_over_beds", VarType::Real, "Pa", "with replicas > 1: the standard error of plateau_hardness from the replicas' spread, s / sqrt(replicas) with s the sample standard deviation of their plateaus; it holds the bed-to-bed scatter one bed cannot show (the shipped quarter beds differ by about 4 % in the seed's window, 11 % over h/r 0.1-0.2: docs/indentation.md). 0 with one replica"),
    depth_origin_offset: Variable::output("depth_origin_offset", VarType::Real, "m", "height of the indenter's first touch above the depth origin (0 with depth_origin = first_touch)"),
    plateau_hydrostatic_stress: Variable::output("plateau_hydrostatic_stress", VarType::Real, "Pa", "hydrostatic_stress averaged over the loading samples (every 100 engine steps) in the plateau window, the level 004 reads from its dynamic bin (Fig. 5.19, Figs. 7.3-7.5); 0 before the window (plateau_samples 0); the mean over the replicas"),
    plateau_hydrostatic_stress_standard_error: Variable::output("plateau_hydrostatic_stress_standard_error", VarType::Real, "Pa", "standard error of plateau_hydrostatic_stress from this run's fluctuations, the estimator of plateau_hardness_standard_error (the replicas' own combined as independent)"),
    plateau_deviatoric_stress: Variable::output("plateau_deviatoric_stress", VarType::Real, "Pa", "deviatoric_stress averaged as plateau_hydrostatic_stress is"),
    plateau_deviatoric_stress_standard_error: Variable::output("plateau_deviatoric_stress_standard_error", VarType::Real, "Pa", "standard error of plateau_deviatoric_stress, as plateau_hydrostatic_stress_standard_error"),
    indenter_motion: Variable::parameter("indenter_motion", Value::String("prescribed".into()), "", "prescribed (load at indentation_speed to max_penetration, unload at the same speed until the indenter leaves the bed) or input (follow indenter_displacement and indenter_velocity)"),
    indenter_diameter: Variable::parameter("indenter_diameter", Value::Real(0.016), "m", "d, diameter of the spherical indenter, narrower than the die (default 16 mm, 16 mean diameters of the shipped bed: 004 Ch. 5's smallest reliable size)")
        .with_range(Some(0.0), None),
    indentation_speed: Variable::parameter("indentation_speed", Value::Real(DEFAULT_SPEED), "m/s", "speed of the prescribed loading and unloading (default gamma* = 0.04 on the shipped bed's quarter: the test to h/r 0.5 in 104-116 s on two cores with AVX2; in the seed's window the three quarter beds read at it within 2 % of what they read at the seed's speed gamma* = 0.01, 0.01786 m/s: docs/indentation.md)")
        .with_range(Some(0.0), None),
    max_penetration: Variable::parameter("max_penetration", Value::Real(DEFAULT_MAX_PENETRATION), "m", "depth at which the prescribed indenter turns (default 4 mm: h/r = 0.5, the end of the seed's window)")
        .with_range(Some(0.0), None),
    constraint_factor: Variable::parameter("constraint_factor", Value::Real(3.0), "", "C = hardness / yield strength (004 Eq. 2.10) with constraint_factor_source = constant")
        .with_range(Some(0.0), None),
    constraint_factor_source: Variable::parameter("constraint_factor_source", Value::String("constant".into()), "", "constant (constraint_factor, taken as exact) or measured: C(sigma_1) = H / sigma_c measured for the 004 Ch. 6 material with this unit's default test and UnconfinedCompression's at 1, 3, 10 and 20 kPa, interpolated in ln sigma_1 at the bed's consolidation stress, with its standard error (docs/data/constraint_factor_ch6_seed_window.csv: measured with this default, read over h/r 0.35-0.5 at gamma* 0.04; C = 10.3, 6.5, 7.2, 5.9); refused for a bed of another material or outside 1-20 kPa"),
    plateau_start: Variable::parameter("plateau_start", Value::Real(SEED_WINDOW.0), "", "h/r where the plateau window of plateau_hardness starts, in [0, plateau_end); a window beyond max_penetration / r gets no samples (default 0.35: the seed reads its level after h/r 0.35-0.4, 004 Figs. 5.3-5.4, 6.3)")
        .with_range(Some(0.0), None),
    plateau_end: Variable::parameter("plateau_end", Value::Real(SEED_WINDOW.1), "", "h/r where the plateau window ends, above plateau_start (default 0.5, the default max_penetration; 004 Fig. 5.19)")
        .with_range(Some(0.0), None),
    depth_origin: Variable::parameter("depth_origin", Value::String("first_touch".into()), "", "where h is measured from: first_touch (the indenter's lowest point when it first touches a sphere, lowered along the die axis) or mean_surface (the bed's mean surface under the footprint of max_penetration, probed before the test with a sphere of the mean particle radius on a grid of a quarter mean diameter); depth_origin_offset gives the difference"),
    bed_file: Variable::parameter("bed_file", Value::String(String::new()), "", "a bed file of `powderfmu bed prepare`, or several separated by ';' (one per replica, as many as replicas); empty: the beds in the FMU's resources"),
    threads: Variable::parameter("threads", Value::Integer(2), "", "threads of the bed engine's force loop, in [1, 256] (results differ from one thread's by round-off, which the bed's dynamics then grow); with replicas, every bed steps on all of them, one bed after the other"),
    replicas: Variable::parameter("replicas", Value::Integer(1), "", "how many independently prepared beds the test runs on, stepped one after the other within each step (the same indenter motion in each): the FMU's quarter beds (fidelity = quarter: 1 to 3, fill seeds 1-3; fast and full: 1), or the beds bed_file lists, which must be fills of one scene (only `seed` may differ; another is refused, naming the key). Every output is then the mean over the beds, and plateau_hardness_standard_error_over_beds their spread; the first bed reads what it reads alone, to the bit; the cost is replicas times one bed's"),
    time_step: Variable::parameter("time_step", Value::Real(DEFAULT_TIME_STEP), "s", "the bed engine's time step, refused above the bed's stability limit; the default is half the shipped bed's limit (its error is in docs/indentation.md); 0 = the bed's own (its scene's time_step or rayleigh_fraction of its stability limit)")
        .with_range(Some(0.0), None),
    fidelity: Variable::parameter("fidelity", Value::String("quarter".into()), "", "quarter (the FMU's quarter of the seed's die, 7250 spheres between two mirror planes, every sphere moving; with a bed_file, that bed with every sphere moving), fast (the whole bed; the spheres farther than 3 contact radii a_max from the deepest indentation are held where the bed left them until the force on one changes by 0.1 consolidation_stress x d^2) or full (the whole bed, every sphere moving); their errors are measured in docs/indentation.md"),
}

/// The unit (Co-Simulation only): its own variables, the parameters of the three contacts and time.
pub fn info() -> UnitInfo {
    UnitInfo {
        model_identifier: MODEL_IDENTIFIER,
        description: "Ball indentation of a pre-consolidated bed of cohesive spheres by DEM (powderfmu)",
        variables: {
            let mut v = variables();
            v.push(Variable::time());
            v
        },
        n_states: 0,
        n_event_indicators: 0,
        model_exchange: false,
        can_interpolate_inputs: false,
        returns_early: false,
        // The default test: 56.0 ms of loading; the bed lets go of the indenter within a step of the
        // turn, and is not stepped once it has (room for a deeper origin or a slower unloading).
        stop_time: 0.08,
        step_size: 1e-4,
        new_model: |u, resources| {
            Box::new(BallIndentation {
                variables: u.variables.clone(),
                resources: resources.map(Path::to_path_buf),
                test: None,
                reported: None,
                events: vec![],
                fresh: false,
            })
        },
        guid_cache: std::sync::OnceLock::new(),
        token_cache: std::sync::OnceLock::new(),
    }
}

/// The model of BallIndentation: the indentation test on one bed or on several replicas, stepped by the
/// bed engine over each communication step.
pub struct BallIndentation {
    /// The unit's variable table (the contacts' parameters are read from it by name prefix).
    variables: Vec<Variable>,
    resources: Option<PathBuf>,
    test: Option<Replicas>,
    /// The test's state at the last report, and what to report (`take_events`).
    reported: Option<TestState>,
    events: Vec<String>,
    /// Whether the outputs written last are those of the current state (a reading costs a force pass).
    fresh: bool,
}

fn variable(name: &'static str, why: String) -> UnitError {
    UnitError::Variable { name, why }
}

impl From<BedError> for UnitError {
    fn from(e: BedError) -> UnitError {
        match e {
            BedError::Param(p) => UnitError::Param(p),
            BedError::Setup(why) => UnitError::Variable { name: "bed_file", why },
        }
    }
}

impl BallIndentation {
    /// The bed files the parameters name, one per replica: `bed_file`'s (whatever `fidelity`: a sector of
    /// one's own bed is prepared with die_sector 0.25), or the FMU's own, its quarters for `fidelity =
    /// quarter`.
    fn bed_paths(&self, values: &[Value]) -> Result<Vec<PathBuf>, UnitError> {
        let replicas = super::replica_count(values[REFS.replicas].as_real())?;
        let quarter = values[REFS.fidelity].as_str() == "quarter";
        if let Some(paths) = super::listed_beds(values[REFS.bed_file].as_str(), replicas)? {
            return Ok(paths);
        }
        let shipped = if quarter { 1 + QUARTER_REPLICAS.len() } else { 1 };
        if replicas > shipped {
            return Err(variable(
                "replicas",
                format!(
                    "parameter `replicas` = {replicas} is out of range: the FMU ships {shipped} bed(s) for fidelity = {}, allowed [1, {shipped}]; more beds: prepare them (`powderfmu bed prepare` with other seeds) and list them in bed_file",
                    values[REFS.fidelity].as_str()
                ),
            ));
        }
        match &self.resources {
            Some(dir) if quarter => {
                let names = std::iter::once(RESOURCE_QUARTER_BED).chain(QUARTER_REPLICAS.iter().map(|r| r.0));
                Ok(names.take(replicas).map(|n| dir.join(n)).collect())
            }
            Some(dir) => Ok(vec![dir.join(RESOURCE_BED)]),
            None => Err(variable(
                "bed_file",
                "no bed_file given and the host named no resources folder (fmuResourceLocation) holding the FMU's bed".into(),
            )),
        }
    }

    fn threads(values: &[Value]) -> Result<usize, UnitError> {
        super::engine_threads(values[REFS.threads].as_real())
    }

    /// Whether `constraint_factor_source` asks for the measured C(sigma_1).
    fn measured_constraint_factor(values: &[Value]) -> Result<bool, UnitError> {
        match values[REFS.constraint_factor_source].as_str() {
            "constant" => Ok(false),
            "measured" => Ok(true),
            other => Err(variable(
                "constraint_factor_source",
                format!("parameter `constraint_factor_source` = \"{other}\" is not known: allowed constant, measured"),
            )),
        }
    }

    /// The measured C(sigma_1) and its standard error for a bed (`bed::constraint_factor`): of its
    /// material, at its consolidation stress.
    fn measured_for(scene: &BedScene, path: &Path) -> Result<(f64, f64), UnitError> {
        let refuse = |why: String| variable("constraint_factor_source", format!("parameter `constraint_factor_source` = \"measured\": {why}"));
        let reference = BedScene::from_json(QUARTER_BED_SCENE).expect("the shipped quarter bed's scene is valid");
        let other = first_difference("particle_particle", &scene.particle_particle, &reference.particle_particle)
            .map(|key| format!("particle_particle.{}", key.name))
            .or_else(|| (scene.rolling_friction != reference.rolling_friction).then(|| "rolling_friction".into()))
            .or_else(|| (scene.size_distribution != reference.size_distribution).then(|| "size_distribution".into()));
        if let Some(key) = other {
            return Err(refuse(format!(
                "C was measured for the 004 Ch. 6 material only, and bed_file {} differs from it in {key}; give constraint_factor with constraint_factor_source = constant",
                path.display()
            )));
        }
        constraint_factor::at(constraint_factor::points(), scene.consolidation_stress)
            .map_err(|why| refuse(format!("bed_file {}: {why}", path.display())))
    }

    fn setup(values: &[Value]) -> Result<Setup, UnitError> {
        let motion = match values[REFS.indenter_motion].as_str() {
            "prescribed" => Motion::Prescribed,
            "input" => Motion::Input,
            other => {
                return Err(variable("indenter_motion", format!("parameter `indenter_motion` = \"{other}\" is not known: allowed prescribed, input")))
            }
        };
        let shortcut = match values[REFS.fidelity].as_str() {
            "fast" => Some(FAST),
            "full" | "quarter" => None,
            other => return Err(variable("fidelity", format!("parameter `fidelity` = \"{other}\" is not known: allowed fast, quarter, full"))),
        };
        let depth_origin = match DepthOrigin::parse(values[REFS.depth_origin].as_str()) {
            Some(o) => o,
            None => {
                let other = values[REFS.depth_origin].as_str();
                return Err(variable(
                    "depth_origin",
                    format!("parameter `depth_origin` = \"{other}\" is not known: allowed first_touch, mean_surface"),
                ));
            }
        };
        Ok(Setup {
            indenter_diameter: values[REFS.indenter_diameter].as_real(),
            indentation_speed: values[REFS.indentation_speed].as_real(),
            max_penetration: values[REFS.max_penetration].as_real(),
            constraint_factor: values[REFS.constraint_factor].as_real(),
            constraint_factor_standard_error: 0.0,
            motion,
            shortcut,
            plateau: (values[REFS.plateau_start].as_real(), values[REFS.plateau_end].as_real()),
            depth_origin,
        })
    }

    /// The bed's two contacts must be the parameters' (a bed prepared with other materials is another
    /// powder): the first key that differs is named.
    fn check_bed(&self, values: &[Value], bed: &BedScene, path: &Path) -> Result<(), UnitError> {
        let vars = &self.variables;
        for (contact, bed_map) in [("particle_particle", &bed.particle_particle), ("particle_wall", &bed.particle_wall)] {
            let given = scene_params::group_map(contact, vars, values)?;
            if let Some(key) = first_difference(contact, &given, bed_map) {
                let (ours, theirs) = (resolved(key, &given), resolved(key, bed_map));
                let show = |v: &Option<Json>| v.as_ref().map_or("derived (0)".to_string(), |v| v.to_string());
                return Err(variable(
                    "bed_file",
                    format!(
                        "bed_file {} was prepared with {contact}.{} = {}, but the parameter is {}: set the parameter to the bed's value, or prepare a bed with yours (`powderfmu bed prepare`)",
                        path.display(),
                        key.name,
                        show(&theirs),
                        show(&ours)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The particle-indenter contact: the bed's particle-particle keys with the `particle_indenter.*`
    /// parameters over them (a derived one at 0 derives).
    fn indenter_pair(&self, values: &[Value], bed: &BedScene) -> Result<Map<String, Json>, UnitError> {
        let given = scene_params::group_map("particle_indenter", &self.variables, values)?;
        let mut pair = bed.particle_particle.clone();
        for key in KEYS.iter().filter(|k| contact_key("particle_indenter", k)) {
            match given.get(key.name) {
                Some(v) => pair.insert(key.name.into(), v.clone()),
                None => pair.remove(key.name),
            };
        }
        Ok(pair)
    }

    fn inputs(values: &[Value]) -> Result<(f64, f64), UnitError> {
        let (u, v) = (values[REFS.indenter_displacement].as_real(), values[REFS.indenter_velocity].as_real());
        if !u.is_finite() {
            return Err(variable("indenter_displacement", format!("input `indenter_displacement` = {u} m is not finite")));
        }
        if !v.is_finite() {
            return Err(variable("indenter_velocity", format!("input `indenter_velocity` = {v} m/s is not finite")));
        }
        Ok((u, v))
    }
}

impl Model for BallIndentation {
    fn initialize(&mut self, values: &[Value], _t0: f64, _model_exchange: bool) -> Result<(), UnitError> {
        let setup = Self::setup(values)?;
        let measured = Self::measured_constraint_factor(values)?;
        let threads = Self::threads(values)?;
        let paths = self.bed_paths(values)?;
        let start = match setup.motion {
            Motion::Prescribed => None,
            Motion::Input => {
                let (u, v) = Self::inputs(values)?;
                if u <= 0.0 && v < 0.0 {
                    return Err(variable(
                        "indenter_velocity",
                        format!("input `indenter_velocity` = {v:e} m/s would pull the indenter out of a bed it has not entered (indenter_displacement = {u:e} m)"),
                    ));
                }
                Some(u)
            }
        };
        let mut tests: Vec<Indentation> = Vec::with_capacity(paths.len());
        for (k, path) in paths.iter().enumerate() {
            let (engine, scene) = file::load(path, Some(threads)).map_err(|e| match e {
                BedError::Setup(why) => variable("bed_file", format!("bed_file {}: {why}", path.display())),
                other => UnitError::from(other),
            })?;
            if let Some(first) = tests.first() {
                check_replica(&first.scene, &scene)
                    .map_err(|why| variable("bed_file", format!("replica {} of {}: bed_file {}: {why}", k + 1, paths.len(), path.display())))?;
            }
            self.check_bed(values, &scene, path)?;
            let indenter = self.indenter_pair(values, &scene)?;
            let mut setup = setup;
            if measured {
                (setup.constraint_factor, setup.constraint_factor_standard_error) = Self::measured_for(&scene, path)?;
                self.events.push(format!(
                    "constraint factor measured for the 004 Ch. 6 material at the bed's consolidation stress {:e} Pa: C = {:.3} +- {:.3} (docs/data/constraint_factor_ch6_seed_window.csv)",
                    scene.consolidation_stress, setup.constraint_factor, setup.constraint_factor_standard_error
                ));
            }
            let mut test = Indentation::new(engine, scene, setup, start, Some(&indenter))?;
            let dt = values[REFS.time_step].as_real();
            if dt != 0.0 {
                // After the indenter is in: the limit covers its contacts too.
                test.engine.set_time_step(&test.scene, dt)?;
            }
            let p = test.engine.particles();
            self.events.push(format!(
                "{}bed {}: {} spheres{}, {:.4e} m high, time step {:.4e} s; indenter d = {:.4e} m, first touch at z = {:.6e} m, depth origin ({}) {:.4e} m below it{}",
                if paths.len() > 1 { format!("replica {} of {}: ", k + 1, paths.len()) } else { String::new() },
                path.display(),
                p.len(),
                match test.scene.die_sector {
                    s if s < 1.0 => format!(" in {s} of the die (mirror planes: every output is the whole die's)"),
                    _ => String::new(),
                },
                crate::bed::prepare::bed_height(p),
                test.engine.dt(),
                setup.indenter_diameter,
                test.record.touch,
                setup.depth_origin.name(),
                test.record.touch - test.record.origin,
                if paths.len() > 1 { format!("; the beds step one after the other, each on {threads} engine thread(s)") } else { String::new() }
            ));
            tests.push(test);
        }
        let r = 0.5 * setup.indenter_diameter;
        if setup.motion == Motion::Prescribed && setup.plateau.0 >= setup.max_penetration / r {
            self.events.push(format!(
                "plateau_start = {} (h/r) is at or beyond the turn at max_penetration / r = {:.4}: plateau_hardness will have no samples",
                setup.plateau.0,
                setup.max_penetration / r
            ));
        }
        let test = Replicas::new(tests);
        self.reported = Some(test.state());
        self.test = Some(test);
        self.fresh = false;
        Ok(())
    }

    fn compute(&mut self, values: &mut [Value], _between_events: bool) {
        if self.fresh {
            return;
        }
        let Some(test) = self.test.as_mut() else { return };
        let r = test.reading();
        let over_beds = test.plateau_over_beds();
        for (vr, x) in [
            (REFS.indenter_force, r.force),
            (REFS.penetration_depth, r.depth),
            (REFS.dimensionless_penetration, r.dimensionless_depth),
            (REFS.projected_area, r.projected_area),
            (REFS.hardness, r.hardness),
            (REFS.hardness_standard_error, r.hardness_standard_error),
            (REFS.unconfined_yield_strength, r.unconfined_yield_strength),
            (REFS.unconfined_yield_strength_standard_error, r.unconfined_yield_strength_standard_error),
            (REFS.constraint_factor_used, r.constraint_factor),
            (REFS.constraint_factor_used_standard_error, r.constraint_factor_standard_error),
            (REFS.hydrostatic_stress, r.hydrostatic_stress),
            (REFS.deviatoric_stress, r.deviatoric_stress),
            (REFS.kinetic_energy, r.kinetic_energy),
            (REFS.contact_depth, r.contact_depth),
            (REFS.force_at_turn, r.turn_force),
            (REFS.plateau_hardness, r.plateau.mean),
            (REFS.plateau_hardness_standard_error, r.plateau.standard_error),
            (REFS.depth_origin_offset, r.depth_origin_offset),
            (REFS.plateau_hardness_standard_error_over_beds, over_beds.standard_error),
            (REFS.plateau_hydrostatic_stress, r.window_hydrostatic_stress.mean),
            (REFS.plateau_hydrostatic_stress_standard_error, r.window_hydrostatic_stress.standard_error),
            (REFS.plateau_deviatoric_stress, r.window_deviatoric_stress.mean),
            (REFS.plateau_deviatoric_stress_standard_error, r.window_deviatoric_stress.standard_error),
        ] {
            values[vr] = Value::Real(x);
        }
        values[REFS.contact_depth_from_tangent] = Value::Boolean(r.contact_depth_from_tangent);
        values[REFS.plateau_samples] = Value::Integer(r.plateau.samples.min(i32::MAX as usize) as i32);
        values[REFS.indenter_contacts] = Value::Integer(r.contacts.min(i32::MAX as usize) as i32);
        values[REFS.test_state] = Value::Integer(r.state as i32);
        self.fresh = true;
    }

    // Co-Simulation only: Model Exchange is refused at fmi2Instantiate.
    fn set_time(&mut self, _t: f64) {}
    fn get_states(&self, _x: &mut [f64]) {}
    fn set_states(&mut self, _x: &[f64]) {}
    fn derivatives(&mut self, _values: &[Value], _dx: &mut [f64]) {}
    fn event_indicators(&mut self, _values: &[Value], _z: &mut [f64]) {}
    fn nominals(&self, _x: &mut [f64]) {}
    fn accept(&mut self, _values: &[Value]) -> super::EventUpdate {
        super::EventUpdate::default()
    }

    fn do_step(&mut self, values: &[Value], _t: f64, h: f64) -> Result<(), UnitError> {
        let test = self.test.as_mut().ok_or(UnitError::NotInitialized)?;
        let input = match test.first().setup.motion {
            Motion::Prescribed => None,
            Motion::Input => Some(Self::inputs(values)?),
        };
        // Inputs are checked before anything moves, so a refused step leaves the state of its start.
        test.advance(h, input)?;
        self.fresh = false;
        // Every change of the test's state since the last report, in order (one step may hold several).
        let d = test.first().setup.indenter_diameter;
        let beds = test.len();
        let of_beds = if beds > 1 { format!(" (means over the {beds} beds)") } else { String::new() };
        while let Some(from) = self.reported.filter(|&s| s != test.state()) {
            let next = match (from, test.state()) {
                (TestState::Loading, _) => TestState::Unloading,
                (TestState::Unloading, TestState::Loading) => TestState::Loading,
                _ => TestState::Done,
            };
            self.events.push(match next {
                TestState::Loading => format!("loading again at h = {:.4e} m{of_beds}", test.mean_of(Indentation::depth)),
                TestState::Unloading => {
                    let p = test.plateau();
                    let mut text = format!(
                        "unloading from h_max = {:.4e} m, F_max = {:.4e} N (the loading curve's force there, read over its last tenth; largest sample {:.4e} N); plateau hardness {:.4e} +- {:.2e} Pa (standard error, {} samples, correlation time {:.1} samples{}){of_beds}",
                        test.mean_of(|t| t.record.h_max),
                        test.mean_of(|t| t.record.turn_force(d)),
                        test.mean_of(|t| t.record.f_max),
                        p.mean,
                        p.standard_error,
                        p.samples,
                        p.correlation_time,
                        if p.reliable() { "" } else { ": fewer than 50 correlation times, the error is itself uncertain" }
                    );
                    if beds > 1 {
                        let means: Vec<f64> = test.plateaus().iter().map(|p| p.mean).collect();
                        let each: Vec<String> = means.iter().map(|m| format!("{m:.4e}")).collect();
                        let o = over_beds(&means);
                        text += &format!(
                            "; over the beds {:.4e} +- {:.2e} Pa (standard error from their spread, SD {:.2e} Pa; each bed: {} Pa)",
                            o.mean,
                            o.standard_error,
                            o.standard_deviation,
                            each.join(", ")
                        );
                    }
                    text
                }
                TestState::Done => {
                    let all = test.tests.iter().all(|t| t.record.contact_depth.is_some());
                    let how = if all { "from the tangent to the unloading curve" } else { "= h_max: the bed let go of the indenter too fast for a tangent" };
                    format!(
                        "the indenter has left the bed: h_c = {:.4e} m ({how}), hardness F_max/A(h_c) = {:.4e} Pa{of_beds}",
                        test.mean_of(|t| t.record.contact_depth_or_max()),
                        test.mean_of(|t| t.record.hardness_after_turn(d))
                    )
                }
            });
            self.reported = Some(next);
        }
        Ok(())
    }

    fn save(&self) -> Result<Vec<u8>, UnitError> {
        match &self.test {
            Some(test) => test.save().map_err(|e| UnitError::SavedState(e.to_string())),
            None => Ok(Vec::new()),
        }
    }

    fn take_events(&mut self) -> Vec<String> {
        std::mem::take(&mut self.events)
    }

    fn restore(&mut self, values: &[Value], bytes: &[u8]) -> Result<(), UnitError> {
        if bytes.is_empty() {
            self.test = None;
            return Ok(());
        }
        let threads = Self::threads(values)?;
        let test = Replicas::restore(bytes, threads).map_err(|e| UnitError::SavedState(e.to_string()))?;
        self.reported = Some(test.state());
        self.test = Some(test);
        self.fresh = false;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_parameters_of_the_shipped_bed_are_the_start_values() {
        let bed = BedScene::from_json(DEFAULT_BED_SCENE).unwrap();
        let params = parameters_of_bed(&bed);
        let vars = variables();
        assert!(params.len() > 20, "every contact key of the three contacts");
        for (name, value) in &params {
            let v = vars.iter().find(|v| &v.name == name).unwrap_or_else(|| panic!("`{name}` is a parameter"));
            let start = match v.start.as_ref().expect("a parameter has a start value") {
                Value::Real(x) => Json::from(*x),
                Value::String(s) => Json::from(s.as_str()),
                other => panic!("`{name}`: unexpected start {other:?}"),
            };
            assert_eq!(&start, value, "`{name}`");
        }
    }

    #[test]
    fn the_parameters_of_another_bed_name_its_materials() {
        let quick = BedScene::from_json(include_str!("../../scenes/bed_indentation_quick.json")).unwrap();
        let params = parameters_of_bed(&quick);
        assert_eq!(params["particle_particle.particle_youngs_modulus"], Json::from(55e6));
        assert_eq!(params["particle_indenter.friction_coefficient"], params["particle_wall.friction_coefficient"]);
    }
}
