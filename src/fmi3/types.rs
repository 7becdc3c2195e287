//! The C types of the FMI 3.0 headers (fmi3PlatformTypes.h, fmi3FunctionTypes.h), by hand. A test
//! (`tests/fmi3_headers.rs`) compiles our exported signatures against the official headers.
//! fmi3Boolean is C's `bool` (one byte), not an int as in FMI 2.0.

#![allow(non_camel_case_types, non_snake_case, non_upper_case_globals)]

use std::os::raw::{c_char, c_int, c_void};

pub type fmi3Instance = *mut c_void;
pub type fmi3InstanceEnvironment = *mut c_void;
pub type fmi3FMUState = *mut c_void;
pub type fmi3ValueReference = u32;
pub type fmi3Float32 = f32;
pub type fmi3Float64 = f64;
pub type fmi3Int8 = i8;
pub type fmi3UInt8 = u8;
pub type fmi3Int16 = i16;
pub type fmi3UInt16 = u16;
pub type fmi3Int32 = i32;
pub type fmi3UInt32 = u32;
pub type fmi3Int64 = i64;
pub type fmi3UInt64 = u64;
pub type fmi3Boolean = bool;
pub type fmi3Char = c_char;
pub type fmi3String = *const fmi3Char;
pub type fmi3Byte = u8;
pub type fmi3Binary = *const fmi3Byte;
pub type fmi3Clock = bool;

/// fmi3Status (a C enum: int-sized).
pub type fmi3Status = c_int;
pub const fmi3OK: fmi3Status = 0;
pub const fmi3Warning: fmi3Status = 1;
pub const fmi3Discard: fmi3Status = 2;
pub const fmi3Error: fmi3Status = 3;
pub const fmi3Fatal: fmi3Status = 4;

/// fmi3DependencyKind and fmi3IntervalQualifier (C enums).
pub type fmi3DependencyKind = c_int;
pub type fmi3IntervalQualifier = c_int;

pub type fmi3LogMessageCallback = Option<unsafe extern "C" fn(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String)>;
pub type fmi3ClockUpdateCallback = Option<unsafe extern "C" fn(fmi3InstanceEnvironment)>;
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
pub type fmi3LockPreemptionCallback = Option<unsafe extern "C" fn()>;
pub type fmi3UnlockPreemptionCallback = Option<unsafe extern "C" fn()>;
