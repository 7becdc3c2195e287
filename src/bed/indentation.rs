//! The ball indentation test (`004` Sec. 2.3.5, Chs. 5-7) on a prepared bed: a sphere pushed into the
//! bed surface and pulled out again, the force-depth record, and what the seed derives from it.
//!
//! - Depth h is measured from the depth origin (`DepthOrigin`): the indenter's first touch of the bed
//!   surface (the height of its lowest point when, lowered along the die axis, it would first touch a
//!   sphere: `first_touch_height`), or the bed's mean surface under the indenter's footprint
//!   (`mean_surface_height`). The seed does not say which it used (004 Sec. 5.2 plots from one particle
//!   diameter of depth on).
//! - Projected area A(h) = pi (d h - h^2) (Eq. 2.9); hardness during loading F / A(h) (Eq. 2.7 at the
//!   current load); after unloading H = F_max / A(h_c), with h_c where the tangent to the initial
//!   unloading curve meets zero force (Sec. 2.3.5). "Initial" is read as the upper quarter of the
//!   unloading curve (F >= 0.75 F_0, with h_0, F_0 where unloading starts), sampled at every step: its
//!   least-squares slope S gives the tangent through the start, h_c = h_0 - F_0 / S. Where the bed lets
//!   go of the indenter within a few steps of the turn (a powder bed recovers almost nothing
//!   elastically) the tangent is vertical and h_c = h_max, said so by `contact_depth_from_tangent`.
//! - F_max is the force at the turn read from the loading curve, not its largest sample: the largest of
//!   ~10^3 samples of a force that fluctuates by 10-20 % lies well above its mean (+30 % in the default
//!   test). It is A(h_max) times the mean of F/A(h) over the last `TURN_FIT` of the loading depth.
//! - The plateau hardness: the mean of F/A(h) over the loading samples within the window
//!   `Setup::plateau` (h/r), with its standard error from the samples' autocorrelation (`series`).
//! - Unconfined yield strength = H / C with the constraint factor C (Eq. 2.10).
//! - Hydrostatic and deviatoric stress (Eqs. 5.2-5.3) of Bagi's tensor (Eq. 5.1) in the dynamic bin:
//!   5.2 x 5.2 x 4.2 mean diameters (5.2 x 5.2 x 4.2 mm for the seed's 1 mm spheres), directly below the
//!   indenter, its top at the indenter's lowest point, moving with it (Sec. 5.2, Fig. 5.18).
//! - On a die sector (`BedScene::die_sector`) every output is the whole die's: the sector's force,
//!   contacts and kinetic energy over die_sector, the bin's stress from the sector's share of its spheres.
//!
//! The engine steps with its own time step whatever the communication step: the time not yet stepped is
//! carried to the next call, and every decision (turning at max_penetration, the end of the test, the
//! points of the unloading curve) is taken every `CHECK_EVERY` engine steps counted from the start, so that the
//! communication step changes nothing but when the results are read.

use super::any::{AnyEngine, BedError};
use super::file::{self, BedFile};
use super::particles::Particles;
use super::scene::BedScene;
use super::series::{self, MeanEstimate};
use super::stress::{bagi, Cuboid, Volume};
use super::walls::Wall;
use super::Vec3;
use crate::error::ParamError;
use serde_json::{Map, Value};
use std::f64::consts::PI;

/// Engine steps between two checks of the test's progress (turning, end, unloading points), counted
/// from the start of the bed's time so that they do not depend on the communication step.
const CHECK_EVERY: u64 = 100;
/// The upper part of the unloading curve whose tangent gives h_c: F >= this fraction of the force where
/// unloading starts.
const TANGENT_FRACTION: f64 = 0.75;
/// The dynamic bin in mean diameters (004 Sec. 5.2: 5.2 x 5.2 x 4.2 mm for 1 mm spheres).
const BIN: [f64; 3] = [5.2, 5.2, 4.2];
/// The command line's default depths h/r of the plateau hardness: F/A(h) levels off above about 0.1 (004
/// Figs. 5.2-5.3), and its default test turns at 0.2. Kept so that the recorded commands of docs/ read
/// what they read; the FMU defaults to `SEED_WINDOW`.
pub const PLATEAU: (f64, f64) = (0.1, 0.2);
/// The seed's reading window, h/r: 004 reads its level where the curve has stabilised, after h/r
/// 0.35-0.4 (Figs. 5.3-5.4; the dynamic bin level to 0.5, Fig. 5.19; Fig. 6.3 at 0.475). On the Ch. 6
/// beds it scatters a third to half as much from bed to bed as 0.1-0.2, hardly depends on the depth
/// origin, and has no rate effect from gamma* 0.01 to 0.04 (docs/indentation.md, "The seed's window on
/// the seed's bed").
pub const SEED_WINDOW: (f64, f64) = (0.35, 0.5);
/// The part of the loading depth over which the force at the turn is read: its last tenth.
pub const TURN_FIT: f64 = 0.1;

/// Where the depth h is measured from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum DepthOrigin {
    /// The indenter's lowest point at its first touch of a sphere, lowered along the die axis.
    FirstTouch,
    /// The bed's mean surface under the footprint of the deepest indentation (`mean_surface_height`),
    /// measured before the test.
    MeanSurface,
}

impl DepthOrigin {
    /// Its name in scenes and reports: `first_touch` or `mean_surface`.
    pub fn name(self) -> &'static str {
        match self {
            DepthOrigin::FirstTouch => "first_touch",
            DepthOrigin::MeanSurface => "mean_surface",
        }
    }

    /// The origin of this name (`name`), or none for an unknown one.
    pub fn parse(text: &str) -> Option<DepthOrigin> {
        [DepthOrigin::FirstTouch, DepthOrigin::MeanSurface].into_iter().find(|o| o.name() == text)
    }
}

/// How the indenter moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Motion {
    /// Load at `indentation_speed` to `max_penetration`, unload at the same speed until the indenter
    /// leaves the bed (004 Sec. 2.3.5: unloading at the rate of loading).
    Prescribed,
    /// Follow the inputs: depth and its rate.
    Input,
}

/// The test's set-up.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Setup {
    /// d [m].
    pub indenter_diameter: f64,
    /// [m/s].
    pub indentation_speed: f64,
    /// h_max of the prescribed test [m].
    pub max_penetration: f64,
    /// C of Eq. 2.10.
    pub constraint_factor: f64,
    /// The standard error of C (0: C taken as exact, the constant of the seed; a measured C has one,
    /// `bed::constraint_factor`).
    #[serde(default)]
    pub constraint_factor_standard_error: f64,
    /// How the indenter moves.
    pub motion: Motion,
    /// The shortcut of `fidelity = fast` (none: every sphere moves, `fidelity = full`).
    pub shortcut: Option<Shortcut>,
    /// The window of the plateau hardness, h/r from and to (`PLATEAU` by default).
    pub plateau: (f64, f64),
    /// Where the depth h is measured from.
    pub depth_origin: DepthOrigin,
}

