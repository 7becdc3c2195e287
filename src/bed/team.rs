//! The engine's threads: the caller's own and `threads - 1` helpers, which exist while the engine exists
//! and are joined when it is dropped (FMI hosts count them). Each parallel phase of a step (kick, force
//! loop, the sum of the spills) has one part per thread, and part k goes to thread k (part 0 to the
//! caller): the same thread for the same part in every phase and step, so a part's spheres stay in its
//! core's cache. A helper waits for the next phase spinning for `SPIN`, then yielding its core, and sleeps
//! after `AWAKE`. A part whose helper has not taken it when the caller has finished its own (the helper
//! asleep, or not running: more threads than free cores) is done by the caller, so no phase waits for a
//! thread the kernel has not scheduled.
//!
//! This replaced a rayon pool (issue 30, docs/benchmarks.md "a team of threads"): rayon hands a phase's
//! second part to whichever worker steals it first, and its idle workers yield to the kernel between
//! phases. Which thread runs a part never changes the bits: the parts and the order of their sums are
//! fixed by the partition (`engine::partition`).

use std::cell::UnsafeCell;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long a waiting thread spins on the clock before it yields its core between the checks: the phases
/// of a step follow each other within microseconds and a yield costs a system call, but a thread that only
/// spins keeps its core from one that is not running (more threads than free cores: 3 threads on 2 cores
/// stepped 18 times slower with 2 ms of spinning and no yield).
const SPIN: Duration = Duration::from_micros(2);

/// How long a helper waits for the next phase, yielding, before it sleeps: the gaps between the phases of
/// a step are microseconds (a list rebuild between two phases then costs one wake-up), and a helper gives
/// its core back soon after its host stops stepping. (2 ms and 100 us stepped alike, alone and with two
/// engines sharing two cores: docs/benchmarks.md, "a team of threads".)
const AWAKE: Duration = Duration::from_micros(100);

type Job = *const (dyn Fn(usize) + Sync + 'static);

/// One part's state, on a cache line of its own so the threads' writes do not slow each other.
#[repr(align(128))]
#[derive(Default)]
struct Part {
    /// The last phase in which a thread took this part (only one thread takes it in a phase).
    taken: AtomicU64,
    /// The last phase in which this part was done.
    done: AtomicU64,
    /// Set while this part's helper sleeps (or is about to): the caller then wakes it.
    sleeping: AtomicBool,
}

impl Part {
    /// Takes the part for `phase`, unless a thread has already.
    fn take(&self, phase: u64) -> bool {
        let last = self.taken.load(Ordering::Acquire);
        last < phase && self.taken.compare_exchange(last, phase, Ordering::AcqRel, Ordering::Acquire).is_ok()
    }
}

struct Shared {
    /// Phases posted so far.
    posted: AtomicU64,
    /// The job of the phase posted last (written before `posted` is raised; read only by the thread that
    /// has taken a part of that phase, which the caller waits for before it writes the next job).
    job: UnsafeCell<Option<Job>>,
    parts: Vec<Part>,
    quit: AtomicBool,
    /// The first panic of a part in this phase, raised again on the caller's thread.
    panic: Mutex<Option<Box<dyn std::any::Any + Send>>>,
}

// SAFETY: `job` is written only by the one caller (`Team::run` takes `&mut self`) between phases: after
// every part of the last phase is done, before the next is posted. A helper reads it only after taking a
// part of the phase posted last, which cannot end before that part is done.
unsafe impl Sync for Shared {}
unsafe impl Send for Shared {}

impl Shared {
    /// Runs part k of `phase` (taken by this thread) and marks it done; a panic is kept for the caller.
    fn run_part(&self, k: usize, phase: u64) {
        // SAFETY: the job outlives the phase, and this thread has taken a part of it (see `Shared`).
        let job = unsafe { (*self.job.get()).expect("a phase has a job") };
        // SAFETY: as above.
        if let Err(payload) = catch_unwind(AssertUnwindSafe(|| unsafe { (*job)(k) })) {
            self.panic.lock().unwrap_or_else(|e| e.into_inner()).get_or_insert(payload);
        }
        self.parts[k].done.store(phase, Ordering::Release);
    }
}

pub struct Team {
    shared: Arc<Shared>,
    helpers: Vec<JoinHandle<()>>,
}

impl std::fmt::Debug for Team {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Team({} threads)", self.threads())
    }
}

