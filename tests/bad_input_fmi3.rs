//! Bad input at the FMI 3.0 C ABI, as `bad_input.rs` does for FMI 2.0: a NULL for every pointer argument,
//! lengths that do not match (nValues against nValueReferences too), value references out of range, a
//! type no variable has, NaN and infinities, strings that are not UTF-8, an FMI 2.0 state or instance
//! handed to an fmi3 function, a NULL or freed instance. Each call returns fmi3Error and logs one message
//! that names the function and the argument; the instance is unchanged (its serialized state is the same
//! to the bit) and goes on.

#[macro_use]
mod host;
use host::fmi3::{Api3, DoStep3, GetF64, SetF64};
use host::*;

use powderfmu::fmi2::types::{fmi2CoSimulation, fmi2FMUstate};
use powderfmu::fmi3::types::*;
use powderfmu::units;
use std::ffi::{c_void, CString};
use std::ptr::{null, null_mut};

const PWI: &str = "ParticleWallImpact";

type Typed = unsafe extern "C" fn(Comp, *const fmi3ValueReference, usize, *mut c_void, usize) -> fmi3Status;
type GetState = unsafe extern "C" fn(Comp, *mut fmi3FMUState) -> fmi3Status;
type SetState = unsafe extern "C" fn(Comp, fmi3FMUState) -> fmi3Status;
type StateSize = unsafe extern "C" fn(Comp, fmi3FMUState, *mut usize) -> fmi3Status;
type Serialize = unsafe extern "C" fn(Comp, fmi3FMUState, *mut u8, usize) -> fmi3Status;
type Deserialize = unsafe extern "C" fn(Comp, *const u8, usize, *mut fmi3FMUState) -> fmi3Status;
type Vector = unsafe extern "C" fn(Comp, *mut f64, usize) -> fmi3Status;
type Update = unsafe extern "C" fn(Comp, *mut bool, *mut bool, *mut bool, *mut bool, *mut bool, *mut f64) -> fmi3Status;
type Logging = unsafe extern "C" fn(Comp, bool, usize, *const fmi3String) -> fmi3Status;

type Case<'a> = (&'static str, Vec<&'static str>, Box<dyn Fn() -> fmi3Status + 'a>);

/// An initialized instance: CS in Step Mode (eventModeUsed, earlyReturnAllowed), ME in Continuous-Time Mode.
fn ready(api: &Api3, me: bool, log: &Log) -> Comp {
    let c = api.instantiate(PWI, me, true, true, log);
    assert_eq!(api.enter_initialization(c), fmi3OK);
    assert_eq!(api.call0(b"fmi3ExitInitializationMode", c), fmi3OK);
    let mut b = [false; 5];
    let mut t = 0.0;
    let [b0, b1, b2, b3, b4] = &mut b;
    assert_eq!(unsafe { api.sym::<Update>(b"fmi3UpdateDiscreteStates")(c, b0, b1, b2, b3, b4, &mut t) }, fmi3OK);
    let next: &[u8] = if me { b"fmi3EnterContinuousTimeMode" } else { b"fmi3EnterStepMode" };
    assert_eq!(api.call0(next, c), fmi3OK);
    c
}

fn serialized(api: &Api3, c: Comp) -> Vec<u8> {
    unsafe {
        let mut s = null_mut();
        assert_eq!(api.sym::<GetState>(b"fmi3GetFMUState")(c, &mut s), fmi3OK);
        let mut n = 0;
        api.sym::<StateSize>(b"fmi3SerializedFMUStateSize")(c, s, &mut n);
        let mut b = vec![0; n];
        api.sym::<Serialize>(b"fmi3SerializeFMUState")(c, s, b.as_mut_ptr(), n);
        api.sym::<GetState>(b"fmi3FreeFMUState")(c, &mut s);
        b
    }
}

