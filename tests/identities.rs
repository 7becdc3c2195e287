//! Identities the seeds state: W_0 = W_JKR (000 Eq. 35), the work terms of 000 App. A as integrals of the
//! law, each law reducing to its special cases, the JKR relations of 000 App. B, 003 Eqs. 5-7, and the
//! closed-form restitution equal to the integral of each linear law.

mod common;
use common::*;
use powderfmu::law::jkr::{Jkr, JkrCurve};
use powderfmu::law::nan::Nan;
use powderfmu::law::nan::PullOffLaw;
use powderfmu::law::nan_params::NanParams;
use powderfmu::law::params::{f_y0, k_hjkr_at_zero, Effective};
use powderfmu::law::thornton_ning::ThorntonNing;
use powderfmu::law::tomas::Tomas;
use powderfmu::law::walton_braun::WaltonBraun;
use powderfmu::law::{hertz::Hertz, luding::Luding, AnyLaw, Branch, NormalLaw};
use powderfmu::numeric::tanh_sinh;
use powderfmu::scene::{ModelKind, Scene};
use powderfmu::theory::adhesion::{luding_adhesion_force, tomas_adhesion_force, tomas_adhesion_force_linear};
use powderfmu::theory::sticking::{
    cohesion_yield_number, critical_yield_pressure, jkr_sticking_velocity_closed, sticking_velocities, yield_velocity_closed,
};
use powderfmu::theory::{energy_balance, restitution, work::work_terms};
use std::f64::consts::PI;

fn nan(s: &Scene) -> (Nan, f64) {
    let eff = Effective::from_scene(s).unwrap();
    (Nan::new(NanParams::from_pair(&eff, &s.laws.stiffness, &s.laws.nan).unwrap()), eff.mass)
}

/// Integral of the law's force along a monotone path from `a` to `b`, committing history at each step.
fn path_work<L: NormalLaw>(law: &L, h: &mut L::History, a: f64, b: f64, steps: usize) -> f64 {
    let mut w = 0.0;
    for i in 0..steps {
        let x0 = a + (b - a) * i as f64 / steps as f64;
        let x1 = a + (b - a) * (i + 1) as f64 / steps as f64;
        let hh = *h;
        w += tanh_sinh(|x| law.evaluate(x, &hh).force, x0, x1);
        *h = law.evaluate(x1, h).history;
    }
    w
}

#[test]
fn w0_equals_w_jkr_with_the_exact_k_cl() {
    let (law, _) = nan(&table5(ModelKind::Nan, 2.45e-6, 30e6));
    let w = work_terms(&law, law.p.f_y);
    assert!(rel(w.w0, law.p.w_jkr) < 1e-12, "Eq. 35: {} vs {}", w.w0, law.p.w_jkr);
}

#[test]
fn appendix_a_work_terms_are_the_areas_under_the_law() {
    // A law with f_y > f_0 so every stage exists: p_y high enough (CY large).
    let (law, _) = nan(&table5(ModelKind::Nan, 2.45e-6, 90e6));
    let p = law.p;
    assert!(p.f_y > p.f_0);
    let alpha_max = p.alpha_y * 3.0;
    let f_max = p.f_y + p.k_p * (alpha_max - p.alpha_y);
    let w = work_terms(&law, f_max);
    let mut h = law.initial_history();
    h = law.evaluate(0.0, &h).history;
    let w1 = -path_work(&law, &mut h, 0.0, p.alpha_0, 8);
    let w2 = path_work(&law, &mut h, p.alpha_0, p.alpha_y, 8);
    let w34 = path_work(&law, &mut h, p.alpha_y, alpha_max, 8);
    let pts = law.points(alpha_max);
    let w4 = -path_work(&law, &mut h, alpha_max, pts.alpha_p, 8);
    let w5 = path_work(&law, &mut h, pts.alpha_p, pts.alpha_c0, 8);
    // Split at the kink alpha_cp: quadrature is exact on each straight piece.
    let w6 = path_work(&law, &mut h, pts.alpha_c0, pts.alpha_cp, 8) + path_work(&law, &mut h, pts.alpha_cp, pts.alpha_fp, 8);
    for (name, got, want) in [("W1", w1, w.w1), ("W2", w2, w.w2), ("W3+W4", w34, w.w3 + w.w4), ("W4", w4, w.w4), ("W5", w5, w.w5), ("W6", w6, w.w6)] {
        assert!(rel(got, want) < 1e-9, "{name}: integral {got:e} vs App. A {want:e}");
    }
    assert_eq!(law.evaluate(pts.alpha_fp - 1e-6 * pts.alpha_fp.abs().max(1e-12), &h).branch, Branch::Separated);
}

