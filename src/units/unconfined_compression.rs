//! UnconfinedCompression (Co-Simulation): the uniaxial tester of `004` Sec. 2.1 (Fig. 2.1) on a bed of
//! cohesive spheres consolidated in a die to sigma_1: the die removed, the specimen loaded by a platen
//! at a constant strain rate until it fails. Its peak stress is the unconfined yield strength sigma_c
//! and sigma_1 / sigma_c the flowability ff_c (Eq. 2.1). The test, its readings and their definitions
//! are `bed::compression`; the specimen is a prepared bed file (`powderfmu bed prepare`), whose material
//! and consolidation stress it carries: another powder or another sigma_1 is another bed.
//!
//! `replicas` runs the same test on several independently prepared specimens, one after the other within
//! each step: sigma_c scatters from fill to fill by far more than one test's standard error says (12 %
//! against 0.2 % on the shipped specimen's scene), and only other specimens measure that. One specimen
//! reads what it reads alone, to the bit.

use super::variables::{Value, VarType, Variable};
use super::{Model, UnitError, UnitInfo};
use crate::bed::compression::{Setup, Specimen};
use crate::bed::replicas::{check_replica, independent, over_beds};
use crate::bed::{file, BedError};
use crate::error::ParamError;
use std::path::{Path, PathBuf};

/// The FMI modelIdentifier of the unit.
pub const MODEL_IDENTIFIER: &str = "UnconfinedCompression";

/// The specimen in the FMU's resources folder.
pub const RESOURCE_SPECIMEN: &str = "specimen.pfbed";

/// The scene of the specimen the FMU ships: `004` Ch. 6's material, 4000 spheres in a 15 mm die,
/// consolidated to 10 kPa (beds/README.md).
pub const SPECIMEN_SCENE: &str = include_str!("../../scenes/uct_004_ch6.json");

/// The repository path of the shipped specimen (`fmu_build` refuses it if made with another scene).
pub const SHIPPED_SPECIMEN: &str = "beds/uct_004_ch6.pfbed";

/// The specimens `replicas` runs on beside the first: the shipped specimen's scene filled with other seeds
/// (resource name, scene, repository path).
pub const SPECIMEN_REPLICAS: [(&str, &str, &str); 2] = [
    ("specimen_2.pfbed", include_str!("../../scenes/uct_004_ch6_seed2.json"), "beds/uct_004_ch6_seed2.pfbed"),
    ("specimen_3.pfbed", include_str!("../../scenes/uct_004_ch6_seed3.json"), "beds/uct_004_ch6_seed3.pfbed"),
];

