//! The 75 exported `fmi3*` functions. Like the FMI 2.0 ones (`crate::fmi2::exports`), each checks its
//! pointers, finds its instance among the live ones, checks the calling sequence and runs inside the one
//! `catch_unwind` boundary (`crate::fmi::ffi::call_on`). The instance, its values, the units and the saved
//! states are those of FMI 2.0; what is FMI 3.0's own is here: typed getters and setters (the types the
//! units do not have are refused by reference), Event Mode and early return in Co-Simulation, and the
//! optional parts the units do not offer (clocks, configuration, dependencies, derivatives), refused with
//! the reason.

#![allow(non_snake_case, non_upper_case_globals, clippy::missing_safety_doc, clippy::too_many_arguments)]

use super::types::*;
use crate::fmi::ffi::{self, c_str, out, slice, slice_mut, Registry};
use crate::fmi::instance::{allowed, error, Call, Instance, Kind, LogCallback, Logger, Mode};
use crate::fmi::{state_calls, Api, Status};
use crate::units::variables::{Value, VarType};
use crate::units::{self, LOG_CATEGORIES};
use std::ffi::CString;
use std::os::raw::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

/// The live instances and saved states of this ABI (separate from FMI 2.0's: an FMI 2.0 pointer is foreign here).
static INSTANCES: Registry = Registry::new();
static STATES: Registry = Registry::new();

/// The host's FMI 3.0 logger as the shared layer calls it.
fn log_callback(logger: fmi3LogMessageCallback) -> LogCallback {
    let callback = logger?;
    Some(std::sync::Arc::new(move |environment, name: &std::ffi::CStr, status: Status, category: &std::ffi::CStr, message: &str| {
        // FMI 3.0 passes the message as it is (no printf); the instance name goes in front of it.
        let text = CString::new(format!("{}: {message}", name.to_string_lossy()).replace('\0', " ")).unwrap_or_default();
        // SAFETY: the host gave this callback for exactly these arguments; the strings outlive the call.
        unsafe { callback(environment, status as i32, category.as_ptr(), text.as_ptr()) };
    }))
}

fn call(c: fmi3Instance, function: &'static str, modes: u32, f: impl FnOnce(&mut Instance) -> Call) -> fmi3Status {
    ffi::call_on(&INSTANCES, c, function, None, modes, f) as fmi3Status
}

fn me(c: fmi3Instance, function: &'static str, modes: u32, f: impl FnOnce(&mut Instance) -> Call) -> fmi3Status {
    ffi::call_on(&INSTANCES, c, function, Some(Kind::ModelExchange), modes, f) as fmi3Status
}

fn cs(c: fmi3Instance, function: &'static str, modes: u32, f: impl FnOnce(&mut Instance) -> Call) -> fmi3Status {
    ffi::call_on(&INSTANCES, c, function, Some(Kind::CoSimulation), modes, f) as fmi3Status
}

/// Writes a value to a host's output argument.
///
/// # Safety
/// `p` must be NULL or point to a writable `T`.
unsafe fn put<T>(p: *mut T, value: T, function: &str, name: &str) -> Call {
    let p = out(p, function, name)?;
    // SAFETY: non-NULL (checked by `out`), and the host's output argument by this function's contract.
    unsafe { *p = value };
    Ok(())
}

// ---------------------------------------------------------------------------------------------------
// Inquire version numbers, logging

/// Returns "3.0", the version of the fmi3Functions.h header these functions follow. Implements fmi3GetVersion
/// (FMI 3.0 Sec. 2.2); needs no instance.
#[no_mangle]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

/// Switches the named log categories on or off, or all of them when `nCategories` is 0; a name that is not
/// one of the unit's log categories refuses the whole call. fmi3SetDebugLogging (FMI 3.0 Sec. 2.3.1),
/// allowed in every state but Fatal and Intermediate Update Mode.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    c: fmi3Instance,
    loggingOn: fmi3Boolean,
    nCategories: usize,
    categories: *const fmi3String,
) -> fmi3Status {
    const F: &str = "fmi3SetDebugLogging";
    call(c, F, allowed::ANY_LIVE, |inst| {
        // SAFETY: the host passes an array of this length (FMI 3.0 Sec. 2.2.5); NULL and impossible lengths are refused inside.
        let names = unsafe { slice(categories, nCategories, F, "categories") }?;
        let mut indices = Vec::new();
        for (i, &p) in names.iter().enumerate() {
            // SAFETY: the host passes NUL-terminated strings; NULL is refused inside.
            let name = unsafe { c_str(p, F, &format!("categories[{i}]")) }?;
            match LOG_CATEGORIES.iter().position(|(n, _)| *n == name) {
                Some(k) => indices.push(k),
                None => {
                    let known: Vec<&str> = LOG_CATEGORIES.iter().map(|(n, _)| *n).collect();
                    return error(format!("{F}: unknown log category \"{name}\"; known: {}", known.join(", ")));
                }
            }
        }
        if indices.is_empty() {
            inst.logger.categories.fill(loggingOn);
            inst.logger.logging_on = loggingOn;
        } else {
            for k in indices {
                inst.logger.categories[k] = loggingOn;
            }
            inst.logger.logging_on = inst.logger.categories.iter().any(|&x| x);
        }
        Ok(())
    })
}

// ---------------------------------------------------------------------------------------------------
// Creation and destruction

/// What the three instantiate functions share: the checks of name, token and resource path, and the
/// instance. Errors go to the host's logger; the result is NULL then.
///
/// # Safety
/// The string arguments must be NULL or NUL-terminated strings valid for the call.
unsafe fn instantiate(
    function: &'static str,
    kind: Kind,
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    resourcePath: fmi3String,
    loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
    configure: impl FnOnce(&mut Instance),
) -> fmi3Instance {
    let result = catch_unwind(AssertUnwindSafe(|| {
        let logger = Logger::new(log_callback(logMessage), instanceEnvironment, loggingOn);
        let fail = |name: &str, msg: String| {
            let n = CString::new(name.replace('\0', " ")).unwrap_or_default();
            logger.log(&n, Status::Error, "logStatusError", &msg);
            std::ptr::null_mut()
        };
        // SAFETY: this function's contract: NULL or a NUL-terminated string; NULL is refused inside.
        let name = match unsafe { c_str(instanceName, function, "instanceName") } {
            Ok(n) if !n.is_empty() => n,
            Ok(_) => return fail("", format!("{function}: instanceName is empty")),
            Err(e) => return fail("", e.message),
        };
        // SAFETY: as above.
        let token = match unsafe { c_str(instantiationToken, function, "instantiationToken") } {
            Ok(t) => t,
            Err(e) => return fail(&name, e.message),
        };
        let Some(unit) = units::all().iter().find(|u| u.instantiation_token() == token) else {
            let known: Vec<String> = units::all().iter().map(|u| format!("{} {}", u.model_identifier, u.instantiation_token())).collect();
            let fmi2 =
                units::all().iter().find(|u| u.guid() == token).map(|u| format!(" ({token} is the GUID of the FMI 2.0 {})", u.model_identifier));
            return fail(
                &name,
                format!(
                    "{function}: instantiationToken {token} matches no FMI 3.0 unit of this binary ({}){}; modelDescription.xml and the binary do not belong together",
                    known.join(", "),
                    fmi2.unwrap_or_default()
                ),
            );
        };
        if kind == Kind::ModelExchange && !unit.model_exchange {
            return fail(&name, format!("{function}: {} offers Co-Simulation only (fmi3InstantiateCoSimulation)", unit.model_identifier));
        }
        // FMI 3.0 passes the resources folder as an absolute path with a trailing separator (Sec. 2.3.1).
        let mut resources = None;
        if !resourcePath.is_null() {
            // SAFETY: as above.
            let path = match unsafe { c_str(resourcePath, function, "resourcePath") } {
                Ok(p) => PathBuf::from(p),
                Err(e) => return fail(&name, e.message),
            };
            if !path.is_dir() {
                return fail(&name, format!("{function}: resourcePath {} is not a directory", path.display()));
            }
            resources = Some(path);
        }
        let mut inst = Box::new(Instance::new(Api::Fmi3, &name, unit, kind, logger, resources));
        configure(&mut inst);
        let p = Box::into_raw(inst);
        INSTANCES.register(p as usize);
        p as fmi3Instance
    }));
    result.unwrap_or(std::ptr::null_mut())
}

