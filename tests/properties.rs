//! Property tests for every law over random materials and random load / unload / reload / detach /
//! re-contact sequences: no NaN or infinity, no panic, force continuous except at the documented jumps
//! (which all sit at a boundary with the separated state), history monotone, and a history the law says
//! rests apart left as it is at every negative overlap.

use powderfmu::law::nan::{PullOffLaw, UnloadingStiffnessLaw};
use powderfmu::law::{AnyHistory, AnyLaw, Branch, Evaluation, NormalLaw};
use powderfmu::scene::{ModelKind, Scene};
use proptest::prelude::*;

#[derive(Debug, Clone)]
struct Case {
    model: ModelKind,
    radius: f64,
    youngs: f64,
    yield_ratio: f64,
    gamma: f64,
    kp_ratio: f64,
    variant: usize,
    targets: Vec<f64>,
}

fn case() -> impl Strategy<Value = Case> {
    (
        0usize..ModelKind::ALL.len(),
        -6.3f64..-4.3,                         // log10 radius [m]
        8.7f64..11.3,                          // log10 E [Pa]
        -3.0f64..-1.3,                         // log10 p_y / E*
        prop_oneof![Just(0.0), -3.0f64..-0.3], // log10 Gamma, or no adhesion
        0.05f64..1.0,                          // k_p / k_el
        0usize..4,                             // which options
        prop::collection::vec((any::<bool>(), -6.0f64..-1.5), 2..10),
    )
        .prop_map(|(m, lr, le, ly, lg, kp, variant, t)| Case {
            model: ModelKind::ALL[m],
            radius: 10f64.powf(lr),
            youngs: 10f64.powf(le),
            yield_ratio: 10f64.powf(ly),
            gamma: if lg == 0.0 { 0.0 } else { 10f64.powf(lg) },
            kp_ratio: kp,
            variant,
            targets: t.into_iter().map(|(neg, u)| if neg { -10f64.powf(u) } else { 10f64.powf(u) }).collect(),
        })
}

fn scene(c: &Case) -> Scene {
    let mut s = Scene::new(c.model, c.radius, 2000.0, c.youngs, 0.3);
    let p_y = c.youngs * c.yield_ratio;
    s.particle_yield_pressure = Some(p_y);
    s.surface_energy = c.gamma;
    let k_el = std::f64::consts::PI * c.radius * p_y;
    s.laws.stiffness.plastic_stiffness = Some(c.kp_ratio * k_el);
    s.laws.nan.unloading_stiffness_law =
        if c.variant.is_multiple_of(2) { UnloadingStiffnessLaw::Sqrt } else { UnloadingStiffnessLaw::SqrtPlusPlastic };
    s.laws.nan.pull_off_law = [PullOffLaw::Energy, PullOffLaw::Pasha, PullOffLaw::Curvature, PullOffLaw::WorkRatio][c.variant];
    s.laws.luding.luding_adhesion_stiffness = c.kp_ratio * k_el * 0.5;
    s.laws.pasha_simplified.pasha_pull_off_stiffness = c.kp_ratio * k_el * 0.1;
    s.laws.walton_braun.walton_braun_stiffening_slope = if c.variant == 3 { 1.0 / (c.radius * 1e-3 * k_el) } else { 0.0 };
    if c.variant >= 2 {
        s.laws.pasha.pasha_stiffness_law = powderfmu::law::pasha::PashaStiffnessLaw::LoadDependent;
        s.laws.pasha.pasha_max_elastic_stiffness = Some(20.0 * k_el);
    }
    s
}

/// The history measure that must not decrease while the contact lasts.
fn history_measure(h: &AnyHistory) -> f64 {
    match h {
        AnyHistory::Nan(h) => h.alpha_max,
        AnyHistory::Pasha(h) | AnyHistory::PashaSimplified(h) => h.alpha_max,
        AnyHistory::Luding(h) => h.delta_peak,
        AnyHistory::ThorntonNing(h) => h.alpha_max,
        AnyHistory::Tomas(h) => h.alpha_max,
        AnyHistory::WaltonBraun(h) => h.alpha_max,
        AnyHistory::Jkr(_) | AnyHistory::Hertz(_) | AnyHistory::JkrModified(_) | AnyHistory::Linear(_) => 0.0,
    }
}

/// Laws that forget their history when the surfaces separate (documented in their files).
fn forgets_on_separation(m: ModelKind) -> bool {
    matches!(m, ModelKind::Luding | ModelKind::Tomas)
}

