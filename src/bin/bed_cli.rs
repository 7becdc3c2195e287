//! `powderfmu bed ...`: prepare a bed, describe it, look at it, export it, time it.

use crate::options;
use clap::Subcommand;
use indicatif::{ProgressBar, ProgressStyle};
use powderfmu::bed::file::{self, BedFile};
use powderfmu::bed::indentation::{DepthOrigin, Indentation, Motion, Setup, Shortcut, TestState, FAST, PLATEAU};
use powderfmu::bed::prepare::{self, Progress};
use powderfmu::bed::stress::{bagi, Region};
use powderfmu::bed::{export, render, AnyEngine, BedScene};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// `powderfmu bed ...`
#[derive(Subcommand)]
pub enum BedCommand {
    /// Prepare a bed: fill, settle, consolidate, unload, relax (`004` Sec. 5.1.3, Sec. 6.1)
    ///
    /// A preparation of hours runs in parts: every --checkpoint minutes the bed goes to
    /// OUT.checkpoint.pfbed, and `--resume` goes on from a checkpoint or from a bed saved with --until.
    #[command(after_long_help = powderfmu::bed::scene_keys_help())]
    Prepare(PrepareArgs),
    /// Count, height, solid fraction, coordination, overlap, stress of a bed file
    Info {
        /// The bed file
        bed: PathBuf,
    },
    /// The BallIndentation start values that load this bed (bed_file and its contact parameters), as JSON
    Params {
        /// The bed file
        bed: PathBuf,
    },
    /// The spheres for ParaView (OUT.vtk) or a spreadsheet (OUT.csv)
    Snapshot {
        /// The bed file
        bed: PathBuf,
        /// The output file, ending in .vtk or .csv
        out: PathBuf,
    },
    /// A vertical cross-section through the die axis as a PNG, coloured by vertical stress
    Render {
        /// The bed file
        bed: PathBuf,
        /// The output PNG
        out: PathBuf,
        /// Image width [px]
        #[arg(long, value_name = "PX", default_value_t = 900, value_parser = clap::value_parser!(u32).range(50..=10000))]
        width: u32,
    },
    /// A LAMMPS data file (atom_style sphere)
    ExportLammps {
        /// The bed file
        bed: PathBuf,
        /// The output data file
        out: PathBuf,
    },
    /// Ball indentation (`004` Sec. 2.3.5): load to --max-penetration, unload; force-depth CSV
    Indent(IndentArgs),
    /// Particle-steps per second of the force loop on a bed under a chosen law
    Bench(BenchArgs),
    /// Unconfined compression (`004` Sec. 2.1): the die removed, the platen down at a strain rate until the
    /// specimen fails; stress-strain CSV, sigma_c and ff_c = sigma_1 / sigma_c
    Compress(crate::bed_compress::CompressArgs),
    /// Translational shear cell (`003` Sec. 5.1, `004` Sec. 2.2): the die split into two rings, preshear at
    /// sigma_pre, shears to failure at lower normal stresses; the yield locus, phi_i, c, sigma_c, sigma_1
    Shear(crate::bed_shear::ShearArgs),
}

#[derive(clap::Args)]
pub struct PrepareArgs {
    /// The bed scene (JSON; `--help` lists its keys with their ranges); not with --resume
    #[arg(required_unless_present = "resume", conflicts_with = "resume")]
    scene: Option<PathBuf>,
    /// The bed file to write (default: the scene's name with .bed, or the resumed file)
    #[arg(short, long, value_name = "BED")]
    output: Option<PathBuf>,
    /// Threads of the force loop (default: the scene's `threads`)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=256))]
    threads: Option<u16>,
    /// The last phase to run
    #[arg(long, value_name = "PHASE", default_value = "relax", value_parser = clap::builder::PossibleValuesParser::new(prepare::PHASES))]
    until: String,
    /// Continue a saved bed or checkpoint after the phase it went through
    #[arg(long, value_name = "BED")]
    resume: Option<PathBuf>,
    /// Minutes between checkpoints [min]
    #[arg(long, value_name = "MIN", default_value_t = 10.0, value_parser = options::positive("min"))]
    checkpoint: f64,
    /// With --resume of a bed not yet consolidated (saved with --until fill or settle): consolidate
    /// to this piston stress instead of its scene's [Pa]. One settled fill branched to several
    /// stresses (a flow function on the same fill); the bed written holds the new stress
    #[arg(long, value_name = "PA", value_parser = options::in_range(0.0, 1e9, false, "Pa"))]
    consolidation_stress: Option<f64>,
    /// The kinetic energy, as a fraction of sum(m g d_mean), under which the phases still to run
    /// (settle, relax) count as at rest, instead of the scene's `settle_energy_ratio`: for a bed
    /// whose kinetic energy stopped falling just above it (resume its checkpoint with this). The bed
    /// written holds the new ratio [-]
    #[arg(long, value_name = "RATIO", value_parser = options::in_range(0.0, 1.0, false, "-"))]
    settle_energy_ratio: Option<f64>,
}