#[test]
fn nan_before_yield_is_linear_jkr_and_f_cp_is_f_ce() {
    let mut s = table5(ModelKind::Nan, 2.45e-6, 1e9); // p_y so high the contact stays elastic
    s.laws.nan.pull_off_law = PullOffLaw::Energy;
    let (law, _) = nan(&s);
    let p = law.p;
    let mut h = law.initial_history();
    // Contact forms at alpha = 0 with -8/9 f_ce (000 Eq. 4), follows k_el (alpha - alpha_0) (Eq. 17).
    let e = law.evaluate(0.0, &h);
    assert!(rel(-e.force, 8.0 / 9.0 * p.f_ce) < 1e-12);
    h = e.history;
    for x in [0.3, 1.0, 2.0] {
        let a = x * p.alpha_0;
        assert!((law.evaluate(a, &h).force - p.k_el * (a - p.alpha_0)).abs() < 1e-12 * p.f_ce);
    }
    // Pull-off at alpha_ce with -f_ce (Eq. 8), break at alpha_fe with -5/9 f_ce (Eq. 9).
    let a_ce = p.alpha_0 - p.f_ce / p.k_el;
    assert!(rel(-law.evaluate(a_ce, &h).force, p.f_ce) < 1e-12);
    let a_fe = a_ce - 4.0 / 9.0 * p.f_ce / p.k_cl;
    assert!(rel(-law.evaluate(a_fe, &h).force, 5.0 / 9.0 * p.f_ce) < 1e-12);
    assert_eq!(law.evaluate(a_fe - 1e-12 * p.alpha_0.abs(), &h).force, 0.0);
    // Eq. 59 with alpha_p = alpha_0, k_e = k_el gives f_cp = f_ce; all four methods agree at yield.
    for method in [PullOffLaw::Energy, PullOffLaw::Curvature, PullOffLaw::WorkRatio] {
        let mut p2 = p;
        p2.pull_off_law = method;
        assert!(rel(p2.f_cp(p.k_el, p.alpha_0, p.alpha_y), p.f_ce) < 1e-12, "{method:?}");
    }
}

#[test]
fn nan_pull_off_force_grows_with_plastic_deformation_for_59_64_67() {
    for method in [PullOffLaw::Energy, PullOffLaw::Curvature, PullOffLaw::WorkRatio] {
        let mut s = table5(ModelKind::Nan, 2.45e-6, 30e6);
        s.laws.nan.pull_off_law = method;
        let (law, _) = nan(&s);
        let mut last = law.p.f_ce;
        for k in 1..6 {
            let f = law.points(law.p.alpha_y * (1.0 + k as f64)).f_cp;
            assert!(f > last, "{method:?} f_cp must grow with alpha_max");
            last = f;
        }
    }
}