variable_table! {
    axial_stress: Variable::output("axial_stress", VarType::Real, "Pa", "the platen's force over the die's cross-section, compression positive: the mean over the last sample (100 engine steps); 0 before the platen touches"),
    axial_strain: Variable::output("axial_strain", VarType::Real, "", "(z_touch - z) / z_touch, z the platen's height and z_touch its height at its first contact with the specimen"),
    unconfined_yield_strength: Variable::output("unconfined_yield_strength", VarType::Real, "Pa", "sigma_c (004 Sec. 2.1): the largest mean of axial_stress over a window of `window` strain so far (not the largest sample, which the force's fluctuation would bias high); 0 until a window of loaded samples exists. With failed false it is a lower bound. With replicas > 1, the mean of the specimens' sigma_c (0 until each has a window)"),
    unconfined_yield_strength_standard_error: Variable::output("unconfined_yield_strength_standard_error", VarType::Real, "Pa", "standard error of unconfined_yield_strength from the fluctuation of the window's samples, sqrt(sigma^2 tau / n) with tau their integrated autocorrelation time (as plateau_hardness_standard_error of BallIndentation); on the shipped specimen it covers the scatter between realisations of the test (1.0 Pa against 1.7-2.8 Pa); it holds neither the specimen-to-specimen scatter (12 % between three fills of the shipped specimen's scene: unconfined_yield_strength_standard_error_over_specimens measures it with replicas) nor the specimen's size and rate (1/s reads 7 % above the quasi-static value of 0.03-0.3/s), docs/units/UnconfinedCompression.md. With replicas > 1, the specimens' own errors combined as independent, sqrt(sum se^2) / replicas"),
    strain_at_failure: Variable::output("strain_at_failure", VarType::Real, "", "axial strain at the middle of the window of unconfined_yield_strength (with replicas, the specimens' mean)"),
    failed: Variable::output("failed", VarType::Boolean, "", "true once the window mean has fallen below 0.8 of its peak, one window past it (the specimen has failed; the test then ends); false while it has not, and at max_strain when it never did: unconfined_yield_strength is then a lower bound. With replicas, true once every specimen has failed"),
    flow_function: Variable::output("flow_function", VarType::Real, "", "ff_c = sigma_1 / sigma_c (004 Eq. 2.1) with sigma_1 = consolidation_stress; infinite while sigma_c is 0"),
    consolidation_stress: Variable::output("consolidation_stress", VarType::Real, "Pa", "sigma_1: the stress the specimen was consolidated to in its die (the bed's preparation)"),
    solid_fraction: Variable::output("solid_fraction", VarType::Real, "", "the spheres' volume over the die's cross-section times specimen_height, when the die was removed"),
    specimen_height: Variable::output("specimen_height", VarType::Real, "m", "H_0, the specimen's height when the die was removed (the strain rate is relative to it)"),
    self_weight_stress: Variable::output("self_weight_stress", VarType::Real, "Pa", "the specimen's weight over the die's cross-section: a specimen weaker than it slumps before the platen loads it"),
    kinetic_energy: Variable::output("kinetic_energy", VarType::Real, "J", "kinetic energy of the specimen's spheres, translation and rotation (the whole die's for a sector bed)"),
    test_state: Variable::output("test_state", VarType::Integer, "", "0 loading, 1 done (failed, or max_strain reached; with replicas, every specimen); a specimen is not stepped once done"),
    strain_rate: Variable::parameter("strain_rate", Value::Real(Setup::DEFAULT.strain_rate), "1/s", "the platen's speed over specimen_height, in (0, 1e3] (default 1/s, the seed's consolidation rate, 004 Sec. 6.1; docs/bed.md measures what a slower rate reads)")
        .with_range(Some(0.0), None),
    max_strain: Variable::parameter("max_strain", Value::Real(Setup::DEFAULT.max_strain), "", "the test ends here if the specimen has not failed before, in (0, 0.9]")
        .with_range(Some(0.0), None),
    free_time: Variable::parameter("free_time", Value::Real(0.0), "s", "time the specimen stands free between the die's removal and the platen's start, in [0, 10]")
        .with_range(Some(0.0), None),
    window: Variable::parameter("window", Value::Real(Setup::DEFAULT.window), "", "the strain window of unconfined_yield_strength's mean, in (0, max_strain): narrower than the peak (the shipped specimens' lasts 0.1-0.2 % of strain at 1/s), wide enough to average the force's fluctuation (default 0.05 %, 50 samples at 1/s)")
        .with_range(Some(0.0), None),
    reading_start: Variable::parameter("reading_start", Value::Real(Setup::DEFAULT.reading_start), "", "the strain from which the samples are read for unconfined_yield_strength and the failure, in [0, max_strain - window): past the platen's arrival, an impact whose stress is inertia, not strength (on the shipped specimens at 1/s, several kPa up to 0.015 % of strain; it lasts longer in strain at higher rates). Default 0.05 %")
        .with_range(Some(0.0), None),
    bed_file: Variable::parameter("bed_file", Value::String(String::new()), "", "a bed file of `powderfmu bed prepare`, prepared in a die (floor, die, piston): its material and consolidation_stress make the specimen; several separated by ';', one per replica; empty: the FMU's own (resources/specimen.pfbed: 004 Ch. 6's material, 4000 spheres in a 15 mm die, 10 kPa; specimen_2 and specimen_3.pfbed its other fills)"),
    threads: Variable::parameter("threads", Value::Integer(2), "", "threads of the bed engine's force loop, in [1, 256] (results differ from one thread's by round-off, which the specimen's dynamics then grow)"),
    time_step: Variable::parameter("time_step", Value::Real(0.0), "s", "the bed engine's time step, refused above the bed's stability limit; 0 = the bed's own (its scene's time_step or rayleigh_fraction of its stability limit)")
        .with_range(Some(0.0), None),
    unconfined_yield_strength_standard_error_over_specimens: Variable::output("unconfined_yield_strength_standard_error_over_specimens", VarType::Real, "Pa", "with replicas > 1: the standard error of unconfined_yield_strength from the specimens' spread, s / sqrt(replicas) with s the sample standard deviation of their sigma_c; it holds the specimen-to-specimen scatter one specimen cannot show. 0 with one replica, and until every specimen has a window"),
    replicas: Variable::parameter("replicas", Value::Integer(1), "", "how many independently prepared specimens the test runs on, one after the other within each step, each with the same settings: the FMU's specimens (1 to 3: the shipped specimen's scene with fill seeds 1-3), or the beds bed_file lists, which must be fills of one scene (only `seed` may differ; another is refused, naming the key). Every output is then the mean over the specimens (kinetic_energy too) and unconfined_yield_strength_standard_error_over_specimens their spread; the first specimen reads what it reads alone, to the bit; the cost is replicas times one specimen's"),
}

