//! The translational (Jenike) shear cell (`003` Sec. 5.1, Fig. 13; `004` Sec. 2.2) on a prepared bed:
//! the die split into a fixed lower ring and an upper ring that a drive moves horizontally, the piston
//! as the cell's lid holding the normal stress. One preshear to steady flow at sigma_pre, then from that
//! state, for each lower normal stress sigma_n, the shear to failure (incipient flow); the points
//! (sigma_n, tau_peak) are the yield locus (`yield_locus`), whose Mohr circles give sigma_c and sigma_1.
//!
//! - The rings (`walls::Shape::Ring`) meet at `Setup::split` of the bed's height; the lower one is the
//!   die's cylinder up to there (the floor under it), the upper one the rest of the die. Both carry the
//!   die's particle-wall law. The drive moves the upper ring and the lid together in +x at
//!   `shear_speed` (the lid's wall moves with them, so its friction, if the scene's walls have any,
//!   drags the powder's top as a grooved Jenike lid does).
//! - The lid is stress-controlled (003 Sec. 5.1: "when the reaction force F_N changes because some
//!   particles reorganise, the height of the shear lid is changed accordingly"): every `CHECK_EVERY`
//!   steps its vertical speed is set by a proportional-integral servo on the relative error e of the
//!   sample's mean lid stress, servo_speed (e + sum e / `INTEGRAL_SAMPLES`), capped at servo_speed. The
//!   integral carries the speed a dilating or compacting shear needs, which a proportional servo alone
//!   can only give with a standing error (on the 004 Ch. 6 specimen, a stable proportional gain left the
//!   lid at half of sigma_n while the shear dilated).
//! - The stresses on the shear plane are Bagi's (004 Eq. 5.1, `stress`) in a slab about it: the spheres
//!   whose centres lie within `SLAB` mean diameters of the split and `SLAB` of the lower ring's inner
//!   face, read at the end of every sample; sigma = sigma_zz, tau = -(sigma_xz + sigma_zx) / 2
//!   (compression positive, so the upper half's drag in +x reads positive). Not the drive's force over
//!   the cross-section A: that holds, besides the powder's resistance on the plane, the upper ring's
//!   edge ploughing through the lower half's top where the ring has moved over it, which in a cell a
//!   few tens of diameters wide is not small (on the suite's 7 mm cell the drive read 1.2-1.5 times the
//!   normal stress). The drive's reading, -(F_x on the upper ring and the lid) / A, is kept beside it
//!   (`Sample::drive_stress`), and the lid's, F_z / A (`Sample::lid_stress`).
//! - The Jenike procedure (004 Sec. 2.2; 003 Sec. 6): load to sigma_pre; preshear at it to
//!   `preshear_displacement`, tau_pre the mean over its last `steady_fraction`; then for each sigma_n,
//!   from the preshear's end: the drive reversed until tau on the plane has fallen to zero (the shear
//!   force taken off), the lid brought to sigma_n, and the shear forward to `shear_displacement` or failure;
//!   tau_peak is the largest mean over a window of `window` displacement (not the largest sample:
//!   `compression`'s reasoning), with that window's standard error (`series`).
//! - In two parts: `preshear` returns the cell at the preshear's end (`Presheared`, which a file can
//!   hold: `shear_state`), `shears` runs the shears from it; `run` is the two.

use super::any::{AnyEngine, BedError};
use super::file::{self, BedFile};
use super::prepare::{bed_height, DIE, PISTON};
use super::scene::BedScene;
use super::series::{self, MeanEstimate};
use super::stress::{bagi, Region};
use super::walls::{Shape, Wall};
use super::yield_locus::{Point, YieldLocus};
use super::Vec3;
use crate::error::ParamError;

/// Engine steps per sample (and per servo update).
pub const CHECK_EVERY: u64 = 100;
/// The shear to failure stops once the window mean has fallen below this fraction of its peak.
pub const SOFTENING: f64 = 0.9;
/// Loading and unloading the lid end when the mean error of this many samples is within
/// `SERVO_TOLERANCE` (one sample's lid stress fluctuates by a quarter at 2.5 kPa on the Ch. 6 specimen).
const SETTLED_SAMPLES: usize = 20;
/// Relative error of the lid stress that counts as held.
pub const SERVO_TOLERANCE: f64 = 0.03;
/// The servo's integral time, in samples.
pub const INTEGRAL_SAMPLES: f64 = 50.0;
/// Half-thickness of the measurement slab about the shear plane, and its distance from the ring's inner
/// face, in mean sphere diameters.
pub const SLAB: f64 = 2.0;

