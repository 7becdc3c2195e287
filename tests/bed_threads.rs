//! The bed engine's helper threads are joined when the engine is dropped. A test binary of its own: the thread
//! count of the process must not be disturbed by other tests running beside it.

use powderfmu::bed::prepare;
use powderfmu::bed::{AnyEngine, BedScene};

fn threads() -> usize {
    std::fs::read_dir("/proc/self/task").map(|d| d.count()).unwrap_or(0)
}

#[test]
fn the_helper_threads_are_joined_when_the_engine_is_dropped() {
    let before = threads();
    for _ in 0..3 {
        {
            let scene = BedScene::from_json(
                r#"{"threads": 3, "particle_count": 50, "die_diameter": 0.008, "particle_particle": {"particle_youngs_modulus": 55e6}}"#,
            )
            .unwrap();
            let mut e = AnyEngine::build(&scene, prepare::fill(&scene).unwrap(), prepare::die(&scene)).unwrap();
            e.run(10);
            // Three threads: the caller and two helpers.
            assert_eq!(threads(), before + 2);
        }
        // Every helper has been joined when the drop returns; the kernel reaps the thread a moment later.
        let start = std::time::Instant::now();
        while threads() != before && start.elapsed().as_secs_f64() < 1.0 {
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
        assert_eq!(threads(), before);
    }
}
