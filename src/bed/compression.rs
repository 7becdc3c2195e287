//! The unconfined (uniaxial) compression test (`004` Sec. 2.1, Fig. 2.1) on a prepared bed: the bulk
//! consolidated in the die to sigma_1 (the bed's preparation, `consolidation_stress`), the die removed,
//! the specimen loaded axially by the top platen at a constant strain rate until it fails. Its peak
//! stress is the unconfined yield strength sigma_c, and sigma_1 / sigma_c the flowability ff_c (Eq. 2.1).
//!
//! - The die is removed by taking its cylinder's radius to infinity (no sphere can touch it); the floor
//!   stays, frictionless unless the scene's particle-wall pair says otherwise, as the seed's tester's
//!   low-friction base. Gravity stays: the specimen carries its own weight (`Start::self_weight_stress`),
//!   which matters where sigma_c is small (a specimen weaker than its weight slumps before it is loaded).
//! - The platen is the preparation's piston, put 0.02 mean diameters above the bed and moved down at
//!   strain_rate x H_0 (H_0 the specimen's height when the die is removed). Strain is
//!   (z_touch - z) / z_touch from the platen's height at its touch: the end of the first sample whose
//!   mean stress reaches `TOUCH` of the specimen's own weight stress, the bulk meeting it, not a lone
//!   sphere standing above a rough top (on the 20 kPa Ch. 6 specimen such a sphere met it 0.09 % of
//!   strain before the bulk, with sample means under 40 Pa and single steps above the threshold; the
//!   bulk's arrival is an impact of kPa), or, for a specimen that never carries that much (one with no
//!   strength to speak of, which slumps), where the platen has come `TOUCH_DEPTH` of the specimen's
//!   height below its top; stress the platen's force
//!   over the die's cross-section (the whole die's for a sector bed), averaged over each `CHECK_EVERY`
//!   steps.
//! - sigma_c is the largest mean stress over a window of `Setup::window` strain, with the standard error
//!   of that window's samples (`series`): not the largest sample, which a force fluctuating by tens of
//!   per cent would bias high. The window maximum of a noisy curve is still biased upward by about one
//!   standard error; the reading says how many samples it holds.
//! - The specimen has failed when the window mean has fallen below `SOFTENING` of its peak, at least one
//!   window past the peak; the test then stops. A test that reaches max_strain without that reports the
//!   largest window mean as a lower bound (`Reading::failed` false).

use super::any::{AnyEngine, BedError};
use super::file::{self, BedFile};
use super::prepare::{bed_height, DIE, PISTON};
use super::scene::BedScene;
use super::series::{self, MeanEstimate};
use super::walls::Shape;
use super::Vec3;
use crate::error::ParamError;

/// Engine steps per sample.
pub const CHECK_EVERY: u64 = 100;
/// The fraction of the peak the window mean falls to when the specimen has failed.
pub const SOFTENING: f64 = 0.8;
/// The platen touches the specimen when a sample's mean stress reaches this fraction of the specimen's
/// own weight stress (module docs).
pub const TOUCH: f64 = 0.5;
/// Or when the platen has come this fraction of the specimen's height below its top (module docs).
pub const TOUCH_DEPTH: f64 = 0.01;

/// The test's settings.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Setup {
    /// Axial strain rate of the platen, relative to the specimen's height H_0 [1/s].
    pub strain_rate: f64,
    /// The test ends here if the specimen has not failed before [-].
    pub max_strain: f64,
    /// Time the specimen stands free between the die's removal and the platen's start [s].
    pub free_time: f64,
    /// Width of the strain window over which the stress is averaged for the peak [-].
    pub window: f64,
    /// Strain from which the samples are read for the peak and the failure: the platen's arrival is an
    /// impact whose stress (inertia, not strength) the reading must not hold [-].
    pub reading_start: f64,
}

impl Default for Setup {
    /// 1/s, the seed's consolidation rate (004 Sec. 6.1); to 10 % strain; loaded at once; a window of
    /// 0.05 % strain read from 0.05 % on. At 1/s the shipped specimens' arrival transient is over by
    /// 0.015 % and their peak lasts 0.1-0.2 % of strain, which a wider window averages with the softening
    /// after it (docs/units/UnconfinedCompression.md).
    fn default() -> Setup {
        Setup::DEFAULT
    }
}