/// Makes a Model Exchange instance of the unit whose instantiationToken is `instantiationToken`:
/// fmi3InstantiateModelExchange (FMI 3.0 Sec. 2.3.1). Returns NULL, with the reason sent to `logMessage`,
/// for a NULL or empty name, an unknown token (an FMI 2.0 GUID is named as such), a Co-Simulation-only
/// unit, or a `resourcePath` that is not a directory (NULL is accepted: no resources). `visible` is ignored.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    resourcePath: fmi3String,
    _visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
) -> fmi3Instance {
    // SAFETY: the host's arguments, passed on as they came (FMI 3.0 Sec. 2.3.1).
    unsafe {
        instantiate(
            "fmi3InstantiateModelExchange",
            Kind::ModelExchange,
            instanceName,
            instantiationToken,
            resourcePath,
            loggingOn,
            instanceEnvironment,
            logMessage,
            |_| {},
        )
    }
}

/// Makes a Co-Simulation instance, with the checks of fmi3InstantiateModelExchange:
/// fmi3InstantiateCoSimulation (FMI 3.0 Sec. 2.3.1). `eventModeUsed`, `earlyReturnAllowed` and the
/// intermediate-update callback are kept only for a unit with events inside a step (`returns_early`), and
/// ignored otherwise; `visible` and the required intermediate variables are ignored.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    resourcePath: fmi3String,
    _visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    eventModeUsed: fmi3Boolean,
    earlyReturnAllowed: fmi3Boolean,
    _requiredIntermediateVariables: *const fmi3ValueReference,
    _nRequiredIntermediateVariables: usize,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
    intermediateUpdate: fmi3IntermediateUpdateCallback,
) -> fmi3Instance {
    // SAFETY: the host's arguments, passed on as they came (FMI 3.0 Sec. 2.3.1).
    unsafe {
        instantiate(
            "fmi3InstantiateCoSimulation",
            Kind::CoSimulation,
            instanceName,
            instantiationToken,
            resourcePath,
            loggingOn,
            instanceEnvironment,
            logMessage,
            |inst| {
                // A unit without events inside a step (hasEventMode false) is never in Co-Simulation's
                // Event Mode, whatever the master asks.
                inst.event_mode_used = eventModeUsed && inst.unit.returns_early;
                inst.early_return_allowed = earlyReturnAllowed && inst.unit.returns_early;
                let update: fmi3IntermediateUpdateCallback = if inst.unit.returns_early { intermediateUpdate } else { None };
                inst.abi = Some(Box::new(update));
            },
        )
    }
}

/// fmi3InstantiateScheduledExecution (FMI 3.0 Sec. 2.3.1): always NULL, with a message to `logMessage`
/// that the units offer Model Exchange and Co-Simulation only.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    instanceName: fmi3String,
    _instantiationToken: fmi3String,
    _resourcePath: fmi3String,
    _visible: fmi3Boolean,
    _loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
    _clockUpdate: fmi3ClockUpdateCallback,
    _lockPreemption: fmi3LockPreemptionCallback,
    _unlockPreemption: fmi3UnlockPreemptionCallback,
) -> fmi3Instance {
    let _ = catch_unwind(AssertUnwindSafe(|| {
        let logger = Logger::new(log_callback(logMessage), instanceEnvironment, false);
        // SAFETY: the host passes NULL or a NUL-terminated string.
        let name = unsafe { c_str(instanceName, "fmi3InstantiateScheduledExecution", "instanceName") }.unwrap_or_default();
        let n = CString::new(name.replace('\0', " ")).unwrap_or_default();
        logger.log(
            &n,
            Status::Error,
            "logStatusError",
            "fmi3InstantiateScheduledExecution: the units offer Model Exchange and Co-Simulation, not Scheduled Execution",
        );
    }));
    std::ptr::null_mut()
}

/// Frees an instance made by an fmi3Instantiate function: fmi3FreeInstance (FMI 3.0 Sec. 2.3.1). NULL, or
/// a pointer that is not a live FMI 3.0 instance of this library (freed, foreign, or made through FMI 2.0),
/// is ignored.
#[no_mangle]
pub unsafe extern "C" fn fmi3FreeInstance(c: fmi3Instance) {
    if c.is_null() || !INSTANCES.unregister(c as usize) {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: `c` was live (just unregistered) and came from Box::into_raw in `instantiate`.
        drop(unsafe { Box::from_raw(c as *mut Instance) });
    }));
}

// ---------------------------------------------------------------------------------------------------
// Initialization, events, termination, reset

/// Takes the start time (the instance's time from now on) and, if defined, the stop time, and enters
/// Initialization Mode; the tolerance is ignored. fmi3EnterInitializationMode (FMI 3.0 Sec. 2.3.2), in
/// Instantiated only; a start time that is not finite, or a stop time before it, is refused.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    c: fmi3Instance,
    _toleranceDefined: fmi3Boolean,
    _tolerance: fmi3Float64,
    startTime: fmi3Float64,
    stopTimeDefined: fmi3Boolean,
    stopTime: fmi3Float64,
) -> fmi3Status {
    call(c, "fmi3EnterInitializationMode", allowed::ENTER_INITIALIZATION, |inst| {
        inst.setup_experiment(startTime, stopTimeDefined.then_some(stopTime))?;
        inst.mode = Mode::InitializationMode;
        Ok(())
    })
}

/// Builds the model's initial state from the values set so far and computes the outputs, then enters
/// Event Mode (Model Exchange, and Co-Simulation with Event Mode used) or Step Mode:
/// fmi3ExitInitializationMode (FMI 3.0 Sec. 2.3.3). A model that cannot be initialized puts the instance
/// in the Error state.
#[no_mangle]
pub unsafe extern "C" fn fmi3ExitInitializationMode(c: fmi3Instance) -> fmi3Status {
    call(c, "fmi3ExitInitializationMode", allowed::EXIT_INITIALIZATION, |inst| inst.exit_initialization_mode())
}

