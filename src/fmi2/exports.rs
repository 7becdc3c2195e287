//! The 44 exported `fmi2*` functions. Each one: checks its pointers, finds its instance among the live
//! ones (a freed or foreign pointer is refused, not followed), checks the calling sequence, and runs inside
//! the one `catch_unwind` boundary (`call`), so no panic crosses into the host. Failures are logged through
//! the host's logger with a message naming the function and the argument.

#![allow(non_snake_case, non_upper_case_globals, clippy::missing_safety_doc)]

use super::types::*;
use crate::fmi::ffi::{self, c_str, out, slice, slice_mut, Registry};
use crate::fmi::instance::{allowed, discard, error, Call, Instance, Kind, LogCallback, Logger, Mode};
use crate::fmi::uri::file_uri_to_path;
use crate::fmi::{state_calls, Api, Status};
use crate::units::variables::{Value, VarType};
use crate::units::{self, LOG_CATEGORIES};
use std::ffi::CString;
use std::os::raw::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The live instances and saved states of this ABI: a pointer not in these sets is never dereferenced.
static INSTANCES: Registry = Registry::new();
static STATES: Registry = Registry::new();

/// The host's FMI 2.0 logger as the shared layer calls it.
fn log_callback(logger: fmi2CallbackLogger) -> LogCallback {
    let callback = logger?;
    Some(std::sync::Arc::new(move |environment, name: &std::ffi::CStr, status: Status, category: &std::ffi::CStr, message: &str| {
        // The host formats the message with printf: a literal % must be doubled.
        let text = CString::new(message.replace('%', "%%").replace('\0', " ")).unwrap_or_default();
        // SAFETY: the host gave this callback for exactly these arguments; the strings outlive the call.
        unsafe { callback(environment, name.as_ptr(), status as i32, category.as_ptr(), text.as_ptr()) };
    }))
}

/// Runs `f` on the instance behind `c` if `c` is live and the mode allows `function`.
fn call(c: fmi2Component, function: &'static str, modes: u32, f: impl FnOnce(&mut Instance) -> Call) -> fmi2Status {
    call_for(c, function, None, modes, f)
}

/// `call` for a function of one interface (`kind`), or of both (`None`): the interface is checked before
/// the calling sequence, so a function of the other interface is refused as such in every state.
fn call_for(c: fmi2Component, function: &'static str, kind: Option<Kind>, modes: u32, f: impl FnOnce(&mut Instance) -> Call) -> fmi2Status {
    ffi::call_on(&INSTANCES, c, function, kind, modes, f) as fmi2Status
}

// ---------------------------------------------------------------------------------------------------
// Inquire version numbers, logging

/// Returns "default": the functions use the types of the standard fmi2TypesPlatform.h. Implements
/// fmi2GetTypesPlatform (FMI 2.0.4 Sec. 2.1.4); needs no instance.
#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

/// Returns "2.0", the version of the fmi2Functions.h header these functions follow. Implements fmi2GetVersion
/// (FMI 2.0.4 Sec. 2.1.4); needs no instance.
#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// Switches the named log categories on or off, or all of them when `nCategories` is 0; a name that is not
/// one of the unit's log categories refuses the whole call. fmi2SetDebugLogging (FMI 2.0.4 Sec. 2.1.5),
/// allowed in every state but Fatal.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    call(c, "fmi2SetDebugLogging", allowed::ANY_LIVE, |inst| {
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let names = unsafe { slice(categories, nCategories, "fmi2SetDebugLogging", "categories") }?;
        let on = loggingOn != fmi2False;
        let mut indices = Vec::new();
        for (i, &p) in names.iter().enumerate() {
            // SAFETY: the host passes a NUL-terminated string (FMI 2.0 Sec. 2.1.2); NULL is refused inside.
            let name = unsafe { c_str(p, "fmi2SetDebugLogging", &format!("categories[{i}]")) }?;
            match LOG_CATEGORIES.iter().position(|(n, _)| *n == name) {
                Some(k) => indices.push(k),
                None => {
                    let known: Vec<&str> = LOG_CATEGORIES.iter().map(|(n, _)| *n).collect();
                    return error(format!("fmi2SetDebugLogging: unknown log category \"{name}\"; known: {}", known.join(", ")));
                }
            }
        }
        // No categories: all of them on or off; otherwise only the named ones.
        if indices.is_empty() {
            inst.logger.categories.fill(on);
            inst.logger.logging_on = on;
        } else {
            for k in indices {
                inst.logger.categories[k] = on;
            }
            inst.logger.logging_on = inst.logger.categories.iter().any(|&x| x);
        }
        Ok(())
    })
}

