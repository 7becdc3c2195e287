//! The C types of the FMI 3.0 headers (fmi3PlatformTypes.h, fmi3FunctionTypes.h), by hand. A test
//! (`tests/fmi3_headers.rs`) compiles our exported signatures against the official headers.
//! fmi3Boolean is C's `bool` (one byte), not an int as in FMI 2.0.

#![allow(non_camel_case_types, non_snake_case, non_upper_case_globals)]

use std::os::raw::{c_char, c_int, c_void};

/// fmi3Instance: a C `void*`, the instance handed to the host.
pub type fmi3Instance = *mut c_void;
/// fmi3InstanceEnvironment: a C `void*` of the host's, handed back to its callbacks.
pub type fmi3InstanceEnvironment = *mut c_void;
/// fmi3FMUState: a C `void*`, a saved FMU state.
pub type fmi3FMUState = *mut c_void;
/// fmi3ValueReference: a C `uint32_t`, the handle of a variable.
pub type fmi3ValueReference = u32;
/// fmi3Float32: a C `float`.
pub type fmi3Float32 = f32;
/// fmi3Float64: a C `double`.
pub type fmi3Float64 = f64;
/// fmi3Int8: a C `int8_t`.
pub type fmi3Int8 = i8;
/// fmi3UInt8: a C `uint8_t`.
pub type fmi3UInt8 = u8;
/// fmi3Int16: a C `int16_t`.
pub type fmi3Int16 = i16;
/// fmi3UInt16: a C `uint16_t`.
pub type fmi3UInt16 = u16;
/// fmi3Int32: a C `int32_t`.
pub type fmi3Int32 = i32;
/// fmi3UInt32: a C `uint32_t`.
pub type fmi3UInt32 = u32;
/// fmi3Int64: a C `int64_t`.
pub type fmi3Int64 = i64;
/// fmi3UInt64: a C `uint64_t`.
pub type fmi3UInt64 = u64;
/// fmi3Boolean: a C `bool` (one byte).
pub type fmi3Boolean = bool;
/// fmi3Char: a C `char`.
pub type fmi3Char = c_char;
/// fmi3String: a C `const fmi3Char*`, a NUL-terminated string.
pub type fmi3String = *const fmi3Char;
/// fmi3Byte: a C `uint8_t`.
pub type fmi3Byte = u8;
/// fmi3Binary: a C `const fmi3Byte*`, binary data.
pub type fmi3Binary = *const fmi3Byte;
/// fmi3Clock: a C `bool`, whether a clock is active.
pub type fmi3Clock = bool;

/// fmi3Status (a C enum: int-sized).
pub type fmi3Status = c_int;
/// fmi3OK: the call succeeded; the outputs are defined.
pub const fmi3OK: fmi3Status = 0;
/// fmi3Warning: a non-critical problem; the outputs are defined and the computation may continue.
pub const fmi3Warning: fmi3Status = 1;
/// fmi3Discard: the call did not succeed and the FMU is as before it; the outputs are undefined, but the
/// simulation may go on in another way.
pub const fmi3Discard: fmi3Status = 2;
/// fmi3Error: the call failed; the outputs are undefined and the instance cannot continue unless a saved
/// state is restored or it is reset or freed. Other instances are not affected.
pub const fmi3Error: fmi3Status = 3;
/// fmi3Fatal: the state of all instances is irreparably corrupted; no further call is allowed.
pub const fmi3Fatal: fmi3Status = 4;

/// fmi3DependencyKind: a C enum (int-sized), how an output depends on an input.
pub type fmi3DependencyKind = c_int;
/// fmi3IntervalQualifier: a C enum (int-sized), how a clock's interval is known.
pub type fmi3IntervalQualifier = c_int;

/// fmi3LogMessageCallback: the host's logger (environment, status, category, message); None is a NULL pointer.
pub type fmi3LogMessageCallback = Option<unsafe extern "C" fn(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String)>;
/// fmi3ClockUpdateCallback: the host's callback for a clock activated by the FMU (Scheduled Execution); None
/// is a NULL pointer.
pub type fmi3ClockUpdateCallback = Option<unsafe extern "C" fn(fmi3InstanceEnvironment)>;
/// fmi3IntermediateUpdateCallback: the master's callback at an intermediate point of fmi3DoStep
/// (environment, intermediateUpdateTime, intermediateVariableSetRequested, intermediateVariableGetAllowed,
/// intermediateStepFinished, canReturnEarly, and the outputs earlyReturnRequested and earlyReturnTime);
/// None is a NULL pointer.
pub type fmi3IntermediateUpdateCallback = Option<
    unsafe extern "C" fn(
        fmi3InstanceEnvironment,
        fmi3Float64,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        *mut fmi3Boolean,
        *mut fmi3Float64,
    ),
>;
/// fmi3LockPreemptionCallback: the host's function that locks out preemption (Scheduled Execution); None is
/// a NULL pointer.
pub type fmi3LockPreemptionCallback = Option<unsafe extern "C" fn()>;
/// fmi3UnlockPreemptionCallback: the host's function that allows preemption again (Scheduled Execution);
/// None is a NULL pointer.
pub type fmi3UnlockPreemptionCallback = Option<unsafe extern "C" fn()>;