#[derive(clap::Args)]
pub struct IndentArgs {
    /// A prepared bed file
    bed: PathBuf,
    /// Indenter diameter [m] (default 16 mean sphere diameters)
    #[arg(long, value_name = "M", value_parser = options::positive("m"))]
    diameter: Option<f64>,
    /// Indentation speed, loading and unloading [m/s]
    #[arg(long, value_name = "M_PER_S", default_value_t = 0.02, value_parser = options::positive("m/s"))]
    speed: f64,
    /// Depth to load to [m] (default a tenth of the diameter: h/r = 0.2)
    #[arg(long, value_name = "M", value_parser = options::positive("m"))]
    max_penetration: Option<f64>,
    /// Threads of the force loop (default: the bed scene's)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=256))]
    threads: Option<u16>,
    /// The CSV to write (default: stdout)
    #[arg(long, value_name = "CSV")]
    out: Option<PathBuf>,
    /// Time between CSV rows [s]
    #[arg(long, value_name = "S", default_value_t = 1e-3, value_parser = options::positive("s"))]
    every: f64,
    /// Scene keys of the particle-indenter contact over the bed's own (its `indenter_material`: the particles' material without cohesion, or the walls' contact) (a JSON object)
    #[arg(long, value_name = "JSON")]
    indenter: Option<String>,
    /// Scene keys of the die's, floor's and piston's contacts for this test, over the bed's walls' (a
    /// JSON object): softer walls allow a longer time step
    #[arg(long, value_name = "JSON")]
    walls: Option<String>,
    /// Bed scene keys over the bed's own for this test (a JSON object; `particle_particle` and
    /// `particle_wall` merge key by key): a one-change experiment on the same prepared bed, e.g.
    /// '{"rolling_friction": 0}' or '{"particle_particle": {"surface_energy": 0}}'. The law
    /// (contact_model) stays the bed's; every contact keeps its memory
    #[arg(long, value_name = "JSON")]
    change: Option<String>,
    /// A fixed time step [s] (refused above the bed's stability limit)
    #[arg(long, value_name = "S", value_parser = options::positive("s"))]
    time_step: Option<f64>,
    /// fast: spheres beyond --mobile-zone a_max held until the force on one changes by --release sigma_c d^2;
    /// full: every sphere moves (the default, unless --mobile-zone or --release is given)
    #[arg(long, value_enum)]
    fidelity: Option<Fidelity>,
    /// Mobile zone of --fidelity fast, as a factor on the largest contact radius a_max [-]
    #[arg(long, value_name = "M", value_parser = options::positive("-"))]
    mobile_zone: Option<f64>,
    /// Release threshold of --fidelity fast, a fraction of consolidation_stress x d^2 (inf: never) [-]
    #[arg(long, value_name = "E", value_parser = options::positive("-"))]
    release: Option<f64>,
    /// Where the plateau hardness's window starts, h/r [-]
    #[arg(long, value_name = "H_OVER_R", default_value_t = PLATEAU.0, value_parser = options::in_range(0.0, f64::INFINITY, true, "-"))]
    plateau_start: f64,
    /// Where the plateau hardness's window ends, h/r [-]
    #[arg(long, value_name = "H_OVER_R", default_value_t = PLATEAU.1, value_parser = options::positive("-"))]
    plateau_end: f64,
    /// Where the depth is measured from: the indenter's first touch of the bed, or the bed's mean surface
    /// under the footprint of --max-penetration
    #[arg(long, value_enum, default_value_t = Origin::FirstTouch)]
    depth_origin: Origin,
    /// Also write the loading samples (h [m], F [N], at every check: 100 engine steps) to this CSV
    #[arg(long, value_name = "CSV")]
    samples_out: Option<PathBuf>,
}

#[derive(Clone, Copy, PartialEq, clap::ValueEnum)]
pub enum Origin {
    FirstTouch,
    MeanSurface,
}

#[derive(Clone, Copy, PartialEq, clap::ValueEnum)]
pub enum Fidelity {
    Fast,
    Full,
}