// ---------------------------------------------------------------------------------------------------
// Creation and destruction

/// Makes an instance of the unit whose GUID is `fmuGUID`, for Model Exchange or Co-Simulation: fmi2Instantiate
/// (FMI 2.0.4 Sec. 2.1.5). Returns NULL, with the reason sent to `functions->logger`, for a NULL or empty
/// name, an unknown GUID, Model Exchange asked of a Co-Simulation-only unit, or an `fmuResourceLocation`
/// that is not a `file:` URI of a directory (NULL is accepted: no resources); NULL `functions` gives NULL
/// without a message. `visible` is ignored; the memory callbacks are not used.
#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instanceName: fmi2String,
    fmuType: fmi2Type,
    fmuGUID: fmi2String,
    fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    loggingOn: fmi2Boolean,
) -> fmi2Component {
    if functions.is_null() {
        return std::ptr::null_mut();
    }
    let result = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: `functions` is non-NULL (checked above) and points to the host's callback struct.
        let cb = unsafe { *functions };
        let logger = Logger::new(log_callback(cb.logger), cb.componentEnvironment, loggingOn != fmi2False);
        let fail = |name: &str, msg: String| {
            let n = CString::new(name.replace('\0', " ")).unwrap_or_default();
            logger.log(&n, Status::Error, "logStatusError", &msg);
            std::ptr::null_mut()
        };
        // SAFETY: the host passes a NUL-terminated string (FMI 2.0 Sec. 2.1.2); NULL is refused inside.
        let name = match unsafe { c_str(instanceName, "fmi2Instantiate", "instanceName") } {
            Ok(n) if !n.is_empty() => n,
            Ok(_) => return fail("", "fmi2Instantiate: instanceName is empty".into()),
            Err(e) => return fail("", e.message),
        };
        let kind = match fmuType {
            fmi2ModelExchange => Kind::ModelExchange,
            fmi2CoSimulation => Kind::CoSimulation,
            other => return fail(&name, format!("fmi2Instantiate: fmuType = {other} is neither fmi2ModelExchange (0) nor fmi2CoSimulation (1)")),
        };
        // SAFETY: the host passes a NUL-terminated string (FMI 2.0 Sec. 2.1.2); NULL is refused inside.
        let guid = match unsafe { c_str(fmuGUID, "fmi2Instantiate", "fmuGUID") } {
            Ok(g) => g,
            Err(e) => return fail(&name, e.message),
        };
        let Some(unit) = units::all().iter().find(|u| u.guid() == guid) else {
            let known: Vec<String> = units::all().iter().map(|u| format!("{} {}", u.model_identifier, u.guid())).collect();
            return fail(
                &name,
                format!(
                    "fmi2Instantiate: fmuGUID {guid} matches no unit of this binary ({}); modelDescription.xml and the binary do not belong together",
                    known.join(", ")
                ),
            );
        };
        if kind == Kind::ModelExchange && !unit.model_exchange {
            return fail(&name, format!("fmi2Instantiate: {} offers Co-Simulation only (fmuType = fmi2CoSimulation)", unit.model_identifier));
        }
        let mut resources = None;
        if !fmuResourceLocation.is_null() {
            // SAFETY: the host passes a NUL-terminated string (FMI 2.0 Sec. 2.1.2); NULL is refused inside.
            let uri = match unsafe { c_str(fmuResourceLocation, "fmi2Instantiate", "fmuResourceLocation") } {
                Ok(u) => u,
                Err(e) => return fail(&name, e.message),
            };
            match file_uri_to_path(&uri) {
                Ok(path) if path.is_dir() => resources = Some(path),
                Ok(path) => {
                    return fail(&name, format!("fmi2Instantiate: fmuResourceLocation {uri} names {}, which is not a directory", path.display()))
                }
                Err(e) => return fail(&name, format!("fmi2Instantiate: {e}")),
            }
        }
        let inst = Box::new(Instance::new(Api::Fmi2, &name, unit, kind, logger, resources));
        let p = Box::into_raw(inst);
        INSTANCES.register(p as usize);
        p as fmi2Component
    }));
    result.unwrap_or(std::ptr::null_mut())
}

/// Frees an instance made by fmi2Instantiate: fmi2FreeInstance (FMI 2.0.4 Sec. 2.1.5). NULL, or a pointer
/// that is not a live instance of this library (already freed, or foreign), is ignored.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    if c.is_null() || !INSTANCES.unregister(c as usize) {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: `c` was live (just unregistered) and came from Box::into_raw in fmi2Instantiate.
        drop(unsafe { Box::from_raw(c as *mut Instance) });
    }));
}

