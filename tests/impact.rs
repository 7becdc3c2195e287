//! The sphere-wall dynamics of the ParticleWallImpact unit (`impact::Sphere`, Dormand-Prince steps that
//! land on branch switches) against the quasi-static energy balance of every law: an undamped impact must
//! give the same rebound speed and maximum overlap, and the contact work must close the energy balance.

mod common;
use common::*;
use powderfmu::impact::{Contact, Solver, Sphere, State, WallMotion};
use powderfmu::law::damping::NormalDamping;
use powderfmu::law::params::Effective;
use powderfmu::law::{AnyLaw, Branch};
use powderfmu::scene::{ModelKind, Scene};
use powderfmu::theory::{energy_balance, restitution};

/// The sphere of a scene, starting `gap` above a wall at rest, approaching at `v`.
fn sphere(s: &Scene, tolerance: f64) -> (Sphere, f64) {
    sphere_with(s, Solver::Adaptive, tolerance)
}

fn sphere_with(s: &Scene, solver: Solver, tolerance: f64) -> (Sphere, f64) {
    let law = AnyLaw::from_scene(s).unwrap();
    let eff = Effective::from_scene(s).unwrap();
    let contact = Contact::new(law, NormalDamping::from_scene(s, eff.mass), 1e-3 * s.particle_radius, 1.0);
    (Sphere::new(eff.mass, 0.0, contact, solver, tolerance), eff.mass)
}

/// Runs an impact at speed `v` until the sphere has left the wall; returns the final
/// state [z, v, W] and the largest overlap.
fn run(s: &Scene, v: f64, tolerance: f64) -> (State, f64, Sphere) {
    run_with(s, v, Solver::Adaptive, tolerance)
}

fn run_with(s: &Scene, v: f64, solver: Solver, tolerance: f64) -> (State, f64, Sphere) {
    let (mut sp, _) = sphere_with(s, solver, tolerance);
    let wall = WallMotion { t0: 0.0, position: 0.0, velocity: 0.0 };
    // Farther than any attraction tail (Tomas: 99 a_F = 40 nm), so the approach does all its work.
    let gap = 0.05 * s.particle_radius;
    let mut y = State::new(gap, -v, 0.0);
    sp.accept(&wall, 0.0, &y);
    let mut t = 0.0;
    let dt = 1e-9;
    for _ in 0..100_000 {
        sp.advance(&wall, t, t + dt, &mut y).unwrap();
        t += dt;
        // Left the wall: separated (beyond any adhesive neck or attraction tail) and moving away.
        if y.velocity > 0.0 && sp.contact.accepted.branch == Branch::Separated {
            break;
        }
    }
    let max = sp.contact.max_overlap;
    (y, max, sp)
}

fn scene(model: ModelKind) -> Scene {
    let mut s = table5(model, 2.45e-6, 30e6);
    match model {
        ModelKind::Luding => s.laws.luding.luding_adhesion_stiffness = 20.0,
        ModelKind::Tomas => s.surface_energy = 0.05,
        _ => {}
    }
    s
}

#[test]
fn every_law_rebounds_as_its_energy_balance_says() {
    for model in ModelKind::ALL {
        let s = scene(model);
        let law = AnyLaw::from_scene(&s).unwrap();
        let (_, m) = sphere(&s, 1e-10);
        let v = 5.0;
        let want = energy_balance::impact(&law, m, v, s.particle_radius).unwrap();
        let (y, max, sp) = run(&s, v, 1e-10);
        assert!(!want.sticks, "{model:?}");
        assert!(rel(y.velocity, want.rebound_velocity) < 1e-6, "{model:?}: rebound {} vs energy balance {}", y.velocity, want.rebound_velocity);
        assert!(rel(max, want.max_overlap) < 1e-6, "{model:?}: max overlap {max:e} vs {:e}", want.max_overlap);
        // The contact work is what the sphere lost.
        let lost = 0.5 * m * (v * v - y.velocity * y.velocity);
        let e_in = 0.5 * m * v * v;
        assert!((y.work - lost).abs() < 1e-8 * e_in, "{model:?}: work {:e} vs kinetic energy lost {lost:e}", y.work);
        assert!(sp.events >= 2, "{model:?}: contact and separation must be events");
    }
}

