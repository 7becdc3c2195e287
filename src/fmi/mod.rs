//! What the FMI 2.0 and FMI 3.0 C ABIs share (docs/architecture.md, "Layers", layers 6-7): one `Instance` with its calling
//! sequence and value handling, the byte format of saved states, and the status numbers. `crate::fmi2` and
//! `crate::fmi3` hold the `extern "C"` functions of each standard and their C types.

pub mod ffi;
pub mod instance;
pub mod state_calls;
pub(crate) mod state_format;
pub(crate) mod uri;

/// The status of a call: fmi2Status and fmi3Status have the same numbers (FMI 2.0 Sec. 2.1.3, FMI 3.0
/// Sec. 2.2.3); fmi2Pending (5) is never returned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// The call did what was asked (fmi2OK, fmi3OK).
    Ok = 0,
    /// The call did what was asked, but something is not right; the log says what (fmi2Warning, fmi3Warning).
    Warning = 1,
    /// The call did not do what was asked, and the instance can go on (fmi2Discard, fmi3Discard): the
    /// fmi2Get*Status functions for a status kind that is not available.
    Discard = 2,
    /// The call was refused or failed (fmi2Error, fmi3Error); whether the instance is then in the Error state
    /// is `instance::Failure::enters_error_state`.
    Error = 3,
    /// The instance cannot go on (fmi2Fatal, fmi3Fatal): an internal error put it in the Fatal state.
    Fatal = 4,
}

/// Which standard's C ABI an instance was made through.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Api {
    /// FMI 2.0: the fmi2 functions of `crate::fmi2`.
    Fmi2,
    /// FMI 3.0: the fmi3 functions of `crate::fmi3`.
    Fmi3,
}

impl Api {
    /// What an instance of `unit` made through this standard is checked against at instantiation and in
    /// saved states: the FMI 2.0 GUID or the FMI 3.0 instantiationToken.
    pub fn token(self, unit: &crate::units::UnitInfo) -> String {
        match self {
            Api::Fmi2 => unit.guid(),
            Api::Fmi3 => unit.instantiation_token(),
        }
    }

    /// The name of a function in this standard, given its FMI 2.0 name without the prefix
    /// ("DoStep" is fmi2DoStep or fmi3DoStep; a few were renamed in FMI 3.0).
    pub fn name(self, fmi2_name: &str) -> String {
        match self {
            Api::Fmi2 => format!("fmi2{fmi2_name}"),
            Api::Fmi3 => {
                let renamed = match fmi2_name {
                    "GetDerivatives" => "GetContinuousStateDerivatives",
                    "SetupExperiment" => "EnterInitializationMode",
                    "SetFMUstate" => "SetFMUState",
                    "GetFMUstate" => "GetFMUState",
                    "NewDiscreteStates" => "UpdateDiscreteStates",
                    other => other,
                };
                format!("fmi3{renamed}")
            }
        }
    }
}
