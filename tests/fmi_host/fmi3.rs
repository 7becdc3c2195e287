//! The FMI 3.0 side of the test host: instantiation through the `fmi3*` exports of the same cdylib, a
//! non-variadic logger (FMI 3.0's), and typed get and set by variable name.

use super::{Comp, Log};
use libloading::{Library, Symbol};
use powderfmu::fmi3::types::*;
use powderfmu::units;
use std::ffi::{c_void, CStr, CString};

/// FMI 3.0's logger: (environment, status, category, message).
pub unsafe extern "C" fn logger3(env: fmi3InstanceEnvironment, status: fmi3Status, category: fmi3String, message: fmi3String) {
    let log = &*(env as *const Log);
    log.lock().unwrap().push((
        status,
        CStr::from_ptr(category).to_string_lossy().into_owned(),
        CStr::from_ptr(message).to_string_lossy().into_owned(),
    ));
}

pub type InstantiateCs = unsafe extern "C" fn(
    fmi3String,
    fmi3String,
    fmi3String,
    fmi3Boolean,
    fmi3Boolean,
    fmi3Boolean,
    fmi3Boolean,
    *const fmi3ValueReference,
    usize,
    fmi3InstanceEnvironment,
    fmi3LogMessageCallback,
    fmi3IntermediateUpdateCallback,
) -> Comp;
pub type InstantiateMe =
    unsafe extern "C" fn(fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean, fmi3InstanceEnvironment, fmi3LogMessageCallback) -> Comp;
pub type EnterInit = unsafe extern "C" fn(Comp, fmi3Boolean, fmi3Float64, fmi3Float64, fmi3Boolean, fmi3Float64) -> fmi3Status;
pub type GetF64 = unsafe extern "C" fn(Comp, *const fmi3ValueReference, usize, *mut fmi3Float64, usize) -> fmi3Status;
pub type SetF64 = unsafe extern "C" fn(Comp, *const fmi3ValueReference, usize, *const fmi3Float64, usize) -> fmi3Status;
pub type DoStep3 = unsafe extern "C" fn(
    Comp,
    fmi3Float64,
    fmi3Float64,
    fmi3Boolean,
    *mut fmi3Boolean,
    *mut fmi3Boolean,
    *mut fmi3Boolean,
    *mut fmi3Float64,
) -> fmi3Status;

pub struct Api3<'a> {
    pub lib: &'a Library,
}

impl Api3<'_> {
    pub fn sym<T>(&self, name: &[u8]) -> Symbol<'_, T> {
        // SAFETY: the caller names the symbol's FMI 3.0 type (checked against the headers by fmi3_headers.rs).
        unsafe { self.lib.get(name) }.unwrap_or_else(|_| panic!("an exported {}", String::from_utf8_lossy(name)))
    }

    /// A Co-Simulation instance (eventModeUsed, earlyReturnAllowed as given) or, with `me`, Model Exchange.
    pub fn instantiate(&self, unit: &str, me: bool, event_mode: bool, early_return: bool, log: &Log) -> Comp {
        let u = units::by_identifier(unit).unwrap();
        let name = CString::new("importer3").unwrap();
        let token = CString::new(u.instantiation_token()).unwrap();
        let env = log as *const Log as *mut c_void;
        unsafe {
            if me {
                self.sym::<InstantiateMe>(b"fmi3InstantiateModelExchange")(
                    name.as_ptr(),
                    token.as_ptr(),
                    std::ptr::null(),
                    false,
                    false,
                    env,
                    Some(logger3),
                )
            } else {
                self.sym::<InstantiateCs>(b"fmi3InstantiateCoSimulation")(
                    name.as_ptr(),
                    token.as_ptr(),
                    std::ptr::null(),
                    false,
                    false,
                    event_mode,
                    early_return,
                    std::ptr::null(),
                    0,
                    env,
                    Some(logger3),
                    None,
                )
            }
        }
    }

    pub fn vr(unit: &str, name: &str) -> fmi3ValueReference {
        units::by_identifier(unit).unwrap().vr(name).expect("a variable of the unit") as fmi3ValueReference
    }

    pub fn set(&self, c: Comp, unit: &str, name: &str, value: f64) -> fmi3Status {
        unsafe { self.sym::<SetF64>(b"fmi3SetFloat64")(c, &Self::vr(unit, name), 1, &value, 1) }
    }

    pub fn get(&self, c: Comp, unit: &str, name: &str) -> f64 {
        let mut v = f64::NAN;
        let s = unsafe { self.sym::<GetF64>(b"fmi3GetFloat64")(c, &Self::vr(unit, name), 1, &mut v, 1) };
        assert_eq!(s, fmi3OK, "fmi3GetFloat64({name})");
        v
    }

    pub fn call0(&self, name: &[u8], c: Comp) -> fmi3Status {
        unsafe { self.sym::<unsafe extern "C" fn(Comp) -> fmi3Status>(name)(c) }
    }

    pub fn enter_initialization(&self, c: Comp) -> fmi3Status {
        unsafe { self.sym::<EnterInit>(b"fmi3EnterInitializationMode")(c, false, 0.0, 0.0, false, 0.0) }
    }

    /// fmi3DoStep: (status, eventHandlingNeeded, earlyReturn, lastSuccessfulTime).
    pub fn do_step(&self, c: Comp, t: f64, h: f64) -> (fmi3Status, bool, bool, f64) {
        let (mut event, mut terminate, mut early, mut last) = (false, false, false, f64::NAN);
        let s = unsafe { self.sym::<DoStep3>(b"fmi3DoStep")(c, t, h, true, &mut event, &mut terminate, &mut early, &mut last) };
        (s, event, early, last)
    }

    pub fn free(&self, c: Comp) {
        unsafe { self.sym::<unsafe extern "C" fn(Comp)>(b"fmi3FreeInstance")(c) }
    }
}