impl Setup {
    /// The defaults (`Default`), as a constant for the units' start values.
    pub const DEFAULT: Setup = Setup { strain_rate: 1.0, max_strain: 0.1, free_time: 0.0, window: 0.0005, reading_start: 0.0005 };

    /// Every value in its range, or the first that is not, by name.
    pub fn check(&self) -> Result<(), ParamError> {
        let out = |name: &'static str, value: f64, allowed: &str| ParamError::OutOfRange { name, value, allowed: allowed.into() };
        if !(self.strain_rate > 0.0 && self.strain_rate <= 1e3) {
            return Err(out("strain_rate", self.strain_rate, "(0, 1e3] 1/s"));
        }
        if !(self.max_strain > 0.0 && self.max_strain <= 0.9) {
            return Err(out("max_strain", self.max_strain, "(0, 0.9]"));
        }
        if !(self.free_time >= 0.0 && self.free_time <= 10.0) {
            return Err(out("free_time", self.free_time, "[0, 10] s"));
        }
        if !(self.window > 0.0 && self.window < self.max_strain) {
            return Err(out("window", self.window, "(0, max_strain)"));
        }
        if !(self.reading_start >= 0.0 && self.reading_start + self.window < self.max_strain) {
            return Err(out("reading_start", self.reading_start, "[0, max_strain - window)"));
        }
        Ok(())
    }
}

/// The specimen when the die was removed.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Start {
    /// Height H_0 [m].
    pub height: f64,
    /// Solid fraction: sphere volume over the die's cross-section times H_0 [-].
    pub solid_fraction: f64,
    /// The specimen's weight over the die's cross-section: the stress its own weight puts on its base [Pa].
    pub self_weight_stress: f64,
    /// The consolidation stress of the bed's preparation, sigma_1 [Pa].
    pub consolidation_stress: f64,
}

/// One sample of the stress-strain curve.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    /// Time [s].
    pub time: f64,
    /// Axial strain [-] (0 until the platen touches).
    pub strain: f64,
    /// Platen stress, mean over the sample's steps [Pa].
    pub stress: f64,
}

/// What the test reads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// sigma_c: the largest window mean of the stress, with its standard error [Pa].
    pub unconfined_yield_strength: MeanEstimate,
    /// The strain at the middle of that window [-].
    pub strain_at_failure: f64,
    /// Whether the specimen failed (the stress fell to `SOFTENING` of its peak); if not, sigma_c is a lower
    /// bound.
    pub failed: bool,
    /// ff_c = sigma_1 / sigma_c (004 Eq. 2.1) [-]; infinite for sigma_c <= 0.
    pub flow_function: f64,
}

/// The test on a prepared bed.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Compression {
    /// The settings.
    pub setup: Setup,
    /// The specimen at the start.
    pub start: Start,
    /// The curve, one sample per `CHECK_EVERY` steps from the platen's start.
    pub samples: Vec<Sample>,
    /// The platen's height at its touch (`TOUCH`) [m].
    touch: Option<f64>,
    /// The platen's height at which it touches whatever it carries (`TOUCH_DEPTH`) [m].
    touch_at_the_latest: f64,
    /// Sum of the stress over the current sample's steps, and their count.
    sum: (f64, u64),
    /// Whether the test has ended (failure or max_strain).
    pub done: bool,
    /// The engine's time step [s]: a sample spans `CHECK_EVERY` of them.
    dt: f64,
}