/// Enters Event Mode from Continuous-Time Mode (Model Exchange) or Step Mode (Co-Simulation):
/// fmi3EnterEventMode (FMI 3.0 Secs. 3.2.1 and 4.2.1). A Co-Simulation instance without Event Mode
/// (instantiated with eventModeUsed false, or a unit with no events inside a step) is refused with the reason.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterEventMode(c: fmi3Instance) -> fmi3Status {
    const F: &str = "fmi3EnterEventMode";
    call(c, F, allowed::ENTER_EVENT_MODE_3, |inst| {
        // Model Exchange comes from Continuous-Time Mode; Co-Simulation from Step Mode, with Event Mode used.
        if inst.kind == Kind::CoSimulation && !inst.event_mode_used {
            let why = if inst.unit.returns_early {
                "the master instantiated it with eventModeUsed = false"
            } else {
                "this unit has no events inside a step (hasEventMode is false)"
            };
            return error(format!("{F}: Co-Simulation's Event Mode is not used: {why}"));
        }
        inst.mode = Mode::EventMode;
        Ok(())
    })
}

/// Enters Terminated from Event Mode, Continuous-Time Mode or Step Mode; the values can still be read
/// there. fmi3Terminate (FMI 3.0 Sec. 2.3.4).
#[no_mangle]
pub unsafe extern "C" fn fmi3Terminate(c: fmi3Instance) -> fmi3Status {
    call(c, "fmi3Terminate", allowed::TERMINATE, |inst| {
        inst.mode = Mode::Terminated;
        Ok(())
    })
}

/// Returns the instance to Instantiated: start values, a new model, time 0 and no stop time; the logging
/// settings and the Co-Simulation options given at instantiation stay. fmi3Reset (FMI 3.0 Sec. 2.3.1),
/// allowed in every state but Fatal and Intermediate Update Mode, the Error state included.
#[no_mangle]
pub unsafe extern "C" fn fmi3Reset(c: fmi3Instance) -> fmi3Status {
    call(c, "fmi3Reset", allowed::ANY_LIVE, |inst| {
        inst.reset();
        Ok(())
    })
}

// ---------------------------------------------------------------------------------------------------
// Getting and setting variable values

/// nValues must equal nValueReferences: every variable of the units is a scalar.
fn scalar_count(function: &str, nvr: usize, n_values: usize) -> Call {
    if nvr == n_values {
        Ok(())
    } else {
        error(format!("{function}: nValues = {n_values} but nValueReferences = {nvr}; every variable of this unit is a scalar"))
    }
}

/// fmi3Get* of a type the units have: the values of `vr` into `value`.
///
/// # Safety
/// `vr` and `value` must be the host's arrays (or NULL with length 0), as `slice` says.
unsafe fn get_into<T>(
    c: fmi3Instance,
    function: &'static str,
    vr: *const fmi3ValueReference,
    nvr: usize,
    value: *mut T,
    n_values: usize,
    var_type: VarType,
    convert: impl Fn(&Value) -> T,
) -> fmi3Status {
    call(c, function, allowed::GET, |inst| {
        scalar_count(function, nvr, n_values)?;
        // SAFETY: the host promises arrays of these lengths; NULL and huge lengths are refused first.
        let vrs = unsafe { slice(vr, nvr, function, "valueReferences")? };
        let dst = unsafe { slice_mut(value, n_values, function, "values")? };
        let got = inst.get(function, vrs, var_type)?;
        for (d, v) in dst.iter_mut().zip(&got) {
            *d = convert(v);
        }
        Ok(())
    })
}

/// fmi3Set* of a type the units have.
///
/// # Safety
/// `vr` and `value` must be the host's arrays (or NULL with length 0), as `slice` says.
unsafe fn set_from<T: Copy>(
    c: fmi3Instance,
    function: &'static str,
    modes: u32,
    vr: *const fmi3ValueReference,
    nvr: usize,
    value: *const T,
    n_values: usize,
    var_type: VarType,
    convert: impl Fn(T) -> Value,
) -> fmi3Status {
    call(c, function, modes, |inst| {
        scalar_count(function, nvr, n_values)?;
        // SAFETY: the host promises arrays of these lengths; NULL and huge lengths are refused first.
        let vrs = unsafe { slice(vr, nvr, function, "valueReferences")? };
        let src = unsafe { slice(value, n_values, function, "values")? };
        inst.set(function, vrs, src.iter().map(|&x| convert(x)).collect(), var_type)
    })
}

/// A get or set of a type no variable of the units has: nothing to do for no references; any reference
/// is refused with the type its variable really has.
///
/// # Safety
/// `vr` must be the host's array of `nvr` references (or NULL with `nvr` = 0).
unsafe fn other_type(
    c: fmi3Instance,
    function: &'static str,
    modes: u32,
    type_name: &'static str,
    vr: *const fmi3ValueReference,
    nvr: usize,
) -> fmi3Status {
    call(c, function, modes, |inst| {
        // SAFETY: the host promises an array of this length; NULL and huge lengths are refused first.
        let vrs = unsafe { slice(vr, nvr, function, "valueReferences")? };
        if let Some(&r) = vrs.first() {
            return match inst.unit.variables.get(r as usize) {
                Some(v) => error(format!(
                    "{function}: value reference {r} is `{}`, a {} variable, not {type_name} (the units have Float64, Int32, Boolean and String variables only)",
                    v.name,
                    units::model_description_fmi3::element(v.var_type)
                )),
                None => error(format!("{function}: value reference {r} does not exist (this unit has {} variables)", inst.unit.variables.len())),
            };
        }
        Ok(())
    })
}

/// The values of the Float64 variables `vr` into `values`, with the outputs brought up to date first (in
/// Initialization Mode the model is built from the values set so far). fmi3GetFloat64 (FMI 3.0 Sec. 2.2),
/// from Initialization Mode on, also in Terminated, Error and (outputs only) Intermediate Update Mode;
/// `nValues` must equal `nvr`, and an unknown or non-Float64 reference refuses the call.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetFloat64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    values: *mut fmi3Float64,
    nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { get_into(c, "fmi3GetFloat64", vr, nvr, values, nValues, VarType::Real, Value::as_real) }
}

/// The values of the Int32 variables `vr` into `values`: fmi3GetInt32 (FMI 3.0 Sec. 2.2), with the outputs,
/// modes and checks of fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt32(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    values: *mut fmi3Int32,
    nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { get_into(c, "fmi3GetInt32", vr, nvr, values, nValues, VarType::Integer, |v| if let Value::Integer(i) = v { *i } else { 0 }) }
}

/// The values of the Boolean variables `vr` into `values`: fmi3GetBoolean (FMI 3.0 Sec. 2.2), with the
/// outputs, modes and checks of fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetBoolean(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    values: *mut fmi3Boolean,
    nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { get_into(c, "fmi3GetBoolean", vr, nvr, values, nValues, VarType::Boolean, |v| matches!(v, Value::Boolean(true))) }
}