#[derive(clap::Args)]
pub struct BenchArgs {
    /// A prepared bed file
    bed: PathBuf,
    /// The law: hooke, hertz, jkr, nan or any contact_model
    #[arg(long)]
    model: String,
    /// Timed steps
    #[arg(long, default_value_t = 2000, value_parser = clap::value_parser!(u64).range(1..=100_000_000))]
    steps: u64,
    /// Steps before the timing
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u64).range(0..=100_000_000))]
    warmup: u64,
    /// Threads of the force loop
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=256))]
    threads: u16,
    /// Spring stiffness of hooke [N/m]
    #[arg(long, value_name = "N_PER_M", default_value_t = 2e5, value_parser = options::in_range(0.0, 1e12, false, "N/m"))]
    stiffness: f64,
    /// Yield pressure of the elasto-plastic laws [Pa]
    #[arg(long, value_name = "PA", default_value_t = 2e6, value_parser = options::in_range(0.0, 1e13, false, "Pa"))]
    yield_pressure: f64,
    /// Interface energy [J/m^2] (default: the bed's)
    #[arg(long, value_name = "J_PER_M2", value_parser = options::in_range(0.0, 1e3, true, "J/m^2"))]
    surface_energy: Option<f64>,
    /// Rolling friction coefficient, particles and walls [-] (default: the bed's)
    #[arg(long, value_name = "MU", value_parser = options::in_range(0.0, 10.0, true, "-"))]
    rolling_friction: Option<f64>,
    /// Verlet list skin [m] (default: the bed's; never below twice the adhesive necks' reach)
    #[arg(long, value_name = "M", value_parser = options::in_range(0.0, 1.0, false, "m"))]
    skin: Option<f64>,
    /// Forgetting distance [m]: a contact whose surfaces are farther apart forgets its memory (default:
    /// the bed's; never below twice the adhesive necks' reach)
    #[arg(long, value_name = "M", value_parser = options::in_range(0.0, 1.0, false, "m"))]
    forgetting_distance: Option<f64>,
}

pub fn run(command: BedCommand) -> Result<(), String> {
    match command {
        BedCommand::Prepare(a) => prepare_cmd(a),
        BedCommand::Info { bed } => info_cmd(&bed),
        BedCommand::Params { bed } => params_cmd(&bed),
        BedCommand::Snapshot { bed, out } => snapshot_cmd(&bed, &out),
        BedCommand::Render { bed, out, width } => render_cmd(&bed, &out, width),
        BedCommand::ExportLammps { bed, out } => export_cmd(&bed, &out),
        BedCommand::Bench(a) => bench_cmd(a),
        BedCommand::Indent(a) => indent_cmd(a),
        BedCommand::Compress(a) => crate::bed_compress::compress_cmd(a),
        BedCommand::Shear(a) => crate::bed_shear::shear_cmd(a),
    }
}

/// The progress of a preparation or an indentation: an indicatif bar on a terminal (with the time left),
/// or a plain line per 5 % elsewhere (logs, CI), which a reader of a log can follow.
pub(crate) struct Bar {
    start: Instant,
    bar: Option<ProgressBar>,
    last_line: f64,
}

impl Bar {
    pub(crate) fn new() -> Bar {
        let bar = std::io::stderr().is_terminal().then(|| {
            let b = ProgressBar::new(1000);
            b.set_style(
                ProgressStyle::with_template("[{bar:30}] {percent:>3}% {msg}  elapsed {elapsed_precise}  left ~{eta_precise}")
                    .expect("a valid template")
                    .progress_chars("#>."),
            );
            b
        });
        Bar { start: Instant::now(), bar, last_line: -1.0 }
    }

    fn show(&mut self, p: &Progress) {
        self.show_phase(p.phase, p.fraction, p.time, &p.detail);
    }

    /// `fraction` of the whole job done, in [0, 1]; `time` the simulated time [s].
    pub(crate) fn show_phase(&mut self, phase: &str, fraction: f64, time: f64, detail: &str) {
        let what = format!("{phase:<11} t = {time:.4e} s  {detail}");
        match &self.bar {
            Some(b) => {
                b.set_position((fraction * 1000.0) as u64);
                b.set_message(what);
            }
            None if fraction >= self.last_line + 0.05 || fraction >= 1.0 => {
                self.last_line = fraction;
                let elapsed = self.start.elapsed().as_secs_f64();
                let left = if fraction > 0.01 { elapsed * (1.0 - fraction) / fraction } else { f64::NAN };
                eprintln!("{:3.0}% {what}  elapsed {}  left ~{}", 100.0 * fraction, clock(elapsed), clock(left));
            }
            None => {}
        }
    }

    pub(crate) fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish();
        }
    }
}

fn clock(s: f64) -> String {
    if s.is_finite() {
        format!("{:02}:{:02}:{:02}", (s / 3600.0) as u64, ((s % 3600.0) / 60.0) as u64, (s % 60.0) as u64)
    } else {
        "--:--:--".into()
    }
}

