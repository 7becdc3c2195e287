//! FMI 2.0 as a host sees it (fmi2FunctionTypes.h, fmi2TypesPlatform.h): the callback structure with a
//! logger that collects messages per instance, the event-info structure, the function types the hosts
//! call, and an owning [`Instance`] for checked calls by variable name.

use crate::{check, environment, last_message, Binary, Component, Log, Names, Status};
use std::ffi::{c_char, c_int, c_void, CStr, CString};

/// fmi2Type: Model Exchange.
pub const MODEL_EXCHANGE: c_int = 0;
/// fmi2Type: Co-Simulation.
pub const CO_SIMULATION: c_int = 1;
/// fmi2True.
pub const TRUE: c_int = 1;
/// fmi2False.
pub const FALSE: c_int = 0;

/// fmi2CallbackLogger: (environment, instance name, status, category, printf format, ...).
pub type Logger = unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char, ...);

/// fmi2CallbackFunctions (FMI 2.0.4 Sec. 2.1.5).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct Callbacks {
    /// The host's logger (required by the standard).
    pub logger: Option<Logger>,
    /// allocateMemory (null: the FMU allocates itself).
    pub allocate_memory: *const c_void,
    /// freeMemory.
    pub free_memory: *const c_void,
    /// stepFinished (null: no asynchronous doStep).
    pub step_finished: *const c_void,
    /// componentEnvironment: passed back as the logger's first argument.
    pub component_environment: *mut c_void,
}

/// The logger this crate gives the FMU: appends (status, category, text) to the [`Log`] the instance
/// environment points at (a null environment: the message goes to standard error).
///
/// Stable Rust cannot define a C variadic function. The FMUs these hosts load pass their text already
/// formatted (a literal % doubled) and no variadic arguments, and on x86-64 (System V and Windows alike)
/// such a call reaches a non-variadic function with the same fixed parameters intact; [`callbacks`]
/// casts it to the variadic type.
///
/// # Safety
/// `env` is null or points at a live `Log`; the strings are NUL-terminated (FMI 2.0.4 Sec. 2.1.5).
pub unsafe extern "C" fn logger(env: *mut c_void, _name: *const c_char, status: Status, category: *const c_char, message: *const c_char) {
    // SAFETY: the caller's contract.
    let (category, text) =
        unsafe { (CStr::from_ptr(category).to_string_lossy().into_owned(), CStr::from_ptr(message).to_string_lossy().replace("%%", "%")) };
    if env.is_null() {
        eprintln!("fmu: [{category}, status {status}] {text}");
        return;
    }
    // SAFETY: the caller's contract.
    let log = unsafe { &*(env as *const Log) };
    log.lock().unwrap_or_else(|e| e.into_inner()).push((status, category, text));
}

/// The callbacks of an instance whose messages go to `log`.
pub fn callbacks(log: &Log) -> Callbacks {
    type Plain = unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char);
    // SAFETY: see `logger`.
    let variadic = unsafe { std::mem::transmute::<Plain, Logger>(logger) };
    Callbacks {
        logger: Some(variadic),
        allocate_memory: std::ptr::null(),
        free_memory: std::ptr::null(),
        step_finished: std::ptr::null(),
        component_environment: environment(log),
    }
}

/// fmi2EventInfo (FMI 2.0.4 Sec. 3.2.2).
#[repr(C)]
#[derive(Default, Debug, Clone, Copy)]
pub struct EventInfo {
    /// newDiscreteStatesNeeded.
    pub new_discrete_states_needed: c_int,
    /// terminateSimulation.
    pub terminate_simulation: c_int,
    /// nominalsOfContinuousStatesChanged.
    pub nominals_changed: c_int,
    /// valuesOfContinuousStatesChanged.
    pub values_changed: c_int,
    /// nextEventTimeDefined.
    pub next_event_time_defined: c_int,
    /// nextEventTime, in seconds.
    pub next_event_time: f64,
}

/// fmi2Instantiate.
pub type Instantiate = unsafe extern "C" fn(*const c_char, c_int, *const c_char, *const c_char, *const Callbacks, c_int, c_int) -> Component;
/// A call on the instance alone (fmi2EnterInitializationMode, fmi2Terminate, fmi2Reset, ...).
pub type Call0 = unsafe extern "C" fn(Component) -> Status;
/// fmi2SetReal.
pub type SetReal = unsafe extern "C" fn(Component, *const u32, usize, *const f64) -> Status;
/// fmi2GetReal.
pub type GetReal = unsafe extern "C" fn(Component, *const u32, usize, *mut f64) -> Status;
/// fmi2GetInteger.
pub type GetInteger = unsafe extern "C" fn(Component, *const u32, usize, *mut c_int) -> Status;
/// fmi2SetString.
pub type SetString = unsafe extern "C" fn(Component, *const u32, usize, *const *const c_char) -> Status;
/// fmi2SetupExperiment.
pub type Setup = unsafe extern "C" fn(Component, c_int, f64, f64, c_int, f64) -> Status;
/// fmi2DoStep.
pub type DoStep = unsafe extern "C" fn(Component, f64, f64, c_int) -> Status;
/// fmi2GetContinuousStates, fmi2GetDerivatives, fmi2GetEventIndicators, fmi2GetNominalsOfContinuousStates.
pub type Vector = unsafe extern "C" fn(Component, *mut f64, usize) -> Status;
/// fmi2SetContinuousStates.
pub type SetVector = unsafe extern "C" fn(Component, *const f64, usize) -> Status;
/// fmi2FreeInstance.
pub type Free = unsafe extern "C" fn(Component);

