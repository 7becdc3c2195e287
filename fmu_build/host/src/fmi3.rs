//! FMI 3.0 as a host sees it (fmi3FunctionTypes.h): the logger (not variadic), the instantiation and
//! call types, and an owning [`Instance`] for checked calls by variable name. fmi3Boolean is C's one-byte
//! `bool`.

use crate::{check, environment, last_message, Binary, Component, Log, Names, Status};
use std::ffi::{c_char, c_void, CStr, CString};

/// fmi3LogMessageCallback: (environment, status, category, message).
pub type Logger = unsafe extern "C" fn(*mut c_void, Status, *const c_char, *const c_char);

/// The logger this crate gives the FMU: appends (status, category, message) to the [`Log`] the instance
/// environment points at (a null environment: the message goes to standard error).
///
/// # Safety
/// `env` is null or points at a live `Log`; the strings are NUL-terminated (FMI 3.0 Sec. 2.3.1).
pub unsafe extern "C" fn logger(env: *mut c_void, status: Status, category: *const c_char, message: *const c_char) {
    // SAFETY: the caller's contract.
    let (category, text) =
        unsafe { (CStr::from_ptr(category).to_string_lossy().into_owned(), CStr::from_ptr(message).to_string_lossy().into_owned()) };
    if env.is_null() {
        eprintln!("fmu: [{category}, status {status}] {text}");
        return;
    }
    // SAFETY: the caller's contract.
    let log = unsafe { &*(env as *const Log) };
    log.lock().unwrap_or_else(|e| e.into_inner()).push((status, category, text));
}

/// fmi3IntermediateUpdateCallback: (environment, intermediateUpdateTime, intermediateVariableSetRequested,
/// intermediateVariableGetAllowed, intermediateStepFinished, canReturnEarly, earlyReturnRequested,
/// earlyReturnTime).
pub type IntermediateUpdate = unsafe extern "C" fn(*mut c_void, f64, bool, bool, bool, bool, *mut bool, *mut f64);

/// fmi3InstantiateCoSimulation.
pub type InstantiateCs = unsafe extern "C" fn(
    *const c_char,
    *const c_char,
    *const c_char,
    bool,
    bool,
    bool,
    bool,
    *const u32,
    usize,
    *mut c_void,
    Option<Logger>,
    Option<IntermediateUpdate>,
) -> Component;
/// fmi3InstantiateModelExchange.
pub type InstantiateMe = unsafe extern "C" fn(*const c_char, *const c_char, *const c_char, bool, bool, *mut c_void, Option<Logger>) -> Component;
/// A call on the instance alone (fmi3ExitInitializationMode, fmi3Terminate, fmi3Reset, ...).
pub type Call0 = unsafe extern "C" fn(Component) -> Status;
/// fmi3EnterInitializationMode.
pub type EnterInit = unsafe extern "C" fn(Component, bool, f64, f64, bool, f64) -> Status;
/// fmi3GetFloat64.
pub type GetF64 = unsafe extern "C" fn(Component, *const u32, usize, *mut f64, usize) -> Status;
/// fmi3SetFloat64.
pub type SetF64 = unsafe extern "C" fn(Component, *const u32, usize, *const f64, usize) -> Status;
/// fmi3GetInt32.
pub type GetI32 = unsafe extern "C" fn(Component, *const u32, usize, *mut i32, usize) -> Status;
/// fmi3SetString.
pub type SetString = unsafe extern "C" fn(Component, *const u32, usize, *const *const c_char, usize) -> Status;
/// fmi3DoStep: (instance, current time, step, noSetFMUStatePriorToCurrentPoint, eventHandlingNeeded,
/// terminateSimulation, earlyReturn, lastSuccessfulTime).
pub type DoStep = unsafe extern "C" fn(Component, f64, f64, bool, *mut bool, *mut bool, *mut bool, *mut f64) -> Status;
/// fmi3FreeInstance.
pub type Free = unsafe extern "C" fn(Component);

/// How an instance is made: Model Exchange, or Co-Simulation with the two options the hosts vary.
#[derive(Debug, Clone, Copy)]
pub enum Kind {
    /// fmi3InstantiateModelExchange.
    ModelExchange,
    /// fmi3InstantiateCoSimulation (no intermediate variables, no intermediate-update callback).
    CoSimulation {
        /// eventModeUsed.
        event_mode: bool,
        /// earlyReturnAllowed.
        early_return: bool,
    },
}

