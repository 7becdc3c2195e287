//! The FMI 2.0 C interface as a host sees it: the unzipped FMU, its loaded binary, and typed calls that
//! turn a status other than fmi2OK into an error naming the function and the last logged message.

use crate::model_description::ModelDescription;
use libloading::Library;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

#[cfg(windows)]
pub const PLATFORM: &str = "win64";
#[cfg(not(windows))]
pub const PLATFORM: &str = "linux64";
/// FMI 3.0's name of the same platform (FMI 3.0 Sec. 2.5.1.1).
#[cfg(windows)]
pub const PLATFORM_FMI3: &str = "x86_64-windows";
#[cfg(not(windows))]
pub const PLATFORM_FMI3: &str = "x86_64-linux";
#[cfg(windows)]
const EXTENSION: &str = "dll";
#[cfg(not(windows))]
const EXTENSION: &str = "so";

pub type Component = *mut c_void;
pub type Status = c_int;
pub const OK: Status = 0;
pub const MODEL_EXCHANGE: c_int = 0;
pub const CO_SIMULATION: c_int = 1;

#[repr(C)]
pub struct Callbacks {
    logger: unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char, ...),
    allocate: *const c_void,
    free: *const c_void,
    step_finished: *const c_void,
    environment: *mut c_void,
}

#[repr(C)]
#[derive(Default)]
pub struct EventInfo {
    pub new_discrete_states_needed: c_int,
    pub terminate_simulation: c_int,
    pub nominals_changed: c_int,
    pub values_changed: c_int,
    pub next_event_time_defined: c_int,
    pub next_event_time: f64,
}

/// The last message the FMU logged (one instance at a time in this program).
pub(crate) static LAST_MESSAGE: Mutex<String> = Mutex::new(String::new());

/// The logger the FMU calls. Stable Rust cannot define a C variadic function; the FMU passes its text
/// already formatted and no variadic arguments, and on x86-64 (System V and Windows alike) such a call
/// reaches a non-variadic function with the same fixed parameters intact.
unsafe extern "C" fn logger(_: *mut c_void, _: *const c_char, status: Status, category: *const c_char, message: *const c_char) {
    // SAFETY: the FMU passes NUL-terminated strings (FMI 2.0 Sec. 2.1.5).
    let (category, message) = unsafe { (CStr::from_ptr(category).to_string_lossy(), CStr::from_ptr(message).to_string_lossy()) };
    let text = format!("[{category}, status {status}] {}", message.replace("%%", "%"));
    if status > OK {
        eprintln!("fmu: {text}");
    }
    *LAST_MESSAGE.lock().unwrap_or_else(|e| e.into_inner()) = text;
}

pub struct Unpacked {
    pub dir: PathBuf,
    pub binary: PathBuf,
    pub model_description: ModelDescription,
    pub library: Library,
}

