//! The FMI 3.0 side of the test host: `fmi_host`'s FMI 3.0 calls on the same cdylib, with typed get and
//! set by variable name.

use super::{Binary, Comp, Log};
#[allow(unused_imports)]
pub use fmi_host::fmi3::{logger as logger3, DoStep as DoStep3, EnterInit, GetF64, InstantiateCs, InstantiateMe, Kind, SetF64};
use powderfmu::fmi3::types::*;
use powderfmu::units;

/// The library's FMI 3.0 exports, with the unit's variables named through the crate's own tables.
pub struct Api3<'a> {
    pub lib: &'a Binary,
}

impl Api3<'_> {
    pub fn sym<T: Copy>(&self, name: &[u8]) -> T {
        // SAFETY: the caller names the symbol's FMI 3.0 type (checked against the headers by fmi3_headers.rs).
        unsafe { self.lib.sym(name) }.unwrap_or_else(|e| panic!("{e}"))
    }

    /// A Co-Simulation instance (eventModeUsed, earlyReturnAllowed as given) or, with `me`, Model Exchange.
    pub fn instantiate(&self, unit: &str, me: bool, event_mode: bool, early_return: bool, log: &Log) -> Comp {
        let token = units::by_identifier(unit).unwrap().instantiation_token();
        let kind = if me { Kind::ModelExchange } else { Kind::CoSimulation { event_mode, early_return } };
        fmi_host::fmi3::instantiate(self.lib, "importer3", &token, None, kind, log).expect("fmi3Instantiate exported")
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
