//! Bed preparation (`004` Sec. 5.1.3): random non-overlapping fill of the die, settling under gravity
//! until the kinetic energy is negligible, consolidation by the piston at a constant strain rate to the
//! target stress (10 kPa), unloading at the same speed, and relaxation.

use super::any::{AnyEngine, BedError};
use super::particles::Particles;
use super::random::Random;
use super::scene::BedScene;
use super::stress::{bagi, Region, Stress};
use super::walls::Wall;
use super::{Vec3, ZERO};
use std::f64::consts::PI;

/// Progress of a long preparation, for a progress bar.
#[derive(Clone)]
pub struct Progress<'a> {
    /// The phase running: `fill`, `settle`, `consolidate`, `unload` or `relax`.
    pub phase: &'static str,
    /// Estimated fraction of the whole preparation done, in [0, 1].
    pub fraction: f64,
    /// Simulated time [s] and steps so far.
    pub time: f64,
    /// Steps taken in this phase so far.
    pub steps: u64,
    /// A short reading of the phase's own measure (kinetic energy, piston stress).
    pub detail: String,
    /// The bed as it is: a caller may save it (`bed prepare` writes a checkpoint every few minutes).
    pub bed: &'a AnyEngine,
}

/// What each phase did.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// (phase, simulated time [s], steps).
    pub phases: Vec<(&'static str, f64, u64)>,
    /// Piston stress when consolidation stopped, averaged over the last 100 steps [Pa].
    pub consolidation_stress: f64,
    /// Bagi's stress (004 Eq. 5.1) in the middle half of the bed's height at that moment, over the whole
    /// cross-section of the die (where static equilibrium makes its sigma_zz the piston's stress plus
    /// the weight above).
    pub stress_at_target: Option<Stress>,
    /// The engine's time step [s].
    pub time_step: f64,
}

/// Phase weights of the progress estimate (settling dominates).
const WEIGHTS: [(&str, f64); 5] = [("fill", 0.01), ("settle", 0.55), ("consolidate", 0.2), ("unload", 0.1), ("relax", 0.14)];

fn overall(phase: &str, within: f64) -> f64 {
    let mut before = 0.0;
    for (name, w) in WEIGHTS {
        if name == phase {
            return before + w * within.clamp(0.0, 1.0);
        }
        before += w;
    }
    1.0
}

