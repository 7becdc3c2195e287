//! One FMU instance behind either C ABI (FMI 2.0 `crate::fmi2`, FMI 3.0 `crate::fmi3`): the calling-sequence
//! state machine (FMI 2.0 Secs. 3.2.3 and 4.2.4, FMI 3.0 Sec. 3.2), the variable values indexed by value
//! reference, logging, and the calls into the unit's `Model`. All of it is safe Rust; each `exports` turns
//! C pointers into slices before calling here. The two standards share the status numbers, the modes the
//! units use and what a call may change; they differ in names, which `Api` gives.

use super::state_format;
use super::{Api, Status};
use crate::units::variables::{Causality, Role, Value, VarType, Variability};
use crate::units::{Model, UnitInfo, LOG_CATEGORIES};
use std::ffi::{c_void, CStr, CString};
use std::sync::Arc;

/// The states of the FMI 2.0 calling sequence, by the standard's names (hence "...Mode").
#[allow(clippy::enum_variant_names)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Instantiated: after instantiation or a reset, before Initialization Mode.
    Instantiated,
    /// Initialization Mode: between EnterInitializationMode and ExitInitializationMode.
    InitializationMode,
    /// Event Mode (Model Exchange, and FMI 3.0 Co-Simulation with eventModeUsed).
    EventMode,
    /// Continuous-Time Mode (Model Exchange): between events, while the host integrates the states.
    ContinuousTimeMode,
    /// Co-Simulation between steps: FMI 2.0's Step Complete, FMI 3.0's Step Mode.
    StepComplete,
    /// Terminated: after fmi2Terminate or fmi3Terminate.
    Terminated,
    /// The Error state: a computation failed; the values can still be read, and Reset, SetFMUstate or
    /// FreeInstance lead out of it.
    Error,
    /// The Fatal state: an internal error (a panic); every call is refused, the instance can only be freed.
    Fatal,
    /// FMI 3.0 Co-Simulation: inside the master's intermediate-update callback, at an event within a step
    /// (last, so that the numbers of the other modes in saved states stay as they were).
    IntermediateUpdate,
}

impl Mode {
    /// The mode's bit in the masks of `allowed`.
    pub fn bit(self) -> u32 {
        1 << (self as u32)
    }

    /// The mode's name in the standard of `api` (FMI 3.0 calls Step Complete "Step Mode").
    pub fn name(self, api: Api) -> &'static str {
        match self {
            Mode::StepComplete if api == Api::Fmi3 => "Step Mode",
            Mode::Instantiated => "Instantiated",
            Mode::InitializationMode => "Initialization Mode",
            Mode::EventMode => "Event Mode",
            Mode::ContinuousTimeMode => "Continuous-Time Mode",
            Mode::StepComplete => "Step Complete",
            Mode::Terminated => "Terminated",
            Mode::Error => "Error",
            Mode::Fatal => "Fatal",
            Mode::IntermediateUpdate => "Intermediate Update Mode",
        }
    }

    /// Every mode, in the order of its number (the number a saved state records).
    pub const ALL: [Mode; 9] = [
        Mode::Instantiated,
        Mode::InitializationMode,
        Mode::EventMode,
        Mode::ContinuousTimeMode,
        Mode::StepComplete,
        Mode::Terminated,
        Mode::Error,
        Mode::Fatal,
        Mode::IntermediateUpdate,
    ];
}