/// Instantiates with this crate's logger writing to `log`; `resources`: the resources folder with a
/// trailing separator, or `None` for a null pointer. Null when the FMU refuses.
pub fn instantiate(binary: &Binary, name: &str, token: &str, resources: Option<&str>, kind: Kind, log: &Log) -> Result<Component, String> {
    let (name, token) = (cstring(name)?, cstring(token)?);
    let resources = resources.map(cstring).transpose()?;
    let resources_ptr = resources.as_ref().map_or(std::ptr::null(), |r| r.as_ptr());
    let env = environment(log);
    // SAFETY: the standard's signatures; NUL-terminated strings; the logger and log outlive the call.
    unsafe {
        match kind {
            Kind::ModelExchange => {
                let f: InstantiateMe = binary.sym(b"fmi3InstantiateModelExchange")?;
                Ok(f(name.as_ptr(), token.as_ptr(), resources_ptr, false, false, env, Some(logger)))
            }
            Kind::CoSimulation { event_mode, early_return } => {
                let f: InstantiateCs = binary.sym(b"fmi3InstantiateCoSimulation")?;
                Ok(f(
                    name.as_ptr(),
                    token.as_ptr(),
                    resources_ptr,
                    false,
                    false,
                    event_mode,
                    early_return,
                    std::ptr::null(),
                    0,
                    env,
                    Some(logger),
                    None,
                ))
            }
        }
    }
}

fn cstring(text: &str) -> Result<CString, String> {
    CString::new(text).map_err(|_| format!("{text:?} contains a NUL byte"))
}

/// An instance the host owns: freed on drop, each call checked (an error names the function and the
/// instance's last message), variables named through the host's `names`.
pub struct Instance<'a> {
    binary: &'a Binary,
    names: Names<'a>,
    log: Box<Log>,
    /// The instance handle.
    pub c: Component,
}

