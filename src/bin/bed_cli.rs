//! `powderfmu bed ...`: prepare a bed, describe it, look at it, export it, time it.

use powderfmu::bed::file::{self, BedFile};
use powderfmu::bed::indentation::{Indentation, Motion, Setup, Shortcut, TestState, FAST};
use powderfmu::bed::prepare::{self, Progress};
use powderfmu::bed::stress::{bagi, Region};
use powderfmu::bed::{export, render, AnyEngine, BedScene};
use powderfmu::with_engine;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub const USAGE: &str = "  powderfmu bed prepare SCENE.json [-o BED] [--threads N] [--until PHASE]
                                                        fill, settle, consolidate, unload, relax (004 Sec. 5.1.3)
  powderfmu bed prepare --resume BED [-o BED] [--threads N] [--until PHASE] [--checkpoint MIN]
                                                        continue a bed saved with --until, or a checkpoint (written
                                                        every MIN minutes, default 10, as OUT.checkpoint.pfbed)
  powderfmu bed info BED                                count, height, solid fraction, coordination, overlap, stress
  powderfmu bed snapshot BED OUT.vtk|OUT.csv            spheres for ParaView (VTK) or a spreadsheet (CSV)
  powderfmu bed render BED OUT.png [--width PX]         vertical cross-section through the die axis
  powderfmu bed export-lammps BED OUT.data              LAMMPS data file (atom_style sphere)
  powderfmu bed indent BED [--diameter D] [--speed V] [--max-penetration H] [--threads T] [--out CSV]
                        [--every S] [--indenter JSON] [--time-step DT] [--fidelity full|fast] [--mobile-zone M] [--release E]
                                                        ball indentation (004 Sec. 2.3.5): load to H, unload; force-depth CSV;
                                                        --indenter: scene keys of the particle-indenter contact over the bed's walls' 
                                                        --fidelity fast: spheres beyond M a_max held until the force on one changes by E sigma_c d^2
  powderfmu bed bench BED --model M [--steps N] [--threads T] [--stiffness K] [--yield-pressure P]
                        [--surface-energy G] [--rolling-friction MU]
                                                        particle-steps per second of the force loop";

pub fn run(args: &[String]) -> Result<(), String> {
    match args.first().map(String::as_str) {
        Some("prepare") => prepare_cmd(&args[1..]),
        Some("info") => info_cmd(&args[1..]),
        Some("snapshot") => snapshot_cmd(&args[1..]),
        Some("render") => render_cmd(&args[1..]),
        Some("export-lammps") => export_cmd(&args[1..]),
        Some("bench") => bench_cmd(&args[1..]),
        Some("indent") => indent_cmd(&args[1..]),
        Some(other) => Err(format!("unknown bed subcommand `{other}`\nusage:\n{USAGE}")),
        None => Err(format!("usage:\n{USAGE}")),
    }
}

/// Positional arguments and `--flag value` options.
struct Args {
    positional: Vec<String>,
    options: Vec<(String, String)>,
}

fn parse(args: &[String], flags: &[&str]) -> Result<Args, String> {
    let mut out = Args { positional: vec![], options: vec![] };
    let mut i = 0;
    while i < args.len() {
        let a = &args[i];
        if a.starts_with('-') {
            if !flags.contains(&a.as_str()) {
                return Err(format!("unknown option `{a}` (allowed here: {})", flags.join(", ")));
            }
            let v = args.get(i + 1).ok_or_else(|| format!("option `{a}` needs a value"))?;
            out.options.push((a.clone(), v.clone()));
            i += 2;
        } else {
            out.positional.push(a.clone());
            i += 1;
        }
    }
    Ok(out)
}

impl Args {
    fn get(&self, flag: &str) -> Option<&str> {
        self.options.iter().rev().find(|(f, _)| f == flag).map(|(_, v)| v.as_str())
    }

    fn number<T: std::str::FromStr>(&self, flag: &str, default: T, check: impl Fn(&T) -> bool, allowed: &str) -> Result<T, String> {
        match self.get(flag) {
            None => Ok(default),
            Some(text) => match text.parse::<T>() {
                Ok(v) if check(&v) => Ok(v),
                _ => Err(format!("{flag} = `{text}` is not allowed: {allowed}")),
            },
        }
    }