/// fmi2Instantiate with this crate's logger writing to `log`; the callback structure is leaked, so it
/// outlives the instance whatever the FMU keeps of it. Null when the FMU refuses.
pub fn instantiate(binary: &Binary, name: &str, kind: c_int, guid: &str, resource_uri: &str, log: &Log) -> Result<Component, String> {
    let callbacks: &'static Callbacks = Box::leak(Box::new(callbacks(log)));
    let (name, guid, uri) = (cstring(name)?, cstring(guid)?, cstring(resource_uri)?);
    // SAFETY: the standard's signature.
    let f: Instantiate = unsafe { binary.sym(b"fmi2Instantiate")? };
    // SAFETY: NUL-terminated strings; callbacks and log outlive the call (the log: the caller's).
    Ok(unsafe { f(name.as_ptr(), kind, guid.as_ptr(), uri.as_ptr(), callbacks, FALSE, FALSE) })
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
    /// fmi2Instantiate of `kind` ([`MODEL_EXCHANGE`] or [`CO_SIMULATION`]).
    pub fn new(binary: &'a Binary, kind: c_int, guid: &str, resource_uri: &str, names: Names<'a>) -> Result<Instance<'a>, String> {
        let log = Box::new(Log::default());
        let c = instantiate(binary, "fmi_host", kind, guid, resource_uri, &log)?;
        if c.is_null() {
            return Err(format!("fmi2Instantiate failed: {}", last_message(&log)));
        }
        Ok(Instance { binary, names, log, c })
    }

    /// The messages logged so far.
    pub fn log(&self) -> &Log {
        &self.log
    }

    fn sym<T: Copy>(&self, name: &str) -> Result<T, String> {
        // SAFETY: each caller below names an FMI 2.0 function with its header's signature.
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

    /// fmi2SetupExperiment without tolerance or stop time.
    pub fn setup(&self, start: f64) -> Result<(), String> {
        let f: Setup = self.sym("fmi2SetupExperiment")?;
        // SAFETY: a live instance.
        self.check("fmi2SetupExperiment", unsafe { f(self.c, FALSE, 0.0, start, FALSE, 0.0) })
    }

    /// fmi2SetReal of one variable.
    pub fn set_real(&self, name: &str, value: f64) -> Result<(), String> {
        let vr = (self.names)(name)?;
        let f: SetReal = self.sym("fmi2SetReal")?;
        // SAFETY: one value reference, one value.
        self.check(&format!("fmi2SetReal({name})"), unsafe { f(self.c, &vr, 1, &value) })
    }

    /// fmi2SetString of one variable.
    pub fn set_string(&self, name: &str, value: &str) -> Result<(), String> {
        let vr = (self.names)(name)?;
        let text = cstring(value)?;
        let f: SetString = self.sym("fmi2SetString")?;
        // SAFETY: one value reference, one string.
        self.check(&format!("fmi2SetString({name})"), unsafe { f(self.c, &vr, 1, &text.as_ptr()) })
    }

    /// fmi2GetReal of one variable.
    pub fn real(&self, name: &str) -> Result<f64, String> {
        let vr = (self.names)(name)?;
        let mut v = f64::NAN;
        let f: GetReal = self.sym("fmi2GetReal")?;
        // SAFETY: one value reference, room for one value.
        self.check(&format!("fmi2GetReal({name})"), unsafe { f(self.c, &vr, 1, &mut v) })?;
        Ok(v)
    }

    /// fmi2GetInteger of one variable.
    pub fn integer(&self, name: &str) -> Result<i32, String> {
        let vr = (self.names)(name)?;
        let mut v: c_int = 0;
        let f: GetInteger = self.sym("fmi2GetInteger")?;
        // SAFETY: one value reference, room for one value.
        self.check(&format!("fmi2GetInteger({name})"), unsafe { f(self.c, &vr, 1, &mut v) })?;
        Ok(v)
    }

    /// fmi2SetRealInputDerivatives of one variable at one order.
    pub fn set_input_derivative(&self, name: &str, order: c_int, value: f64) -> Result<(), String> {
        let vr = (self.names)(name)?;
        let f: unsafe extern "C" fn(Component, *const u32, usize, *const c_int, *const f64) -> Status = self.sym("fmi2SetRealInputDerivatives")?;
        // SAFETY: one value reference, one order, one value.
        self.check(&format!("fmi2SetRealInputDerivatives({name})"), unsafe { f(self.c, &vr, 1, &order, &value) })
    }

    /// fmi2DoStep from `t` by `h`, noSetFMUStatePriorToCurrentPoint true.
    pub fn do_step(&self, t: f64, h: f64) -> Result<(), String> {
        let f: DoStep = self.sym("fmi2DoStep")?;
        // SAFETY: a live instance.
        self.check("fmi2DoStep", unsafe { f(self.c, t, h, TRUE) })
    }

    /// The state serialized to bytes (fmi2GetFMUstate, fmi2SerializedFMUstateSize, fmi2SerializeFMUstate,
    /// fmi2FreeFMUstate).
    pub fn serialize_state(&self) -> Result<Vec<u8>, String> {
        let get: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.sym("fmi2GetFMUstate")?;
        let size: unsafe extern "C" fn(Component, *mut c_void, *mut usize) -> Status = self.sym("fmi2SerializedFMUstateSize")?;
        let ser: unsafe extern "C" fn(Component, *mut c_void, *mut c_char, usize) -> Status = self.sym("fmi2SerializeFMUstate")?;
        let free: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.sym("fmi2FreeFMUstate")?;
        let mut state = std::ptr::null_mut();
        let mut n = 0usize;
        // SAFETY: the standard's calling sequence with a buffer of the size the FMU gives.
        unsafe {
            self.check("fmi2GetFMUstate", get(self.c, &mut state))?;
            self.check("fmi2SerializedFMUstateSize", size(self.c, state, &mut n))?;
            let mut bytes = vec![0u8; n];
            self.check("fmi2SerializeFMUstate", ser(self.c, state, bytes.as_mut_ptr() as *mut c_char, n))?;
            self.check("fmi2FreeFMUstate", free(self.c, &mut state))?;
            Ok(bytes)
        }
    }

    /// Sets the state from bytes (fmi2DeSerializeFMUstate, fmi2SetFMUstate, fmi2FreeFMUstate).
    pub fn restore_state(&self, bytes: &[u8]) -> Result<(), String> {
        let de: unsafe extern "C" fn(Component, *const c_char, usize, *mut *mut c_void) -> Status = self.sym("fmi2DeSerializeFMUstate")?;
        let set: unsafe extern "C" fn(Component, *mut c_void) -> Status = self.sym("fmi2SetFMUstate")?;
        let free: unsafe extern "C" fn(Component, *mut *mut c_void) -> Status = self.sym("fmi2FreeFMUstate")?;
        let mut state = std::ptr::null_mut();
        // SAFETY: bytes of the given length; the state is freed after use.
        unsafe {
            self.check("fmi2DeSerializeFMUstate", de(self.c, bytes.as_ptr() as *const c_char, bytes.len(), &mut state))?;
            self.check("fmi2SetFMUstate", set(self.c, state))?;
            self.check("fmi2FreeFMUstate", free(self.c, &mut state))
        }
    }

    /// fmi2NewDiscreteStates (Model Exchange).
    pub fn new_discrete_states(&self) -> Result<EventInfo, String> {
        let f: unsafe extern "C" fn(Component, *mut EventInfo) -> Status = self.sym("fmi2NewDiscreteStates")?;
        let mut info = EventInfo::default();
        // SAFETY: a live instance and an EventInfo of the standard's layout.
        self.check("fmi2NewDiscreteStates", unsafe { f(self.c, &mut info) })?;
        Ok(info)
    }

    /// fmi2SetTime (Model Exchange).
    pub fn set_time(&self, t: f64) -> Result<(), String> {
        let f: unsafe extern "C" fn(Component, f64) -> Status = self.sym("fmi2SetTime")?;
        // SAFETY: a live instance.
        self.check("fmi2SetTime", unsafe { f(self.c, t) })
    }

    /// A getter of a vector (`function`: fmi2GetContinuousStates, fmi2GetDerivatives, ...) into `out`.
    pub fn vector(&self, function: &str, out: &mut [f64]) -> Result<(), String> {
        let f: Vector = self.sym(function)?;
        // SAFETY: a buffer of the length passed.
        self.check(function, unsafe { f(self.c, out.as_mut_ptr(), out.len()) })
    }

    /// fmi2SetContinuousStates.
    pub fn set_states(&self, x: &[f64]) -> Result<(), String> {
        let f: SetVector = self.sym("fmi2SetContinuousStates")?;
        // SAFETY: a buffer of the length passed.
        self.check("fmi2SetContinuousStates", unsafe { f(self.c, x.as_ptr(), x.len()) })
    }

    /// fmi2CompletedIntegratorStep: whether the FMU asks for an event now.
    pub fn completed_step(&self) -> Result<bool, String> {
        let f: unsafe extern "C" fn(Component, c_int, *mut c_int, *mut c_int) -> Status = self.sym("fmi2CompletedIntegratorStep")?;
        let (mut enter, mut terminate) = (0, 0);
        // SAFETY: two out-parameters.
        self.check("fmi2CompletedIntegratorStep", unsafe { f(self.c, TRUE, &mut enter, &mut terminate) })?;
        Ok(enter != 0)
    }
}

impl Drop for Instance<'_> {
    fn drop(&mut self) {
        if let Ok(f) = self.sym::<Free>("fmi2FreeInstance") {
            // SAFETY: the instance is freed once, here; the log outlives the call.
            unsafe { f(self.c) }
        }
    }
}