/// The test's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    /// Normal stress of the preshear, sigma_pre [Pa].
    pub preshear_stress: f64,
    /// Normal stresses of the shear to failure, sigma_n, each below sigma_pre [Pa].
    pub normal_stresses: Vec<f64>,
    /// Speed of the drive [m/s].
    pub shear_speed: f64,
    /// Height at which the rings meet, as a fraction of the bed's height [-].
    pub split: f64,
    /// Travel of the preshear [m].
    pub preshear_displacement: f64,
    /// Fraction of the preshear's travel over which tau_pre is averaged (its steady end) [-].
    pub steady_fraction: f64,
    /// Largest travel of each shear to failure [m].
    pub shear_displacement: f64,
    /// Displacement window of the mean for tau_peak [m].
    pub window: f64,
    /// The lid's largest vertical speed under the servo [m/s].
    pub servo_speed: f64,
    /// Time allowed to each loading or unloading of the lid before the test is refused [s].
    pub servo_time: f64,
}

impl Setup {
    /// The drive's travel over the whole test, preshear and every shear at its longest [m]: what progress
    /// is counted against.
    pub fn total_travel(&self) -> f64 {
        self.preshear_displacement + self.normal_stresses.len() as f64 * self.shear_displacement
    }

    /// Every value in its range, or the first that is not, by name.
    pub fn check(&self) -> Result<(), ParamError> {
        let out = |name: &'static str, value: f64, allowed: String| ParamError::OutOfRange { name, value, allowed };
        if !(self.preshear_stress > 0.0 && self.preshear_stress <= 1e7) {
            return Err(out("preshear_stress", self.preshear_stress, "(0, 1e7] Pa".into()));
        }
        if self.normal_stresses.len() < 2 {
            return Err(ParamError::Inconsistent { name: "normal_stresses", why: "a yield locus needs at least two normal stresses".into() });
        }
        for &s in &self.normal_stresses {
            if !(s > 0.0 && s < self.preshear_stress) {
                return Err(out("normal_stresses", s, format!("(0, preshear_stress = {} Pa)", self.preshear_stress)));
            }
        }
        if !(self.shear_speed > 0.0 && self.shear_speed <= 10.0) {
            return Err(out("shear_speed", self.shear_speed, "(0, 10] m/s".into()));
        }
        if !(self.split > 0.1 && self.split < 0.9) {
            return Err(out("split", self.split, "(0.1, 0.9) of the bed's height".into()));
        }
        if !(self.preshear_displacement > 0.0) {
            return Err(out("preshear_displacement", self.preshear_displacement, "(0, inf) m".into()));
        }
        if !(self.steady_fraction > 0.0 && self.steady_fraction < 1.0) {
            return Err(out("steady_fraction", self.steady_fraction, "(0, 1)".into()));
        }
        if !(self.shear_displacement > 0.0) {
            return Err(out("shear_displacement", self.shear_displacement, "(0, inf) m".into()));
        }
        if !(self.window > 0.0 && self.window < self.shear_displacement) {
            return Err(out("window", self.window, "(0, shear_displacement) m".into()));
        }
        if !(self.servo_speed > 0.0 && self.servo_speed <= 10.0) {
            return Err(out("servo_speed", self.servo_speed, "(0, 10] m/s".into()));
        }
        if !(self.servo_time > 0.0) {
            return Err(out("servo_time", self.servo_time, "(0, inf) s".into()));
        }
        Ok(())
    }
}

/// One sample of a phase.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    /// Time [s].
    pub time: f64,
    /// The upper ring's travel from its start [m].
    pub displacement: f64,
    /// Normal stress on the shear plane: Bagi's sigma_zz in the slab about it, at the sample's end [Pa].
    pub normal_stress: f64,
    /// Shear stress on the shear plane: Bagi's, in the slab, at the sample's end [Pa].
    pub shear_stress: f64,
    /// The largest principal stress of Bagi's tensor in the slab (symmetrised), at the sample's end [Pa]:
    /// sigma_1 measured where the Mohr construction has to infer it.
    pub major_principal_stress: f64,
    /// The lid's stress, F_z / A, mean over the sample [Pa].
    pub lid_stress: f64,
    /// The drive's, -(F_x on the upper ring and the lid) / A, mean over the sample [Pa].
    pub drive_stress: f64,
    /// The lid's height [m].
    pub lid: f64,
}

/// What a shear to failure read.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// The normal stress asked of the lid [Pa].
    pub target: f64,
    /// The normal stress on the shear plane over the peak's window (lid and weight above), its mean.
    pub normal_stress: MeanEstimate,
    /// tau_peak: the largest window mean of the shear stress, with its standard error [Pa].
    pub shear_stress: MeanEstimate,
    /// Travel at the middle of that window, from the shear's start [m].
    pub displacement: f64,
    /// Whether tau fell to `SOFTENING` of its peak before `shear_displacement`; if not, tau_peak is the
    /// largest window mean of a curve that reached a plateau or still rose: a lower bound.
    pub failed: bool,
    /// The shear's curve (from the lid's arrival at sigma_n).
    pub samples: Vec<Sample>,
}

