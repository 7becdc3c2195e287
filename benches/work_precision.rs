//! The work-precision study of the sphere-wall integrators (`cargo bench --bench work_precision`).
//!
//! For every law and each solver (exact, adaptive over tolerances, verlet over fractions of the Rayleigh
//! step), single impacts below, near and far above the law's sticking velocity: the error of the rebound
//! velocity, restitution, maximum overlap and plastic overlap against a reference, and the native cost
//! in nanoseconds per impact (median of repeated runs, all in this one process). References: the closed
//! forms of `theory::restitution` for the undamped piecewise-linear laws, `adaptive` at tolerance 1e-13
//! elsewhere (nonlinear laws, damped Nan). Also the fidelity axis on 004 Table 4.1: each linear law's
//! restitution curve and sticking velocity against Thornton-Ning's, beside each law's cost per force
//! evaluation.
//!
//! Writes docs/figures/work_precision.csv, docs/figures/fidelity_curves.csv and
//! docs/figures/fidelity.csv; `benches/work_precision_plot.py` turns them into figures and tables.

#[path = "../tests/common/mod.rs"]
mod common;

use powderfmu::impact::{Contact, Solver, Sphere, State, WallMotion};
use powderfmu::law::damping::NormalDamping;
use powderfmu::law::params::Effective;
use powderfmu::law::{AnyLaw, Branch, NormalLaw};
use powderfmu::scene::{ModelKind, Scene};
use powderfmu::theory::{energy_balance, restitution, time_step};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// One simulated impact: what the errors are measured on.
#[derive(Debug, Clone, Copy)]
struct Outcome {
    rebound: f64,
    max_overlap: f64,
    plastic_overlap: f64,
    separated: bool,
}

/// The scene of a case: 000 Table 5 (R = 2.45 um, p_y = 30 MPa) with the law's own parameters where
/// it needs them (as `tests/impact.rs`).
fn scene(model: ModelKind) -> Scene {
    let mut s = common::table5(model, 2.45e-6, 30e6);
    match model {
        ModelKind::Luding => s.laws.luding.luding_adhesion_stiffness = 20.0,
        ModelKind::Tomas => s.surface_energy = 0.05,
        _ => {}
    }
    s
}

struct Case {
    label: String,
    scene: Scene,
    law: AnyLaw,
    mass: f64,
}

impl Case {
    fn new(label: &str, scene: Scene) -> Case {
        let law = AnyLaw::from_scene(&scene).expect("scene");
        let mass = Effective::from_scene(&scene).expect("scene").mass;
        Case { label: label.into(), scene, law, mass }
    }

    /// The start: just before contact, so that every solver spends its cost on the contact (a long
    /// approach would cost Verlet steps and the others nothing); beyond the attraction tail for Tomas
    /// (99 a_F = 40 nm), so its approach does all its work.
    fn gap(&self) -> f64 {
        let r = self.scene.particle_radius;
        if self.scene.contact_model == ModelKind::Tomas {
            0.02 * r
        } else {
            1e-4 * r
        }
    }

    fn sphere(&self, solver: Solver, tolerance: f64, v: f64) -> Sphere {
        let contact = Contact::new(self.law.clone(), NormalDamping::from_scene(&self.scene, self.mass), 1e-3 * self.scene.particle_radius, v);
        Sphere::new(self.mass, 0.0, contact, solver, tolerance)
    }

    /// One impact at `v` integrated from 0 to `t_end` in a single communication step.
    fn run(&self, solver: Solver, tolerance: f64, v: f64, t_end: f64) -> Option<Outcome> {
        let mut sp = self.sphere(solver, tolerance, v);
        let wall = WallMotion { t0: 0.0, position: 0.0, velocity: 0.0 };
        let mut y = State::new(self.gap(), -v, 0.0);
        sp.accept(&wall, 0.0, &y);
        if let Err(e) = sp.advance(&wall, 0.0, t_end, &mut y) {
            eprintln!("work_precision: {} {solver:?} tolerance {tolerance:e} at {v} m/s: {e}", self.label);
            return None;
        }
        Some(Outcome {
            rebound: y.velocity,
            max_overlap: sp.contact.max_overlap,
            plastic_overlap: self.law.plastic_overlap(sp.contact.history()),
            separated: sp.contact.accepted.branch == Branch::Separated && y.velocity > 0.0,
        })
    }