fn prepare_cmd(a: PrepareArgs) -> Result<(), String> {
    let PrepareArgs { scene: scene_path, output, threads, until, resume, checkpoint: every, consolidation_stress, settle_energy_ratio } = a;
    let threads = threads.map(usize::from);
    let until = until.as_str();
    if consolidation_stress.is_some() && resume.is_none() {
        return Err("--consolidation-stress goes with --resume of a bed saved with --until fill or settle; a new preparation consolidates to its scene's consolidation_stress".into());
    }
    let (mut scene, saved, default_out) = match (&resume, scene_path) {
        (Some(bed), _) => {
            let (engine, mut scene) = load(bed, threads)?;
            if let Some(stress) = consolidation_stress {
                if prepare::consolidation_started(&engine, &scene) {
                    return Err(format!(
                        "--consolidation-stress: {} has been consolidated (to {:e} Pa) already; give a bed saved with --until fill or --until settle",
                        bed.display(),
                        scene.consolidation_stress
                    ));
                }
                scene.consolidation_stress = stress;
            }
            (scene, Some(engine), bed.clone())
        }
        (None, Some(scene_path)) => {
            let text = std::fs::read_to_string(&scene_path).map_err(|e| format!("cannot read bed scene `{}`: {e}", scene_path.display()))?;
            let scene = BedScene::from_json(&text).map_err(|e| format!("{}: {e}", scene_path.display()))?;
            (scene, None, scene_path.with_extension("bed"))
        }
        (None, None) => return Err("give the bed scene file (JSON), or --resume BED".into()),
    };
    if let Some(t) = threads {
        scene.threads = t;
    }
    if let Some(r) = settle_energy_ratio {
        scene.settle_energy_ratio = r;
    }
    let out = output.unwrap_or(default_out);
    eprintln!(
        "preparing {} spheres ({:?}, mean diameter {:.3e} m) in a die of {} m, to {} Pa, on {} thread(s) -> {}",
        scene.particle_count,
        scene.model,
        scene.size_distribution.mean_diameter(),
        scene.die_diameter,
        scene.consolidation_stress,
        scene.threads,
        out.display()
    );
    let mut bar = Bar::new();
    // Every few minutes the bed as it is goes to a checkpoint file beside the output, so that a stopped
    // preparation of hours loses at most those minutes: `--resume` it.
    let checkpoint = out.with_extension("checkpoint.pfbed");
    let mut last_checkpoint = Instant::now();
    let mut show = |p: &Progress| {
        bar.show(p);
        if last_checkpoint.elapsed().as_secs_f64() > 60.0 * every {
            last_checkpoint = Instant::now();
            if let Err(e) = file::save(&checkpoint, p.bed, &scene) {
                eprintln!("warning: cannot write the checkpoint {}: {e}", checkpoint.display());
            }
        }
    };
    let (engine, report) = match saved {
        Some(engine) => {
            let done = prepare::phase_done(&engine, &scene);
            eprintln!("resuming {} after phase `{done}` (bed time {:.4e} s)", resume.as_deref().unwrap_or(Path::new("")).display(), engine.time());
            prepare::resume(engine, &scene, until, &mut show)
        }
        None => prepare::prepare_until(&scene, until, &mut show),
    }
    .map_err(|e| {
        if checkpoint.exists() {
            // A bed that stopped calming just above the threshold goes on from its checkpoint with a looser one.
            format!(
                "{e}\nthe last checkpoint is {0}: go on from it with `powderfmu bed prepare --resume {0}` (with --settle-energy-ratio above the ratio printed, if the bed did not come to rest)",
                checkpoint.display()
            )
        } else {
            e.to_string()
        }
    })?;
    bar.finish();
    file::save(&out, &engine, &scene).map_err(|e| format!("cannot write bed file `{}`: {e}", out.display()))?;
    let _ = std::fs::remove_file(&checkpoint);
    println!("time step: {:.4e} s", report.time_step);
    for (phase, t, steps) in &report.phases {
        println!("{phase:<12} {t:.4e} s simulated, {steps} steps");
    }
    if let Some(s) = report.stress_at_target {
        println!(
            "consolidation stress reached: piston {:.4e} Pa, Bagi sigma_zz in the middle half {:.4e} Pa (target {:.4e} Pa)",
            report.consolidation_stress,
            s.get(2, 2),
            scene.consolidation_stress
        );
    }
    println!("wall time: {:.1} s", bar.start.elapsed().as_secs_f64());
    drop(engine);
    // The bed as the file gives it back (one thread), so that every number here, memory included, is the
    // one `bed info` prints for the file.
    let (mut engine, scene) = load(&out, Some(1))?;
    describe(&mut engine, &scene);
    println!("bed written to {}", out.display());
    Ok(())
}

