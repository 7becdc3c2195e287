//! Arbitrary sequences of fmi2 calls (up to 64 per run), with arbitrary arguments, on a Model Exchange and a Co-Simulation
//! instance: never a crash, a hang or fmi2Fatal (a caught panic). Each call is one opcode byte followed by
//! the bytes of its arguments.
#![no_main]

#[path = "common.rs"]
mod common;
use common::*;
use libfuzzer_sys::fuzz_target;
use powderfmu::fmi2::exports::*;
use powderfmu::fmi2::types::*;
use std::ffi::CString;
use std::ptr::{null, null_mut};

struct Input<'a>(&'a [u8]);

impl Input<'_> {
    fn byte(&mut self) -> Option<u8> {
        let (&b, rest) = self.0.split_first()?;
        self.0 = rest;
        Some(b)
    }
    fn f64(&mut self) -> Option<f64> {
        if self.0.len() < 8 {
            return None;
        }
        let (head, rest) = self.0.split_at(8);
        self.0 = rest;
        Some(f64::from_le_bytes(head.try_into().unwrap()))
    }
    fn string(&mut self) -> Option<CString> {
        let n = (self.byte()? % 24) as usize;
        let n = n.min(self.0.len());
        let (head, rest) = self.0.split_at(n);
        self.0 = rest;
        CString::new(head.iter().map(|&b| b.max(1)).collect::<Vec<u8>>()).ok()
    }
}

fuzz_target!(|data: &[u8]| {
    let me = instantiate(fmi2ModelExchange);
    let cs = instantiate(fmi2CoSimulation);
    let mut input = Input(data);
    let mut states: Vec<fmi2FMUstate> = Vec::new();
    let n_vars = powderfmu::units::by_identifier(PWI).unwrap().variables.len() as u32;
    let mut calls = 0;
    while let Some(op) = input.byte() {
        calls += 1;
        if calls > 64 {
            break;
        }
        let c = if op & 0x80 != 0 { cs } else { me };
        let status = unsafe {
            match op & 0x7f {
                0 => fmi2SetupExperiment(c, fmi2False, 0.0, input.f64().unwrap_or(0.0), fmi2False, 0.0),
                1 => fmi2EnterInitializationMode(c),
                2 => fmi2ExitInitializationMode(c),
                3 => fmi2Terminate(c),
                4 => fmi2Reset(c),
                5 => {
                    let vr = input.byte().unwrap_or(0) as u32 % (n_vars + 2);
                    fmi2SetReal(c, &vr, 1, &input.f64().unwrap_or(0.0))
                }
                6 => {
                    let vr = input.byte().unwrap_or(0) as u32 % (n_vars + 2);
                    let mut v = 0.0;
                    fmi2GetReal(c, &vr, 1, &mut v)
                }
                7 => {
                    let vr = input.byte().unwrap_or(0) as u32 % (n_vars + 2);
                    let s = input.string().unwrap_or_default();
                    fmi2SetString(c, &vr, 1, &s.as_ptr())
                }
                8 => {
                    let vr = input.byte().unwrap_or(0) as u32 % (n_vars + 2);
                    let mut s = null();
                    fmi2GetString(c, &vr, 1, &mut s)
                }
                9 => {
                    let t = input.f64().unwrap_or(0.0);
                    let mut h = input.f64().unwrap_or(1e-9);
                    // Zero, negative, NaN and infinite steps as they come; finite ones at most 1 us, so
                    // that the fuzzer spends its time on the interface, not on long physics (a long step
                    // of a stuck sphere is up to 1e7 segments, then an error).
                    if h.is_finite() && h.abs() > 1e-6 {
                        h = h.signum() * 1e-6;
                    }
                    fmi2DoStep(c, t, h, fmi2True)
                }
                10 => {
                    let mut t = 0.0;
                    let s = fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &mut t);
                    if s == fmi2OK {
                        fmi2DoStep(c, t, (input.byte().unwrap_or(1) as f64 + 1.0) * 1e-10, fmi2True)
                    } else {
                        s
                    }
                }
                11 => fmi2SetTime(c, input.f64().unwrap_or(0.0)),
                12 => {
                    let x = [input.f64().unwrap_or(0.0), input.f64().unwrap_or(0.0), input.f64().unwrap_or(0.0)];
                    fmi2SetContinuousStates(c, x.as_ptr(), 3)
                }
                13 => {
                    let mut d = [0.0; 3];
                    fmi2GetDerivatives(c, d.as_mut_ptr(), 3)
                }
                14 => {
                    let mut g = [0.0; 3];
                    fmi2GetEventIndicators(c, g.as_mut_ptr(), 3)
                }
                15 => {
                    let mut info = fmi2EventInfo::default();
                    fmi2NewDiscreteStates(c, &mut info)
                }
                16 => fmi2EnterContinuousTimeMode(c),
                17 => fmi2EnterEventMode(c),
                18 => {
                    let (mut e, mut t) = (fmi2False, fmi2False);
                    fmi2CompletedIntegratorStep(c, fmi2True, &mut e, &mut t)
                }
                19 => {
                    let mut s = null_mut();
                    let r = fmi2GetFMUstate(c, &mut s);
                    if r == fmi2OK {
                        states.push(s);
                    }
                    r
                }
                20 => match states.last() {
                    Some(&s) => fmi2SetFMUstate(c, s),
                    None => fmi2SetFMUstate(c, null_mut()),
                },
                21 => match states.pop() {
                    Some(mut s) => fmi2FreeFMUstate(c, &mut s),
                    None => fmi2FreeFMUstate(c, null_mut()),
                },
                22 => {
                    // A serialize/deserialize round trip of the newest state, with an arbitrary size.
                    let Some(&s) = states.last() else { continue };
                    let mut size = 0;
                    let r = fmi2SerializedFMUstateSize(c, s, &mut size);
                    if r != fmi2OK {
                        r
                    } else {
                        let wrong = input.byte().unwrap_or(0) as usize;
                        let mut buf = vec![0 as fmi2Byte; size + 64];
                        let asked = if wrong < 200 { size } else { size.saturating_sub(wrong - 199) };
                        let r = fmi2SerializeFMUstate(c, s, buf.as_mut_ptr(), asked);
                        let mut back = null_mut();
                        let r2 = fmi2DeSerializeFMUstate(c, buf.as_ptr(), asked, &mut back);
                        if r2 == fmi2OK {
                            states.push(back);
                        }
                        not_fatal(r, "fmi2SerializeFMUstate");
                        r2
                    }
                }
                23 => {
                    let on = input.byte().unwrap_or(0);
                    let cat = input.string().unwrap_or_default();
                    fmi2SetDebugLogging(c, fmi2Boolean::from(on & 1), 1, &cat.as_ptr())
                }
                24 => {
                    let mut x = [0.0; 3];
                    fmi2GetContinuousStates(c, x.as_mut_ptr(), 3)
                }
                25 => {
                    // Lengths that do not match the unit, and NULL arrays with nonzero lengths.
                    let n = input.byte().unwrap_or(0) as usize;
                    fmi2GetDerivatives(c, null_mut(), n)
                }
                _ => {
                    let n = input.byte().unwrap_or(0) as usize;
                    fmi2GetReal(c, null(), n, null_mut())
                }
            }
        };
        not_fatal(status, "a call");
    }
    unsafe {
        for mut s in states {
            fmi2FreeFMUstate(me, &mut s);
        }
        fmi2FreeInstance(me);
        fmi2FreeInstance(cs);
    }
});
