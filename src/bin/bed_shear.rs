//! `powderfmu bed shear`: the translational shear cell (`003` Sec. 5.1; `004` Sec. 2.2) on a prepared bed:
//! preshear, the shears to failure, the yield locus with its Mohr circles (`powderfmu::bed::shear`).

use crate::bed_cli::{load, Bar};
use crate::options;
use powderfmu::bed::file;
use powderfmu::bed::series::MeanEstimate;
use powderfmu::bed::shear::{self, Setup};
use powderfmu::bed::shear_state;
use powderfmu::bed::{AnyEngine, BedScene};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct ShearArgs {
    /// A prepared bed file (a whole die or a half: the shear runs along the half's mirror plane); not with --from-preshear
    #[arg(required_unless_present = "from_preshear", conflicts_with = "from_preshear")]
    bed: Option<PathBuf>,
    /// Start from a preshear saved with --save-preshear: its cell, stress, split, travel and time step;
    /// only the shears run (the preshear's curve and tau_pre are the saved run's)
    #[arg(long, value_name = "FILE", conflicts_with_all = ["preshear_stress", "split", "preshear_travel", "time_step", "save_preshear"])]
    from_preshear: Option<PathBuf>,
    /// Save the cell at the preshear's end to this file before the shears, for `--from-preshear`
    #[arg(long, value_name = "FILE")]
    save_preshear: Option<PathBuf>,
    /// Normal stress of the preshear, sigma_pre [Pa] (default: the bed's consolidation_stress)
    #[arg(long, value_name = "PA", value_parser = options::positive("Pa"))]
    preshear_stress: Option<f64>,
    /// Normal stresses of the shears to failure, as fractions of sigma_pre, comma-separated (003 Sec. 6's 0.25, 0.4, 0.6, 0.8)
    #[arg(long, value_name = "F,F,...", value_delimiter = ',', default_values_t = [0.25, 0.4, 0.6, 0.8])]
    normal_fractions: Vec<f64>,
    /// Speed of the drive [m/s]
    #[arg(long, value_name = "M_PER_S", default_value_t = 0.005, value_parser = options::positive("m/s"))]
    shear_speed: f64,
    /// Height of the rings' meeting, a fraction of the bed's height [default: 0.5]
    #[arg(long, value_name = "F", value_parser = options::in_range(0.1, 0.9, false, "-"))]
    split: Option<f64>,
    /// Travel of the preshear, in mean sphere diameters (on the Ch. 6 specimen 2 were not enough for steady
    /// flow and 5 were: docs/bed.md "The shear cell") [default: 5]
    #[arg(long, value_name = "D", value_parser = options::positive("mean diameters"))]
    preshear_travel: Option<f64>,
    /// Fraction of the preshear's travel over which tau_pre is averaged
    #[arg(long, value_name = "F", default_value_t = 0.3, value_parser = options::in_range(0.0, 1.0, false, "-"))]
    steady_fraction: f64,
    /// Largest travel of each shear to failure, in mean sphere diameters
    #[arg(long, value_name = "D", default_value_t = 0.5, value_parser = options::positive("mean diameters"))]
    shear_travel: f64,
    /// Travel window of the mean for tau_peak, in mean sphere diameters
    #[arg(long, value_name = "D", default_value_t = 0.05, value_parser = options::positive("mean diameters"))]
    window: f64,
    /// The lid's largest vertical speed under its servo [m/s] (default: half the drive's)
    #[arg(long, value_name = "M_PER_S", value_parser = options::positive("m/s"))]
    servo_speed: Option<f64>,
    /// Time allowed to each loading or unloading of the lid [s]
    #[arg(long, value_name = "S", default_value_t = 0.5, value_parser = options::positive("s"))]
    servo_time: f64,
    /// A fixed time step [s] (refused above the bed's stability limit; default: the bed's)
    #[arg(long, value_name = "S", value_parser = options::positive("s"))]
    time_step: Option<f64>,
    /// Threads of the force loop (default: the bed scene's)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=256))]
    threads: Option<u16>,
    /// The CSV to write (default: stdout): one row per sample (100 engine steps) of every phase
    #[arg(long, value_name = "CSV")]
    out: Option<PathBuf>,
}

/// Where the test starts: a prepared bed (the whole test) or a saved preshear (the shears only).
enum Start {
    Bed(Box<AnyEngine>, BedScene),
    Saved(shear::Presheared),
}

fn pm(x: &MeanEstimate) -> String {
    format!("{:.4e} +- {:.1e}", x.mean, x.standard_error)
}

/// ff_c = sigma_1 / sigma_c (004 Eq. 2.2), or why there is none: a sigma_c not above zero by two of its
/// standard errors (a cohesionless bed's locus through the origin) gives no finite ratio, and a negative
/// one no meaningful one.
fn flow_factor(sigma_1: f64, sc: f64, sc_e: f64) -> String {
    if sc > 2.0 * sc_e {
        format!("{:.3}", sigma_1 / sc)
    } else {
        "none: sigma_c is zero within two standard errors (a locus through the origin; free flowing)".into()
    }
}