impl Team {
    /// A team of `threads` (the caller and `threads - 1` helpers named `powderfmu-bed-k`).
    pub fn new(threads: usize) -> Result<Team, String> {
        let helpers = threads.saturating_sub(1);
        let shared = Arc::new(Shared {
            posted: AtomicU64::new(0),
            job: UnsafeCell::new(None),
            parts: (0..threads.max(1)).map(|_| Part::default()).collect(),
            quit: AtomicBool::new(false),
            panic: Mutex::new(None),
        });
        let mut team = Team { shared, helpers: Vec::with_capacity(helpers) };
        for k in 1..threads {
            let shared = team.shared.clone();
            let handle = std::thread::Builder::new()
                .name(format!("powderfmu-bed-{k}"))
                .spawn(move || helper(&shared, k))
                .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
            team.helpers.push(handle);
        }
        Ok(team)
    }

    /// The caller and the helpers.
    pub fn threads(&self) -> usize {
        self.helpers.len() + 1
    }

    /// Runs `job(k)` for every thread k, `job(0)` on the calling thread; returns when every part is
    /// done. A part that panics makes `run` panic with its payload once all are done.
    pub fn run(&mut self, job: &(dyn Fn(usize) + Sync)) {
        if self.helpers.is_empty() {
            return job(0);
        }
        let s = &*self.shared;
        // SAFETY: the lifetime is erased only for the phase: `run` returns after every part is done (the
        // waits below), and a helper reads the job only after taking a part of this phase (`Shared`).
        let erased: Job = unsafe { std::mem::transmute::<*const (dyn Fn(usize) + Sync + '_), Job>(job) };
        // SAFETY: no helper reads `job` now (see `Shared`).
        unsafe { *s.job.get() = Some(erased) };
        // SeqCst with the helper's `sleeping` store and `posted` load: either the helper sees the phase
        // before it sleeps, or this thread sees it asleep and wakes it.
        let phase = s.posted.fetch_add(1, Ordering::SeqCst) + 1;
        for (part, handle) in s.parts[1..].iter().zip(&self.helpers) {
            if part.sleeping.load(Ordering::SeqCst) {
                handle.thread().unpark();
            }
        }
        for k in 0..s.parts.len() {
            // Part 0, then each part its helper has not taken yet.
            if s.parts[k].take(phase) {
                s.run_part(k, phase);
            }
        }
        for part in &s.parts {
            wait(|| part.done.load(Ordering::Acquire) == phase, Duration::MAX, || {});
        }
        if let Some(payload) = s.panic.lock().unwrap_or_else(|e| e.into_inner()).take() {
            resume_unwind(payload);
        }
    }

    /// `f(k, items[k])` on thread k for each item (at most one per thread), the results in order.
    pub fn map<T: Send, R: Send>(&mut self, items: Vec<T>, f: impl Fn(usize, T) -> R + Sync) -> Vec<R> {
        assert!(items.len() <= self.threads(), "at most one item per thread");
        let count = items.len();
        let items: Vec<Mutex<Option<T>>> = items.into_iter().map(|t| Mutex::new(Some(t))).collect();
        let results: Vec<Mutex<Option<R>>> = (0..count).map(|_| Mutex::new(None)).collect();
        self.run(&|k| {
            if k < count {
                let item = items[k].lock().unwrap_or_else(|e| e.into_inner()).take().expect("each item taken once");
                *results[k].lock().unwrap_or_else(|e| e.into_inner()) = Some(f(k, item));
            }
        });
        results.into_iter().map(|r| r.into_inner().unwrap_or_else(|e| e.into_inner()).expect("every part ran")).collect()
    }
}

/// Waits until `ready`: spinning for `SPIN`, then yielding the core between the checks until `awake`, then
/// calling `sleep` between the checks. The clock is read every 64 checks.
#[inline]
fn wait(ready: impl Fn() -> bool, awake: Duration, mut sleep: impl FnMut()) {
    let start = Instant::now();
    let mut checks = 0u32;
    let mut waited = Duration::ZERO;
    while !ready() {
        checks = checks.wrapping_add(1);
        if checks.is_multiple_of(64) {
            waited = start.elapsed();
        }
        if waited < SPIN {
            std::hint::spin_loop();
        } else if waited < awake {
            std::thread::yield_now();
        } else {
            sleep();
        }
    }
}

/// Helper k's life: part k of each phase posted (unless the caller has taken it); asleep when no phase
/// comes within `AWAKE`.
fn helper(s: &Shared, k: usize) {
    let part = &s.parts[k];
    let mut seen = 0u64;
    loop {
        wait(
            || s.posted.load(Ordering::Acquire) != seen,
            AWAKE,
            || {
                part.sleeping.store(true, Ordering::SeqCst);
                if s.posted.load(Ordering::SeqCst) == seen {
                    // An unpark between the store and here makes the park return at once.
                    std::thread::park();
                }
                part.sleeping.store(false, Ordering::SeqCst);
            },
        );
        seen = s.posted.load(Ordering::Acquire);
        if s.quit.load(Ordering::Acquire) {
            return;
        }
        if part.take(seen) {
            s.run_part(k, seen);
        }
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        let s = &*self.shared;
        s.quit.store(true, Ordering::SeqCst);
        s.posted.fetch_add(1, Ordering::SeqCst);
        for handle in &self.helpers {
            handle.thread().unpark();
        }
        // Every helper returns at once (it runs no job after `quit`): joined, so the host gets its threads back.
        for handle in self.helpers.drain(..) {
            let _ = handle.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    #[test]
    fn each_part_runs_once_in_every_phase_on_its_thread_or_the_callers() {
        let mut team = Team::new(3).unwrap();
        let caller = std::thread::current().id();
        let mut by_helper = [0usize; 3];
        for _ in 0..200 {
            let ran: Vec<(std::thread::ThreadId, String)> = team.map(vec![(); 3], |_, ()| {
                // A part long enough for a helper that was asleep or not running to take its own.
                let start = Instant::now();
                while start.elapsed() < Duration::from_micros(100) {
                    std::hint::spin_loop();
                }
                let me = std::thread::current();
                (me.id(), me.name().unwrap_or("").to_string())
            });
            assert_eq!(ran[0].0, caller, "part 0 is the caller's");
            for k in 1..3 {
                if ran[k].0 != caller {
                    assert_eq!(ran[k].1, format!("powderfmu-bed-{k}"), "part {k} runs on its own helper or the caller");
                    by_helper[k] += 1;
                }
            }
        }
        assert!(by_helper[1] > 0 && by_helper[2] > 0, "the helpers take their parts: {by_helper:?}");
        let count = AtomicUsize::new(0);
        team.run(&|k| {
            count.fetch_add(1 << (8 * k), Ordering::Relaxed);
        });
        assert_eq!(count.into_inner(), 0x010101, "each part once");
    }

    #[test]
    fn a_sleeping_helper_is_woken() {
        let mut team = Team::new(2).unwrap();
        // Asleep after AWAKE (polled: a busy machine may run the helper late).
        let start = Instant::now();
        while !team.shared.parts[1].sleeping.load(Ordering::SeqCst) && start.elapsed() < Duration::from_secs(5) {
            std::thread::sleep(AWAKE);
        }
        assert!(team.shared.parts[1].sleeping.load(Ordering::SeqCst), "the helper sleeps after AWAKE");
        assert_eq!(team.map(vec![1, 2], |k, x| x * 10 + k), vec![10, 21]);
    }

    #[test]
    fn a_helpers_panic_reaches_the_caller_and_the_team_stays_usable() {
        let mut team = Team::new(2).unwrap();
        let r = catch_unwind(AssertUnwindSafe(|| team.run(&|k| assert!(k != 1, "part 1 fails"))));
        assert!(r.is_err());
        assert_eq!(team.map(vec![3, 4], |_, x| x + 1), vec![4, 5]);
    }
}