#[test]
fn every_bad_argument_is_refused_by_name_and_changes_nothing() {
    let lib = library();
    let api = &Api3 { lib: &lib };
    let fmi2 = Api { lib: &lib };
    let unit = units::by_identifier(PWI).unwrap();
    let vr = |n: &str| unit.vr(n).expect("a variable of the unit") as fmi3ValueReference;
    let beyond = unit.variables.len() as fmi3ValueReference;
    let not_utf8 = [0xffu8 as std::os::raw::c_char, 0xfe_u8 as std::os::raw::c_char, 0];
    let mut failures = Vec::new();
    let mut cases = 0;
    for me in [false, true] {
        let kind = if me { "ME" } else { "CS" };
        let log = Log::default();
        let c = ready(api, me, &log);
        let helper = ready(api, me, &log);
        let mut state: fmi3FMUState = null_mut();
        unsafe { api.sym::<GetState>(b"fmi3GetFMUState")(helper, &mut state) };
        let state = state;
        // An FMI 2.0 instance and its saved state: foreign to the FMI 3.0 functions.
        let log2 = Log::default();
        let c2 = fmi2.instantiate(PWI, fmi2CoSimulation, &log2, None);
        let mut state2: fmi2FMUstate = null_mut();
        unsafe { f!(fmi2, b"fmi2GetFMUstate", unsafe extern "C" fn(Comp, *mut fmi2FMUstate) -> i32)(c2, &mut state2) };
        let state2 = state2;
        let mut real = [0.0f64; 8];
        let real_p = real.as_mut_ptr();
        let bytes = serialized(api, helper);
        let fmi2_bytes = {
            let mut s = state2;
            let mut n = 0usize;
            unsafe {
                f!(fmi2, b"fmi2SerializedFMUstateSize", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut usize) -> i32)(c2, s, &mut n);
                let mut b = vec![0u8; n];
                f!(fmi2, b"fmi2SerializeFMUstate", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut u8, usize) -> i32)(c2, s, b.as_mut_ptr(), n);
                s = null_mut();
                let _ = s;
                b
            }
        };
        let cat = CString::new("logNoSuchCategory").unwrap();
        let cats = [cat.as_ptr()];
        let bad_string = [not_utf8.as_ptr()];
        let mut table: Vec<Case> = vec![
            (
                "GetFloat64 valueReferences NULL",
                vec!["fmi3GetFloat64", "valueReferences"],
                Box::new(|| unsafe { api.sym::<GetF64>(b"fmi3GetFloat64")(c, null(), 1, real_p, 1) }),
            ),
            (
                "GetFloat64 values NULL",
                vec!["fmi3GetFloat64", "values"],
                Box::new(|| unsafe { api.sym::<GetF64>(b"fmi3GetFloat64")(c, &vr("force"), 1, null_mut(), 1) }),
            ),
            (
                "GetFloat64 beyond",
                vec!["fmi3GetFloat64", "value reference"],
                Box::new(|| unsafe { api.sym::<GetF64>(b"fmi3GetFloat64")(c, &beyond, 1, real_p, 1) }),
            ),
            (
                "GetFloat64 absurd length",
                vec!["fmi3GetFloat64", "length"],
                Box::new(|| unsafe { api.sym::<GetF64>(b"fmi3GetFloat64")(c, &vr("force"), usize::MAX, real_p, usize::MAX) }),
            ),
            (
                "GetFloat64 nValues != nValueReferences",
                vec!["fmi3GetFloat64", "nValues"],
                Box::new(|| unsafe { api.sym::<GetF64>(b"fmi3GetFloat64")(c, &vr("force"), 1, real_p, 2) }),
            ),
            (
                "GetInt32 of a Float64",
                vec!["fmi3GetInt32", "force"],
                Box::new(|| unsafe { api.sym::<Typed>(b"fmi3GetInt32")(c, &vr("force"), 1, real_p.cast(), 1) }),
            ),
            (
                "GetUInt16 of a Float64",
                vec!["fmi3GetUInt16", "force", "Float64"],
                Box::new(|| unsafe { api.sym::<Typed>(b"fmi3GetUInt16")(c, &vr("force"), 1, real_p.cast(), 1) }),
            ),
            (
                "SetFloat64 beyond",
                vec!["fmi3SetFloat64", "does not exist"],
                Box::new(|| unsafe { api.sym::<SetF64>(b"fmi3SetFloat64")(c, &beyond, 1, &0.0, 1) }),
            ),
            (
                "SetFloat64 NaN input",
                vec!["fmi3SetFloat64", "wall_displacement", "not a finite"],
                Box::new(|| unsafe { api.sym::<SetF64>(b"fmi3SetFloat64")(c, &vr("wall_displacement"), 1, &f64::NAN, 1) }),
            ),
            (
                "SetFloat64 -inf input",
                vec!["fmi3SetFloat64", "wall_velocity", "not a finite"],
                Box::new(|| unsafe { api.sym::<SetF64>(b"fmi3SetFloat64")(c, &vr("wall_velocity"), 1, &f64::NEG_INFINITY, 1) }),
            ),
            (
                "SetFloat64 values NULL",
                vec!["fmi3SetFloat64", "values"],
                Box::new(|| unsafe { api.sym::<SetF64>(b"fmi3SetFloat64")(c, &vr("wall_velocity"), 1, null(), 1) }),
            ),
            (
                "SetFloat64 an output",
                vec!["fmi3SetFloat64", "force", "cannot be set"],
                Box::new(|| unsafe { api.sym::<SetF64>(b"fmi3SetFloat64")(c, &vr("force"), 1, &1.0, 1) }),
            ),
            (
                "SetFloat64 a fixed parameter",
                vec!["fmi3SetFloat64", "particle_radius", "fixed"],
                Box::new(|| unsafe { api.sym::<SetF64>(b"fmi3SetFloat64")(c, &vr("particle_radius"), 1, &1e-6, 1) }),
            ),
            (
                "SetFloat64 time",
                vec!["fmi3SetFloat64", "time", "cannot be set"],
                Box::new(|| unsafe { api.sym::<SetF64>(b"fmi3SetFloat64")(c, &vr("time"), 1, &1.0, 1) }),
            ),
            (
                "GetString values NULL",
                vec!["fmi3GetString", "values"],
                Box::new(|| unsafe { api.sym::<Typed>(b"fmi3GetString")(c, &vr("contact_model"), 1, null_mut(), 1) }),
            ),
            (
                "SetDebugLogging unknown category",
                vec!["fmi3SetDebugLogging", "logNoSuchCategory"],
                Box::new(|| unsafe { api.sym::<Logging>(b"fmi3SetDebugLogging")(c, true, 1, cats.as_ptr()) }),
            ),
            (
                "SetDebugLogging categories NULL",
                vec!["fmi3SetDebugLogging", "categories"],
                Box::new(|| unsafe { api.sym::<Logging>(b"fmi3SetDebugLogging")(c, true, 2, null()) }),
            ),
            ("GetFMUState NULL", vec!["fmi3GetFMUState", "FMUState"], Box::new(|| unsafe { api.sym::<GetState>(b"fmi3GetFMUState")(c, null_mut()) })),
            ("SetFMUState NULL", vec!["fmi3SetFMUState", "FMUState"], Box::new(|| unsafe { api.sym::<SetState>(b"fmi3SetFMUState")(c, null_mut()) })),
            (
                "SetFMUState an FMI 2.0 state",
                vec!["fmi3SetFMUState", "not a live state"],
                Box::new(|| unsafe { api.sym::<SetState>(b"fmi3SetFMUState")(c, state2) }),
            ),
            (
                "SerializedFMUStateSize size NULL",
                vec!["fmi3SerializedFMUStateSize", "size"],
                Box::new(|| unsafe { api.sym::<StateSize>(b"fmi3SerializedFMUStateSize")(c, state, null_mut()) }),
            ),
            (
                "SerializeFMUState buffer too small",
                vec!["fmi3SerializeFMUState", "smaller"],
                Box::new(|| unsafe { api.sym::<Serialize>(b"fmi3SerializeFMUState")(c, state, real_p.cast(), 8) }),
            ),
            (
                "DeserializeFMUState truncated",
                vec!["fmi3DeserializeFMUState"],
                Box::new(|| {
                    let mut out = null_mut();
                    unsafe { api.sym::<Deserialize>(b"fmi3DeserializeFMUState")(c, bytes.as_ptr(), bytes.len() / 2, &mut out) }
                }),
            ),
            (
                "DeserializeFMUState an FMI 2.0 state's bytes",
                vec!["fmi3DeserializeFMUState", "not by this unit"],
                Box::new(|| {
                    let mut out = null_mut();
                    unsafe { api.sym::<Deserialize>(b"fmi3DeserializeFMUState")(c, fmi2_bytes.as_ptr(), fmi2_bytes.len(), &mut out) }
                }),
            ),
            (
                "DeserializeFMUState FMUState NULL",
                vec!["fmi3DeserializeFMUState", "FMUState"],
                Box::new(|| unsafe { api.sym::<Deserialize>(b"fmi3DeserializeFMUState")(c, bytes.as_ptr(), bytes.len(), null_mut()) }),
            ),
            (
                "UpdateDiscreteStates outside Event Mode",
                vec!["fmi3UpdateDiscreteStates", "must not be called in"],
                Box::new(|| {
                    let mut b = [false; 5];
                    let mut t = 0.0;
                    let [b0, b1, b2, b3, b4] = &mut b;
                    unsafe { api.sym::<Update>(b"fmi3UpdateDiscreteStates")(c, b0, b1, b2, b3, b4, &mut t) }
                }),
            ),
        ];
        if !me {
            // Not in Continuous-Time Mode, where the calling sequence refuses them first.
            table.push((
                "SetInt64 beyond",
                vec!["fmi3SetInt64", "does not exist"],
                Box::new(move || unsafe { api.sym::<Typed>(b"fmi3SetInt64")(c, &beyond, 1, real_p.cast(), 1) }),
            ));
            let bad = bad_string.as_ptr() as *mut c_void;
            let model = vr("contact_model");
            table.push((
                "SetString not UTF-8",
                vec!["fmi3SetString", "UTF-8"],
                Box::new(move || unsafe { api.sym::<Typed>(b"fmi3SetString")(c, &model, 1, bad, 1) }),
            ));
            let step: DoStep3 = api.sym(b"fmi3DoStep");
            let flag = std::cell::Cell::new(false);
            let fp = flag.as_ptr();
            let mut t_last = 0.0;
            let tp = &mut t_last as *mut f64;
            for (what, arg) in [
                ("DoStep eventHandlingNeeded NULL", 0),
                ("DoStep terminateSimulation NULL", 1),
                ("DoStep earlyReturn NULL", 2),
                ("DoStep lastSuccessfulTime NULL", 3),
            ] {
                let words = vec!["fmi3DoStep", ["eventHandlingNeeded", "terminateSimulation", "earlyReturn", "lastSuccessfulTime"][arg]];
                table.push((
                    what,
                    words,
                    Box::new(move || unsafe {
                        let p = |i: usize| if i == arg { null_mut() } else { fp };
                        step(c, 0.0, 1e-9, true, p(0), p(1), p(2), if arg == 3 { null_mut() } else { tp })
                    }),
                ));
            }
            table.push(("DoStep zero step", vec!["fmi3DoStep", "positive"], Box::new(move || api.do_step(c, 0.0, 0.0).0)));
            table.push(("DoStep NaN time", vec!["fmi3DoStep", "finite"], Box::new(move || api.do_step(c, f64::NAN, 1e-9).0)));
            table.push(("DoStep not at the unit's time", vec!["fmi3DoStep", "not the unit's time"], Box::new(move || api.do_step(c, 1.0, 1e-9).0)));
            table.push(("EnterStepMode in Step Mode", vec!["fmi3EnterStepMode", "Step Mode"], Box::new(move || api.call0(b"fmi3EnterStepMode", c))));
        } else {
            for name in
                ["fmi3GetContinuousStateDerivatives", "fmi3GetEventIndicators", "fmi3GetContinuousStates", "fmi3GetNominalsOfContinuousStates"]
            {
                table.push(("a vector NULL", vec![name], Box::new(move || unsafe { api.sym::<Vector>(name.as_bytes())(c, null_mut(), 3) })));
                table.push(("a vector of length 7", vec![name, "7"], Box::new(move || unsafe { api.sym::<Vector>(name.as_bytes())(c, real_p, 7) })));
            }
            table.push((
                "SetContinuousStates NaN",
                vec!["fmi3SetContinuousStates", "not finite"],
                Box::new(move || unsafe {
                    api.sym::<unsafe extern "C" fn(Comp, *const f64, usize) -> fmi3Status>(b"fmi3SetContinuousStates")(
                        c,
                        [f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0].as_ptr(),
                        6,
                    )
                }),
            ));
            table.push((
                "SetTime +inf",
                vec!["fmi3SetTime", "not finite"],
                Box::new(move || unsafe { api.sym::<unsafe extern "C" fn(Comp, f64) -> fmi3Status>(b"fmi3SetTime")(c, f64::INFINITY) }),
            ));
            table.push((
                "GetNumberOfEventIndicators NULL",
                vec!["fmi3GetNumberOfEventIndicators", "nEventIndicators"],
                Box::new(move || unsafe {
                    api.sym::<unsafe extern "C" fn(Comp, *mut usize) -> fmi3Status>(b"fmi3GetNumberOfEventIndicators")(c, null_mut())
                }),
            ));
            table.push((
                "CompletedIntegratorStep NULL",
                vec!["fmi3CompletedIntegratorStep", "enterEventMode"],
                Box::new(move || unsafe {
                    let mut stop = false;
                    api.sym::<unsafe extern "C" fn(Comp, bool, *mut bool, *mut bool) -> fmi3Status>(b"fmi3CompletedIntegratorStep")(
                        c,
                        true,
                        null_mut(),
                        &mut stop,
                    )
                }),
            ));
        }
        for (what, words, call) in &table {
            cases += 1;
            let before = serialized(api, c);
            log.lock().unwrap().clear();
            let status = call();
            let messages: Vec<String> = log.lock().unwrap().iter().filter(|m| m.0 == fmi3Error).map(|m| m.2.clone()).collect();
            if status != fmi3Error {
                failures.push(format!("{kind} {what}: status {status}"));
            } else if !messages.iter().any(|m| words.iter().all(|w| m.contains(w))) {
                failures.push(format!("{kind} {what}: no message with {words:?}: {messages:?}"));
            }
            if serialized(api, c) != before {
                failures.push(format!("{kind} {what}: the instance changed"));
            }
        }
        // After all that the instance still works.
        if me {
            let mut d = [0.0; 6];
            assert_eq!(unsafe { api.sym::<Vector>(b"fmi3GetContinuousStateDerivatives")(c, d.as_mut_ptr(), 6) }, fmi3OK);
        } else {
            assert_eq!(api.do_step(c, 0.0, 1e-9).0, fmi3OK);
        }
        drop(table);
        // An FMI 2.0 instance is foreign to the FMI 3.0 functions, and the other way round.
        assert_eq!(api.call0(b"fmi3Terminate", c2), fmi3Error);
        assert_eq!(fmi2.call0(b"fmi2Terminate", c), fmi3Error);
        let mut state2 = state2;
        unsafe { f!(fmi2, b"fmi2FreeFMUstate", unsafe extern "C" fn(Comp, *mut fmi2FMUstate) -> i32)(c2, &mut state2) };
        fmi2.free(c2);
        let mut state = state;
        unsafe { api.sym::<GetState>(b"fmi3FreeFMUState")(helper, &mut state) };
        api.free(helper);
        // A freed instance is refused, never followed; so is NULL.
        api.free(c);
        assert_eq!(api.call0(b"fmi3Terminate", c), fmi3Error);
        assert_eq!(api.call0(b"fmi3Reset", null_mut()), fmi3Error);
    }
    assert!(failures.is_empty(), "{} of {cases} cases:\n{}", failures.len(), failures.join("\n"));
    println!("{cases} bad calls refused");
}

