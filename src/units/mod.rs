//! The FMUs: each unit is a variable table plus a `Model` that drives the dynamics (docs/architecture.md, "Layers"). The FMI
//! glue in `crate::fmi2` knows only this module's `UnitInfo` and `Model` trait, never the physics.

#[macro_use]
pub mod variables;
pub mod ball_indentation;
pub mod contact_element;
mod contact_parts;
mod error;
pub mod model_description;
pub mod model_description_fmi3;
pub mod particle_wall_impact;
mod scene_params;
pub mod unconfined_compression;

pub use error::UnitError;
pub use scene_params::DEFAULT_SCENE;
use std::sync::OnceLock;
use variables::Value;

/// The log categories of every unit (FMI 2.0 Sec. 2.2.4), name and meaning. The descriptions name the
/// statuses as FMI 2.0 does; the FMI 3.0 model description names them fmi3
/// (`model_description::units_categories_experiment`).
pub const LOG_CATEGORIES: &[(&str, &str)] = &[
    ("logEvents", "Branch switches of the contact law and other events"),
    ("logStatusWarning", "Calls that returned fmi2Warning"),
    ("logStatusError", "Calls that returned fmi2Error: bad input or a call out of sequence"),
    ("logStatusFatal", "Calls that returned fmi2Fatal"),
    ("logAll", "Every call"),
];

/// What a unit does, as the FMI glue sees it. Values are indexed by value reference (the position in
/// the variable table); the glue has checked types, causality and the calling sequence before a call.
pub trait Model: Send {
    /// Reads the parameters and inputs and sets the initial state at `t0` (fmi2ExitInitializationMode)
    /// for Model Exchange or Co-Simulation. An error names the parameter and its allowed range.
    fn initialize(&mut self, values: &[Value], t0: f64, model_exchange: bool) -> Result<(), UnitError>;
    /// Writes the outputs and locals for the current time, state and inputs into `values`.
    /// `between_events` is Model Exchange's Continuous-Time Mode: everything stays on the branch accepted
    /// at the last event (discrete outputs included). Elsewhere (initialization, Event Mode,
    /// Co-Simulation) the outputs at new inputs are those of the history walked to them, the values the
    /// next event or step starts from.
    fn compute(&mut self, values: &mut [Value], between_events: bool);
    /// ME: the solver's time.
    fn set_time(&mut self, t: f64);
    /// ME: the continuous states, into `x` (one entry per state).
    fn get_states(&self, x: &mut [f64]);
    /// ME: takes the continuous states the host's integrator gives.
    fn set_states(&mut self, x: &[f64]);
    /// ME: the derivatives of the continuous states at the current time, states and inputs, into `dx`.
    fn derivatives(&mut self, values: &[Value], dx: &mut [f64]);
    /// ME: the event indicators at the current state and inputs, into `z`.
    fn event_indicators(&mut self, values: &[Value], z: &mut [f64]);
    /// ME: the nominal values of the continuous states, into `x`.
    fn nominals(&self, x: &mut [f64]);
    /// ME: an event (fmi2NewDiscreteStates): the contact's history accepts the current state. The only
    /// place where Model Exchange changes a branch (or, crossing a vertical branch end, the states).
    fn accept(&mut self, values: &[Value]) -> EventUpdate;
    /// ME: a completed integrator step (fmi2CompletedIntegratorStep), after the inputs of its time are
    /// set: a history that grows along its branch keeps the point reached (`Contact::keep_growth`);
    /// nothing the right-hand side uses changes.
    fn completed_step(&mut self, _values: &[Value]) {}
    /// CS: advance from `t` by `h` with the current inputs.
    fn do_step(&mut self, values: &[Value], t: f64, h: f64) -> Result<(), UnitError>;
    /// CS with early return (FMI 3.0 `earlyReturnAllowed`): advance from `t` by at most `h`, ending at the
    /// first change of the contact state inside the step. Returns the time of that event, or None when the
    /// step went to `t + h`. Units whose state changes only at communication points (`returns_early`
    /// false) step to the end.
    fn do_step_to_event(&mut self, values: &[Value], t: f64, h: f64) -> Result<Option<f64>, UnitError> {
        self.do_step(values, t, h).map(|()| None)
    }
    /// CS, fmi2SetRealInputDerivatives: (value reference, order, value) of time derivatives of inputs at
    /// the start of the next step. Only units with `can_interpolate_inputs` take any; a refusal of one
    /// changes nothing.
    fn set_input_derivatives(&mut self, _derivatives: &[(usize, i32, f64)]) -> Result<(), UnitError> {
        Err(UnitError::Unsupported("this unit takes no input derivatives (canInterpolateInputs is false)".into()))
    }
    /// A value the host sets (after its type and range are checked): `Err` with the reason refuses it and
    /// nothing changes. For values allowed in one interface kind only (`model_exchange`).
    fn check_set(&self, _vr: usize, _value: &Value, _model_exchange: bool) -> Result<(), String> {
        Ok(())
    }
    /// The dynamic state (not the parameters) as bytes (empty: not initialized); `restore` reads it back.
    fn save(&self) -> Result<Vec<u8>, UnitError>;
    /// What happened since the last call worth telling the user (progress of a long test), for the
    /// logEvents category; drained by the FMI glue after each call.
    fn take_events(&mut self) -> Vec<String> {
        Vec::new()
    }
    /// Sets the model to a state `save` wrote; `values` are the variable values saved with it. A state that
    /// cannot be read, or that does not fit the parameters, is refused.
    fn restore(&mut self, values: &[Value], bytes: &[u8]) -> Result<(), UnitError>;
}