impl Compression {
    /// Removes the die of a prepared bed, lets the specimen stand `free_time`, and starts the platen.
    pub fn new(e: &mut AnyEngine, scene: &BedScene, setup: Setup) -> Result<Compression, ParamError> {
        setup.check()?;
        if !matches!(e.walls().get(DIE).map(|w| w.shape), Some(Shape::Cylinder { .. })) || e.walls().len() <= PISTON {
            return Err(ParamError::Inconsistent { name: "bed", why: "not a prepared bed in a die (floor, die, piston)".into() });
        }
        // The window's mean needs samples enough for its standard error (`series::MIN_SAMPLES`); how many
        // it holds depends on the bed's step and the rate, so a window too narrow for them is refused.
        let per_sample = setup.strain_rate * e.dt() * CHECK_EVERY as f64;
        if setup.window / per_sample < series::MIN_SAMPLES as f64 - 0.5 {
            return Err(ParamError::OutOfRange {
                name: "window",
                value: setup.window,
                allowed: format!(
                    "[{:.3e}, max_strain): at least {} samples of {CHECK_EVERY} engine steps, {per_sample:.3e} of strain each at this bed's step {:.3e} s and strain_rate {} 1/s",
                    (series::MIN_SAMPLES as f64 - 0.5) * per_sample,
                    series::MIN_SAMPLES,
                    e.dt(),
                    setup.strain_rate
                ),
            });
        }
        let area = scene.sector_area();
        let p = e.particles();
        let height = bed_height(p);
        let volume: f64 = p.radius.iter().map(|r| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3)).sum();
        let solid_fraction = volume / (area * height);
        // From the masses, not the floor's force: a cohesive bed just unloaded can hang in the die with
        // its floor force far from its weight (the shipped Ch. 6 quarter bed: 0-1 Pa against 246 Pa).
        let self_weight_stress = p.mass.iter().sum::<f64>() * scene.gravity / area;
        e.walls_mut()[DIE].shape = Shape::Cylinder { radius: f64::INFINITY };
        e.rebuild();
        let free_steps = (setup.free_time / e.dt()).ceil() as u64;
        e.run(free_steps);
        let top = bed_height(e.particles());
        let platen = &mut e.walls_mut()[PISTON];
        platen.position[2] = top + 0.02 * scene.size_distribution.mean_diameter();
        platen.velocity = Vec3::new(0.0, 0.0, -setup.strain_rate * height);
        e.rebuild();
        let start = Start { height, solid_fraction, self_weight_stress, consolidation_stress: scene.consolidation_stress };
        let touch_at_the_latest = top - TOUCH_DEPTH * height;
        Ok(Compression { setup, start, samples: Vec::new(), touch: None, touch_at_the_latest, sum: (0.0, 0), done: false, dt: e.dt() })
    }

    /// Runs `steps` engine steps (or fewer, if the test ends), sampling every `CHECK_EVERY`. The steps run
    /// in one go (`AnyEngine::run_while`), the platen read after each: the same bits as a call per step,
    /// and 7 % less time per step on the shipped specimen at two threads (99.6 against 106.8 us, `bed
    /// compress` to 1 % strain, two runs each; 0.2 against 0.4 s on the suite's 800-sphere stand-in).
    pub fn advance(&mut self, e: &mut AnyEngine, scene: &BedScene, steps: u64) {
        if self.done {
            return;
        }
        let area = scene.sector_area();
        e.run_while(steps, |walls, time| {
            // piston_stress(e, scene), from the walls the step left.
            self.observe(walls[PISTON].force[2] / area, walls[PISTON].position[2], time);
            !self.done
        });
    }

    /// One step's platen stress [Pa] and height [m] at `time` [s]: the touch, the sample's sum, and every
    /// `CHECK_EVERY` steps a sample and whether the test has ended.
    fn observe(&mut self, stress: f64, z: f64, time: f64) {
        self.sum = (self.sum.0 + stress, self.sum.1 + 1);
        if self.sum.1 == CHECK_EVERY {
            let mean = self.sum.0 / CHECK_EVERY as f64;
            let carries = mean > 0.0 && mean >= TOUCH * self.start.self_weight_stress;
            if self.touch.is_none() && (carries || z <= self.touch_at_the_latest) {
                self.touch = Some(z);
            }
            let strain = self.touch.map_or(0.0, |t| (t - z) / t);
            self.samples.push(Sample { time, strain, stress: mean });
            self.sum = (0.0, 0);
            self.done = strain >= self.setup.max_strain || self.has_failed();
        }
    }

    /// Samples per window.
    fn window_samples(&self) -> usize {
        ((self.setup.window / (self.setup.strain_rate * self.dt * CHECK_EVERY as f64)).round() as usize).max(1)
    }

    /// The part of the curve the reading holds: from the first sample after the platen's touch at or
    /// beyond `reading_start`.
    fn loaded(&self) -> &[Sample] {
        let start = self.setup.reading_start;
        let first = self.samples.iter().position(|s| s.strain > 0.0 && s.strain >= start).unwrap_or(self.samples.len());
        &self.samples[first..]
    }

    /// The largest window mean: (first sample index in `loaded`, mean).
    fn peak(&self, w: usize) -> Option<(usize, f64)> {
        series::largest_window_mean(self.loaded(), w, |x| x.stress)
    }

    fn has_failed(&self) -> bool {
        series::has_softened(self.loaded(), self.window_samples(), |x| x.stress, SOFTENING)
    }

    /// sigma_c, the strain at failure, whether it failed, ff_c (module docs). None before a window of
    /// loaded samples.
    pub fn reading(&self) -> Option<Reading> {
        let w = self.window_samples();
        let (i, _) = self.peak(w)?;
        let window: Vec<f64> = self.loaded()[i..i + w].iter().map(|x| x.stress).collect();
        let estimate = series::mean_with_error(&window);
        let sigma_c = estimate.mean;
        Some(Reading {
            unconfined_yield_strength: estimate,
            strain_at_failure: self.loaded()[i + w / 2].strain,
            failed: self.has_failed(),
            flow_function: if sigma_c > 0.0 { self.start.consolidation_stress / sigma_c } else { f64::INFINITY },
        })
    }
}

