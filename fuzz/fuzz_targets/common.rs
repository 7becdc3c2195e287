//! What both fuzz targets share: instances made through the C ABI as a host would, with no logger.

use powderfmu::fmi2::exports::*;
use powderfmu::fmi2::types::*;
use powderfmu::units;
use std::ffi::CString;

pub const PWI: &str = "ParticleWallImpact";

pub fn instantiate(kind: fmi2Type) -> fmi2Component {
    let unit = units::by_identifier(PWI).unwrap();
    let name = CString::new("fuzz").unwrap();
    let guid = CString::new(unit.guid()).unwrap();
    let uri = CString::new(format!("file://{}/", std::env::temp_dir().display())).unwrap();
    let cb = fmi2CallbackFunctions { logger: None, allocateMemory: None, freeMemory: None, stepFinished: None, componentEnvironment: std::ptr::null_mut() };
    let c = unsafe { fmi2Instantiate(name.as_ptr(), kind, guid.as_ptr(), uri.as_ptr(), &cb, fmi2False, fmi2False) };
    assert!(!c.is_null());
    c
}

#[allow(dead_code)]
pub fn vr(name: &str) -> fmi2ValueReference {
    units::by_identifier(PWI).unwrap().vr(name).expect("a variable of the unit") as fmi2ValueReference
}

/// fmi2Fatal means a panic was caught inside the unit: a bug, whatever the input.
pub fn not_fatal(status: fmi2Status, what: &str) -> fmi2Status {
    assert_ne!(status, fmi2Fatal, "{what} returned fmi2Fatal: an internal error");
    status
}