pub(crate) fn load(path: &Path, threads: Option<usize>) -> Result<(AnyEngine, BedScene), String> {
    file::load(path, threads).map_err(|e| format!("{}: {e}", path.display()))
}

/// The numbers `bed info` prints.
fn describe(engine: &mut AnyEngine, scene: &BedScene) {
    let p = engine.particles();
    let n = p.len();
    let height = prepare::bed_height(p);
    let solid: f64 = p.radius.iter().map(|r| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3)).sum();
    let die_area = scene.sector_area();
    let (contacts, mean_overlap) = engine.contact_statistics();
    let mean_d = 2.0 * p.radius.iter().sum::<f64>() / n.max(1) as f64;
    if scene.die_sector < 1.0 {
        println!(
            "particles:            {n} in {} of the die (mirror planes; the whole die would hold {:.0})",
            scene.die_sector,
            n as f64 / scene.die_sector
        );
    } else {
        println!("particles:            {n}");
    }
    println!("contact model:        {:?}", scene.model);
    println!("bed height:           {height:.5e} m ({:.1} mean diameters)", height / mean_d);
    println!("solid fraction:       {:.4}", solid / (die_area * height));
    println!("coordination number:  {:.3} (particle contacts per particle)", 2.0 * contacts as f64 / n.max(1) as f64);
    println!("mean overlap:         {mean_overlap:.4e} m ({:.3e} of the mean diameter)", mean_overlap / mean_d);
    println!("kinetic energy:       {:.4e} J", p.kinetic_energy());
    println!("time step:            {:.4e} s", engine.dt());
    println!("bed time:             {:.5e} s, prepared through `{}`", engine.time(), prepare::phase_done(engine, scene));
    println!(
        "memory:               {:.0} bytes per particle (the engine on one thread, as loaded from the file)",
        engine.memory_bytes() as f64 / n.max(1) as f64
    );
    // Bagi's stress in the middle of the bed, a die radius wide minus two diameters.
    let region = Region { radius: 0.5 * scene.die_diameter - 2.0 * mean_d, z_low: 0.25 * height, z_high: 0.75 * height };
    let s = bagi(engine, &region).of_whole_die(scene.die_sector);
    println!(
        "stress, middle half:  sigma_zz {:.4e} Pa, sigma_xx {:.4e} Pa, hydrostatic {:.4e} Pa, deviatoric {:.4e} Pa (004 Eqs. 5.1-5.3)",
        s.get(2, 2),
        s.get(0, 0),
        s.hydrostatic(),
        s.deviatoric()
    );
}

fn info_cmd(path: &Path) -> Result<(), String> {
    let (mut engine, scene) = load(path, Some(1))?;
    println!("bed file:             {} (format version {})", path.display(), file::VERSION);
    describe(&mut engine, &scene);
    Ok(())
}

/// Reads only the bed's scene (not its spheres' engine), so that it is quick on a large bed.
fn params_cmd(path: &Path) -> Result<(), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
    let bed = file::decode(&bytes).map_err(|e| format!("`{}`: {e}", path.display()))?;
    let scene = BedScene::from_stored_json(&bed.scene).map_err(|e| format!("`{}`: its scene: {e}", path.display()))?;
    let absolute = std::fs::canonicalize(path).map_err(|e| format!("`{}`: {e}", path.display()))?;
    let mut params = serde_json::Map::new();
    params.insert("bed_file".into(), absolute.display().to_string().into());
    params.extend(powderfmu::units::ball_indentation::parameters_of_bed(&scene));
    println!("{}", serde_json::to_string_pretty(&params).expect("JSON"));
    Ok(())
}

fn snapshot_cmd(path: &Path, out: &Path) -> Result<(), String> {
    let format = out.extension().and_then(|e| e.to_str()).filter(|e| *e == "vtk" || *e == "csv");
    let Some(format) = format else { return Err(format!("output `{}`: give a file ending in .vtk or .csv", out.display())) };
    let (engine, _) = load(path, Some(1))?;
    let text = if format == "vtk" { export::vtk(&engine) } else { export::csv(&engine) };
    file::write_atomic(out, text.as_bytes()).map_err(|e| format!("cannot write `{}`: {e}", out.display()))?;
    println!("{} spheres written to {}", engine.particles().len(), out.display());
    Ok(())
}