/// What the whole test read.
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// The preshear's steady state: the normal stress on the plane [Pa] (mean over its steady end).
    pub preshear_normal: MeanEstimate,
    /// The preshear's steady state: the shear stress on the plane, tau_pre [Pa].
    pub preshear_shear: MeanEstimate,
    /// The preshear's steady state: the largest principal stress in the slab, sigma_1 as measured [Pa].
    pub preshear_major: MeanEstimate,
    /// The shears' tau_peak read off the steady preshear (`steady_peak`): the steady end cut into stretches
    /// of one shear's travel, in each the largest window mean of tau; their mean and its standard error
    /// over the stretches [Pa]. None with fewer than two stretches.
    pub preshear_peak: Option<MeanEstimate>,
    /// The preshear's curve.
    pub preshear: Vec<Sample>,
    /// The shears to failure, one per normal stress.
    pub failures: Vec<Failure>,
    /// The yield locus through the failures' points, when they give one.
    pub locus: Option<YieldLocus>,
    /// Solid fraction of the bed in the cell at the preshear's start [-].
    pub solid_fraction: f64,
}

impl Reading {
    /// The locus's points.
    pub fn points(&self) -> Vec<Point> {
        self.failures
            .iter()
            .map(|f| Point {
                normal_stress: f.normal_stress.mean,
                shear_stress: f.shear_stress.mean,
                shear_stress_error: f.shear_stress.standard_error,
            })
            .collect()
    }
}

/// The cell: the walls' indices and the geometry the readings need.
#[derive(Clone, Copy)]
struct Cell {
    upper: usize,
    area: f64,
    /// The slab about the shear plane where the stresses are read.
    slab: Region,
    /// Part of the die simulated (a half's slab holds half the cylinder's spheres).
    sector: f64,
    /// The servo's last relative error and the samples it has run.
    check: (f64, u64),
    /// The servo's integral term, in units of servo_speed.
    integral: f64,
}

/// Progress of a long test: the phase, the normal stress it works at, and its last sample.
pub struct Progress<'a> {
    /// `load`, `preshear`, `unload` or `shear`.
    pub phase: &'static str,
    /// The normal stress the lid holds [Pa].
    pub target: f64,
    /// The last sample.
    pub sample: &'a Sample,
    /// Fraction of the whole test done, in [0, 1].
    pub fraction: f64,
}

impl Cell {
    /// Splits the die of a prepared bed into two rings at `split` of the bed's height and lays the lid on
    /// the bed.
    fn new(e: &mut AnyEngine, scene: &BedScene, setup: &Setup) -> Result<Cell, BedError> {
        let die = e.walls().get(DIE).cloned();
        let Some(Wall { shape: Shape::Cylinder { radius }, .. }) = die else {
            return Err(ParamError::Inconsistent { name: "bed", why: "not a prepared bed in a die (floor, die, piston)".into() }.into());
        };
        if e.walls().len() <= PISTON || !radius.is_finite() {
            return Err(ParamError::Inconsistent { name: "bed", why: "not a prepared bed in a die (floor, die, piston)".into() }.into());
        }
        if scene.die_sector < 0.5 {
            // A quarter's mirror plane x = 0 is across the shear's direction: no symmetry holds there.
            return Err(ParamError::Inconsistent {
                name: "die_sector",
                why: "the shear cell runs on a whole die or a half (its mirror plane y = 0 along the shear), not a quarter".into(),
            }
            .into());
        }
        let height = bed_height(e.particles());
        let split_z = setup.split * height;
        let d_mean = scene.size_distribution.mean_diameter();
        // Rings as thick as the die's radius: no sphere reaches around one.
        let thickness = radius;
        let top = scene.die_height.max(2.0 * height);
        e.walls_mut()[DIE] = Wall::ring("lower_ring", Vec3::new(0.0, 0.0, -top), radius, top + split_z, thickness);
        e.add_wall(
            scene,
            Wall::ring("upper_ring", Vec3::new(0.0, 0.0, split_z), radius, top, thickness),
            &scene.particle_wall,
            scene.wall_rolling_friction,
        )?;
        let upper = e.walls().len() - 1;
        let lid = &mut e.walls_mut()[PISTON];
        lid.position[2] = height + 0.02 * d_mean;
        lid.velocity = Vec3::zeros();
        e.rebuild();
        let h = SLAB * d_mean;
        if radius <= h {
            return Err(ParamError::Inconsistent {
                name: "die_diameter",
                why: format!("the die ({:.3e} m) holds no measurement slab {SLAB} mean diameters from its wall", 2.0 * radius),
            }
            .into());
        }
        let slab = Region { radius: radius - h, z_low: split_z - h, z_high: split_z + h };
        Ok(Cell { upper, area: scene.sector_area(), slab, sector: scene.die_sector, check: (0.0, 0), integral: 0.0 })
    }

    /// Sets the drive (upper ring and lid) to `vx` [m/s] in x and the lid to `vz`.
    fn drive(&self, e: &mut AnyEngine, vx: f64, vz: f64) {
        let upper = self.upper;
        let w = e.walls_mut();
        w[upper].velocity = Vec3::new(vx, 0.0, 0.0);
        w[PISTON].velocity = Vec3::new(vx, 0.0, vz);
    }