/// What an event changed (`Model::accept`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EventUpdate {
    /// A message for the logEvents category (a branch switch).
    pub message: Option<String>,
    /// The right-hand side or the continuous states changed: an integrator that stepped across the event
    /// on the old branch must restart from the event (valuesOfContinuousStatesChanged). A host such as
    /// fmusim restarts CVode only when told; without it, it goes on with the old branch's step.
    pub restart: bool,
}

/// One unit: identifier, variables, sizes and a constructor of its model.
pub struct UnitInfo {
    /// The FMI modelIdentifier (`by_identifier` finds the unit by it).
    pub model_identifier: &'static str,
    /// The unit's description in its model description.
    pub description: &'static str,
    /// The variable table; a variable's position in it is its value reference.
    pub variables: Vec<variables::Variable>,
    /// The number of continuous states (Model Exchange).
    pub n_states: usize,
    /// The number of event indicators (Model Exchange).
    pub n_event_indicators: usize,
    /// Whether the unit offers Model Exchange (every unit offers Co-Simulation).
    pub model_exchange: bool,
    /// CS: whether the unit takes input derivatives (fmi2SetRealInputDerivatives, canInterpolateInputs).
    pub can_interpolate_inputs: bool,
    /// CS: whether a step can have events inside it, where FMI 3.0 returns early (`do_step_to_event`).
    pub returns_early: bool,
    /// DefaultExperiment of the XML [s].
    pub stop_time: f64,
    /// DefaultExperiment stepSize of the XML [s].
    pub step_size: f64,
    /// A fresh model; the second argument is the unzipped `resources` folder, when the host gave one.
    pub new_model: fn(&UnitInfo, Option<&std::path::Path>) -> Box<dyn Model>,
    /// The GUID and the FMI 3.0 instantiation token, computed once (each hashes its model description).
    pub guid_cache: OnceLock<String>,
    /// The FMI 3.0 instantiation token, computed once (`instantiation_token`).
    pub token_cache: OnceLock<String>,
}

impl UnitInfo {
    /// The value reference (table position) of a variable, by name: for hosts and tests. The units
    /// themselves use the references their tables give (`variable_table!`).
    pub fn vr(&self, name: &str) -> Option<usize> {
        self.variables.iter().position(|v| v.name == name)
    }

    /// The GUID: a hash of the model description without it, so it changes exactly when the interface does.
    pub fn guid(&self) -> String {
        self.guid_cache.get_or_init(|| uuid_of(&model_description::xml(self, ""))).clone()
    }