#[test]
fn jkr_curve_obeys_appendix_b() {
    let (r, e, g) = (2.45e-6, 1.3e9, 0.2);
    let c = JkrCurve::new(r, e, g);
    let f_c = c.pull_off_force();
    // B5-B6: at alpha = 0, a^3 = 2 pi Gamma R^2 / E* and f = -8/9 f_c.
    let a0 = c.contact_radius(0.0);
    assert!(rel(a0.powi(3), 2.0 * PI * g * r * r / e) < 1e-12);
    assert!(rel(-c.force(a0), 8.0 / 9.0 * f_c) < 1e-12);
    // B11: the zero-force overlap alpha_0 = (3/4)^(1/3) (pi^2 R Gamma^2 / E*^2)^(1/3).
    let alpha_zero = (0.75f64).cbrt() * (PI * PI * r * g * g / (e * e)).cbrt();
    let a_zero = c.contact_radius(alpha_zero);
    assert!(c.force(a_zero).abs() < 1e-10 * f_c);
    // B13: at alpha_0 the JKR stiffness is 3 sqrt(3)/5 = 1.04 times Hertz's.
    let k_ratio = c.stiffness(a_zero) / (2.0 * e * (r * alpha_zero).sqrt());
    assert!(rel(k_ratio, 3.0 * 3f64.sqrt() / 5.0) < 1e-10);
    // B7: the stiffness at alpha = 0.
    assert!(rel(c.stiffness(a0), k_hjkr_at_zero(g, e, r)) < 1e-10);
    // Pull-off -f_c at a_c, detachment at -5/9 f_c (004 Sec. 3.4.3.1).
    assert!(rel(-c.force(c.pull_off_radius()), f_c) < 1e-12);
    assert!(rel(-c.force(c.detach_radius()), 5.0 / 9.0 * f_c) < 1e-12);
    // The contact radius inverts the overlap across the whole stable branch.
    for alpha in [c.detach_overlap() * 0.999, -1e-9, 0.0, 1e-9, 1e-7, 1e-5] {
        let a = c.contact_radius(alpha);
        assert!((c.overlap(a) - alpha).abs() < 1e-12 * alpha.abs().max(1e-9), "alpha {alpha}");
        // The DEM bed's warm start (Newton from the radius one step earlier, 1 % away on either side,
        // or from nothing) finds the same radius.
        for guess in [0.0, 0.99 * a, 1.01 * a] {
            let b = c.contact_radius_from(alpha, guess);
            assert!(rel(b, a) < 1e-13, "alpha {alpha}, guess {guess}: {b} vs {a}");
        }
    }
}

#[test]
fn jkr_without_adhesion_is_hertz_and_its_sticking_velocity_is_eq_73() {
    let hz = Hertz::new(2e-6, 5e9);
    let jkr = Jkr::new(2e-6, 5e9, 0.0);
    let h = jkr.evaluate(0.0, &jkr.initial_history()).history;
    for a in [1e-10, 1e-9, 1e-8] {
        assert!(rel(jkr.evaluate(a, &h).force, hz.evaluate(a, &()).force) < 1e-12);
    }
    let s = table5(ModelKind::Jkr, 2.45e-6, 30e6);
    let eff = Effective::from_scene(&s).unwrap();
    let law = AnyLaw::from_scene(&s).unwrap();
    let v_s = energy_balance::sticking_velocity(&law, eff.mass, eff.radius, 0.05, 5.0).unwrap();
    let closed = jkr_sticking_velocity_closed(0.24, 2.45e-6, 1350.0, eff.youngs_modulus);
    // Eq. 37's 7.09 and Eq. 73's 1.84 are rounded constants.
    assert!(rel(v_s, closed) < 0.01, "JKR sticking {v_s} vs Eq. 73 {closed}");
}

#[test]
fn closed_forms_73_74_80_81_agree_with_the_definitions() {
    let s = table5(ModelKind::Nan, 2.45e-6, 30e6);
    let (law, m) = nan(&s);
    let v = sticking_velocities(&law, m);
    let e = law.p.youngs_modulus;
    assert!(rel(v.jkr_sticking_velocity, jkr_sticking_velocity_closed(0.24, 2.45e-6, 1350.0, e)) < 0.01);
    assert!(rel(v.yield_velocity, yield_velocity_closed(e, 1350.0, 30e6)) < 1e-12);
    // Eq. 80: at the critical p_y, f_y = f_0.
    let p_c = critical_yield_pressure(0.24, e, 2.45e-6);
    let (law_c, _) = nan(&table5(ModelKind::Nan, 2.45e-6, p_c));
    assert!(rel(law_c.p.f_y, law_c.p.f_0) < 1e-12);
    // Eq. 81: f_y0 / f_ce is 1.1 CY.
    let cy = cohesion_yield_number(30e6, 2.45e-6, e, 0.24);
    assert!(rel(f_y0(2.45e-6, e, 30e6) / law.p.f_ce, 1.1 * cy) < 0.01);
    // 000 Sec. 5: p_y = 0.5 MPa, particle-particle R* = R/2 with Table 7's mean R = 0.25 mm, E = 63 MPa
    // (nu 0.2): CY = 4.2 for Gamma = 3.5 mJ/m^2 and 0.5 for 27 mJ/m^2.
    for (gamma, want) in [(3.5e-3, 4.2), (27e-3, 0.5)] {
        let e_star = 1.0 / (2.0 * (1.0 - 0.04) / 63e6);
        let cy = cohesion_yield_number(0.5e6, 0.125e-3, e_star, gamma);
        assert!(rel(cy, want) < 0.1, "Gamma {gamma}: CY {cy} vs {want}");
    }
}