/// Pointers to the values of the String variables `vr` into `values`: fmi3GetString (FMI 3.0 Sec. 2.2), with
/// the modes and checks of fmi3GetFloat64. The instance holds the strings until the next fmi3GetString or
/// fmi3FreeInstance; a NUL inside a value is passed as a space.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetString(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    values: *mut fmi3String,
    nValues: usize,
) -> fmi3Status {
    const F: &str = "fmi3GetString";
    call(c, F, allowed::GET, |inst| {
        scalar_count(F, nvr, nValues)?;
        // SAFETY: the host passes arrays of these lengths; NULL and impossible lengths are refused inside.
        let vrs = unsafe { slice(vr, nvr, F, "valueReferences") }?;
        let dst = unsafe { slice_mut(values, nValues, F, "values") }?;
        let got = inst.get(F, vrs, VarType::String)?;
        // Valid until the next call (FMI 3.0 Sec. 2.2.6.1).
        inst.strings = got.iter().map(|v| CString::new(v.as_str().replace('\0', " ")).unwrap_or_default()).collect();
        for (d, s) in dst.iter_mut().zip(&inst.strings) {
            *d = s.as_ptr();
        }
        Ok(())
    })
}

/// Sets the Float64 variables `vr` to `values`, all or none: fmi3SetFloat64 (FMI 3.0 Sec. 2.2). Inputs can be
/// set, parameters only before fmi3ExitInitializationMode, in Continuous-Time Mode only continuous inputs;
/// `nValues` must equal `nvr`, and a value that is not finite or lies outside min/max refuses the call.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetFloat64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    values: *const fmi3Float64,
    nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { set_from(c, "fmi3SetFloat64", allowed::SET_REAL, vr, nvr, values, nValues, VarType::Real, Value::Real) }
}

/// Sets the Int32 variables `vr` to `values`, all or none: fmi3SetInt32 (FMI 3.0 Sec. 2.2), with the
/// reference, count and causality checks of fmi3SetFloat64; not allowed in Continuous-Time Mode.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt32(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    values: *const fmi3Int32,
    nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { set_from(c, "fmi3SetInt32", allowed::SET_OTHER, vr, nvr, values, nValues, VarType::Integer, Value::Integer) }
}

/// Sets the Boolean variables `vr`, all or none; each value is read as a byte, any byte but 0 being true.
/// fmi3SetBoolean (FMI 3.0 Sec. 2.2), with the checks of fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetBoolean(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    values: *const fmi3Boolean,
    nValues: usize,
) -> fmi3Status {
    // The host's C bools read as bytes: a value other than 0 or 1 from a host that is not C must not
    // become an invalid Rust bool.
    // SAFETY: the host's arguments of this FMI function, passed on as they came (fmi3Boolean is one byte).
    unsafe { set_from(c, "fmi3SetBoolean", allowed::SET_OTHER, vr, nvr, values.cast::<u8>(), nValues, VarType::Boolean, |b| Value::Boolean(b != 0)) }
}

/// Sets the String variables `vr` to copies of the strings in `values`, all or none: fmi3SetString
/// (FMI 3.0 Sec. 2.2), with the checks of fmi3SetInt32; a NULL or non-UTF-8 string refuses the call.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetString(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    values: *const fmi3String,
    nValues: usize,
) -> fmi3Status {
    const F: &str = "fmi3SetString";
    call(c, F, allowed::SET_OTHER, |inst| {
        scalar_count(F, nvr, nValues)?;
        // SAFETY: the host passes arrays of these lengths; NULL and impossible lengths are refused inside.
        let vrs = unsafe { slice(vr, nvr, F, "valueReferences") }?;
        let src = unsafe { slice(values, nValues, F, "values") }?;
        let mut strings = Vec::with_capacity(nvr);
        for (i, &p) in src.iter().enumerate() {
            // SAFETY: the host passes NUL-terminated strings; NULL is refused inside.
            strings.push(Value::String(unsafe { c_str(p, F, &format!("values[{i}]")) }?));
        }
        inst.set(F, vrs, strings, VarType::String)
    })
}

// The getters and setters of the types no variable of the units has (`other_type`), written out one by
// one so that the header check (cbindgen, which does not expand macros) sees every prototype.

/// fmi3GetFloat32 (FMI 3.0 Sec. 2.2): no variable of the units is Float32, so with no value references it
/// does nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetFloat32(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *mut fmi3Float32,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetFloat32", allowed::GET, "Float32", vr, nvr) }
}

/// fmi3SetFloat32 (FMI 3.0 Sec. 2.2): no variable of the units is Float32, so with no value references it
/// does nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetFloat32(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *const fmi3Float32,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetFloat32", allowed::SET_OTHER, "Float32", vr, nvr) }
}

/// fmi3GetInt8 (FMI 3.0 Sec. 2.2): no variable of the units is Int8, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt8(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *mut fmi3Int8,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetInt8", allowed::GET, "Int8", vr, nvr) }
}

/// fmi3SetInt8 (FMI 3.0 Sec. 2.2): no variable of the units is Int8, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt8(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *const fmi3Int8,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetInt8", allowed::SET_OTHER, "Int8", vr, nvr) }
}

/// fmi3GetUInt8 (FMI 3.0 Sec. 2.2): no variable of the units is UInt8, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt8(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *mut fmi3UInt8,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetUInt8", allowed::GET, "UInt8", vr, nvr) }
}

/// fmi3SetUInt8 (FMI 3.0 Sec. 2.2): no variable of the units is UInt8, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt8(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *const fmi3UInt8,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetUInt8", allowed::SET_OTHER, "UInt8", vr, nvr) }
}

/// fmi3GetInt16 (FMI 3.0 Sec. 2.2): no variable of the units is Int16, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt16(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *mut fmi3Int16,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetInt16", allowed::GET, "Int16", vr, nvr) }
}

/// fmi3SetInt16 (FMI 3.0 Sec. 2.2): no variable of the units is Int16, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt16(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *const fmi3Int16,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetInt16", allowed::SET_OTHER, "Int16", vr, nvr) }
}

/// fmi3GetUInt16 (FMI 3.0 Sec. 2.2): no variable of the units is UInt16, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt16(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *mut fmi3UInt16,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetUInt16", allowed::GET, "UInt16", vr, nvr) }
}

/// fmi3SetUInt16 (FMI 3.0 Sec. 2.2): no variable of the units is UInt16, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt16(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *const fmi3UInt16,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetUInt16", allowed::SET_OTHER, "UInt16", vr, nvr) }
}

/// fmi3GetUInt32 (FMI 3.0 Sec. 2.2): no variable of the units is UInt32, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt32(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *mut fmi3UInt32,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetUInt32", allowed::GET, "UInt32", vr, nvr) }
}

/// fmi3SetUInt32 (FMI 3.0 Sec. 2.2): no variable of the units is UInt32, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt32(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *const fmi3UInt32,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetUInt32", allowed::SET_OTHER, "UInt32", vr, nvr) }
}

/// fmi3GetInt64 (FMI 3.0 Sec. 2.2): no variable of the units is Int64, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *mut fmi3Int64,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetInt64", allowed::GET, "Int64", vr, nvr) }
}

/// fmi3SetInt64 (FMI 3.0 Sec. 2.2): no variable of the units is Int64, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *const fmi3Int64,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetInt64", allowed::SET_OTHER, "Int64", vr, nvr) }
}