    /// When the tight reference leaves the wall (or, if it sticks, ten loading times).
    fn end_time(&self, v: f64) -> f64 {
        let mut sp = self.sphere(Solver::Adaptive, 1e-12, v);
        let wall = WallMotion { t0: 0.0, position: 0.0, velocity: 0.0 };
        let mut y = State::new(self.gap(), -v, 0.0);
        sp.accept(&wall, 0.0, &y);
        let approach = self.gap() / v;
        let dt = approach / 50.0;
        let mut t = 0.0;
        while t < 2000.0 * approach {
            sp.advance(&wall, t, t + dt, &mut y).expect("reference run");
            t += dt;
            if y.velocity > 0.0 && sp.contact.accepted.branch == Branch::Separated {
                // A little free flight after separation, the same for every solver.
                return t + 10.0 * dt;
            }
        }
        approach + 10.0 * 2.0 * sp.contact.max_overlap.max(0.0) / v
    }
}

/// Median wall time of `f` in ns, from batches of at least 5 ms (at most 1 s in all).
fn median_ns(mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    f();
    let once = start.elapsed();
    let per_batch = ((Duration::from_millis(5).as_secs_f64() / once.as_secs_f64().max(1e-9)).ceil() as u32).max(1);
    let batches = if once > Duration::from_millis(200) { 1 } else { 7 };
    let mut times: Vec<f64> = (0..batches)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..per_batch {
                f();
            }
            t.elapsed().as_secs_f64() * 1e9 / f64::from(per_batch)
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn rel(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        a.abs()
    } else {
        (a - b).abs() / b.abs()
    }
}

const TOLERANCES: [f64; 8] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11];
const FRACTIONS: [f64; 10] = [0.3, 0.1, 0.03, 0.01, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5];

fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let figures = root.join("docs/figures");
    std::fs::create_dir_all(&figures).expect("docs/figures");
    let mut csv = String::from(
        "law,solver,setting,case,impact_velocity_m_s,ns_per_impact,rebound_velocity_m_s,rebound_rel_error,restitution_abs_error,max_overlap_rel_error,plastic_overlap_rel_error,reference\n",
    );
    let mut cases: Vec<Case> = ModelKind::ALL.iter().map(|&m| Case::new(m.name(), scene(m))).collect();
    let mut damped = scene(ModelKind::Nan);
    damped.restitution_coefficient = 0.5;
    cases.insert(1, Case::new("nan_damped_e0.5", damped));

    let started = Instant::now();
    for (i, case) in cases.iter().enumerate() {
        let r = case.scene.particle_radius;
        let v_stick = energy_balance::sticking_velocity(&case.law, case.mass, r, 1e-3, 100.0);
        let velocities: Vec<(&str, f64)> = match v_stick {
            Some(vs) => vec![("below", 0.5 * vs), ("near", 1.05 * vs), ("far", 20.0 * vs)],
            None => vec![("below", 0.1), ("near", 1.0), ("far", 10.0)],
        };
        let rayleigh =
            time_step::rayleigh_time_step(r, case.scene.particle_density, case.scene.particle_shear_modulus(), case.scene.particle_poisson_ratio);
        let undamped_linear = case.law.is_piecewise_linear() && case.scene.restitution_coefficient >= 1.0;
        for (name, v) in velocities {
            let t_end = case.end_time(v);
            let reference = if undamped_linear {
                let c = restitution::closed_form(&case.law, case.mass, v).expect("closed form");
                // The plastic overlap of the closed form's history: the law walked to alpha_max.
                // The plastic overlap after the impact: the law walked to alpha_max and back out of contact.
                let mut contact = Contact::new(case.law.clone(), NormalDamping::from_scene(&case.scene, case.mass), 1e-3 * r, v);
                contact.accept(-case.gap(), 1.0);
                contact.follow(c.max_overlap);
                contact.follow(-case.gap());
                Outcome {
                    rebound: c.rebound_velocity,
                    max_overlap: c.max_overlap,
                    plastic_overlap: case.law.plastic_overlap(contact.history()),
                    separated: !c.sticks,
                }
            } else {
                case.run(Solver::Adaptive, 1e-13, v, t_end).expect("reference")
            };
            let reference_name = if undamped_linear { "closed_form" } else { "adaptive_1e-13" };
            let mut runs: Vec<(&str, String, Solver, f64)> = Vec::new();
            if case.law.is_piecewise_linear() {
                runs.push(("exact", "-".into(), Solver::Exact, 0.0));
            }
            for tol in TOLERANCES {
                runs.push(("adaptive", format!("{tol:e}"), Solver::Adaptive, tol));
            }
            for fr in FRACTIONS {
                runs.push(("verlet", format!("{fr:e}"), Solver::Verlet { step: fr * rayleigh }, 0.0));
            }
            for (solver_name, setting, solver, tol) in runs {
                let Some(out) = case.run(solver, tol, v, t_end) else {
                    writeln!(csv, "{},{solver_name},{setting},{name},{v},,,,,,,{reference_name}", case.label).unwrap();
                    continue;
                };
                let ns = median_ns(|| {
                    black_box(case.run(solver, tol, black_box(v), t_end));
                });
                let (rebound_err, restitution_err) = if reference.separated {
                    (rel(out.rebound.max(0.0), reference.rebound), (out.rebound.max(0.0) - reference.rebound).abs() / v)
                } else {
                    // Sticks: the rebound is 0; a solver that lets the sphere go has the error of its speed.
                    (f64::NAN, if out.separated { out.rebound / v } else { 0.0 })
                };
                // After a rebound the history is final; a stuck sphere's history still moves (Luding).
                let plastic_err = if reference.separated && reference.plastic_overlap.abs() > 0.0 {
                    rel(out.plastic_overlap, reference.plastic_overlap)
                } else {
                    f64::NAN
                };
                writeln!(
                    csv,
                    "{},{solver_name},{setting},{name},{v},{ns:.1},{},{rebound_err:e},{restitution_err:e},{:e},{plastic_err:e},{reference_name}",
                    case.label,
                    out.rebound,
                    rel(out.max_overlap, reference.max_overlap)
                )
                .unwrap();
            }
        }
        eprintln!("work_precision: {}/{} {} done ({:.0} s elapsed)", i + 1, cases.len(), case.label, started.elapsed().as_secs_f64());
    }
    std::fs::write(figures.join("work_precision.csv"), csv).expect("write work_precision.csv");
    fidelity(&figures);
    eprintln!("work_precision: wrote docs/figures/work_precision.csv, fidelity.csv, fidelity_curves.csv in {:.0} s", started.elapsed().as_secs_f64());
}