/// Sets of modes in which a function may be called.
pub mod allowed {
    use super::Mode::*;
    const fn m(modes: &[super::Mode]) -> u32 {
        let mut bits = 0;
        let mut i = 0;
        while i < modes.len() {
            bits |= 1 << (modes[i] as u32);
            i += 1;
        }
        bits
    }
    /// Every mode but Fatal and Intermediate Update Mode: SetDebugLogging, Reset, the FMU-state calls (get,
    /// set, free, size, serialize, deserialize), fmi3GetNumberOfEventIndicators,
    /// fmi3GetNumberOfContinuousStates, and the functions refused in every mode as not supported.
    pub const ANY_LIVE: u32 = m(&[Instantiated, InitializationMode, EventMode, ContinuousTimeMode, StepComplete, Terminated, Error]);
    /// fmi2SetupExperiment: Instantiated only.
    pub const SETUP_EXPERIMENT: u32 = m(&[Instantiated]);
    /// fmi2EnterInitializationMode and fmi3EnterInitializationMode: Instantiated only.
    pub const ENTER_INITIALIZATION: u32 = m(&[Instantiated]);
    /// fmi2ExitInitializationMode and fmi3ExitInitializationMode: Initialization Mode only.
    pub const EXIT_INITIALIZATION: u32 = m(&[InitializationMode]);
    /// fmi2Terminate and fmi3Terminate: Event Mode, Continuous-Time Mode and Step Complete (Step Mode).
    pub const TERMINATE: u32 = m(&[EventMode, ContinuousTimeMode, StepComplete]);
    /// The getters of variable values (fmi2GetReal, fmi2GetInteger, fmi2GetBoolean, fmi2GetString and
    /// the fmi3Get functions of every type): Initialization Mode, Event Mode, Continuous-Time Mode, Step
    /// Complete, Terminated, Error and Intermediate Update Mode.
    pub const GET: u32 = m(&[InitializationMode, EventMode, ContinuousTimeMode, StepComplete, Terminated, Error, IntermediateUpdate]);
    /// fmi2SetReal and fmi3SetFloat64: Instantiated, Initialization Mode, Event Mode, Continuous-Time Mode
    /// and Step Complete (in Continuous-Time Mode only continuous variables, `Instance::set`).
    pub const SET_REAL: u32 = m(&[Instantiated, InitializationMode, EventMode, ContinuousTimeMode, StepComplete]);
    /// The setters of the other types (fmi2SetInteger, fmi2SetBoolean, fmi2SetString and the other fmi3Set
    /// functions): as `SET_REAL` but not in Continuous-Time Mode.
    pub const SET_OTHER: u32 = m(&[Instantiated, InitializationMode, EventMode, StepComplete]);
    /// fmi2EnterEventMode: Event Mode and Continuous-Time Mode.
    pub const ENTER_EVENT_MODE: u32 = m(&[EventMode, ContinuousTimeMode]);
    /// fmi2NewDiscreteStates and fmi3UpdateDiscreteStates: Event Mode only.
    pub const NEW_DISCRETE_STATES: u32 = m(&[EventMode]);
    /// fmi2EnterContinuousTimeMode and fmi3EnterContinuousTimeMode: Event Mode only.
    pub const ENTER_CONTINUOUS_TIME: u32 = m(&[EventMode]);
    /// fmi2CompletedIntegratorStep and fmi3CompletedIntegratorStep: Continuous-Time Mode only.
    pub const COMPLETED_INTEGRATOR_STEP: u32 = m(&[ContinuousTimeMode]);
    /// fmi2SetTime and fmi3SetTime: Event Mode and Continuous-Time Mode.
    pub const SET_TIME: u32 = m(&[EventMode, ContinuousTimeMode]);
    /// fmi2SetContinuousStates and fmi3SetContinuousStates: Continuous-Time Mode only.
    pub const SET_CONTINUOUS_STATES: u32 = m(&[ContinuousTimeMode]);
    /// fmi2GetDerivatives, fmi2GetEventIndicators, fmi2GetContinuousStates and their fmi3 counterparts
    /// (fmi3GetContinuousStateDerivatives, fmi3GetEventIndicators, fmi3GetContinuousStates): Initialization
    /// Mode, Event Mode, Continuous-Time Mode, Terminated and Error.
    pub const GET_DERIVATIVES: u32 = m(&[InitializationMode, EventMode, ContinuousTimeMode, Terminated, Error]);
    /// fmi2GetNominalsOfContinuousStates and fmi3GetNominalsOfContinuousStates: the modes of
    /// `GET_DERIVATIVES` and Instantiated.
    pub const GET_NOMINALS: u32 = m(&[Instantiated, InitializationMode, EventMode, ContinuousTimeMode, Terminated, Error]);
    /// fmi2DoStep and fmi3DoStep: Step Complete (Step Mode) only.
    pub const DO_STEP: u32 = m(&[StepComplete]);
    /// fmi2SetRealInputDerivatives: Instantiated, Initialization Mode and Step Complete.
    pub const SET_INPUT_DERIVATIVES: u32 = m(&[Instantiated, InitializationMode, StepComplete]);
    /// fmi2GetStatus, fmi2GetRealStatus, fmi2GetIntegerStatus, fmi2GetBooleanStatus and
    /// fmi2GetStringStatus: Step Complete and Terminated.
    pub const CS_STATUS: u32 = m(&[StepComplete, Terminated]);
    /// FMI 3.0: Event Mode is entered from Continuous-Time Mode (ME) and from Step Mode (CS, eventModeUsed).
    pub const ENTER_EVENT_MODE_3: u32 = m(&[ContinuousTimeMode, StepComplete]);
    /// fmi3EnterStepMode: Event Mode only.
    pub const ENTER_STEP_MODE: u32 = m(&[EventMode]);
    /// fmi3DoStep's return to Step Mode after the master's intermediate-update callback: Intermediate Update
    /// Mode only.
    pub const INTERMEDIATE_UPDATE: u32 = m(&[IntermediateUpdate]);
}

/// Which interface the instance was made for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Model Exchange: the host integrates the continuous states.
    ModelExchange,
    /// Co-Simulation: the unit advances itself in steps (DoStep).
    CoSimulation,
}