/// fmi3GetUInt64 (FMI 3.0 Sec. 2.2): no variable of the units is UInt64, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetUInt64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *mut fmi3UInt64,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetUInt64", allowed::GET, "UInt64", vr, nvr) }
}

/// fmi3SetUInt64 (FMI 3.0 Sec. 2.2): no variable of the units is UInt64, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetUInt64(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _values: *const fmi3UInt64,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetUInt64", allowed::SET_OTHER, "UInt64", vr, nvr) }
}

/// fmi3GetBinary (FMI 3.0 Sec. 2.2): no variable of the units is Binary, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetBinary(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _valueSizes: *mut usize,
    _values: *mut fmi3Binary,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetBinary", allowed::GET, "Binary", vr, nvr) }
}

/// fmi3SetBinary (FMI 3.0 Sec. 2.2): no variable of the units is Binary, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetBinary(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    nvr: usize,
    _valueSizes: *const usize,
    _values: *const fmi3Binary,
    _nValues: usize,
) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetBinary", allowed::SET_OTHER, "Binary", vr, nvr) }
}

/// fmi3GetClock (FMI 3.0 Sec. 2.2): no variable of the units is a Clock, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3GetFloat64.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetClock(c: fmi3Instance, vr: *const fmi3ValueReference, nvr: usize, _values: *mut fmi3Clock) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3GetClock", allowed::GET, "Clock", vr, nvr) }
}

/// fmi3SetClock (FMI 3.0 Sec. 2.2): no variable of the units is a Clock, so with no value references it does
/// nothing, and any reference is refused with the type its variable has. Allowed in the modes of
/// fmi3SetInt32.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetClock(c: fmi3Instance, vr: *const fmi3ValueReference, nvr: usize, _values: *const fmi3Clock) -> fmi3Status {
    // SAFETY: the host's arguments of this FMI function, passed on as they came.
    unsafe { other_type(c, "fmi3SetClock", allowed::SET_OTHER, "Clock", vr, nvr) }
}

// ---------------------------------------------------------------------------------------------------
// Variable dependencies, derivatives, configuration, clocks: optional parts the units do not offer

/// A refusal that names the capability the model description leaves out.
fn unsupported(c: fmi3Instance, function: &'static str, why: &'static str) -> fmi3Status {
    call(c, function, allowed::ANY_LIVE, |_| error(format!("{function} is not supported ({why})")))
}

/// `unsupported` for a Co-Simulation function: on a Model Exchange instance it is refused as such.
fn unsupported_cs(c: fmi3Instance, function: &'static str, why: &'static str) -> fmi3Status {
    cs(c, function, allowed::ANY_LIVE, |_| error(format!("{function} is not supported ({why})")))
}

/// fmi3GetNumberOfVariableDependencies (FMI 3.0 Sec. 2.2) is not supported (providesPerElementDependencies
/// is false): always fmi3Error, with that reason in the log.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(
    c: fmi3Instance,
    _valueReference: fmi3ValueReference,
    _nDependencies: *mut usize,
) -> fmi3Status {
    unsupported(c, "fmi3GetNumberOfVariableDependencies", "providesPerElementDependencies is false; ModelStructure lists the unknowns")
}

/// fmi3GetVariableDependencies (FMI 3.0 Sec. 2.2) is not supported (providesPerElementDependencies is
/// false): always fmi3Error, with that reason in the log.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetVariableDependencies(
    c: fmi3Instance,
    _dependent: fmi3ValueReference,
    _elementIndicesOfDependent: *mut usize,
    _independents: *mut fmi3ValueReference,
    _elementIndicesOfIndependents: *mut usize,
    _dependencyKinds: *mut fmi3DependencyKind,
    _nDependencies: usize,
) -> fmi3Status {
    unsupported(c, "fmi3GetVariableDependencies", "providesPerElementDependencies is false; ModelStructure lists the unknowns")
}

/// fmi3GetDirectionalDerivative (FMI 3.0 Sec. 2.2) is not supported (providesDirectionalDerivatives is
/// false): always fmi3Error, with that reason in the log.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetDirectionalDerivative(
    c: fmi3Instance,
    _unknowns: *const fmi3ValueReference,
    _nUnknowns: usize,
    _knowns: *const fmi3ValueReference,
    _nKnowns: usize,
    _seed: *const fmi3Float64,
    _nSeed: usize,
    _sensitivity: *mut fmi3Float64,
    _nSensitivity: usize,
) -> fmi3Status {
    unsupported(c, "fmi3GetDirectionalDerivative", "providesDirectionalDerivatives is false")
}

/// fmi3GetAdjointDerivative (FMI 3.0 Sec. 2.2) is not supported (providesAdjointDerivatives is false):
/// always fmi3Error, with that reason in the log.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetAdjointDerivative(
    c: fmi3Instance,
    _unknowns: *const fmi3ValueReference,
    _nUnknowns: usize,
    _knowns: *const fmi3ValueReference,
    _nKnowns: usize,
    _seed: *const fmi3Float64,
    _nSeed: usize,
    _sensitivity: *mut fmi3Float64,
    _nSensitivity: usize,
) -> fmi3Status {
    unsupported(c, "fmi3GetAdjointDerivative", "providesAdjointDerivatives is false")
}

/// fmi3EnterConfigurationMode (FMI 3.0 Sec. 2.3.2) is not supported, since the units have no structural
/// parameters: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterConfigurationMode(c: fmi3Instance) -> fmi3Status {
    unsupported(c, "fmi3EnterConfigurationMode", "the units have no structural parameters")
}

/// fmi3ExitConfigurationMode (FMI 3.0 Sec. 2.3.6) is not supported, since the units have no structural
/// parameters: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3ExitConfigurationMode(c: fmi3Instance) -> fmi3Status {
    unsupported(c, "fmi3ExitConfigurationMode", "the units have no structural parameters")
}

const NO_CLOCKS: &str = "the units have no clocks";

/// fmi3GetIntervalDecimal (FMI 3.0 Sec. 2.2) is not supported, since the units have no clocks: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetIntervalDecimal(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _nvr: usize,
    _intervals: *mut fmi3Float64,
    _qualifiers: *mut fmi3IntervalQualifier,
) -> fmi3Status {
    unsupported(c, "fmi3GetIntervalDecimal", NO_CLOCKS)
}

/// fmi3GetIntervalFraction (FMI 3.0 Sec. 2.2) is not supported, since the units have no clocks: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetIntervalFraction(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _nvr: usize,
    _counters: *mut fmi3UInt64,
    _resolutions: *mut fmi3UInt64,
    _qualifiers: *mut fmi3IntervalQualifier,
) -> fmi3Status {
    unsupported(c, "fmi3GetIntervalFraction", NO_CLOCKS)
}

/// fmi3GetShiftDecimal (FMI 3.0 Sec. 2.2) is not supported, since the units have no clocks: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetShiftDecimal(c: fmi3Instance, _vr: *const fmi3ValueReference, _nvr: usize, _shifts: *mut fmi3Float64) -> fmi3Status {
    unsupported(c, "fmi3GetShiftDecimal", NO_CLOCKS)
}