// ---------------------------------------------------------------------------------------------------
// Initialization, termination, reset

/// Takes the start time (the instance's time from now on) and, if defined, the stop time; the tolerance
/// is ignored. fmi2SetupExperiment (FMI 2.0.4 Sec. 2.1.6), in Instantiated only; a start time that is not
/// finite, or a stop time before it, is refused.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    _toleranceDefined: fmi2Boolean,
    _tolerance: fmi2Real,
    startTime: fmi2Real,
    stopTimeDefined: fmi2Boolean,
    stopTime: fmi2Real,
) -> fmi2Status {
    call(c, "fmi2SetupExperiment", allowed::SETUP_EXPERIMENT, |inst| {
        inst.setup_experiment(startTime, (stopTimeDefined != fmi2False).then_some(stopTime))
    })
}

/// Moves from Instantiated to Initialization Mode; nothing is computed yet. fmi2EnterInitializationMode
/// (FMI 2.0.4 Sec. 2.1.6).
#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    call(c, "fmi2EnterInitializationMode", allowed::ENTER_INITIALIZATION, |inst| {
        inst.mode = Mode::InitializationMode;
        Ok(())
    })
}

/// Builds the model's initial state from the values set so far and computes the outputs, then enters
/// Event Mode (Model Exchange) or Step Complete (Co-Simulation): fmi2ExitInitializationMode (FMI 2.0.4
/// Sec. 2.1.6), in Initialization Mode only. A model that cannot be initialized puts the instance in the
/// Error state.
#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    call(c, "fmi2ExitInitializationMode", allowed::EXIT_INITIALIZATION, |inst| inst.exit_initialization_mode())
}

/// Enters Terminated from Event Mode, Continuous-Time Mode or Step Complete; the values can still be read
/// there. fmi2Terminate (FMI 2.0.4 Sec. 2.1.6).
#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    call(c, "fmi2Terminate", allowed::TERMINATE, |inst| {
        inst.mode = Mode::Terminated;
        Ok(())
    })
}

/// Returns the instance to Instantiated: start values, a new model, time 0 and no stop time; the logging
/// settings stay. fmi2Reset (FMI 2.0.4 Sec. 2.1.6), allowed in every state but Fatal, the Error state included.
#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    call(c, "fmi2Reset", allowed::ANY_LIVE, |inst| {
        inst.reset();
        Ok(())
    })
}

// ---------------------------------------------------------------------------------------------------
// Getting and setting variable values

/// fmi2Get* of one type: the values of `vr` into `value`.
///
/// # Safety
/// `vr` and `value` must be the host's arrays of `nvr` elements (or NULL with `nvr` = 0), as `slice` says.
unsafe fn get_into<T>(
    c: fmi2Component,
    function: &'static str,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut T,
    var_type: VarType,
    convert: impl Fn(&Value, &mut Instance) -> T,
) -> fmi2Status {
    call(c, function, allowed::GET, |inst| {
        // SAFETY: the host promises arrays of length nvr; NULL and huge lengths are refused first.
        let vrs = unsafe { slice(vr, nvr, function, "vr")? };
        let dst = unsafe { slice_mut(value, nvr, function, "value")? };
        let got = inst.get(function, vrs, var_type)?;
        for (d, v) in dst.iter_mut().zip(&got) {
            *d = convert(v, inst);
        }
        Ok(())
    })
}

/// The values of the Real variables `vr` into `value`, with the outputs brought up to date first (in
/// Initialization Mode the model is built from the values set so far). fmi2GetReal (FMI 2.0.4 Sec. 2.1.7),
/// allowed from Initialization Mode on, also in Terminated and Error; an unknown or non-Real reference
/// refuses the call.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Real) -> fmi2Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came (FMI 2.0 Sec. 2.1).
    unsafe { get_into(c, "fmi2GetReal", vr, nvr, value, VarType::Real, |v, _| v.as_real()) }
}

/// The values of the Integer variables `vr` into `value`: fmi2GetInteger (FMI 2.0.4 Sec. 2.1.7), with the
/// outputs, modes and checks of fmi2GetReal.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Integer) -> fmi2Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came (FMI 2.0 Sec. 2.1).
    unsafe { get_into(c, "fmi2GetInteger", vr, nvr, value, VarType::Integer, |v, _| if let Value::Integer(i) = v { *i } else { 0 }) }
}