/// A failed call: the status to return, the message to log, and whether the instance enters the Error
/// state (docs/robustness.md): a computation that failed does; a call refused for its arguments or its
/// place in the calling sequence changed nothing, and leaves the instance as it was.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// The status the call returns.
    pub status: Status,
    /// The message for the host's logger.
    pub message: String,
    /// Whether the instance goes to the Error state (a failed computation) or stays as it was (a refused
    /// call).
    pub enters_error_state: bool,
}

/// What a call on an instance returns: its result, or the failure to report.
pub type Call<T = ()> = Result<T, Failure>;

/// A refused call: Error, nothing changed.
pub fn error<T>(message: impl Into<String>) -> Call<T> {
    Err(Failure { status: Status::Error, message: message.into(), enters_error_state: false })
}

/// A call that could not do what was asked and changed nothing, the instance going on as it was: Discard
/// (FMI 2.0.4 Sec. 4.2.3: a status kind that is not available).
pub fn discard<T>(message: impl Into<String>) -> Call<T> {
    Err(Failure { status: Status::Discard, message: message.into(), enters_error_state: false })
}

/// A computation that failed: Error, and the instance is in the Error state.
pub fn failed<T>(message: impl Into<String>) -> Call<T> {
    Err(Failure { status: Status::Error, message: message.into(), enters_error_state: true })
}

/// The host's logging function as its ABI's exports wrap it (FMI 2.0's takes printf-style text and the
/// instance name, FMI 3.0's the text as it is): called with the host's environment pointer, the
/// instance's name, the status, the category and the message. None: the host gave no logger.
pub type LogCallback = Option<Arc<dyn Fn(*mut c_void, &CStr, Status, &CStr, &str) + Send + Sync>>;

/// The host's logger and which categories are switched on.
#[derive(Clone)]
pub struct Logger {
    /// The host's logging function (None: the host gave none).
    pub callback: LogCallback,
    /// The host's environment pointer (fmi2ComponentEnvironment, fmi3InstanceEnvironment).
    pub environment: *mut c_void,
    /// Whether debug logging is on (loggingOn at instantiation; after SetDebugLogging, whether any category
    /// is on).
    pub logging_on: bool,
    /// One flag per entry of `LOG_CATEGORIES`, in its order: whether SetDebugLogging left the category on
    /// (all on at first).
    pub categories: Vec<bool>,
}

// SAFETY: the environment pointer is the host's and never dereferenced here; it is only handed back to
// the host's logger, which FMI lets the host call from the thread the instance is used on.
unsafe impl Send for Logger {}

impl Logger {
    /// A logger with every category on.
    pub fn new(callback: LogCallback, environment: *mut c_void, logging_on: bool) -> Logger {
        Logger { callback, environment, logging_on, categories: vec![true; LOG_CATEGORIES.len()] }
    }

    /// Errors, warnings and fatal messages are always passed on; the debug categories only with logging on.
    pub fn enabled(&self, category: &str) -> bool {
        let always = matches!(category, "logStatusError" | "logStatusWarning" | "logStatusFatal");
        let index = LOG_CATEGORIES.iter().position(|(name, _)| *name == category);
        let on = index.is_some_and(|i| self.categories[i]);
        if always {
            on || !self.logging_on
        } else {
            self.logging_on && on
        }
    }

    /// Passes a message to the host's logging function, if its category is enabled and the host gave one.
    pub fn log(&self, instance_name: &CString, status: Status, category: &str, message: &str) {
        if !self.enabled(category) {
            return;
        }
        let category = CString::new(category).unwrap_or_default();
        if let Some(callback) = &self.callback {
            callback(self.environment, instance_name, status, &category, message);
        }
    }
}

/// One FMU instance: the unit, the mode in the calling sequence, the variable values, the model, the time
/// and the host's logger.
pub struct Instance {
    /// Which C ABI made the instance: the names in its messages.
    pub api: Api,
    /// The instance name the host gave (NUL bytes replaced by spaces).
    pub name: CString,
    /// The unit this is an instance of.
    pub unit: &'static UnitInfo,
    /// The interface the instance was made for.
    pub kind: Kind,
    /// The current mode of the calling sequence.
    pub mode: Mode,
    /// Every variable's value, indexed by value reference.
    pub values: Vec<Value>,
    /// The unit's model, which holds the dynamic state.
    pub model: Box<dyn Model>,
    /// The instance's current time [s].
    pub time: f64,
    /// The startTime the host gave (SetupExperiment, EnterInitializationMode) [s].
    pub start_time: f64,
    /// The stopTime the host gave, if any [s].
    pub stop_time: Option<f64>,
    /// The host's logger and the categories switched on.
    pub logger: Logger,
    /// The strings handed out by the last fmi2GetString (valid until the next call, FMI 2.0 Sec. 2.1.7).
    pub strings: Vec<CString>,
    /// Messages for the host's logger, passed on after the call (`log`).
    pending_log: Vec<(Status, String, String)>,
    /// Whether the model's state reflects the current parameters (false after a parameter changes
    /// before the end of initialization).
    model_ready: bool,
    /// The unzipped `resources` folder the host named (fmuResourceLocation), if any.
    resources: Option<std::path::PathBuf>,
    /// FMI 3.0 Co-Simulation: whether the master uses Event Mode and lets a step return early, and its
    /// intermediate-update callback (called at the events inside a step).
    pub event_mode_used: bool,
    /// FMI 3.0 Co-Simulation: earlyReturnAllowed as the master gave it, kept only for a unit that
    /// `returns_early`.
    pub early_return_allowed: bool,
    /// What the ABI's exports keep with the instance (FMI 3.0: the intermediate-update callback); this
    /// layer only holds it.
    pub abi: Option<Box<dyn std::any::Any + Send>>,
    /// Model Exchange: an input was given a new value in Event Mode since the last event iteration.
    inputs_changed_in_event_mode: bool,
    /// Model Exchange: the event indicators at the last event or completed integrator step, against
    /// which `completed_integrator_step` looks for a change of sign (None: not known, after a restored
    /// state).
    indicators_seen: Option<Vec<f64>>,
}