/// Random sequential insertion of the scene's spheres in the die, from the largest class down, in a
/// column whose height gives the scene's fill solid fraction. Particles come out in spatial order (cells
/// from the bottom up), which keeps the force loop's memory access local.
pub fn fill(scene: &BedScene) -> Result<Particles, BedError> {
    let psd = &scene.size_distribution;
    let n = scene.particle_count;
    let die_r = 0.5 * scene.die_diameter;
    let d_max = psd.max_diameter();
    if die_r <= d_max {
        return Err(BedError::Param(crate::ParamError::OutOfRange {
            name: "die_diameter",
            value: scene.die_diameter,
            allowed: format!("above twice the largest sphere diameter, {:.4e} m", 2.0 * d_max),
        }));
    }
    let height = psd.solid_volume(n) / (scene.fill_solid_fraction * scene.sector_area()) + d_max;
    if height > scene.die_height {
        return Err(BedError::Setup(format!(
            "insertion impossible: {n} spheres at fill_solid_fraction {} need a column {:.4} m high, above die_height = {} m; lower particle_count, or raise die_diameter or die_height",
            scene.fill_solid_fraction, height, scene.die_height
        )));
    }
    let counts = psd.class_counts(n);
    let mut order: Vec<usize> = (0..psd.diameters.len()).collect();
    order.sort_by(|&a, &b| psd.diameters[b].total_cmp(&psd.diameters[a]));
    let mut rng = Random::new(scene.seed);
    // A grid of cells of the largest diameter: a sphere can only overlap spheres in the 27 cells around it.
    let cell = d_max;
    let nx = ((2.0 * die_r) / cell).ceil() as usize + 1;
    let nz = (height / cell).ceil() as usize + 1;
    let mut grid: Vec<Vec<u32>> = vec![Vec::new(); nx * nx * nz];
    let key = |x: Vec3| -> (usize, usize, usize) { (((x[0] + die_r) / cell) as usize, ((x[1] + die_r) / cell) as usize, (x[2] / cell) as usize) };
    let mut placed: Vec<(Vec3, f64, u16)> = Vec::with_capacity(n);
    for &s in &order {
        let r = 0.5 * psd.diameters[s];
        for _ in 0..counts[s] {
            let mut ok = false;
            for _attempt in 0..5000 {
                let rho = (die_r - r) * rng.uniform().sqrt();
                let th = 2.0 * PI * scene.die_sector * rng.uniform();
                let x = Vec3::new(rho * th.cos(), rho * th.sin(), r + (height - 2.0 * r) * rng.uniform());
                // Clear of the sector's mirror planes (y = 0 for a half, also x = 0 for a quarter).
                if (scene.die_sector < 1.0 && x[1] < r) || (scene.die_sector < 0.5 && x[0] < r) {
                    continue;
                }
                let (cx, cy, cz) = key(x);
                let mut free = true;
                'search: for z in cz.saturating_sub(1)..(cz + 2).min(nz) {
                    for y in cy.saturating_sub(1)..(cy + 2).min(nx) {
                        for xx in cx.saturating_sub(1)..(cx + 2).min(nx) {
                            for &k in &grid[(z * nx + y) * nx + xx] {
                                let (p, rp, _) = placed[k as usize];
                                if (p - x).norm_squared() < (r + rp) * (r + rp) {
                                    free = false;
                                    break 'search;
                                }
                            }
                        }
                    }
                }
                if free {
                    grid[(cz * nx + cy) * nx + cx].push(placed.len() as u32);
                    placed.push((x, r, s as u16));
                    ok = true;
                    break;
                }
            }
            if !ok {
                return Err(BedError::Setup(format!(
                    "insertion impossible: placed {} of {n} spheres without overlap in the die ({} m wide, fill {height:.4} m high, fill_solid_fraction {}); lower fill_solid_fraction or particle_count",
                    placed.len(),
                    scene.die_diameter,
                    scene.fill_solid_fraction
                )));
            }
        }
    }
    // Spatial order: by cell, bottom up.
    let mut idx: Vec<usize> = (0..placed.len()).collect();
    idx.sort_by_key(|&k| {
        let (x, y, z) = key(placed[k].0);
        ((z * nx + y) * nx + x, k)
    });
    let mut p = Particles::default();
    for k in idx {
        let (x, r, s) = placed[k];
        p.push(x, r, scene.density, s);
    }
    Ok(p)
}

/// The die: floor at z = 0, the cylinder, and the piston parked at the top of the die; for a sector,
/// its mirror planes after them (y = 0 for a half, and x = 0 for a quarter).
pub fn die(scene: &BedScene) -> Vec<Wall> {
    let mut walls = vec![
        Wall::plane("floor", ZERO, Vec3::z()),
        Wall::cylinder("die", ZERO, 0.5 * scene.die_diameter),
        Wall::plane("piston", Vec3::new(0.0, 0.0, scene.die_height), Vec3::new(0.0, 0.0, -1.0)),
    ];
    if scene.die_sector < 1.0 {
        walls.push(Wall::mirror("mirror_y", ZERO, Vec3::y()));
    }
    if scene.die_sector < 0.5 {
        walls.push(Wall::mirror("mirror_x", ZERO, Vec3::x()));
    }
    walls
}

/// Index of the floor among the walls of `die`.
pub const FLOOR: usize = 0;
/// Index of the die's cylinder among the walls of `die`.
pub const DIE: usize = 1;
/// Index of the piston among the walls of `die`.
pub const PISTON: usize = 2;

/// Height of the bed: the highest sphere top [m].
pub fn bed_height(p: &Particles) -> f64 {
    p.position.iter().zip(&p.radius).map(|(x, r)| x[2] + r).fold(0.0, f64::max)
}

/// Kinetic energy over sum(m g d_mean): the settling measure.
fn energy_ratio(e: &AnyEngine, scene: &BedScene) -> f64 {
    let p = e.particles();
    let scale: f64 = p.mass.iter().sum::<f64>() * scene.gravity.max(1e-3) * scene.size_distribution.mean_diameter();
    p.kinetic_energy() / scale
}

