//! The `powderfmu` command-line tool: the physics of the FMUs without FMI.

use powderfmu::analysis::{analyze, OUTPUTS};
use powderfmu::curves::{force_overlap_csv, restitution_csv};
use powderfmu::scene::{Scene, KEYS};
use std::process::ExitCode;

mod bed_cli;

const USAGE: &str = "usage:
  powderfmu analyze SCENE.json [--velocity V]          derived parameters and closed-form results (JSON)
  powderfmu curve SCENE.json --path A1,A2,.. [--points N]  force along a quasi-static overlap path (CSV)
  powderfmu restitution SCENE.json --velocities V1,V2,..   undamped impacts on the wall (CSV)
  powderfmu analyze --help                              every scene key with its unit and default
";

fn main() -> ExitCode {
    // A closed pipe (`powderfmu bed info BED | head`) ends the tool quietly, as it ends other Unix
    // tools, instead of a panic on the next print. Rust sets SIGPIPE to "ignore" before main.
    #[cfg(unix)]
    // SAFETY: called once at the start of main, before any other thread exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("analyze") => run_analyze(&args[1..]),
        Some("curve") => run_csv(&args[1..], "--path", force_overlap_csv),
        Some("bed") => match bed_cli::run(&args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(&e),
        },
        Some("restitution") => run_csv(&args[1..], "--velocities", |scene, list, _| restitution_csv(scene, list)),
        Some("--help") | Some("-h") | Some("help") => {
            println!("powderfmu: contact mechanics of elasto-plastic adhesive spheres\n\n{USAGE}{}", bed_cli::USAGE);
            ExitCode::SUCCESS
        }
        Some("--version") => {
            println!("powderfmu {}", env!("CARGO_PKG_VERSION"));
            ExitCode::SUCCESS
        }
        Some(other) => fail(&format!("unknown subcommand `{other}`\n{USAGE}")),
        None => fail(&format!("{USAGE}{}", bed_cli::USAGE)),
    }
}

fn run_analyze(args: &[String]) -> ExitCode {
    if args.iter().any(|a| a == "--help" || a == "-h") {
        print_analyze_help();
        return ExitCode::SUCCESS;
    }
    let mut path = None;
    let mut velocity = None;
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--velocity" => {
                let Some(text) = args.get(i + 1) else { return fail("--velocity needs a value in m/s") };
                match text.parse::<f64>() {
                    Ok(v) if v.is_finite() && v > 0.0 => velocity = Some(v),
                    _ => return fail(&format!("--velocity = `{text}` is not allowed: give a positive speed in m/s")),
                }
                i += 2;
            }
            a if a.starts_with('-') => return fail(&format!("unknown option `{a}`\n{USAGE}")),
            a => {
                if path.replace(a.to_string()).is_some() {
                    return fail(&format!("give one scene file\n{USAGE}"));
                }
                i += 1;
            }
        }
    }
    let Some(path) = path else { return fail(USAGE) };
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => return fail(&format!("cannot read scene `{path}`: {e}")),
    };
    let result = Scene::from_json(&text).and_then(|scene| analyze(&scene, velocity));
    match result {
        Ok(value) => {
            println!("{}", serde_json::to_string_pretty(&value).expect("a JSON value always serialises"));
            ExitCode::SUCCESS
        }
        Err(e) => fail(&format!("{path}: {e}")),
    }
}

/// `curve` and `restitution`: a scene, one list option of numbers, and `--points N`.
fn run_csv(args: &[String], list_flag: &str, make: impl Fn(&Scene, &[f64], usize) -> Result<String, powderfmu::ParamError>) -> ExitCode {
    let mut path = None;
    let mut list = None;
    let mut points = 200usize;
    let mut i = 0;
    while i < args.len() {
        let a = args[i].as_str();
        if a == list_flag || a == "--points" {
            let Some(text) = args.get(i + 1) else { return fail(&format!("{a} needs a value")) };
            if a == "--points" {
                match text.parse::<usize>() {
                    Ok(n) if (2..=1_000_000).contains(&n) => points = n,
                    _ => return fail(&format!("--points = `{text}` is not allowed: give a whole number in [2, 1000000]")),
                }
            } else {
                let parsed: Result<Vec<f64>, _> = text.split(',').map(|x| x.trim().parse::<f64>()).collect();
                match parsed {
                    Ok(v) => list = Some(v),
                    Err(_) => return fail(&format!("{list_flag} = `{text}` is not a comma-separated list of numbers")),
                }
            }
            i += 2;
        } else if a.starts_with('-') {
            return fail(&format!("unknown option `{a}`\n{USAGE}"));
        } else {
            if path.replace(a.to_string()).is_some() {
                return fail(&format!("give one scene file\n{USAGE}"));
            }
            i += 1;
        }
    }
    let (Some(path), Some(list)) = (path, list) else { return fail(USAGE) };
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => return fail(&format!("cannot read scene `{path}`: {e}")),
    };
    match Scene::from_json(&text).and_then(|scene| make(&scene, &list, points)) {
        Ok(csv) => {
            print!("{csv}");
            ExitCode::SUCCESS
        }
        Err(e) => fail(&format!("{path}: {e}")),
    }
}

fn print_analyze_help() {
    println!("powderfmu analyze SCENE.json [--velocity V]\n");
    println!("Reads a scene (a JSON object of the keys below, SI units) and prints, as JSON, the derived");
    println!("parameters and the closed-form results. With --velocity V [m/s] it adds one undamped impact of");
    println!("the active law on the wall by energy balance.\n\nSCENE KEYS\n");
    for k in KEYS.iter() {
        println!("  {:<32} [{}] default {}, allowed {}\n      {}", k.name, k.unit, k.default_text(), k.allowed_text(), k.doc);
    }
    println!("\nOUTPUT KEYS (the `units` object of the output repeats the unit of each)\n");
    for o in OUTPUTS {
        println!("  {:<32} [{}] {}", o.name, o.unit, o.doc);
    }
}

fn fail(message: &str) -> ExitCode {
    eprintln!("powderfmu: error: {message}");
    ExitCode::from(2)
}