/// The values of the Boolean variables `vr` into `value`, as fmi2True or fmi2False: fmi2GetBoolean (FMI 2.0.4
/// Sec. 2.1.7), with the outputs, modes and checks of fmi2GetReal.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Boolean) -> fmi2Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came (FMI 2.0 Sec. 2.1).
    unsafe { get_into(c, "fmi2GetBoolean", vr, nvr, value, VarType::Boolean, |v, _| if let Value::Boolean(true) = v { fmi2True } else { fmi2False }) }
}

/// Pointers to the values of the String variables `vr` into `value`: fmi2GetString (FMI 2.0.4 Sec. 2.1.7),
/// with the modes and checks of fmi2GetReal. The instance holds the strings until the next fmi2GetString
/// or fmi2FreeInstance; a NUL inside a value is passed as a space.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2String) -> fmi2Status {
    call(c, "fmi2GetString", allowed::GET, |inst| {
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let vrs = unsafe { slice(vr, nvr, "fmi2GetString", "vr") }?;
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let dst = unsafe { slice_mut(value, nvr, "fmi2GetString", "value") }?;
        let got = inst.get("fmi2GetString", vrs, VarType::String)?;
        inst.strings = got
            .iter()
            .map(|v| if let Value::String(s) = v { CString::new(s.replace('\0', " ")).unwrap_or_default() } else { CString::default() })
            .collect();
        for (d, s) in dst.iter_mut().zip(&inst.strings) {
            *d = s.as_ptr();
        }
        Ok(())
    })
}

/// fmi2Set* of one type: the values of `value` into the variables `vr`.
///
/// # Safety
/// `vr` and `value` must be the host's arrays of `nvr` elements (or NULL with `nvr` = 0), as `slice` says.
#[allow(clippy::too_many_arguments)] // the fmi2Set* arguments plus what this one setter needs to know
unsafe fn set_from<T: Copy>(
    c: fmi2Component,
    function: &'static str,
    modes: u32,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const T,
    var_type: VarType,
    convert: impl Fn(T) -> Value,
) -> fmi2Status {
    call(c, function, modes, |inst| {
        // SAFETY: this function's contract: the host's arrays of nvr elements; NULL and huge lengths are refused inside.
        let vrs = unsafe { slice(vr, nvr, function, "vr")? };
        let src = unsafe { slice(value, nvr, function, "value")? };
        inst.set(function, vrs, src.iter().map(|&x| convert(x)).collect(), var_type)
    })
}

/// Sets the Real variables `vr` to `value`, all or none: fmi2SetReal (FMI 2.0.4 Sec. 2.1.7). Inputs can be
/// set, parameters only before fmi2ExitInitializationMode, in Continuous-Time Mode only continuous inputs;
/// a value that is not finite or lies outside the variable's min/max refuses the call.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Real) -> fmi2Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came (FMI 2.0 Sec. 2.1).
    unsafe { set_from(c, "fmi2SetReal", allowed::SET_REAL, vr, nvr, value, VarType::Real, Value::Real) }
}

/// Sets the Integer variables `vr` to `value`, all or none: fmi2SetInteger (FMI 2.0.4 Sec. 2.1.7), with the
/// reference and causality checks of fmi2SetReal; not allowed in Continuous-Time Mode.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Integer) -> fmi2Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came (FMI 2.0 Sec. 2.1).
    unsafe { set_from(c, "fmi2SetInteger", allowed::SET_OTHER, vr, nvr, value, VarType::Integer, Value::Integer) }
}

/// Sets the Boolean variables `vr` (any value other than fmi2False is true), all or none: fmi2SetBoolean
/// (FMI 2.0.4 Sec. 2.1.7), with the reference and causality checks of fmi2SetReal; not allowed in
/// Continuous-Time Mode.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Boolean) -> fmi2Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came (FMI 2.0 Sec. 2.1).
    unsafe { set_from(c, "fmi2SetBoolean", allowed::SET_OTHER, vr, nvr, value, VarType::Boolean, |b| Value::Boolean(b != fmi2False)) }
}

/// Sets the String variables `vr` to copies of the strings in `value`, all or none: fmi2SetString (FMI 2.0.4
/// Sec. 2.1.7), with the checks of fmi2SetInteger; a NULL or non-UTF-8 string refuses the call.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2String) -> fmi2Status {
    call(c, "fmi2SetString", allowed::SET_OTHER, |inst| {
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let vrs = unsafe { slice(vr, nvr, "fmi2SetString", "vr") }?;
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let src = unsafe { slice(value, nvr, "fmi2SetString", "value") }?;
        let mut strings = Vec::with_capacity(nvr);
        for (i, &p) in src.iter().enumerate() {
            // SAFETY: the host passes a NUL-terminated string (FMI 2.0 Sec. 2.1.2); NULL is refused inside.
            strings.push(Value::String(unsafe { c_str(p, "fmi2SetString", &format!("value[{i}]")) }?));
        }
        inst.set("fmi2SetString", vrs, strings, VarType::String)
    })
}

