//! The runs of each unit: a short scenario per unit in Co-Simulation (with a saved state halfway; for
//! ParticleWallImpact a vibrating wall given by its acceleration, an input derivative) and in
//! Model Exchange (explicit Euler at a fixed step with event handling); for an FMI 3.0 FMU, Co-Simulation
//! with early return (FMI 3.0 has no input derivatives: the wall stands still). Each prints its final
//! outputs with `{:e}` (the shortest text that reads back to the same f64), to be compared across platforms.

use crate::fmi::{print_warnings, Unpacked, CO_SIMULATION, MODEL_EXCHANGE};
use fmi_host::fmi2::Instance;
use fmi_host::fmi3::Instance as Instance3;
use std::path::Path;

/// A unit's scenario: start values, the steps, the inputs at a time, and the outputs to print.
struct Scenario {
    strings: &'static [(&'static str, &'static str)],
    reals: &'static [(&'static str, f64)],
    steps: usize,
    step: f64,
    inputs: fn(f64) -> Vec<(&'static str, f64)>,
    /// Co-Simulation only: input derivatives (name, order, value) at the start of each step.
    derivatives: fn(f64) -> Vec<(&'static str, i32, f64)>,
    outputs: &'static [&'static str],
    integers: &'static [&'static str],
}

/// A triangle wave of the wall for ContactElement: up to 2e-8 m and back in 2e-6 s (a few times the
/// adhesive and plastic overlaps of the default scene, 000 Table 5), then apart.
fn contact_wall(t: f64) -> Vec<(&'static str, f64)> {
    let (peak, half) = (2e-8, 1e-6);
    let (z, v) = if t < half {
        (peak * t / half, peak / half)
    } else if t < 2.0 * half {
        (peak * (2.0 - t / half), -peak / half)
    } else {
        (0.0, 0.0)
    };
    vec![("wall_displacement", z), ("wall_velocity", v)]
}

fn no_inputs(_: f64) -> Vec<(&'static str, f64)> {
    Vec::new()
}

fn no_derivatives(_: f64) -> Vec<(&'static str, i32, f64)> {
    Vec::new()
}

/// ParticleWallImpact in Co-Simulation: the wall vibrates, its acceleration given as an input derivative
/// (fmi2SetRealInputDerivatives, order 1 of wall_velocity), 1e6 m/s2 peak at 5 MHz.
fn vibrating_wall(t: f64) -> Vec<(&'static str, i32, f64)> {
    vec![("wall_velocity", 1, 1e6 * (2.0 * std::f64::consts::PI * 5e6 * t).cos())]
}

fn scenario(id: &str) -> Result<Scenario, String> {
    match id {
        // An impact at 3 m/s of the default sphere (000 Table 5, Nan's law) on a still wall.
        "ParticleWallImpact" => Ok(Scenario {
            strings: &[("contact_model", "nan")],
            reals: &[("initial_velocity", 3.0)],
            steps: 300,
            step: 1e-9,
            inputs: no_inputs,
            derivatives: vibrating_wall,
            outputs: &["force", "overlap", "sphere_position", "sphere_velocity", "max_overlap", "dissipated_energy"],
            integers: &["contact_state"],
        }),
        "ContactElement" => Ok(Scenario {
            strings: &[],
            reals: &[],
            steps: 250,
            step: 1e-8,
            inputs: contact_wall,
            derivatives: no_derivatives,
            outputs: &["force", "overlap", "max_overlap", "plastic_overlap", "pull_off_force", "dissipated_energy"],
            integers: &["contact_state"],
        }),
        // The first 1 ms of the default test on the shipped bed (the resources folder, by URI): 4000
        // steps of 29000 spheres, a few seconds, the same bits on every platform.
        "BallIndentation" => Ok(Scenario {
            strings: &[],
            reals: &[],
            steps: 10,
            step: 1e-4,
            inputs: no_inputs,
            derivatives: no_derivatives,
            outputs: &["indenter_force", "penetration_depth", "hardness", "kinetic_energy"],
            integers: &["test_state", "indenter_contacts"],
        }),
        // The first 2 ms of the default test on the shipped specimen: the platen's approach and its first
        // 0.1 % of strain, 20000 steps of 4000 spheres, the same bits on every platform.
        "UnconfinedCompression" => Ok(Scenario {
            strings: &[],
            reals: &[],
            steps: 10,
            step: 2e-4,
            inputs: no_inputs,
            derivatives: no_derivatives,
            outputs: &["axial_stress", "axial_strain", "kinetic_energy", "solid_fraction"],
            integers: &["test_state"],
        }),
        other => Err(format!("no scenario for unit {other}")),
    }
}

