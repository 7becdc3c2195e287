//! The engine for the law a scene names: one `Engine<L>` per law, so every force loop is compiled for
//! its law with no dispatch inside it. `with_engine!` runs one expression on whichever is inside.

use super::engine::Engine;
use super::interaction::{BedLaw, Interaction};
use super::particles::Particles;
use super::scene::BedScene;
use super::walls::Wall;
use crate::error::ParamError;
use crate::law;
use crate::scene::ModelKind;

pub enum AnyEngine {
    Nan(Engine<law::nan::Nan>),
    Pasha(Engine<law::pasha::Pasha>),
    PashaSimplified(Engine<law::pasha_simplified::PashaSimplified>),
    Luding(Engine<law::luding::Luding>),
    ThorntonNing(Engine<law::thornton_ning::ThorntonNing>),
    Tomas(Engine<law::tomas::Tomas>),
    Hertz(Engine<law::hertz::Hertz>),
    Jkr(Engine<law::jkr::Jkr>),
    JkrModified(Engine<law::jkr_modified::JkrModified>),
    Linear(Engine<law::linear::Linear>),
    WaltonBraun(Engine<law::walton_braun::WaltonBraun>),
}

/// Runs `$body` with `$e` bound to the engine inside `$any`.
#[macro_export]
macro_rules! with_engine {
    ($any:expr, $e:ident => $body:expr) => {
        match $any {
            $crate::bed::AnyEngine::Nan($e) => $body,
            $crate::bed::AnyEngine::Pasha($e) => $body,
            $crate::bed::AnyEngine::PashaSimplified($e) => $body,
            $crate::bed::AnyEngine::Luding($e) => $body,
            $crate::bed::AnyEngine::ThorntonNing($e) => $body,
            $crate::bed::AnyEngine::Tomas($e) => $body,
            $crate::bed::AnyEngine::Hertz($e) => $body,
            $crate::bed::AnyEngine::Jkr($e) => $body,
            $crate::bed::AnyEngine::JkrModified($e) => $body,
            $crate::bed::AnyEngine::Linear($e) => $body,
            $crate::bed::AnyEngine::WaltonBraun($e) => $body,
        }
    };
}

/// Why an engine cannot be built: a parameter (named) or the set-up.
#[derive(Debug, Clone, PartialEq)]
pub enum BedError {
    Param(ParamError),
    Setup(String),
}

impl std::fmt::Display for BedError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BedError::Param(e) => write!(f, "{e}"),
            BedError::Setup(s) => write!(f, "{s}"),
        }
    }
}

impl std::error::Error for BedError {}

impl From<ParamError> for BedError {
    fn from(e: ParamError) -> BedError {
        BedError::Param(e)
    }
}

impl From<String> for BedError {
    fn from(e: String) -> BedError {
        BedError::Setup(e)
    }
}

/// The interaction tables of a scene for law `L`: species pairs, and each wall with each species.
pub fn interactions<L: BedLaw>(scene: &BedScene, walls: &[Wall]) -> Result<(Vec<Interaction<L>>, Vec<Vec<Interaction<L>>>), ParamError> {
    let sp = scene.species();
    let mut pairs = Vec::with_capacity(sp.len() * sp.len());
    for &(r1, m1) in &sp {
        for &(r2, m2) in &sp {
            pairs.push(Interaction::particle_pair(&scene.particle_particle, r1, m1, r2, m2, scene.rolling_friction)?);
        }
    }
    let mut wall_pairs = Vec::with_capacity(walls.len());
    for w in walls {
        let mut row = Vec::with_capacity(sp.len());
        for &(r, m) in &sp {
            row.push(Interaction::particle_wall(&scene.particle_wall, r, m, w.curvature_radius(), scene.wall_rolling_friction)?);
        }
        wall_pairs.push(row);
    }
    Ok((pairs, wall_pairs))
}

