//! The conformance matrix of the C ABI: every fmi2 function that takes an instance, called with valid
//! arguments on a fresh ParticleWallImpact instance in every state it can be in (Model Exchange:
//! Instantiated, Initialization Mode, Event Mode, Continuous-Time Mode, Terminated, Error; Co-Simulation:
//! Instantiated, Initialization Mode, Step Complete, Terminated, Error), against the status FMI 2.0 says it
//! must return: fmi2OK where the standard's tables of allowed calls (FMI 2.0.4, Secs. 3.2.3 and 4.2.4)
//! allow the call, fmi2Error with a message otherwise, and fmi2Error with a reason for the optional
//! capabilities the units do not offer; fmi2Discard for a status kind the units do not have (Sec. 4.2.3). The matrix is written to docs/robustness.md; the test fails when
//! the file differs (`POWDERFMU_UPDATE_DOCS=1 cargo test --test conformance` rewrites it).

#[macro_use]
mod host;
use host::*;

use powderfmu::fmi2::types::*;
use powderfmu::units;
use std::ptr::{null, null_mut};

const PWI: &str = "ParticleWallImpact";

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Instantiated,
    Initialization,
    Event,
    ContinuousTime,
    StepComplete,
    Terminated,
    Error,
}
use State::*;

impl State {
    fn title(self) -> &'static str {
        match self {
            Instantiated => "Instantiated",
            Initialization => "Initialization Mode",
            Event => "Event Mode",
            ContinuousTime => "Continuous-Time Mode",
            StepComplete => "Step Complete",
            Terminated => "Terminated",
            Error => "Error",
        }
    }
}