    fn need(&self, k: usize, what: &str) -> Result<&str, String> {
        self.positional.get(k).map(String::as_str).ok_or_else(|| format!("missing {what}"))
    }
}

fn threads_option(a: &Args) -> Result<Option<usize>, String> {
    if a.get("--threads").is_none() {
        return Ok(None);
    }
    a.number("--threads", 1usize, |t| (1..=256).contains(t), "give a whole number in [1, 256]").map(Some)
}

/// A progress bar on a terminal (redrawn in place), or a line per 5 % elsewhere (logs, CI).
struct Bar {
    start: Instant,
    tty: bool,
    last_line: f64,
}

impl Bar {
    fn show(&mut self, p: &Progress) {
        let elapsed = self.start.elapsed().as_secs_f64();
        let left = if p.fraction > 0.01 { elapsed * (1.0 - p.fraction) / p.fraction } else { f64::NAN };
        let clock = |s: f64| if s.is_finite() { format!("{:02}:{:02}", (s / 60.0) as u64, (s % 60.0) as u64) } else { "--:--".into() };
        let filled = (p.fraction * 30.0) as usize;
        let line = format!(
            "[{}{}] {:3.0}% {:<11} t = {:.4e} s  {}  elapsed {}  left ~{}",
            "#".repeat(filled),
            ".".repeat(30 - filled),
            100.0 * p.fraction,
            p.phase,
            p.time,
            p.detail,
            clock(elapsed),
            clock(left)
        );
        if self.tty {
            eprint!("\r{line}\x1b[K");
        } else if p.fraction >= self.last_line + 0.05 || p.fraction >= 1.0 {
            self.last_line = p.fraction;
            eprintln!("{line}");
        }
    }
}

fn prepare_cmd(args: &[String]) -> Result<(), String> {
    let a = parse(args, &["-o", "--output", "--threads", "--until", "--resume", "--checkpoint"])?;
    let every = a.number("--checkpoint", 10.0f64, |m| m.is_finite() && *m > 0.0, "give minutes > 0")?;
    let until = a.get("--until").unwrap_or("relax");
    if !prepare::PHASES.contains(&until) {
        return Err(format!("--until = `{until}` is not allowed: give one of {}", prepare::PHASES.join(", ")));
    }
    let resume = a.get("--resume");
    let threads = threads_option(&a)?;
    let (mut scene, saved, default_out) = match resume {
        Some(bed) => {
            let (engine, scene) = load(bed, threads)?;
            (scene, Some(engine), PathBuf::from(bed))
        }
        None => {
            let scene_path = a.need(0, "the bed scene file (JSON), or --resume BED")?;
            let text = std::fs::read_to_string(scene_path).map_err(|e| format!("cannot read bed scene `{scene_path}`: {e}"))?;
            let scene = BedScene::from_json(&text).map_err(|e| format!("{scene_path}: {e}"))?;
            (scene, None, Path::new(scene_path).with_extension("bed"))
        }
    };
    if let Some(t) = threads {
        scene.threads = t;
    }
    let out = match a.get("-o").or(a.get("--output")) {
        Some(o) => PathBuf::from(o),
        None => default_out,
    };
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
    let mut bar = Bar { start: Instant::now(), tty: std::io::stderr().is_terminal(), last_line: -1.0 };
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
    let (mut engine, report) = match saved {
        Some(engine) => {
            let done = prepare::phase_done(&engine, &scene);
            eprintln!("resuming {} after phase `{done}` (bed time {:.4e} s)", resume.unwrap_or_default(), engine.time());
            prepare::resume(engine, &scene, until, &mut show)
        }
        None => prepare::prepare_until(&scene, until, &mut show),
    }
    .map_err(|e| {
        if checkpoint.exists() {
            format!("{e}\nthe last checkpoint is {}", checkpoint.display())
        } else {
            e.to_string()
        }
    })?;
    if bar.tty {
        eprintln!();
    }
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
    describe(&mut engine, &scene);
    println!("bed written to {}", out.display());
    Ok(())
}

fn load(path: &str, threads: Option<usize>) -> Result<(AnyEngine, BedScene), String> {
    file::load(Path::new(path), threads).map_err(|e| format!("{path}: {e}"))
}

