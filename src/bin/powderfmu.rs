//! The `powderfmu` command-line tool: the physics of the FMUs without FMI. The command line is clap's
//! (derive): every subcommand has `--help`, errors name the option, `completions` writes shell completions.

use clap::{CommandFactory, Parser, Subcommand};
use powderfmu::analysis::{analyze, to_text, OUTPUTS};
use powderfmu::curves::{force_overlap_csv, restitution_csv};
use powderfmu::scene::{Scene, KEYS};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

mod bed_cli;
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
        Command::Curve { scene, path, start, points } => with_scene(&scene, |s| force_overlap_csv(s, start, &path, points as usize)).map(|csv| print!("{csv}")),
        Command::Restitution { scene, velocities } => with_scene(&scene, |s| restitution_csv(s, &velocities)).map(|csv| print!("{csv}")),
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