#[test]
fn a_wrong_token_or_resource_path_is_refused_at_instantiation() {
    let lib = library();
    let api = Api3 { lib: &lib };
    let log = Log::default();
    let env = &log as *const Log as *mut c_void;
    let name = CString::new("x").unwrap();
    let guid = CString::new(units::by_identifier(PWI).unwrap().guid()).unwrap();
    let token = CString::new(units::by_identifier(PWI).unwrap().instantiation_token()).unwrap();
    let nowhere = CString::new("/nonexistent/resources/").unwrap();
    type Me = host::fmi3::InstantiateMe;
    let make = |t: &CString, r: *const std::os::raw::c_char| unsafe {
        api.sym::<Me>(b"fmi3InstantiateModelExchange")(name.as_ptr(), t.as_ptr(), r, false, false, env, Some(host::fmi3::logger3))
    };
    assert!(make(&guid, null()).is_null());
    assert!(log.lock().unwrap().iter().any(|m| m.2.contains("is the GUID of the FMI 2.0 ParticleWallImpact")), "{:?}", log.lock().unwrap());
    assert!(make(&token, nowhere.as_ptr()).is_null());
    assert!(log.lock().unwrap().iter().any(|m| m.2.contains("resourcePath /nonexistent/resources/ is not a directory")));
    // BallIndentation offers no Model Exchange.
    let bi = CString::new(units::by_identifier("BallIndentation").unwrap().instantiation_token()).unwrap();
    assert!(make(&bi, null()).is_null());
    assert!(log.lock().unwrap().iter().any(|m| m.2.contains("Co-Simulation only")));
    // And with the right token the same call makes an instance.
    let c = make(&token, null());
    assert!(!c.is_null());
    api.free(c);
}