const ME_STATES: [State; 6] = [Instantiated, Initialization, Event, ContinuousTime, Terminated, Error];
const CS_STATES: [State; 5] = [Instantiated, Initialization, StepComplete, Terminated, Error];
const ALL: &[State] = &[Instantiated, Initialization, Event, ContinuousTime, StepComplete, Terminated, Error];
const GETS: &[State] = &[Initialization, Event, ContinuousTime, StepComplete, Terminated, Error];

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Interface {
    Both,
    ModelExchange,
    CoSimulation,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Support {
    Full,
    /// An optional capability the units do not have (the model description says so).
    Unsupported,
    /// Allowed, but the status kind asked for exists only for asynchronous steps (fmi2Pending).
    AsynchronousOnly,
}

/// One function: where the standard allows it, and what the units offer.
struct Function {
    name: &'static str,
    interface: Interface,
    support: Support,
    allowed: &'static [State],
}

const fn f(name: &'static str, interface: Interface, support: Support, allowed: &'static [State]) -> Function {
    Function { name, interface, support, allowed }
}

use Interface::{Both, CoSimulation as Cs, ModelExchange as Me};
use Support::{AsynchronousOnly, Full, Unsupported};

/// The FMI 2.0 tables of allowed calls (Fatal, which no valid call reaches, is left out). Where the
/// standard's state machine figure and its table disagree (fmi2GetDerivatives and the nominals in
/// Initialization Mode), the table holds (the standard's own errata, fmi-standard issues 301 and 395).
const FUNCTIONS: &[Function] = &[
    f("fmi2SetDebugLogging", Both, Full, ALL),
    f("fmi2SetupExperiment", Both, Full, &[Instantiated]),
    f("fmi2EnterInitializationMode", Both, Full, &[Instantiated]),
    f("fmi2ExitInitializationMode", Both, Full, &[Initialization]),
    f("fmi2Terminate", Both, Full, &[Event, ContinuousTime, StepComplete]),
    f("fmi2Reset", Both, Full, ALL),
    f("fmi2GetReal", Both, Full, GETS),
    f("fmi2GetInteger", Both, Full, GETS),
    f("fmi2GetBoolean", Both, Full, GETS),
    f("fmi2GetString", Both, Full, GETS),
    f("fmi2SetReal", Both, Full, &[Instantiated, Initialization, Event, ContinuousTime, StepComplete]),
    f("fmi2SetInteger", Both, Full, &[Instantiated, Initialization, Event, StepComplete]),
    f("fmi2SetBoolean", Both, Full, &[Instantiated, Initialization, Event, StepComplete]),
    f("fmi2SetString", Both, Full, &[Instantiated, Initialization, Event, StepComplete]),
    f("fmi2GetFMUstate", Both, Full, ALL),
    f("fmi2SetFMUstate", Both, Full, ALL),
    f("fmi2FreeFMUstate", Both, Full, ALL),
    f("fmi2SerializedFMUstateSize", Both, Full, ALL),
    f("fmi2SerializeFMUstate", Both, Full, ALL),
    f("fmi2DeSerializeFMUstate", Both, Full, ALL),
    f("fmi2GetDirectionalDerivative", Both, Unsupported, GETS),
    f("fmi2EnterEventMode", Me, Full, &[Event, ContinuousTime]),
    f("fmi2NewDiscreteStates", Me, Full, &[Event]),
    f("fmi2EnterContinuousTimeMode", Me, Full, &[Event]),
    f("fmi2CompletedIntegratorStep", Me, Full, &[ContinuousTime]),
    f("fmi2SetTime", Me, Full, &[Event, ContinuousTime]),
    f("fmi2SetContinuousStates", Me, Full, &[ContinuousTime]),
    f("fmi2GetDerivatives", Me, Full, &[Initialization, Event, ContinuousTime, Terminated, Error]),
    f("fmi2GetEventIndicators", Me, Full, &[Initialization, Event, ContinuousTime, Terminated, Error]),
    f("fmi2GetContinuousStates", Me, Full, &[Initialization, Event, ContinuousTime, Terminated, Error]),
    f("fmi2GetNominalsOfContinuousStates", Me, Full, &[Instantiated, Initialization, Event, ContinuousTime, Terminated, Error]),
    f("fmi2SetRealInputDerivatives", Cs, Full, &[Instantiated, Initialization, StepComplete]),
    f("fmi2GetRealOutputDerivatives", Cs, Unsupported, &[StepComplete, Terminated, Error]),
    f("fmi2DoStep", Cs, Full, &[StepComplete]),
    f("fmi2CancelStep", Cs, Unsupported, &[]),
    f("fmi2GetStatus", Cs, AsynchronousOnly, &[StepComplete, Terminated]),
    f("fmi2GetRealStatus", Cs, Full, &[StepComplete, Terminated]),
    f("fmi2GetIntegerStatus", Cs, AsynchronousOnly, &[StepComplete, Terminated]),
    f("fmi2GetBooleanStatus", Cs, Full, &[StepComplete, Terminated]),
    f("fmi2GetStringStatus", Cs, AsynchronousOnly, &[StepComplete, Terminated]),
];

/// What a cell must show.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Expect {
    Ok,
    /// Refused by the calling sequence: the message names the state.
    Sequence,
    /// A function of the other interface.
    OtherInterface,
    /// An optional capability the unit does not have.
    NotSupported,
    /// A status kind that only asynchronous steps have.
    NoSuchStatus,
}

impl Expect {
    fn cell(self) -> &'static str {
        match self {
            Expect::Ok => "OK",
            Expect::Sequence => "Error",
            Expect::OtherInterface => "Error (interface)",
            Expect::NotSupported => "Error (not supported)",
            Expect::NoSuchStatus => "Discard (no such status)",
        }
    }

    /// Words the logged message must contain.
    fn words(self, state: State) -> Vec<String> {
        match self {
            Expect::Ok => vec![],
            Expect::Sequence => vec!["must not be called in".into(), state_name(state).into()],
            Expect::OtherInterface => vec!["other interface".into()],
            Expect::NotSupported => vec![],
            Expect::NoSuchStatus => vec!["not available".into()],
        }
    }
}

/// The state's name in the unit's messages.
fn state_name(state: State) -> &'static str {
    match state {
        ContinuousTime => "Continuous-Time Mode",
        other => other.title(),
    }
}

fn expected(function: &Function, kind: fmi2Type, state: State) -> Expect {
    let mine = match function.interface {
        Both => true,
        Me => kind == fmi2ModelExchange,
        Cs => kind == fmi2CoSimulation,
    };
    if !mine {
        Expect::OtherInterface
    } else if function.support == Unsupported {
        Expect::NotSupported
    } else if !function.allowed.contains(&state) {
        Expect::Sequence
    } else if function.support == AsynchronousOnly {
        Expect::NoSuchStatus
    } else {
        Expect::Ok
    }
}

