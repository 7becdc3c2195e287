//! `fmu_build`: packages the powderfmu cdylib, each unit's modelDescription.xml, resources and
//! documentation into `target/fmu/<Unit>.fmu`. The FMI units themselves are not part of the crate yet
//! (see README.md); what is here is the reproducible archive writer the packaging will use.

use std::process::ExitCode;

fn main() -> ExitCode {
    eprintln!("fmu_build: the crate defines no FMI unit yet, so there is nothing to package.");
    eprintln!("fmu_build: the reproducible archive writer (fmu_build/src/archive.rs) is ready and tested.");
    ExitCode::from(2)
}