/// The unit (Co-Simulation only): its variables and time.
pub fn info() -> UnitInfo {
    UnitInfo {
        model_identifier: MODEL_IDENTIFIER,
        description: "Unconfined compression of a pre-consolidated bed of cohesive spheres by DEM: sigma_c and ff_c (powderfmu)",
        variables: {
            let mut v = own_variables();
            v.push(Variable::time());
            v
        },
        n_states: 0,
        n_event_indicators: 0,
        model_exchange: false,
        can_interpolate_inputs: false,
        returns_early: false,
        // The default test: the platen's approach (0.02 mean diameters at 22.8 mm/s) and 10 % strain at
        // 1/s, about 0.1 s; the specimen is not stepped once the test has ended.
        stop_time: 0.11,
        step_size: 1e-3,
        new_model: |_, resources| {
            Box::new(UnconfinedCompression {
                resources: resources.map(Path::to_path_buf),
                specimens: Vec::new(),
                events: vec![],
                reported_done: false,
                reported_tenths: 0,
            })
        },
        guid_cache: std::sync::OnceLock::new(),
        token_cache: std::sync::OnceLock::new(),
    }
}

/// The model of UnconfinedCompression: one specimen or several replicas, each stepped by the bed engine
/// over each communication step.
pub struct UnconfinedCompression {
    resources: Option<PathBuf>,
    /// The specimens, the first the reference; empty before initialisation.
    specimens: Vec<Specimen>,
    events: Vec<String>,
    /// Whether the end of the test has been reported (`take_events`).
    reported_done: bool,
    /// Tenths of max_strain reported so far (progress, `take_events`).
    reported_tenths: u32,
}

fn variable(name: &'static str, why: String) -> UnitError {
    UnitError::Variable { name, why }
}

impl UnconfinedCompression {
    /// The specimens' bed files, one per replica: `bed_file`'s, or the FMU's own.
    fn bed_paths(&self, values: &[Value]) -> Result<Vec<PathBuf>, UnitError> {
        let replicas = super::replica_count(values[REFS.replicas].as_real())?;
        if let Some(paths) = super::listed_beds(values[REFS.bed_file].as_str(), replicas)? {
            return Ok(paths);
        }
        let shipped = 1 + SPECIMEN_REPLICAS.len();
        if replicas > shipped {
            return Err(variable(
                "replicas",
                format!(
                    "parameter `replicas` = {replicas} is out of range: the FMU ships {shipped} specimens, allowed [1, {shipped}]; more: prepare them (`powderfmu bed prepare` with other seeds) and list them in bed_file"
                ),
            ));
        }
        match &self.resources {
            Some(dir) => {
                let names = std::iter::once(RESOURCE_SPECIMEN).chain(SPECIMEN_REPLICAS.iter().map(|r| r.0));
                Ok(names.take(replicas).map(|n| dir.join(n)).collect())
            }
            None => Err(variable(
                "bed_file",
                "no bed_file given and the host named no resources folder (fmuResourceLocation) holding the FMU's specimen".into(),
            )),
        }
    }