    /// Runs one sample (`CHECK_EVERY` steps) at drive speed `vx` with the lid servo on `target`, and
    /// returns it (`x0` the ring's x at the phase's start). The servo acts on this sample's lid stress for
    /// the next.
    fn sample(&mut self, e: &mut AnyEngine, setup: &Setup, vx: f64, target: f64, x0: f64) -> Sample {
        let area = self.area;
        let upper = self.upper;
        let (mut lid_sum, mut tau_sum) = (0.0, 0.0);
        e.run_while(CHECK_EVERY, |walls, _| {
            lid_sum += walls[PISTON].force[2];
            tau_sum -= walls[upper].force[0] + walls[PISTON].force[0];
            true
        });
        let n = CHECK_EVERY as f64;
        let lid_stress = lid_sum / n / area;
        let error = (target - lid_stress) / target;
        self.integral = (self.integral + error / INTEGRAL_SAMPLES).clamp(-1.0, 1.0);
        let vz = -(setup.servo_speed * (error + self.integral)).clamp(-setup.servo_speed, setup.servo_speed);
        self.drive(e, vx, vz);
        self.check = (error, self.check.1 + 1);
        let plane = bagi(e, &self.slab).of_whole_die(self.sector);
        let symmetric = 0.5 * (plane.0 + plane.0.transpose());
        let major_principal_stress = symmetric.symmetric_eigenvalues().max();
        let walls = e.walls();
        Sample {
            time: e.time(),
            displacement: walls[upper].position[0] - x0,
            normal_stress: plane.get(2, 2),
            shear_stress: -0.5 * (plane.get(0, 2) + plane.get(2, 0)),
            major_principal_stress,
            lid_stress,
            drive_stress: tau_sum / n / area,
            lid: walls[PISTON].position[2],
        }
    }

    /// Holds the drive at `vx` until the lid's stress has been within `SERVO_TOLERANCE` of `target` for
    /// `SETTLED_SAMPLES` samples (and, if `until_unloaded`, tau has fallen to zero); refused after
    /// `servo_time`.
    fn settle(
        &mut self,
        e: &mut AnyEngine,
        setup: &Setup,
        vx: f64,
        target: f64,
        until_unloaded: bool,
        mut progress: impl FnMut(&Sample),
    ) -> Result<(), BedError> {
        let phase = if until_unloaded { "unloading to a normal stress" } else { "loading to preshear_stress" };
        let (start, x0) = (e.time(), e.walls()[self.upper].position[0]);
        let mut errors = std::collections::VecDeque::with_capacity(SETTLED_SAMPLES);
        let mut unloaded = !until_unloaded;
        loop {
            // The drive runs until tau has fallen to zero, then stands while the lid settles.
            let s = self.sample(e, setup, if unloaded { 0.0 } else { vx }, target, x0);
            progress(&s);
            unloaded |= s.shear_stress <= 0.0;
            if errors.len() == SETTLED_SAMPLES {
                errors.pop_front();
            }
            errors.push_back(self.check.0);
            let mean = errors.iter().sum::<f64>() / errors.len() as f64;
            if errors.len() == SETTLED_SAMPLES && mean.abs() <= SERVO_TOLERANCE && unloaded {
                let vz = e.walls()[PISTON].velocity[2];
                self.drive(e, 0.0, vz);
                return Ok(());
            }
            if e.time() - start > setup.servo_time {
                return Err(BedError::Setup(format!(
                    "shear cell, {phase}: the lid did not hold {target:.4e} Pa within servo_time = {} s (last error {:.1} %); raise servo_time or servo_speed",
                    setup.servo_time,
                    100.0 * self.check.0
                )));
            }
        }
    }

    /// Shears at `setup.shear_speed` with the lid on `target` until `travel`, or (if `stop_on_failure`) the
    /// failure; calls `progress` every sample.
    fn shear(
        &mut self,
        e: &mut AnyEngine,
        setup: &Setup,
        target: f64,
        travel: f64,
        stop_on_failure: bool,
        mut progress: impl FnMut(&Sample),
    ) -> Vec<Sample> {
        let x0 = e.walls()[self.upper].position[0];
        let w = window_samples(setup.window, setup.shear_speed, e.dt());
        let mut samples = Vec::new();
        loop {
            let s = self.sample(e, setup, setup.shear_speed, target, x0);
            progress(&s);
            samples.push(s);
            if s.displacement >= travel || (stop_on_failure && has_failed(&samples, w)) {
                break;
            }
        }
        self.drive(e, 0.0, 0.0);
        samples
    }
}

/// Samples per displacement `window` at drive speed `speed`.
fn window_samples(window: f64, speed: f64, dt: f64) -> usize {
    ((window / (speed * dt * CHECK_EVERY as f64)).round() as usize).max(series::MIN_SAMPLES)
}

