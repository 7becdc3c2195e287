//! 16 instances stepped at once from 16 threads give, bit for bit, what the same 16 give one after the
//! other; the library starts no thread of its own, so none is alive after fmi2FreeInstance (fmpy unloads
//! the library right after).

#[macro_use]
mod fmi_host;
use fmi_host::*;

use libloading::Symbol;
use powderfmu::fmi2::types::*;

const PWI: &str = "ParticleWallImpact";
const INSTANCES: usize = 16;
const STEPS: usize = 300;

/// One instance's run: impact speed by index, every output of every step as bits.
fn run(api: &Api, index: usize) -> Vec<u64> {
    let log = Log::default();
    let c = api.instantiate(PWI, fmi2CoSimulation, &log, None);
    assert!(!c.is_null());
    let setup = f!(api, b"fmi2SetupExperiment", Setup);
    let step = f!(api, b"fmi2DoStep", DoStep);
    // Laws with and without the exact solver, damped and not: each thread its own path.
    assert_eq!(api.set(c, PWI, "initial_velocity", 0.5 + 0.37 * index as f64), fmi2OK);
    assert_eq!(api.set(c, PWI, "restitution_coefficient", if index % 2 == 0 { 1.0 } else { 0.6 }), fmi2OK);
    unsafe {
        assert_eq!(setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK);
    }
    assert_eq!(api.call0(b"fmi2EnterInitializationMode", c), fmi2OK);
    assert_eq!(api.call0(b"fmi2ExitInitializationMode", c), fmi2OK);
    let mut bits = Vec::with_capacity(STEPS * 4);
    let h = 1e-9;
    for k in 0..STEPS {
        assert_eq!(unsafe { step(c, k as f64 * h, h, fmi2True) }, fmi2OK, "step {k} of instance {index}: {:?}", log.lock().unwrap().last());
        for name in ["sphere_position", "sphere_velocity", "force", "dissipated_energy"] {
            bits.push(api.get(c, PWI, name).to_bits());
        }
    }
    api.free(c);
    bits
}

fn threads_of_this_process() -> usize {
    std::fs::read_dir("/proc/self/task").map(|d| d.count()).unwrap_or(0)
}

#[test]
fn sixteen_threads_give_bitwise_the_sequential_results_and_leave_no_thread() {
    let lib = library();
    let api = Api { lib: &lib };
    let sequential: Vec<Vec<u64>> = (0..INSTANCES).map(|i| run(&api, i)).collect();
    let before = threads_of_this_process();
    let concurrent: Vec<Vec<u64>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..INSTANCES)
            .map(|i| {
                let api = Api { lib: &lib };
                scope.spawn(move || run(&api, i))
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("a thread of the test panicked")).collect()
    });
    for (i, (a, b)) in sequential.iter().zip(&concurrent).enumerate() {
        assert_eq!(a, b, "instance {i}: concurrent run differs from the sequential one");
    }
    // The runs differ from each other (so the comparison means something).
    assert_ne!(sequential[0], sequential[1]);
    // Our threads (the scoped ones) are joined; the library left none behind.
    assert_eq!(threads_of_this_process(), before, "threads alive after every instance was freed");
}