// ---------------------------------------------------------------------------------------------------
// FMU state: get, set, free, serialize

/// Saves the instance (values, mode, times and the model's state) into `*FMUstate`: into the state already
/// there if it is a live state of this library, else into a new one. fmi2GetFMUstate (FMI 2.0.4 Sec. 2.1.8),
/// allowed in every state but Fatal; a model that cannot save itself gives fmi2Error.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
    // SAFETY: the host's output argument (`state_calls::get` checks NULL).
    call(c, "fmi2GetFMUstate", allowed::ANY_LIVE, |inst| unsafe { state_calls::get(&STATES, inst, FMUstate, "fmi2GetFMUstate", "FMUstate") })
}

/// Restores the instance from a live state of this library: fmi2SetFMUstate (FMI 2.0.4 Sec. 2.1.8), allowed
/// in every state but Fatal, so also a way out of the Error state. A freed or foreign pointer, or a state of
/// another unit or of the other interface, is refused and the instance left as it was.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    call(c, "fmi2SetFMUstate", allowed::ANY_LIVE, |inst| state_calls::set(&STATES, inst, FMUstate, "fmi2SetFMUstate"))
}

/// Frees the state `*FMUstate` and sets `*FMUstate` to NULL; a NULL `*FMUstate` is nothing to free.
/// fmi2FreeFMUstate (FMI 2.0.4 Sec. 2.1.8). A state passed itself instead of its address is freed too, with
/// a warning in the log, and the call still returns fmi2OK; a `*FMUstate` that is not live is refused.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
    // SAFETY: the host's argument, as `state_calls::free` requires.
    call(c, "fmi2FreeFMUstate", allowed::ANY_LIVE, |inst| unsafe { state_calls::free(&STATES, inst, FMUstate, "fmi2FreeFMUstate", "FMUstate") })
}

/// The number of bytes of a live state into `*size`: fmi2SerializedFMUstateSize (FMI 2.0.4 Sec. 2.1.8).
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(c: fmi2Component, FMUstate: fmi2FMUstate, size: *mut usize) -> fmi2Status {
    // SAFETY: the host's output argument (NULL is refused inside).
    call(c, "fmi2SerializedFMUstateSize", allowed::ANY_LIVE, |_| unsafe { state_calls::size(&STATES, FMUstate, size, "fmi2SerializedFMUstateSize") })
}

/// Copies the bytes of a live state into `serializedState`: fmi2SerializeFMUstate (FMI 2.0.4 Sec. 2.1.8).
/// Refused when `size` is smaller than fmi2SerializedFMUstateSize gives.
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate, serializedState: *mut fmi2Byte, size: usize) -> fmi2Status {
    const F: &str = "fmi2SerializeFMUstate";
    // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
    call(c, F, allowed::ANY_LIVE, |_| unsafe {
        state_calls::serialize(&STATES, FMUstate, serializedState as *mut u8, size, F, "fmi2SerializedFMUstateSize")
    })
}

/// Makes a new state from the `size` bytes at `serializedState` and puts it into `*FMUstate`:
/// fmi2DeSerializeFMUstate (FMI 2.0.4 Sec. 2.1.8). Refused unless the bytes are a state of this unit saved
/// through FMI 2.0 (format version, checksum, model identifier and GUID are checked).
#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    const F: &str = "fmi2DeSerializeFMUstate";
    // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1) and its output argument; NULLs are refused inside.
    call(c, F, allowed::ANY_LIVE, |inst| unsafe {
        state_calls::deserialize(&STATES, inst, serializedState as *const u8, size, FMUstate, F, "FMUstate")
    })
}

/// fmi2GetDirectionalDerivative (FMI 2.0.4 Sec. 2.1.9) is not supported (providesDirectionalDerivative is
/// false): always fmi2Error, with that reason in the log.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    _vUnknown_ref: *const fmi2ValueReference,
    _nUnknown: usize,
    _vKnown_ref: *const fmi2ValueReference,
    _nKnown: usize,
    _dvKnown: *const fmi2Real,
    _dvUnknown: *mut fmi2Real,
) -> fmi2Status {
    call(c, "fmi2GetDirectionalDerivative", allowed::ANY_LIVE, |_| {
        error("fmi2GetDirectionalDerivative is not supported (providesDirectionalDerivative is false)")
    })
}