#[test]
fn exact_rebounds_as_the_closed_form_to_1e_12_for_every_piecewise_linear_law() {
    for model in ModelKind::ALL.into_iter().filter(|m| m.is_piecewise_linear()) {
        let s = scene(model);
        let law = AnyLaw::from_scene(&s).unwrap();
        let (_, m) = sphere(&s, 1e-10);
        for v in [3.0, 5.0, 20.0] {
            let want = restitution::closed_form(&law, m, v).unwrap();
            let (y, max, _sp) = run_with(&s, v, Solver::Exact, 0.0);
            assert!(
                rel(y.velocity, want.rebound_velocity) < 1e-12,
                "{model:?} at {v} m/s: rebound {} vs energy balance {}",
                y.velocity,
                want.rebound_velocity
            );
            assert!(rel(max, want.max_overlap) < 1e-12, "{model:?}: max overlap {max:e} vs {:e}", want.max_overlap);
            let lost = 0.5 * m * (v * v - y.velocity * y.velocity);
            assert!((y.work - lost).abs() < 1e-12 * 0.5 * m * v * v, "{model:?}: work {:e} vs {lost:e}", y.work);
        }
    }
}

#[test]
fn hertz_without_damping_is_perfectly_elastic_and_with_damping_restitutes_less() {
    let mut s = scene(ModelKind::Hertz);
    let (y, _, _) = run(&s, 2.0, 1e-10);
    assert!(rel(y.velocity, 2.0) < 1e-8, "{}", y.velocity);
    s.restitution_coefficient = 0.7;
    let (y, _, _) = run(&s, 2.0, 1e-10);
    assert!(y.velocity > 0.3 && y.velocity < 2.0 * 0.95, "{}", y.velocity);
}

#[test]
fn below_the_sticking_velocity_the_nan_sphere_stays_on_the_wall() {
    let s = scene(ModelKind::Nan);
    // 000 Table 6: V_ys = 1.86 m/s for this sphere.
    let (y, _, sp) = run(&s, 1.8, 1e-10);
    assert!(sp.contact.accepted.branch.in_contact(), "{:?}", sp.contact.accepted.branch);
    assert!(y.bottom < 1e-3 * s.particle_radius);
    let (y, _, _) = run(&s, 1.9, 1e-10);
    assert!(y.velocity > 0.0);
}

#[test]
fn a_tighter_tolerance_converges_to_the_energy_balance() {
    let s = scene(ModelKind::ThorntonNing);
    let law = AnyLaw::from_scene(&s).unwrap();
    let (_, m) = sphere(&s, 1e-6);
    let want = energy_balance::impact(&law, m, 4.0, s.particle_radius).unwrap().rebound_velocity;
    let err = |tol: f64| (run(&s, 4.0, tol).0[1] - want).abs() / want;
    let (loose, tight) = (err(1e-5), err(1e-11));
    assert!(tight < 1e-8, "{tight:e}");
    assert!(tight <= loose, "{tight:e} vs {loose:e}");
}

#[test]
fn accepting_the_same_point_twice_changes_nothing() {
    // A master may accept one state more than once (an event, then a completed step at the same time).
    let s = scene(ModelKind::Nan);
    let (mut sp, _) = sphere(&s, 1e-10);
    let c = &mut sp.contact;
    for alpha in [-1e-9, 0.0, 5e-9, 20e-9, 40e-9] {
        c.accept(alpha, 1.0);
    }
    assert_eq!(c.accepted.branch, Branch::Plastic);
    let (history, branch) = (*c.history(), c.accepted.branch);
    c.accept(40e-9, 1.0);
    assert_eq!((*c.history(), c.accepted.branch), (history, branch));
    assert_eq!(c.force(40e-9, 1.0).branch, Branch::Plastic, "plastic loading goes on at the accepted point");
    c.accept(40e-9, -1.0);
    assert_eq!(c.accepted.branch, Branch::Elastic, "unloading from the turning point");
    assert_eq!(*c.history(), history);
}

/// A contact of the default Nan scene with k_p < k_el, so that the plastic line differs from the elastic one.
fn nan_contact() -> (Contact, powderfmu::law::nan::Nan) {
    let mut s = scene(ModelKind::Nan);
    s.laws.stiffness.plastic_stiffness = Some(50.0);
    let (sp, _) = sphere(&s, 1e-10);
    let AnyLaw::Nan(law) = sp.contact.law.clone() else { unreachable!() };
    (sp.contact, law)
}

