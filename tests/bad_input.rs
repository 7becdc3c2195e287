//! Bad input at the C ABI, argument by argument: a NULL for every pointer argument, lengths that do not
//! match, value references out of range, NaN and infinities, strings that are not UTF-8, a NULL or freed
//! instance. Each call returns fmi2Error and logs one message that names the function and the argument;
//! the instance is unchanged (its serialized state is the same to the bit) and goes on.

#[macro_use]
mod host;
use host::*;

use powderfmu::fmi2::types::*;
use powderfmu::units;
use std::ptr::{null, null_mut};

const PWI: &str = "ParticleWallImpact";

type GetR = unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *mut fmi2Real) -> fmi2Status;
type SetS = unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *const fmi2String) -> fmi2Status;
type GetS = unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *mut fmi2String) -> fmi2Status;
type GetI = unsafe extern "C" fn(Comp, *const fmi2ValueReference, usize, *mut fmi2Integer) -> fmi2Status;
type GetState = unsafe extern "C" fn(Comp, *mut fmi2FMUstate) -> fmi2Status;
type SetState = unsafe extern "C" fn(Comp, fmi2FMUstate) -> fmi2Status;
type StateSize = unsafe extern "C" fn(Comp, fmi2FMUstate, *mut usize) -> fmi2Status;
type Serialize = unsafe extern "C" fn(Comp, fmi2FMUstate, *mut fmi2Byte, usize) -> fmi2Status;
type Deserialize = unsafe extern "C" fn(Comp, *const fmi2Byte, usize, *mut fmi2FMUstate) -> fmi2Status;
type Logging = unsafe extern "C" fn(Comp, fmi2Boolean, usize, *const fmi2String) -> fmi2Status;
type RealStatus = unsafe extern "C" fn(Comp, fmi2StatusKind, *mut fmi2Real) -> fmi2Status;
type BoolStatus = unsafe extern "C" fn(Comp, fmi2StatusKind, *mut fmi2Boolean) -> fmi2Status;
type Discrete = unsafe extern "C" fn(Comp, *mut fmi2EventInfo) -> fmi2Status;
type Completed = unsafe extern "C" fn(Comp, fmi2Boolean, *mut fmi2Boolean, *mut fmi2Boolean) -> fmi2Status;

/// One bad call: what it is, the words its message must contain, and the call.
type Case<'a> = (&'static str, Vec<&'static str>, Box<dyn Fn() -> fmi2Status + 'a>);

/// An initialized instance of `kind` (CS: Step Complete; ME: Continuous-Time Mode).
fn ready(api: &Api, kind: fmi2Type, log: &Log) -> Comp {
    let c = api.instantiate(PWI, kind, log, None);
    unsafe { f!(api, b"fmi2SetupExperiment", Setup)(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) };
    api.call0(b"fmi2EnterInitializationMode", c);
    assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2OK);
    if kind == fmi2ModelExchange {
        let mut info = fmi2EventInfo::default();
        unsafe { f!(api, b"fmi2NewDiscreteStates", Discrete)(c, &mut info) };
        api.call0(b"fmi2EnterContinuousTimeMode", c);
    }
    c
}

fn serialized(api: &Api, c: Comp) -> Vec<fmi2Byte> {
    unsafe {
        let mut s = null_mut();
        assert_eq!(f!(api, b"fmi2GetFMUstate", GetState)(c, &mut s), fmi2OK);
        let mut n = 0;
        f!(api, b"fmi2SerializedFMUstateSize", StateSize)(c, s, &mut n);
        let mut b = vec![0; n];
        f!(api, b"fmi2SerializeFMUstate", Serialize)(c, s, b.as_mut_ptr(), n);
        f!(api, b"fmi2FreeFMUstate", GetState)(c, &mut s);
        b
    }
}