impl Instance {
    /// A new instance in Instantiated mode at time 0 [s], every variable at its start value, with a fresh
    /// model; `resources` is the unzipped resources folder the host named, if any.
    pub fn new(api: Api, name: &str, unit: &'static UnitInfo, kind: Kind, logger: Logger, resources: Option<std::path::PathBuf>) -> Instance {
        Instance {
            api,
            name: CString::new(name.replace('\0', " ")).unwrap_or_default(),
            unit,
            kind,
            mode: Mode::Instantiated,
            values: unit.start_values(),
            model: (unit.new_model)(unit, resources.as_deref()),
            time: 0.0,
            start_time: 0.0,
            stop_time: None,
            logger,
            strings: Vec::new(),
            pending_log: Vec::new(),
            model_ready: false,
            resources,
            event_mode_used: false,
            inputs_changed_in_event_mode: false,
            indicators_seen: None,
            early_return_allowed: false,
            abi: None,
        }
    }

    /// The GUID (FMI 2.0) or instantiationToken (FMI 3.0) of the unit: what a saved state is tied to.
    pub fn token(&self) -> String {
        self.api.token(self.unit)
    }

    /// Keeps a message for the host's logger; `ffi::call_on` passes the messages on when the call is
    /// done and the instance no longer borrowed, so that a logger that calls back into the library (or
    /// frees the instance) finds it in a consistent state.
    pub fn log(&mut self, status: Status, category: &str, message: &str) {
        if self.logger.enabled(category) {
            self.pending_log.push((status, category.to_string(), message.to_string()));
        }
    }

    /// The logger, the instance's name and the messages kept since the last call.
    pub fn take_log(&mut self) -> (Logger, CString, Vec<(Status, String, String)>) {
        (self.logger.clone(), self.name.clone(), std::mem::take(&mut self.pending_log))
    }

    /// The calling-sequence check of one function.
    pub fn check_mode(&self, function: &str, allowed: u32) -> Call {
        if allowed & self.mode.bit() != 0 {
            return Ok(());
        }
        // Intermediate Update Mode exists only for FMI 3.0 Co-Simulation.
        let has = |m: &Mode| *m != Mode::IntermediateUpdate || (self.api == Api::Fmi3 && self.kind == Kind::CoSimulation);
        let modes: Vec<&str> = Mode::ALL.iter().filter(|m| allowed & m.bit() != 0 && has(m)).map(|m| m.name(self.api)).collect();
        error(format!("{function} must not be called in {}; allowed in: {}", self.mode.name(self.api), modes.join(", ")))
    }

    /// Refuses a function of the other interface (a Model Exchange function on a Co-Simulation instance, or
    /// the reverse).
    pub fn check_kind(&self, function: &str, kind: Kind) -> Call {
        if self.kind == kind {
            return Ok(());
        }
        let what = if kind == Kind::ModelExchange { "Model Exchange" } else { "Co-Simulation" };
        error(format!("{function} is a {what} function, but this instance was instantiated for the other interface"))
    }

    /// Back to Instantiated (fmi2Reset, fmi3Reset): start values, a fresh model, time 0; the name, the
    /// logger and what the host chose at instantiation stay.
    pub fn reset(&mut self) {
        self.mode = Mode::Instantiated;
        self.values = self.unit.start_values();
        self.model = (self.unit.new_model)(self.unit, self.resources.as_deref());
        self.time = 0.0;
        self.start_time = 0.0;
        self.stop_time = None;
        self.model_ready = false;
    }

