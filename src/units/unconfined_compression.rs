//! UnconfinedCompression (Co-Simulation): the uniaxial tester of `004` Sec. 2.1 (Fig. 2.1) on a bed of
//! cohesive spheres consolidated in a die to sigma_1: the die removed, the specimen loaded by a platen
//! at a constant strain rate until it fails. Its peak stress is the unconfined yield strength sigma_c
//! and sigma_1 / sigma_c the flowability ff_c (Eq. 2.1). The test, its readings and their definitions
//! are `bed::compression`; the specimen is a prepared bed file (`powderfmu bed prepare`), whose material
//! and consolidation stress it carries: another powder or another sigma_1 is another bed.

use super::variables::{Value, VarType, Variable};
use super::{Model, UnitError, UnitInfo};
use crate::bed::compression::{Setup, Specimen};
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

variable_table! {
    axial_stress: Variable::output("axial_stress", VarType::Real, "Pa", "the platen's force over the die's cross-section, compression positive: the mean over the last sample (100 engine steps); 0 before the platen touches"),
    axial_strain: Variable::output("axial_strain", VarType::Real, "", "(z_touch - z) / z_touch, z the platen's height and z_touch its height at its first contact with the specimen"),
    unconfined_yield_strength: Variable::output("unconfined_yield_strength", VarType::Real, "Pa", "sigma_c (004 Sec. 2.1): the largest mean of axial_stress over a window of `window` strain so far (not the largest sample, which the force's fluctuation would bias high); 0 until a window of loaded samples exists. With failed false it is a lower bound"),
    unconfined_yield_strength_standard_error: Variable::output("unconfined_yield_strength_standard_error", VarType::Real, "Pa", "standard error of unconfined_yield_strength from the fluctuation of the window's samples, sqrt(sigma^2 tau / n) with tau their integrated autocorrelation time (as plateau_hardness_standard_error of BallIndentation); on the shipped specimen it covers the scatter between realisations of the test (1.0 Pa against 1.7-2.8 Pa); it holds neither the specimen-to-specimen scatter (12 % between three fills of the shipped specimen's scene) nor the specimen's size and rate (1/s reads 7 % above the quasi-static value of 0.03-0.3/s), docs/units/UnconfinedCompression.md"),
    strain_at_failure: Variable::output("strain_at_failure", VarType::Real, "", "axial strain at the middle of the window of unconfined_yield_strength"),
    failed: Variable::output("failed", VarType::Boolean, "", "true once the window mean has fallen below 0.8 of its peak, one window past it (the specimen has failed; the test then ends); false while it has not, and at max_strain when it never did: unconfined_yield_strength is then a lower bound"),
    flow_function: Variable::output("flow_function", VarType::Real, "", "ff_c = sigma_1 / sigma_c (004 Eq. 2.1) with sigma_1 = consolidation_stress; infinite while sigma_c is 0"),
    consolidation_stress: Variable::output("consolidation_stress", VarType::Real, "Pa", "sigma_1: the stress the specimen was consolidated to in its die (the bed's preparation)"),
    solid_fraction: Variable::output("solid_fraction", VarType::Real, "", "the spheres' volume over the die's cross-section times specimen_height, when the die was removed"),
    specimen_height: Variable::output("specimen_height", VarType::Real, "m", "H_0, the specimen's height when the die was removed (the strain rate is relative to it)"),
    self_weight_stress: Variable::output("self_weight_stress", VarType::Real, "Pa", "the specimen's weight over the die's cross-section: a specimen weaker than it slumps before the platen loads it"),
    kinetic_energy: Variable::output("kinetic_energy", VarType::Real, "J", "kinetic energy of the specimen's spheres, translation and rotation (the whole die's for a sector bed)"),
    test_state: Variable::output("test_state", VarType::Integer, "", "0 loading, 1 done (failed, or max_strain reached); the specimen is not stepped once done"),
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
    bed_file: Variable::parameter("bed_file", Value::String(String::new()), "", "a bed file of `powderfmu bed prepare`, prepared in a die (floor, die, piston): its material and consolidation_stress make the specimen; empty: the FMU's own (resources/specimen.pfbed: 004 Ch. 6's material, 4000 spheres in a 15 mm die, 10 kPa)"),
    threads: Variable::parameter("threads", Value::Integer(2), "", "threads of the bed engine's force loop, in [1, 256] (results differ from one thread's by round-off, which the specimen's dynamics then grow)"),
    time_step: Variable::parameter("time_step", Value::Real(0.0), "s", "the bed engine's time step, refused above the bed's stability limit; 0 = the bed's own (its scene's time_step or rayleigh_fraction of its stability limit)")
        .with_range(Some(0.0), None),
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
                specimen: None,
                events: vec![],
                reported_done: false,
                reported_tenths: 0,
            })
        },
        guid_cache: std::sync::OnceLock::new(),
        token_cache: std::sync::OnceLock::new(),
    }
}