pub fn shear_cmd(a: ShearArgs) -> Result<(), String> {
    let threads = a.threads.map(usize::from);
    let start = match (&a.bed, &a.from_preshear) {
        (Some(path), _) => {
            let (mut engine, scene) = load(path, threads)?;
            if let Some(dt) = a.time_step {
                engine.set_time_step(&scene, dt).map_err(|e| format!("--time-step: {e}"))?;
            }
            Start::Bed(Box::new(engine), scene)
        }
        (None, Some(path)) => {
            let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
            Start::Saved(shear_state::decode(&bytes).map_err(|e| format!("{}: {e}", path.display()))?)
        }
        (None, None) => return Err("give a bed file or --from-preshear FILE".into()),
    };
    let scene = match &start {
        Start::Bed(_, scene) => scene.clone(),
        Start::Saved(state) => state.scene().map_err(|e| e.to_string())?,
    };
    let saved = match &start {
        Start::Saved(state) => Some(state),
        Start::Bed(..) => None,
    };
    let d = scene.size_distribution.mean_diameter();
    let pre = saved.map_or(a.preshear_stress.unwrap_or(scene.consolidation_stress), |s| s.preshear_stress);
    let setup = Setup {
        preshear_stress: pre,
        normal_stresses: a.normal_fractions.iter().map(|f| f * pre).collect(),
        shear_speed: a.shear_speed,
        split: saved.map_or(a.split.unwrap_or(0.5), |s| s.split),
        preshear_displacement: saved.map_or(a.preshear_travel.unwrap_or(5.0) * d, |s| s.preshear_displacement),
        steady_fraction: a.steady_fraction,
        shear_displacement: a.shear_travel * d,
        window: a.window * d,
        servo_speed: a.servo_speed.unwrap_or(0.5 * a.shear_speed),
        servo_time: a.servo_time,
    };
    eprintln!(
        "shear cell: die {:.4e} m split at {} of the bed's height; preshear at {pre:.4e} Pa over {:.3e} m, shears at {:?} Pa over up to {:.3e} m each, drive {} m/s",
        scene.die_diameter, setup.split, setup.preshear_displacement, setup.normal_stresses, setup.shear_displacement, setup.shear_speed
    );
    if let (Some(path), Some(state)) = (&a.from_preshear, saved) {
        eprintln!(
            "shear cell: from the preshear saved in {} (drive {} m/s, time step {:.4e} s): the shears only",
            path.display(),
            state.shear_speed,
            state.time_step
        );
    }
    if let Some(path) = &a.save_preshear {
        let folder = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
        if !folder.is_dir() {
            return Err(format!("--save-preshear: the folder {} does not exist", folder.display()));
        }
    }
    // From a saved preshear its travel is done before the clock starts: the bar counts the shears' travel
    // alone, so that the time it says is left is theirs (it said 1.5 minutes of a 20-minute run).
    let skip = if saved.is_some() { setup.preshear_displacement / setup.total_travel() } else { 0.0 };
    let started = Instant::now();
    let mut bar = Bar::new();
    let mut show = |p: shear::Progress| {
        let s = p.sample;
        bar.show_phase(
            p.phase,
            ((p.fraction - skip) / (1.0 - skip)).max(0.0),
            s.time,
            &format!(
                "target {:.3e} Pa  lid {:.4e} Pa  travel {:.3e} m  sigma {:.4e} Pa  tau {:.4e} Pa  drive {:.4e} Pa",
                p.target, s.lid_stress, s.displacement, s.normal_stress, s.shear_stress, s.drive_stress
            ),
        );
        if std::env::var_os("POWDERFMU_SHEAR_TRACE").is_some() {
            eprintln!("{} {:.6e} {:.4e} {:.4e} {:.6e}", p.phase, s.time, s.lid_stress, s.drive_stress, s.lid);
        }
    };
    let state = match start {
        Start::Saved(state) => state,
        Start::Bed(mut engine, scene) => {
            let state = shear::preshear(&mut engine, &scene, &setup, &mut show).map_err(|e| e.to_string())?;
            if let Some(path) = &a.save_preshear {
                let bytes = shear_state::encode(&state).map_err(|e| e.to_string())?;
                // The shears still run when the file cannot be written: the preshear is not thrown away with it.
                match file::write_atomic(path, &bytes) {
                    Ok(()) => eprintln!("shear cell: the cell at the preshear's end saved in {} ({} bytes)", path.display(), bytes.len()),
                    Err(e) => eprintln!("shear cell: warning: --save-preshear: cannot write {} ({e}); the shears go on", path.display()),
                }
            }
            state
        }
    };
    let reading = shear::shears(&state, &setup, threads, &mut show).map_err(|e| e.to_string())?;
    bar.finish();
    let wall = started.elapsed().as_secs_f64();
    eprintln!(
        "shear cell: solid fraction {:.4} under sigma_pre; preshear steady state on the plane sigma {} Pa, tau {} Pa; its largest principal stress {} Pa",
        reading.solid_fraction,
        pm(&reading.preshear_normal),
        pm(&reading.preshear_shear),
        pm(&reading.preshear_major)
    );
    if let Some(pk) = &reading.preshear_peak {
        eprintln!(
            "shear cell: the steady preshear read as the shears read tau_peak (the largest window mean over each shear's travel, {} stretches): {} Pa, {:+.1} % of tau_pre from the fluctuation alone",
            pk.samples,
            pm(pk),
            100.0 * (pk.mean / reading.preshear_shear.mean - 1.0)
        );
    }
    for f in &reading.failures {
        eprintln!(
            "shear cell: sigma_n {:.4e} Pa: on the plane sigma {} Pa, tau_peak {} Pa at travel {:.3e} m ({})",
            f.target,
            pm(&f.normal_stress),
            pm(&f.shear_stress),
            f.displacement,
            if f.failed {
                "failed: fell to 0.9 of the peak"
            } else {
                "no fall to 0.9 of the peak within the travel: the largest mean of a plateau or a rise, a lower bound"
            }
        );
    }
    match &reading.locus {
        Some(yl) => {
            let (sc, sc_e) = yl.unconfined_yield_strength();
            eprintln!(
                "shear cell: yield locus tau = c + sigma tan(phi_i): c = {:.4e} +- {:.1e} Pa, phi_i = {:.2} +- {:.2} deg (chi^2 {:.1} for {} degrees of freedom)",
                yl.cohesion,
                yl.cohesion_error,
                yl.internal_friction_angle().to_degrees(),
                yl.internal_friction_angle_error().to_degrees(),
                yl.chi2,
                yl.dof
            );
            let (on, on_e) = yl.at(reading.preshear_normal.mean);
            let gap = (reading.preshear_shear.mean - on) / (on_e.powi(2) + reading.preshear_shear.standard_error.powi(2)).sqrt();
            eprintln!("shear cell: the preshear point against the locus extended to it: tau_pre {:.4e} Pa, locus {on:.4e} +- {on_e:.1e} Pa ({gap:+.1} standard errors)", reading.preshear_shear.mean);
            if let Some(pk) = &reading.preshear_peak {
                // Like with like: the shears' points are largest window means, tau_pre is a mean.
                let gap = (pk.mean - on) / (on_e.powi(2) + pk.standard_error.powi(2)).sqrt();
                eprintln!("shear cell: the steady preshear read as a shear point against the locus: {:.4e} Pa ({gap:+.1} standard errors)", pk.mean);
            }
            match yl.major_consolidation_stress(reading.preshear_normal.mean, reading.preshear_shear.mean) {
                Some((s1, s1_e)) => eprintln!(
                    "shear cell: sigma_c = {sc:.4e} +- {sc_e:.1e} Pa, sigma_1 = {s1:.4e} +- {s1_e:.1e} Pa (Mohr circles, 004 Fig. 2.5), ff_c = {}; {wall:.1} s wall time",
                    flow_factor(s1, sc, sc_e)
                ),
                None => eprintln!("shear cell: sigma_c = {sc:.4e} +- {sc_e:.1e} Pa; no Mohr circle through the preshear point is tangent to the locus (the point lies above it): no sigma_1 by construction; {wall:.1} s wall time"),
            }
        }
        None => eprintln!("shear cell: the points give no yield locus (fewer than two distinct normal stresses, or a line that does not rise with sigma: the points span too little normal stress for their scatter)"),
    }
    if let Some(yl) = &reading.locus {
        let (sc, sc_e) = yl.unconfined_yield_strength();
        eprintln!(
            "shear cell: with sigma_1 as measured (the slab's principal stress in the preshear), ff_c = {}",
            flow_factor(reading.preshear_major.mean, sc, sc_e)
        );
    }
    let mut csv = String::from("phase,normal_stress_target_Pa,time_s,displacement_m,normal_stress_Pa,shear_stress_Pa,major_principal_stress_Pa,lid_stress_Pa,drive_stress_Pa,lid_height_m\n");
    let mut rows = |phase: &str, target: f64, samples: &[shear::Sample]| {
        for s in samples {
            csv += &format!(
                "{phase},{target:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}\n",
                s.time, s.displacement, s.normal_stress, s.shear_stress, s.major_principal_stress, s.lid_stress, s.drive_stress, s.lid
            );
        }
    };
    rows("preshear", pre, &reading.preshear);
    for f in &reading.failures {
        rows("shear", f.target, &f.samples);
    }
    match &a.out {
        Some(path) => file::write_atomic(path, csv.as_bytes()).map_err(|e| format!("cannot write {}: {e}", path.display())),
        None => {
            print!("{csv}");
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::flow_factor;

    #[test]
    fn no_flow_factor_from_a_sigma_c_that_is_zero_within_its_error() {
        assert_eq!(flow_factor(2e4, 2e3, 1e2), "10.000");
        // 003's TiO2 case at k_c = 0 read sigma_c = -820 +- 660 Pa: no ff_c of -39.
        for (sc, sc_e) in [(-820.0, 660.0), (100.0, 60.0), (0.0, 0.0)] {
            assert!(flow_factor(3.2e4, sc, sc_e).starts_with("none: sigma_c is zero"), "{sc} +- {sc_e}");
        }
    }
}