/// fmi3GetShiftFraction (FMI 3.0 Sec. 2.2) is not supported, since the units have no clocks: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetShiftFraction(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _nvr: usize,
    _counters: *mut fmi3UInt64,
    _resolutions: *mut fmi3UInt64,
) -> fmi3Status {
    unsupported(c, "fmi3GetShiftFraction", NO_CLOCKS)
}

/// fmi3SetIntervalDecimal (FMI 3.0 Sec. 2.2) is not supported, since the units have no clocks: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetIntervalDecimal(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _nvr: usize,
    _intervals: *const fmi3Float64,
) -> fmi3Status {
    unsupported(c, "fmi3SetIntervalDecimal", NO_CLOCKS)
}

/// fmi3SetIntervalFraction (FMI 3.0 Sec. 2.2) is not supported, since the units have no clocks: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetIntervalFraction(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _nvr: usize,
    _counters: *const fmi3UInt64,
    _resolutions: *const fmi3UInt64,
) -> fmi3Status {
    unsupported(c, "fmi3SetIntervalFraction", NO_CLOCKS)
}

/// fmi3SetShiftDecimal (FMI 3.0 Sec. 2.2) is not supported, since the units have no clocks: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetShiftDecimal(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _nvr: usize,
    _shifts: *const fmi3Float64,
) -> fmi3Status {
    unsupported(c, "fmi3SetShiftDecimal", NO_CLOCKS)
}

/// fmi3SetShiftFraction (FMI 3.0 Sec. 2.2) is not supported, since the units have no clocks: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetShiftFraction(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _nvr: usize,
    _counters: *const fmi3UInt64,
    _resolutions: *const fmi3UInt64,
) -> fmi3Status {
    unsupported(c, "fmi3SetShiftFraction", NO_CLOCKS)
}

/// fmi3ActivateModelPartition (FMI 3.0 Sec. 5.2.1) is not supported, since the units offer no Scheduled
/// Execution: always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3ActivateModelPartition(
    c: fmi3Instance,
    _clockReference: fmi3ValueReference,
    _activationTime: fmi3Float64,
) -> fmi3Status {
    unsupported(c, "fmi3ActivateModelPartition", "the units offer no Scheduled Execution")
}

/// fmi3EvaluateDiscreteStates (FMI 3.0 Sec. 2.3.5) is not supported (providesEvaluateDiscreteStates is
/// false): always fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(c: fmi3Instance) -> fmi3Status {
    unsupported(c, "fmi3EvaluateDiscreteStates", "providesEvaluateDiscreteStates is false")
}

/// fmi3GetOutputDerivatives (FMI 3.0 Sec. 4.1.2) is not supported (maxOutputDerivativeOrder is 0): always
/// fmi3Error, and on a Model Exchange instance refused as a Co-Simulation function.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetOutputDerivatives(
    c: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _nvr: usize,
    _orders: *const fmi3Int32,
    _values: *mut fmi3Float64,
    _nValues: usize,
) -> fmi3Status {
    unsupported_cs(c, "fmi3GetOutputDerivatives", "maxOutputDerivativeOrder is 0")
}

// ---------------------------------------------------------------------------------------------------
// FMU state: get, set, free, serialize (the bytes of `crate::fmi::state_format`, tied to the FMI 3.0 token)

/// Saves the instance (values, mode, times and the model's state) into `*FMUState`: into the state already
/// there if it is a live state of this library, else into a new one. fmi3GetFMUState (FMI 3.0 Sec. 2.2),
/// allowed in every state but Fatal and Intermediate Update Mode; a model that cannot save itself gives
/// fmi3Error.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetFMUState(c: fmi3Instance, FMUState: *mut fmi3FMUState) -> fmi3Status {
    const F: &str = "fmi3GetFMUState";
    // SAFETY: the host's output argument (`state_calls::get` checks NULL).
    call(c, F, allowed::ANY_LIVE, |inst| unsafe { state_calls::get(&STATES, inst, FMUState, F, "FMUState") })
}

/// Restores the instance from a live FMI 3.0 state of this library: fmi3SetFMUState (FMI 3.0 Sec. 2.2), also
/// a way out of the Error state. A freed or foreign pointer (an FMI 2.0 state included), or a state of
/// another unit or of the other interface, is refused and the instance left as it was.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetFMUState(c: fmi3Instance, FMUState: fmi3FMUState) -> fmi3Status {
    call(c, "fmi3SetFMUState", allowed::ANY_LIVE, |inst| state_calls::set(&STATES, inst, FMUState, "fmi3SetFMUState"))
}

/// Frees the state `*FMUState` and sets `*FMUState` to NULL; a NULL `*FMUState` is nothing to free.
/// fmi3FreeFMUState (FMI 3.0 Sec. 2.2). A state passed itself instead of its address is freed too, with a
/// warning in the log, and the call still returns fmi3OK; a `*FMUState` that is not live is refused.
#[no_mangle]
pub unsafe extern "C" fn fmi3FreeFMUState(c: fmi3Instance, FMUState: *mut fmi3FMUState) -> fmi3Status {
    // SAFETY: the host's argument, as `state_calls::free` requires.
    call(c, "fmi3FreeFMUState", allowed::ANY_LIVE, |inst| unsafe { state_calls::free(&STATES, inst, FMUState, "fmi3FreeFMUState", "FMUState") })
}

/// The number of bytes of a live state into `*size`: fmi3SerializedFMUStateSize (FMI 3.0 Sec. 2.2).
#[no_mangle]
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(c: fmi3Instance, FMUState: fmi3FMUState, size: *mut usize) -> fmi3Status {
    const F: &str = "fmi3SerializedFMUStateSize";
    // SAFETY: the host's output argument (NULL is refused inside).
    call(c, F, allowed::ANY_LIVE, |_| unsafe { state_calls::size(&STATES, FMUState, size, F) })
}

/// Copies the bytes of a live state into `serializedState`: fmi3SerializeFMUState (FMI 3.0 Sec. 2.2).
/// Refused when `size` is smaller than fmi3SerializedFMUStateSize gives.
#[no_mangle]
pub unsafe extern "C" fn fmi3SerializeFMUState(c: fmi3Instance, FMUState: fmi3FMUState, serializedState: *mut fmi3Byte, size: usize) -> fmi3Status {
    const F: &str = "fmi3SerializeFMUState";
    // SAFETY: the host passes an array of this length; NULL and impossible lengths are refused inside.
    call(c, F, allowed::ANY_LIVE, |_| unsafe { state_calls::serialize(&STATES, FMUState, serializedState, size, F, "fmi3SerializedFMUStateSize") })
}

/// Makes a new state from the `size` bytes at `serializedState` and puts it into `*FMUState`:
/// fmi3DeserializeFMUState (FMI 3.0 Sec. 2.2). Refused unless the bytes are a state of this unit saved
/// through FMI 3.0 (format version, checksum, model identifier and instantiationToken are checked).
#[no_mangle]
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    c: fmi3Instance,
    serializedState: *const fmi3Byte,
    size: usize,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    const F: &str = "fmi3DeserializeFMUState";
    // SAFETY: the host passes an array of this length and its output argument; NULLs are refused inside.
    call(c, F, allowed::ANY_LIVE, |inst| unsafe { state_calls::deserialize(&STATES, inst, serializedState, size, FMUState, F, "FMUState") })
}