fn render_cmd(path: &Path, out: &Path, width: u32) -> Result<(), String> {
    let (mut engine, scene) = load(path, Some(1))?;
    let (png, legend) = render::cross_section(&mut engine, scene.die_diameter, width)?;
    file::write_atomic(out, &png).map_err(|e| format!("cannot write `{}`: {e}", out.display()))?;
    let out = out.display();
    println!(
        "{}x{} px, {} spheres cut by the plane y = 0; colour: vertical stress per sphere, {:.3e} Pa (dark blue) to {:.3e} Pa (yellow), log scale; grey: unloaded -> {out}",
        legend.width, legend.height, legend.spheres_cut, legend.stress_low, legend.stress_high
    );
    Ok(())
}

fn export_cmd(path: &Path, out: &Path) -> Result<(), String> {
    let (engine, scene) = load(path, Some(1))?;
    let text = powderfmu::bed::lammps::data_file(&engine, scene.density);
    file::write_atomic(out, text.as_bytes()).map_err(|e| format!("cannot write `{}`: {e}", out.display()))?;
    println!("{} spheres written to {}", engine.particles().len(), out.display());
    Ok(())
}

/// The bed of `path` under another law: same positions and walls, contacts start fresh.
#[allow(clippy::too_many_arguments)] // the bench's options, each laid over the bed's scene
fn with_model(
    path: &Path,
    model: &str,
    stiffness: f64,
    yield_pressure: f64,
    surface_energy: Option<f64>,
    threads: usize,
    rolling: Option<f64>,
    skin: Option<f64>,
    forget: Option<f64>,
) -> Result<(AnyEngine, BedScene), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read bed file `{}`: {e}", path.display()))?;
    let mut f: BedFile = file::decode(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut scene: serde_json::Value = serde_json::from_str(&f.scene).map_err(|e| e.to_string())?;
    let law = if model == "hooke" { "linear" } else { model };
    for key in ["particle_particle", "particle_wall"] {
        let m = scene[key].as_object_mut().ok_or("bed scene without law maps")?;
        m.insert("contact_model".into(), law.into());
        if law == "linear" {
            m.insert("linear_stiffness".into(), stiffness.into());
        }
        if let (Some(gamma), "particle_particle") = (surface_energy, key) {
            m.insert("surface_energy".into(), gamma.into());
        }
        if !m.contains_key("particle_yield_pressure") && !m.contains_key("particle_yield_stress") {
            // The elasto-plastic laws need a yield pressure (000 Sec. 3.1); the others ignore it.
            m.insert("particle_yield_pressure".into(), yield_pressure.into());
        }
    }
    scene["threads"] = threads.into();
    if let Some(mu_r) = rolling {
        scene["rolling_friction"] = mu_r.into();
        scene["wall_rolling_friction"] = mu_r.into();
    }
    if let Some(skin) = skin {
        scene["skin"] = skin.into();
    }
    if let Some(forget) = forget {
        scene["forgetting_distance"] = forget.into();
    }
    f.scene = scene.to_string();
    // No contacts of the old law: empty lists (an empty list encodes the same whatever its item type).
    f.contacts = powderfmu::codec::to_bytes(&Vec::<()>::new())?;
    f.wall_contacts = powderfmu::codec::to_bytes(&vec![Vec::<()>::new(); f.walls.len()])?;
    AnyEngine::from_file(&f, Some(threads)).map_err(|e| format!("{} under {model}: {e}", path.display()))
}

fn bench_cmd(a: BenchArgs) -> Result<(), String> {
    let BenchArgs { bed, model, steps, warmup, threads, stiffness, yield_pressure, surface_energy, rolling_friction, skin, forgetting_distance } = a;
    let threads = usize::from(threads);
    let (mut engine, _) = with_model(&bed, &model, stiffness, yield_pressure, surface_energy, threads, rolling_friction, skin, forgetting_distance)?;
    engine.run(warmup);
    let n = engine.particles().len();
    let start = Instant::now();
    engine.run(steps);
    let seconds = start.elapsed().as_secs_f64();
    let ke = engine.particles().kinetic_energy();
    let builds = engine.list_builds();
    let (near_builds, near_per_sphere, near_mode) = engine.near_lists();
    let (contacts, _) = engine.contact_statistics();
    let digest = engine.state_digest();
    let (isa, pair_loop) = engine.isa_and_pair_loop();
    println!(
        "model={model} particles={n} steps={steps} threads={threads} dt={:.4e} seconds={seconds:.4} particle_steps_per_s={:.4e} bytes_per_particle={:.0} kinetic_energy={ke:.3e} list_builds={builds} near_builds={near_builds} near_per_particle={near_per_sphere:.3} near_mode={near_mode} contacts_per_particle={:.3} isa={isa} pair_loop={pair_loop} state_digest={digest:016x}",
        engine.dt(),
        n as f64 * steps as f64 / seconds,
        engine.memory_bytes() as f64 / n as f64,
        contacts as f64 / n as f64
    );
    Ok(())
}