/// Spheres far from the indenter held until disturbed: at the start only those within `zone` contact
/// radii a_max = (d h_max - h_max^2)^(1/2) of the deepest indentation move (`held_outside`); a held
/// sphere is released once the force on it has changed by more than `release` times the contact force
/// scale of the consolidated bed, consolidation_stress x d_mean^2 (checked every `CHECK_EVERY` steps).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Shortcut {
    /// m: the moving zone's size in contact radii a_max [-].
    pub zone: f64,
    /// Release threshold as a fraction of consolidation_stress x d_mean^2 [-].
    pub release: f64,
}

/// The shortcut of `fidelity = fast`, chosen from the measured work-precision curve (docs/indentation.md):
/// on three soft beds of 4000 spheres, 1.9 times faster than full with the plateau hardness within 3.7 %.
pub const FAST: Shortcut = Shortcut { zone: 3.0, release: 0.1 };

/// Which spheres the shortcut holds: those whose centre lies farther than L = m a_max from the die axis,
/// or deeper than L below the indenter's deepest point, with L at least the dynamic bin plus two mean
/// diameters (the bin's stress must see only moving spheres). `touch`: height of the first touch [m].
pub fn held_outside(p: &Particles, setup: &Setup, touch: f64, mean_diameter: f64) -> Vec<bool> {
    let Some(Shortcut { zone: m, .. }) = setup.shortcut else {
        return vec![false; p.len()];
    };
    let (d, h) = (setup.indenter_diameter, setup.max_penetration);
    let a_max = (d * h - h * h).max(0.0).sqrt();
    let reach = (m * a_max).max((0.5 * BIN[0].max(BIN[1]) + 2.0) * mean_diameter).max((BIN[2] + 2.0) * mean_diameter);
    let floor = touch - h - reach;
    p.position.iter().map(|x| x.xy().norm() > reach || x.z < floor).collect()
}

/// Where the test is.
/// Ordered as the test runs: loading before unloading before done.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
pub enum TestState {
    /// The indenter goes into the bed.
    Loading = 0,
    /// The indenter comes out of the bed after the turn.
    Unloading = 1,
    /// The indenter has left the bed after unloading.
    Done = 2,
}

/// What the test has recorded so far (saved with the bed in a saved state).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Record {
    /// Where the test is.
    pub state: TestState,
    /// Largest force and largest depth of the loading [N], [m].
    pub f_max: f64,
    /// Largest depth of the loading [m].
    pub h_max: f64,
    /// (h, F) of the upper part of the unloading curve.
    pub unloading: Vec<(f64, f64)>,
    /// h_c once the tangent is known [m].
    pub contact_depth: Option<f64>,
    /// Whether the unloading has ended its upper part (the tangent found or not).
    pub tangent_done: bool,
    /// Height of the indenter's lowest point at first touch [m].
    pub touch: f64,
    /// Height of the depth origin [m] (`DepthOrigin`): h = origin - the indenter's lowest point.
    pub origin: f64,
    /// Communication time not yet stepped [s].
    pub time_debt: f64,
    /// Engine steps since the indenter was put in (the checks fall on multiples of `CHECK_EVERY`).
    pub steps: u64,
    /// (h, F) at every check while loading, in the order taken.
    pub loading: Vec<(f64, f64)>,
    /// (h, sigma_hyd, tau_D) of the dynamic bin (004 Eqs. 5.2-5.3, Sec. 5.3) at every check while loading
    /// with h/r in the plateau window, in the order taken [m], [Pa], [Pa].
    pub window_stress: Vec<(f64, f64, f64)>,
}

impl Record {
    /// The plateau hardness: the mean of F/A(h) over the loading samples at h/r within `window` (004
    /// Figs. 5.2-5.3), its standard error and the number of samples (mean 0 before the first) [Pa].
    pub fn plateau(&self, d: f64, window: (f64, f64)) -> MeanEstimate {
        let samples: Vec<f64> = self.loading.iter().filter(|&&(h, _)| in_window(d, h, window)).map(|&(h, f)| f / projected_area(d, h)).collect();
        series::mean_with_error(&samples)
    }

    /// The dynamic bin's hydrostatic and deviatoric stresses (004 Eqs. 5.2-5.3) averaged over the loading
    /// checks at h/r within `window`, each with its standard error from the autocorrelated samples
    /// (`series::mean_with_error`; mean 0 before the first) [Pa]: the levels 004 reads from its dynamic bin
    /// (Fig. 5.19, Figs. 7.3-7.5). Only checks within the test's own window were sampled.
    pub fn window_stress(&self, d: f64, window: (f64, f64)) -> [MeanEstimate; 2] {
        let inside: Vec<&(f64, f64, f64)> = self.window_stress.iter().filter(|s| in_window(d, s.0, window)).collect();
        [
            series::mean_with_error(&inside.iter().map(|s| s.1).collect::<Vec<_>>()),
            series::mean_with_error(&inside.iter().map(|s| s.2).collect::<Vec<_>>()),
        ]
    }

    /// The force at the turn [N]: A(h_max) times the mean of F/A(h) over the loading samples within the
    /// last `TURN_FIT` of h_max (the largest sample where none lie there). A local reading of the
    /// fluctuating curve, not its largest sample: over the 29 recorded runs of docs/data the largest
    /// sample read the hardness 19 % above the plateau on average (-13 to +71 %), this reading 4 % below
    /// (-23 to +14 %), and the least-squares line over the same samples taken at h_max 12 % below
    /// (`benches/indentation_outputs.py`).
    pub fn turn_force(&self, d: f64) -> f64 {
        let hardness = self.turn_samples(d);
        if hardness.is_empty() {
            return self.f_max;
        }
        projected_area(d, self.h_max) * hardness.iter().sum::<f64>() / hardness.len() as f64
    }

    /// F/A(h) of the loading samples within the last `TURN_FIT` of h_max, in the order taken [Pa].
    fn turn_samples(&self, d: f64) -> Vec<f64> {
        let from = self.h_max * (1.0 - TURN_FIT);
        self.loading.iter().filter(|&&(h, _)| h >= from && projected_area(d, h) > 0.0).map(|&(h, f)| f / projected_area(d, h)).collect()
    }