// ---------------------------------------------------------------------------------------------------
// Event Mode (both interfaces)

/// One event iteration, in Event Mode of either interface: fmi3UpdateDiscreteStates (FMI 3.0 Sec. 2.3.5).
/// Model Exchange: the model accepts the current state as that of the event, and
/// `valuesOfContinuousStatesChanged` says whether the integrator must restart. Co-Simulation: nothing is
/// updated (the step accepted the state where it returned) and that flag is false. The other outputs are
/// false (no time event); all six output pointers are checked before anything changes.
#[no_mangle]
pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
    c: fmi3Instance,
    discreteStatesNeedUpdate: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
    nominalsOfContinuousStatesChanged: *mut fmi3Boolean,
    valuesOfContinuousStatesChanged: *mut fmi3Boolean,
    nextEventTimeDefined: *mut fmi3Boolean,
    nextEventTime: *mut fmi3Float64,
) -> fmi3Status {
    const F: &str = "fmi3UpdateDiscreteStates";
    call(c, F, allowed::NEW_DISCRETE_STATES, |inst| {
        // All outputs are checked before anything changes.
        for (p, name) in [
            (discreteStatesNeedUpdate, "discreteStatesNeedUpdate"),
            (terminateSimulation, "terminateSimulation"),
            (nominalsOfContinuousStatesChanged, "nominalsOfContinuousStatesChanged"),
            (valuesOfContinuousStatesChanged, "valuesOfContinuousStatesChanged"),
            (nextEventTimeDefined, "nextEventTimeDefined"),
        ] {
            out(p, F, name)?;
        }
        out(nextEventTime, F, "nextEventTime")?;
        // Model Exchange: the history accepts the state of the event (the accepted-branch rule). In
        // Co-Simulation the step already accepted it where it returned; inputs set in Event Mode are
        // followed at the start of the next step, as between any two steps.
        let restart = inst.kind == Kind::ModelExchange && inst.accept();
        // SAFETY: the host's output arguments, each checked non-NULL above.
        unsafe {
            *discreteStatesNeedUpdate = false;
            *terminateSimulation = false;
            *nominalsOfContinuousStatesChanged = false;
            *valuesOfContinuousStatesChanged = restart;
            *nextEventTimeDefined = false;
            *nextEventTime = 0.0;
        }
        Ok(())
    })
}

// ---------------------------------------------------------------------------------------------------
// Model Exchange

/// Moves from Event Mode to Continuous-Time Mode: fmi3EnterContinuousTimeMode (FMI 3.0 Sec. 2.3.5), Model
/// Exchange only.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterContinuousTimeMode(c: fmi3Instance) -> fmi3Status {
    me(c, "fmi3EnterContinuousTimeMode", allowed::ENTER_CONTINUOUS_TIME, |inst| {
        inst.mode = Mode::ContinuousTimeMode;
        Ok(())
    })
}

/// Tells the model an integrator step is complete. `*enterEventMode` is true when an event indicator has
/// changed sign since the last event or completed step (for example after an input set in Continuous-Time
/// Mode); `*terminateSimulation` is always false. fmi3CompletedIntegratorStep (FMI 3.0 Sec. 3.2.1), Model
/// Exchange, Continuous-Time Mode only.
#[no_mangle]
pub unsafe extern "C" fn fmi3CompletedIntegratorStep(
    c: fmi3Instance,
    _noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
    enterEventMode: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
) -> fmi3Status {
    const F: &str = "fmi3CompletedIntegratorStep";
    me(c, F, allowed::COMPLETED_INTEGRATOR_STEP, |inst| {
        out(enterEventMode, F, "enterEventMode")?;
        out(terminateSimulation, F, "terminateSimulation")?;
        // Between events the units stay on the branch of the last event; an input set in
        // Continuous-Time Mode that left it asks for Event Mode here (`Instance::completed_integrator_step`).
        let event = inst.completed_integrator_step()?;
        // SAFETY: the host's output arguments, checked non-NULL above.
        unsafe {
            *enterEventMode = event;
            *terminateSimulation = false;
        }
        Ok(())
    })
}

/// Sets the time of the instance and its model; a time that is not finite is refused. fmi3SetTime
/// (FMI 3.0 Sec. 3.2.1), Model Exchange, in Event Mode or Continuous-Time Mode.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetTime(c: fmi3Instance, time: fmi3Float64) -> fmi3Status {
    me(c, "fmi3SetTime", allowed::SET_TIME, |inst| inst.set_time(time))
}

/// Sets the model's continuous states; `nContinuousStates` must be the unit's number of states and every
/// value finite. fmi3SetContinuousStates (FMI 3.0 Sec. 3.2.1), Model Exchange, Continuous-Time Mode only.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetContinuousStates(c: fmi3Instance, continuousStates: *const fmi3Float64, nContinuousStates: usize) -> fmi3Status {
    const F: &str = "fmi3SetContinuousStates";
    me(c, F, allowed::SET_CONTINUOUS_STATES, |inst| {
        // SAFETY: the host passes an array of this length; NULL and impossible lengths are refused inside.
        let x = unsafe { slice(continuousStates, nContinuousStates, F, "continuousStates") }?;
        inst.set_continuous_states(x)
    })
}

/// The derivatives of the continuous states at the current time, states and inputs, into `derivatives`;
/// `nContinuousStates` must be the unit's number of states. fmi3GetContinuousStateDerivatives (FMI 3.0
/// Sec. 3.2.1), Model Exchange, from Initialization Mode on (also in Terminated and Error).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(c: fmi3Instance, derivatives: *mut fmi3Float64, nContinuousStates: usize) -> fmi3Status {
    const F: &str = "fmi3GetContinuousStateDerivatives";
    me(c, F, allowed::GET_DERIVATIVES, |inst| {
        // SAFETY: the host passes an array of this length; NULL and impossible lengths are refused inside.
        let dx = unsafe { slice_mut(derivatives, nContinuousStates, F, "derivatives") }?;
        inst.get_derivatives(dx)
    })
}

/// The event indicators at the current time, states and inputs, into `eventIndicators`; `nEventIndicators`
/// must be the unit's number. fmi3GetEventIndicators (FMI 3.0 Sec. 3.2.1), Model Exchange, in the modes of
/// fmi3GetContinuousStateDerivatives.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetEventIndicators(c: fmi3Instance, eventIndicators: *mut fmi3Float64, nEventIndicators: usize) -> fmi3Status {
    const F: &str = "fmi3GetEventIndicators";
    me(c, F, allowed::GET_DERIVATIVES, |inst| {
        // SAFETY: the host passes an array of this length; NULL and impossible lengths are refused inside.
        let z = unsafe { slice_mut(eventIndicators, nEventIndicators, F, "eventIndicators") }?;
        inst.get_event_indicators(z)
    })
}

/// The model's continuous states into `continuousStates`; `nContinuousStates` must be the unit's number of
/// states. fmi3GetContinuousStates (FMI 3.0 Sec. 2.3.3), Model Exchange, in the modes of
/// fmi3GetContinuousStateDerivatives.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetContinuousStates(c: fmi3Instance, continuousStates: *mut fmi3Float64, nContinuousStates: usize) -> fmi3Status {
    const F: &str = "fmi3GetContinuousStates";
    me(c, F, allowed::GET_DERIVATIVES, |inst| {
        // SAFETY: the host passes an array of this length; NULL and impossible lengths are refused inside.
        let x = unsafe { slice_mut(continuousStates, nContinuousStates, F, "continuousStates") }?;
        inst.get_continuous_states(x)
    })
}