/// The bed's scene with `overlay` (a JSON object of bed scene keys) laid over it, given to the running
/// bed: the objects `particle_particle` and `particle_wall` merge key by key, other keys replace.
fn changed_scene(engine: &mut AnyEngine, scene: &BedScene, overlay: &str) -> Result<BedScene, String> {
    let overlay: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(overlay).map_err(|e| format!("must be a JSON object of bed scene keys: {e}"))?;
    for group in ["particle_particle", "particle_wall"] {
        if let Some(model) = overlay.get(group).and_then(|g| g.get("contact_model")) {
            if model.as_str() != Some(scene.model.name()) {
                return Err(format!("contact_model must stay the bed's ({}), got {model}: the contacts' memory is that law's", scene.model.name()));
            }
        }
    }
    let serde_json::Value::Object(mut map) = scene.to_json() else { unreachable!("a bed scene is a JSON object") };
    for (key, value) in overlay {
        match (map.get_mut(&key), value) {
            (Some(serde_json::Value::Object(base)), serde_json::Value::Object(keys)) => base.extend(keys),
            (_, value) => {
                map.insert(key, value);
            }
        }
    }
    let changed = BedScene::from_map(&map).map_err(|e| e.to_string())?;
    if changed.model != scene.model {
        return Err(format!("contact_model must stay the bed's ({}): the contacts' memory is that law's", scene.model.name()));
    }
    engine.set_scene(&changed).map_err(|e| e.to_string())?;
    if let Some(skin) = changed.skin {
        engine.set_skin(skin)?;
    }
    if let Some(forget) = changed.forgetting_distance {
        engine.set_forgetting_distance(forget)?;
    }
    Ok(changed)
}

/// The loading's share of an indentation's progress bar (the unloading is short; see `indent_cmd`).
const LOADING_SHARE: f64 = 0.95;