type Status1<A> = unsafe extern "C" fn(Comp, A) -> fmi2Status;

/// A fresh instance of `kind` brought into `state` by valid calls.
fn drive(api: &Api, kind: fmi2Type, state: State, log: &Log) -> Comp {
    let c = api.instantiate(PWI, kind, log, None);
    assert!(!c.is_null());
    let setup = f!(api, b"fmi2SetupExperiment", Setup);
    let ok = |s: fmi2Status, what: &str| assert_eq!(s, fmi2OK, "{what} while driving to {state:?}: {:?}", log.lock().unwrap().last());
    if state == Instantiated {
        return c;
    }
    if state == Error {
        // A failed computation: initialization with an invalid parameter.
        ok(api.set(c, PWI, "particle_radius", -1e-6), "fmi2SetReal");
        ok(unsafe { setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) }, "fmi2SetupExperiment");
        ok(api.call0(b"fmi2EnterInitializationMode", c), "fmi2EnterInitializationMode");
        assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2Error);
        return c;
    }
    ok(unsafe { setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) }, "fmi2SetupExperiment");
    ok(api.call0(b"fmi2EnterInitializationMode", c), "fmi2EnterInitializationMode");
    if state == Initialization {
        return c;
    }
    ok(api.call0(b"fmi2ExitInitializationMode", c), "fmi2ExitInitializationMode");
    if state == ContinuousTime {
        let mut info = fmi2EventInfo::default();
        ok(unsafe { f!(api, b"fmi2NewDiscreteStates", Status1<*mut fmi2EventInfo>)(c, &mut info) }, "fmi2NewDiscreteStates");
        ok(api.call0(b"fmi2EnterContinuousTimeMode", c), "fmi2EnterContinuousTimeMode");
    }
    if state == Terminated {
        ok(api.call0(b"fmi2Terminate", c), "fmi2Terminate");
    }
    c
}

/// The serialized FMU state of `c`: everything the instance holds.
fn snapshot(api: &Api, c: Comp) -> Vec<u8> {
    unsafe {
        let mut s: fmi2FMUstate = null_mut();
        assert_eq!(f!(api, b"fmi2GetFMUstate", Status1<*mut fmi2FMUstate>)(c, &mut s), fmi2OK);
        let mut size = 0usize;
        f!(api, b"fmi2SerializedFMUstateSize", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut usize) -> fmi2Status)(c, s, &mut size);
        let mut bytes = vec![0 as fmi2Byte; size];
        f!(api, b"fmi2SerializeFMUstate", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut fmi2Byte, usize) -> fmi2Status)(
            c,
            s,
            bytes.as_mut_ptr(),
            size,
        );
        f!(api, b"fmi2FreeFMUstate", Status1<*mut fmi2FMUstate>)(c, &mut s);
        bytes.into_iter().map(|b| b as u8).collect()
    }
}

/// A saved state of a helper instance of the same kind, for the functions that take one.
fn saved_state(api: &Api, kind: fmi2Type, log: &Log) -> (Comp, fmi2FMUstate) {
    let helper = api.instantiate(PWI, kind, log, None);
    let mut s: fmi2FMUstate = null_mut();
    assert_eq!(unsafe { f!(api, b"fmi2GetFMUstate", Status1<*mut fmi2FMUstate>)(helper, &mut s) }, fmi2OK);
    (helper, s)
}