// ---------------------------------------------------------------------------------------------------
// Model Exchange

fn me(c: fmi2Component, function: &'static str, modes: u32, f: impl FnOnce(&mut Instance) -> Call) -> fmi2Status {
    call_for(c, function, Some(Kind::ModelExchange), modes, f)
}

/// Enters Event Mode from Continuous-Time Mode (or stays in it): fmi2EnterEventMode (FMI 2.0.4 Sec. 3.2.2),
/// Model Exchange only.
#[no_mangle]
pub unsafe extern "C" fn fmi2EnterEventMode(c: fmi2Component) -> fmi2Status {
    me(c, "fmi2EnterEventMode", allowed::ENTER_EVENT_MODE, |inst| {
        inst.mode = Mode::EventMode;
        Ok(())
    })
}

/// One event iteration: the model accepts the current state as that of the event, and
/// `valuesOfContinuousStatesChanged` says whether the integrator must restart (the model's branch or states
/// changed, or an input was set in this Event Mode); the other flags are false and no time event is
/// announced. fmi2NewDiscreteStates (FMI 2.0.4 Sec. 3.2.2), Model Exchange, Event Mode only.
#[no_mangle]
pub unsafe extern "C" fn fmi2NewDiscreteStates(c: fmi2Component, fmi2eventInfo: *mut fmi2EventInfo) -> fmi2Status {
    me(c, "fmi2NewDiscreteStates", allowed::NEW_DISCRETE_STATES, |inst| {
        let p = out(fmi2eventInfo, "fmi2NewDiscreteStates", "fmi2eventInfo")?;
        let restart = inst.accept();
        // SAFETY: an output argument of the host, checked non-NULL by `out` above.
        unsafe { *p = fmi2EventInfo { valuesOfContinuousStatesChanged: fmi2Boolean::from(restart), ..fmi2EventInfo::default() } };
        Ok(())
    })
}

/// Moves from Event Mode to Continuous-Time Mode: fmi2EnterContinuousTimeMode (FMI 2.0.4 Sec. 3.2.2), Model
/// Exchange only.
#[no_mangle]
pub unsafe extern "C" fn fmi2EnterContinuousTimeMode(c: fmi2Component) -> fmi2Status {
    me(c, "fmi2EnterContinuousTimeMode", allowed::ENTER_CONTINUOUS_TIME, |inst| {
        inst.mode = Mode::ContinuousTimeMode;
        Ok(())
    })
}

/// Tells the model an integrator step is complete. `*enterEventMode` is true when an event indicator has
/// changed sign since the last event or completed step (for example after an input set in Continuous-Time
/// Mode); `*terminateSimulation` is always false. fmi2CompletedIntegratorStep (FMI 2.0.4 Sec. 3.2.2), Model
/// Exchange, Continuous-Time Mode only.
#[no_mangle]
pub unsafe extern "C" fn fmi2CompletedIntegratorStep(
    c: fmi2Component,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
    enterEventMode: *mut fmi2Boolean,
    terminateSimulation: *mut fmi2Boolean,
) -> fmi2Status {
    me(c, "fmi2CompletedIntegratorStep", allowed::COMPLETED_INTEGRATOR_STEP, |inst| {
        let e = out(enterEventMode, "fmi2CompletedIntegratorStep", "enterEventMode")?;
        let t = out(terminateSimulation, "fmi2CompletedIntegratorStep", "terminateSimulation")?;
        // Between events the units stay on the branch of the last event; an input set in
        // Continuous-Time Mode that left it asks for Event Mode here (`Instance::completed_integrator_step`).
        let event = inst.completed_integrator_step()?;
        // SAFETY: an output argument of the host, checked non-NULL by `out` above.
        unsafe { *e = fmi2Boolean::from(event) };
        // SAFETY: an output argument of the host, checked non-NULL by `out` above.
        unsafe { *t = fmi2False };
        Ok(())
    })
}

/// Sets the time of the instance and its model; a time that is not finite is refused. fmi2SetTime
/// (FMI 2.0.4 Sec. 3.2.1), Model Exchange, in Event Mode or Continuous-Time Mode.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetTime(c: fmi2Component, time: fmi2Real) -> fmi2Status {
    me(c, "fmi2SetTime", allowed::SET_TIME, |inst| inst.set_time(time))
}