/// Is the force jump-free on the monotone step from a (history h, evaluation ea) to b? Inside one branch
/// the force is that branch's formula, continuous by construction; so the step is bisected until every
/// branch switch is pinned to a width of 1e-14 relative, and the force must agree across each switch
/// within the slope times that width (plus a square-root allowance for the JKR curves, whose slope is
/// infinite at detachment). Switches into or out of separation are the documented jumps.
#[allow(clippy::too_many_arguments)] // one path step: law, history, the two points and their evaluations
fn continuous(
    law: &AnyLaw,
    h: AnyHistory,
    a: f64,
    ea: &Evaluation<AnyHistory>,
    b: f64,
    f_ref: f64,
    scale: f64,
    depth: u32,
) -> Result<Evaluation<AnyHistory>, String> {
    let eb = law.evaluate(b, &h);
    if !(eb.force.is_finite() && eb.stiffness.is_finite()) {
        return Err(format!("non-finite force {} or stiffness {} at {b:e} on {:?}", eb.force, eb.stiffness, eb.branch));
    }
    if eb.branch == ea.branch {
        return Ok(eb);
    }
    let d = (b - a).abs();
    if d <= 1e-14 * a.abs().max(b.abs()) || depth == 0 {
        if ea.branch == Branch::Separated || eb.branch == Branch::Separated {
            return Ok(eb);
        }
        let allowed = (ea.stiffness.abs() + eb.stiffness.abs()) * d * (1.0 + 1e-9) + 1e-9 * f_ref + 10.0 * f_ref * (d / scale).sqrt();
        if (eb.force - ea.force).abs() > allowed {
            return Err(format!("force jumps from {:e} at {a:e} ({:?}) to {:e} at {b:e} ({:?})", ea.force, ea.branch, eb.force, eb.branch));
        }
        return Ok(eb);
    }
    // The evaluation at m as reached from a carries the branch of the left half and the history to go on
    // with (re-evaluating m with that history would report the branch of the next step instead).
    let m = 0.5 * (a + b);
    let em = continuous(law, h, a, ea, m, f_ref, scale, depth - 1)?;
    continuous(law, em.history, m, &em, b, f_ref, scale, depth - 1)
}

fn walk(c: &Case) -> Result<(), String> {
    let s = scene(c);
    let Ok(law) = AnyLaw::from_scene(&s) else { return Ok(()) };
    let mut h = law.initial_history();
    let mut alpha = -c.radius * 1e-3;
    let mut e = law.evaluate(alpha, &h);
    h = e.history;
    // Force scale: the pull-off force, or the force of a fresh contact at 0.1 % of the radius.
    let fresh = law.evaluate(c.radius * 1e-3, &law.evaluate(0.0, &law.initial_history()).history).force.abs();
    let f_ref = law.pull_off_force(&h).max(fresh);
    for target in c.targets.iter().map(|t| t * c.radius) {
        let steps = 40;
        let start = alpha;
        for i in 1..=steps {
            let next = start + (target - start) * i as f64 / steps as f64;
            let before = history_measure(&h);
            let en = law.evaluate(next, &h);
            if !(en.force.is_finite() && en.stiffness.is_finite()) {
                return Err(format!("non-finite force {} or stiffness {} at {next:e} on {:?}", en.force, en.stiffness, en.branch));
            }
            // Also refuses NaN bounds.
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            let empty = !(en.lower <= en.upper);
            if empty {
                return Err(format!("branch interval [{}, {}] is empty at {next:e}", en.lower, en.upper));
            }
            continuous(&law, h, alpha, &e, next, f_ref, c.radius * 1e-3, 80)?;
            // A law that says it rests apart with this history (the bed then skips evaluating it) must
            // leave it separated and unchanged at every negative overlap.
            if law.rests_apart(&h) {
                for apart in [next.min(-f64::MIN_POSITIVE), -1e-12 * c.radius, -0.1 * c.radius] {
                    let ea = law.evaluate(apart, &h);
                    if ea.branch != Branch::Separated || ea.force != 0.0 || ea.history != h {
                        return Err(format!("rests apart, but at {apart:e} it is {:?} with {:e} N and {:?}", ea.branch, ea.force, ea.history));
                    }
                }
            }
            let after = history_measure(&en.history);
            let reset_allowed = forgets_on_separation(c.model) && en.branch == Branch::Separated;
            if after < before && !reset_allowed {
                return Err(format!("history went back from {before:e} to {after:e} at {next:e}"));
            }
            h = en.history;
            e = en;
            alpha = next;
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1500, ..ProptestConfig::default() })]

    #[test]
    fn every_law_survives_random_loading_paths(c in case()) {
        if let Err(msg) = walk(&c) {
            prop_assert!(false, "{:?}: {}", c.model, msg);
        }
    }
}

/// The same walk on each law explicitly, so a law that fails to build on the defaults shows up.
#[test]
fn every_law_builds_and_walks_a_fixed_path() {
    for model in ModelKind::ALL {
        let c = Case {
            model,
            radius: 2.45e-6,
            youngs: 1.2e9,
            yield_ratio: 0.03,
            gamma: 0.2,
            kp_ratio: 0.5,
            variant: 0,
            targets: vec![1e-2, -1e-3, 3e-3, -1e-2, 2e-2, 1e-4],
        };
        AnyLaw::from_scene(&scene(&c)).unwrap_or_else(|e| panic!("{model:?}: {e}"));
        walk(&c).unwrap_or_else(|e| panic!("{model:?}: {e}"));
    }
}

#[test]
fn random_cases_mostly_build_a_law() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let mut built = [0usize; 11];
    let mut total = [0usize; 11];
    for _ in 0..2000 {
        let c = case().new_tree(&mut runner).unwrap().current();
        let i = ModelKind::ALL.iter().position(|m| *m == c.model).unwrap();
        total[i] += 1;
        if AnyLaw::from_scene(&scene(&c)).is_ok() {
            built[i] += 1;
        }
    }
    for i in 0..11 {
        eprintln!("{:?}: {} of {}", ModelKind::ALL[i], built[i], total[i]);
        // At least two thirds of the random materials give a valid law, so the walk is not vacuous.
        assert!(built[i] * 3 >= total[i] * 2, "{:?}: only {} of {} built", ModelKind::ALL[i], built[i], total[i]);
    }
}