/// Calls `name` with valid arguments on `c`.
fn invoke(api: &Api, name: &str, c: Comp, kind: fmi2Type, log: &Log) -> fmi2Status {
    let unit = units::by_identifier(PWI).unwrap();
    let vr = |n: &str| unit.vr(n).expect("a variable of the unit") as fmi2ValueReference;
    let mut real = [0.0f64; 6];
    let mut int: fmi2Integer = 0;
    let mut boolean: fmi2Boolean = 0;
    let mut string: fmi2String = null();
    let mut status: fmi2Status = fmi2OK;
    unsafe {
        match name {
            "fmi2SetDebugLogging" => {
                f!(api, b"fmi2SetDebugLogging", unsafe extern "C" fn(Comp, fmi2Boolean, usize, *const fmi2String) -> fmi2Status)(
                    c,
                    fmi2True,
                    0,
                    null(),
                )
            }
            "fmi2SetupExperiment" => f!(api, b"fmi2SetupExperiment", Setup)(c, fmi2False, 0.0, 0.0, fmi2False, 0.0),
            "fmi2EnterInitializationMode"
            | "fmi2ExitInitializationMode"
            | "fmi2Terminate"
            | "fmi2Reset"
            | "fmi2EnterEventMode"
            | "fmi2EnterContinuousTimeMode"
            | "fmi2CancelStep" => api.call0(name.as_bytes(), c),
            "fmi2GetReal" => f!(api, b"fmi2GetReal", GetReal)(c, &vr("sphere_velocity"), 1, real.as_mut_ptr()),
            "fmi2GetInteger" => f!(
                api,
                b"fmi2GetInteger",
                unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *mut fmi2Integer) -> fmi2Status
            )(c, &vr("contact_state"), 1, &mut int),
            "fmi2GetBoolean" => f!(
                api,
                b"fmi2GetBoolean",
                unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *mut fmi2Boolean) -> fmi2Status
            )(c, null(), 0, null_mut()),
            "fmi2GetString" => {
                f!(api, b"fmi2GetString", unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *mut fmi2String) -> fmi2Status)(
                    c,
                    &vr("contact_model"),
                    1,
                    &mut string,
                )
            }
            "fmi2SetReal" => f!(api, b"fmi2SetReal", SetReal)(c, &vr("wall_displacement"), 1, &0.0),
            "fmi2SetInteger" => f!(
                api,
                b"fmi2SetInteger",
                unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *const fmi2Integer) -> fmi2Status
            )(c, null(), 0, null()),
            "fmi2SetBoolean" => f!(
                api,
                b"fmi2SetBoolean",
                unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *const fmi2Boolean) -> fmi2Status
            )(c, null(), 0, null()),
            "fmi2SetString" => f!(
                api,
                b"fmi2SetString",
                unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *const fmi2String) -> fmi2Status
            )(c, null(), 0, null()),
            "fmi2GetFMUstate" => {
                let mut s: fmi2FMUstate = null_mut();
                let r = f!(api, b"fmi2GetFMUstate", Status1<*mut fmi2FMUstate>)(c, &mut s);
                if r == fmi2OK {
                    f!(api, b"fmi2FreeFMUstate", Status1<*mut fmi2FMUstate>)(c, &mut s);
                }
                r
            }
            "fmi2SetFMUstate" | "fmi2FreeFMUstate" | "fmi2SerializedFMUstateSize" | "fmi2SerializeFMUstate" | "fmi2DeSerializeFMUstate" => {
                let (helper, mut s) = saved_state(api, kind, log);
                let mut size = 0usize;
                f!(api, b"fmi2SerializedFMUstateSize", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut usize) -> fmi2Status)(helper, s, &mut size);
                let mut bytes = vec![0 as fmi2Byte; size];
                f!(api, b"fmi2SerializeFMUstate", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut fmi2Byte, usize) -> fmi2Status)(
                    helper,
                    s,
                    bytes.as_mut_ptr(),
                    size,
                );
                log.lock().unwrap().clear();
                let r = match name {
                    "fmi2SetFMUstate" => f!(api, b"fmi2SetFMUstate", Status1<fmi2FMUstate>)(c, s),
                    "fmi2FreeFMUstate" => f!(api, b"fmi2FreeFMUstate", Status1<*mut fmi2FMUstate>)(c, &mut s),
                    "fmi2SerializedFMUstateSize" => {
                        f!(api, b"fmi2SerializedFMUstateSize", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut usize) -> fmi2Status)(c, s, &mut size)
                    }
                    "fmi2SerializeFMUstate" => f!(
                        api,
                        b"fmi2SerializeFMUstate",
                        unsafe extern "C" fn(Comp, fmi2FMUstate, *mut fmi2Byte, usize) -> fmi2Status
                    )(c, s, bytes.as_mut_ptr(), size),
                    _ => {
                        let mut back: fmi2FMUstate = null_mut();
                        let r = f!(
                            api,
                            b"fmi2DeSerializeFMUstate",
                            unsafe extern "C" fn(Comp, *const fmi2Byte, usize, *mut fmi2FMUstate) -> fmi2Status
                        )(c, bytes.as_ptr(), size, &mut back);
                        if r == fmi2OK {
                            f!(api, b"fmi2FreeFMUstate", Status1<*mut fmi2FMUstate>)(helper, &mut back);
                        }
                        r
                    }
                };
                if !s.is_null() {
                    f!(api, b"fmi2FreeFMUstate", Status1<*mut fmi2FMUstate>)(helper, &mut s);
                }
                api.free(helper);
                r
            }
            "fmi2GetDirectionalDerivative" => f!(
                api,
                b"fmi2GetDirectionalDerivative",
                unsafe extern "C" fn(
                    Comp,
                    *const fmi2ValueReference,
                    usize,
                    *const fmi2ValueReference,
                    usize,
                    *const fmi2Real,
                    *mut fmi2Real,
                ) -> fmi2Status
            )(c, null(), 0, null(), 0, null(), null_mut()),
            "fmi2NewDiscreteStates" => {
                let mut info = fmi2EventInfo::default();
                f!(api, b"fmi2NewDiscreteStates", Status1<*mut fmi2EventInfo>)(c, &mut info)
            }
            "fmi2CompletedIntegratorStep" => {
                let (mut event, mut stop) = (fmi2False, fmi2False);
                f!(api, b"fmi2CompletedIntegratorStep", unsafe extern "C" fn(Comp, fmi2Boolean, *mut fmi2Boolean, *mut fmi2Boolean) -> fmi2Status)(
                    c, fmi2True, &mut event, &mut stop,
                )
            }
            "fmi2SetTime" => f!(api, b"fmi2SetTime", Status1<fmi2Real>)(c, 0.0),
            "fmi2SetContinuousStates" => f!(api, b"fmi2SetContinuousStates", SetVector)(c, [2.45e-9, -1.0, 0.0, 0.0, 0.0, 0.0].as_ptr(), 6),
            // Six states (the normal three, the motion along the wall, the spin and the spring), four indicators.
            "fmi2GetEventIndicators" => f!(api, name.as_bytes(), Vector)(c, real.as_mut_ptr(), 4),
            "fmi2GetDerivatives" | "fmi2GetContinuousStates" | "fmi2GetNominalsOfContinuousStates" => {
                f!(api, name.as_bytes(), Vector)(c, real.as_mut_ptr(), 6)
            }
            "fmi2SetRealInputDerivatives" => f!(
                api,
                b"fmi2SetRealInputDerivatives",
                unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *const fmi2Integer, *const fmi2Real) -> fmi2Status
            )(c, &vr("wall_displacement"), 1, &1, &0.0),
            "fmi2GetRealOutputDerivatives" => f!(
                api,
                b"fmi2GetRealOutputDerivatives",
                unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *const fmi2Integer, *mut fmi2Real) -> fmi2Status
            )(c, &vr("force"), 1, &1, real.as_mut_ptr()),
            "fmi2DoStep" => f!(api, b"fmi2DoStep", DoStep)(c, 0.0, 1e-9, fmi2True),
            "fmi2GetStatus" => {
                f!(api, b"fmi2GetStatus", unsafe extern "C" fn(Comp, fmi2StatusKind, *mut fmi2Status) -> fmi2Status)(c, fmi2DoStepStatus, &mut status)
            }
            "fmi2GetRealStatus" => f!(api, b"fmi2GetRealStatus", unsafe extern "C" fn(Comp, fmi2StatusKind, *mut fmi2Real) -> fmi2Status)(
                c,
                fmi2LastSuccessfulTime,
                real.as_mut_ptr(),
            ),
            "fmi2GetIntegerStatus" => f!(api, b"fmi2GetIntegerStatus", unsafe extern "C" fn(Comp, fmi2StatusKind, *mut fmi2Integer) -> fmi2Status)(
                c,
                fmi2DoStepStatus,
                &mut int,
            ),
            "fmi2GetBooleanStatus" => f!(api, b"fmi2GetBooleanStatus", unsafe extern "C" fn(Comp, fmi2StatusKind, *mut fmi2Boolean) -> fmi2Status)(
                c,
                fmi2Terminated,
                &mut boolean,
            ),
            "fmi2GetStringStatus" => f!(api, b"fmi2GetStringStatus", unsafe extern "C" fn(Comp, fmi2StatusKind, *mut fmi2String) -> fmi2Status)(
                c,
                fmi2PendingStatus,
                &mut string,
            ),
            other => panic!("no call written for {other}"),
        }
    }
}