    /// The standard error of `hardness_after_turn` from the fluctuations of the force it reads [Pa]. The m
    /// samples behind `turn_force` span less than one correlation time of the force (tens to hundreds of
    /// samples), so their own scatter would understate the error (by 3 times over five default runs,
    /// docs/indentation.md): the variance sigma^2 and the correlation time tau come from the longer series
    /// of the loading's deeper half (h >= h_max / 2, `series::mean_with_error`), and the local mean's
    /// variance is sigma^2 min(1, tau / m) (one sample's where m < tau). Times A(h_max) / A(h_c). 0 below
    /// `series::MIN_SAMPLES` samples in either series. h_c's own uncertainty is not in it.
    pub fn hardness_after_turn_error(&self, d: f64) -> f64 {
        let a = projected_area(d, self.contact_depth_or_max());
        let m = self.turn_samples(d).len();
        let deeper: Vec<f64> = self
            .loading
            .iter()
            .filter(|&&(h, _)| h >= 0.5 * self.h_max && projected_area(d, h) > 0.0)
            .map(|&(h, f)| f / projected_area(d, h))
            .collect();
        let e = series::mean_with_error(&deeper);
        if !(a > 0.0) || m < series::MIN_SAMPLES || e.correlation_time == 0.0 {
            return 0.0;
        }
        let n = deeper.len() as f64;
        let sigma2 = deeper.iter().map(|x| (x - e.mean) * (x - e.mean)).sum::<f64>() / (n - 1.0);
        projected_area(d, self.h_max) / a * (sigma2 * (e.correlation_time / m as f64).min(1.0)).sqrt()
    }

    /// h_c from the tangent, or h_max where there is none (yet) [m].
    pub fn contact_depth_or_max(&self) -> f64 {
        self.contact_depth.unwrap_or(self.h_max)
    }

    /// The hardness after the turn, F_max / A(h_c) with F_max = `turn_force` (0 before any depth) [Pa].
    pub fn hardness_after_turn(&self, d: f64) -> f64 {
        let a = projected_area(d, self.contact_depth_or_max());
        if a > 0.0 {
            self.turn_force(d) / a
        } else {
            0.0
        }
    }
}

/// The outputs of the test at the current state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// Force of the bed on the indenter, upward [N].
    pub force: f64,
    /// h [m].
    pub depth: f64,
    /// h / r.
    pub dimensionless_depth: f64,
    /// A(h) [m^2].
    pub projected_area: f64,
    /// [Pa].
    pub hardness: f64,
    /// After the turn, the standard error of `hardness` from the fluctuations of the force at the turn
    /// (`Record::hardness_after_turn_error`); 0 while loading (the hardness is then one sample) [Pa].
    pub hardness_standard_error: f64,
    /// `hardness` / C (004 Eq. 2.10) [Pa].
    pub unconfined_yield_strength: f64,
    /// The standard error of `unconfined_yield_strength` from those of the hardness and of C
    /// (`yield_strength_error`) [Pa].
    pub unconfined_yield_strength_standard_error: f64,
    /// C the yield strength was divided by.
    pub constraint_factor: f64,
    /// C's standard error (0 for a constant C).
    pub constraint_factor_standard_error: f64,
    /// Hydrostatic stress of Bagi's tensor in the dynamic bin (004 Eq. 5.2) [Pa].
    pub hydrostatic_stress: f64,
    /// Deviatoric stress of Bagi's tensor in the dynamic bin (004 Eq. 5.3) [Pa].
    pub deviatoric_stress: f64,
    /// `hydrostatic_stress` averaged over the loading checks in the plateau window, with its standard
    /// error (`Record::window_stress`).
    pub window_hydrostatic_stress: MeanEstimate,
    /// The same for `deviatoric_stress`.
    pub window_deviatoric_stress: MeanEstimate,
    /// Spheres touching the indenter (the whole die's on a sector).
    pub contacts: usize,
    /// Kinetic energy of the bed, translational plus rotational (the whole die's on a sector) [J].
    pub kinetic_energy: f64,
    /// Where the test is.
    pub state: TestState,
    /// h_c from the tangent to the unloading curve; h_max (so far) where there is none [m].
    pub contact_depth: f64,
    /// Whether `contact_depth` is the tangent's.
    pub contact_depth_from_tangent: bool,
    /// The force at the turn (`Record::turn_force`) [N]; during loading, the same reading at the
    /// deepest point so far.
    pub turn_force: f64,
    /// Mean F/A(h) while loading within the plateau window, its standard error and sample count.
    pub plateau: MeanEstimate,
    /// Height of the first touch above the depth origin [m] (0 with `DepthOrigin::FirstTouch`).
    pub depth_origin_offset: f64,
}

/// The standard error of sigma_c = H / C from the part the hardness gives (its standard error over C)
/// and C's relative standard error: the two independent, added in quadrature. With C exact, the first
/// to the bit.
pub fn yield_strength_error(from_hardness: f64, yield_strength: f64, relative_c_error: f64) -> f64 {
    from_hardness.hypot(yield_strength * relative_c_error)
}

/// A prepared bed with the indenter in it.
pub struct Indentation {
    /// The bed's engine, the indenter among its walls.
    pub engine: AnyEngine,
    /// The bed's scene.
    pub scene: BedScene,
    /// The test's set-up.
    pub setup: Setup,
    /// What the test has recorded so far.
    pub record: Record,
    /// The indenter's index among the walls.
    indenter: usize,
    /// The particle-indenter scene keys and rolling friction coefficient, and the die's, floor's and
    /// piston's keys for this test if not the bed's own (`set_die_walls`): a saved state carries them,
    /// as the bed file holds only the bed's.
    indenter_pair: Map<String, Value>,
    indenter_rolling_friction: f64,
    die_pair: Option<Map<String, Value>>,
    /// The window's estimates of the last reading (the plateau, the bin's two levels) and how many loading
    /// samples they saw (the bin is sampled with them): a host reading at every short communication step
    /// does not repeat the autocorrelation sums (O(n W)) between checks.
    window_cache: Option<(usize, MeanEstimate, [MeanEstimate; 2])>,
}

/// Whether depth h [m] of an indenter of diameter d [m] lies in `window` (h/r, both ends included) with
/// the indenter in the bed: the samples the plateau and the bin's levels are read from.
fn in_window(d: f64, h: f64, window: (f64, f64)) -> bool {
    let hr = h / (0.5 * d);
    hr >= window.0 && hr <= window.1 && projected_area(d, h) > 0.0
}

/// A(h) = pi (d h - h^2) (004 Eq. 2.9), 0 outside the indenter.
pub fn projected_area(d: f64, h: f64) -> f64 {
    let h = h.clamp(0.0, d);
    PI * (d * h - h * h)
}

/// Height of the lowest point of a sphere of radius `r_i`, lowered along the die axis, when it first
/// touches one of the particles: max over the spheres within reach of z - r_i + sqrt((r_i + r)^2 - rho^2).
pub fn first_touch_height(p: &Particles, r_i: f64) -> Option<f64> {
    touch_height_at(p.position.iter().copied().zip(p.radius.iter().copied()), r_i, 0.0, 0.0)
}

