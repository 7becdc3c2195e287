//! The conformance matrix of the FMI 3.0 C ABI, as `conformance.rs` is FMI 2.0's: every fmi3 function that
//! takes an instance, called with valid arguments on a fresh ParticleWallImpact instance in every state it
//! can be in (Model Exchange: Instantiated, Initialization Mode, Event Mode, Continuous-Time Mode,
//! Terminated, Error; Co-Simulation with eventModeUsed: Instantiated, Initialization Mode, Event Mode, Step
//! Mode, Terminated, Error), against the status FMI 3.0 says it must return: fmi3OK where the standard's
//! state machines (FMI 3.0, Secs. 3.2 and 4.2) allow the call, fmi3Error with a message otherwise, and
//! fmi3Error with a reason for the optional capabilities the units do not offer. Where the standard leaves
//! a state open, the FMI 2.0 choice holds (getters and the FMU state in the Error state, the nominals in
//! Instantiated). The matrix is written to docs/robustness.md; the test fails when the file differs
//! (`POWDERFMU_UPDATE_DOCS=1 cargo test --test conformance_fmi3` rewrites it).

#[macro_use]
mod host;
use host::fmi3::{Api3, EnterInit};
use host::*;

use powderfmu::fmi3::types::*;
use std::ffi::c_void;
use std::ptr::{null, null_mut};

const PWI: &str = "ParticleWallImpact";

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Instantiated,
    Initialization,
    Event,
    ContinuousTime,
    Step,
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
            Step => "Step Mode",
            Terminated => "Terminated",
            Error => "Error",
        }
    }
}

const ME_STATES: [State; 6] = [Instantiated, Initialization, Event, ContinuousTime, Terminated, Error];
const CS_STATES: [State; 6] = [Instantiated, Initialization, Event, Step, Terminated, Error];
const ALL: &[State] = &[Instantiated, Initialization, Event, ContinuousTime, Step, Terminated, Error];
const GETS: &[State] = &[Initialization, Event, ContinuousTime, Step, Terminated, Error];
const SET_FLOAT: &[State] = &[Instantiated, Initialization, Event, ContinuousTime, Step];
const SET_OTHER: &[State] = &[Instantiated, Initialization, Event, Step];
const EVALUATE: &[State] = &[Initialization, Event, ContinuousTime, Terminated, Error];

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Interface {
    Both,
    ModelExchange,
    CoSimulation,
}
use Interface::{Both, CoSimulation as Cs, ModelExchange as Me};

struct Function {
    name: &'static str,
    interface: Interface,
    /// False: an optional capability the units do not have (the model description says so).
    supported: bool,
    allowed: &'static [State],
}

const fn f(name: &'static str, interface: Interface, allowed: &'static [State]) -> Function {
    Function { name, interface, supported: true, allowed }
}

const fn no(name: &'static str, interface: Interface) -> Function {
    Function { name, interface, supported: false, allowed: &[] }
}

/// The getters and setters of the types no variable has: called with no value references, they do nothing
/// where the calling sequence allows them.
const OTHER_TYPES: [&str; 8] = ["Float32", "Int8", "UInt8", "Int16", "UInt16", "UInt32", "Int64", "UInt64"];