    /// Takes startTime and the optional stopTime [s] (fmi2SetupExperiment, fmi3EnterInitializationMode); the
    /// instance's time starts at startTime. Refuses a start that is not finite or a stop before the start.
    pub fn setup_experiment(&mut self, start: f64, stop: Option<f64>) -> Call {
        if !start.is_finite() {
            return error(format!("{}: startTime = {start} is not finite", self.api.name("SetupExperiment")));
        }
        if let Some(stop) = stop {
            if !(stop >= start) {
                return error(format!("{}: stopTime = {stop:e} s must not be less than startTime = {start:e} s", self.api.name("SetupExperiment")));
            }
        }
        self.start_time = start;
        self.time = start;
        self.stop_time = stop;
        Ok(())
    }

    /// Builds the model's initial state from the current values.
    fn initialize_model(&mut self, function: &str) -> Call {
        let result = self.model.initialize(&self.values, self.time, self.kind == Kind::ModelExchange);
        self.log_events();
        match result {
            Ok(()) => {
                self.model_ready = true;
                self.model.compute(&mut self.values, false);
                Ok(())
            }
            Err(message) => {
                self.model_ready = false;
                failed(format!("{function}: {message}"))
            }
        }
    }

    /// fmi2ExitInitializationMode, fmi3ExitInitializationMode: builds the model's initial state from the
    /// current values, then goes to Event Mode (Model Exchange, and FMI 3.0 Co-Simulation with eventModeUsed)
    /// or to Step Complete (Step Mode).
    pub fn exit_initialization_mode(&mut self) -> Call {
        self.initialize_model(&self.api.name("ExitInitializationMode"))?;
        // FMI 3.0 Co-Simulation with Event Mode starts in Event Mode, as Model Exchange does.
        self.mode = if self.kind == Kind::ModelExchange || self.event_mode_used { Mode::EventMode } else { Mode::StepComplete };
        Ok(())
    }

    /// Brings the outputs up to date before a get.
    fn refresh(&mut self, function: &str) -> Call {
        if self.mode == Mode::InitializationMode && !self.model_ready {
            self.initialize_model(function)?;
        }
        if self.model_ready {
            let between_events = self.kind == Kind::ModelExchange && self.mode == Mode::ContinuousTimeMode;
            self.model.compute(&mut self.values, between_events);
            self.write_time_and_indicators();
        }
        Ok(())
    }

    /// The variables the glue itself knows: `time` and the event indicators (`Role`).
    fn write_time_and_indicators(&mut self) {
        let mut z = vec![0.0; self.unit.n_event_indicators];
        if !z.is_empty() {
            self.model.event_indicators(&self.values, &mut z);
        }
        for (value, v) in self.values.iter_mut().zip(&self.unit.variables) {
            match v.role {
                Role::Time => *value = Value::Real(self.time),
                Role::Indicator(i) => *value = Value::Real(z[i]),
                _ => {}
            }
        }
    }

    /// Checks value references and types of a get or set.
    fn check_refs(&self, function: &str, vrs: &[u32], var_type: VarType) -> Call {
        let n = self.unit.variables.len();
        for &vr in vrs {
            let Some(v) = self.unit.variables.get(vr as usize) else {
                return error(format!("{function}: value reference {vr} does not exist (this unit has {n} variables, 0..{})", n.saturating_sub(1)));
            };
            if v.var_type != var_type {
                return error(format!(
                    "{function}: value reference {vr} is `{}`, a {} variable, not {}",
                    v.name,
                    v.var_type.xml_name(),
                    var_type.xml_name()
                ));
            }
        }
        Ok(())
    }

    /// The values of the value references `vrs`, all of type `var_type`, with the outputs brought up to date
    /// first (the getters of both standards); in Intermediate Update Mode only outputs can be read.
    pub fn get(&mut self, function: &str, vrs: &[u32], var_type: VarType) -> Call<Vec<Value>> {
        self.check_refs(function, vrs, var_type)?;
        if self.mode == Mode::IntermediateUpdate {
            // FMI 3.0 Sec. 4.2.5: only the variables marked intermediateUpdate, the outputs.
            if let Some(v) = vrs.iter().map(|&vr| &self.unit.variables[vr as usize]).find(|v| v.causality != Causality::Output) {
                return error(format!(
                    "{function}: `{}` is not an output; in Intermediate Update Mode only the outputs (intermediateUpdate) can be read",
                    v.name
                ));
            }
        }
        self.refresh(function)?;
        Ok(vrs.iter().map(|&vr| self.values[vr as usize].clone()).collect())
    }

