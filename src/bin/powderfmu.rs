//! The `powderfmu` command-line tool: the physics of the FMUs without FMI. The command line is clap's
//! (derive): every subcommand has `--help`, errors name the option, `completions` writes shell completions.

use clap::{CommandFactory, Parser, Subcommand};
use powderfmu::analysis::{analyze, to_text, OUTPUTS};
use powderfmu::curves::{force_overlap_csv, restitution_csv};
use powderfmu::impact::oblique;
use powderfmu::scene::{Scene, KEYS};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

mod bed_cli;
mod bed_compress;
mod bed_shear;
mod options;

#[derive(Parser)]
#[command(
    name = "powderfmu",
    version,
    about = "Contact mechanics of elasto-plastic adhesive spheres (Nan, Pasha, Luding, Thornton-Ning, Tomas, JKR, Hertz): the physics of the powderfmu FMUs without FMI",
    after_help = "Scenes are JSON objects of scene keys in SI units; `powderfmu analyze --help` lists every key with its unit, default and range."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Derived parameters and closed-form results of a scene, each with its unit, by law (--json: JSON)
    #[command(after_long_help = keys_help())]
    Analyze {
        /// Print JSON (the values by key, and a `units` object with the unit of each) instead of text
        #[arg(long)]
        json: bool,
        /// The scene file (JSON object of scene keys, SI units)
        scene: PathBuf,
        /// Adds one undamped impact of the active law on the wall at this speed, by energy balance [m/s]
        #[arg(long, value_name = "M_PER_S", allow_hyphen_values = true, value_parser = options::positive("m/s"))]
        velocity: Option<f64>,
    },
    /// Force along a quasi-static overlap path (CSV on stdout: overlap_m, force_N, stiffness_N_per_m, branch, contact_state)
    ///
    /// The path starts apart, at --start (default -|A1|, as far apart as the first turn is deep), runs
    /// straight to A1, then to A2, and so on, with --points states per leg.
    Curve {
        /// The scene file (JSON object of scene keys, SI units)
        scene: PathBuf,
        /// Turning overlaps A1,A2,... of the path [m] (negative: apart)
        #[arg(long, value_name = "A1,A2,..", value_delimiter = ',', required = true, allow_hyphen_values = true, value_parser = options::finite("m"))]
        path: Vec<f64>,
        /// Where the path starts [m] (default -|A1|)
        #[arg(long, value_name = "A0", allow_hyphen_values = true, value_parser = options::finite("m"))]
        start: Option<f64>,
        /// States per leg of the path
        #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u32).range(2..=1_000_000))]
        points: u32,
    },
    /// Undamped impacts on the wall by energy balance: restitution against impact velocity (CSV on stdout)
    Restitution {
        /// The scene file (JSON object of scene keys, SI units)
        scene: PathBuf,
        /// Impact speeds V1,V2,... [m/s]
        #[arg(long, value_name = "V1,V2,..", value_delimiter = ',', required = true, allow_hyphen_values = true, value_parser = options::positive("m/s"))]
        velocities: Vec<f64>,
    },
    /// Oblique impacts on the wall with tangential motion and spin, the 2D impact of the DEM benchmarks (CSV on stdout)
    ///
    /// One row per incident angle (from the wall normal) at one speed, by velocity Verlet from first
    /// touch until the sphere has left: the rebound velocities, spin, tangential restitution and rebound
    /// angle. The tangential force follows the law's pairing (Mindlin for the Hertz-based laws, k_t
    /// proportional to k_n for the linear ones, Tomas's for tomas) with the scene's friction_coefficient.
    /// Positive spin rolls the sphere toward its tangential motion. Chung and Ooi's Test 4: --speed 3.9
    /// --angles 5,10,...,85 on aluminium oxide (scenes/chung_ooi_alumina.json). A sphere the adhesion
    /// holds (still on the wall after a thousand Rayleigh steps) gets a row with sticks = true and its
    /// velocity and spin then. `mechanism` names how the contact broke (sliding detachment: on the
    /// Coulomb limit at its last step; sticking detachment: the contact point held while it broke) or
    /// where a held sphere goes (held sliding, rolling or at rest along the wall).
    Oblique {
        /// The scene file (JSON object of scene keys, SI units)
        scene: PathBuf,
        /// Impact speed |v| [m/s]
        #[arg(long, value_name = "M_PER_S", value_parser = options::positive("m/s"))]
        speed: f64,
        /// Incident angles A1,A2,... from the wall normal [deg], in [0, 90)
        #[arg(long, value_name = "A1,A2,..", value_delimiter = ',', required = true, value_parser = options::in_range(0.0, 90.0, true, "deg"))]
        angles: Vec<f64>,
        /// Spin before the impact [rad/s]
        #[arg(long, value_name = "RAD_PER_S", default_value_t = 0.0, allow_hyphen_values = true, value_parser = options::finite("rad/s"))]
        angular_velocity: f64,
        /// Rolling friction mu_r (EDEM's constant directional torque mu_r |f_n| R)
        #[arg(long, default_value_t = 0.0, value_parser = options::in_range(0.0, 1e3, true, "-"))]
        rolling_friction: f64,
        /// Time step as a fraction of the Rayleigh time step (000 Eq. 71)
        #[arg(long, default_value_t = 0.01, value_parser = options::in_range(0.0, 1.0, false, "-"))]
        rayleigh_fraction: f64,
        /// Where the tangential force acts: mid-overlap (R - alpha/2, the bed's) or radius (R, LAMMPS's walls)
        #[arg(long, default_value = "mid-overlap", value_parser = ["mid-overlap", "radius"])]
        lever: String,
        /// verlet (fixed step, what DEM codes do) or adaptive (Dormand-Prince 5(4) landing on the normal
        /// law's switches and the stick-slip switches; no rolling friction; --rayleigh-fraction is then the
        /// contact time's resolution)
        #[arg(long, default_value = "verlet", value_parser = ["verlet", "adaptive"])]
        solver: String,
        /// Relative tolerance of the adaptive solver
        #[arg(long, default_value_t = 1e-10, value_parser = options::in_range(1e-14, 1e-2, true, "-"))]
        tolerance: f64,
    },
    /// The DEM bed: prepare, describe, look at, export, time, indent
    Bed {
        #[command(subcommand)]
        command: bed_cli::BedCommand,
    },
    /// Shell completions on stdout, e.g. `powderfmu completions bash > /etc/bash_completion.d/powderfmu`
    Completions {
        /// bash, zsh, fish, elvish or powershell
        shell: clap_complete::Shell,
    },
}