#[test]
fn trial_forces_stay_on_the_accepted_branch_and_continue_it() {
    let (mut c, law) = nan_contact();
    let p = law.p;
    // Free flight accepted: a trial state in the wall is still free flight (no jump to -8/9 f_ce).
    c.accept(-1e-9, 1.0);
    for alpha in [1e-20, 1e-12, 1e-9, 5e-8] {
        let f = c.force(alpha, 1.0);
        assert_eq!((f.total(), f.branch), (0.0, Branch::Separated), "alpha = {alpha:e}");
    }
    // The elastic line before yield goes on past alpha_y until yield is accepted.
    c.accept(0.5 * p.alpha_y, 1.0);
    assert_eq!(c.accepted.branch, Branch::Elastic);
    let (a1, a2) = (1.5 * p.alpha_y, 2.0 * p.alpha_y);
    let slope = (c.force(a2, 0.0).law - c.force(a1, 0.0).law) / (a2 - a1);
    assert!(rel(slope, p.k_el) < 1e-9, "{slope} vs k_el {}", p.k_el);
    // The law itself says plastic there: the DEM-style evaluation switches, the accepted branch does not.
    assert_eq!(c.law_force(a2, 0.0).branch, Branch::Plastic);
    // Yield accepted: plastic loading, and below the accepted point the plastic line goes on (until the
    // turning point is accepted, the unloading line does not start).
    c.accept(a1, 1.0);
    assert_eq!(c.accepted.branch, Branch::Plastic);
    let slope = (c.force(a1, 0.0).law - c.force(0.9 * a1, 0.0).law) / (0.1 * a1);
    assert!(rel(slope, p.k_p) < 1e-9, "{slope} vs k_p {}", p.k_p);
    // Continuous across the accepted point, both ways.
    let f_at = c.force(a1, 0.0).law;
    assert!(rel(c.force(a1 * (1.0 + 1e-12), 0.0).law, f_at) < 1e-9);
    assert!(rel(c.force(a1 * (1.0 - 1e-12), 0.0).law, f_at) < 1e-9);
}

#[test]
fn accepted_branches_follow_the_papers_inequalities_within_1e_14() {
    let (mut c, law) = nan_contact();
    let pts = law.points(law.p.alpha_y);
    // 000 Eq. 20 before any contact: not established below alpha_c0 = 0, established from it on.
    c.accept(-1e-9, 1.0);
    c.accept(-f64::MIN_POSITIVE, 1.0);
    assert_eq!(c.accepted.branch, Branch::Separated);
    c.accept(0.0, 1.0);
    assert!(c.accepted.branch.in_contact());
    // Unloading: adhesive on alpha_fp <= alpha <= alpha_cp, detached strictly below alpha_fp; 1e-14
    // inside the adhesive branch (some 50 ulps), moving out, the contact still holds.
    let above = |x: f64| x + 1e-14 * x.abs();
    let below = |x: f64| x - 1e-14 * x.abs();
    let walk = |c: &mut Contact, to: f64| {
        c.follow(to);
        c.accept(to, -1.0);
        c.accepted.branch
    };
    walk(&mut c, 0.5 * law.p.alpha_0);
    assert_eq!(walk(&mut c, above(pts.alpha_cp)), Branch::Elastic);
    assert_eq!(walk(&mut c, pts.alpha_cp), Branch::Adhesive, "alpha = alpha_cp is adhesive");
    assert_eq!(walk(&mut c, above(pts.alpha_fp)), Branch::Adhesive, "just above alpha_fp the contact holds");
    assert_eq!(walk(&mut c, below(pts.alpha_fp)), Branch::Separated, "below alpha_fp the contact detaches");
}