impl<'a> Instance<'a> {
    /// Instantiates (see [`instantiate`]).
    pub fn new(binary: &'a Binary, kind: Kind, token: &str, resources: Option<&str>, names: Names<'a>) -> Result<Instance<'a>, String> {
        let log = Box::new(Log::default());
        let c = instantiate(binary, "fmi_host", token, resources, kind, &log)?;
        if c.is_null() {
            return Err(format!("fmi3Instantiate failed: {}", last_message(&log)));
        }
        Ok(Instance { binary, names, log, c })
    }

    /// The messages logged so far.
    pub fn log(&self) -> &Log {
        &self.log
    }

    fn sym<T: Copy>(&self, name: &str) -> Result<T, String> {
        // SAFETY: each caller below names an FMI 3.0 function with its header's signature.
        unsafe { self.binary.sym(name.as_bytes()) }
    }

    fn check(&self, function: &str, status: Status) -> Result<(), String> {
        check(function, status, &self.log)
    }

    /// A call on the instance alone, by function name.
    pub fn call(&self, function: &str) -> Result<(), String> {
        let f: Call0 = self.sym(function)?;
        // SAFETY: a live instance.
        self.check(function, unsafe { f(self.c) })
    }

    /// fmi3EnterInitializationMode without tolerance or stop time.
    pub fn enter_initialization(&self, start: f64) -> Result<(), String> {
        let f: EnterInit = self.sym("fmi3EnterInitializationMode")?;
        // SAFETY: a live instance.
        self.check("fmi3EnterInitializationMode", unsafe { f(self.c, false, 0.0, start, false, 0.0) })
    }

    /// fmi3SetFloat64 of one variable.
    pub fn set_real(&self, name: &str, value: f64) -> Result<(), String> {
        let vr = (self.names)(name)?;
        let f: SetF64 = self.sym("fmi3SetFloat64")?;
        // SAFETY: one value reference, one value.
        self.check(&format!("fmi3SetFloat64({name})"), unsafe { f(self.c, &vr, 1, &value, 1) })
    }

    /// fmi3SetString of one variable.
    pub fn set_string(&self, name: &str, value: &str) -> Result<(), String> {
        let vr = (self.names)(name)?;
        let text = cstring(value)?;
        let f: SetString = self.sym("fmi3SetString")?;
        // SAFETY: one value reference, one string.
        self.check(&format!("fmi3SetString({name})"), unsafe { f(self.c, &vr, 1, &text.as_ptr(), 1) })
    }

    /// fmi3GetFloat64 of one variable.
    pub fn real(&self, name: &str) -> Result<f64, String> {
        let vr = (self.names)(name)?;
        let mut v = f64::NAN;
        let f: GetF64 = self.sym("fmi3GetFloat64")?;
        // SAFETY: one value reference, room for one value.
        self.check(&format!("fmi3GetFloat64({name})"), unsafe { f(self.c, &vr, 1, &mut v, 1) })?;
        Ok(v)
    }

    /// fmi3GetInt32 of one variable.
    pub fn integer(&self, name: &str) -> Result<i32, String> {
        let vr = (self.names)(name)?;
        let mut v = 0i32;
        let f: GetI32 = self.sym("fmi3GetInt32")?;
        // SAFETY: one value reference, room for one value.
        self.check(&format!("fmi3GetInt32({name})"), unsafe { f(self.c, &vr, 1, &mut v, 1) })?;
        Ok(v)
    }

    /// fmi3DoStep from `t` by `h`: (eventHandlingNeeded, earlyReturn, lastSuccessfulTime).
    pub fn do_step(&self, t: f64, h: f64) -> Result<(bool, bool, f64), String> {
        let f: DoStep = self.sym("fmi3DoStep")?;
        let (mut event, mut terminate, mut early, mut last) = (false, false, false, f64::NAN);
        // SAFETY: four out-parameters.
        self.check("fmi3DoStep", unsafe { f(self.c, t, h, true, &mut event, &mut terminate, &mut early, &mut last) })?;
        Ok((event, early, last))
    }

    /// The state serialized to bytes (fmi3GetFMUState, fmi3SerializedFMUStateSize, fmi3SerializeFMUState,
    /// fmi3FreeFMUState).
    pub fn serialize_state(&self) -> Result<Vec<u8>, String> {
        let get: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.sym("fmi3GetFMUState")?;
        let size: unsafe extern "C" fn(Component, *mut c_void, *mut usize) -> Status = self.sym("fmi3SerializedFMUStateSize")?;
        let ser: unsafe extern "C" fn(Component, *mut c_void, *mut u8, usize) -> Status = self.sym("fmi3SerializeFMUState")?;
        let free: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.sym("fmi3FreeFMUState")?;
        let mut state = std::ptr::null_mut();
        let mut n = 0usize;
        // SAFETY: the standard's calling sequence with a buffer of the size the FMU gives.
        unsafe {
            self.check("fmi3GetFMUState", get(self.c, &mut state))?;
            self.check("fmi3SerializedFMUStateSize", size(self.c, state, &mut n))?;
            let mut bytes = vec![0u8; n];
            self.check("fmi3SerializeFMUState", ser(self.c, state, bytes.as_mut_ptr(), n))?;
            self.check("fmi3FreeFMUState", free(self.c, &mut state))?;
            Ok(bytes)
        }
    }

    /// Sets the state from bytes (fmi3DeserializeFMUState, fmi3SetFMUState, fmi3FreeFMUState).
    pub fn restore_state(&self, bytes: &[u8]) -> Result<(), String> {
        let de: unsafe extern "C" fn(Component, *const u8, usize, *mut *mut c_void) -> Status = self.sym("fmi3DeserializeFMUState")?;
        let set: unsafe extern "C" fn(Component, *mut c_void) -> Status = self.sym("fmi3SetFMUState")?;
        let free: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.sym("fmi3FreeFMUState")?;
        let mut state = std::ptr::null_mut();
        // SAFETY: bytes of the given length; the state is freed after use.
        unsafe {
            self.check("fmi3DeserializeFMUState", de(self.c, bytes.as_ptr(), bytes.len(), &mut state))?;
            self.check("fmi3SetFMUState", set(self.c, state))?;
            self.check("fmi3FreeFMUState", free(self.c, &mut state))
        }
    }
}

impl Drop for Instance<'_> {
    fn drop(&mut self) {
        if let Ok(f) = self.sym::<Free>("fmi3FreeInstance") {
            // SAFETY: the instance is freed once, here; the log outlives the call.
            unsafe { f(self.c) }
        }
    }
}
