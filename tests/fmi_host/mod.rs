//! A host for the FMU's C ABI in Rust, shared by the importer and conformance tests: loads the cdylib of
//! the current sources with libloading, collects log messages per instance, and calls the exports.
#![allow(dead_code, non_snake_case)]

use libloading::{Library, Symbol};
use powderfmu::fmi2::types::*;
use powderfmu::units;
use std::ffi::{c_void, CStr, CString};
use std::sync::Mutex;

/// The cdylib of the current sources. `cargo test` compiles the library once with both its crate types,
/// so the cdylib sits next to this test binary (`target/<profile>/deps`; cargo does not copy it up a level
/// in a test run). Building it again with `cargo build --lib` cost about two minutes per clean test run:
/// without the dev-dependencies two crates get other features, and the library is compiled a second time.
/// That build stays as the fallback when the file is not there.
pub fn library() -> Library {
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
    // SAFETY: our own library; its initialisers have no preconditions.
    unsafe { Library::new(&path) }.unwrap_or_else(|e| panic!("cannot load {}: {e}", path.display()))
}

/// Collected log messages of one instance (the component environment points at one).
pub type Log = Mutex<Vec<(fmi2Status, String, String)>>;

/// Called by the FMU as a C variadic function. Stable Rust cannot define one; every message we log is
/// passed with its text already formatted and no variadic arguments, and on x86-64 System V a variadic call
/// without variadic arguments reaches a non-variadic function with the same fixed parameters intact.
pub unsafe extern "C" fn logger(env: fmi2ComponentEnvironment, _name: fmi2String, status: fmi2Status, category: fmi2String, message: fmi2String) {
    let log = &*(env as *const Log);
    let text = CStr::from_ptr(message).to_string_lossy().replace("%%", "%");
    log.lock().unwrap().push((status, CStr::from_ptr(category).to_string_lossy().into_owned(), text));
}

pub fn callbacks(log: &Log) -> fmi2CallbackFunctions {
    type Plain = unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String);
    // SAFETY: see `logger`.
    let variadic = unsafe {
        std::mem::transmute::<Plain, unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...)>(logger)
    };
    fmi2CallbackFunctions {
        logger: Some(variadic),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: log as *const Log as *mut c_void,
    }
}

pub mod fmi3;

pub struct Api<'a> {
    pub lib: &'a Library,
}

#[macro_export]
macro_rules! f {
    ($api:expr, $name:expr, $ty:ty) => {{
        // SAFETY: the symbol has this FMI 2.0 signature (checked against the headers by fmi2_headers.rs).
        let (lib, name): (&libloading::Library, &[u8]) = (&$api.lib, $name);
        #[allow(unused_unsafe)]
        let s: Symbol<$ty> = unsafe { lib.get(name) }.expect("an exported fmi2 function");
        s
    }};
}

pub type Comp = fmi2Component;
pub type Status0 = unsafe extern "C" fn(Comp) -> fmi2Status;
pub type SetReal = unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *const fmi2Real) -> fmi2Status;
pub type GetReal = unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *mut fmi2Real) -> fmi2Status;
pub type Instantiate =
    unsafe extern "C" fn(fmi2String, fmi2Type, fmi2String, fmi2String, *const fmi2CallbackFunctions, fmi2Boolean, fmi2Boolean) -> Comp;
pub type Setup = unsafe extern "C" fn(Comp, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real) -> fmi2Status;
pub type DoStep = unsafe extern "C" fn(Comp, fmi2Real, fmi2Real, fmi2Boolean) -> fmi2Status;
pub type Vector = unsafe extern "C" fn(Comp, *mut fmi2Real, usize) -> fmi2Status;
pub type SetVector = unsafe extern "C" fn(Comp, *const fmi2Real, usize) -> fmi2Status;

impl<'a> Api<'a> {
    pub fn instantiate(&self, unit: &str, kind: fmi2Type, log: &Log, resources: Option<&str>) -> Comp {
        let u = units::by_identifier(unit).unwrap();
        let name = CString::new("importer").unwrap();
        let guid = CString::new(u.guid()).unwrap();
        let res = CString::new(resources.map(str::to_owned).unwrap_or_else(resource_uri)).unwrap();
        let cb = callbacks(log);
        unsafe { f!(self, b"fmi2Instantiate", Instantiate)(name.as_ptr(), kind, guid.as_ptr(), res.as_ptr(), &cb, fmi2False, fmi2False) }
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
        unsafe { f!(self, b"fmi2FreeInstance", unsafe extern "C" fn(Comp))(c) }
    }
}

pub fn resource_uri() -> String {
    format!("file://{}/", std::env::temp_dir().display())
}