fn functions() -> Vec<Function> {
    let mut list = vec![
        f("fmi3SetDebugLogging", Both, ALL),
        f("fmi3EnterInitializationMode", Both, &[Instantiated]),
        f("fmi3ExitInitializationMode", Both, &[Initialization]),
        f("fmi3EnterEventMode", Both, &[ContinuousTime, Step]),
        f("fmi3Terminate", Both, &[Event, ContinuousTime, Step]),
        f("fmi3Reset", Both, ALL),
        f("fmi3GetFloat64", Both, GETS),
        f("fmi3GetInt32", Both, GETS),
        f("fmi3GetBoolean", Both, GETS),
        f("fmi3GetString", Both, GETS),
        f("fmi3GetBinary", Both, GETS),
        f("fmi3GetClock", Both, GETS),
        f("fmi3SetFloat64", Both, SET_FLOAT),
        f("fmi3SetInt32", Both, SET_OTHER),
        f("fmi3SetBoolean", Both, SET_OTHER),
        f("fmi3SetString", Both, SET_OTHER),
        f("fmi3SetBinary", Both, SET_OTHER),
        f("fmi3SetClock", Both, SET_OTHER),
    ];
    for t in OTHER_TYPES {
        list.push(f(Box::leak(format!("fmi3Get{t}").into_boxed_str()), Both, GETS));
        list.push(f(Box::leak(format!("fmi3Set{t}").into_boxed_str()), Both, SET_OTHER));
    }
    list.extend([
        no("fmi3GetNumberOfVariableDependencies", Both),
        no("fmi3GetVariableDependencies", Both),
        f("fmi3GetFMUState", Both, ALL),
        f("fmi3SetFMUState", Both, ALL),
        f("fmi3FreeFMUState", Both, ALL),
        f("fmi3SerializedFMUStateSize", Both, ALL),
        f("fmi3SerializeFMUState", Both, ALL),
        f("fmi3DeserializeFMUState", Both, ALL),
        no("fmi3GetDirectionalDerivative", Both),
        no("fmi3GetAdjointDerivative", Both),
        no("fmi3EnterConfigurationMode", Both),
        no("fmi3ExitConfigurationMode", Both),
        no("fmi3GetIntervalDecimal", Both),
        no("fmi3GetIntervalFraction", Both),
        no("fmi3GetShiftDecimal", Both),
        no("fmi3GetShiftFraction", Both),
        no("fmi3SetIntervalDecimal", Both),
        no("fmi3SetIntervalFraction", Both),
        no("fmi3SetShiftDecimal", Both),
        no("fmi3SetShiftFraction", Both),
        no("fmi3EvaluateDiscreteStates", Both),
        f("fmi3UpdateDiscreteStates", Both, &[Event]),
        f("fmi3EnterContinuousTimeMode", Me, &[Event]),
        f("fmi3CompletedIntegratorStep", Me, &[ContinuousTime]),
        f("fmi3SetTime", Me, &[Event, ContinuousTime]),
        f("fmi3SetContinuousStates", Me, &[ContinuousTime]),
        f("fmi3GetContinuousStateDerivatives", Me, EVALUATE),
        f("fmi3GetEventIndicators", Me, EVALUATE),
        f("fmi3GetContinuousStates", Me, EVALUATE),
        f("fmi3GetNominalsOfContinuousStates", Me, &[Instantiated, Initialization, Event, ContinuousTime, Terminated, Error]),
        f("fmi3GetNumberOfEventIndicators", Me, ALL),
        f("fmi3GetNumberOfContinuousStates", Me, ALL),
        f("fmi3EnterStepMode", Cs, &[Event]),
        no("fmi3GetOutputDerivatives", Cs),
        f("fmi3DoStep", Cs, &[Step]),
        no("fmi3ActivateModelPartition", Both),
    ]);
    list
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Expect {
    Ok,
    Sequence,
    OtherInterface,
    NotSupported,
}

impl Expect {
    fn cell(self) -> &'static str {
        match self {
            Expect::Ok => "OK",
            Expect::Sequence => "Error",
            Expect::OtherInterface => "Error (interface)",
            Expect::NotSupported => "Error (not supported)",
        }
    }

    fn words(self, state: State) -> Vec<&'static str> {
        match self {
            Expect::Ok => vec![],
            Expect::Sequence => vec!["must not be called in", state.title()],
            Expect::OtherInterface => vec!["other interface"],
            Expect::NotSupported => vec!["not supported"],
        }
    }
}

