//! Instantiate / initialize / step / save / restore / free cycles through the C ABI, as a host that
//! creates many short-lived instances would, printing the resident memory as it goes: the workload of
//! `tools/leak_check.sh` (under valgrind, and natively for the memory curve).
//!
//! Usage: cargo run --release --example lifecycle -- [CYCLES]

use powderfmu::fmi2::exports::*;
use powderfmu::fmi2::types::*;
use powderfmu::units;
use std::ffi::CString;
use std::ptr::null_mut;

fn resident_kib() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
    let pages: u64 = statm.split_whitespace().nth(1).and_then(|p| p.parse().ok()).unwrap_or(0);
    pages * 4
}

fn cycle(kind: fmi2Type, guid: &CString, uri: &CString, vr_velocity: fmi2ValueReference) {
    let name = CString::new("cycle").unwrap();
    let cb = fmi2CallbackFunctions { logger: None, allocateMemory: None, freeMemory: None, stepFinished: None, componentEnvironment: null_mut() };
    unsafe {
        let c = fmi2Instantiate(name.as_ptr(), kind, guid.as_ptr(), uri.as_ptr(), &cb, fmi2False, fmi2False);
        assert!(!c.is_null(), "fmi2Instantiate failed");
        assert_eq!(fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK);
        assert_eq!(fmi2SetReal(c, &vr_velocity, 1, &3.0), fmi2OK);
        assert_eq!(fmi2EnterInitializationMode(c), fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(c), fmi2OK);
        if kind == fmi2CoSimulation {
            for k in 0..10 {
                assert_eq!(fmi2DoStep(c, k as f64 * 2e-8, 2e-8, fmi2True), fmi2OK);
            }
        } else {
            let mut x = [0.0; 3];
            assert_eq!(fmi2GetDerivatives(c, x.as_mut_ptr(), 3), fmi2OK);
        }
        // A saved state, serialized, read back and restored, and a refused call on the way.
        let mut s = null_mut();
        assert_eq!(fmi2GetFMUstate(c, &mut s), fmi2OK);
        let mut size = 0;
        assert_eq!(fmi2SerializedFMUstateSize(c, s, &mut size), fmi2OK);
        let mut bytes = vec![0 as fmi2Byte; size];
        assert_eq!(fmi2SerializeFMUstate(c, s, bytes.as_mut_ptr(), size), fmi2OK);
        let mut back = null_mut();
        assert_eq!(fmi2DeSerializeFMUstate(c, bytes.as_ptr(), size, &mut back), fmi2OK);
        assert_eq!(fmi2SetFMUstate(c, back), fmi2OK);
        assert_eq!(fmi2DeSerializeFMUstate(c, bytes.as_ptr(), size / 2, &mut back), fmi2Error);
        assert_eq!(fmi2FreeFMUstate(c, &mut back), fmi2OK);
        assert_eq!(fmi2FreeFMUstate(c, &mut s), fmi2OK);
        assert_eq!(fmi2Terminate(c), fmi2OK);
        fmi2FreeInstance(c);
    }
}

fn main() {
    let cycles: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10_000);
    let unit = units::by_identifier("ParticleWallImpact").unwrap();
    let guid = CString::new(unit.guid()).unwrap();
    let uri = CString::new(format!("file://{}/", std::env::temp_dir().display())).unwrap();
    let vr = unit.vr("initial_velocity").expect("a variable of the unit") as fmi2ValueReference;
    let report = (cycles / 10).max(1);
    let mut first = 0;
    for i in 0..cycles {
        cycle(if i % 2 == 0 { fmi2CoSimulation } else { fmi2ModelExchange }, &guid, &uri, vr);
        if (i + 1) % report == 0 {
            let kib = resident_kib();
            if first == 0 {
                first = kib;
            }
            println!("lifecycle: {:>7} cycles, resident {kib} KiB ({:+} KiB since the first report)", i + 1, kib as i64 - first as i64);
        }
    }
}