/// The test with its specimen, stepped by time (the FMU's communication steps) and saved whole: what
/// UnconfinedCompression runs.
pub struct Specimen {
    /// The specimen's engine: the bed with its die removed and the platen moving.
    pub engine: AnyEngine,
    /// The bed's scene (its material and the consolidation stress sigma_1).
    pub scene: BedScene,
    /// The test's settings, the specimen at the start and the curve so far.
    pub test: Compression,
    /// Time asked for but not yet stepped: less than one engine step [s].
    time_debt: f64,
}

impl Specimen {
    /// Starts the test on a prepared bed (`Compression::new`), at the engine step `time_step` [s] when
    /// given (refused above the bed's stability limit).
    pub fn new(mut engine: AnyEngine, scene: BedScene, setup: Setup, time_step: Option<f64>) -> Result<Specimen, BedError> {
        if let Some(dt) = time_step {
            engine.set_time_step(&scene, dt)?;
        }
        let test = Compression::new(&mut engine, &scene, setup)?;
        Ok(Specimen { engine, scene, test, time_debt: 0.0 })
    }

    /// Advances by `h` [s]: as many whole engine steps as fit, the rest carried to the next call. Once
    /// the test has ended the specimen is not stepped any more (nobody reads a broken specimen).
    pub fn advance(&mut self, h: f64) {
        if self.test.done {
            return;
        }
        let dt = self.engine.dt();
        self.time_debt += h;
        let n = (self.time_debt / dt).floor().max(0.0) as u64;
        self.time_debt -= n as f64 * dt;
        self.test.advance(&mut self.engine, &self.scene, n);
    }

    /// The whole state as bytes: the specimen (every contact's memory, the platen's motion, `bed::file`),
    /// the curve so far, and the list's build positions, so a restored test continues bit for bit.
    pub fn save(&self) -> Result<Vec<u8>, BedError> {
        let (list_reference, wall_reference) = self.engine.list_reference();
        let saved = SavedSpecimen {
            bed: file::encode(&self.engine.to_file(&self.scene)?)?,
            test: self.test.clone(),
            time_debt: self.time_debt,
            time_step: self.engine.dt(),
            list_reference,
            wall_reference,
        };
        crate::codec::to_bytes(&saved).map_err(|e| BedError::Setup(format!("the compression test's state cannot be saved: {e}")))
    }

    /// Reads back what `save` wrote, with `threads` threads.
    pub fn restore(bytes: &[u8], threads: Option<usize>) -> Result<Specimen, BedError> {
        let saved: SavedSpecimen =
            crate::codec::from_bytes(bytes).map_err(|e| BedError::Setup(format!("the saved compression test's state cannot be read: {e}")))?;
        let bed: BedFile = file::decode(&saved.bed)?;
        let (mut engine, scene) = AnyEngine::from_file(&bed, threads)?;
        if engine.walls().len() <= PISTON {
            return Err(BedError::Setup("the saved compression test's specimen has no platen".into()));
        }
        engine.set_time_step(&scene, saved.time_step)?;
        if !engine.rebuild_at(&saved.list_reference, &saved.wall_reference) {
            return Err(BedError::Setup("the saved compression test's list positions do not match its specimen".into()));
        }
        Ok(Specimen { engine, scene, test: saved.test, time_debt: saved.time_debt })
    }
}