/// 004 Table 4.1: restitution curves and sticking velocities of each law against Thornton-Ning's, and the
/// cost of one force evaluation.
fn fidelity(figures: &std::path::Path) {
    let laws = [
        ModelKind::ThorntonNing,
        ModelKind::Nan,
        ModelKind::Pasha,
        ModelKind::PashaSimplified,
        ModelKind::Luding,
        ModelKind::WaltonBraun,
        ModelKind::Linear,
    ];
    let velocities: Vec<f64> = (0..=40).map(|i| 0.1 * 10f64.powf(i as f64 / 20.0)).collect();
    let mut curves = String::from("law,impact_velocity_m_s,restitution\n");
    let mut summary = String::from("law,sticking_velocity_m_s,rms_restitution_difference_vs_thornton_ning,ns_per_force_evaluation\n");
    let mut tn_curve = Vec::new();
    for model in laws {
        let mut s = common::table4_1(model);
        if model == ModelKind::Luding {
            s.laws.luding.luding_adhesion_stiffness = 20.0;
        }
        let law = match AnyLaw::from_scene(&s) {
            Ok(l) => l,
            Err(e) => {
                eprintln!("fidelity: {} not built from Table 4.1: {e}", model.name());
                continue;
            }
        };
        let m = Effective::from_scene(&s).expect("scene").mass;
        let r = s.particle_radius;
        let curve: Vec<f64> = velocities
            .iter()
            .map(|&v| restitution::closed_form(&law, m, v).or_else(|| energy_balance::impact(&law, m, v, r).ok()).map_or(f64::NAN, |o| o.restitution))
            .collect();
        for (v, e) in velocities.iter().zip(&curve) {
            writeln!(curves, "{},{v},{e}", model.name()).unwrap();
        }
        if model == ModelKind::ThorntonNing {
            tn_curve = curve.clone();
        }
        let rms = (curve.iter().zip(&tn_curve).map(|(a, b)| (a - b).powi(2)).sum::<f64>() / curve.len() as f64).sqrt();
        let v_stick = energy_balance::sticking_velocity(&law, m, r, 1e-3, 100.0).map_or(String::from("none"), |v| format!("{v}"));
        // Force evaluations over a loading-unloading sweep, with the history accepted as it goes.
        let mut contact = Contact::new(law.clone(), NormalDamping::from_scene(&s, m), 1e-3 * r, 1.0);
        contact.accept(-1e-9, 1.0);
        contact.follow(0.3e-6);
        let h = *contact.history();
        let overlaps: Vec<f64> = (0..256).map(|i| -0.05e-6 + 0.35e-6 * i as f64 / 255.0).collect();
        let ns = median_ns(|| {
            for &a in &overlaps {
                black_box(law.evaluate(black_box(a), &h));
            }
        }) / overlaps.len() as f64;
        writeln!(summary, "{},{v_stick},{rms},{ns:.2}", model.name()).unwrap();
    }
    std::fs::write(figures.join("fidelity_curves.csv"), curves).expect("write fidelity_curves.csv");
    std::fs::write(figures.join("fidelity.csv"), summary).expect("write fidelity.csv");
}
