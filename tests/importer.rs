//! An importer in Rust: loads the cdylib through `fmi_host` and drives the C ABI through whole Model Exchange
//! and Co-Simulation runs, as fmpy would, so that ABI faults show up in `cargo test` with a backtrace.
//! The logger is a plain C function (see `logger`): messages are collected per instance.

#![allow(non_snake_case)]

use powderfmu::fmi2::types::*;
use powderfmu::law::params::Effective;
use powderfmu::law::AnyLaw;
use powderfmu::scene::Scene;
use powderfmu::theory::energy_balance;
use powderfmu::units;
use std::ffi::CString;
use std::os::raw::c_char;

#[macro_use]
mod host;
use host::*;

/// The default scene at 3 m/s: its undamped rebound speed by the energy balance.
fn expected_rebound(v: f64) -> f64 {
    let s = Scene::from_json(units::DEFAULT_SCENE).unwrap();
    let law = AnyLaw::from_scene(&s).unwrap();
    let m = Effective::from_scene(&s).unwrap().mass;
    energy_balance::impact(&law, m, v, s.particle_radius).unwrap().rebound_velocity
}

const PWI: &str = "ParticleWallImpact";
/// ParticleWallImpact's continuous states and event indicators (checked against the unit below).
const NX: usize = 6;
const NZ: usize = 4;

#[test]
fn co_simulation_run_rebounds_as_the_energy_balance_says() {
    let lib = library();
    let api = Api { lib: &lib };
    let log = Log::default();
    let c = api.instantiate(PWI, fmi2CoSimulation, &log, None);
    assert!(!c.is_null(), "{:?}", log.lock().unwrap());
    assert_eq!(api.set(c, PWI, "initial_velocity", 3.0), fmi2OK);
    unsafe { assert_eq!(f!(api, b"fmi2SetupExperiment", Setup)(c, fmi2False, 0.0, 0.0, fmi2True, 2e-7), fmi2OK) };
    assert_eq!(api.call0(b"fmi2EnterInitializationMode", c), fmi2OK);
    assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2OK);
    let step = f!(api, b"fmi2DoStep", DoStep);
    let h = 1e-9;
    for i in 0..200 {
        assert_eq!(unsafe { step(c, i as f64 * h, h, fmi2True) }, fmi2OK, "{:?}", log.lock().unwrap());
    }
    let v = api.get(c, PWI, "sphere_velocity");
    let want = expected_rebound(3.0);
    assert!((v - want).abs() < 1e-7 * want, "rebound {v} vs energy balance {want}");
    assert!(api.get(c, PWI, "overlap") < 0.0);
    assert_eq!(api.call0(b"fmi2Terminate", c), fmi2OK);
    api.free(c);
}