    /// Whether every specimen's test has ended.
    fn done(&self) -> bool {
        !self.specimens.is_empty() && self.specimens.iter().all(|s| s.test.done)
    }

    fn threads(values: &[Value]) -> Result<usize, UnitError> {
        super::engine_threads(values[REFS.threads].as_real())
    }

    fn setup(values: &[Value]) -> Result<Setup, UnitError> {
        let setup = Setup {
            strain_rate: values[REFS.strain_rate].as_real(),
            max_strain: values[REFS.max_strain].as_real(),
            free_time: values[REFS.free_time].as_real(),
            window: values[REFS.window].as_real(),
            reading_start: values[REFS.reading_start].as_real(),
        };
        setup.check()?;
        Ok(setup)
    }

    /// What the outputs read of the specimens: one specimen's own reading, or the mean over the
    /// specimens once each has a window (`Reading::unconfined_yield_strength`).
    fn reading(&self) -> Option<Aggregate> {
        let readings: Vec<_> = self.specimens.iter().map(|s| s.test.reading()).collect::<Option<_>>()?;
        if let [r] = readings.as_slice() {
            let own = r.unconfined_yield_strength;
            return Some(Aggregate {
                sigma_c: own.mean,
                standard_error: own.standard_error,
                over_specimens: 0.0,
                strain_at_failure: r.strain_at_failure,
                failed: r.failed,
                flow_function: r.flow_function,
                each: vec![own.mean],
            });
        }
        let n = readings.len() as f64;
        let each: Vec<f64> = readings.iter().map(|r| r.unconfined_yield_strength.mean).collect();
        let over = over_beds(&each);
        let sigma_1 = self.mean_of(|s| s.test.start.consolidation_stress);
        Some(Aggregate {
            sigma_c: over.mean,
            standard_error: independent(readings.iter().map(|r| r.unconfined_yield_strength.standard_error)),
            over_specimens: over.standard_error,
            strain_at_failure: readings.iter().map(|r| r.strain_at_failure).sum::<f64>() / n,
            failed: readings.iter().all(|r| r.failed),
            flow_function: if over.mean > 0.0 { sigma_1 / over.mean } else { f64::INFINITY },
            each,
        })
    }

    /// Tenths of max_strain the least advanced specimen has reached (the progress reports').
    fn tenths(&self) -> u32 {
        let Some(first) = self.specimens.first() else { return 0 };
        let least = self.specimens.iter().map(|s| s.test.samples.last().map_or(0.0, |x| x.strain)).fold(f64::INFINITY, f64::min);
        ((least / first.test.setup.max_strain) * 10.0).floor().clamp(0.0, 10.0) as u32
    }

    /// The mean over the specimens of `f` (one specimen's own value, to the bit).
    fn mean_of(&self, f: impl Fn(&Specimen) -> f64) -> f64 {
        self.specimens.iter().map(f).sum::<f64>() / self.specimens.len() as f64
    }