    /// Sets values after checking every one of them: a call either sets all or none.
    pub fn set(&mut self, function: &str, vrs: &[u32], new: Vec<Value>, var_type: VarType) -> Call {
        self.check_refs(function, vrs, var_type)?;
        for (&vr, value) in vrs.iter().zip(&new) {
            let v = &self.unit.variables[vr as usize];
            let settable = match (v.causality, self.mode) {
                (Causality::Input, _) => true,
                (Causality::Parameter, Mode::Instantiated | Mode::InitializationMode) => true,
                (Causality::Parameter, _) => {
                    return error(format!(
                        "{function}: parameter `{}` is fixed; it can only be set before {} (now in {})",
                        v.name,
                        self.api.name("ExitInitializationMode"),
                        self.mode.name(self.api)
                    ))
                }
                _ => false,
            };
            if !settable {
                return error(format!("{function}: `{}` is a calculated {} and cannot be set", v.name, v.causality.xml_name()));
            }
            if self.mode == Mode::ContinuousTimeMode && v.variability != Variability::Continuous {
                return error(format!("{function}: `{}` can only be set in Event Mode", v.name));
            }
            if let Value::Real(x) = value {
                if !x.is_finite() {
                    return error(format!("{function}: `{}` = {x} is not a finite number", v.name));
                }
                if let Some(min) = v.min {
                    if *x < min {
                        return error(format!("{function}: `{}` = {x:e} is below its minimum {min:e}", v.name));
                    }
                }
                if let Some(max) = v.max {
                    if *x > max {
                        return error(format!("{function}: `{}` = {x:e} is above its maximum {max:e}", v.name));
                    }
                }
            }
            if let Err(why) = self.model.check_set(vr as usize, value, self.kind == Kind::ModelExchange) {
                return error(format!("{function}: `{}`: {why}", v.name));
            }
        }
        if matches!(self.mode, Mode::Instantiated | Mode::InitializationMode) {
            // The initial state depends on every parameter and input: build it again when asked.
            self.model_ready = false;
        }
        for (&vr, value) in vrs.iter().zip(new) {
            let i = vr as usize;
            if self.mode == Mode::EventMode && self.unit.variables[i].causality == Causality::Input && self.values[i] != value {
                self.inputs_changed_in_event_mode = true;
            }
            self.values[i] = value;
        }
        Ok(())
    }

    /// Model Exchange: sets the time [s] (fmi2SetTime, fmi3SetTime); a time that is not finite is refused.
    pub fn set_time(&mut self, t: f64) -> Call {
        if !t.is_finite() {
            return error(format!("{}: time = {t} is not finite", self.api.name("SetTime")));
        }
        self.time = t;
        self.model.set_time(t);
        Ok(())
    }

    fn check_len(&self, function: &str, what: &str, n: usize, expected: usize) -> Call {
        if n == expected {
            Ok(())
        } else {
            error(format!("{function}: {what} = {n}, but this unit has {expected}"))
        }
    }

    /// Model Exchange: sets the continuous states (fmi2SetContinuousStates, fmi3SetContinuousStates); a wrong
    /// count or a value that is not finite is refused.
    pub fn set_continuous_states(&mut self, x: &[f64]) -> Call {
        let f = self.api.name("SetContinuousStates");
        self.check_len(&f, "nx", x.len(), self.unit.n_states)?;
        if let Some(i) = x.iter().position(|v| !v.is_finite()) {
            return error(format!("{f}: x[{i}] = {} is not finite", x[i]));
        }
        self.model.set_states(x);
        Ok(())
    }

    /// Model Exchange: the continuous states, into `x`, one entry per state (fmi2GetContinuousStates,
    /// fmi3GetContinuousStates).
    pub fn get_continuous_states(&mut self, x: &mut [f64]) -> Call {
        let f = self.api.name("GetContinuousStates");
        self.check_len(&f, "nx", x.len(), self.unit.n_states)?;
        self.refresh(&f)?;
        self.model.get_states(x);
        Ok(())
    }

    /// Model Exchange: the derivatives of the continuous states, into `dx`, one entry per state
    /// (fmi2GetDerivatives, fmi3GetContinuousStateDerivatives).
    pub fn get_derivatives(&mut self, dx: &mut [f64]) -> Call {
        let f = self.api.name("GetDerivatives");
        self.check_len(&f, "nx", dx.len(), self.unit.n_states)?;
        self.refresh(&f)?;
        self.model.derivatives(&self.values, dx);
        Ok(())
    }

    /// Model Exchange: the event indicators, into `z`, one entry per indicator (fmi2GetEventIndicators,
    /// fmi3GetEventIndicators).
    pub fn get_event_indicators(&mut self, z: &mut [f64]) -> Call {
        let f = self.api.name("GetEventIndicators");
        self.check_len(&f, "ni", z.len(), self.unit.n_event_indicators)?;
        self.refresh(&f)?;
        self.model.event_indicators(&self.values, z);
        Ok(())
    }

    /// fmi2CompletedIntegratorStep: whether the accepted branch has stopped holding at the current state
    /// and inputs (an event indicator below zero) without the host having located it. A master that sets
    /// its inputs in Continuous-Time Mode (sampled inputs held between samples) moves the overlap with no
    /// zero crossing for its integrator to find; the FMI 2.0 calling sequence calls this after the inputs
    /// of the new time are set, so the event is handled there instead of a step later.
    ///
    /// An event is a change of sign of an indicator since the last completed step or event, as a host
    /// detects it (an indicator may stay below zero after its event: the overlap rate after a turning
    /// point).
    pub fn completed_integrator_step(&mut self) -> Call<bool> {
        // Continuous-Time Mode: the model is initialized; the outputs are computed when asked for.
        self.model.completed_step(&self.values);
        let z = self.indicators_now();
        let event = self.indicators_seen.as_ref().is_some_and(|seen| seen.iter().zip(&z).any(|(a, b)| (*a >= 0.0) != (*b >= 0.0)));
        self.indicators_seen = Some(z);
        Ok(event)
    }