/// The largest stable step of velocity Verlet for these interactions: the Rayleigh time of the
/// smallest sphere (000 Eq. 71), and for stiff linear springs 2 sqrt(m*/k) (000 Eq. 68) with k the
/// loading stiffness at an overlap of 0.1 % of R*.
pub fn stability_limit<L: BedLaw>(scene: &BedScene, pairs: &[Interaction<L>], wall_pairs: &[Vec<Interaction<L>>]) -> f64 {
    let mut limit = scene.rayleigh_time();
    for it in pairs.iter().chain(wall_pairs.iter().flatten()) {
        let alpha = 1e-3 * it.radius;
        let mut h = it.initial;
        let mut k: f64 = 0.0;
        for q in 1..=10 {
            let ev = it.law.evaluate(alpha * q as f64 / 10.0, &h);
            h = ev.history;
            k = k.max(ev.stiffness.abs());
        }
        if k > 0.0 && k.is_finite() {
            limit = limit.min(crate::theory::time_step::critical_time_step(it.mass, k));
        }
    }
    limit
}

impl AnyEngine {
    /// Builds the engine of a scene's law over these particles and walls. The step is the scene's
    /// `time_step` if given (refused above the stability limit), else `rayleigh_fraction` of the limit.
    pub fn build(scene: &BedScene, particles: Particles, walls: Vec<Wall>) -> Result<AnyEngine, BedError> {
        fn make<L: BedLaw>(scene: &BedScene, particles: Particles, walls: Vec<Wall>) -> Result<Engine<L>, BedError> {
            let (pairs, wall_pairs) = interactions::<L>(scene, &walls)?;
            let limit = stability_limit(scene, &pairs, &wall_pairs);
            let dt = match scene.time_step {
                Some(dt) if dt > limit => {
                    return Err(BedError::Param(ParamError::OutOfRange {
                        name: "time_step",
                        value: dt,
                        allowed: format!("(0, {limit:.4e}] s: the stability limit of this bed (the Rayleigh time of the smallest sphere, 000 Eq. 71, or 2 sqrt(m*/k), 000 Eq. 68)"),
                    }))
                }
                Some(dt) => dt,
                None => scene.rayleigh_fraction * limit,
            };
            let reach = pairs.iter().chain(wall_pairs.iter().flatten()).map(|it| it.reach).fold(0.0, f64::max);
            let skin = scene.skin.unwrap_or(0.1 * scene.size_distribution.mean_diameter()).max(2.0 * reach);
            let species = scene.species().len();
            Ok(Engine::new(particles, walls, pairs, wall_pairs, species, [0.0, 0.0, -scene.gravity], dt, skin, scene.threads)?)
        }
        Ok(match scene.model {
            ModelKind::Nan => AnyEngine::Nan(make(scene, particles, walls)?),
            ModelKind::Pasha => AnyEngine::Pasha(make(scene, particles, walls)?),
            ModelKind::PashaSimplified => AnyEngine::PashaSimplified(make(scene, particles, walls)?),
            ModelKind::Luding => AnyEngine::Luding(make(scene, particles, walls)?),
            ModelKind::ThorntonNing => AnyEngine::ThorntonNing(make(scene, particles, walls)?),
            ModelKind::Tomas => AnyEngine::Tomas(make(scene, particles, walls)?),
            ModelKind::Hertz => AnyEngine::Hertz(make(scene, particles, walls)?),
            ModelKind::Jkr => AnyEngine::Jkr(make(scene, particles, walls)?),
            ModelKind::JkrModified => AnyEngine::JkrModified(make(scene, particles, walls)?),
            ModelKind::Linear => AnyEngine::Linear(make(scene, particles, walls)?),
            ModelKind::WaltonBraun => AnyEngine::WaltonBraun(make(scene, particles, walls)?),
        })
    }

    pub fn particles(&self) -> &Particles {
        with_engine!(self, e => &e.particles)
    }

    pub fn walls(&self) -> &[Wall] {
        with_engine!(self, e => &e.walls)
    }

    pub fn walls_mut(&mut self) -> &mut Vec<Wall> {
        with_engine!(self, e => &mut e.walls)
    }

    pub fn step(&mut self) {
        with_engine!(self, e => e.step())
    }

    pub fn run(&mut self, steps: u64) {
        with_engine!(self, e => e.run(steps))
    }

    pub fn dt(&self) -> f64 {
        with_engine!(self, e => e.dt)
    }

    pub fn time(&self) -> f64 {
        with_engine!(self, e => e.time)
    }

    pub fn memory_bytes(&self) -> usize {
        with_engine!(self, e => e.memory_bytes())
    }
}