/// Sets the model's continuous states to `x`; `nx` must be the unit's number of states and every value
/// finite. fmi2SetContinuousStates (FMI 2.0.4 Sec. 3.2.1), Model Exchange, Continuous-Time Mode only.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetContinuousStates(c: fmi2Component, x: *const fmi2Real, nx: usize) -> fmi2Status {
    me(c, "fmi2SetContinuousStates", allowed::SET_CONTINUOUS_STATES, |inst| {
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let x = unsafe { slice(x, nx, "fmi2SetContinuousStates", "x") }?;
        inst.set_continuous_states(x)
    })
}

/// The derivatives of the continuous states at the current time, states and inputs, into `derivatives`;
/// `nx` must be the unit's number of states. fmi2GetDerivatives (FMI 2.0.4 Sec. 3.2.2), Model Exchange, from
/// Initialization Mode on (also in Terminated and Error).
#[no_mangle]
pub unsafe extern "C" fn fmi2GetDerivatives(c: fmi2Component, derivatives: *mut fmi2Real, nx: usize) -> fmi2Status {
    me(c, "fmi2GetDerivatives", allowed::GET_DERIVATIVES, |inst| {
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let dx = unsafe { slice_mut(derivatives, nx, "fmi2GetDerivatives", "derivatives") }?;
        inst.get_derivatives(dx)
    })
}

/// The event indicators at the current time, states and inputs, into `eventIndicators`; `ni` must be the
/// unit's number of event indicators. fmi2GetEventIndicators (FMI 2.0.4 Sec. 3.2.2), Model Exchange, in the
/// modes of fmi2GetDerivatives.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetEventIndicators(c: fmi2Component, eventIndicators: *mut fmi2Real, ni: usize) -> fmi2Status {
    me(c, "fmi2GetEventIndicators", allowed::GET_DERIVATIVES, |inst| {
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let z = unsafe { slice_mut(eventIndicators, ni, "fmi2GetEventIndicators", "eventIndicators") }?;
        inst.get_event_indicators(z)
    })
}

/// The model's continuous states into `x`; `nx` must be the unit's number of states.
/// fmi2GetContinuousStates (FMI 2.0.4 Sec. 3.2.2), Model Exchange, in the modes of fmi2GetDerivatives.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetContinuousStates(c: fmi2Component, x: *mut fmi2Real, nx: usize) -> fmi2Status {
    me(c, "fmi2GetContinuousStates", allowed::GET_DERIVATIVES, |inst| {
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let x = unsafe { slice_mut(x, nx, "fmi2GetContinuousStates", "x") }?;
        inst.get_continuous_states(x)
    })
}

/// The nominal values of the continuous states into `x_nominal`: 1.0 each until the model's initial state
/// is built. fmi2GetNominalsOfContinuousStates (FMI 2.0.4 Sec. 3.2.2), Model Exchange, from Instantiated on
/// (also in Terminated and Error).
#[no_mangle]
pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(c: fmi2Component, x_nominal: *mut fmi2Real, nx: usize) -> fmi2Status {
    me(c, "fmi2GetNominalsOfContinuousStates", allowed::GET_NOMINALS, |inst| {
        // SAFETY: the host passes an array of this length (FMI 2.0 Sec. 2.1); NULL and impossible lengths are refused inside.
        let x = unsafe { slice_mut(x_nominal, nx, "fmi2GetNominalsOfContinuousStates", "x_nominal") }?;
        inst.get_nominals(x)
    })
}

// ---------------------------------------------------------------------------------------------------
// Co-Simulation

fn cs(c: fmi2Component, function: &'static str, modes: u32, f: impl FnOnce(&mut Instance) -> Call) -> fmi2Status {
    call_for(c, function, Some(Kind::CoSimulation), modes, f)
}

/// Passes derivatives (order 1 or higher) of Real inputs to the model; all are checked before any is
/// taken. fmi2SetRealInputDerivatives (FMI 2.0.4 Sec. 4.2.1), Co-Simulation, in Instantiated, Initialization
/// Mode or Step Complete; refused by a unit with canInterpolateInputs false, and for a variable that is not
/// an input.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status {
    const F: &str = "fmi2SetRealInputDerivatives";
    cs(c, F, allowed::SET_INPUT_DERIVATIVES, |inst| {
        // SAFETY: the host passes arrays of nvr elements (FMI 2.0 Sec. 4.2.1); NULL and impossible lengths are refused inside.
        let vrs = unsafe { slice(vr, nvr, F, "vr") }?;
        let orders = unsafe { slice(order, nvr, F, "order") }?;
        let values = unsafe { slice(value, nvr, F, "value") }?;
        inst.set_input_derivatives(vrs, orders, values)
    })
}