/// The numbers `bed info` prints.
fn describe(engine: &mut AnyEngine, scene: &BedScene) {
    let p = engine.particles();
    let n = p.len();
    let height = prepare::bed_height(p);
    let solid: f64 = p.radius.iter().map(|r| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3)).sum();
    let die_area = std::f64::consts::PI * 0.25 * scene.die_diameter * scene.die_diameter;
    let (contacts, mean_overlap) = with_engine!(&*engine, e => e.contact_statistics());
    let mean_d = 2.0 * p.radius.iter().sum::<f64>() / n.max(1) as f64;
    println!("particles:            {n}");
    println!("contact model:        {:?}", scene.model);
    println!("bed height:           {height:.5e} m ({:.1} mean diameters)", height / mean_d);
    println!("solid fraction:       {:.4}", solid / (die_area * height));
    println!("coordination number:  {:.3} (particle contacts per particle)", 2.0 * contacts as f64 / n.max(1) as f64);
    println!("mean overlap:         {mean_overlap:.4e} m ({:.3e} of the mean diameter)", mean_overlap / mean_d);
    println!("kinetic energy:       {:.4e} J", p.kinetic_energy());
    println!("time step:            {:.4e} s", engine.dt());
    println!("bed time:             {:.5e} s, prepared through `{}`", engine.time(), prepare::phase_done(engine, scene));
    println!("memory:               {:.0} bytes per particle", engine.memory_bytes() as f64 / n.max(1) as f64);
    // Bagi's stress in the middle of the bed, a die radius wide minus two diameters.
    let region = Region { radius: 0.5 * scene.die_diameter - 2.0 * mean_d, z_low: 0.25 * height, z_high: 0.75 * height };
    let s = bagi(engine, &region);
    println!(
        "stress, middle half:  sigma_zz {:.4e} Pa, sigma_xx {:.4e} Pa, hydrostatic {:.4e} Pa, deviatoric {:.4e} Pa (004 Eqs. 5.1-5.3)",
        s.get(2, 2),
        s.get(0, 0),
        s.hydrostatic(),
        s.deviatoric()
    );
}

fn info_cmd(args: &[String]) -> Result<(), String> {
    let a = parse(args, &[])?;
    let path = a.need(0, "the bed file")?;
    let (mut engine, scene) = load(path, Some(1))?;
    println!("bed file:             {path} (format version {})", file::VERSION);
    describe(&mut engine, &scene);
    Ok(())
}

fn snapshot_cmd(args: &[String]) -> Result<(), String> {
    let a = parse(args, &[])?;
    let (path, out) = (a.need(0, "the bed file")?, a.need(1, "the output file (.vtk or .csv)")?);
    let (engine, _) = load(path, Some(1))?;
    let text = if out.ends_with(".vtk") {
        export::vtk(&engine)
    } else if out.ends_with(".csv") {
        export::csv(&engine)
    } else {
        return Err(format!("output `{out}`: give a file ending in .vtk or .csv"));
    };
    file::write_atomic(Path::new(out), text.as_bytes()).map_err(|e| format!("cannot write `{out}`: {e}"))?;
    println!("{} spheres written to {out}", engine.particles().len());
    Ok(())
}

fn render_cmd(args: &[String]) -> Result<(), String> {
    let a = parse(args, &["--width"])?;
    let (path, out) = (a.need(0, "the bed file")?, a.need(1, "the output PNG")?);
    let width = a.number("--width", 900u32, |w| (50..=10000).contains(w), "give a whole number of pixels in [50, 10000]")?;
    let (mut engine, scene) = load(path, Some(1))?;
    let (png, legend) = render::cross_section(&mut engine, scene.die_diameter, width)?;
    file::write_atomic(Path::new(out), &png).map_err(|e| format!("cannot write `{out}`: {e}"))?;
    println!(
        "{}x{} px, {} spheres cut by the plane y = 0; colour: vertical stress per sphere, {:.3e} Pa (dark blue) to {:.3e} Pa (yellow), log scale; grey: unloaded -> {out}",
        legend.width, legend.height, legend.spheres_cut, legend.stress_low, legend.stress_high
    );
    Ok(())
}