    /// Progress at every tenth of max_strain reached by the least advanced specimen (the default test takes
    /// minutes), then the end.
    fn report(&mut self) {
        let Some(first) = self.specimens.first() else { return };
        let max_strain = first.test.setup.max_strain;
        let tenths = self.tenths();
        let done = self.done();
        if tenths > self.reported_tenths && !done {
            self.reported_tenths = tenths;
            let last = first.test.samples.last().copied().unwrap_or_default();
            let so_far = first.test.reading().map_or(0.0, |r| r.unconfined_yield_strength.mean);
            let of = if self.specimens.len() > 1 { format!(" (the first of {} specimens)", self.specimens.len()) } else { String::new() };
            self.events.push(format!(
                "strain {:.4} of max_strain {max_strain} (t = {:.4e} s){of}: axial stress {:.4e} Pa, the largest window mean so far {so_far:.4e} Pa",
                last.strain, last.time, last.stress
            ));
        }
        if !done || self.reported_done {
            return;
        }
        self.reported_done = true;
        let last = first.test.samples.last().map_or(0.0, |x| x.strain);
        let window = first.test.setup.window;
        let message = match (self.specimens.as_slice(), first.test.reading(), self.reading()) {
            ([_], Some(r), _) => format!(
                "the test has ended at strain {last:.4}: sigma_c = {:.4e} +- {:.2e} Pa (standard error; the largest mean over {} strain, {} samples) at strain {:.4}, {}; ff_c = sigma_1 / sigma_c = {:.3}",
                r.unconfined_yield_strength.mean,
                r.unconfined_yield_strength.standard_error,
                window,
                r.unconfined_yield_strength.samples,
                r.strain_at_failure,
                if r.failed { "failed" } else { "not failed by max_strain: sigma_c is a lower bound" },
                r.flow_function
            ),
            (many, _, Some(a)) if many.len() > 1 => format!(
                "the test has ended on {} specimens: sigma_c = {:.4e} Pa, +- {:.2e} Pa from their spread (standard error over the specimens), +- {:.2e} Pa from their own fluctuations; each {} Pa; {}; ff_c = sigma_1 / sigma_c = {:.3}",
                many.len(),
                a.sigma_c,
                a.over_specimens,
                a.standard_error,
                a.each.iter().map(|x| format!("{x:.4e}")).collect::<Vec<_>>().join(", "),
                if a.failed { "every one failed" } else { "not every one failed by max_strain: sigma_c is a lower bound" },
                a.flow_function
            ),
            _ => format!("the test has ended at strain {last:.4} without a window of loaded samples on every specimen: no sigma_c"),
        };
        self.events.push(message);
    }
}

/// The readings the outputs give: one specimen's, or the specimens' mean.
struct Aggregate {
    sigma_c: f64,
    /// The specimens' own standard errors combined as independent [Pa].
    standard_error: f64,
    /// The standard error of the mean from the specimens' spread (0 for one) [Pa].
    over_specimens: f64,
    strain_at_failure: f64,
    failed: bool,
    flow_function: f64,
    /// Each specimen's sigma_c [Pa].
    each: Vec<f64>,
}

impl Model for UnconfinedCompression {
    fn initialize(&mut self, values: &[Value], _t0: f64, _model_exchange: bool) -> Result<(), UnitError> {
        let setup = Self::setup(values)?;
        let threads = Self::threads(values)?;
        let paths = self.bed_paths(values)?;
        let dt = values[REFS.time_step].as_real();
        let mut specimens: Vec<Specimen> = Vec::with_capacity(paths.len());
        for (k, path) in paths.iter().enumerate() {
            let which = if paths.len() > 1 { format!("replica {} of {}: ", k + 1, paths.len()) } else { String::new() };
            let (engine, scene) = file::load(path, Some(threads)).map_err(|e| match e {
                BedError::Setup(why) => variable("bed_file", format!("{which}bed_file {}: {why}", path.display())),
                other => UnitError::from(other),
            })?;
            if let Some(first) = specimens.first() {
                check_replica(&first.scene, &scene).map_err(|why| variable("bed_file", format!("{which}bed_file {}: {why}", path.display())))?;
            }
            let specimen = Specimen::new(engine, scene, setup, (dt != 0.0).then_some(dt)).map_err(|e| match e {
                // A bed not prepared in a die is the file's fault; the settings and time_step name themselves.
                BedError::Param(p @ ParamError::Inconsistent { name: "bed", .. }) => {
                    variable("bed_file", format!("{which}bed_file {}: {p}", path.display()))
                }
                BedError::Param(p) => UnitError::Param(p),
                BedError::Setup(why) => variable("bed_file", format!("{which}bed_file {}: {why}", path.display())),
            })?;
            let s = &specimen.test.start;
            self.events.push(format!(
                "{which}specimen {}: {} spheres, H_0 = {:.4e} m, solid fraction {:.4}, consolidated to sigma_1 = {:.4e} Pa, its own weight {:.3e} Pa on its base; time step {:.4e} s; the platen at {} 1/s to strain {}",
                path.display(),
                specimen.engine.particles().len(),
                s.height,
                s.solid_fraction,
                s.consolidation_stress,
                s.self_weight_stress,
                specimen.engine.dt(),
                setup.strain_rate,
                setup.max_strain
            ));
            specimens.push(specimen);
        }
        self.specimens = specimens;
        self.reported_done = false;
        self.reported_tenths = 0;
        Ok(())
    }