fn table(kind: fmi2Type, states: &[State], cells: &[(String, Vec<Expect>)]) -> String {
    let title = if kind == fmi2ModelExchange { "Model Exchange instance" } else { "Co-Simulation instance" };
    let mut out = format!(
        "#### {title}\n\n| function | {} |\n|---|{}\n",
        states.iter().map(|s| s.title()).collect::<Vec<_>>().join(" | "),
        "---|".repeat(states.len())
    );
    for (name, row) in cells {
        out += &format!("| `{name}` | {} |\n", row.iter().map(|e| e.cell()).collect::<Vec<_>>().join(" | "));
    }
    out
}

#[test]
fn every_function_in_every_state_returns_what_fmi_2_0_says() {
    let lib = library();
    let api = Api { lib: &lib };
    let exported: Vec<&str> = FUNCTIONS.iter().map(|f| f.name).collect();
    assert_eq!(exported.len(), 40, "every fmi2 function that takes an instance, except instantiate and free");
    let mut failures = Vec::new();
    let mut doc = String::new();
    for (kind, states) in [(fmi2ModelExchange, &ME_STATES[..]), (fmi2CoSimulation, &CS_STATES[..])] {
        let mut rows = Vec::new();
        for function in FUNCTIONS {
            let mut row = Vec::new();
            for &state in states {
                let log = Log::default();
                let c = drive(&api, kind, state, &log);
                let before = snapshot(&api, c);
                log.lock().unwrap().clear();
                let got = invoke(&api, function.name, c, kind, &log);
                let want = expected(function, kind, state);
                let messages: Vec<String> = log.lock().unwrap().iter().filter(|m| m.0 != fmi2OK).map(|m| m.2.clone()).collect();
                let want_status = match want {
                    Expect::Ok => fmi2OK,
                    Expect::NoSuchStatus => fmi2Discard,
                    _ => fmi2Error,
                };
                if got != want_status {
                    failures.push(format!("{} in {state:?} ({kind}): status {got}, want {want_status} ({want:?}); log {messages:?}", function.name));
                } else if want != Expect::Ok {
                    let words = want.words(state);
                    let named = messages
                        .iter()
                        .any(|m| m.contains(function.name) || want == Expect::NotSupported && m.contains("not supported") || m.contains("never"));
                    if !(named && messages.iter().any(|m| words.iter().all(|w| m.contains(w.as_str())))) {
                        failures.push(format!("{} in {state:?} ({kind}): message {messages:?} lacks the function name or {words:?}", function.name));
                    }
                    // A refused call changes nothing: the saved state is the same to the bit.
                    if snapshot(&api, c) != before {
                        failures.push(format!("{} in {state:?} ({kind}): refused, but the instance changed", function.name));
                    }
                }
                api.free(c);
                row.push(want);
            }
            rows.push((function.name.to_string(), row));
        }
        doc += &table(kind, states, &rows);
        doc += "\n";
    }
    assert!(failures.is_empty(), "{} cells differ from FMI 2.0:\n{}", failures.len(), failures.join("\n"));
    check_doc(&doc);
}

const BEGIN: &str = "<!-- conformance:begin -->";
const END: &str = "<!-- conformance:end -->";

/// The generated matrix must be the one in docs/robustness.md.
fn check_doc(generated: &str) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/robustness.md");
    let text = std::fs::read_to_string(&path).unwrap_or_default();
    let block = format!("{BEGIN}\n{generated}{END}");
    let current = match (text.find(BEGIN), text.find(END)) {
        (Some(a), Some(b)) => &text[a..b + END.len()],
        _ => "",
    };
    if current == block {
        return;
    }
    if std::env::var("POWDERFMU_UPDATE_DOCS").is_ok() {
        let new = if current.is_empty() { format!("{text}\n{block}\n") } else { text.replace(current, &block) };
        std::fs::write(&path, new).unwrap();
        return;
    }
    panic!("docs/robustness.md does not hold the current conformance matrix; run POWDERFMU_UPDATE_DOCS=1 cargo test --test conformance");
}