fn export_cmd(args: &[String]) -> Result<(), String> {
    let a = parse(args, &[])?;
    let (path, out) = (a.need(0, "the bed file")?, a.need(1, "the output data file")?);
    let (engine, scene) = load(path, Some(1))?;
    let text = powderfmu::bed::lammps::data_file(&engine, scene.density);
    file::write_atomic(Path::new(out), text.as_bytes()).map_err(|e| format!("cannot write `{out}`: {e}"))?;
    println!("{} spheres written to {out}", engine.particles().len());
    Ok(())
}

/// The bed of `path` under another law: same positions and walls, contacts start fresh.
fn with_model(
    path: &str,
    model: &str,
    stiffness: f64,
    yield_pressure: f64,
    surface_energy: Option<f64>,
    threads: usize,
    rolling: Option<f64>,
) -> Result<(AnyEngine, BedScene), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read bed file `{path}`: {e}"))?;
    let mut f: BedFile = file::decode(&bytes).map_err(|e| format!("{path}: {e}"))?;
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
    f.scene = scene.to_string();
    // No contacts of the old law: empty lists (an empty list encodes the same whatever its item type).
    f.contacts = powderfmu::codec::to_bytes(&Vec::<()>::new())?;
    f.wall_contacts = powderfmu::codec::to_bytes(&vec![Vec::<()>::new(); f.walls.len()])?;
    AnyEngine::from_file(&f, Some(threads)).map_err(|e| format!("{path} under {model}: {e}"))
}

fn bench_cmd(args: &[String]) -> Result<(), String> {
    let a = parse(args, &["--model", "--steps", "--threads", "--stiffness", "--warmup", "--yield-pressure", "--surface-energy", "--rolling-friction"])?;
    let rolling = match a.get("--rolling-friction") {
        None => None,
        Some(_) => Some(a.number("--rolling-friction", 0.0f64, |m| m.is_finite() && *m >= 0.0 && *m < 10.0, "give a rolling friction coefficient in [0, 10)")?),
    };
    let path = a.need(0, "the bed file")?;
    let model = a.get("--model").ok_or("--model is required: hooke, hertz, jkr, nan or any contact_model")?;
    let steps = a.number("--steps", 2000u64, |s| (1..=100_000_000).contains(s), "give a whole number in [1, 1e8]")?;
    let warmup = a.number("--warmup", 200u64, |s| *s <= 100_000_000, "give a whole number in [0, 1e8]")?;
    let threads = a.number("--threads", 1usize, |t| (1..=256).contains(t), "give a whole number in [1, 256]")?;
    let stiffness = a.number("--stiffness", 2e5f64, |k| k.is_finite() && *k > 0.0 && *k < 1e12, "give a spring stiffness in (0, 1e12) N/m")?;
    let yield_pressure =
        a.number("--yield-pressure", 2e6f64, |p| p.is_finite() && *p > 0.0 && *p < 1e13, "give a yield pressure in (0, 1e13) Pa")?;
    let surface_energy = match a.get("--surface-energy") {
        None => None,
        Some(_) => Some(a.number("--surface-energy", 0.0f64, |g| g.is_finite() && *g >= 0.0 && *g < 1e3, "give an interface energy in [0, 1e3) J/m^2")?),
    };
    let (mut engine, _) = with_model(path, model, stiffness, yield_pressure, surface_energy, threads, rolling)?;
    engine.run(warmup);
    let n = engine.particles().len();
    let start = Instant::now();
    engine.run(steps);
    let seconds = start.elapsed().as_secs_f64();
    let ke = engine.particles().kinetic_energy();
    let builds = with_engine!(&engine, e => e.list.builds);
    let (contacts, _) = with_engine!(&engine, e => e.contact_statistics());
    println!(
        "model={model} particles={n} steps={steps} threads={threads} dt={:.4e} seconds={seconds:.4} particle_steps_per_s={:.4e} bytes_per_particle={:.0} kinetic_energy={ke:.3e} list_builds={builds} contacts_per_particle={:.3}",
        engine.dt(),
        n as f64 * steps as f64 / seconds,
        engine.memory_bytes() as f64 / n as f64,
        contacts as f64 / n as f64
    );
    Ok(())
}

