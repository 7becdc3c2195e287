//! The test suite's side of the project's one Rust FMI host (`fmu_build/host`, the `fmi_host` crate, which
//! `fmu_check` uses too): finds the cdylib of the current sources and names the units' variables through
//! the crate's own tables. Loading, the loggers (messages collected per instance), the C types a host
//! declares and the typed calls are `fmi_host`'s.
#![allow(dead_code, non_snake_case)]

#[allow(unused_imports)]
pub use fmi_host::fmi2::{callbacks, Call0 as Status0, Callbacks, DoStep, GetReal, Instantiate, SetReal, SetVector, Setup, Vector};
pub use fmi_host::{Binary, Log};
use powderfmu::fmi2::types::*;
use powderfmu::units;

/// The cdylib of the current sources. `cargo test` compiles the library once with both its crate types,
/// so the cdylib sits next to this test binary (`target/<profile>/deps`; cargo does not copy it up a level
/// in a test run). Building it again with `cargo build --lib` cost about two minutes per clean test run:
/// without the dev-dependencies two crates get other features, and the library is compiled a second time.
/// That build stays as the fallback when the file is not there.
pub fn library() -> Binary {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    let mut path = deps.join("libpowderfmu.so");
    if !path.exists() {
        static BUILT: std::sync::OnceLock<()> = std::sync::OnceLock::new();
        BUILT.get_or_init(|| {
            let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
            let status = std::process::Command::new(cargo)
                .args(["build", "--quiet", "--lib", "-p", "powderfmu"])
                .current_dir(env!("CARGO_MANIFEST_DIR"))
                .status()
                .expect("cargo runs");
            assert!(status.success(), "cargo build --lib failed");
        });
        path = deps.parent().unwrap().join("libpowderfmu.so");
    }
    Binary::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

pub mod fmi3;

/// The library's FMI 2.0 exports, with the unit's variables named through the crate's own tables.
pub struct Api<'a> {
    pub lib: &'a Binary,
}

/// The export `$name` as the FMI 2.0 function type `$ty`.
#[macro_export]
macro_rules! f {
    ($api:expr, $name:expr, $ty:ty) => {{
        // SAFETY: the symbol has this FMI 2.0 signature (checked against the headers by fmi2_headers.rs).
        let (lib, name): (&fmi_host::Binary, &[u8]) = (&$api.lib, $name);
        #[allow(unused_unsafe)]
        let s: $ty = unsafe { lib.sym(name) }.expect("an exported fmi2 function");
        s
    }};
}

pub type Comp = fmi2Component;

impl<'a> Api<'a> {
    pub fn instantiate(&self, unit: &str, kind: fmi2Type, log: &Log, resources: Option<&str>) -> Comp {
        let guid = units::by_identifier(unit).unwrap().guid();
        let res = resources.map(str::to_owned).unwrap_or_else(resource_uri);
        fmi_host::fmi2::instantiate(self.lib, "importer", kind, &guid, &res, log).expect("fmi2Instantiate exported")
    }

    pub fn set(&self, c: Comp, unit: &str, name: &str, value: f64) -> fmi2Status {
        let vr = units::by_identifier(unit).unwrap().vr(name).expect("a variable of the unit") as fmi2ValueReference;
        unsafe { f!(self, b"fmi2SetReal", SetReal)(c, &vr, 1, &value) }
    }

    pub fn get(&self, c: Comp, unit: &str, name: &str) -> f64 {
        let vr = units::by_identifier(unit).unwrap().vr(name).expect("a variable of the unit") as fmi2ValueReference;
        let mut v = f64::NAN;
        let s = unsafe { f!(self, b"fmi2GetReal", GetReal)(c, &vr, 1, &mut v) };
        assert_eq!(s, fmi2OK, "fmi2GetReal({name})");
        v
    }

    pub fn call0(&self, name: &[u8], c: Comp) -> fmi2Status {
        unsafe { f!(self, name, Status0)(c) }
    }

    pub fn free(&self, c: Comp) {
        unsafe { f!(self, b"fmi2FreeInstance", fmi_host::fmi2::Free)(c) }
    }
}

pub fn resource_uri() -> String {
    format!("file://{}/", std::env::temp_dir().display())
}