/// Runs until the kinetic energy is negligible (and at least `min_time`), reporting progress.
fn calm(
    e: &mut AnyEngine,
    scene: &BedScene,
    phase: &'static str,
    min_time: f64,
    max_time: f64,
    progress: &mut dyn FnMut(&Progress),
) -> Result<(f64, u64), BedError> {
    let t0 = e.time();
    let chunk = ((2e-4 / e.dt()) as u64).clamp(50, 5000);
    let mut steps = 0;
    // The ratio when min_time is reached: the start of the log scale of the progress estimate.
    let mut first: Option<f64> = None;
    loop {
        e.run(chunk);
        steps += chunk;
        let t = e.time() - t0;
        let ratio = energy_ratio(e, scene);
        if !ratio.is_finite() {
            return Err(BedError::Setup(format!(
                "{phase}: the bed blew up (kinetic energy not finite) after {t:.4e} s; lower rayleigh_fraction or time_step"
            )));
        }
        // Progress: time towards min_time, then kinetic energy towards the threshold on a log scale.
        let within = if t < min_time {
            0.5 * t / min_time
        } else {
            let f = *first.get_or_insert(ratio.max(10.0 * scene.settle_energy_ratio));
            0.5 + 0.5 * ((f / ratio.max(1e-300)).ln() / (f / scene.settle_energy_ratio).ln()).clamp(0.0, 1.0)
        };
        progress(&Progress {
            phase,
            fraction: overall(phase, within),
            time: e.time(),
            steps,
            detail: format!("kinetic energy ratio {ratio:.2e}"),
            bed: e,
        });
        if t >= min_time && ratio < scene.settle_energy_ratio {
            return Ok((t, steps));
        }
        if t > max_time {
            return Err(BedError::Setup(format!(
                "{phase}: the bed did not come to rest within {max_time:.3} s (kinetic energy ratio {ratio:.2e} > settle_energy_ratio {})",
                scene.settle_energy_ratio
            )));
        }
    }
}

/// The piston's stress on the bed [Pa] (compressive positive).
pub fn piston_stress(e: &AnyEngine, scene: &BedScene) -> f64 {
    e.walls()[PISTON].force[2] / scene.sector_area()
}

/// The phases, in order.
pub const PHASES: [&str; 5] = ["fill", "settle", "consolidate", "unload", "relax"];

/// The whole protocol, from an empty die to a relaxed, pre-consolidated bed.
///
/// A small soft bed, prepared and indented to h/r = 0.1 (compiled, not run here: a bed takes minutes in
/// a debug build; `tests/indentation.rs` runs the same steps):
/// ```no_run
/// use powderfmu::bed::indentation::{DepthOrigin, Indentation, Motion, Setup, TestState, PLATEAU};
/// use powderfmu::bed::{prepare, BedScene};
///
/// let scene = BedScene::from_json(r#"{"particle_particle": {"particle_youngs_modulus": 55e6},
///                                     "particle_count": 800, "die_diameter": 0.007}"#)?;
/// let (bed, report) = prepare::prepare(&scene, &mut |p| eprintln!("{} {:.0} %", p.phase, 100.0 * p.fraction))?;
/// let setup = Setup {
///     indenter_diameter: 0.004,
///     indentation_speed: 0.05,
///     max_penetration: 0.1 * 0.002,
///     constraint_factor: 3.0,
///     constraint_factor_standard_error: 0.0,
///     motion: Motion::Prescribed,
///     shortcut: None,
///     plateau: PLATEAU,
///     depth_origin: DepthOrigin::FirstTouch,
/// };
/// let mut test = Indentation::new(bed, scene, setup, None, None)?;
/// while test.reading().state != TestState::Done {
///     test.advance(1e-4, None)?;
/// }
/// println!("{report:?}: hardness {:.0} Pa", test.reading().hardness);
/// # Ok::<(), powderfmu::bed::BedError>(())
/// ```
pub fn prepare(scene: &BedScene, progress: &mut dyn FnMut(&Progress)) -> Result<(AnyEngine, Report), BedError> {
    prepare_until(scene, "relax", progress)
}