fn indent_cmd(args: &[String]) -> Result<(), String> {
    let a = parse(args, &["--diameter", "--speed", "--max-penetration", "--threads", "--out", "--every", "--indenter", "--time-step", "--fidelity", "--mobile-zone", "--release"])?;
    let (engine, scene) = load(a.need(0, "BED (a prepared bed file)")?, threads_option(&a)?)?;
    let mean = scene.size_distribution.mean_diameter();
    let d = a.number("--diameter", 16.0 * mean, |v: &f64| *v > 0.0, "a diameter > 0 [m]")?;
    let setup = Setup {
        indenter_diameter: d,
        indentation_speed: a.number("--speed", 0.02, |v: &f64| *v > 0.0, "a speed > 0 [m/s]")?,
        max_penetration: a.number("--max-penetration", 0.1 * d, |v: &f64| *v > 0.0, "a depth > 0 [m]")?,
        constraint_factor: 3.0,
        motion: Motion::Prescribed,
        shortcut: match (a.get("--fidelity"), a.get("--mobile-zone").or(a.get("--release"))) {
            (Some("full") | None, None) => None,
            (Some("fast") | None, _) => Some(Shortcut {
                zone: a.number("--mobile-zone", FAST.zone, |m: &f64| *m > 0.0 && m.is_finite(), "a factor > 0 on the contact radius a_max")?,
                release: a.number("--release", FAST.release, |e: &f64| *e > 0.0, "a fraction > 0 of consolidation_stress x d^2 (inf: never)")?,
            }),
            (Some("full"), Some(_)) => return Err("--mobile-zone and --release set the shortcut of --fidelity fast; --fidelity full moves every sphere".into()),
            (Some(other), _) => return Err(format!("--fidelity = `{other}` is not allowed: give fast or full")),
        },
    };
    let every = a.number("--every", 1e-3, |v: &f64| *v > 0.0, "a time > 0 [s]")?;
    let indenter = match a.get("--indenter") {
        None => None,
        Some(text) => {
            let overlay: serde_json::Map<String, serde_json::Value> =
                serde_json::from_str(text).map_err(|e| format!("--indenter must be a JSON object of scene keys: {e}"))?;
            let mut pair = scene.particle_wall.clone();
            pair.extend(overlay);
            Some(pair)
        }
    };
    let mut test = Indentation::new(engine, scene, setup, 0.0, indenter.as_ref()).map_err(|e| e.to_string())?;
    if let Some(dt) = a.get("--time-step") {
        let dt: f64 = dt.parse().map_err(|_| format!("--time-step = `{dt}` is not a number [s]"))?;
        test.engine.set_time_step(&test.scene, dt).map_err(|e| e.to_string())?;
    }
    let mut csv = String::from("time_s,depth_m,depth_over_r,force_N,hardness_Pa,hydrostatic_Pa,deviatoric_Pa,contacts,kinetic_energy_J,state\n");
    let started = Instant::now();
    let mut t = 0.0;
    let limit = 4.0 * setup.max_penetration / setup.indentation_speed + 1.0;
    loop {
        test.advance(every, None).map_err(|e| e.to_string())?;
        t += every;
        let r = test.reading();
        csv += &format!(
            "{t:.6e},{:.6e},{:.5},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.4e},{}\n",
            r.depth, r.dimensionless_depth, r.force, r.hardness, r.hydrostatic_stress, r.deviatoric_stress, r.contacts, r.kinetic_energy, r.state as u8
        );
        if r.state == TestState::Done || t > limit {
            let wall = started.elapsed().as_secs_f64();
            let particle_steps = test.engine.particles().len() as f64 * test.record.steps as f64;
            let moving = test.engine.particles().held.iter().filter(|&&h| !h).count();
            eprintln!(
                "indentation: h_max {:.4e} m (h/r {:.3}), F_max {:.4e} N, h_c {:.4e} m, hardness {:.4e} Pa, {:.1} s wall time, {} steps, {:.3e} particle-steps/s, {moving} spheres moving",
                test.record.h_max,
                test.record.h_max / (0.5 * d),
                test.record.f_max,
                r.contact_depth,
                r.hardness,
                wall,
                test.record.steps,
                particle_steps / wall
            );
            break;
        }
    }
    match a.get("--out") {
        Some(path) => std::fs::write(path, csv).map_err(|e| format!("cannot write {path}: {e}")),
        None => {
            print!("{csv}");
            Ok(())
        }
    }
}