/// JKR under displacement control ends on a vertical tangent (000 App. B). Model Exchange's lead puts the
/// detachment indicator 1 % of the zone (pull-off to detachment overlap) above the end; `accept_crossing`
/// then crosses the rest in no time by its exact work. Checked against `JkrCurve::work`, the closed form.
#[test]
fn model_exchange_crosses_the_vertical_end_of_jkr_by_its_closed_form_work() {
    use powderfmu::impact::contact::VERTICAL_END_LEAD;
    use powderfmu::law::NormalLaw;
    let s = scene(ModelKind::Jkr);
    let (mut sp, mass) = sphere(&s, 1e-10);
    sp.contact.lead_vertical_ends = true;
    let AnyLaw::Jkr(jkr) = sp.contact.law.clone() else { panic!("a jkr scene") };
    let curve = jkr.curve;
    let (alpha_c, alpha_d) = (curve.pull_off_overlap(), curve.detach_overlap());
    let wall = WallMotion { t0: 0.0, position: 0.0, velocity: 0.0 };
    // Established and unloading on the adhesive branch, half-way between pull-off and detachment.
    sp.contact.accept(0.5 * curve.zero_overlap_radius().powi(2) / curve.radius, -1.0);
    sp.contact.accept(0.5 * (alpha_c + alpha_d), -1.0);
    assert_eq!(sp.contact.accepted.branch, Branch::Adhesive);
    let (end, lead) = sp.contact.vertical_end_ahead().expect("the lead is on above the vertical end");
    assert_eq!(end, alpha_d);
    assert!((lead / (VERTICAL_END_LEAD * (alpha_c - alpha_d)) - 1.0).abs() < 1e-12);
    // The lower indicator crosses zero at the lead, not at the end.
    let at = |alpha: f64| sp.contact.indicators(alpha, -1.0)[0];
    assert!(at(end + 1.01 * lead) > 0.0 && at(end + 0.99 * lead) < 0.0);

    // The state the event is located at: just inside the lead, leaving at 1 m/s.
    let alpha = end + 0.999_999_9 * lead;
    let mut y = State::new(-alpha, 1.0, 0.0);
    let (switched, crossed) = sp.accept_crossing(&wall, 0.0, &mut y);
    assert!(switched && crossed);
    assert!(!sp.contact.accepted.branch.in_contact());
    let work = curve.work(curve.contact_radius(alpha), curve.detach_radius());
    assert!((y.work / work - 1.0).abs() < 1e-10, "work {} against the closed form {work}", y.work);
    let v = (1.0 - 2.0 * work / mass).sqrt();
    assert!((y.velocity / v - 1.0).abs() < 1e-12, "leaves at {} m/s, energy says {v}", y.velocity);
    // The contact has ended and forgotten it was established: no force where it is, and no contact
    // until the surfaces touch again at alpha = 0.
    assert_eq!(sp.contact.force(alpha, -1.0).total(), 0.0);
    assert!(sp.contact.indicators(alpha, -1.0).iter().all(|&g| g > 0.0));
    assert_eq!(sp.contact.law.evaluate(alpha, sp.contact.history()).branch, Branch::Separated);
}

/// 000 Eq. 20 at its boundaries, to rounding: the unit takes a point within 8 machine epsilons (relative)
/// of a bound (the rounding of the bound's own formula, `BOUND_ULPS` in impact/contact.rs), moving out of
/// its branch, as on the bound and goes to the branch beyond; from 9 epsilons on, the paper's inequality
/// decides alone. At the equality itself with no motion the contact holds (alpha_fp <= alpha is
/// adhesive). docs/models.md, "Reading the seeds", says why the band is kept.
#[test]
fn eq_20_decides_from_nine_epsilons_beyond_a_bound_and_at_the_equality_without_motion() {
    let (mut c, law) = nan_contact();
    let pts = law.points(law.p.alpha_y);
    // k machine epsilons of |x| toward zero (above a negative bound).
    let toward_zero = |x: f64, k: f64| x - k * f64::EPSILON * x;
    let established = |c: &mut Contact| {
        c.accept(-1e-9, 1.0);
        c.accept(0.0, 1.0);
        c.follow(0.5 * law.p.alpha_0);
        c.accept(0.5 * law.p.alpha_0, -1.0);
    };
    let fp = pts.alpha_fp; // negative: "above" is toward zero, k ulps of smaller magnitude
    for (k, rate, holds) in [(9.0, -1.0, true), (50.0, -1.0, true), (0.0, 0.0, true), (7.0, -1.0, false), (0.0, -1.0, false), (-1.0, -1.0, false)] {
        established(&mut c);
        let at = toward_zero(fp, k);
        c.follow(at);
        c.accept(at, rate);
        assert_eq!(c.accepted.branch.in_contact(), holds, "{k} epsilons above alpha_fp, rate {rate}");
    }
    // Re-contact at alpha_c0 = 0 before yield: below it no contact, at it contact (Eq. 20: cs = 0 on
    // alpha < alpha_c0 strictly).
    established(&mut c);
    c.follow(2.0 * fp);
    c.accept(2.0 * fp, -1.0);
    assert!(!c.accepted.branch.in_contact());
    c.accept(-1e-300, 1.0);
    assert!(!c.accepted.branch.in_contact());
    c.accept(0.0, 1.0);
    assert!(c.accepted.branch.in_contact());
}