fn main() -> ExitCode {
    // A closed pipe (`powderfmu analyze --help | head -1`) ends the tool quietly with exit code 0: the
    // reader has what it wanted. Rust sets SIGPIPE to "ignore" before main, and the next print would
    // panic on the broken pipe.
    #[cfg(unix)]
    // SAFETY: called once at the start of main, before any other thread exists; the handler only calls
    // the async-signal-safe _exit.
    unsafe {
        extern "C" fn reader_gone(_: libc::c_int) {
            // SAFETY: _exit is async-signal-safe.
            unsafe { libc::_exit(0) }
        }
        libc::signal(libc::SIGPIPE, reader_gone as extern "C" fn(libc::c_int) as libc::sighandler_t);
    }
    let result = match Cli::parse().command {
        Command::Analyze { scene, velocity, json } => with_scene(&scene, |s| analyze(s, velocity)).map(|value| {
            if json {
                println!("{}", serde_json::to_string_pretty(&value).expect("a JSON value always serialises"));
            } else {
                print!("{}", to_text(&value));
            }
        }),
        Command::Curve { scene, path, start, points } => {
            with_scene(&scene, |s| force_overlap_csv(s, start, &path, points as usize)).map(|csv| print!("{csv}"))
        }
        Command::Restitution { scene, velocities } => with_scene(&scene, |s| restitution_csv(s, &velocities)).map(|csv| print!("{csv}")),
        Command::Oblique { scene, speed, angles, angular_velocity, rolling_friction, rayleigh_fraction, lever, solver, tolerance } => {
            let lever = if lever == "radius" { oblique::Lever::Radius } else { oblique::Lever::MidOverlap };
            let solver = if solver == "adaptive" { oblique::ObliqueSolver::Adaptive(tolerance) } else { oblique::ObliqueSolver::Verlet };
            let options = oblique::ImpactOptions { angular_velocity, rolling_friction, lever, rayleigh_fraction, solver };
            with_scene(&scene, |s| oblique_csv(s, speed, &angles, &options)).map(|csv| print!("{csv}"))
        }
        Command::Bed { command } => bed_cli::run(command),
        Command::Completions { shell } => {
            clap_complete::generate(shell, &mut Cli::command(), "powderfmu", &mut std::io::stdout());
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("powderfmu: error: {e}");
            ExitCode::from(2)
        }
    }
}