    fn compute(&mut self, values: &mut [Value], _between_events: bool) {
        if self.specimens.is_empty() {
            return;
        }
        let last = |s: &Specimen| s.test.samples.last().copied().unwrap_or_default();
        let a = self.reading();
        let (sigma_c, error, over, at, failed, ff_c) = match &a {
            Some(a) => (a.sigma_c, a.standard_error, a.over_specimens, a.strain_at_failure, a.failed, a.flow_function),
            None => (0.0, 0.0, 0.0, 0.0, false, f64::INFINITY),
        };
        for (vr, x) in [
            (REFS.axial_stress, self.mean_of(|s| last(s).stress)),
            (REFS.axial_strain, self.mean_of(|s| last(s).strain)),
            (REFS.unconfined_yield_strength, sigma_c),
            (REFS.unconfined_yield_strength_standard_error, error),
            (REFS.unconfined_yield_strength_standard_error_over_specimens, over),
            (REFS.strain_at_failure, at),
            (REFS.flow_function, ff_c),
            (REFS.consolidation_stress, self.mean_of(|s| s.test.start.consolidation_stress)),
            (REFS.solid_fraction, self.mean_of(|s| s.test.start.solid_fraction)),
            (REFS.specimen_height, self.mean_of(|s| s.test.start.height)),
            (REFS.self_weight_stress, self.mean_of(|s| s.test.start.self_weight_stress)),
            (REFS.kinetic_energy, self.mean_of(|s| s.engine.particles().kinetic_energy() / s.scene.die_sector)),
        ] {
            values[vr] = Value::Real(x);
        }
        values[REFS.failed] = Value::Boolean(failed);
        values[REFS.test_state] = Value::Integer(i32::from(self.done()));
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

    fn do_step(&mut self, _values: &[Value], _t: f64, h: f64) -> Result<(), UnitError> {
        if self.specimens.is_empty() {
            return Err(UnitError::NotInitialized);
        }
        for s in &mut self.specimens {
            s.advance(h);
        }
        self.report();
        Ok(())
    }

    /// Every specimen's state (`Specimen::save`), in order; nothing before initialisation.
    fn save(&self) -> Result<Vec<u8>, UnitError> {
        if self.specimens.is_empty() {
            return Ok(Vec::new());
        }
        let states: Vec<Vec<u8>> =
            self.specimens.iter().map(Specimen::save).collect::<Result<_, _>>().map_err(|e| UnitError::SavedState(e.to_string()))?;
        crate::codec::to_bytes(&states).map_err(|e| UnitError::SavedState(format!("the specimens' states cannot be saved: {e}")))
    }

    fn take_events(&mut self) -> Vec<String> {
        std::mem::take(&mut self.events)
    }

    fn restore(&mut self, values: &[Value], bytes: &[u8]) -> Result<(), UnitError> {
        if bytes.is_empty() {
            self.specimens.clear();
            return Ok(());
        }
        let threads = Self::threads(values)?;
        let states: Vec<Vec<u8>> =
            crate::codec::from_bytes(bytes).map_err(|e| UnitError::SavedState(format!("the saved specimens cannot be read: {e}")))?;
        if states.is_empty() {
            return Err(UnitError::SavedState("the saved state holds no specimen".into()));
        }
        let specimens = states
            .iter()
            .map(|b| Specimen::restore(b, Some(threads)))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| UnitError::SavedState(e.to_string()))?;
        self.specimens = specimens;
        self.reported_done = self.done();
        self.reported_tenths = self.tenths();
        Ok(())
    }
}