impl Unpacked {
    /// Unzips `fmu` into a fresh temporary folder and loads the binary of this platform.
    pub fn open(fmu: &Path) -> Result<Unpacked, String> {
        let file = std::fs::File::open(fmu).map_err(|e| format!("cannot open {}: {e}", fmu.display()))?;
        let mut archive = zip::ZipArchive::new(file).map_err(|e| format!("{} is not a zip archive: {e}", fmu.display()))?;
        let stem = fmu.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let dir = std::env::temp_dir().join(format!("fmu_check-{stem}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        archive.extract(&dir).map_err(|e| format!("cannot unzip {}: {e}", fmu.display()))?;
        let xml = std::fs::read_to_string(dir.join("modelDescription.xml")).map_err(|e| format!("modelDescription.xml: {e}"))?;
        let model_description = ModelDescription::parse(&xml)?;
        let platform = if model_description.fmi3 { PLATFORM_FMI3 } else { PLATFORM };
        let binary = dir.join("binaries").join(platform).join(format!("{}.{EXTENSION}", model_description.model_identifier));
        // SAFETY: the FMU's binary; loading runs its initialisers, which a host must trust.
        let library = unsafe { Library::new(&binary) }.map_err(|e| format!("cannot load {}: {e}", binary.display()))?;
        Ok(Unpacked { dir, binary, model_description, library })
    }

    /// The `fmuResourceLocation` URI of the unzipped resources folder (`file:///C:/...` on Windows).
    pub fn resource_uri(&self) -> String {
        let path = self.dir.join("resources");
        let text = path.to_string_lossy().replace('\\', "/");
        let text = text.strip_prefix("//?/").unwrap_or(&text).to_string();
        let escaped: String = text.chars().map(|c| if c == ' ' { "%20".to_string() } else { c.to_string() }).collect();
        if escaped.starts_with('/') {
            format!("file://{escaped}/")
        } else {
            format!("file:///{escaped}/")
        }
    }

    pub(crate) fn symbol<T: Copy>(&self, name: &str) -> Result<T, String> {
        // SAFETY: each caller names an FMI function with the signature T of the standard's header.
        unsafe { self.library.get::<T>(name.as_bytes()).map(|s| *s).map_err(|e| format!("{name} not exported: {e}")) }
    }
}

impl Drop for Unpacked {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// One instance and the calls the runs make.
pub struct Instance<'a> {
    pub fmu: &'a Unpacked,
    pub c: Component,
}

pub(crate) fn check(function: &str, status: Status) -> Result<(), String> {
    if status == OK {
        Ok(())
    } else {
        Err(format!("{function} returned status {status}: {}", LAST_MESSAGE.lock().unwrap_or_else(|e| e.into_inner())))
    }
}

type Instantiate = unsafe extern "C" fn(*const c_char, c_int, *const c_char, *const c_char, *const Callbacks, c_int, c_int) -> Component;
type Call0 = unsafe extern "C" fn(Component) -> Status;
type Reals = unsafe extern "C" fn(Component, *const u32, usize, *mut f64) -> Status;
type Ints = unsafe extern "C" fn(Component, *const u32, usize, *mut c_int) -> Status;
type Strings = unsafe extern "C" fn(Component, *const u32, usize, *const *const c_char) -> Status;

impl<'a> Instance<'a> {
    pub fn new(fmu: &'a Unpacked, kind: c_int) -> Result<Instance<'a>, String> {
        let md = &fmu.model_description;
        let callbacks = Box::leak(Box::new(Callbacks {
            // SAFETY: see `logger`.
            logger: unsafe {
                std::mem::transmute::<
                    unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char),
                    unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char, ...),
                >(logger)
            },
            allocate: std::ptr::null(),
            free: std::ptr::null(),
            step_finished: std::ptr::null(),
            environment: std::ptr::null_mut(),
        }));
        let name = CString::new("fmu_check").expect("no NUL");
        let guid = CString::new(md.guid.clone()).map_err(|e| e.to_string())?;
        let uri = CString::new(fmu.resource_uri()).map_err(|e| e.to_string())?;
        let instantiate: Instantiate = fmu.symbol("fmi2Instantiate")?;
        // SAFETY: valid NUL-terminated strings and callbacks that outlive the instance (leaked).
        let c = unsafe { instantiate(name.as_ptr(), kind, guid.as_ptr(), uri.as_ptr(), callbacks, 0, 0) };
        if c.is_null() {
            return Err(format!("fmi2Instantiate failed: {}", LAST_MESSAGE.lock().unwrap_or_else(|e| e.into_inner())));
        }
        Ok(Instance { fmu, c })
    }

    pub fn call(&self, function: &str) -> Result<(), String> {
        let f: Call0 = self.fmu.symbol(function)?;
        // SAFETY: a live instance.
        check(function, unsafe { f(self.c) })
    }

    pub fn setup(&self, start: f64) -> Result<(), String> {
        let f: unsafe extern "C" fn(Component, c_int, f64, f64, c_int, f64) -> Status = self.fmu.symbol("fmi2SetupExperiment")?;
        // SAFETY: a live instance.
        check("fmi2SetupExperiment", unsafe { f(self.c, 0, 0.0, start, 0, 0.0) })
    }

    pub fn set_real(&self, name: &str, value: f64) -> Result<(), String> {
        let vr = self.fmu.model_description.vr(name)?;
        let f: Reals = self.fmu.symbol("fmi2SetReal")?;
        // SAFETY: one value reference, one value.
        check(&format!("fmi2SetReal({name})"), unsafe { f(self.c, &vr, 1, &value as *const f64 as *mut f64) })
    }

    pub fn set_string(&self, name: &str, value: &str) -> Result<(), String> {
        let vr = self.fmu.model_description.vr(name)?;
        let text = CString::new(value).map_err(|e| e.to_string())?;
        let f: Strings = self.fmu.symbol("fmi2SetString")?;
        // SAFETY: one value reference, one string.
        check(&format!("fmi2SetString({name})"), unsafe { f(self.c, &vr, 1, &text.as_ptr()) })
    }

    pub fn real(&self, name: &str) -> Result<f64, String> {
        let vr = self.fmu.model_description.vr(name)?;
        let mut v = f64::NAN;
        let f: Reals = self.fmu.symbol("fmi2GetReal")?;
        // SAFETY: one value reference, room for one value.
        check(&format!("fmi2GetReal({name})"), unsafe { f(self.c, &vr, 1, &mut v) })?;
        Ok(v)
    }

    pub fn integer(&self, name: &str) -> Result<i32, String> {
        let vr = self.fmu.model_description.vr(name)?;
        let mut v: c_int = 0;
        let f: Ints = self.fmu.symbol("fmi2GetInteger")?;
        // SAFETY: one value reference, room for one value.
        check(&format!("fmi2GetInteger({name})"), unsafe { f(self.c, &vr, 1, &mut v) })?;
        Ok(v)
    }

    pub fn set_input_derivative(&self, name: &str, order: c_int, value: f64) -> Result<(), String> {
        let vr = self.fmu.model_description.vr(name)?;
        let f: unsafe extern "C" fn(Component, *const u32, usize, *const c_int, *const f64) -> Status = self.fmu.symbol("fmi2SetRealInputDerivatives")?;
        // SAFETY: one value reference, one order, one value.
        check(&format!("fmi2SetRealInputDerivatives({name})"), unsafe { f(self.c, &vr, 1, &order, &value) })
    }

    pub fn do_step(&self, t: f64, h: f64) -> Result<(), String> {
        let f: unsafe extern "C" fn(Component, f64, f64, c_int) -> Status = self.fmu.symbol("fmi2DoStep")?;
        // SAFETY: a live instance.
        check("fmi2DoStep", unsafe { f(self.c, t, h, 1) })
    }

    /// The state serialized to bytes (fmi2GetFMUstate, fmi2SerializeFMUstate).
    pub fn serialize_state(&self) -> Result<Vec<u8>, String> {
        let get: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.fmu.symbol("fmi2GetFMUstate")?;
        let size: unsafe extern "C" fn(Component, *mut c_void, *mut usize) -> Status = self.fmu.symbol("fmi2SerializedFMUstateSize")?;
        let ser: unsafe extern "C" fn(Component, *mut c_void, *mut c_char, usize) -> Status = self.fmu.symbol("fmi2SerializeFMUstate")?;
        let free: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.fmu.symbol("fmi2FreeFMUstate")?;
        let mut state = std::ptr::null_mut();
        let mut n = 0usize;
        // SAFETY: the standard's calling sequence with buffers of the size the FMU gives.
        unsafe {
            check("fmi2GetFMUstate", get(self.c, &mut state))?;
            check("fmi2SerializedFMUstateSize", size(self.c, state, &mut n))?;
            let mut bytes = vec![0u8; n];
            check("fmi2SerializeFMUstate", ser(self.c, state, bytes.as_mut_ptr() as *mut c_char, n))?;
            check("fmi2FreeFMUstate", free(self.c, &mut state))?;
            Ok(bytes)
        }
    }

    /// Sets the state from bytes (fmi2DeSerializeFMUstate, fmi2SetFMUstate).
    pub fn restore_state(&self, bytes: &[u8]) -> Result<(), String> {
        let de: unsafe extern "C" fn(Component, *const c_char, usize, *mut *mut c_void) -> Status = self.fmu.symbol("fmi2DeSerializeFMUstate")?;
        let set: unsafe extern "C" fn(Component, *mut c_void) -> Status = self.fmu.symbol("fmi2SetFMUstate")?;
        let free: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.fmu.symbol("fmi2FreeFMUstate")?;
        let mut state = std::ptr::null_mut();
        // SAFETY: bytes of the given length; the state is freed after use.
        unsafe {
            check("fmi2DeSerializeFMUstate", de(self.c, bytes.as_ptr() as *const c_char, bytes.len(), &mut state))?;
            check("fmi2SetFMUstate", set(self.c, state))?;
            check("fmi2FreeFMUstate", free(self.c, &mut state))
        }
    }

    // Model Exchange.
    pub fn new_discrete_states(&self) -> Result<EventInfo, String> {
        let f: unsafe extern "C" fn(Component, *mut EventInfo) -> Status = self.fmu.symbol("fmi2NewDiscreteStates")?;
        let mut info = EventInfo::default();
        // SAFETY: a live instance and an EventInfo of the standard's layout.
        check("fmi2NewDiscreteStates", unsafe { f(self.c, &mut info) })?;
        Ok(info)
    }

    pub fn set_time(&self, t: f64) -> Result<(), String> {
        let f: unsafe extern "C" fn(Component, f64) -> Status = self.fmu.symbol("fmi2SetTime")?;
        // SAFETY: a live instance.
        check("fmi2SetTime", unsafe { f(self.c, t) })
    }

    pub fn vector(&self, function: &str, out: &mut [f64]) -> Result<(), String> {
        let f: unsafe extern "C" fn(Component, *mut f64, usize) -> Status = self.fmu.symbol(function)?;
        // SAFETY: a buffer of the length passed.
        check(function, unsafe { f(self.c, out.as_mut_ptr(), out.len()) })
    }

    pub fn set_states(&self, x: &[f64]) -> Result<(), String> {
        let f: unsafe extern "C" fn(Component, *const f64, usize) -> Status = self.fmu.symbol("fmi2SetContinuousStates")?;
        // SAFETY: a buffer of the length passed.
        check("fmi2SetContinuousStates", unsafe { f(self.c, x.as_ptr(), x.len()) })
    }

    /// fmi2CompletedIntegratorStep: whether the FMU asks for an event now.
    pub fn completed_step(&self) -> Result<bool, String> {
        let f: unsafe extern "C" fn(Component, c_int, *mut c_int, *mut c_int) -> Status = self.fmu.symbol("fmi2CompletedIntegratorStep")?;
        let (mut enter, mut terminate) = (0, 0);
        // SAFETY: two out-parameters.
        check("fmi2CompletedIntegratorStep", unsafe { f(self.c, 1, &mut enter, &mut terminate) })?;
        Ok(enter != 0)
    }
}

impl Drop for Instance<'_> {
    fn drop(&mut self) {
        if let Ok(f) = self.fmu.symbol::<unsafe extern "C" fn(Component)>("fmi2FreeInstance") {
            // SAFETY: the instance is freed once, here.
            unsafe { f(self.c) }
        }
    }
}