fn expected(function: &Function, me: bool, state: State) -> Expect {
    let mine = match function.interface {
        Both => true,
        Me => me,
        Cs => !me,
    };
    if !mine {
        Expect::OtherInterface
    } else if !function.supported {
        Expect::NotSupported
    } else if !function.allowed.contains(&state) {
        Expect::Sequence
    } else {
        Expect::Ok
    }
}

type Update = unsafe extern "C" fn(Comp, *mut bool, *mut bool, *mut bool, *mut bool, *mut bool, *mut f64) -> fmi3Status;

fn update(api: &Api3, c: Comp) -> fmi3Status {
    let mut b = [false; 5];
    let mut t = 0.0;
    let [b0, b1, b2, b3, b4] = &mut b;
    unsafe { api.sym::<Update>(b"fmi3UpdateDiscreteStates")(c, b0, b1, b2, b3, b4, &mut t) }
}

/// A fresh instance brought into `state` by valid calls (Co-Simulation with eventModeUsed).
fn drive(api: &Api3, me: bool, state: State, log: &Log) -> Comp {
    let c = api.instantiate(PWI, me, true, true, log);
    assert!(!c.is_null(), "{:?}", log.lock().unwrap().last());
    let ok = |s: fmi3Status, what: &str| assert_eq!(s, fmi3OK, "{what} while driving to {state:?}: {:?}", log.lock().unwrap().last());
    if state == Instantiated {
        return c;
    }
    if state == Error {
        ok(api.set(c, PWI, "particle_radius", -1e-6), "fmi3SetFloat64");
        ok(api.enter_initialization(c), "fmi3EnterInitializationMode");
        assert_eq!(api.call0(b"fmi3ExitInitializationMode", c), fmi3Error);
        return c;
    }
    ok(api.enter_initialization(c), "fmi3EnterInitializationMode");
    if state == Initialization {
        return c;
    }
    ok(api.call0(b"fmi3ExitInitializationMode", c), "fmi3ExitInitializationMode");
    match state {
        ContinuousTime => {
            ok(update(api, c), "fmi3UpdateDiscreteStates");
            ok(api.call0(b"fmi3EnterContinuousTimeMode", c), "fmi3EnterContinuousTimeMode");
        }
        Step => ok(api.call0(b"fmi3EnterStepMode", c), "fmi3EnterStepMode"),
        Terminated => ok(api.call0(b"fmi3Terminate", c), "fmi3Terminate"),
        _ => {}
    }
    c
}

type GetState = unsafe extern "C" fn(Comp, *mut fmi3FMUState) -> fmi3Status;
type StateSize = unsafe extern "C" fn(Comp, fmi3FMUState, *mut usize) -> fmi3Status;
type Serialize = unsafe extern "C" fn(Comp, fmi3FMUState, *mut u8, usize) -> fmi3Status;
type Deserialize = unsafe extern "C" fn(Comp, *const u8, usize, *mut fmi3FMUState) -> fmi3Status;

/// The serialized FMU state of `c` and a live state made from it.
fn snapshot(api: &Api3, c: Comp) -> Vec<u8> {
    unsafe {
        let mut s: fmi3FMUState = null_mut();
        assert_eq!(api.sym::<GetState>(b"fmi3GetFMUState")(c, &mut s), fmi3OK);
        let mut size = 0usize;
        api.sym::<StateSize>(b"fmi3SerializedFMUStateSize")(c, s, &mut size);
        let mut bytes = vec![0u8; size];
        api.sym::<Serialize>(b"fmi3SerializeFMUState")(c, s, bytes.as_mut_ptr(), size);
        api.sym::<GetState>(b"fmi3FreeFMUState")(c, &mut s);
        bytes
    }
}