/// Height of the lowest point of a sphere of radius `r_i` lowered along the vertical line through (x, y)
/// when it first touches one of `spheres` (centre, radius): max over those within reach of
/// z - r_i + sqrt((r_i + r)^2 - rho^2), rho their distance from the line.
fn touch_height_at(spheres: impl IntoIterator<Item = (Vec3, f64)>, r_i: f64, x: f64, y: f64) -> Option<f64> {
    let mut top: Option<f64> = None;
    for (c, r) in spheres {
        let (dx, dy) = (c.x - x, c.y - y);
        let rho2 = dx * dx + dy * dy;
        let reach2 = (r_i + r) * (r_i + r);
        if rho2 < reach2 {
            let z = c.z - r_i + (reach2 - rho2).sqrt();
            top = Some(top.map_or(z, |t: f64| t.max(z)));
        }
    }
    top
}

/// Height of the bed's mean surface under a disc of radius `footprint` about the die axis: a probe sphere
/// of radius `probe`, lowered along vertical lines on a square grid of spacing `spacing` within the disc,
/// gives at each line the height of its lowest point when it first touches a sphere (or a mirror image of
/// one: `mirrors`, the die sector's planes); the mean over the lines. None where no line meets a sphere.
pub fn mean_surface_height(p: &Particles, mirrors: &[Wall], probe: f64, footprint: f64, spacing: f64) -> Option<f64> {
    // The spheres and their images through every combination of the mirror planes.
    let mut centres: Vec<(Vec3, f64)> = p.position.iter().copied().zip(p.radius.iter().copied()).collect();
    for m in mirrors {
        let images: Vec<(Vec3, f64)> = centres
            .iter()
            .map(|&(x, r)| {
                // touch() of a mirror at r = 0 gives -2 (d . n) along -n: the image is x - 2 (d . n) n.
                let t = m.touch(x, 0.0);
                (x - t.normal * t.overlap, r)
            })
            .collect();
        centres.extend(images);
    }
    centres.retain(|&(c, r)| c.xy().norm() < footprint + probe + r);
    let k = (footprint / spacing).floor() as i64;
    let (mut sum, mut lines) = (0.0, 0usize);
    for a in -k..=k {
        for b in -k..=k {
            let (x, y) = (a as f64 * spacing, b as f64 * spacing);
            if x * x + y * y > footprint * footprint {
                continue;
            }
            if let Some(z) = touch_height_at(centres.iter().copied(), probe, x, y) {
                sum += z;
                lines += 1;
            }
        }
    }
    (lines > 0).then(|| sum / lines as f64)
}

impl Indentation {
    /// Puts the indenter into a prepared bed, its lowest point at depth `start_depth` below the depth
    /// origin (negative = above it; none: at the first touch). Refuses an indenter wider than the die, a
    /// depth beyond the bed, a start inside the bed, an empty plateau window, and a bed with nothing
    /// under the indenter (a window beyond the turn is allowed: its plateau stays without samples). `indenter_pair`: the particle-indenter scene keys (none: the
    /// bed's, `BedScene::indenter_pair`); the rolling friction against the indenter is the bed's
    /// (`BedScene::indenter_rolling_friction`).
    pub fn new(
        mut engine: AnyEngine,
        scene: BedScene,
        setup: Setup,
        start_depth: Option<f64>,
        indenter_pair: Option<&Map<String, Value>>,
    ) -> Result<Indentation, BedError> {
        let d = setup.indenter_diameter;
        let die = scene.die_diameter;
        if !(d > 0.0 && d < die) {
            return Err(
                ParamError::OutOfRange { name: "indenter_diameter", value: d, allowed: format!("(0, {die:e}) m: narrower than the die") }.into()
            );
        }
        let height = super::prepare::bed_height(engine.particles());
        if !(setup.max_penetration > 0.0 && setup.max_penetration < height.min(0.5 * d)) {
            return Err(ParamError::OutOfRange {
                name: "max_penetration",
                value: setup.max_penetration,
                allowed: format!("(0, {:e}) m: within the bed ({height:e} m high) and the indenter's radius", height.min(0.5 * d)),
            }
            .into());
        }
        if !(setup.indentation_speed > 0.0 && setup.indentation_speed.is_finite()) {
            return Err(ParamError::OutOfRange { name: "indentation_speed", value: setup.indentation_speed, allowed: "(0, inf) m/s".into() }.into());
        }
        if !(setup.constraint_factor > 0.0 && setup.constraint_factor.is_finite()) {
            return Err(ParamError::OutOfRange { name: "constraint_factor", value: setup.constraint_factor, allowed: "(0, inf)".into() }.into());
        }
        let c_error = setup.constraint_factor_standard_error;
        if !(c_error >= 0.0 && c_error.is_finite()) {
            return Err(ParamError::OutOfRange { name: "constraint_factor_standard_error", value: c_error, allowed: "[0, inf)".into() }.into());
        }
        let (p0, p1) = setup.plateau;
        if !(p0 >= 0.0 && p0.is_finite()) {
            return Err(ParamError::OutOfRange { name: "plateau_start", value: p0, allowed: "[0, plateau_end) (h/r)".into() }.into());
        }
        if !(p1 > p0 && p1.is_finite()) {
            return Err(ParamError::OutOfRange { name: "plateau_end", value: p1, allowed: format!("({p0}, inf) (h/r): above plateau_start") }.into());
        }
        let r_i = 0.5 * d;
        let touch = first_touch_height(engine.particles(), r_i)
            .ok_or_else(|| BedError::Setup("no sphere of the bed lies under the indenter: nothing to indent".into()))?;
        let origin = match setup.depth_origin {
            DepthOrigin::FirstTouch => touch,
            DepthOrigin::MeanSurface => {
                let mean = scene.size_distribution.mean_diameter();
                let h = setup.max_penetration;
                let footprint = (d * h - h * h).sqrt();
                let mirrors: Vec<Wall> = engine.walls().iter().filter(|w| w.is_mirror()).cloned().collect();
                mean_surface_height(engine.particles(), &mirrors, 0.5 * mean, footprint, 0.25 * mean)
                    .ok_or_else(|| BedError::Setup("no sphere of the bed lies under the indenter's footprint: no mean surface".into()))?
            }
        };
        let start_depth = start_depth.unwrap_or(origin - touch);
        if !(start_depth <= origin - touch) {
            return Err(ParamError::OutOfRange {
                name: "indenter_displacement",
                value: start_depth,
                allowed: format!(
                    "(-inf, {:e}] m at the start: the indenter starts at or above its first touch of the bed ({:e} m below the depth origin, {})",
                    origin - touch,
                    origin - touch,
                    setup.depth_origin.name()
                ),
            }
            .into());
        }
        let bottom = origin - start_depth;
        let pair = indenter_pair.cloned().unwrap_or_else(|| scene.indenter_pair());
        let rolling = scene.indenter_rolling_friction();
        engine.add_wall(&scene, Wall::sphere("indenter", Vec3::new(0.0, 0.0, bottom + r_i), r_i), &pair, rolling)?;
        let indenter = engine.walls().len() - 1;
        if let Some(Shortcut { zone, release }) = setup.shortcut {
            if !(zone > 0.0 && zone.is_finite()) {
                return Err(ParamError::OutOfRange { name: "mobile_zone", value: zone, allowed: "(0, inf) contact radii".into() }.into());
            }
            if !(release > 0.0) {
                return Err(ParamError::OutOfRange { name: "release", value: release, allowed: "(0, inf] of the contact force scale".into() }.into());
            }
            let held = held_outside(engine.particles(), &setup, touch, scene.size_distribution.mean_diameter());
            engine.hold(&held);
        }
        let record = Record {
            state: TestState::Loading,
            f_max: 0.0,
            h_max: 0.0,
            unloading: vec![],
            contact_depth: None,
            tangent_done: false,
            touch,
            origin,
            time_debt: 0.0,
            steps: 0,
            loading: vec![],
            window_stress: vec![],
        };
        let mut test = Indentation {
            engine,
            scene,
            setup,
            record,
            indenter,
            indenter_pair: pair,
            indenter_rolling_friction: rolling,
            die_pair: None,
            window_cache: None,
        };
        if setup.motion == Motion::Prescribed {
            test.set_indenter_velocity(-setup.indentation_speed);
        }
        Ok(test)
    }