fn indent_cmd(a: IndentArgs) -> Result<(), String> {
    let (mut engine, mut scene) = load(&a.bed, a.threads.map(usize::from))?;
    if let Some(text) = &a.change {
        scene = changed_scene(&mut engine, &scene, text).map_err(|e| format!("--change: {e}"))?;
        eprintln!("indentation: the bed's scene changed by {text}");
    }
    let mean = scene.size_distribution.mean_diameter();
    let d = a.diameter.unwrap_or(16.0 * mean);
    let tuned = a.mobile_zone.is_some() || a.release.is_some();
    let shortcut = match a.fidelity {
        Some(Fidelity::Full) if tuned => {
            return Err("--mobile-zone and --release set the shortcut of --fidelity fast; --fidelity full moves every sphere".into())
        }
        Some(Fidelity::Full) => None,
        None if !tuned => None,
        _ => Some(Shortcut { zone: a.mobile_zone.unwrap_or(FAST.zone), release: a.release.unwrap_or(FAST.release) }),
    };
    let setup = Setup {
        indenter_diameter: d,
        indentation_speed: a.speed,
        max_penetration: a.max_penetration.unwrap_or(0.1 * d),
        constraint_factor: 3.0,
        constraint_factor_standard_error: 0.0,
        motion: Motion::Prescribed,
        shortcut,
        plateau: (a.plateau_start, a.plateau_end),
        depth_origin: match a.depth_origin {
            Origin::FirstTouch => DepthOrigin::FirstTouch,
            Origin::MeanSurface => DepthOrigin::MeanSurface,
        },
    };
    let every = a.every;
    let over = |option: &str,
                text: &Option<String>,
                base: serde_json::Map<String, serde_json::Value>|
     -> Result<Option<serde_json::Map<String, serde_json::Value>>, String> {
        let Some(text) = text else { return Ok(None) };
        let overlay: serde_json::Map<String, serde_json::Value> =
            serde_json::from_str(text).map_err(|e| format!("{option} must be a JSON object of scene keys: {e}"))?;
        let mut pair = base;
        pair.extend(overlay);
        Ok(Some(pair))
    };
    let indenter = over("--indenter", &a.indenter, scene.indenter_pair())?;
    let walls = over("--walls", &a.walls, scene.particle_wall.clone())?;
    let mut test = Indentation::new(engine, scene, setup, None, indenter.as_ref()).map_err(|e| e.to_string())?;
    if let Some(pair) = &walls {
        test.set_die_walls(pair).map_err(|e| format!("--walls: {e}"))?;
    }
    if let Some(dt) = a.time_step {
        test.engine.set_time_step(&test.scene, dt).map_err(|e| format!("--time-step: {e}"))?;
    }
    eprintln!(
        "indentation: depth from the {} ({:.4e} m below the first touch at z = {:.6e} m); plateau window h/r {}-{}",
        setup.depth_origin.name().replace('_', " "),
        test.record.touch - test.record.origin,
        test.record.touch,
        setup.plateau.0,
        setup.plateau.1
    );
    let mut csv = String::from("time_s,depth_m,depth_over_r,force_N,hardness_Pa,hydrostatic_Pa,deviatoric_Pa,contacts,kinetic_energy_J,state\n");
    let started = Instant::now();
    let mut t = 0.0;
    let limit = 4.0 * setup.max_penetration / setup.indentation_speed + 1.0;
    let mut bar = Bar::new();
    loop {
        test.advance(every, None).map_err(|e| e.to_string())?;
        t += every;
        let r = test.reading();
        // Loading to h_max is nearly the whole job: on the sixteen Ch. 5 runs in docs/data the bed let go
        // within one 1 ms sample of the turn. Counting the unloading as half (as before) doubled the time
        // left shown all through the loading; it now gets the last 5 %, and the bar jumps to the end
        // when the bed lets go.
        let depth_fraction = (r.depth / setup.max_penetration).clamp(0.0, 1.0);
        let (phase, fraction) = match r.state {
            TestState::Loading => ("loading", LOADING_SHARE * depth_fraction),
            TestState::Unloading => ("unloading", (1.0 - (1.0 - LOADING_SHARE) * depth_fraction).min(0.99)),
            TestState::Done => ("done", 1.0),
        };
        let detail = format!("h/r {:.3}  F {:.4e} N", r.dimensionless_depth, r.force);
        bar.show_phase(phase, fraction, t, &detail);
        csv += &format!(
            "{t:.6e},{:.6e},{:.5},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.4e},{}\n",
            r.depth,
            r.dimensionless_depth,
            r.force,
            r.hardness,
            r.hydrostatic_stress,
            r.deviatoric_stress,
            r.contacts,
            r.kinetic_energy,
            r.state as u8
        );
        if r.state == TestState::Done || t > limit {
            bar.finish();
            let wall = started.elapsed().as_secs_f64();
            let particle_steps = test.engine.particles().len() as f64 * test.record.steps as f64;
            let moving = test.engine.particles().held.iter().filter(|&&h| !h).count();
            let p = r.plateau;
            eprintln!(
                "indentation: h_max {:.4e} m (h/r {:.3}; depth from the {}, {:.4e} m below the first touch), F_max {:.4e} N (read over the last tenth of the loading; largest sample {:.4e} N), h_c {:.4e} m ({}), hardness {:.4e} +- {:.2e} Pa (standard error of the force at the turn), plateau hardness {:.4e} +- {:.2e} Pa (standard error; h/r {}-{}, {} samples, correlation time {:.1} samples{}), {:.1} s wall time, {} steps, {:.3e} particle-steps/s, {moving} spheres moving",
                test.record.h_max,
                test.record.h_max / (0.5 * d),
                setup.depth_origin.name().replace('_', " "),
                r.depth_origin_offset,
                r.turn_force,
                test.record.f_max,
                r.contact_depth,
                if r.contact_depth_from_tangent { "tangent" } else { "no tangent: h_max" },
                r.hardness,
                r.hardness_standard_error,
                p.mean,
                p.standard_error,
                setup.plateau.0,
                setup.plateau.1,
                p.samples,
                p.correlation_time,
                if p.reliable() { "" } else { ", under 50 correlation times: the error is itself uncertain" },
                wall,
                test.record.steps,
                particle_steps / wall
            );
            let (hyd, dev) = (r.window_hydrostatic_stress, r.window_deviatoric_stress);
            eprintln!(
                "dynamic bin, h/r {}-{}: hydrostatic {:.4e} +- {:.2e} Pa, deviatoric {:.4e} +- {:.2e} Pa (standard errors; {} samples while loading; 004 Eqs. 5.2-5.3, Fig. 5.19)",
                setup.plateau.0, setup.plateau.1, hyd.mean, hyd.standard_error, dev.mean, dev.standard_error, hyd.samples
            );
            if let Some(path) = &a.samples_out {
                let mut rows = String::from("depth_m,force_N\n");
                for (h, f) in &test.record.loading {
                    rows += &format!("{h:.6e},{f:.6e}\n");
                }
                file::write_atomic(path, rows.as_bytes()).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            }
            break;
        }
    }
    match &a.out {
        Some(path) => file::write_atomic(path, csv.as_bytes()).map_err(|e| format!("cannot write {}: {e}", path.display())),
        None => {
            print!("{csv}");
            Ok(())
        }
    }
}
