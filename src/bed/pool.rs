//! The engine's own thread pool: rayon workers that exist while the engine exists and are joined when
//! it is dropped, so a host that frees the bed gets its threads back (FMI hosts count them).

use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

pub struct Pool {
    pool: Option<rayon::ThreadPool>,
    exited: Arc<(Mutex<usize>, Condvar)>,
    threads: usize,
}

impl std::fmt::Debug for Pool {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Pool({} threads)", self.threads)
    }
}

impl Pool {
    pub fn new(threads: usize) -> Result<Pool, String> {
        let exited = Arc::new((Mutex::new(0usize), Condvar::new()));
        let signal = exited.clone();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|k| format!("powderfmu-bed-{k}"))
            .exit_handler(move |_| {
                let (count, cv) = &*signal;
                *count.lock().unwrap_or_else(|e| e.into_inner()) += 1;
                cv.notify_all();
            })
            .build()
            .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
        Ok(Pool { pool: Some(pool), exited, threads })
    }

    pub fn install<R: Send>(&self, f: impl FnOnce() -> R + Send) -> R {
        self.pool.as_ref().expect("pool present until drop").install(f)
    }
}

impl Drop for Pool {
    fn drop(&mut self) {
        drop(self.pool.take());
        let (count, cv) = &*self.exited;
        let mut n = count.lock().unwrap_or_else(|e| e.into_inner());
        // Wait for every worker to leave (bounded, so a stuck worker cannot hang the host).
        let deadline = std::time::Instant::now() + Duration::from_secs(10);
        while *n < self.threads {
            let left = deadline.saturating_duration_since(std::time::Instant::now());
            if left.is_zero() {
                break;
            }
            n = cv.wait_timeout(n, left).unwrap_or_else(|e| e.into_inner()).0;
        }
    }
}