    /// Gives the die, its floor and the piston the particle-wall scene keys `pair` for this test (a
    /// mirror plane keeps the particles' own law), every contact keeping its memory. A shortcut: softer
    /// walls allow a longer time step (docs/indentation.md measures what it costs).
    pub fn set_die_walls(&mut self, pair: &Map<String, Value>) -> Result<(), BedError> {
        set_die_pair(&mut self.engine, &self.scene, self.indenter, pair)?;
        self.die_pair = Some(pair.clone());
        Ok(())
    }

    fn indenter(&self) -> &Wall {
        &self.engine.walls()[self.indenter]
    }

    fn set_indenter_velocity(&mut self, vz: f64) {
        let w = self.indenter;
        self.engine.walls_mut()[w].velocity = Vec3::new(0.0, 0.0, vz);
    }

    /// Depth of the indenter's lowest point below the depth origin [m].
    pub fn depth(&self) -> f64 {
        let w = self.indenter();
        self.record.origin - (w.position[2] - 0.5 * self.setup.indenter_diameter)
    }

    /// Force of the bed on the indenter, upward [N]: on a die sector, the sector's times the number of
    /// its images (each sphere stands for 1 / die_sector spheres of the whole die).
    pub fn force(&self) -> f64 {
        self.indenter().force[2] / self.scene.die_sector
    }

    /// Spheres touching the indenter (on a die sector, with their mirror images).
    pub fn contacts(&self) -> usize {
        (self.engine.wall_touching(self.indenter) as f64 / self.scene.die_sector).round() as usize
    }

    /// The depth an input step asks for by its end, refused (naming the input) if not finite or past the
    /// indenter's radius; none with a prescribed motion. Nothing moves: callers check every bed before
    /// stepping any (`bed::replicas`).
    pub fn input_target(&self, h: f64, input: Option<(f64, f64)>) -> Result<Option<f64>, BedError> {
        Ok(match (self.setup.motion, input) {
            (Motion::Input, Some((depth, rate))) => {
                let target = depth + rate * h;
                if !(target.is_finite() && target < 0.5 * self.setup.indenter_diameter) {
                    return Err(ParamError::OutOfRange {
                        name: "indenter_displacement",
                        value: target,
                        allowed: format!("below {:e} m (the indenter's radius) and finite", 0.5 * self.setup.indenter_diameter),
                    }
                    .into());
                }
                Some(target)
            }
            _ => None,
        })
    }

    /// Advances the test by `h` seconds. With `Motion::Input`, `input` = (depth, rate) at the start of
    /// the step: the indenter moves at constant speed to depth + rate h over the step.
    pub fn advance(&mut self, h: f64, input: Option<(f64, f64)>) -> Result<(), BedError> {
        let dt = self.engine.dt();
        // The inputs are checked before anything moves: a refused step leaves the state as it was.
        let target = self.input_target(h, input)?;
        if self.setup.motion == Motion::Prescribed && self.record.state == TestState::Done {
            // The prescribed test is over: the bed is not stepped any more (it would cost as much as the
            // test itself, for a bed nobody reads), so a host's stop time past the end is free.
            return Ok(());
        }
        self.record.time_debt += h;
        let n = (self.record.time_debt / dt).floor().max(0.0) as u64;
        self.record.time_debt -= n as f64 * dt;
        if n == 0 {
            return Ok(());
        }
        if let Some(target) = target {
            let vz = -(target - self.depth()) / (n as f64 * dt);
            self.set_indenter_velocity(vz);
        }
        let mut left = n;
        while left > 0 {
            // The upper unloading curve is steep: sampled at every step until its tangent is known.
            let every = if self.record.state == TestState::Unloading && !self.record.tangent_done { 1 } else { CHECK_EVERY };
            let to_check = every - self.record.steps % every;
            let mut chunk = left.min(to_check);
            // A prescribed indenter turns at the step that reaches max_penetration.
            let mut turn = false;
            if self.setup.motion == Motion::Prescribed && self.record.state == TestState::Loading {
                let k = ((self.setup.max_penetration - self.depth()) / (self.setup.indentation_speed * dt)).ceil().max(1.0) as u64;
                if k <= chunk {
                    chunk = k;
                    turn = true;
                }
            }
            self.engine.run(chunk);
            self.record.steps += chunk;
            left -= chunk;
            if chunk == to_check || turn {
                self.check();
            }
        }
        if !self.engine.particles().kinetic_energy().is_finite() {
            return Err(BedError::Setup("the bed blew up (kinetic energy not finite): lower the bed's time_step or the indentation speed".into()));
        }
        Ok(())
    }

    /// The test's progress at a check: the released spheres, the largest force, the unloading points,
    /// turning and ending.
    fn check(&mut self) {
        if let Some(s) = self.setup.shortcut {
            let d = self.scene.size_distribution.mean_diameter();
            self.engine.release_disturbed(s.release * self.scene.consolidation_stress * d * d);
        }
        let (h, f) = (self.depth(), self.force());
        let loading = match self.setup.motion {
            Motion::Prescribed => self.record.state == TestState::Loading,
            Motion::Input => self.indenter().velocity[2] <= 0.0,
        };
        if loading && self.record.state != TestState::Done {
            self.record.state = TestState::Loading;
            self.record.f_max = self.record.f_max.max(f);
            self.record.h_max = self.record.h_max.max(h);
            self.record.unloading.clear();
            self.record.contact_depth = None;
            self.record.tangent_done = false;
            self.record.loading.push((h, f));
            // The bin's stresses where the plateau is read: a force evaluation per check there (about 1 % of
            // the window's steps), none elsewhere.
            if in_window(self.setup.indenter_diameter, h, self.setup.plateau) {
                let stress = self.bin_stress();
                self.record.window_stress.push((h, stress.hydrostatic(), stress.deviatoric()));
            }
            if self.setup.motion == Motion::Prescribed && h >= self.setup.max_penetration * (1.0 - 1e-9) {
                self.record.state = TestState::Unloading;
                self.set_indenter_velocity(self.setup.indentation_speed);
            }
            return;
        }
        if self.record.state == TestState::Loading {
            self.record.state = TestState::Unloading;
        }
        if self.record.state == TestState::Unloading {
            if !self.record.tangent_done {
                let start = self.record.unloading.first().map_or(f, |p| p.1);
                if f >= TANGENT_FRACTION * start && f > 0.0 {
                    self.record.unloading.push((h, f));
                } else {
                    self.record.contact_depth = tangent_depth(&self.record.unloading);
                    self.record.tangent_done = true;
                }
            }
            // Done once the indenter has left the bed; a prescribed indenter goes on rising at its speed,
            // so that the bed's surface, relaxing, does not meet it again.
            if self.contacts() == 0 && h < self.record.h_max {
                self.record.state = TestState::Done;
            }
        }
    }