/// What the callback below needs: the library's fmi3FreeInstance and the instance.
struct Freer {
    free: unsafe extern "C" fn(Comp),
    instance: Comp,
    calls: usize,
}

/// An intermediate-update callback that frees the instance it is called for: a master's bug the step
/// must survive.
unsafe extern "C" fn free_in_callback(
    env: fmi3InstanceEnvironment,
    _t: f64,
    _set: bool,
    _get: bool,
    _finished: bool,
    _early: bool,
    _req: *mut bool,
    _time: *mut f64,
) {
    let freer = &mut *(env as *mut Freer);
    freer.calls += 1;
    (freer.free)(freer.instance);
}

#[test]
fn an_instance_freed_inside_its_intermediate_update_ends_the_step_with_an_error() {
    let lib = library();
    let api = Api3 { lib: &lib };
    let unit = units::by_identifier(PWI).unwrap();
    let name = CString::new("freed").unwrap();
    let token = CString::new(unit.instantiation_token()).unwrap();
    let free = api.sym::<unsafe extern "C" fn(Comp)>(b"fmi3FreeInstance");
    let mut freer = Freer { free, instance: null_mut(), calls: 0 };
    let env = &mut freer as *mut Freer as *mut c_void;
    let c = unsafe {
        api.sym::<host::fmi3::InstantiateCs>(b"fmi3InstantiateCoSimulation")(
            name.as_ptr(),
            token.as_ptr(),
            null(),
            false,
            false,
            false,
            false,
            null(),
            0,
            env,
            None,
            Some(free_in_callback),
        )
    };
    assert!(!c.is_null());
    freer.instance = c;
    assert_eq!(api.enter_initialization(c), fmi3OK);
    assert_eq!(api.call0(b"fmi3ExitInitializationMode", c), fmi3OK);
    // The default impact has its contact inside the first microsecond.
    let (status, _, _, _) = api.do_step(c, 0.0, 1e-6);
    assert_eq!(status, fmi3Error, "the step cannot go on with a freed instance");
    assert_eq!(freer.calls, 1, "called once, at the first event; the freed instance is not followed");
    assert_eq!(api.call0(b"fmi3Terminate", c), fmi3Error, "and it stays refused");
}