/// Calls `name` with valid arguments on `c`.
fn invoke(api: &Api3, name: &str, c: Comp, me: bool, log: &Log) -> fmi3Status {
    let vr = |n: &str| Api3::vr(PWI, n);
    let mut real = [0.0f64; 6];
    let mut int = 0i32;
    let mut string: fmi3String = null();
    let mut size = 0usize;
    let p = null_mut::<c_void>();
    type Typed = unsafe extern "C" fn(Comp, *const fmi3ValueReference, usize, *mut c_void, usize) -> fmi3Status;
    type Binary = unsafe extern "C" fn(Comp, *const fmi3ValueReference, usize, *mut usize, *mut c_void, usize) -> fmi3Status;
    type Clock = unsafe extern "C" fn(Comp, *const fmi3ValueReference, usize, *mut c_void) -> fmi3Status;
    type Two = unsafe extern "C" fn(Comp, *const fmi3ValueReference, usize, *mut c_void, *mut c_void) -> fmi3Status;
    type Three = unsafe extern "C" fn(Comp, *const fmi3ValueReference, usize, *mut c_void, *mut c_void, *mut c_void) -> fmi3Status;
    type Vector = unsafe extern "C" fn(Comp, *mut f64, usize) -> fmi3Status;
    type Count = unsafe extern "C" fn(Comp, *mut usize) -> fmi3Status;
    type Derivative = unsafe extern "C" fn(Comp, *const u32, usize, *const u32, usize, *const f64, usize, *mut f64, usize) -> fmi3Status;
    let n = name.as_bytes();
    unsafe {
        match name {
            "fmi3SetDebugLogging" => api.sym::<unsafe extern "C" fn(Comp, bool, usize, *const fmi3String) -> fmi3Status>(n)(c, true, 0, null()),
            "fmi3EnterInitializationMode" => api.sym::<EnterInit>(n)(c, false, 0.0, 0.0, false, 0.0),
            "fmi3ExitInitializationMode"
            | "fmi3EnterEventMode"
            | "fmi3Terminate"
            | "fmi3Reset"
            | "fmi3EnterConfigurationMode"
            | "fmi3ExitConfigurationMode"
            | "fmi3EvaluateDiscreteStates"
            | "fmi3EnterContinuousTimeMode"
            | "fmi3EnterStepMode" => api.call0(n, c),
            "fmi3GetFloat64" => api.sym::<Typed>(n)(c, &vr("sphere_velocity"), 1, real.as_mut_ptr().cast(), 1),
            "fmi3GetInt32" => api.sym::<Typed>(n)(c, &vr("contact_state"), 1, (&mut int as *mut i32).cast(), 1),
            "fmi3GetString" => api.sym::<Typed>(n)(c, &vr("contact_model"), 1, (&mut string as *mut fmi3String).cast(), 1),
            "fmi3SetFloat64" => api.sym::<Typed>(n)(c, &vr("wall_displacement"), 1, real.as_mut_ptr().cast(), 1),
            "fmi3GetBinary" | "fmi3SetBinary" => api.sym::<Binary>(n)(c, null(), 0, null_mut(), p, 0),
            "fmi3GetClock" | "fmi3SetClock" => api.sym::<Clock>(n)(c, null(), 0, p),
            "fmi3GetNumberOfVariableDependencies" => {
                api.sym::<unsafe extern "C" fn(Comp, fmi3ValueReference, *mut usize) -> fmi3Status>(n)(c, vr("force"), &mut size)
            }
            "fmi3GetVariableDependencies" => api.sym::<unsafe extern "C" fn(
                Comp,
                fmi3ValueReference,
                *mut usize,
                *mut u32,
                *mut usize,
                *mut fmi3DependencyKind,
                usize,
            ) -> fmi3Status>(n)(c, vr("force"), null_mut(), null_mut(), null_mut(), null_mut(), 0),
            "fmi3GetDirectionalDerivative" | "fmi3GetAdjointDerivative" => {
                api.sym::<Derivative>(n)(c, null(), 0, null(), 0, null(), 0, null_mut(), 0)
            }
            "fmi3GetShiftDecimal" | "fmi3SetIntervalDecimal" | "fmi3SetShiftDecimal" => api.sym::<Clock>(n)(c, null(), 0, p),
            "fmi3GetIntervalDecimal" | "fmi3GetShiftFraction" | "fmi3SetIntervalFraction" | "fmi3SetShiftFraction" => {
                api.sym::<Two>(n)(c, null(), 0, p, p)
            }
            "fmi3GetIntervalFraction" => api.sym::<Three>(n)(c, null(), 0, p, p, p),
            "fmi3GetFMUState" => {
                let mut s: fmi3FMUState = null_mut();
                let r = api.sym::<GetState>(n)(c, &mut s);
                if r == fmi3OK {
                    api.sym::<GetState>(b"fmi3FreeFMUState")(c, &mut s);
                }
                r
            }
            "fmi3SetFMUState" | "fmi3FreeFMUState" | "fmi3SerializedFMUStateSize" | "fmi3SerializeFMUState" | "fmi3DeserializeFMUState" => {
                // A state of a helper instance of the same interface.
                let helper_log = Log::default();
                let helper = api.instantiate(PWI, me, true, true, &helper_log);
                let mut s: fmi3FMUState = null_mut();
                assert_eq!(api.sym::<GetState>(b"fmi3GetFMUState")(helper, &mut s), fmi3OK);
                api.sym::<StateSize>(b"fmi3SerializedFMUStateSize")(helper, s, &mut size);
                let mut bytes = vec![0u8; size];
                api.sym::<Serialize>(b"fmi3SerializeFMUState")(helper, s, bytes.as_mut_ptr(), size);
                log.lock().unwrap().clear();
                let r = match name {
                    "fmi3SetFMUState" => api.sym::<unsafe extern "C" fn(Comp, fmi3FMUState) -> fmi3Status>(n)(c, s),
                    "fmi3FreeFMUState" => api.sym::<GetState>(n)(c, &mut s),
                    "fmi3SerializedFMUStateSize" => api.sym::<StateSize>(n)(c, s, &mut size),
                    "fmi3SerializeFMUState" => api.sym::<Serialize>(n)(c, s, bytes.as_mut_ptr(), size),
                    _ => {
                        let mut back: fmi3FMUState = null_mut();
                        let r = api.sym::<Deserialize>(n)(c, bytes.as_ptr(), size, &mut back);
                        if r == fmi3OK {
                            api.sym::<GetState>(b"fmi3FreeFMUState")(helper, &mut back);
                        }
                        r
                    }
                };
                if !s.is_null() {
                    api.sym::<GetState>(b"fmi3FreeFMUState")(helper, &mut s);
                }
                api.free(helper);
                r
            }
            "fmi3UpdateDiscreteStates" => update(api, c),
            "fmi3CompletedIntegratorStep" => {
                let (mut event, mut stop) = (false, false);
                api.sym::<unsafe extern "C" fn(Comp, bool, *mut bool, *mut bool) -> fmi3Status>(n)(c, true, &mut event, &mut stop)
            }
            "fmi3SetTime" => api.sym::<unsafe extern "C" fn(Comp, f64) -> fmi3Status>(n)(c, 0.0),
            "fmi3SetContinuousStates" => {
                api.sym::<unsafe extern "C" fn(Comp, *const f64, usize) -> fmi3Status>(n)(c, [2.45e-9, -1.0, 0.0, 0.0, 0.0, 0.0].as_ptr(), 6)
            }
            // Six states (the normal three, the motion along the wall, the spin and the spring), four indicators.
            "fmi3GetEventIndicators" => api.sym::<Vector>(n)(c, real.as_mut_ptr(), 4),
            "fmi3GetContinuousStateDerivatives" | "fmi3GetContinuousStates" | "fmi3GetNominalsOfContinuousStates" => {
                api.sym::<Vector>(n)(c, real.as_mut_ptr(), 6)
            }
            "fmi3GetNumberOfEventIndicators" | "fmi3GetNumberOfContinuousStates" => api.sym::<Count>(n)(c, &mut size),
            "fmi3GetOutputDerivatives" => api.sym::<unsafe extern "C" fn(Comp, *const u32, usize, *const i32, *mut f64, usize) -> fmi3Status>(n)(
                c,
                &vr("force"),
                1,
                &1,
                real.as_mut_ptr(),
                1,
            ),
            "fmi3DoStep" => api.do_step(c, 0.0, 1e-9).0,
            "fmi3ActivateModelPartition" => api.sym::<unsafe extern "C" fn(Comp, u32, f64) -> fmi3Status>(n)(c, 0, 0.0),
            other if other.starts_with("fmi3Get") || other.starts_with("fmi3Set") => api.sym::<Typed>(n)(c, null(), 0, p, 0),
            other => panic!("no call written for {other}"),
        }
    }
}