    /// The plateau hardness and the bin's levels of the record so far (`Record::plateau` and
    /// `Record::window_stress` with the set-up's window), computed again only when a loading sample has
    /// been added.
    fn window_estimates(&mut self) -> (MeanEstimate, [MeanEstimate; 2]) {
        let n = self.record.loading.len();
        match self.window_cache {
            Some((seen, p, s)) if seen == n => (p, s),
            _ => {
                let (d, window) = (self.setup.indenter_diameter, self.setup.plateau);
                let (p, s) = (self.record.plateau(d, window), self.record.window_stress(d, window));
                self.window_cache = Some((n, p, s));
                (p, s)
            }
        }
    }

    /// The plateau hardness of the record so far (`window_estimates`).
    pub fn plateau(&mut self) -> MeanEstimate {
        self.window_estimates().0
    }

    /// Bagi's stress (004 Eq. 5.1) in the dynamic bin: BIN mean diameters wide and deep, directly under
    /// the indenter and moving with it (004 Sec. 5.3, Fig. 5.18), as the whole die's on a sector. One extra
    /// force evaluation, which leaves the state unchanged.
    fn bin_stress(&mut self) -> super::stress::Stress {
        let mean = self.scene.size_distribution.mean_diameter();
        let bottom = self.indenter().position[2] - 0.5 * self.setup.indenter_diameter;
        let bin = Cuboid { width_x: BIN[0] * mean, width_y: BIN[1] * mean, z_low: bottom - BIN[2] * mean, z_high: bottom };
        assert!(bin.volume() > 0.0);
        bagi(&mut self.engine, &bin).of_whole_die(self.scene.die_sector)
    }

    /// The bin's hydrostatic and deviatoric levels of the record so far (`window_estimates`).
    pub fn window_stress(&mut self) -> [MeanEstimate; 2] {
        self.window_estimates().1
    }

    /// The outputs at the current state (one extra force evaluation for Bagi's stress, which leaves the
    /// state unchanged).
    pub fn reading(&mut self) -> Reading {
        let (d, f, h) = (self.setup.indenter_diameter, self.force(), self.depth());
        let (c, c_error) = (self.setup.constraint_factor, self.setup.constraint_factor_standard_error);
        let area = projected_area(d, h);
        let (hardness, hardness_standard_error) = match self.record.state {
            TestState::Loading if area > 0.0 => (f / area, 0.0),
            TestState::Loading => (0.0, 0.0),
            _ => (self.record.hardness_after_turn(d), self.record.hardness_after_turn_error(d)),
        };
        let stress = self.bin_stress();
        let window_stress = self.window_stress();
        Reading {
            force: f,
            depth: h,
            dimensionless_depth: h / (0.5 * d),
            projected_area: area,
            hardness,
            hardness_standard_error,
            unconfined_yield_strength: hardness / c,
            unconfined_yield_strength_standard_error: yield_strength_error(hardness_standard_error / c, hardness / c, c_error / c),
            constraint_factor: c,
            constraint_factor_standard_error: c_error,
            hydrostatic_stress: stress.hydrostatic(),
            deviatoric_stress: stress.deviatoric(),
            window_hydrostatic_stress: window_stress[0],
            window_deviatoric_stress: window_stress[1],
            contacts: self.contacts(),
            kinetic_energy: self.engine.particles().kinetic_energy() / self.scene.die_sector,
            state: self.record.state,
            contact_depth: self.record.contact_depth_or_max(),
            contact_depth_from_tangent: self.record.contact_depth.is_some(),
            turn_force: self.record.turn_force(d),
            plateau: self.plateau(),
            depth_origin_offset: self.record.touch - self.record.origin,
        }
    }

    /// The whole state as bytes: the bed (with the indenter, every contact's memory and the last
    /// forces, `bed::file`) and the record; an error where some part cannot be serialised.
    pub fn save(&self) -> Result<Vec<u8>, BedError> {
        let (list_reference, wall_reference) = self.engine.list_reference();
        let saved = Saved {
            bed: file::encode(&self.engine.to_file(&self.scene)?)?,
            setup: self.setup,
            record: self.record.clone(),
            indenter: self.indenter as u32,
            time_step: self.engine.dt(),
            held: self.engine.particles().held.clone(),
            held_reference: self.engine.held_reference(),
            indenter_pair: Value::Object(self.indenter_pair.clone()).to_string(),
            indenter_rolling_friction: self.indenter_rolling_friction,
            die_pair: self.die_pair.as_ref().map(|m| Value::Object(m.clone()).to_string()),
            list_reference,
            wall_reference,
        };
        crate::codec::to_bytes(&saved).map_err(|e| BedError::Setup(format!("the indentation state cannot be saved: {e}")))
    }

    /// Reads back what `save` wrote, with `threads` threads.
    pub fn restore(bytes: &[u8], threads: Option<usize>) -> Result<Indentation, BedError> {
        let saved: Saved =
            crate::codec::from_bytes(bytes).map_err(|e| BedError::Setup(format!("the saved indentation state cannot be read: {e}")))?;
        let file: BedFile = file::decode(&saved.bed)?;
        let (mut engine, scene) = AnyEngine::from_file(&file, threads)?;
        let indenter = saved.indenter as usize;
        if indenter >= engine.walls().len() {
            return Err(BedError::Setup("the saved indentation state has no indenter".into()));
        }
        // The bed file rebuilds every wall with the bed's particle-wall keys: the test's own go back on
        // before the step they allow.
        let object = |text: &str| -> Result<Map<String, Value>, BedError> {
            match serde_json::from_str(text) {
                Ok(Value::Object(m)) => Ok(m),
                _ => Err(BedError::Setup("the saved indentation state holds unreadable wall keys".into())),
            }
        };
        let indenter_pair = object(&saved.indenter_pair)?;
        engine.set_wall_pair(&scene, indenter, &indenter_pair, saved.indenter_rolling_friction)?;
        let die_pair = saved.die_pair.as_deref().map(object).transpose()?;
        if let Some(pair) = &die_pair {
            set_die_pair(&mut engine, &scene, indenter, pair)?;
        }
        engine.set_time_step(&scene, saved.time_step)?;
        if saved.held.len() != engine.particles().len() {
            return Err(BedError::Setup("the saved indentation state holds a different number of spheres than its bed".into()));
        }
        if saved.held.iter().any(|&h| h) {
            if saved.held_reference.len() != saved.held.len() {
                return Err(BedError::Setup("the saved indentation state has no reference forces for its held spheres".into()));
            }
            engine.restore_held(saved.held, saved.held_reference);
        }
        if !engine.rebuild_at(&saved.list_reference, &saved.wall_reference) {
            return Err(BedError::Setup("the saved indentation state's list positions do not match its bed".into()));
        }
        Ok(Indentation {
            engine,
            scene,
            setup: saved.setup,
            record: saved.record,
            indenter,
            indenter_pair,
            indenter_rolling_friction: saved.indenter_rolling_friction,
            die_pair,
            window_cache: None,
        })
    }
}