    /// The FMI 3.0 instantiationToken: the same kind of hash, of the FMI 3.0 model description.
    pub fn instantiation_token(&self) -> String {
        self.token_cache.get_or_init(|| uuid_of(&model_description_fmi3::xml(self, ""))).clone()
    }

    /// The FMI 2.0 modelDescription.xml of the unit, with its GUID.
    pub fn model_description(&self) -> String {
        model_description::xml(self, &self.guid())
    }

    /// The FMI 3.0 modelDescription.xml of the unit, with its instantiationToken.
    pub fn model_description_fmi3(&self) -> String {
        model_description_fmi3::xml(self, &self.instantiation_token())
    }

    /// Every variable at its start value.
    pub fn start_values(&self) -> Vec<Value> {
        self.variables.iter().map(|v| v.initial_value()).collect()
    }
}

/// A UUID-shaped hash of a text (two FNV-1a 64 with different offsets).
fn uuid_of(text: &str) -> String {
    use crate::envelope::{fnv1a64, FNV_OFFSET};
    let a = fnv1a64(text.as_bytes(), FNV_OFFSET);
    let b = fnv1a64(text.as_bytes(), 0x6c62_272e_07bb_0142);
    format!("{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}", a >> 32, (a >> 16) & 0xffff, a & 0xffff, b >> 48, b & 0xffff_ffff_ffff)
}

/// Every unit of the crate, built once.
pub fn all() -> &'static [UnitInfo] {
    static UNITS: OnceLock<Vec<UnitInfo>> = OnceLock::new();
    UNITS.get_or_init(|| vec![particle_wall_impact::info(), contact_element::info(), ball_indentation::info(), unconfined_compression::info()])
}

/// The unit with this model identifier.
pub fn by_identifier(id: &str) -> Option<&'static UnitInfo> {
    all().iter().find(|u| u.model_identifier == id)
}

/// The DEM units' `replicas` parameter: how many beds the test runs on, in [1, 64].
pub(crate) fn replica_count(n: f64) -> Result<usize, UnitError> {
    if !(1.0..=64.0).contains(&n) {
        return Err(UnitError::Variable { name: "replicas", why: format!("parameter `replicas` = {n} is out of range: allowed [1, 64]") });
    }
    Ok(n as usize)
}

/// The beds a DEM unit's `bed_file` lists (';'-separated, one per replica), or None where it is empty (the
/// FMU's own beds then); a count other than `replicas` is refused, naming `replicas`.
pub(crate) fn listed_beds(bed_file: &str, replicas: usize) -> Result<Option<Vec<std::path::PathBuf>>, UnitError> {
    let paths: Vec<std::path::PathBuf> = bed_file.split(';').map(str::trim).filter(|p| !p.is_empty()).map(Into::into).collect();
    if paths.is_empty() {
        return Ok(None);
    }
    if paths.len() != replicas {
        return Err(UnitError::Variable {
            name: "replicas",
            why: format!("parameter `replicas` = {replicas}, but bed_file lists {} bed(s): list one bed per replica, separated by ';'", paths.len()),
        });
    }
    Ok(Some(paths))
}

/// The DEM units' `threads` parameter: the bed engine's threads, in [1, 256].
pub(crate) fn engine_threads(t: f64) -> Result<usize, UnitError> {
    if !(1.0..=256.0).contains(&t) {
        return Err(UnitError::Variable { name: "threads", why: format!("parameter `threads` = {t} is out of range: allowed [1, 256]") });
    }
    Ok(t as usize)
}

/// Reads a model snapshot written by `contact_parts::encode` (`codec`), refusing anything larger than
/// 1 MiB (a contact unit's snapshot is a few hundred bytes) or with bytes left over.
pub(crate) fn decode<T: serde::de::DeserializeOwned>(bytes: &[u8]) -> Result<T, UnitError> {
    if bytes.len() > 1 << 20 {
        return Err(UnitError::SavedState(format!(
            "the saved model state cannot be read: {} bytes, above the 1 MiB a contact unit's state can take",
            bytes.len()
        )));
    }
    crate::codec::from_bytes(bytes).map_err(|e| UnitError::SavedState(format!("the saved model state cannot be read: {e}")))
}