#[test]
fn model_exchange_run_with_a_simple_importer_integrator() {
    let unit = units::by_identifier(PWI).unwrap();
    assert_eq!((unit.n_states, unit.n_event_indicators), (NX, NZ));
    let lib = library();
    let api = Api { lib: &lib };
    let log = Log::default();
    let c = api.instantiate(PWI, fmi2ModelExchange, &log, None);
    assert!(!c.is_null());
    api.set(c, PWI, "initial_velocity", 3.0);
    unsafe { f!(api, b"fmi2SetupExperiment", Setup)(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) };
    api.call0(b"fmi2EnterInitializationMode", c);
    assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2OK);
    let new_discrete = f!(api, b"fmi2NewDiscreteStates", unsafe extern "C" fn(Comp, *mut fmi2EventInfo) -> fmi2Status);
    let mut info = fmi2EventInfo::default();
    assert_eq!(unsafe { new_discrete(c, &mut info) }, fmi2OK);
    assert_eq!(api.call0(b"fmi2EnterContinuousTimeMode", c), fmi2OK);
    let get_x = f!(api, b"fmi2GetContinuousStates", Vector);
    let set_x = f!(api, b"fmi2SetContinuousStates", SetVector);
    let get_dx = f!(api, b"fmi2GetDerivatives", Vector);
    let get_z = f!(api, b"fmi2GetEventIndicators", Vector);
    let set_time = f!(api, b"fmi2SetTime", unsafe extern "C" fn(Comp, fmi2Real) -> fmi2Status);
    let completed =
        f!(api, b"fmi2CompletedIntegratorStep", unsafe extern "C" fn(Comp, fmi2Boolean, *mut fmi2Boolean, *mut fmi2Boolean) -> fmi2Status);
    // The unit's six states (the normal three, the motion along the wall, the spin, the spring) and four indicators.
    let mut x = [0.0; NX];
    let mut z = [0.0; NZ];
    let mut z_new = [0.0; NZ];
    unsafe { get_x(c, x.as_mut_ptr(), NX) };
    unsafe { get_z(c, z.as_mut_ptr(), NZ) };
    // Classical RK4 with events at the step where an indicator changes sign.
    let dt = 2e-12;
    let mut t = 0.0;
    let mut events = 0;
    let deriv = |t: f64, x: &[f64; NX]| -> [f64; NX] {
        let mut dx = [0.0; NX];
        unsafe {
            set_time(c, t);
            set_x(c, x.as_ptr(), NX);
            get_dx(c, dx.as_mut_ptr(), NX);
        }
        dx
    };
    while t < 1.5e-7 {
        let k1 = deriv(t, &x);
        let add = |a: &[f64; NX], k: &[f64; NX], s: f64| -> [f64; NX] { std::array::from_fn(|i| a[i] + s * k[i]) };
        let k2 = deriv(t + dt / 2.0, &add(&x, &k1, dt / 2.0));
        let k3 = deriv(t + dt / 2.0, &add(&x, &k2, dt / 2.0));
        let k4 = deriv(t + dt, &add(&x, &k3, dt));
        for i in 0..NX {
            x[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        t += dt;
        unsafe {
            set_time(c, t);
            assert_eq!(set_x(c, x.as_ptr(), NX), fmi2OK);
            get_z(c, z_new.as_mut_ptr(), NZ);
        }
        if z.iter().zip(&z_new).any(|(a, b)| (*a > 0.0) != (*b > 0.0)) {
            events += 1;
            assert_eq!(api.call0(b"fmi2EnterEventMode", c), fmi2OK);
            assert_eq!(unsafe { new_discrete(c, &mut info) }, fmi2OK);
            assert_eq!(info.newDiscreteStatesNeeded, fmi2False);
            assert_eq!(api.call0(b"fmi2EnterContinuousTimeMode", c), fmi2OK);
            unsafe { get_z(c, z_new.as_mut_ptr(), NZ) };
        } else {
            let (mut enter, mut term) = (fmi2True, fmi2True);
            assert_eq!(unsafe { completed(c, fmi2True, &mut enter, &mut term) }, fmi2OK);
            assert_eq!((enter, term), (fmi2False, fmi2False));
        }
        z = z_new;
    }
    let v = api.get(c, PWI, "sphere_velocity");
    let want = expected_rebound(3.0);
    // Events are located to one step of 2 ps here (CVode locates them exactly): 1e-3 is this importer's accuracy.
    assert!((v - want).abs() < 1e-3 * want, "rebound {v} vs energy balance {want}");
    assert!(events >= 4, "contact, yield, turning point, pull-off, separation: {events} events");
    api.free(c);
}

#[test]
fn bad_calls_return_fmi2error_with_a_message_and_the_instance_stays_usable_or_resets() {
    let lib = library();
    let api = Api { lib: &lib };
    let log = Log::default();
    let c = api.instantiate(PWI, fmi2CoSimulation, &log, None);
    let step = f!(api, b"fmi2DoStep", DoStep);
    let last = |log: &Log| log.lock().unwrap().last().cloned().unwrap_or((fmi2OK, String::new(), String::new()));

    assert_eq!(unsafe { step(c, 0.0, 1e-9, fmi2True) }, fmi2Error);
    let (s, cat, m) = last(&log);
    assert_eq!((s, cat.as_str()), (fmi2Error, "logStatusError"));
    assert!(m.contains("fmi2DoStep") && m.contains("Instantiated"), "{m}");

    assert_eq!(api.set(c, PWI, "particle_radius", f64::NAN), fmi2Error);
    assert!(last(&log).2.contains("particle_radius"), "{:?}", last(&log));
    assert_eq!(api.set(c, PWI, "particle_radius", -1e-6), fmi2OK, "range is checked at initialization");
    api.call0(b"fmi2EnterInitializationMode", c);
    assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2Error);
    assert!(last(&log).2.contains("particle_radius"), "{:?}", last(&log));
    // A failed initialization is a failed computation: the instance is in the Error state, where only
    // gets, states, fmi2Reset and fmi2FreeInstance are allowed. fmi2Reset brings back the start values.
    assert!(last(&log).2.contains("Error state"), "{:?}", last(&log));
    assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2Error);
    assert!(last(&log).2.contains("must not be called in Error"), "{:?}", last(&log));
    assert_eq!(api.call0(b"fmi2Reset", c), fmi2OK);
    assert_eq!(api.set(c, PWI, "particle_radius", 2.45e-6), fmi2OK);
    api.call0(b"fmi2EnterInitializationMode", c);
    assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2OK);
    assert_eq!(unsafe { step(c, 0.0, -1e-9, fmi2True) }, fmi2Error);
    assert!(last(&log).2.contains("communicationStepSize"));
    assert_eq!(api.set(c, PWI, "particle_radius", 1e-6), fmi2Error);
    assert!(last(&log).2.contains("fixed"));
    assert_eq!(api.set(c, PWI, "force", 1.0), fmi2Error);
    let vr: fmi2ValueReference = 100_000;
    let mut v = 0.0;
    assert_eq!(unsafe { f!(api, b"fmi2GetReal", GetReal)(c, &vr, 1, &mut v) }, fmi2Error);
    assert!(last(&log).2.contains("100000"));
    assert_eq!(unsafe { f!(api, b"fmi2GetReal", GetReal)(c, std::ptr::null(), 1, &mut v) }, fmi2Error);
    assert!(last(&log).2.contains("NULL"));
    assert_eq!(unsafe { step(c, 0.0, 1e-9, fmi2True) }, fmi2OK);
    // A percent sign in a message reaches the host doubled (printf-escaped) and arrives as one.
    api.free(c);
    // A freed or foreign pointer is refused, not followed.
    assert_eq!(unsafe { step(c, 1e-9, 1e-9, fmi2True) }, fmi2Error);
    let mut junk = [0u64; 8];
    assert_eq!(unsafe { step(junk.as_mut_ptr() as Comp, 0.0, 1e-9, fmi2True) }, fmi2Error);
}