/// Reading outputs, in either version.
trait Reads {
    fn real(&self, name: &str) -> Result<f64, String>;
    fn integer(&self, name: &str) -> Result<i32, String>;
}

impl Reads for Instance<'_> {
    fn real(&self, name: &str) -> Result<f64, String> {
        Instance::real(self, name)
    }
    fn integer(&self, name: &str) -> Result<i32, String> {
        Instance::integer(self, name)
    }
}

impl Reads for Instance3<'_> {
    fn real(&self, name: &str) -> Result<f64, String> {
        Instance3::real(self, name)
    }
    fn integer(&self, name: &str) -> Result<i32, String> {
        Instance3::integer(self, name)
    }
}

fn line(what: &str, i: &impl Reads, s: &Scenario, t: f64) -> Result<(), String> {
    let mut text = format!("{what} t={t:e}");
    for name in s.outputs {
        text += &format!(" {name}={:e}", i.real(name)?);
    }
    for name in s.integers {
        text += &format!(" {name}={}", i.integer(name)?);
    }
    println!("{text}");
    Ok(())
}

fn start<'a>(fmu: &'a Unpacked, kind: i32, s: &Scenario) -> Result<Instance<'a>, String> {
    let i = fmu.instance(kind)?;
    i.setup(0.0)?;
    for (name, value) in s.strings {
        i.set_string(name, value)?;
    }
    for (name, value) in s.reals {
        i.set_real(name, *value)?;
    }
    for (name, value) in (s.inputs)(0.0) {
        i.set_real(name, value)?;
    }
    i.call("fmi2EnterInitializationMode")?;
    i.call("fmi2ExitInitializationMode")?;
    Ok(i)
}

/// Co-Simulation: the scenario's steps; halfway the state is written to `state_out`, or (with
/// `state_in`) the run starts there from the saved state.
pub fn co_simulation(fmu: &Unpacked, state_out: Option<&Path>, state_in: Option<&Path>) -> Result<(), String> {
    let s = scenario(&fmu.model_description.model_identifier)?;
    let i = start(fmu, CO_SIMULATION, &s)?;
    let half = s.steps / 2;
    let mut first = 0;
    if let Some(path) = state_in {
        let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        i.restore_state(&bytes)?;
        first = half;
        line("CS restored", &i, &s, half as f64 * s.step)?;
    }
    for k in first..s.steps {
        if k == half {
            if let Some(path) = state_out {
                std::fs::write(path, i.serialize_state()?).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                line("CS saved", &i, &s, k as f64 * s.step)?;
            }
        }
        let t = k as f64 * s.step;
        for (name, value) in (s.inputs)(t) {
            i.set_real(name, value)?;
        }
        for (name, order, value) in (s.derivatives)(t) {
            i.set_input_derivative(name, order, value)?;
        }
        i.do_step(t, s.step)?;
    }
    line("CS final", &i, &s, s.steps as f64 * s.step)?;
    let end = i.call("fmi2Terminate");
    print_warnings(i.log());
    end
}