    /// The event indicators at the current state and inputs.
    fn indicators_now(&mut self) -> Vec<f64> {
        let mut z = vec![0.0; self.unit.n_event_indicators];
        self.model.event_indicators(&self.values, &mut z);
        z
    }

    /// Model Exchange: the nominal values of the continuous states, into `x` (fmi2GetNominalsOfContinuousStates,
    /// fmi3GetNominalsOfContinuousStates); 1.0 each until the model is initialized.
    pub fn get_nominals(&mut self, x: &mut [f64]) -> Call {
        self.check_len(&self.api.name("GetNominalsOfContinuousStates"), "nx", x.len(), self.unit.n_states)?;
        if self.model_ready {
            self.model.nominals(x);
        } else {
            x.fill(1.0);
        }
        Ok(())
    }

    /// The model's news since the last call, under logEvents.
    fn log_events(&mut self) {
        for message in self.model.take_events() {
            self.log(Status::Ok, "logEvents", &message);
        }
    }

    /// Event iteration (fmi2NewDiscreteStates): the history accepts the current state. Returns whether
    /// the host's integrator must restart (valuesOfContinuousStatesChanged): the model's branch, history
    /// or states changed, or an input changed in this Event Mode (a jump the integrator did not see).
    pub fn accept(&mut self) -> bool {
        let update = self.model.accept(&self.values);
        if let Some(message) = &update.message {
            self.log(Status::Ok, "logEvents", message);
        }
        let restart = update.restart || self.inputs_changed_in_event_mode;
        self.inputs_changed_in_event_mode = false;
        self.indicators_seen = Some(self.indicators_now());
        restart
    }

    /// Co-Simulation: one step from `t` by `h` [s] to its end (fmi2DoStep); `t` must be the instance's time.
    pub fn do_step(&mut self, t: f64, h: f64) -> Call {
        self.step(t, h, false).map(|_| ())
    }

    /// A step that may end early (FMI 3.0 with earlyReturnAllowed): at the first change of the contact
    /// state inside it, whose time it returns (None: the step went to t + h).
    pub fn step(&mut self, t: f64, h: f64, may_return_early: bool) -> Call<Option<f64>> {
        if !t.is_finite() || !h.is_finite() {
            return error(format!("{}: currentCommunicationPoint = {t} and communicationStepSize = {h} must be finite", self.api.name("DoStep")));
        }
        if h <= 0.0 {
            return error(format!("{}: communicationStepSize = {h:e} s must be positive", self.api.name("DoStep")));
        }
        if (t - self.time).abs() > 1e-10 * h.max(t.abs()) {
            return error(format!(
                "{}: currentCommunicationPoint = {t:e} s is not the unit's time {:e} s (steps must follow each other; use {} to go back)",
                self.api.name("DoStep"),
                self.time,
                self.api.name("SetFMUstate")
            ));
        }
        let result =
            if may_return_early { self.model.do_step_to_event(&self.values, t, h) } else { self.model.do_step(&self.values, t, h).map(|()| None) };
        self.log_events();
        match result {
            Ok(event) => {
                self.time = event.unwrap_or(t + h);
                Ok(event)
            }
            Err(message) => {
                failed(format!("{} from t = {t:e} s by {h:e} s failed, the state is that of t = {t:e} s: {message}", self.api.name("DoStep")))
            }
        }
    }

    /// fmi2SetRealInputDerivatives: every (vr, order, value) is checked before any is taken, so a refusal
    /// changes nothing.
    pub fn set_input_derivatives(&mut self, vrs: &[u32], orders: &[i32], values: &[f64]) -> Call {
        const F: &str = "fmi2SetRealInputDerivatives";
        if !self.unit.can_interpolate_inputs {
            return error(format!("{F}: {} takes no input derivatives (canInterpolateInputs is false)", self.unit.model_identifier));
        }
        self.check_refs(F, vrs, VarType::Real)?;
        for (&vr, &order) in vrs.iter().zip(orders) {
            let v = &self.unit.variables[vr as usize];
            if v.causality != Causality::Input {
                return error(format!("{F}: `{}` is not an input; only inputs have derivatives to set", v.name));
            }
            if order < 1 {
                return error(format!("{F}: order {order} of `{}` is out of range: allowed >= 1", v.name));
            }
        }
        let derivatives: Vec<(usize, i32, f64)> =
            vrs.iter().zip(orders).zip(values).map(|((&vr, &order), &value)| (vr as usize, order, value)).collect();
        self.model.set_input_derivatives(&derivatives).or_else(|e| error(format!("{F}: {e}")))
    }