/// The shears' peak estimator on steady flow: `steady` cut into as many stretches of `travel` as it holds
/// (equal sample counts), in each the largest mean of tau over `w` samples (as `peak` reads tau_peak); the
/// mean over the stretches and its standard error (the stretches taken as independent: each is a shear's
/// travel, many correlation lengths of the flow's fluctuation). A stationary fluctuating tau has a largest window mean above its
/// level: on the cells of docs/bed.md "The tangency check" 5-12 % of tau_pre. That is what a shear point
/// carries from the fluctuation alone, and the preshear point to hold against the shears' locus when the
/// two are to be read alike. None with fewer than two whole stretches.
fn steady_peak(steady: &[&Sample], travel: f64, w: usize) -> Option<MeanEstimate> {
    let [first, .., last] = steady else { return None };
    // Each sample stands for one spacing of travel: N samples cover N spacings (the default's 1.5 d steady end
    // holds three 0.5 d shears' travel, not two and a bit). Equal counts, the drive's speed being constant.
    let spacing = (last.displacement - first.displacement) / (steady.len() - 1) as f64;
    let whole = ((steady.len() as f64 * spacing) / travel + 1e-9).floor() as usize;
    if whole < 2 {
        return None;
    }
    let per = steady.len() / whole;
    let peaks: Vec<f64> = steady
        .chunks_exact(per)
        .take(whole)
        .filter_map(|stretch| series::largest_window_mean(stretch, w, |s| s.shear_stress).map(|(_, m)| m))
        .collect();
    let n = peaks.len();
    if n < 2 {
        return None;
    }
    let mean = peaks.iter().sum::<f64>() / n as f64;
    let variance = peaks.iter().map(|p| (p - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    Some(MeanEstimate { mean, standard_error: (variance / n as f64).sqrt(), samples: n, correlation_time: 0.0 })
}

/// The largest window mean of the shear stress: (first sample, mean).
fn peak(samples: &[Sample], w: usize) -> Option<(usize, f64)> {
    series::largest_window_mean(samples, w, |s| s.shear_stress)
}

fn has_failed(samples: &[Sample], w: usize) -> bool {
    series::has_softened(samples, w, |s| s.shear_stress, SOFTENING)
}

/// The cell's geometry as the shears need it: the upper ring's wall index, the cross-section the lid and
/// the drive act on, the measurement slab (radius, lower and upper height) and the die's sector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SavedCell {
    /// Index of the upper ring among the walls.
    pub upper: u32,
    /// Cross-section of the (sector of the) die [m^2].
    pub area: f64,
    /// The slab about the shear plane: radius, lower height, upper height [m].
    pub slab: [f64; 3],
    /// Part of the die simulated.
    pub sector: f64,
}

/// The shear cell at the preshear's end (`preshear`), from which `shears` starts each shear: the engine's
/// state with the rings and the lid, the neighbour list's build positions (a restored state steps as the
/// original would), the preshear's curve and settings; `shear_state` writes it to a file and reads it back.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Presheared {
    /// Normal stress the preshear ran at, sigma_pre [Pa].
    pub preshear_stress: f64,
    /// Drive speed of the preshear [m/s].
    pub shear_speed: f64,
    /// Height of the rings' meeting, a fraction of the bed's height [-].
    pub split: f64,
    /// Travel of the preshear [m].
    pub preshear_displacement: f64,
    /// The engine's time step [s].
    pub time_step: f64,
    /// Solid fraction of the bed in the cell under sigma_pre, at the preshear's start [-].
    pub solid_fraction: f64,
    /// The preshear's curve.
    pub preshear: Vec<Sample>,
    /// The cell's geometry.
    pub cell: SavedCell,
    /// The engine's state as a bed file's bytes (envelope included).
    pub bed: Vec<u8>,
    /// The neighbour list's build positions of the particles and the walls.
    pub list: Vec<Vec3>,
    /// The walls' positions at the list's build.
    pub walls: Vec<Vec3>,
}

impl Presheared {
    /// The bed scene the state was prepared with.
    pub fn scene(&self) -> Result<BedScene, BedError> {
        let bed: BedFile = file::decode(&self.bed)?;
        Ok(BedScene::from_stored_json(&bed.scene)?)
    }

    /// The engine at the preshear's end, on `threads` (default: the scene's), with its list as it was.
    pub fn engine(&self, threads: Option<usize>) -> Result<AnyEngine, BedError> {
        let bed: BedFile = file::decode(&self.bed)?;
        let (mut e, scene) = AnyEngine::from_file(&bed, threads)?;
        e.set_time_step(&scene, self.time_step)?;
        if !e.rebuild_at(&self.list, &self.walls) {
            return Err(BedError::Setup("the shear cell's preshear state did not restore".into()));
        }
        Ok(e)
    }
}

/// Refuses a `window` of fewer than `series::MIN_SAMPLES` samples at time step `dt`.
fn check_window(setup: &Setup, dt: f64) -> Result<(), BedError> {
    let per_sample = setup.shear_speed * dt * CHECK_EVERY as f64;
    if setup.window / per_sample < series::MIN_SAMPLES as f64 - 0.5 {
        return Err(ParamError::OutOfRange {
            name: "window",
            value: setup.window,
            allowed: format!(
                "at least {} samples: [{:.3e}, shear_displacement) m at this bed's step {dt:.3e} s and shear_speed {} m/s",
                series::MIN_SAMPLES,
                (series::MIN_SAMPLES as f64 - 0.5) * per_sample,
                setup.shear_speed
            ),
        }
        .into());
    }
    Ok(())
}