/// The protocol up to and including phase `last` (one of `PHASES`).
pub fn prepare_until(scene: &BedScene, last: &str, progress: &mut dyn FnMut(&Progress)) -> Result<(AnyEngine, Report), BedError> {
    check_phase(last)?;
    let particles = fill(scene)?;
    let fill_height = bed_height(&particles);
    let e = AnyEngine::build(scene, particles, die(scene))?;
    progress(&Progress {
        phase: "fill",
        fraction: overall("fill", 1.0),
        time: 0.0,
        steps: 0,
        detail: format!("{} spheres, fill {fill_height:.4} m high", scene.particle_count),
        bed: &e,
    });
    run_phases(e, scene, "fill", last, fill_height, progress)
}

/// The last phase a saved bed went through, read from its piston and its motion: parked at the top of
/// the die before consolidation (settled once the bed is at rest), moving down during consolidation,
/// turned (moving up) once it carries the target stress and while unloading, parked above the bed after. A
/// checkpoint taken within a phase names the phase before it, and `resume` goes on with the phase.
pub fn phase_done(e: &AnyEngine, scene: &BedScene) -> &'static str {
    let piston = &e.walls()[PISTON];
    if piston.velocity[2] < 0.0 {
        "settle"
    } else if piston.velocity[2] > 0.0 {
        "consolidate"
    } else if piston.position[2] == scene.die_height {
        if e.time() > 0.0 && energy_ratio(e, scene) < scene.settle_energy_ratio {
            "settle"
        } else {
            "fill"
        }
    } else {
        "unload"
    }
}

/// Whether a saved bed's consolidation has begun: its piston has left its parked place at the top of the
/// die. Before, the consolidation stress can still be chosen (`bed prepare --resume --consolidation-stress`).
pub fn consolidation_started(e: &AnyEngine, scene: &BedScene) -> bool {
    let piston = &e.walls()[PISTON];
    piston.velocity[2] != 0.0 || piston.position[2] != scene.die_height
}

/// Continues a saved bed (`powderfmu bed prepare --resume`) after the phase it went through, up to and
/// including `last`: a preparation of hours can be done in parts, and nothing is lost when one stops.
pub fn resume(e: AnyEngine, scene: &BedScene, last: &str, progress: &mut dyn FnMut(&Progress)) -> Result<(AnyEngine, Report), BedError> {
    check_phase(last)?;
    let done = phase_done(&e, scene);
    // The fill column's height, as `fill` makes it: the scale of the settling and relaxation times.
    let psd = &scene.size_distribution;
    let fill_height = psd.solid_volume(scene.particle_count) / (scene.fill_solid_fraction * scene.sector_area()) + psd.max_diameter();
    run_phases(e, scene, done, last, fill_height, progress)
}

fn check_phase(last: &str) -> Result<(), BedError> {
    if PHASES.contains(&last) {
        Ok(())
    } else {
        Err(BedError::Setup(format!("unknown phase `{last}`: allowed {}", PHASES.join(", "))))
    }
}