/// Model Exchange: explicit Euler at 1/1000 of the CS step, an event when an indicator changes sign or
/// the FMU asks for one at a completed step.
pub fn model_exchange(fmu: &Unpacked) -> Result<(), String> {
    let md = &fmu.model_description;
    let s = scenario(&md.model_identifier)?;
    let i = start(fmu, MODEL_EXCHANGE, &s)?;
    let settle = |i: &Instance| -> Result<(), String> {
        while i.new_discrete_states()?.new_discrete_states_needed != 0 {}
        Ok(())
    };
    settle(&i)?;
    i.call("fmi2EnterContinuousTimeMode")?;
    let (mut x, mut dx) = (vec![0.0; md.states], vec![0.0; md.states]);
    let mut z = vec![0.0; md.event_indicators];
    let mut z_new = z.clone();
    i.vector("fmi2GetContinuousStates", &mut x)?;
    i.vector("fmi2GetEventIndicators", &mut z)?;
    let h = s.step / 1000.0;
    let n = s.steps * 1000;
    let mut events = 0;
    for k in 0..n {
        let t = k as f64 * h;
        i.vector("fmi2GetDerivatives", &mut dx)?;
        for (xi, di) in x.iter_mut().zip(&dx) {
            *xi += h * di;
        }
        let t_next = t + h;
        i.set_time(t_next)?;
        for (name, value) in (s.inputs)(t_next) {
            i.set_real(name, value)?;
        }
        i.set_states(&x)?;
        i.vector("fmi2GetEventIndicators", &mut z_new)?;
        let crossed = z.iter().zip(&z_new).any(|(a, b)| (*a > 0.0) != (*b > 0.0));
        if i.completed_step()? || crossed {
            i.call("fmi2EnterEventMode")?;
            settle(&i)?;
            i.call("fmi2EnterContinuousTimeMode")?;
            i.vector("fmi2GetContinuousStates", &mut x)?;
            i.vector("fmi2GetEventIndicators", &mut z_new)?;
            events += 1;
        }
        std::mem::swap(&mut z, &mut z_new);
    }
    line(&format!("ME final ({events} events)"), &i, &s, n as f64 * h)?;
    let end = i.call("fmi2Terminate");
    print_warnings(i.log());
    end
}

/// FMI 3.0 Co-Simulation with early return: the scenario's grid, each step ending early at a contact
/// event and the next going on from there to the grid; the state saved or restored halfway as in
/// `co_simulation`. Prints the final outputs and the number of early returns.
pub fn co_simulation_fmi3(fmu: &Unpacked, state_out: Option<&Path>, state_in: Option<&Path>) -> Result<(), String> {
    let s = scenario(&fmu.model_description.model_identifier)?;
    let i = fmu.instance3(true)?;
    i.enter_initialization(0.0)?;
    for (name, value) in s.strings {
        i.set_string(name, value)?;
    }
    for (name, value) in s.reals {
        i.set_real(name, *value)?;
    }
    for (name, value) in (s.inputs)(0.0) {
        i.set_real(name, value)?;
    }
    i.call("fmi3ExitInitializationMode")?;
    let half = s.steps / 2;
    let (mut k, mut t, mut early_returns) = (0, 0.0, 0);
    if let Some(path) = state_in {
        let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        i.restore_state(&bytes)?;
        (k, t) = (half, half as f64 * s.step);
        line("CS3 restored", &i, &s, t)?;
    }
    let mut saved = state_in.is_some();
    while k < s.steps {
        if k == half && !saved {
            saved = true;
            if let Some(path) = state_out {
                std::fs::write(path, i.serialize_state()?).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                line("CS3 saved", &i, &s, t)?;
            }
        }
        for (name, value) in (s.inputs)(t) {
            i.set_real(name, value)?;
        }
        // On the grid: a step of the scenario; after an early return: to the next grid point.
        let on_grid = t == k as f64 * s.step;
        let h = if on_grid { s.step } else { (k + 1) as f64 * s.step - t };
        let (_, early, last) = i.do_step(t, h)?;
        if early {
            early_returns += 1;
            t = last;
        } else {
            k += 1;
            t = k as f64 * s.step;
        }
    }
    line(&format!("CS3 final ({early_returns} early returns)"), &i, &s, t)?;
    let end = i.call("fmi3Terminate");
    print_warnings(i.log());
    end
}