/// The nominal values of the continuous states into `nominals`: 1.0 each until the model's initial state is
/// built. fmi3GetNominalsOfContinuousStates (FMI 3.0 Sec. 2.3.3), Model Exchange, from Instantiated on (also
/// in Terminated and Error).
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(c: fmi3Instance, nominals: *mut fmi3Float64, nContinuousStates: usize) -> fmi3Status {
    const F: &str = "fmi3GetNominalsOfContinuousStates";
    me(c, F, allowed::GET_NOMINALS, |inst| {
        // SAFETY: the host passes an array of this length; NULL and impossible lengths are refused inside.
        let x = unsafe { slice_mut(nominals, nContinuousStates, F, "nominals") }?;
        inst.get_nominals(x)
    })
}

/// The unit's number of event indicators into `*nEventIndicators`: fmi3GetNumberOfEventIndicators
/// (FMI 3.0 Sec. 2.3.2), Model Exchange, in every state but Fatal.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(c: fmi3Instance, nEventIndicators: *mut usize) -> fmi3Status {
    const F: &str = "fmi3GetNumberOfEventIndicators";
    // SAFETY: the host's output argument; NULL is refused inside.
    me(c, F, allowed::ANY_LIVE, |inst| unsafe { put(nEventIndicators, inst.unit.n_event_indicators, F, "nEventIndicators") })
}

/// The unit's number of continuous states into `*nContinuousStates`: fmi3GetNumberOfContinuousStates
/// (FMI 3.0 Sec. 2.3.2), Model Exchange, in every state but Fatal.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(c: fmi3Instance, nContinuousStates: *mut usize) -> fmi3Status {
    const F: &str = "fmi3GetNumberOfContinuousStates";
    // SAFETY: the host's output argument; NULL is refused inside.
    me(c, F, allowed::ANY_LIVE, |inst| unsafe { put(nContinuousStates, inst.unit.n_states, F, "nContinuousStates") })
}

// ---------------------------------------------------------------------------------------------------
// Co-Simulation

/// Moves from Event Mode to Step Mode: fmi3EnterStepMode (FMI 3.0 Sec. 2.3.5), Co-Simulation only.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterStepMode(c: fmi3Instance) -> fmi3Status {
    cs(c, "fmi3EnterStepMode", allowed::ENTER_STEP_MODE, |inst| {
        inst.mode = Mode::StepComplete;
        Ok(())
    })
}

/// A step of at most `communicationStepSize`, in pieces that end at the contact events inside it (a unit
/// with `returns_early`). At each event the master's intermediate-update callback, if it gave one, hears
/// of it and may read the outputs there (Intermediate Update Mode) and, with earlyReturnAllowed, ask the
/// step to end; without a callback, earlyReturnAllowed ends the step at the first event. `earlyReturn`
/// and `lastSuccessfulTime` say where the step ended; with eventModeUsed `eventHandlingNeeded` asks the
/// master into Event Mode there. The callback calls back into this library, so no borrow of the instance
/// is held while it runs: each piece is its own `call_on`.
#[no_mangle]
pub unsafe extern "C" fn fmi3DoStep(
    c: fmi3Instance,
    currentCommunicationPoint: fmi3Float64,
    communicationStepSize: fmi3Float64,
    _noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
    eventHandlingNeeded: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
    earlyReturn: *mut fmi3Boolean,
    lastSuccessfulTime: *mut fmi3Float64,
) -> fmi3Status {
    const F: &str = "fmi3DoStep";
    let end = currentCommunicationPoint + communicationStepSize;
    let mut from = currentCommunicationPoint;
    let mut first = true;
    loop {
        // One piece: from `from` to the step's end or the next event. What the rest of the loop needs.
        let mut piece = None;
        let status = cs(c, F, allowed::DO_STEP, |inst| {
            out(eventHandlingNeeded, F, "eventHandlingNeeded")?;
            out(terminateSimulation, F, "terminateSimulation")?;
            out(earlyReturn, F, "earlyReturn")?;
            out(lastSuccessfulTime, F, "lastSuccessfulTime")?;
            // The first piece is the master's step as given (bit for bit the step of a run without events).
            let h = if first { communicationStepSize } else { end - from };
            let callback = inst.abi.as_ref().and_then(|a| a.downcast_ref::<fmi3IntermediateUpdateCallback>()).copied().flatten();
            let result = inst.step(from, h, inst.early_return_allowed || callback.is_some());
            let event = result.as_ref().ok().copied().flatten();
            piece = Some((event, callback, inst.logger.environment, inst.early_return_allowed, inst.event_mode_used, inst.time));
            result.map(|_| ())
        });
        let Some((event, callback, environment, early_allowed, event_mode, time)) = piece else { return status };
        // A piece that ended at an event: before the step's end it is an early return; at the end the step
        // is complete, and with Event Mode the master is asked to handle the event there too.
        let finish = |at_event: bool| {
            // SAFETY: the host's output arguments, checked non-NULL in the piece above.
            unsafe {
                *eventHandlingNeeded = at_event && event_mode;
                *terminateSimulation = false;
                *earlyReturn = at_event && end - time > 4.0 * f64::EPSILON * end.abs();
                *lastSuccessfulTime = time;
            }
            status
        };
        if status != fmi3OK {
            return finish(false);
        }
        let Some(t_event) = event else { return finish(false) };
        if !(t_event > from) {
            // The integrators report only events after a piece's start; a master must never be handed a
            // step that ends where it began.
            return fmi3Error;
        }
        let Some(update) = callback else { return finish(true) };
        // The master hears of the event, reads the outputs there if it likes, and may end the step.
        if cs(c, F, allowed::DO_STEP, |inst| {
            inst.mode = Mode::IntermediateUpdate;
            Ok(())
        }) != fmi3OK
        {
            return fmi3Error;
        }
        // A C bool the host writes: read as a byte, so that a host writing another value than 0 or 1
        // cannot make an invalid Rust bool.
        let (mut requested, mut requested_time) = (0u8, t_event);
        // SAFETY: the host's callback with the arguments FMI 3.0 Sec. 4.2.2 gives it; no borrow of the
        // instance is held across it; `requested` is one byte, as a C bool.
        unsafe { update(environment, t_event, false, true, true, early_allowed, (&mut requested as *mut u8).cast(), &mut requested_time) };
        // Back to Step Mode; an instance the master freed or broke meanwhile is refused here.
        let back = ffi::call_on(&INSTANCES, c, F, Some(Kind::CoSimulation), allowed::INTERMEDIATE_UPDATE, |inst| {
            inst.mode = Mode::StepComplete;
            Ok(())
        });
        if back != Status::Ok {
            return back as fmi3Status;
        }
        let at_end = !(end - t_event > 4.0 * f64::EPSILON * end.abs());
        if (early_allowed && requested != 0) || at_end {
            return finish(true);
        }
        from = t_event;
        first = false;
    }
}