#[test]
fn thornton_ning_reduces_to_jkr_before_yield_and_to_thornton_without_adhesion() {
    let tn = ThorntonNing::new(2.45e-6, 1.3e9, 0.2, 35.3e6);
    let jkr = Jkr::new(2.45e-6, 1.3e9, 0.2);
    let (mut ht, mut hj) = (tn.initial_history(), jkr.initial_history());
    for k in 0..50 {
        let a = tn.alpha_y * k as f64 / 50.0;
        let (et, ej) = (tn.evaluate(a, &ht), jkr.evaluate(a, &hj));
        assert!((et.force - ej.force).abs() < 1e-12 * tn.f_y.abs().max(1e-9));
        ht = et.history;
        hj = ej.history;
    }
    // Without adhesion: Thornton's model, F = F_y + pi R p_y (alpha - alpha_y) (004 Eq. 3.28) with
    // F_y, alpha_y of Eqs. 3.27, 3.29, and the unloading radius of Eq. 3.30.
    let t = ThorntonNing::new(2.45e-6, 1.3e9, 0.0, 35.3e6);
    let r = 2.45e-6;
    assert!(rel(t.f_y, PI.powi(3) * r * r * 35.3e6f64.powi(3) / (6.0 * 1.3e9f64.powi(2))) < 1e-10);
    assert!(rel(t.alpha_y, PI * PI * r * 35.3e6f64.powi(2) / (4.0 * 1.3e9f64.powi(2))) < 1e-10);
    let am = 5.0 * t.alpha_y;
    let (f, _) = t.plastic_force(am);
    assert!(rel(f, t.f_y + PI * r * 35.3e6 * (am - t.alpha_y)) < 1e-12);
    let (r_p, alpha_p) = t.unloading_curve(am);
    let r_p_330 = 4.0 * 1.3e9 / (3.0 * f) * ((2.0 * f + t.f_y) / (2.0 * PI * 35.3e6)).powf(1.5);
    assert!(rel(r_p, r_p_330) < 0.05, "Eq. 3.30 {r_p_330} vs {r_p}");
    // Eq. 3.32: alpha_p = alpha_max (1 - R*/R_p*) for the Hertz unloading curve (Eq. 3.31).
    assert!(rel(alpha_p, am * (1.0 - r / r_p)) < 1e-9);
}

#[test]
fn thornton_ning_pull_off_grows_with_plastic_loading_and_force_is_continuous_at_the_peak() {
    let tn = ThorntonNing::new(2.45e-6, 1.3e9, 0.2, 35.3e6);
    let mut h = tn.initial_history();
    let mut last_fcp = tn.pull_off_force(&h);
    for k in 1..30 {
        let a = tn.alpha_y * (1.0 + 0.5 * k as f64);
        let e = tn.evaluate(a, &h);
        h = e.history;
        // Unloading curve passes through the peak (Eq. 3.58 built so).
        let back = tn.evaluate(a * (1.0 - 1e-12), &h);
        assert!(rel(back.force, e.force) < 1e-6, "{} vs {}", back.force, e.force);
        let fcp = tn.pull_off_force(&h);
        assert!(fcp > last_fcp);
        last_fcp = fcp;
    }
}