/// What the re-entrant logger below needs.
struct Reentrant {
    get: unsafe extern "C" fn(Comp, *const u32, usize, *mut f64, usize) -> fmi3Status,
    free: unsafe extern "C" fn(Comp),
    instance: Comp,
    force: u32,
    /// Free the instance from inside the logger (else: read an output of it).
    free_it: bool,
    statuses: Vec<fmi3Status>,
}

/// A host logger that calls back into the library for the instance it logs about.
unsafe extern "C" fn reentrant_logger(env: fmi3InstanceEnvironment, _status: fmi3Status, _category: fmi3String, _message: fmi3String) {
    let r = &mut *(env as *mut Reentrant);
    if r.instance.is_null() {
        return;
    }
    if r.free_it {
        (r.free)(r.instance);
        r.instance = null_mut();
    } else {
        let mut v = 0.0;
        let s = (r.get)(r.instance, &r.force, 1, &mut v, 1);
        r.statuses.push(s);
    }
}

#[test]
fn a_logger_that_calls_back_in_or_frees_the_instance_finds_it_consistent() {
    let lib = library();
    let api = Api3 { lib: &lib };
    let unit = units::by_identifier(PWI).unwrap();
    let token = CString::new(unit.instantiation_token()).unwrap();
    let name = CString::new("reentrant").unwrap();
    for free_it in [false, true] {
        let mut r = Reentrant {
            get: api.sym::<unsafe extern "C" fn(Comp, *const u32, usize, *mut f64, usize) -> fmi3Status>(b"fmi3GetFloat64"),
            free: api.sym::<unsafe extern "C" fn(Comp)>(b"fmi3FreeInstance"),
            instance: null_mut(),
            force: unit.vr("force").unwrap() as u32,
            free_it,
            statuses: Vec::new(),
        };
        let env = &mut r as *mut Reentrant as *mut c_void;
        let c = unsafe {
            api.sym::<host::fmi3::InstantiateMe>(b"fmi3InstantiateModelExchange")(
                name.as_ptr(),
                token.as_ptr(),
                null(),
                false,
                false,
                env,
                Some(reentrant_logger),
            )
        };
        assert!(!c.is_null());
        assert_eq!(api.enter_initialization(c), fmi3OK);
        assert_eq!(api.call0(b"fmi3ExitInitializationMode", c), fmi3OK);
        r.instance = c;
        // A refused call logs an error (logging off: errors only, so the getter inside the logger logs
        // nothing and does not recurse): the logger runs after the call, with the instance consistent.
        assert_eq!(api.call0(b"fmi3EnterStepMode", c), fmi3Error);
        if free_it {
            assert!(r.instance.is_null(), "the logger freed the instance");
            assert_eq!(api.call0(b"fmi3Terminate", c), fmi3Error, "a freed instance is refused");
        } else {
            assert!(!r.statuses.is_empty() && r.statuses.iter().all(|&s| s == fmi3OK), "{:?}", r.statuses);
            r.instance = null_mut();
            api.free(c);
        }
    }
}
