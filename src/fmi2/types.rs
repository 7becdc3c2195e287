//! The C types of the FMI 2.0 headers (fmi2TypesPlatform.h, fmi2FunctionTypes.h), by hand. A test
//! (`tests/fmi2_headers.rs`) compiles our exported signatures against the official headers.

#![allow(non_camel_case_types, non_snake_case, non_upper_case_globals)]

use std::os::raw::{c_char, c_int, c_uint, c_void};

/// fmi2Component: a C `void*`, the instance handed to the host.
pub type fmi2Component = *mut c_void;
/// fmi2ComponentEnvironment: a C `void*` of the host's, handed back to its callbacks.
pub type fmi2ComponentEnvironment = *mut c_void;
/// fmi2FMUstate: a C `void*`, a saved FMU state.
pub type fmi2FMUstate = *mut c_void;
/// fmi2ValueReference: a C `unsigned int`, the handle of a variable.
pub type fmi2ValueReference = c_uint;
/// fmi2Real: a C `double`.
pub type fmi2Real = f64;
/// fmi2Integer: a C `int`.
pub type fmi2Integer = c_int;
/// fmi2Boolean: a C `int`, fmi2True or fmi2False.
pub type fmi2Boolean = c_int;
/// fmi2Char: a C `char`.
pub type fmi2Char = c_char;
/// fmi2String: a C `const fmi2Char*`, a NUL-terminated string.
pub type fmi2String = *const fmi2Char;
/// fmi2Byte: a C `char`, one byte of a serialized FMU state.
pub type fmi2Byte = c_char;

/// fmi2True: 1.
pub const fmi2True: fmi2Boolean = 1;
/// fmi2False: 0.
pub const fmi2False: fmi2Boolean = 0;

/// fmi2Status (a C enum: int-sized).
pub type fmi2Status = c_int;
/// fmi2OK: all well.
pub const fmi2OK: fmi2Status = 0;
/// fmi2Warning: things are not quite right, but the computation can continue.
pub const fmi2Warning: fmi2Status = 1;
/// fmi2Discard: the call did not succeed, but the simulation may go on in another way (a smaller step, for
/// example); only for the functions the standard names.
pub const fmi2Discard: fmi2Status = 2;
/// fmi2Error: the call failed; the instance cannot continue unless a saved state is restored or it is
/// reset or freed. Other instances are not affected.
pub const fmi2Error: fmi2Status = 3;
/// fmi2Fatal: the computations of all instances are irreparably corrupted; no further call is allowed.
pub const fmi2Fatal: fmi2Status = 4;
/// fmi2Pending: an asynchronous fmi2DoStep is still running (Co-Simulation only).
pub const fmi2Pending: fmi2Status = 5;

/// fmi2Type.
pub type fmi2Type = c_int;
/// fmi2ModelExchange: an instance for Model Exchange.
pub const fmi2ModelExchange: fmi2Type = 0;
/// fmi2CoSimulation: an instance for Co-Simulation.
pub const fmi2CoSimulation: fmi2Type = 1;

/// fmi2StatusKind.
pub type fmi2StatusKind = c_int;
/// fmi2DoStepStatus: the fmi2Status of an asynchronous fmi2DoStep (fmi2GetStatus).
pub const fmi2DoStepStatus: fmi2StatusKind = 0;
/// fmi2PendingStatus: a string on the progress of an asynchronous fmi2DoStep (fmi2GetStringStatus).
pub const fmi2PendingStatus: fmi2StatusKind = 1;
/// fmi2LastSuccessfulTime: the end time of the last completed communication step (fmi2GetRealStatus).
pub const fmi2LastSuccessfulTime: fmi2StatusKind = 2;
/// fmi2Terminated: whether the slave wants to end the simulation (fmi2GetBooleanStatus).
pub const fmi2Terminated: fmi2StatusKind = 3;

/// fmi2CallbackLogger: the host's logger (environment, instance name, status, category, printf-style
/// message and its arguments); None is a NULL pointer.
pub type fmi2CallbackLogger = Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...)>;
/// fmi2CallbackAllocateMemory: the host's `calloc`-like allocator (count, size); None is a NULL pointer.
pub type fmi2CallbackAllocateMemory = Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>;
/// fmi2CallbackFreeMemory: the host's function that frees what fmi2CallbackAllocateMemory gave; None is a
/// NULL pointer.
pub type fmi2CallbackFreeMemory = Option<unsafe extern "C" fn(*mut c_void)>;
/// fmi2StepFinished: the host's callback for the end of an asynchronous fmi2DoStep; None is a NULL pointer.
pub type fmi2StepFinished = Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>;

/// fmi2CallbackFunctions: the callbacks the host passes to fmi2Instantiate (C struct layout).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct fmi2CallbackFunctions {
    /// Where the instance's messages go.
    pub logger: fmi2CallbackLogger,
    /// The host's allocator.
    pub allocateMemory: fmi2CallbackAllocateMemory,
    /// The host's deallocator.
    pub freeMemory: fmi2CallbackFreeMemory,
    /// Called at the end of an asynchronous fmi2DoStep.
    pub stepFinished: fmi2StepFinished,
    /// Passed back as the first argument of `logger` and `stepFinished`.
    pub componentEnvironment: fmi2ComponentEnvironment,
}

/// fmi2EventInfo: what fmi2NewDiscreteStates reports (C struct layout).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct fmi2EventInfo {
    /// Another fmi2NewDiscreteStates is needed: the event iteration has not converged.
    pub newDiscreteStatesNeeded: fmi2Boolean,
    /// The model asks to end the simulation.
    pub terminateSimulation: fmi2Boolean,
    /// The nominal values of the continuous states changed (read them again).
    pub nominalsOfContinuousStatesChanged: fmi2Boolean,
    /// The values of the continuous states changed (read them again; the integrator restarts).
    pub valuesOfContinuousStatesChanged: fmi2Boolean,
    /// `nextEventTime` holds the time of the next time event.
    pub nextEventTimeDefined: fmi2Boolean,
    /// The time of the next time event, if `nextEventTimeDefined`.
    pub nextEventTime: fmi2Real,
}
