//! `fmu_check`: a small FMI 2.0 importer, independent of the powderfmu crate, that does what a host on
//! another platform does with a `.fmu`: unzip it, read `modelDescription.xml`, load the binary of its
//! platform (`binaries/win64/*.dll` when built for Windows and run under wine, `linux64/*.so` on Linux),
//! and run the unit in Co-Simulation and, where offered, Model Exchange. It prints one line per run with
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
    println!("{} {} ({})", md.model_identifier, fmi::PLATFORM, unpacked.binary.display());
    runs::co_simulation(&unpacked, state_out.as_deref(), state_in.as_deref())?;
    if md.model_exchange && state_in.is_none() {
        runs::model_exchange(&unpacked)?;
    }
    Ok(())
}