/// The model of UnconfinedCompression: one specimen, stepped by the bed engine over each communication step.
pub struct UnconfinedCompression {
    resources: Option<PathBuf>,
    specimen: Option<Specimen>,
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
    fn bed_path(&self, values: &[Value]) -> Result<PathBuf, UnitError> {
        let given = values[REFS.bed_file].as_str().trim();
        if !given.is_empty() {
            return Ok(PathBuf::from(given));
        }
        match &self.resources {
            Some(dir) => Ok(dir.join(RESOURCE_SPECIMEN)),
            None => Err(variable(
                "bed_file",
                "no bed_file given and the host named no resources folder (fmuResourceLocation) holding the FMU's specimen".into(),
            )),
        }
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

    /// Progress at every tenth of max_strain reached (the default test takes minutes), then the end.
    fn report(&mut self) {
        let Some(s) = &self.specimen else { return };
        let last = s.test.samples.last().copied().unwrap_or_default();
        let tenths = ((last.strain / s.test.setup.max_strain) * 10.0).floor().clamp(0.0, 10.0) as u32;
        if tenths > self.reported_tenths && !s.test.done {
            self.reported_tenths = tenths;
            let so_far = s.test.reading().map_or(0.0, |r| r.unconfined_yield_strength.mean);
            self.events.push(format!(
                "strain {:.4} of max_strain {} (t = {:.4e} s): axial stress {:.4e} Pa, the largest window mean so far {so_far:.4e} Pa",
                last.strain, s.test.setup.max_strain, last.time, last.stress
            ));
        }
        if !s.test.done || self.reported_done {
            return;
        }
        self.reported_done = true;
        let last = s.test.samples.last().map_or(0.0, |x| x.strain);
        self.events.push(match s.test.reading() {
            Some(r) => format!(
                "the test has ended at strain {last:.4}: sigma_c = {:.4e} +- {:.2e} Pa (standard error; the largest mean over {} strain, {} samples) at strain {:.4}, {}; ff_c = sigma_1 / sigma_c = {:.3}",
                r.unconfined_yield_strength.mean,
                r.unconfined_yield_strength.standard_error,
                s.test.setup.window,
                r.unconfined_yield_strength.samples,
                r.strain_at_failure,
                if r.failed { "failed" } else { "not failed by max_strain: sigma_c is a lower bound" },
                r.flow_function
            ),
            None => format!("the test has ended at strain {last:.4} without a window of loaded samples: no sigma_c"),
        });
    }
}

impl Model for UnconfinedCompression {
    fn initialize(&mut self, values: &[Value], _t0: f64, _model_exchange: bool) -> Result<(), UnitError> {
        let setup = Self::setup(values)?;
        let threads = Self::threads(values)?;
        let path = self.bed_path(values)?;
        let dt = values[REFS.time_step].as_real();
        let (engine, scene) = file::load(&path, Some(threads)).map_err(|e| match e {
            BedError::Setup(why) => variable("bed_file", format!("bed_file {}: {why}", path.display())),
            other => UnitError::from(other),
        })?;
        let specimen = Specimen::new(engine, scene, setup, (dt != 0.0).then_some(dt)).map_err(|e| match e {
            // A bed not prepared in a die is the file's fault; the settings and time_step name themselves.
            BedError::Param(p @ ParamError::Inconsistent { name: "bed", .. }) => variable("bed_file", format!("bed_file {}: {p}", path.display())),
            BedError::Param(p) => UnitError::Param(p),
            BedError::Setup(why) => variable("bed_file", format!("bed_file {}: {why}", path.display())),
        })?;
        let s = &specimen.test.start;
        self.events.push(format!(
            "specimen {}: {} spheres, H_0 = {:.4e} m, solid fraction {:.4}, consolidated to sigma_1 = {:.4e} Pa, its own weight {:.3e} Pa on its base; time step {:.4e} s; the platen at {} 1/s to strain {}",
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
        self.specimen = Some(specimen);
        self.reported_done = false;
        self.reported_tenths = 0;
        Ok(())
    }

    fn compute(&mut self, values: &mut [Value], _between_events: bool) {
        let Some(s) = &self.specimen else { return };
        let t = &s.test;
        let last = t.samples.last().copied().unwrap_or_default();
        let reading = t.reading();
        let (sigma_c, error, at, failed, ff_c) = match &reading {
            Some(r) => (r.unconfined_yield_strength.mean, r.unconfined_yield_strength.standard_error, r.strain_at_failure, r.failed, r.flow_function),
            None => (0.0, 0.0, 0.0, false, f64::INFINITY),
        };
        for (vr, x) in [
            (REFS.axial_stress, last.stress),
            (REFS.axial_strain, last.strain),
            (REFS.unconfined_yield_strength, sigma_c),
            (REFS.unconfined_yield_strength_standard_error, error),
            (REFS.strain_at_failure, at),
            (REFS.flow_function, ff_c),
            (REFS.consolidation_stress, t.start.consolidation_stress),
            (REFS.solid_fraction, t.start.solid_fraction),
            (REFS.specimen_height, t.start.height),
            (REFS.self_weight_stress, t.start.self_weight_stress),
            (REFS.kinetic_energy, s.engine.particles().kinetic_energy() / s.scene.die_sector),
        ] {
            values[vr] = Value::Real(x);
        }
        values[REFS.failed] = Value::Boolean(failed);
        values[REFS.test_state] = Value::Integer(i32::from(t.done));
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
        let s = self.specimen.as_mut().ok_or(UnitError::NotInitialized)?;
        s.advance(h);
        self.report();
        Ok(())
    }

    fn save(&self) -> Result<Vec<u8>, UnitError> {
        match &self.specimen {
            Some(s) => s.save().map_err(|e| UnitError::SavedState(e.to_string())),
            None => Ok(Vec::new()),
        }
    }

    fn take_events(&mut self) -> Vec<String> {
        std::mem::take(&mut self.events)
    }

    fn restore(&mut self, values: &[Value], bytes: &[u8]) -> Result<(), UnitError> {
        if bytes.is_empty() {
            self.specimen = None;
            return Ok(());
        }
        let threads = Self::threads(values)?;
        let s = Specimen::restore(bytes, Some(threads)).map_err(|e| UnitError::SavedState(e.to_string()))?;
        self.reported_done = s.test.done;
        let strain = s.test.samples.last().map_or(0.0, |x| x.strain);
        self.reported_tenths = ((strain / s.test.setup.max_strain) * 10.0).floor().clamp(0.0, 10.0) as u32;
        self.specimen = Some(s);
        Ok(())
    }
}