/// Refuses a preshear whose steady end (`steady_fraction` of its travel) would hold fewer than
/// `series::MIN_SAMPLES` samples at time step `dt`: checked before the preshear, not after it.
fn check_steady_end(setup: &Setup, dt: f64) -> Result<(), BedError> {
    let per_sample = setup.shear_speed * dt * CHECK_EVERY as f64;
    if setup.steady_fraction * setup.preshear_displacement / per_sample < series::MIN_SAMPLES as f64 {
        return Err(ParamError::OutOfRange {
            name: "steady_fraction",
            value: setup.steady_fraction,
            allowed: format!(
                "a steady end of at least {} samples: [{:.3e}, 1) at this preshear's travel {:.3e} m, step {dt:.3e} s and shear_speed {} m/s",
                series::MIN_SAMPLES,
                series::MIN_SAMPLES as f64 * per_sample / setup.preshear_displacement,
                setup.preshear_displacement,
                setup.shear_speed
            ),
        }
        .into());
    }
    Ok(())
}

/// The whole test on a prepared bed (`engine`, its `scene`): loading, preshear, and one shear to failure
/// per normal stress; `threads` for the restored states; `progress` every sample.
pub fn run(
    engine: &mut AnyEngine,
    scene: &BedScene,
    setup: &Setup,
    threads: Option<usize>,
    mut progress: impl FnMut(Progress),
) -> Result<Reading, BedError> {
    let state = preshear(engine, scene, setup, &mut progress)?;
    shears(&state, setup, threads, progress)
}

/// The test's first part on a prepared bed: the cell built, the lid loaded to sigma_pre and the preshear
/// run; returns the cell at the preshear's end (`Presheared`), from which `shears` starts each shear.
/// Checks the whole setup first, so that no bad shear setting is found after the preshear's hour.
pub fn preshear(engine: &mut AnyEngine, scene: &BedScene, setup: &Setup, mut progress: impl FnMut(Progress)) -> Result<Presheared, BedError> {
    setup.check()?;
    check_window(setup, engine.dt())?;
    check_steady_end(setup, engine.dt())?;
    let mut cell = Cell::new(engine, scene, setup)?;
    let p = engine.particles();
    let volume: f64 = p.radius.iter().map(|r| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3)).sum();
    let total = setup.total_travel();
    cell.settle(engine, setup, 0.0, setup.preshear_stress, false, |s| {
        progress(Progress { phase: "load", target: setup.preshear_stress, sample: s, fraction: 0.0 })
    })?;
    let solid_fraction = volume / (cell.area * engine.walls()[PISTON].position[2]);
    let pre = setup.preshear_stress;
    let preshear = cell.shear(engine, setup, pre, setup.preshear_displacement, false, |s| {
        progress(Progress { phase: "preshear", target: pre, sample: s, fraction: s.displacement / total })
    });
    let (list, walls) = engine.list_reference();
    let slab = cell.slab;
    Ok(Presheared {
        preshear_stress: pre,
        shear_speed: setup.shear_speed,
        split: setup.split,
        preshear_displacement: setup.preshear_displacement,
        time_step: engine.dt(),
        solid_fraction,
        preshear,
        cell: SavedCell { upper: cell.upper as u32, area: cell.area, slab: [slab.radius, slab.z_low, slab.z_high], sector: cell.sector },
        bed: file::encode(&engine.to_file(scene)?)?,
        list,
        walls,
    })
}