    /// The saved state; a model that cannot serialize itself is an error the host sees (fmi2Error), never
    /// an empty state that would restore as "not initialized".
    pub fn save(&self) -> Call<Vec<u8>> {
        state_format::write(self).map_err(|m| Failure {
            status: Status::Error,
            message: format!("FMU state not saved: {m}"),
            enters_error_state: false,
        })
    }

    /// Sets the instance to a saved state (fmi2SetFMUstate, fmi3SetFMUState): the model, the values, the mode
    /// and the times. A state of the other interface, with an invalid mode, or that the model refuses is
    /// refused, and nothing changes.
    pub fn restore(&mut self, bytes: &[u8]) -> Call {
        let s = state_format::read(self.unit, self.api, bytes).map_err(|m| Failure {
            status: Status::Error,
            message: format!("FMU state rejected: {m}"),
            enters_error_state: false,
        })?;
        let kind = if s.kind == 0 { Kind::ModelExchange } else { Kind::CoSimulation };
        if kind != self.kind {
            return error("FMU state rejected: it was saved by an instance of the other interface (Model Exchange vs Co-Simulation)");
        }
        let mode = Mode::ALL.get(s.mode as usize).copied().filter(|m| !matches!(m, Mode::Error | Mode::Fatal | Mode::IntermediateUpdate));
        let Some(mode) = mode else { return error("FMU state rejected: it records an invalid mode") };
        // Model first: if it refuses, nothing of this instance has changed.
        let mut model = (self.unit.new_model)(self.unit, self.resources.as_deref());
        model.restore(&s.values, &s.model).map_err(|m| Failure {
            status: Status::Error,
            message: format!("FMU state rejected: {m}"),
            enters_error_state: false,
        })?;
        model.set_time(s.time);
        self.model = model;
        self.values = s.values;
        self.mode = mode;
        self.time = s.time;
        self.start_time = s.start_time;
        self.stop_time = s.stop_time;
        self.model_ready = s.model_ready;
        self.indicators_seen = None;
        self.inputs_changed_in_event_mode = false;
        Ok(())
    }

    /// Whether the model's state reflects the current parameters (a saved state records it).
    pub fn model_ready(&self) -> bool {
        self.model_ready
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::variables::Variable;

    /// A model whose state cannot be serialized.
    struct Unserializable;

    impl Model for Unserializable {
        fn initialize(&mut self, _: &[Value], _: f64, _: bool) -> Result<(), crate::units::UnitError> {
            Ok(())
        }
        fn compute(&mut self, _: &mut [Value], _: bool) {}
        fn set_time(&mut self, _: f64) {}
        fn get_states(&self, _: &mut [f64]) {}
        fn set_states(&mut self, _: &[f64]) {}
        fn derivatives(&mut self, _: &[Value], _: &mut [f64]) {}
        fn event_indicators(&mut self, _: &[Value], _: &mut [f64]) {}
        fn nominals(&self, _: &mut [f64]) {}
        fn accept(&mut self, _: &[Value]) -> crate::units::EventUpdate {
            crate::units::EventUpdate::default()
        }
        fn do_step(&mut self, _: &[Value], _: f64, _: f64) -> Result<(), crate::units::UnitError> {
            Ok(())
        }
        fn save(&self) -> Result<Vec<u8>, crate::units::UnitError> {
            Err(crate::units::UnitError::SavedState("a failure of the serializer".into()))
        }
        fn restore(&mut self, _: &[Value], _: &[u8]) -> Result<(), crate::units::UnitError> {
            Ok(())
        }
    }

    #[test]
    fn a_model_that_cannot_save_is_an_error_not_an_empty_state() {
        let unit: &'static UnitInfo = Box::leak(Box::new(UnitInfo {
            model_identifier: "Unserializable",
            description: "",
            variables: vec![Variable::parameter("p", Value::Real(1.0), "", "")],
            n_states: 0,
            n_event_indicators: 0,
            stop_time: 1.0,
            step_size: 0.1,
            model_exchange: true,
            can_interpolate_inputs: false,
            returns_early: false,
            new_model: |_, _| Box::new(Unserializable),
            guid_cache: std::sync::OnceLock::new(),
            token_cache: std::sync::OnceLock::new(),
        }));
        let mut inst = Instance::new(Api::Fmi2, "i", unit, Kind::CoSimulation, Logger::new(None, std::ptr::null_mut(), false), None);
        inst.exit_initialization_mode().unwrap();
        let failure = inst.save().unwrap_err();
        assert_eq!(failure.status, Status::Error);
        assert!(failure.message.contains("a failure of the serializer"), "{}", failure.message);
        assert!(!failure.enters_error_state, "the unit stays usable");
    }
}
