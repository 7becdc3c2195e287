//! `powderfmu bed compress`: the unconfined compression test (`004` Sec. 2.1) on a prepared bed; the
//! stress-strain CSV and sigma_c, ff_c (`powderfmu::bed::compression`).

use crate::bed_cli::{load, Bar};
use crate::options;
use powderfmu::bed::compression::{Compression, Setup, CHECK_EVERY};
use powderfmu::bed::file;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct CompressArgs {
    /// A prepared bed file (consolidated in its die: sigma_1 is its consolidation_stress)
    bed: PathBuf,
    /// Axial strain rate of the platen [1/s]
    #[arg(long, value_name = "PER_S", default_value_t = Setup::default().strain_rate, value_parser = options::positive("1/s"))]
    strain_rate: f64,
    /// Strain at which the test ends if the specimen has not failed [-]
    #[arg(long, value_name = "STRAIN", default_value_t = Setup::default().max_strain, value_parser = options::positive("-"))]
    max_strain: f64,
    /// Time the specimen stands free between the die's removal and the platen's start [s]
    #[arg(long, value_name = "S", default_value_t = Setup::default().free_time, value_parser = options::in_range(0.0, 10.0, true, "s"))]
    free_time: f64,
    /// Strain window of the stress's mean for the peak sigma_c [-]
    #[arg(long, value_name = "STRAIN", default_value_t = Setup::default().window, value_parser = options::positive("-"))]
    window: f64,
    /// Strain from which the samples are read for sigma_c and the failure (past the platen's arrival transient) [-]
    #[arg(long, value_name = "STRAIN", default_value_t = Setup::default().reading_start, value_parser = options::in_range(0.0, 0.9, true, "-"))]
    reading_start: f64,
    /// Threads of the force loop (default: the bed scene's)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=256))]
    threads: Option<u16>,
    /// The CSV to write (default: stdout): one row per sample (100 engine steps)
    #[arg(long, value_name = "CSV")]
    out: Option<PathBuf>,
}

pub fn compress_cmd(a: CompressArgs) -> Result<(), String> {
    let (mut engine, scene) = load(&a.bed, a.threads.map(usize::from))?;
    let setup =
        Setup { strain_rate: a.strain_rate, max_strain: a.max_strain, free_time: a.free_time, window: a.window, reading_start: a.reading_start };
    let started = Instant::now();
    let mut test = Compression::new(&mut engine, &scene, setup).map_err(|e| e.to_string())?;
    let s = test.start;
    let aspect = s.height / (scene.die_diameter);
    eprintln!(
        "unconfined compression: specimen {:.4e} m high (H/D {aspect:.2}), solid fraction {:.4}, consolidated to sigma_1 = {:.4e} Pa, its own weight {:.3e} Pa on its base; die removed, {} s free; platen at {} 1/s",
        s.height, s.solid_fraction, s.consolidation_stress, s.self_weight_stress, setup.free_time, setup.strain_rate
    );
    // The platen's travel until the strain ends the test, with a margin for the approach: a bound on the steps.
    let limit = ((1.5 * setup.max_strain + 0.05) / setup.strain_rate / engine.dt()) as u64;
    let chunk = 50 * CHECK_EVERY;
    let mut bar = Bar::new();
    let mut steps = 0;
    while !test.done && steps < limit {
        test.advance(&mut engine, &scene, chunk);
        steps += chunk;
        let last = test.samples.last().copied().unwrap_or_default();
        bar.show_phase(
            "loading",
            (last.strain / setup.max_strain).clamp(0.0, 1.0),
            last.time,
            &format!("strain {:.4}  stress {:.4e} Pa", last.strain, last.stress),
        );
    }
    bar.finish();
    let mut csv = String::from("time_s,strain,stress_Pa\n");
    for x in &test.samples {
        csv += &format!("{:.6e},{:.6e},{:.6e}\n", x.time, x.strain, x.stress);
    }
    let wall = started.elapsed().as_secs_f64();
    match test.reading() {
        Some(r) => {
            let u = r.unconfined_yield_strength;
            eprintln!(
                "unconfined compression: sigma_c {:.4e} +- {:.2e} Pa (the largest mean over {} strain, {} samples, correlation time {:.1} samples{}) at strain {:.4}, {}; ff_c = sigma_1 / sigma_c = {:.3}; {steps} steps, {wall:.1} s wall time",
                u.mean,
                u.standard_error,
                setup.window,
                u.samples,
                u.correlation_time,
                if u.reliable() { "" } else { ", under 50 correlation times: the error is itself uncertain" },
                r.strain_at_failure,
                if r.failed { "failed (the stress fell to 0.8 of its peak)" } else { "not failed by max_strain: sigma_c is a lower bound" },
                r.flow_function
            );
        }
        None => eprintln!("unconfined compression: the platen did not load the specimen over a window of {} strain; no sigma_c", setup.window),
    }
    match &a.out {
        Some(path) => file::write_atomic(path, csv.as_bytes()).map_err(|e| format!("cannot write {}: {e}", path.display())),
        None => {
            print!("{csv}");
            Ok(())
        }
    }
}