#[test]
fn every_bad_argument_is_refused_by_name_and_changes_nothing() {
    let lib = library();
    let api = Api { lib: &lib };
    let unit = units::by_identifier(PWI).unwrap();
    let vr = |n: &str| unit.vr(n).expect("a variable of the unit") as fmi2ValueReference;
    let beyond = unit.variables.len() as fmi2ValueReference;
    let not_utf8 = [0xffu8 as std::os::raw::c_char, 0xfe_u8 as std::os::raw::c_char, 0];
    let mut failures = Vec::new();
    let mut cases = 0;
    for kind in [fmi2CoSimulation, fmi2ModelExchange] {
        let log = Log::default();
        let c = ready(&api, kind, &log);
        let helper = ready(&api, kind, &log);
        let mut state: fmi2FMUstate = null_mut();
        unsafe { f!(api, b"fmi2GetFMUstate", GetState)(helper, &mut state) };
        let state = state;
        let real = [0.0f64; 8];
        let int = [0 as fmi2Integer; 2];
        let string: [fmi2String; 1] = [null()];
        let size = 0usize;
        let flag = fmi2False;
        let bytes = serialized(&api, helper);
        // (what, the words the message must contain, the call)
        let mut table: Vec<Case> = vec![
            (
                "GetReal vr NULL",
                vec!["fmi2GetReal", "vr"],
                Box::new(|| unsafe { f!(api, b"fmi2GetReal", GetR)(c, null(), 1, real.as_ptr() as *mut _) }),
            ),
            (
                "GetReal value NULL",
                vec!["fmi2GetReal", "value"],
                Box::new(|| unsafe { f!(api, b"fmi2GetReal", GetR)(c, &vr("force"), 1, null_mut()) }),
            ),
            (
                "GetReal vr beyond",
                vec!["fmi2GetReal", "value reference"],
                Box::new(|| unsafe { f!(api, b"fmi2GetReal", GetR)(c, &beyond, 1, real.as_ptr() as *mut _) }),
            ),
            (
                "GetReal absurd length",
                vec!["fmi2GetReal", "length"],
                Box::new(|| unsafe { f!(api, b"fmi2GetReal", GetR)(c, &vr("force"), usize::MAX, real.as_ptr() as *mut _) }),
            ),
            (
                "GetInteger of a Real",
                vec!["fmi2GetInteger", "force"],
                Box::new(|| unsafe { f!(api, b"fmi2GetInteger", GetI)(c, &vr("force"), 1, int.as_ptr() as *mut _) }),
            ),
            (
                "SetReal NaN input",
                vec!["fmi2SetReal", "wall_displacement", "not a finite"],
                Box::new(|| unsafe { f!(api, b"fmi2SetReal", SetReal)(c, &vr("wall_displacement"), 1, &f64::NAN) }),
            ),
            (
                "SetReal +inf input",
                vec!["fmi2SetReal", "wall_velocity", "not a finite"],
                Box::new(|| unsafe { f!(api, b"fmi2SetReal", SetReal)(c, &vr("wall_velocity"), 1, &f64::INFINITY) }),
            ),
            (
                "SetReal value NULL",
                vec!["fmi2SetReal", "value"],
                Box::new(|| unsafe { f!(api, b"fmi2SetReal", SetReal)(c, &vr("wall_velocity"), 1, null()) }),
            ),
            (
                "SetReal an output",
                vec!["fmi2SetReal", "force", "cannot be set"],
                Box::new(|| unsafe { f!(api, b"fmi2SetReal", SetReal)(c, &vr("force"), 1, &1.0) }),
            ),
            (
                "GetString value NULL",
                vec!["fmi2GetString", "value"],
                Box::new(|| unsafe { f!(api, b"fmi2GetString", GetS)(c, &vr("contact_model"), 1, null_mut()) }),
            ),
            (
                "GetString vr NULL",
                vec!["fmi2GetString", "vr"],
                Box::new(|| unsafe { f!(api, b"fmi2GetString", GetS)(c, null(), 1, string.as_ptr() as *mut _) }),
            ),
            (
                "SetDebugLogging categories NULL",
                vec!["fmi2SetDebugLogging", "categories"],
                Box::new(|| unsafe { f!(api, b"fmi2SetDebugLogging", Logging)(c, fmi2True, 2, null()) }),
            ),
            (
                "SetDebugLogging category not UTF-8",
                vec!["fmi2SetDebugLogging", "categories[0]"],
                Box::new(|| unsafe { f!(api, b"fmi2SetDebugLogging", Logging)(c, fmi2True, 1, &not_utf8.as_ptr()) }),
            ),
            ("GetFMUstate NULL", vec!["fmi2GetFMUstate", "FMUstate"], Box::new(|| unsafe { f!(api, b"fmi2GetFMUstate", GetState)(c, null_mut()) })),
            ("SetFMUstate NULL", vec!["fmi2SetFMUstate", "FMUstate"], Box::new(|| unsafe { f!(api, b"fmi2SetFMUstate", SetState)(c, null_mut()) })),
            (
                "SetFMUstate foreign pointer",
                vec!["fmi2SetFMUstate", "FMUstate"],
                Box::new(|| unsafe { f!(api, b"fmi2SetFMUstate", SetState)(c, real.as_ptr() as fmi2FMUstate) }),
            ),
            (
                "SerializedFMUstateSize state NULL",
                vec!["fmi2SerializedFMUstateSize", "FMUstate"],
                Box::new(|| unsafe { f!(api, b"fmi2SerializedFMUstateSize", StateSize)(c, null_mut(), &size as *const _ as *mut _) }),
            ),
            (
                "SerializedFMUstateSize size NULL",
                vec!["fmi2SerializedFMUstateSize", "size"],
                Box::new(|| unsafe { f!(api, b"fmi2SerializedFMUstateSize", StateSize)(c, state, null_mut()) }),
            ),
            (
                "SerializeFMUstate buffer NULL",
                vec!["fmi2SerializeFMUstate", "serializedState"],
                Box::new(|| unsafe { f!(api, b"fmi2SerializeFMUstate", Serialize)(c, state, null_mut(), bytes.len()) }),
            ),
            (
                "SerializeFMUstate size too small",
                vec!["fmi2SerializeFMUstate", "size"],
                Box::new(|| unsafe {
                    let mut b = vec![0; 8];
                    f!(api, b"fmi2SerializeFMUstate", Serialize)(c, state, b.as_mut_ptr(), 8)
                }),
            ),
            (
                "DeSerializeFMUstate bytes NULL",
                vec!["fmi2DeSerializeFMUstate", "serializedState"],
                Box::new(|| unsafe {
                    let mut s = null_mut();
                    f!(api, b"fmi2DeSerializeFMUstate", Deserialize)(c, null(), bytes.len(), &mut s)
                }),
            ),
            (
                "DeSerializeFMUstate out NULL",
                vec!["fmi2DeSerializeFMUstate", "FMUstate"],
                Box::new(|| unsafe { f!(api, b"fmi2DeSerializeFMUstate", Deserialize)(c, bytes.as_ptr(), bytes.len(), null_mut()) }),
            ),
            (
                "DeSerializeFMUstate truncated",
                vec!["fmi2DeSerializeFMUstate"],
                Box::new(|| unsafe {
                    let mut s = null_mut();
                    f!(api, b"fmi2DeSerializeFMUstate", Deserialize)(c, bytes.as_ptr(), bytes.len() - 9, &mut s)
                }),
            ),
        ];
        if kind == fmi2CoSimulation {
            // Strings can be set in Step Complete (not in Continuous-Time Mode).
            table.push((
                "SetString value NULL",
                vec!["fmi2SetString", "value"],
                Box::new(|| unsafe { f!(api, b"fmi2SetString", SetS)(c, &vr("contact_model"), 1, null()) }),
            ));
            table.push((
                "SetString not UTF-8",
                vec!["fmi2SetString", "UTF-8"],
                Box::new(|| unsafe { f!(api, b"fmi2SetString", SetS)(c, &vr("contact_model"), 1, &not_utf8.as_ptr()) }),
            ));
            table.push((
                "DoStep NaN step",
                vec!["fmi2DoStep", "finite"],
                Box::new(|| unsafe { f!(api, b"fmi2DoStep", DoStep)(c, 0.0, f64::NAN, fmi2True) }),
            ));
            table.push((
                "DoStep zero step",
                vec!["fmi2DoStep", "positive"],
                Box::new(|| unsafe { f!(api, b"fmi2DoStep", DoStep)(c, 0.0, 0.0, fmi2True) }),
            ));
            table.push((
                "DoStep negative step",
                vec!["fmi2DoStep", "positive"],
                Box::new(|| unsafe { f!(api, b"fmi2DoStep", DoStep)(c, 0.0, -1e-9, fmi2True) }),
            ));
            table.push((
                "DoStep infinite time",
                vec!["fmi2DoStep", "finite"],
                Box::new(|| unsafe { f!(api, b"fmi2DoStep", DoStep)(c, f64::INFINITY, 1e-9, fmi2True) }),
            ));
            table.push((
                "GetRealStatus value NULL",
                vec!["fmi2GetRealStatus", "value"],
                Box::new(|| unsafe { f!(api, b"fmi2GetRealStatus", RealStatus)(c, fmi2LastSuccessfulTime, null_mut()) }),
            ));
            table.push((
                "GetBooleanStatus value NULL",
                vec!["fmi2GetBooleanStatus", "value"],
                Box::new(|| unsafe { f!(api, b"fmi2GetBooleanStatus", BoolStatus)(c, fmi2Terminated, null_mut()) }),
            ));
        } else {
            table.push((
                "SetContinuousStates x NULL",
                vec!["fmi2SetContinuousStates", "x"],
                Box::new(|| unsafe { f!(api, b"fmi2SetContinuousStates", SetVector)(c, null(), 6) }),
            ));
            table.push((
                "SetContinuousStates nx 2",
                vec!["fmi2SetContinuousStates", "nx = 2"],
                Box::new(|| unsafe { f!(api, b"fmi2SetContinuousStates", SetVector)(c, real.as_ptr(), 2) }),
            ));
            table.push((
                "SetContinuousStates NaN",
                vec!["fmi2SetContinuousStates", "not finite"],
                Box::new(|| unsafe { f!(api, b"fmi2SetContinuousStates", SetVector)(c, [f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0].as_ptr(), 6) }),
            ));
            for name in ["fmi2GetDerivatives", "fmi2GetEventIndicators", "fmi2GetContinuousStates", "fmi2GetNominalsOfContinuousStates"] {
                table.push(("a vector NULL", vec![name], Box::new(move || unsafe { f!(api, name.as_bytes(), Vector)(c, null_mut(), 3) })));
                table.push((
                    "a vector of length 7",
                    vec![name, "7"],
                    Box::new(move || unsafe { f!(api, name.as_bytes(), Vector)(c, real.as_ptr() as *mut _, 7) }),
                ));
            }
            table.push((
                "SetTime NaN",
                vec!["fmi2SetTime", "not finite"],
                Box::new(|| unsafe { f!(api, b"fmi2SetTime", unsafe extern "C" fn(Comp, fmi2Real) -> fmi2Status)(c, f64::NAN) }),
            ));
            table.push((
                "NewDiscreteStates NULL",
                vec!["fmi2NewDiscreteStates"],
                Box::new(|| unsafe {
                    api.call0(b"fmi2EnterEventMode", c);
                    let r = f!(api, b"fmi2NewDiscreteStates", Discrete)(c, null_mut());
                    api.call0(b"fmi2EnterContinuousTimeMode", c);
                    r
                }),
            ));
            table.push((
                "CompletedIntegratorStep NULL",
                vec!["fmi2CompletedIntegratorStep"],
                Box::new(|| unsafe { f!(api, b"fmi2CompletedIntegratorStep", Completed)(c, fmi2True, null_mut(), &flag as *const _ as *mut _) }),
            ));
        }
        for (what, words, call) in &table {
            cases += 1;
            let before = serialized(&api, c);
            log.lock().unwrap().clear();
            let status = call();
            let messages: Vec<String> = log.lock().unwrap().iter().filter(|m| m.0 == fmi2Error).map(|m| m.2.clone()).collect();
            if status != fmi2Error {
                failures.push(format!("{kind} {what}: status {status}"));
            } else if !messages.iter().any(|m| words.iter().all(|w| m.contains(w))) {
                failures.push(format!("{kind} {what}: no message with {words:?}: {messages:?}"));
            }
            if serialized(&api, c) != before && !what.starts_with("NewDiscreteStates") {
                failures.push(format!("{kind} {what}: the instance changed"));
            }
        }
        // After all that the instance still works.
        if kind == fmi2CoSimulation {
            assert_eq!(unsafe { f!(api, b"fmi2DoStep", DoStep)(c, 0.0, 1e-9, fmi2True) }, fmi2OK);
        } else {
            let mut d = [0.0; 6];
            assert_eq!(unsafe { f!(api, b"fmi2GetDerivatives", Vector)(c, d.as_mut_ptr(), 6) }, fmi2OK);
        }
        drop(table);
        let mut state = state;
        unsafe { f!(api, b"fmi2FreeFMUstate", GetState)(helper, &mut state) };
        api.free(helper);
        // A freed instance is refused, never followed.
        api.free(c);
        assert_eq!(api.call0(b"fmi2Terminate", c), fmi2Error);
        assert_eq!(api.call0(b"fmi2Reset", null_mut()), fmi2Error);
    }
    assert!(failures.is_empty(), "{} of {cases} cases:\n{}", failures.len(), failures.join("\n"));
}