/// Runs the phases after `done` up to and including `last`.
fn run_phases(
    mut e: AnyEngine,
    scene: &BedScene,
    done: &str,
    last: &str,
    fill_height: f64,
    progress: &mut dyn FnMut(&Progress),
) -> Result<(AnyEngine, Report), BedError> {
    let mut report = Report { time_step: e.dt(), ..Default::default() };
    let index = |name: &str| PHASES.iter().position(|&p| p == name).unwrap_or(0);
    let (first, last_index) = (index(done) + 1, index(last));
    let runs = |phase: &str| (first..=last_index).contains(&index(phase));
    // Progress every REPORT_EVERY steps of the piston's phases (by steps, not by the clock, so that what
    // a caller sees and saves does not depend on the machine).
    const REPORT_EVERY: u64 = 1000;
    let fall = (2.0 * fill_height / scene.gravity.max(1e-3)).sqrt();
    if runs("settle") {
        // A checkpoint within the settling has settled for its bed time already.
        let before = e.time();
        let (t, s) = calm(&mut e, scene, "settle", (fall - before).max(0.0), 50.0 * fall + 0.1 - before, progress)?;
        report.phases.push(("settle", t, s));
    }

    if runs("consolidate") {
        // Consolidate: the piston comes down from just above the bed at v = strain_rate x height.
        // (A checkpoint within the consolidation goes on where its piston is.)
        let h0 = bed_height(e.particles());
        if e.walls()[PISTON].velocity[2] >= 0.0 {
            let speed = scene.strain_rate * h0;
            let piston = &mut e.walls_mut()[PISTON];
            piston.position[2] = h0 + 0.02 * scene.size_distribution.mean_diameter();
            piston.velocity = Vec3::new(0.0, 0.0, -speed);
        }
        let t0 = e.time();
        let mut steps = 0u64;
        let mut window = std::collections::VecDeque::with_capacity(100);
        loop {
            e.step();
            steps += 1;
            if window.len() == 100 {
                window.pop_front();
            }
            window.push_back(piston_stress(&e, scene));
            let mean = window.iter().sum::<f64>() / window.len() as f64;
            if window.len() == 100 && mean >= scene.consolidation_stress {
                report.consolidation_stress = mean;
                let top = e.walls()[PISTON].position[2];
                let region = Region { radius: 0.5 * scene.die_diameter, z_low: 0.25 * top, z_high: 0.75 * top };
                report.stress_at_target = Some(bagi(&mut e, &region).of_whole_die(scene.die_sector));
                break;
            }
            let travel = h0 - e.walls()[PISTON].position[2];
            if travel > 0.5 * h0 {
                return Err(BedError::Setup(format!(
                    "consolidate: the piston travelled half the bed height without reaching {} Pa (reached {mean:.4e} Pa)",
                    scene.consolidation_stress
                )));
            }
            if steps.is_multiple_of(REPORT_EVERY) {
                progress(&Progress {
                    phase: "consolidate",
                    fraction: overall("consolidate", mean / scene.consolidation_stress),
                    time: e.time(),
                    steps,
                    detail: format!("piston stress {mean:.4e} Pa"),
                    bed: &e,
                });
            }
        }
        // The piston turns at once: a bed saved here says by its piston that it is consolidated.
        let speed = e.walls()[PISTON].velocity[2].abs();
        e.walls_mut()[PISTON].velocity = Vec3::new(0.0, 0.0, speed);
        report.phases.push(("consolidate", e.time() - t0, steps));
    }

    if runs("unload") {
        // Unload at the same speed until the piston has carried no force for 100 steps; then it is parked
        // one mean diameter higher, out of reach.
        let t0 = e.time();
        // The piston goes up at the speed it came down with (it turned at the end of the consolidation).
        if report.consolidation_stress == 0.0 {
            // Resumed after consolidation: the stress it reached is the piston's now.
            report.consolidation_stress = piston_stress(&e, scene);
        }
        let mut steps = 0u64;
        let mut free_steps = 0;
        while free_steps < 100 {
            e.step();
            steps += 1;
            free_steps = if e.walls()[PISTON].force == ZERO { free_steps + 1 } else { 0 };
            if steps.is_multiple_of(REPORT_EVERY) {
                let sigma = piston_stress(&e, scene);
                progress(&Progress {
                    phase: "unload",
                    fraction: overall("unload", 1.0 - sigma / report.consolidation_stress),
                    time: e.time(),
                    steps,
                    detail: format!("piston stress {sigma:.4e} Pa"),
                    bed: &e,
                });
            }
        }
        e.walls_mut()[PISTON].position[2] += scene.size_distribution.mean_diameter();
        e.walls_mut()[PISTON].velocity = ZERO;
        // The jump ends the piston's contacts now, not at the next list rebuild, so a bed saved here
        // holds no contact out of range.
        e.rebuild();
        report.phases.push(("unload", e.time() - t0, steps));
    }

    if runs("relax") {
        let (t, s) = calm(&mut e, scene, "relax", 1e-3, 5.0 * fall + 0.1, progress)?;
        report.phases.push(("relax", t, s));
        progress(&Progress { phase: "relax", fraction: 1.0, time: e.time(), steps: s, detail: "done".into(), bed: &e });
    }
    Ok((e, report))
}