#[test]
fn wrong_guid_and_missing_resources_refuse_to_instantiate() {
    let lib = library();
    let api = Api { lib: &lib };
    let log = Log::default();
    let inst = f!(api, b"fmi2Instantiate", Instantiate);
    let name = CString::new("x").unwrap();
    let guid = CString::new("{00000000-0000-0000-0000-000000000000}").unwrap();
    let res = CString::new(resource_uri()).unwrap();
    let cb = callbacks(&log);
    let c = unsafe { inst(name.as_ptr(), fmi2CoSimulation, guid.as_ptr(), res.as_ptr(), &cb, 0, 0) };
    assert!(c.is_null());
    assert!(log.lock().unwrap().last().unwrap().2.contains("fmuGUID"));
    let c = api.instantiate(PWI, fmi2CoSimulation, &log, Some("file:///nonexistent/powderfmu/resources"));
    assert!(c.is_null());
    assert!(log.lock().unwrap().last().unwrap().2.contains("not a directory"));
    let c = api.instantiate(PWI, fmi2CoSimulation, &log, Some("http://example.org/resources"));
    assert!(c.is_null());
    assert!(log.lock().unwrap().last().unwrap().2.contains("not a file URI"));
}

#[test]
fn saved_state_restores_and_repeats_the_step_bit_for_bit() {
    let lib = library();
    let api = Api { lib: &lib };
    let log = Log::default();
    let c = api.instantiate(PWI, fmi2CoSimulation, &log, None);
    api.set(c, PWI, "initial_velocity", 3.0);
    api.call0(b"fmi2EnterInitializationMode", c);
    api.call0(b"fmi2ExitInitializationMode", c);
    let step = f!(api, b"fmi2DoStep", DoStep);
    let h = 1e-9;
    for i in 0..20 {
        unsafe { step(c, i as f64 * h, h, fmi2False) };
    }
    let get_state = f!(api, b"fmi2GetFMUstate", unsafe extern "C" fn(Comp, *mut fmi2FMUstate) -> fmi2Status);
    let set_state = f!(api, b"fmi2SetFMUstate", unsafe extern "C" fn(Comp, fmi2FMUstate) -> fmi2Status);
    let free_state = f!(api, b"fmi2FreeFMUstate", unsafe extern "C" fn(Comp, *mut fmi2FMUstate) -> fmi2Status);
    let size = f!(api, b"fmi2SerializedFMUstateSize", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut usize) -> fmi2Status);
    let ser = f!(api, b"fmi2SerializeFMUstate", unsafe extern "C" fn(Comp, fmi2FMUstate, *mut fmi2Byte, usize) -> fmi2Status);
    let de = f!(api, b"fmi2DeSerializeFMUstate", unsafe extern "C" fn(Comp, *const fmi2Byte, usize, *mut fmi2FMUstate) -> fmi2Status);
    let mut s: fmi2FMUstate = std::ptr::null_mut();
    assert_eq!(unsafe { get_state(c, &mut s) }, fmi2OK);
    let run = |from: usize| -> Vec<u64> {
        (from..from + 60)
            .map(|i| {
                unsafe { step(c, i as f64 * h, h, fmi2False) };
                api.get(c, PWI, "sphere_velocity").to_bits() ^ api.get(c, PWI, "force").to_bits()
            })
            .collect()
    };
    let first = run(20);
    assert_eq!(unsafe { set_state(c, s) }, fmi2OK);
    assert_eq!(run(20), first, "rollback repeats the steps bit for bit");
    // Serialize, corrupt one byte: refused; intact: restores.
    let mut n = 0usize;
    unsafe { size(c, s, &mut n) };
    let mut bytes = vec![0 as c_char; n];
    assert_eq!(unsafe { ser(c, s, bytes.as_mut_ptr(), n) }, fmi2OK);
    let mut s2: fmi2FMUstate = std::ptr::null_mut();
    bytes[n / 2] ^= 0x10;
    assert_eq!(unsafe { de(c, bytes.as_ptr(), n, &mut s2) }, fmi2Error);
    assert!(log.lock().unwrap().last().unwrap().2.contains("checksum"));
    bytes[n / 2] ^= 0x10;
    assert_eq!(unsafe { de(c, bytes.as_ptr(), n - 3, &mut s2) }, fmi2Error);
    // A state of the bincode era (format version 2), checksum intact: refused by name.
    let mut old: Vec<u8> = bytes.iter().map(|&b| b as u8).collect();
    old[8..12].copy_from_slice(&2u32.to_le_bytes());
    let sum = powderfmu::envelope::fnv1a64(&old[powderfmu::envelope::HEADER..n - 8], powderfmu::envelope::FNV_OFFSET);
    old[n - 8..].copy_from_slice(&sum.to_le_bytes());
    assert_eq!(unsafe { de(c, old.as_ptr() as *const c_char, n, &mut s2) }, fmi2Error);
    let said = log.lock().unwrap().last().unwrap().2.clone();
    assert!(said.contains("format version 2") && said.contains("bincode"), "{said}");
    // A state of format version 3, in its own layout (magic, version, the fields, the checksum of all
    // before it, no length): refused by name, with what to do.
    let fields = &bytes[powderfmu::envelope::HEADER..n - 8];
    let mut v3: Vec<u8> = b"PFMUSTAT".to_vec();
    v3.extend_from_slice(&3u32.to_le_bytes());
    v3.extend(fields.iter().map(|&b| b as u8));
    let sum = powderfmu::envelope::fnv1a64(&v3, powderfmu::envelope::FNV_OFFSET);
    v3.extend_from_slice(&sum.to_le_bytes());
    assert_eq!(unsafe { de(c, v3.as_ptr() as *const c_char, v3.len(), &mut s2) }, fmi2Error);
    let said = log.lock().unwrap().last().unwrap().2.clone();
    assert!(said.contains("format version 3") && said.contains("save the state again"), "{said}");
    assert_eq!(unsafe { de(c, bytes.as_ptr(), n, &mut s2) }, fmi2OK);
    assert_eq!(unsafe { set_state(c, s2) }, fmi2OK);
    assert_eq!(run(20), first, "a deserialized state continues identically");
    unsafe {
        assert_eq!(free_state(c, &mut s), fmi2OK);
        assert_eq!(free_state(c, &mut s2), fmi2OK);
        assert!(s.is_null());
        assert_eq!(set_state(c, s2), fmi2Error, "a freed state is refused");
        // fmusim 0.0.39 passes the state itself, not its address: freed, OK, the mistake logged.
        let mut s3: fmi2FMUstate = std::ptr::null_mut();
        assert_eq!(get_state(c, &mut s3), fmi2OK);
        assert_eq!(free_state(c, s3 as *mut fmi2FMUstate), fmi2OK);
        let said = log.lock().unwrap().last().unwrap().clone();
        assert!(said.2.contains("the FMU state itself, not the address"), "{said:?}");
        assert_eq!(set_state(c, s3), fmi2Error, "that state is freed");
    }
    api.free(c);
}

