//! fmi2DeSerializeFMUstate on untrusted bytes: never a crash or an out-of-bounds read, and a state it
//! accepts restores and steps. The first input byte chooses how the rest is used: as the whole byte
//! string; as the payload of a correct envelope (so the fuzzer reaches the parser behind it); or as edits
//! (position, value pairs) of a genuine state's payload, sealed again.
#![no_main]

#[path = "common.rs"]
mod common;
use common::*;
use libfuzzer_sys::fuzz_target;
use powderfmu::fmi2::exports::*;
use powderfmu::fmi2::types::*;
use std::ptr::null_mut;

/// A genuine saved state (after 20 steps of an impact), made once.
fn genuine() -> Vec<u8> {
    static BYTES: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    BYTES.get_or_init(make_genuine).clone()
}

fn make_genuine() -> Vec<u8> {
    let c = instantiate(fmi2CoSimulation);
    unsafe {
        fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0);
        fmi2EnterInitializationMode(c);
        fmi2ExitInitializationMode(c);
        for k in 0..20 {
            fmi2DoStep(c, k as f64 * 1e-9, 1e-9, fmi2True);
        }
        let mut s = null_mut();
        fmi2GetFMUstate(c, &mut s);
        let mut size = 0;
        fmi2SerializedFMUstateSize(c, s, &mut size);
        let mut bytes = vec![0 as fmi2Byte; size];
        fmi2SerializeFMUstate(c, s, bytes.as_mut_ptr(), size);
        fmi2FreeFMUstate(c, &mut s);
        fmi2FreeInstance(c);
        bytes.into_iter().map(|b| b as u8).collect()
    }
}

/// `payload` sealed as a genuine state is (the saved-data envelope with its magic, version, length and
/// checksum), so the fuzzer reaches the parser behind the envelope.
fn sealed(payload: &[u8]) -> Vec<u8> {
    let g = genuine();
    let format = powderfmu::envelope::Format { magic: b"PFMUSTAT", version: u32::from_le_bytes(g[8..12].try_into().unwrap()) };
    powderfmu::envelope::seal(format, payload)
}

fuzz_target!(|data: &[u8]| {
    let Some((&how, rest)) = data.split_first() else { return };
    let c = instantiate(fmi2CoSimulation);
    let bytes = match how % 3 {
        0 => rest.to_vec(),
        1 => sealed(rest),
        _ => {
            let g = genuine();
            let mut g = g[powderfmu::envelope::HEADER..g.len() - powderfmu::envelope::TRAILER].to_vec();
            for pair in rest.chunks_exact(3) {
                let at = u16::from_le_bytes([pair[0], pair[1]]) as usize;
                if !g.is_empty() {
                    let i = at % g.len();
                    g[i] = pair[2];
                }
            }
            if rest.len() % 3 == 1 {
                let cut = rest[rest.len() - 1] as usize;
                g.truncate(g.len().saturating_sub(cut));
            }
            sealed(&g)
        }
    };
    unsafe {
        let mut s: fmi2FMUstate = null_mut();
        let st = not_fatal(fmi2DeSerializeFMUstate(c, bytes.as_ptr() as *const fmi2Byte, bytes.len(), &mut s), "fmi2DeSerializeFMUstate");
        if st == fmi2OK {
            if not_fatal(fmi2SetFMUstate(c, s), "fmi2SetFMUstate") == fmi2OK {
                let mut t = 0.0;
                fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &mut t);
                if t.is_finite() {
                    // A short step: what matters is that the restored state steps, not how far.
                    not_fatal(fmi2DoStep(c, t, 1e-12, fmi2True), "fmi2DoStep");
                }
                let mut v = 0.0;
                not_fatal(fmi2GetReal(c, &vr("sphere_velocity"), 1, &mut v), "fmi2GetReal");
            }
            fmi2FreeFMUstate(c, &mut s);
        }
        fmi2FreeInstance(c);
    }
});