#[test]
fn tomas_point_a_is_the_fixed_point_of_003_eq_5_and_eq_6_overestimates_it() {
    // 003 Sec. 3.3, limestone: p_f = 350 MPa, kappa = 0.223, kappa_p = 0.152, E*_Tomas = 150 GPa, d50 = 1.2 um.
    let (p_f, kappa_p) = (350e6, 0.152);
    let kappa_a = kappa_p + kappa_p / 0.223;
    let r12 = 0.6e-6;
    let e_tomas = 150e9;
    let f0 = 5e-9;
    let law = Tomas::new(r12, e_tomas / 2.0, p_f, kappa_a, kappa_p, f0, 4e-10);
    assert!(rel(law.kappa, 0.223) < 1e-12);
    for f_n in [20e-9, 100e-9, 500e-9] {
        let alpha_max = (f_n + f0) / law.k1;
        let mut h = law.initial_history();
        h = law.evaluate(alpha_max, &h).history;
        let from_law = law.pull_off_force(&h);
        let eq5 = tomas_adhesion_force(f_n, f0, 0.223, kappa_p, p_f, r12, e_tomas).unwrap();
        assert!(rel(from_law, eq5) < 1e-9, "f_N {f_n}: law {from_law} vs Eq. 5 {eq5}");
        // 003: the linearised Eq. 6 gives considerably larger adhesion forces.
        assert!(tomas_adhesion_force_linear(f_n, f0, 0.223) > eq5);
    }
}

#[test]
fn luding_pull_off_after_loading_is_003_eq_7() {
    let law = Luding::new(1e3, 5e3, 2e3, 1e-7, 0.05, 1e-5);
    for f_n in [1e-6, 5e-6, 2e-5] {
        let alpha_max = (f_n + law.f0) / law.k1;
        let h = law.evaluate(alpha_max, &law.initial_history()).history;
        let want = luding_adhesion_force(f_n, law.f0, law.k1, law.k2(alpha_max), law.kc);
        assert!(rel(law.pull_off_force(&h), want) < 1e-12);
        // And the force along unloading really reaches it.
        let a_c = law.k2(alpha_max) * h.delta_0 / (law.k2(alpha_max) + law.kc);
        assert!(rel(-law.evaluate(a_c, &h).force, want) < 1e-9);
    }
}

#[test]
fn closed_form_restitution_equals_the_integral_of_each_linear_law() {
    let v_list = [0.3, 1.0, 2.5, 7.0, 40.0];
    let s = table5(ModelKind::Nan, 2.45e-6, 30e6);
    let (nan_law, m) = nan(&s);
    for v in v_list {
        let a = restitution::nan(&nan_law, m, v);
        let b = energy_balance::impact(&nan_law, m, v, 2.45e-6).unwrap();
        assert_eq!(a.sticks, b.sticks, "nan {v}");
        assert!((a.rebound_velocity - b.rebound_velocity).abs() < 1e-8 * v, "nan {v}: {} vs {}", a.rebound_velocity, b.rebound_velocity);
        assert!(rel(a.max_overlap, b.max_overlap) < 1e-8);
    }
    let s = table4_2(ModelKind::Pasha);
    let eff = Effective::from_scene(&s).unwrap();
    let AnyLaw::Pasha(p) = AnyLaw::from_scene(&s).unwrap() else { unreachable!() };
    let AnyLaw::PashaSimplified(ps) = AnyLaw::from_scene(&Scene { contact_model: ModelKind::PashaSimplified, ..s.clone() }).unwrap() else {
        unreachable!()
    };
    for v in v_list.iter().chain([12.0, 100.0].iter()) {
        let v = *v;
        for (name, a, b) in [
            ("pasha", restitution::pasha(&p, eff.mass, v), energy_balance::impact(&p, eff.mass, v, eff.radius).unwrap()),
            ("pasha_simplified", restitution::pasha_simplified(&ps, eff.mass, v), energy_balance::impact(&ps, eff.mass, v, eff.radius).unwrap()),
        ] {
            assert_eq!(a.sticks, b.sticks, "{name} {v}");
            assert!((a.rebound_velocity - b.rebound_velocity).abs() < 1e-8 * v, "{name} {v}: {} vs {}", a.rebound_velocity, b.rebound_velocity);
        }
    }
    let wb = WaltonBraun { k_p: 200.0, k_e: 1800.0, slope: 0.0 };
    for v in v_list {
        let a = restitution::walton_braun(&wb, 1e-13, v);
        let b = energy_balance::impact(&wb, 1e-13, v, 1e-6).unwrap();
        assert!(rel(a.restitution, (200.0f64 / 1800.0).sqrt()) < 1e-12, "004 Sec. 3.4.2.3: e = sqrt(k_p/k_e)");
        assert!(rel(b.restitution, a.restitution) < 1e-9);
    }
}