#[test]
fn contact_element_force_follows_its_input() {
    let lib = library();
    let api = Api { lib: &lib };
    let log = Log::default();
    let u = "ContactElement";
    let c = api.instantiate(u, fmi2CoSimulation, &log, None);
    assert!(!c.is_null());
    api.call0(b"fmi2EnterInitializationMode", c);
    assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2OK);
    let step = f!(api, b"fmi2DoStep", DoStep);
    // Load to 60 nm and unload: the force follows the Nan law; unloading leaves a plastic overlap.
    let n = 200;
    let mut t = 0.0;
    let mut peak = 0.0f64;
    for i in 0..=2 * n {
        let alpha = 60e-9 * (1.0 - ((i as f64 - n as f64) / n as f64).abs());
        api.set(c, u, "wall_displacement", alpha);
        peak = peak.max(api.get(c, u, "force"));
        unsafe { step(c, t, 1e-3, fmi2True) };
        t += 1e-3;
    }
    assert!(peak > 1e-6, "{peak}");
    assert!(api.get(c, u, "plastic_overlap") > 0.0);
    assert!(api.get(c, u, "max_overlap") >= 60e-9 * (1.0 - 1e-9));
    assert!(api.get(c, u, "dissipated_energy") > 0.0);
    api.free(c);
}
