//! 16 instances stepped at once from 16 threads give, bit for bit, what the same 16 give one after the
//! other; the library starts no thread of its own, so none is alive after fmi2FreeInstance (fmpy unloads
//! the library right after). The same for FMI 3.0 instances (with early return), whose runs without early
//! return are the FMI 2.0 ones to the bit.

#[macro_use]
mod host;
use host::fmi3::Api3;
use host::*;

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
    assert_eq!(api.set(c, PWI, "restitution_coefficient", if index.is_multiple_of(2) { 1.0 } else { 0.6 }), fmi2OK);
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

/// The two tests count the process's threads: they run one after the other.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn threads_of_this_process() -> usize {
    std::fs::read_dir("/proc/self/task").map(|d| d.count()).unwrap_or(0)
}

#[test]
fn sixteen_threads_give_bitwise_the_sequential_results_and_leave_no_thread() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
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

/// One FMI 3.0 instance's run (`run`'s scene): with `early_return`, the steps end at contact events and
/// the next starts from lastSuccessfulTime; the bits of every output at every step end.
fn run3(api: &Api3, index: usize, early_return: bool) -> Vec<u64> {
    let log = Log::default();
    let c = api.instantiate(PWI, false, false, early_return, &log);
    assert!(!c.is_null(), "{:?}", log.lock().unwrap().last());
    assert_eq!(api.set(c, PWI, "initial_velocity", 0.5 + 0.37 * index as f64), fmi2OK);
    assert_eq!(api.set(c, PWI, "restitution_coefficient", if index.is_multiple_of(2) { 1.0 } else { 0.6 }), fmi2OK);
    assert_eq!(api.enter_initialization(c), fmi2OK);
    assert_eq!(api.call0(b"fmi3ExitInitializationMode", c), fmi2OK);
    let mut bits = Vec::with_capacity(STEPS * 4);
    let (h, mut t, mut k) = (1e-9, 0.0, 0usize);
    while k < STEPS {
        let end = (k + 1) as f64 * h;
        // The grid of `run` (from k h by h) where the last step ended on it; from an event, to the grid.
        let (status, _, early, last) = if t == k as f64 * h { api.do_step(c, t, h) } else { api.do_step(c, t, end - t) };
        assert_eq!(status, fmi2OK, "step {k} of instance {index}: {:?}", log.lock().unwrap().last());
        t = last;
        if !early {
            t = end;
            k += 1;
        }
        for name in ["sphere_position", "sphere_velocity", "force", "dissipated_energy"] {
            bits.push(api.get(c, PWI, name).to_bits());
        }
    }
    api.free(c);
    bits
}

#[test]
fn sixteen_fmi3_threads_give_bitwise_the_sequential_results_and_without_early_return_the_fmi2_ones() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let lib = library();
    let api = Api3 { lib: &lib };
    let sequential: Vec<Vec<u64>> = (0..INSTANCES).map(|i| run3(&api, i, true)).collect();
    let before = threads_of_this_process();
    let concurrent: Vec<Vec<u64>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..INSTANCES)
            .map(|i| {
                let api = Api3 { lib: &lib };
                scope.spawn(move || run3(&api, i, true))
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("a thread of the test panicked")).collect()
    });
    for (i, (a, b)) in sequential.iter().zip(&concurrent).enumerate() {
        assert_eq!(a, b, "FMI 3.0 instance {i}: concurrent run differs from the sequential one");
    }
    // Early return added rows (the contact events inside the steps).
    assert!(sequential.iter().all(|r| r.len() > STEPS * 4), "every impact has events inside its steps");
    assert_eq!(threads_of_this_process(), before, "threads alive after every instance was freed");
    let fmi2 = Api { lib: &lib };
    for i in [0, 1, 7] {
        assert_eq!(run3(&api, i, false), run(&fmi2, i), "instance {i}: FMI 3.0 without early return differs from FMI 2.0");
    }
}