/// The rows of `powderfmu oblique`.
fn oblique_csv(scene: &Scene, speed: f64, angles: &[f64], options: &oblique::ImpactOptions) -> Result<String, String> {
    use std::fmt::Write;
    let mut out = String::from(
        "incident_angle_deg,normal_velocity_in_m_per_s,tangential_velocity_in_m_per_s,angular_velocity_in_rad_per_s,normal_velocity_out_m_per_s,\
tangential_velocity_out_m_per_s,angular_velocity_out_rad_per_s,tangential_restitution,rebound_angle_deg,max_overlap_m,max_force_N,contact_time_s,\
slid_throughout,dissipated_energy_J,kinetic_energy_lost_J,sticks,mechanism\n",
    );
    for &angle in angles {
        let (v_n, v_t) = (speed * angle.to_radians().cos(), speed * angle.to_radians().sin());
        let o = match oblique::impact(scene, v_n, v_t, options) {
            Ok(o) => o,
            // Held by adhesion: the row says so, with where the sphere goes along the wall.
            Err(oblique::ObliqueError::Sticks(held)) => {
                let _ = writeln!(
                    out,
                    "{angle},{v_n:e},{v_t:e},{:e},NaN,{:e},{:e},NaN,NaN,NaN,NaN,NaN,,NaN,NaN,true,held {}",
                    options.angular_velocity,
                    held.tangential_velocity,
                    held.angular_velocity,
                    held.mechanism()
                );
                continue;
            }
            Err(e) => return Err(format!("at {angle} deg: {e}")),
        };
        let _ = writeln!(
            out,
            "{angle},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e},{:e},false,{} detachment",
            o.normal_velocity_in,
            o.tangential_velocity_in,
            o.angular_velocity_in,
            o.normal_velocity_out,
            o.tangential_velocity_out,
            o.angular_velocity_out,
            o.tangential_restitution(),
            o.rebound_angle().to_degrees(),
            o.max_overlap,
            o.max_force,
            o.contact_time,
            o.slid_throughout,
            o.dissipated_energy,
            o.kinetic_energy_lost,
            if o.sliding_at_separation { "sliding" } else { "sticking" }
        );
    }
    Ok(out)
}

/// Reads the scene at `path` and runs `work` on it; any error names the file.
fn with_scene<T, E: std::fmt::Display>(path: &Path, work: impl FnOnce(&Scene) -> Result<T, E>) -> Result<T, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read scene `{}`: {e}", path.display()))?;
    let scene = Scene::from_json(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    work(&scene).map_err(|e| format!("{}: {e}", path.display()))
}

/// The scene keys and the output keys of `analyze`, each with its unit: the long help of `analyze`.
fn keys_help() -> String {
    let mut s = String::from("SCENE KEYS\n\n");
    for k in KEYS.iter() {
        s += &format!("  {:<32} [{}] default {}, allowed {}\n      {}\n", k.name, k.unit, k.default_text(), k.allowed_text(), k.doc);
    }
    s += "\nOUTPUT KEYS (in the text, each value has its unit beside it; in --json the `units` object gives them)\n\n";
    for o in OUTPUTS {
        s += &format!("  {:<32} [{}] {} ({})\n", o.name, o.unit, o.doc, o.group.title("the scene's contact_model"));
    }
    s
}