/// Gives every wall but the indenter and the mirror planes (the die, its floor, the piston) the
/// particle-wall keys `pair`.
fn set_die_pair(engine: &mut AnyEngine, scene: &BedScene, indenter: usize, pair: &Map<String, Value>) -> Result<(), BedError> {
    for w in 0..engine.walls().len() {
        if w != indenter && !engine.walls()[w].is_mirror() {
            engine.set_wall_pair(scene, w, pair, scene.wall_rolling_friction)?;
        }
    }
    Ok(())
}

#[derive(serde::Serialize, serde::Deserialize)]
struct Saved {
    bed: Vec<u8>,
    setup: Setup,
    record: Record,
    indenter: u32,
    /// The engine's step (a bed file holds its scene's, which the test may have changed).
    time_step: f64,
    /// The spheres held by the shortcut, and the force on each when it was held.
    held: Vec<bool>,
    held_reference: Vec<Vec3>,
    /// The particle-indenter keys and the test's die keys (JSON objects), and the indenter's rolling
    /// friction coefficient.
    indenter_pair: String,
    indenter_rolling_friction: f64,
    die_pair: Option<String>,
    /// The positions of the engine's last list build, the spheres' and the walls' (`Engine::rebuild_at`):
    /// a restored test rebuilds its list there, so it continues bit for bit on any number of threads.
    list_reference: Vec<Vec3>,
    wall_reference: Vec<Vec3>,
}