#[test]
fn thornton_ning_plastic_stiffness_is_eq_3_56_and_the_closed_form_integrates_it() {
    let (r, e, g, p_y) = (2.45e-6, 1.3e9, 0.2, 35.3e6);
    let tn = ThorntonNing::new(r, e, g, p_y);
    let a_c = (3.0 * r * 1.5 * PI * g * r / (4.0 * e)).cbrt(); // 004 Eq. 3.57
    for x in [1.01, 1.5, 3.0, 10.0, 40.0] {
        let alpha = tn.alpha_y * x;
        let a = tn.curve.contact_radius(alpha);
        let s = (a_c / a).powf(1.5);
        let k_356 = (3.0 * PI * r * p_y - 2.0 * e * tn.a_y * s) / (3.0 - s);
        let (_, k) = tn.plastic_force(alpha);
        assert!(rel(k, k_356) < 1e-9, "x {x}: {k} vs Eq. 3.56 {k_356}");
        // The closed-form force is the integral of that stiffness from the yield point.
        let integral = tn.f_y + tanh_sinh(|y| tn.plastic_force(y).1, tn.alpha_y, alpha);
        assert!(rel(tn.plastic_force(alpha).0, integral) < 1e-10);
    }
}

#[test]
fn thornton_ning_that_yields_on_formation_starts_at_minus_8_9_f_c() {
    // Adhesion-induced yield: a_y below the formation radius a_0, alpha_y < 0.
    let tn = ThorntonNing::new(1e-6, 1e9, 0.5, 0.1e6);
    assert!(tn.alpha_y < 0.0);
    let f_c = tn.curve.pull_off_force();
    let h = tn.initial_history();
    let first = tn.evaluate(1e-15, &h);
    assert_eq!(first.branch, Branch::Plastic);
    assert!(rel(-first.force, 8.0 / 9.0 * f_c) < 1e-6, "{} vs {}", -first.force, 8.0 / 9.0 * f_c);
    // And its plastic stiffness is still Eq. 3.56 integrated: the closed form is its integral from 0.
    let alpha = 1e-8;
    let integral = -8.0 / 9.0 * f_c + tanh_sinh(|y| tn.plastic_force(y).1, 0.0, alpha);
    assert!(rel(tn.plastic_force(alpha).0, integral) < 1e-9);
}

#[test]
fn jkr_curves_damp_with_2_e_a_and_give_mindlin_their_contact_radius() {
    let jkr = Jkr::new(2.45e-6, 1.3e9, 0.2);
    let h = jkr.evaluate(0.0, &jkr.initial_history()).history;
    let alpha_f = jkr.curve.detach_overlap();
    let a_f = jkr.contact_radius(alpha_f, &h).unwrap();
    assert!(rel(a_f, jkr.curve.detach_radius()) < 1e-9);
    // At detachment the branch slope is capped huge; the damping stiffness stays the Hertz 2 E* a.
    let e = jkr.evaluate(alpha_f, &h);
    assert!(e.stiffness.abs() > 1e3 * 2.0 * 1.3e9 * a_f);
    assert!(rel(jkr.damping_stiffness(alpha_f, &h, e.stiffness), 2.0 * 1.3e9 * a_f) < 1e-12);
    let tn = ThorntonNing::new(2.45e-6, 1.3e9, 0.2, 35.3e6);
    let ht = tn.evaluate(0.0, &tn.initial_history()).history;
    assert!(rel(tn.contact_radius(0.0, &ht).unwrap(), jkr.contact_radius(0.0, &h).unwrap()) < 1e-12);
}