fn table(me: bool, states: &[State], rows: &[(String, Vec<Expect>)]) -> String {
    let title = if me { "FMI 3.0 Model Exchange instance" } else { "FMI 3.0 Co-Simulation instance (eventModeUsed, earlyReturnAllowed)" };
    let mut out = format!(
        "#### {title}\n\n| function | {} |\n|---|{}\n",
        states.iter().map(|s| s.title()).collect::<Vec<_>>().join(" | "),
        "---|".repeat(states.len())
    );
    for (name, row) in rows {
        out += &format!("| `{name}` | {} |\n", row.iter().map(|e| e.cell()).collect::<Vec<_>>().join(" | "));
    }
    out
}

#[test]
fn every_function_in_every_state_returns_what_fmi_3_0_says() {
    let lib = library();
    let api = Api3 { lib: &lib };
    let list = functions();
    assert_eq!(list.len(), 70, "every fmi3 function that takes an instance: the 75 less GetVersion, the three instantiates and FreeInstance");
    let mut failures = Vec::new();
    let mut doc = String::new();
    for (me, states) in [(true, &ME_STATES[..]), (false, &CS_STATES[..])] {
        let mut rows = Vec::new();
        for function in &list {
            let mut row = Vec::new();
            for &state in states {
                let log = Log::default();
                let c = drive(&api, me, state, &log);
                let before = snapshot(&api, c);
                log.lock().unwrap().clear();
                let got = invoke(&api, function.name, c, me, &log);
                let want = expected(function, me, state);
                let messages: Vec<String> = log.lock().unwrap().iter().filter(|m| m.0 == fmi3Error).map(|m| m.2.clone()).collect();
                let want_status = if want == Expect::Ok { fmi3OK } else { fmi3Error };
                let kind = if me { "ME" } else { "CS" };
                if got != want_status {
                    failures.push(format!("{} in {state:?} ({kind}): status {got}, want {want_status} ({want:?}); log {messages:?}", function.name));
                } else if want != Expect::Ok {
                    let words = want.words(state);
                    if !messages.iter().any(|m| m.contains(function.name) && words.iter().all(|w| m.contains(w))) {
                        failures.push(format!("{} in {state:?} ({kind}): message {messages:?} lacks the function name or {words:?}", function.name));
                    }
                    if snapshot(&api, c) != before {
                        failures.push(format!("{} in {state:?} ({kind}): refused, but the instance changed", function.name));
                    }
                }
                api.free(c);
                row.push(want);
            }
            rows.push((function.name.to_string(), row));
        }
        doc += &table(me, states, &rows);
        doc += "\n";
    }
    assert!(failures.is_empty(), "{} cells differ from FMI 3.0:\n{}", failures.len(), failures.join("\n"));
    check_doc(&doc);
}

const BEGIN: &str = "<!-- conformance3:begin -->";
const END: &str = "<!-- conformance3:end -->";

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
    panic!("docs/robustness.md does not hold the current FMI 3.0 conformance matrix; run POWDERFMU_UPDATE_DOCS=1 cargo test --test conformance_fmi3");
}
