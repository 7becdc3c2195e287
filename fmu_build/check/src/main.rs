//! `fmu_check`: a small FMI 2.0 and 3.0 importer, independent of the powderfmu crate (its calls are
//! `fmi_host`'s, the project's one Rust FMI host), that does what a
//! host on another platform does with a `.fmu`: unzip it, read `modelDescription.xml`, load the binary of
//! its platform (`binaries/win64/*.dll` or `x86_64-windows` when built for Windows and run under wine,
//! `linux64/*.so` or `x86_64-linux` on Linux), and run the unit in Co-Simulation and, where offered (FMI
//! 2.0), Model Exchange; an FMI 3.0 FMU in Co-Simulation with early return. It prints one line per run with
//! the final outputs in full precision, so that two platforms' lines can be compared.
//!
//! Usage: fmu_check UNIT.fmu [--state-out FILE] [--state-in FILE]
//!   --state-out FILE  in the CS run, serialize the state halfway to FILE and go on
//!   --state-in FILE   in the CS run, start from the state in FILE (written by --state-out, on any
//!                     platform) at halfway, and go on to the end

mod fmi;
mod model_description;
mod runs;

use std::path::PathBuf;
use std::process::ExitCode;

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fmu_check: error: {e}");
            ExitCode::from(1)
        }
    }
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let mut fmu = None;
    let (mut state_out, mut state_in) = (None, None);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--state-out" => state_out = Some(PathBuf::from(args.next().ok_or("--state-out needs a file")?)),
            "--state-in" => state_in = Some(PathBuf::from(args.next().ok_or("--state-in needs a file")?)),
            "-h" | "--help" => {
                println!("usage: fmu_check UNIT.fmu [--state-out FILE] [--state-in FILE]");
                return Ok(());
            }
            other if other.starts_with('-') => return Err(format!("unknown option `{other}`")),
            other => fmu = Some(PathBuf::from(other)),
        }
    }
    let fmu = fmu.ok_or("give the .fmu file")?;
    let unpacked = fmi::Unpacked::open(&fmu)?;
    let md = &unpacked.model_description;
    let platform = if md.fmi3 { fmi::PLATFORM_FMI3 } else { fmi::PLATFORM };
    println!("{} {} ({})", md.model_identifier, platform, unpacked.binary.path().display());
    if md.fmi3 {
        return runs::co_simulation_fmi3(&unpacked, state_out.as_deref(), state_in.as_deref());
    }
    runs::co_simulation(&unpacked, state_out.as_deref(), state_in.as_deref())?;
    if md.model_exchange && state_in.is_none() {
        runs::model_exchange(&unpacked)?;
    }
    Ok(())
}