/// The test's second part: from the cell at the preshear's end (`state`, of this run or a saved one),
/// tau_pre over the preshear's last `setup.steady_fraction`, and for each of `setup.normal_stresses` the
/// shear force taken off (the drive reversed until tau is zero), the lid brought to sigma_n and the shear
/// to failure, each from the same state; `threads` for the restored states. The setup's preshear (its
/// stress, split and travel) must be the state's; its drive speed, window and the shears' settings are
/// the shears' own.
pub fn shears(state: &Presheared, setup: &Setup, threads: Option<usize>, mut progress: impl FnMut(Progress)) -> Result<Reading, BedError> {
    setup.check()?;
    let differs = |a: f64, b: f64| (a - b).abs() > 1e-12 * a.abs().max(b.abs());
    for (name, asked, saved, unit) in [
        ("preshear_stress", setup.preshear_stress, state.preshear_stress, "Pa"),
        ("split", setup.split, state.split, "of the bed's height"),
        ("preshear_displacement", setup.preshear_displacement, state.preshear_displacement, "m"),
    ] {
        if differs(asked, saved) {
            return Err(ParamError::Inconsistent {
                name,
                why: format!("the saved preshear ran with {saved:.6e} {unit}, the setup asks {asked:.6e}"),
            }
            .into());
        }
    }
    let dt = state.time_step;
    check_window(setup, dt)?;
    let steady: Vec<&Sample> =
        state.preshear.iter().filter(|s| s.displacement >= (1.0 - setup.steady_fraction) * setup.preshear_displacement).collect();
    if steady.len() < series::MIN_SAMPLES {
        return Err(ParamError::OutOfRange {
            name: "steady_fraction",
            value: setup.steady_fraction,
            allowed: format!("a steady end of at least {} samples of the preshear's {}", series::MIN_SAMPLES, state.preshear.len()),
        }
        .into());
    }
    let preshear_normal = series::mean_with_error(&steady.iter().map(|s| s.normal_stress).collect::<Vec<_>>());
    let preshear_shear = series::mean_with_error(&steady.iter().map(|s| s.shear_stress).collect::<Vec<_>>());
    let preshear_major = series::mean_with_error(&steady.iter().map(|s| s.major_principal_stress).collect::<Vec<_>>());
    let saved = state.cell;
    let cell = Cell {
        upper: saved.upper as usize,
        area: saved.area,
        slab: Region { radius: saved.slab[0], z_low: saved.slab[1], z_high: saved.slab[2] },
        sector: saved.sector,
        check: (0.0, 0),
        integral: 0.0,
    };
    let total = setup.total_travel();
    let mut failures = Vec::new();
    for (k, &target) in setup.normal_stresses.iter().enumerate() {
        let mut e = state.engine(threads)?;
        let mut c = cell;
        // The shear force taken off (the drive reversed until tau is zero), the lid brought to sigma_n.
        let done = setup.preshear_displacement + k as f64 * setup.shear_displacement;
        c.settle(&mut e, setup, -setup.shear_speed, target, true, |s| {
            progress(Progress { phase: "unload", target, sample: s, fraction: done / total })
        })?;
        let samples = c.shear(&mut e, setup, target, setup.shear_displacement, true, |s| {
            progress(Progress { phase: "shear", target, sample: s, fraction: (done + s.displacement) / total })
        });
        let w = window_samples(setup.window, setup.shear_speed, dt);
        let (i, _) = peak(&samples, w)
            .ok_or_else(|| BedError::Setup(format!("shear cell: the shear at {target:.4e} Pa ended before a window of {} m", setup.window)))?;
        let window = &samples[i..i + w];
        failures.push(Failure {
            target,
            normal_stress: series::mean_with_error(&window.iter().map(|s| s.normal_stress).collect::<Vec<_>>()),
            shear_stress: series::mean_with_error(&window.iter().map(|s| s.shear_stress).collect::<Vec<_>>()),
            displacement: samples[i + w / 2].displacement,
            failed: has_failed(&samples, w),
            samples,
        });
    }
    // The preshear's samples are spaced by its own drive speed, which a saved one may not share with the shears.
    let preshear_peak = steady_peak(&steady, setup.shear_displacement, window_samples(setup.window, state.shear_speed, dt));
    let mut reading = Reading {
        preshear_normal,
        preshear_shear,
        preshear_major,
        preshear_peak,
        preshear: state.preshear.clone(),
        failures,
        locus: None,
        solid_fraction: state.solid_fraction,
    };
    reading.locus = YieldLocus::fit(&reading.points());
    Ok(reading)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn saved_state() -> Presheared {
        let sample = Sample { time: 0.5, displacement: 1e-4, normal_stress: 1.1e4, shear_stress: 4.5e3, ..Default::default() };
        Presheared {
            preshear_stress: 1e4,
            shear_speed: 0.01,
            split: 0.5,
            preshear_displacement: 2e-3,
            time_step: 2.5e-7,
            solid_fraction: 0.55,
            preshear: vec![sample; 3],
            cell: SavedCell { upper: 3, area: 1.7e-4, slab: [6e-3, 9e-3, 1.3e-2], sector: 0.5 },
            bed: vec![1, 2, 3],
            list: vec![Vec3::new(1.0, 2.0, 3.0)],
            walls: vec![Vec3::zeros(); 4],
        }
    }

    fn setup() -> Setup {
        Setup {
            preshear_stress: 1e4,
            normal_stresses: vec![2e3, 5e3, 8e3],
            shear_speed: 0.01,
            split: 0.5,
            preshear_displacement: 2e-3,
            steady_fraction: 0.3,
            shear_displacement: 1e-3,
            window: 1e-4,
            servo_speed: 0.01,
            servo_time: 0.5,
        }
    }

    #[test]
    fn bad_settings_are_refused_by_name() {
        let cases: Vec<(Setup, &str)> = vec![
            (Setup { preshear_stress: 0.0, ..setup() }, "preshear_stress"),
            (Setup { normal_stresses: vec![2e3], ..setup() }, "normal_stresses"),
            (Setup { normal_stresses: vec![2e3, 1.2e4], ..setup() }, "normal_stresses"),
            (Setup { shear_speed: -1.0, ..setup() }, "shear_speed"),
            (Setup { split: 0.95, ..setup() }, "split"),
            (Setup { preshear_displacement: 0.0, ..setup() }, "preshear_displacement"),
            (Setup { steady_fraction: 1.0, ..setup() }, "steady_fraction"),
            (Setup { window: 2e-3, ..setup() }, "window"),
            (Setup { servo_speed: 0.0, ..setup() }, "servo_speed"),
            (Setup { servo_time: 0.0, ..setup() }, "servo_time"),
        ];
        assert!(setup().check().is_ok());
        for (s, name) in cases {
            let e = s.check().unwrap_err().to_string();
            assert!(e.contains(name), "{e}");
        }
    }

    #[test]
    fn shears_refuse_a_setup_whose_preshear_is_not_the_saved_one() {
        let state = saved_state();
        for (s, name) in [
            (Setup { preshear_stress: 2e4, normal_stresses: vec![5e3, 8e3], ..setup() }, "preshear_stress"),
            (Setup { split: 0.4, ..setup() }, "split"),
            (Setup { preshear_displacement: 3e-3, ..setup() }, "preshear_displacement"),
        ] {
            let e = shears(&state, &s, None, |_| {}).unwrap_err().to_string();
            assert!(e.contains(name) && e.contains("the saved preshear ran with"), "{e}");
        }
        // The three saved samples are fewer than a steady end needs.
        let e = shears(&state, &setup(), None, |_| {}).unwrap_err().to_string();
        assert!(e.contains("steady_fraction"), "{e}");
    }

    #[test]
    fn a_steady_end_too_short_for_its_error_is_refused_before_the_preshear() {
        // 2 mm at 10 mm/s, 100 steps of 1e-6 s a sample: 2000 samples, 600 in the default steady end.
        assert!(check_steady_end(&setup(), 1e-6).is_ok());
        let e = check_steady_end(&Setup { steady_fraction: 0.003, ..setup() }, 1e-6).unwrap_err().to_string();
        assert!(e.contains("steady_fraction") && e.contains("at least 8 samples"), "{e}");
    }

    #[test]
    fn the_peak_is_a_window_mean_and_failure_needs_the_fall() {
        let at = |tau: &[f64]| {
            tau.iter().enumerate().map(|(k, &t)| Sample { displacement: k as f64, shear_stress: t, ..Default::default() }).collect::<Vec<_>>()
        };
        let mut tau: Vec<f64> = (0..10).map(|k| 10.0 * k as f64).collect();
        tau.extend([100.0, 100.0, 400.0, 100.0]);
        let s = at(&tau);
        let (i, top) = peak(&s, 4).unwrap();
        assert_eq!((i, top), (10, 175.0));
        assert!(!has_failed(&s, 4), "no window after the peak yet");
        tau.extend([50.0; 8]);
        assert!(has_failed(&at(&tau), 4));
    }

    #[test]
    fn the_peak_estimator_on_steady_flow_reads_the_largest_window_mean_of_each_stretch() {
        // A stick-slip sawtooth about a level L: ramps from L - A to L + A over P samples, then a slip.
        // The largest mean of w samples is the ramp's top w: L + A (1 - (w - 1)/(P - 1)), above the level.
        let (level, amplitude, period, w) = (1e4, 2e3, 50usize, 10usize);
        let samples: Vec<Sample> = (0..1000)
            .map(|k| Sample {
                displacement: k as f64 * 1e-6,
                shear_stress: level + amplitude * (2.0 * (k % period) as f64 / (period - 1) as f64 - 1.0),
                ..Default::default()
            })
            .collect();
        let steady: Vec<&Sample> = samples.iter().collect();
        let peak = steady_peak(&steady, 2e-4, w).unwrap();
        let want = level + amplitude * (1.0 - (w - 1) as f64 / (period - 1) as f64);
        assert!((peak.mean - want).abs() < 1e-9 * want, "{peak:?} against {want}");
        // 1000 samples of 1 um in stretches of 200 um: 5 whole stretches, all alike.
        assert_eq!(peak.samples, 5);
        assert!(peak.standard_error < 1e-9 * want, "{peak:?}");
        // Flat flow reads its level; less than two stretches give no estimate.
        let flat: Vec<Sample> = (0..1000).map(|k| Sample { displacement: k as f64 * 1e-6, shear_stress: level, ..Default::default() }).collect();
        let flat: Vec<&Sample> = flat.iter().collect();
        assert_eq!(steady_peak(&flat, 2e-4, w).unwrap().mean, level);
        assert!(steady_peak(&flat, 6e-4, w).is_none(), "one stretch of 600 um in 1 mm");
        // 1.5 mm of steady end in 0.5 mm shears (the default's 0.3 of 5 d, 0.5 d): three stretches, not two.
        let default: Vec<Sample> =
            (0..1500).map(|k| Sample { displacement: 3.5e-3 + k as f64 * 1e-6, shear_stress: level, ..Default::default() }).collect();
        let default: Vec<&Sample> = default.iter().collect();
        assert_eq!(steady_peak(&default, 5e-4, w).unwrap().samples, 3);
    }
}