/// fmi2GetRealOutputDerivatives (FMI 2.0.4 Sec. 4.2.1) is not supported (maxOutputDerivativeOrder is 0):
/// always fmi2Error on a Co-Simulation instance.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    cs(c, "fmi2GetRealOutputDerivatives", allowed::ANY_LIVE, |_| {
        error("fmi2GetRealOutputDerivatives is not supported (maxOutputDerivativeOrder is 0)")
    })
}

/// Advances the model from `currentCommunicationPoint` by `communicationStepSize`, synchronously:
/// fmi2DoStep (FMI 2.0.4 Sec. 4.2.2), Co-Simulation, Step Complete only. The step must be finite and
/// positive and start at the instance's time; a step the model cannot complete gives fmi2Error and puts
/// the instance in the Error state. The model's events go to the log under logEvents.
#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
) -> fmi2Status {
    cs(c, "fmi2DoStep", allowed::DO_STEP, |inst| inst.do_step(currentCommunicationPoint, communicationStepSize))
}

/// fmi2CancelStep (FMI 2.0.4 Sec. 4.2.2): always fmi2Error, since fmi2DoStep is synchronous and there is
/// never a step to cancel.
#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    cs(c, "fmi2CancelStep", allowed::ANY_LIVE, |_| error("fmi2CancelStep: fmi2DoStep is synchronous, there is never a step to cancel"))
}

/// A status kind the unit does not have: fmi2Discard, as FMI 2.0.4 Sec. 4.2.3 says for a status that is not
/// available; the instance goes on.
fn status_kind_error(function: &str, s: fmi2StatusKind) -> Call {
    discard(format!("{function}: status kind {s} is not available (fmi2DoStep never returns fmi2Pending or fmi2Discard)"))
}

/// fmi2GetStatus (FMI 2.0.4 Sec. 4.2.3): fmi2Discard for every status kind, since fmi2DoStep never returns
/// fmi2Pending. Co-Simulation, in Step Complete or Terminated.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(c: fmi2Component, s: fmi2StatusKind, _value: *mut fmi2Status) -> fmi2Status {
    cs(c, "fmi2GetStatus", allowed::CS_STATUS, |_| status_kind_error("fmi2GetStatus", s))
}

/// For fmi2LastSuccessfulTime, the instance's time (the end of the last completed step) into `*value`; any
/// other status kind is refused. fmi2GetRealStatus (FMI 2.0.4 Sec. 4.2.3), Co-Simulation, in Step Complete
/// or Terminated.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Real) -> fmi2Status {
    cs(c, "fmi2GetRealStatus", allowed::CS_STATUS, |inst| {
        let p = out(value, "fmi2GetRealStatus", "value")?;
        if s != fmi2LastSuccessfulTime {
            return status_kind_error("fmi2GetRealStatus", s);
        }
        // SAFETY: an output argument of the host, checked non-NULL by `out` above.
        unsafe { *p = inst.time };
        Ok(())
    })
}

/// fmi2GetIntegerStatus (FMI 2.0.4 Sec. 4.2.3): no status kind has an Integer value, so it is always
/// fmi2Discard. Co-Simulation, in Step Complete or Terminated.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(c: fmi2Component, s: fmi2StatusKind, _value: *mut fmi2Integer) -> fmi2Status {
    cs(c, "fmi2GetIntegerStatus", allowed::CS_STATUS, |_| status_kind_error("fmi2GetIntegerStatus", s))
}

/// For fmi2Terminated, fmi2False into `*value` (the unit never asks to end the simulation); any other
/// status kind is refused. fmi2GetBooleanStatus (FMI 2.0.4 Sec. 4.2.3), Co-Simulation, in Step Complete or
/// Terminated.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Boolean) -> fmi2Status {
    cs(c, "fmi2GetBooleanStatus", allowed::CS_STATUS, |_| {
        let p = out(value, "fmi2GetBooleanStatus", "value")?;
        if s != fmi2Terminated {
            return status_kind_error("fmi2GetBooleanStatus", s);
        }
        // SAFETY: an output argument of the host, checked non-NULL by `out` above.
        unsafe { *p = fmi2False };
        Ok(())
    })
}

/// fmi2GetStringStatus (FMI 2.0.4 Sec. 4.2.3): always fmi2Discard, since fmi2PendingStatus needs an
/// asynchronous step. Co-Simulation, in Step Complete or Terminated.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(c: fmi2Component, s: fmi2StatusKind, _value: *mut fmi2String) -> fmi2Status {
    cs(c, "fmi2GetStringStatus", allowed::CS_STATUS, |_| status_kind_error("fmi2GetStringStatus", s))
}