/// h_c = h_0 - F_0 / S: where the tangent to the unloading curve at its start (h_0, F_0) = `points[0]`
/// meets zero force, S the least-squares slope of F against h over `points` (at least three; S > 0 and
/// h_c within (0, h_0]); none otherwise.
pub fn tangent_depth(points: &[(f64, f64)]) -> Option<f64> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let (mh, mf) = points.iter().fold((0.0, 0.0), |(a, b), (h, f)| (a + h / n, b + f / n));
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), (h, f)| (a + (h - mh) * (f - mf), b + (h - mh) * (h - mh)));
    let slope = sxy / sxx;
    let (h0, f0) = points[0];
    let hc = h0 - f0 / slope;
    (slope > 0.0 && hc > 0.0 && hc <= h0).then_some(hc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A finished record whose loading samples read F/A(h) = `hardness(k)` at sample k, h from 0 to h_max.
    fn record(d: f64, h_max: f64, contact_depth: f64, n: usize, mut hardness: impl FnMut(usize) -> f64) -> Record {
        let loading: Vec<(f64, f64)> = (1..=n)
            .map(|k| {
                let h = h_max * k as f64 / n as f64;
                (h, hardness(k) * projected_area(d, h))
            })
            .collect();
        let f_max = loading.iter().map(|p| p.1).fold(0.0, f64::max);
        Record {
            state: TestState::Done,
            f_max,
            h_max,
            unloading: vec![],
            contact_depth: Some(contact_depth),
            tangent_done: true,
            touch: 0.0,
            origin: 0.0,
            time_debt: 0.0,
            steps: 0,
            loading,
            window_stress: vec![],
        }
    }

    #[test]
    fn the_window_stresses_are_means_over_the_window_with_the_series_error() {
        let d = 0.016;
        let r = 0.5 * d;
        let mut rec = record(d, 4e-3, 4e-3, 10, |_| 7e3);
        // White noise of known variance around 5 and 3 kPa inside h/r 0.35-0.5; other levels outside it.
        let mut x = 0.123f64;
        for k in 0..2000 {
            let hr = 0.3 + 0.25 * k as f64 / 2000.0;
            x = (x * 9301.0 + 0.4927).fract();
            let (hyd, dev) = if (0.35..=0.5).contains(&hr) { (5e3 + 600.0 * (x - 0.5), 3e3 - 600.0 * (x - 0.5)) } else { (9e4, 9e4) };
            rec.window_stress.push((hr * r, hyd, dev));
        }
        let [hyd, dev] = rec.window_stress(d, (0.35, 0.5));
        assert_eq!(hyd.samples, dev.samples);
        assert!((1150..=1250).contains(&hyd.samples), "{}", hyd.samples);
        // sigma = 600 / sqrt(12) = 173 Pa: the mean within 4 standard errors of white noise (5 Pa).
        let se = 600.0 / 12f64.sqrt() / (hyd.samples as f64).sqrt();
        assert!((hyd.mean - 5e3).abs() < 4.0 * se && (dev.mean - 3e3).abs() < 4.0 * se, "{hyd:?} {dev:?}");
        assert!(hyd.standard_error > 0.5 * se && hyd.standard_error < 2.0 * se, "{} against {se}", hyd.standard_error);
        // Before the window: no estimate, mean 0.
        let empty = Record { window_stress: vec![], ..rec.clone() }.window_stress(d, (0.35, 0.5));
        assert_eq!((empty[0].mean, empty[0].samples), (0.0, 0));
    }

    #[test]
    fn the_hardness_error_is_the_turn_force_s_scaled_to_the_contact_depth() {
        let (d, h_max, h_c) = (0.016, 1.6e-3, 1.4e-3);
        // White noise of known variance: uniform on [-u, u], sigma = u / sqrt(3), around 8 kPa.
        let (u, n) = (800.0, 4000);
        let mut state = 12345u64;
        let rec = record(d, h_max, h_c, n, |_| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            8000.0 + u * (2.0 * (state >> 11) as f64 / (1u64 << 53) as f64 - 1.0)
        });
        // The last tenth of h_max holds 401 samples (k = 3600..=4000).
        let m = (n / 10 + 1) as f64;
        let expected = projected_area(d, h_max) / projected_area(d, h_c) * u / 3f64.sqrt() / m.sqrt();
        let got = rec.hardness_after_turn_error(d);
        // White noise: tau = 1 from the 2000 samples of the deeper half, so sigma / sqrt(m) to the
        // estimators' scatter.
        assert!((got / expected - 1.0).abs() < 0.15, "{got} vs {expected} Pa");
        // A force that wanders slowly (autoregressive, tau = (1 + phi) / (1 - phi) = 99 samples: the
        // turn's 401 samples hold four correlation times, the deeper half's 2000 twenty). Over 100 such
        // runs the error's mean square against the exact variance of an AR(1) window's mean, sigma^2/m
        // (tau - 2 phi (1 - phi^m) / (m (1 - phi)^2)): not below it, and the error conservative by less
        // than sqrt(2) (sigma^2 tau / m is the long-window limit, 1.14 times the exact value here, and
        // the put-back of `series::mean_with_error` errs high on twenty tau: measured 1.60 in variance,
        // 1.26 in the error). The 401 samples' own scatter understates it.
        let phi: f64 = 0.98;
        let sigma = 400.0;
        let mut state = 987654321u64;
        let mut normal = move || {
            let mut u = || {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
            };
            let (a, b) = (u(), u());
            (-2.0 * a.ln()).sqrt() * (2.0 * std::f64::consts::PI * b).cos()
        };
        let ratio = projected_area(d, h_max) / projected_area(d, h_c);
        let (runs, mut got2, mut own2) = (100, 0.0, 0.0);
        for _ in 0..runs {
            let mut x = normal() / (1.0 - phi * phi).sqrt();
            let slow = record(d, h_max, h_c, n, |_| {
                x = phi * x + normal();
                8000.0 + sigma * (1.0 - phi * phi).sqrt() * x
            });
            got2 += (slow.hardness_after_turn_error(d) / ratio).powi(2) / runs as f64;
            own2 += series::mean_with_error(&slow.turn_samples(d)).standard_error.powi(2) / runs as f64;
        }
        let exact2 = sigma * sigma / m * (99.0 - 2.0 * phi * (1.0 - phi.powf(m)) / (m * (1.0 - phi).powi(2)));
        assert!(got2 > exact2 && got2 < 2.0 * exact2, "mean square {got2:.0} against {exact2:.0} Pa^2");
        assert!(got2 > 1.3 * own2, "{got2:.0} against the turn samples' own {own2:.0} Pa^2");
        // A smooth curve has no fluctuation to read (F/A(h) of F = 8000 A(h) is 8000 to rounding); fewer
        // than 8 samples give no error.
        assert!(record(d, h_max, h_c, n, |_| 8000.0).hardness_after_turn_error(d) < 1e-12 * 8000.0);
        assert_eq!(record(d, h_max, h_c, 40, |k| 8000.0 + 100.0 * (k % 2) as f64).hardness_after_turn_error(d), 0.0);
    }

    #[test]
    fn projected_area_is_the_cap_base() {
        // 004 Eq. 2.9: at h = r the base is the equator.
        let d = 0.016;
        assert!((projected_area(d, 0.5 * d) - PI * 0.25 * d * d).abs() < 1e-18);
        assert_eq!(projected_area(d, -1e-3), 0.0);
    }

    #[test]
    fn tangent_of_a_straight_unloading_line_meets_zero_where_the_line_does() {
        // F = 100 (h - 0.6e-3) from h_max = 1e-3: h_c = 0.6e-3.
        let pts: Vec<(f64, f64)> = (0..5).map(|k| 1e-3 - k as f64 * 1e-5).map(|h| (h, 100.0 * (h - 0.6e-3))).collect();
        let hc = tangent_depth(&pts).unwrap();
        assert!((hc - 0.6e-3).abs() < 1e-12, "{hc}");
        assert_eq!(tangent_depth(&pts[..2]), None);
    }

    #[test]
    fn the_mean_surface_of_a_layer_lies_between_its_valleys_and_its_tops_and_a_quarter_gives_the_whole() {
        // A square layer of touching 1 mm spheres, centres at z = 0.5 mm, symmetric about x = 0 and y = 0.
        let r = 0.5e-3;
        let (mut whole, mut quarter) = (Particles::default(), Particles::default());
        for i in -10..10 {
            for j in -10..10 {
                let x = Vec3::new((i as f64 + 0.5) * 2.0 * r, (j as f64 + 0.5) * 2.0 * r, r);
                whole.push(x, r, 2500.0, 0);
                if i >= 0 && j >= 0 {
                    quarter.push(x, r, 2500.0, 0);
                }
            }
        }
        let mirrors = [Wall::mirror("mirror_x", Vec3::zeros(), Vec3::x()), Wall::mirror("mirror_y", Vec3::zeros(), Vec3::y())];
        let m = mean_surface_height(&whole, &[], r, 4e-3, 0.25e-3).unwrap();
        // The probe's lowest point: 2r over a top, r + r (sqrt(2) - 1)... over the hollow between four.
        let hollow = r + ((2.0 * r).powi(2) - 2.0 * r * r).sqrt() - r;
        assert!(m > hollow && m < 2.0 * r, "mean surface {m} m between {hollow} and {}", 2.0 * r);
        let q = mean_surface_height(&quarter, &mirrors, r, 4e-3, 0.25e-3).unwrap();
        assert!((q - m).abs() < 1e-15, "quarter with mirrors {q} m, whole {m} m");
        // Without its mirror images the quarter's lines outside it find nothing or lower spheres.
        let alone = mean_surface_height(&quarter, &[], r, 4e-3, 0.25e-3).unwrap();
        assert!((alone - m).abs() > 1e-6);
        assert_eq!(mean_surface_height(&Particles::default(), &[], r, 4e-3, 0.25e-3), None);
    }

    #[test]
    fn the_depth_origin_names_parse_back() {
        for o in [DepthOrigin::FirstTouch, DepthOrigin::MeanSurface] {
            assert_eq!(DepthOrigin::parse(o.name()), Some(o));
        }
        assert_eq!(DepthOrigin::parse("surface"), None);
    }

    #[test]
    fn first_touch_of_a_sphere_on_a_sphere_below_it() {
        let mut p = Particles::default();
        p.push(Vec3::new(0.0, 0.0, 1e-3), 0.5e-3, 2500.0, 0);
        p.push(Vec3::new(3e-3, 0.0, 5e-3), 0.5e-3, 2500.0, 0); // beyond the indenter's reach
        let z = first_touch_height(&p, 2e-3).unwrap();
        assert!((z - 1.5e-3).abs() < 1e-15, "{z}");
        // Off axis by rho: the lowest point is below the sphere's top.
        let mut q = Particles::default();
        q.push(Vec3::new(1e-3, 0.0, 1e-3), 0.5e-3, 2500.0, 0);
        let z = first_touch_height(&q, 2e-3).unwrap();
        assert!((z - (1e-3 - 2e-3 + (2.5e-3f64.powi(2) - 1e-6).sqrt())).abs() < 1e-15);
    }
}