#[derive(serde::Serialize, serde::Deserialize)]
struct SavedSpecimen {
    bed: Vec<u8>,
    test: Compression,
    time_debt: f64,
    /// The engine's step (a bed file holds its scene's, which the test may have changed).
    time_step: f64,
    list_reference: Vec<Vec3>,
    wall_reference: Vec<Vec3>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn test_with(stresses: &[f64]) -> Compression {
        let start = Start { height: 1.0, solid_fraction: 0.5, self_weight_stress: 0.0, consolidation_stress: 1e4 };
        let setup = Setup { strain_rate: 1.0, max_strain: 0.5, free_time: 0.0, window: 0.005, reading_start: 0.0 };
        let dt = 1e-5; // 100 steps of 1e-5 s at 1/s: 1e-3 strain per sample, a window of 5 samples
        let samples =
            stresses.iter().enumerate().map(|(k, &s)| Sample { time: (k + 1) as f64 * 100.0 * dt, strain: k as f64 * 1e-3, stress: s }).collect();
        Compression { setup, start, samples, touch: Some(1.0), touch_at_the_latest: 0.99, sum: (0.0, 0), done: false, dt }
    }

    #[test]
    fn the_peak_is_the_largest_window_mean_not_the_largest_sample() {
        // A rise to 100, one spike of 300 and a fall: the spike moves the window mean by 40, not to 300.
        let mut s: Vec<f64> = (0..20).map(|k| 5.0 * k as f64).collect();
        s.extend([100.0, 100.0, 300.0, 100.0, 100.0]);
        s.extend((0..30).map(|k| 100.0 - 3.0 * k as f64));
        let t = test_with(&s);
        let r = t.reading().unwrap();
        assert!((r.unconfined_yield_strength.mean - 140.0).abs() < 1e-9, "{r:?}");
        assert!(r.failed, "fell to {} of the peak", s.last().unwrap() / 140.0);
        assert!((r.flow_function - 1e4 / 140.0).abs() < 1e-9);
    }

    #[test]
    fn a_curve_still_rising_has_not_failed_and_its_strength_is_a_lower_bound() {
        let s: Vec<f64> = (1..40).map(|k| k as f64).collect();
        let r = test_with(&s).reading().unwrap();
        assert!(!r.failed);
        assert!((r.unconfined_yield_strength.mean - 37.0).abs() < 1e-9, "{r:?}");
    }

    #[test]
    fn the_touch_is_the_bulks_not_a_lone_spheres() {
        // A sample with one step above half the weight stress but a mean far below it (a lone sphere on
        // a rough top) does not set the strain's origin; the first sample whose mean reaches it does.
        let mut t = test_with(&[]);
        t.touch = None;
        t.start.self_weight_stress = 300.0;
        let mut z = 1.0;
        for k in 0..CHECK_EVERY {
            z -= 1e-6;
            t.observe(if k == 40 { 400.0 } else { 0.0 }, z, 0.0);
        }
        assert_eq!(t.touch, None);
        assert_eq!(t.samples[0].strain, 0.0);
        for _ in 0..CHECK_EVERY {
            z -= 1e-6;
            t.observe(2000.0, z, 0.0);
        }
        assert_eq!(t.touch, Some(z), "the end of the bulk's first sample");
        z -= 1e-6;
        t.observe(2000.0, z, 0.0);
        assert_eq!(t.samples.len(), 2);
        // A specimen that never carries it: touched where the platen has come TOUCH_DEPTH below the top.
        let mut weak = test_with(&[]);
        (weak.touch, weak.start.self_weight_stress, weak.touch_at_the_latest) = (None, 300.0, 0.99);
        let mut z = 1.0;
        while weak.touch.is_none() {
            z -= 1e-5;
            weak.observe(10.0, z, 0.0);
        }
        assert!((0.99 - 1e-3..=0.99).contains(&weak.touch.unwrap()), "{:?}", weak.touch);
    }

    #[test]
    fn bad_settings_are_refused_by_name() {
        for (setup, name) in [
            (Setup { strain_rate: 0.0, ..Setup::default() }, "strain_rate"),
            (Setup { max_strain: 1.5, ..Setup::default() }, "max_strain"),
            (Setup { free_time: -1.0, ..Setup::default() }, "free_time"),
            (Setup { reading_start: 0.0998, ..Setup::default() }, "reading_start"),
            (Setup { window: 0.2, ..Setup::default() }, "window"),
        ] {
            let e = setup.check().unwrap_err();
            assert!(e.to_string().contains(name), "{e}");
        }
    }
}
