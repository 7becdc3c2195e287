//! The oblique impact (`impact::oblique`) on Chung and Ooi's Test 4 (Granular Matter 13 (2011) 643-656):
//! an aluminium oxide sphere (R = 2.5 mm, E = 380 GPa, nu = 0.23, rho = 4000 kg/m^3, mu = 0.092) hits a
//! rigid plane at 3.9 m/s and incident angles 5-85 deg, elastic (Hertz-Mindlin, no damping). Where the
//! contact slides throughout, Maw, Barber and Fawcett's solution is closed: Delta v_t = mu (1 + e_n) v_n
//! and omega R = 5/2 Delta v_t; it slides throughout from the normalised incident angle
//! Psi_1 = 2 (1 - nu) / (mu (2 - nu)) tan(theta) >= 4 chi - 1, chi = (1 - nu) / (2 - nu) (1 + 1/K^2),
//! K^2 = 2/5 (28.3 deg here). Below that the micro-slip regime has no closed form: the peer comparison
//! with LAMMPS covers it (tests/python/test_peers.py).

use powderfmu::impact::oblique::{impact, ImpactOptions, Lever, ObliqueSolver};
use powderfmu::scene::{ModelKind, Scene};

const SPEED: f64 = 3.9;
const MU: f64 = 0.092;
const NU: f64 = 0.23;
const RADIUS: f64 = 2.5e-3;

fn alumina() -> Scene {
    let mut s = Scene::new(ModelKind::Hertz, RADIUS, 4000.0, 3.8e11, NU);
    s.friction_coefficient = MU;
    s.restitution_coefficient = 1.0;
    s
}

/// Psi_1 of an incident angle [deg].
fn psi(theta_deg: f64) -> f64 {
    2.0 * (1.0 - NU) / (MU * (2.0 - NU)) * theta_deg.to_radians().tan()
}

/// 4 chi - 1: where gross sliding begins.
fn gross_sliding_from() -> f64 {
    4.0 * (1.0 - NU) / (2.0 - NU) * (1.0 + 1.0 / 0.4) - 1.0
}

#[test]
fn chung_ooi_test_4_slides_throughout_where_maw_barber_fawcett_say_and_meets_their_closed_form_there() {
    let scene = alumina();
    let mut sliding_seen = 0;
    for k in 1..=17 {
        let theta = 5.0 * k as f64;
        let (v_n, v_t) = (SPEED * theta.to_radians().cos(), SPEED * theta.to_radians().sin());
        let o = impact(&scene, v_n, v_t, &ImpactOptions::default()).unwrap();
        let e_n = o.normal_velocity_out / v_n;
        assert!((e_n - 1.0).abs() < 1e-5, "{theta} deg: elastic, e_n = {e_n}");
        // Energy: the contact's work is the kinetic energy lost (translation and spin), to the scheme.
        let scale = 0.5 * 4.0 / 3.0 * std::f64::consts::PI * RADIUS.powi(3) * 4000.0 * SPEED * SPEED;
        assert!((o.dissipated_energy - o.kinetic_energy_lost).abs() < 1e-3 * o.kinetic_energy_lost.abs() + 1e-5 * scale, "{theta} deg: {o:?}");
        let psi1 = psi(theta);
        // Within 1.5 deg of the transition the first and last steps of the contact decide; stay clear.
        if (theta - 28.3).abs() > 1.5 {
            assert_eq!(o.slid_throughout, psi1 >= gross_sliding_from(), "{theta} deg: Psi_1 = {psi1}");
        }
        if o.slid_throughout {
            sliding_seen += 1;
            let dv = v_t - o.tangential_velocity_out;
            let closed = MU * (1.0 + e_n) * v_n;
            assert!((dv / closed - 1.0).abs() < 1e-4, "{theta} deg: Delta v_t {dv} against {closed}");
            assert!((o.tangential_restitution() - (1.0 - MU * (1.0 + e_n) / theta.to_radians().tan())).abs() < 1e-4);
            // The spin: 5/2 Delta v_t / R, with the lever R - alpha/2 (at most alpha_max / 2R below).
            let ratio = o.angular_velocity_out * RADIUS / (2.5 * dv);
            assert!(ratio <= 1.0 + 1e-9 && ratio >= 1.0 - o.max_overlap / (2.0 * RADIUS), "{theta} deg: omega R / (5/2 Delta v_t) = {ratio}");
        }
    }
    assert_eq!(sliding_seen, 12, "30-85 deg slide throughout");
}

#[test]
fn the_lever_at_the_radius_makes_omega_r_exactly_five_halves_of_delta_v_t_in_gross_sliding() {
    let scene = alumina();
    let options = ImpactOptions { lever: Lever::Radius, ..ImpactOptions::default() };
    for theta in [40.0f64, 70.0] {
        let (v_n, v_t) = (SPEED * theta.to_radians().cos(), SPEED * theta.to_radians().sin());
        let o = impact(&scene, v_n, v_t, &options).unwrap();
        let dv = v_t - o.tangential_velocity_out;
        assert!((o.angular_velocity_out * RADIUS / (2.5 * dv) - 1.0).abs() < 1e-12, "{theta} deg");
    }
}

#[test]
fn a_frictionless_wall_and_normal_incidence_give_no_spin() {
    let mut scene = alumina();
    let o = impact(&scene, SPEED, 0.0, &ImpactOptions::default()).unwrap();
    assert_eq!((o.tangential_velocity_out, o.angular_velocity_out), (0.0, 0.0));
    scene.friction_coefficient = 0.0;
    let o = impact(&scene, 2.0, 3.0, &ImpactOptions::default()).unwrap();
    assert_eq!((o.tangential_velocity_out, o.angular_velocity_out), (3.0, 0.0));
}

#[test]
fn a_sphere_rolling_in_without_slip_keeps_rolling() {
    // v_t = R omega: no slip at the contact point, no tangential force (to the lever's alpha/2R).
    let scene = alumina();
    let options = ImpactOptions { angular_velocity: 1.0 / RADIUS, lever: Lever::Radius, ..ImpactOptions::default() };
    let o = impact(&scene, 1.0, 1.0, &options).unwrap();
    assert_eq!(o.tangential_velocity_out, 1.0);
    assert_eq!(o.angular_velocity_out, 1.0 / RADIUS);
}

#[test]
fn rolling_friction_slows_the_spin_and_never_reverses_it() {
    let scene = alumina();
    let free = impact(&scene, 1.0, 1.0, &ImpactOptions { angular_velocity: 1.0 / RADIUS, ..ImpactOptions::default() }).unwrap();
    let braked =
        impact(&scene, 1.0, 1.0, &ImpactOptions { angular_velocity: 1.0 / RADIUS, rolling_friction: 0.1, ..ImpactOptions::default() }).unwrap();
    assert!(braked.angular_velocity_out < free.angular_velocity_out && braked.angular_velocity_out > 0.0, "{free:?} {braked:?}");
    assert!(braked.dissipated_energy > free.dissipated_energy);
    // A strong brake stops a slow spin within the contact and leaves it at 0.
    let stopped = impact(&scene, 1.0, 0.0, &ImpactOptions { angular_velocity: 1.0, rolling_friction: 10.0, ..ImpactOptions::default() }).unwrap();
    assert!(stopped.angular_velocity_out.abs() < 1.0, "{stopped:?}");
}

#[test]
fn bad_options_are_refused_by_name() {
    let scene = alumina();
    let e = impact(&scene, -1.0, 0.0, &ImpactOptions::default()).unwrap_err().to_string();
    assert!(e.contains("normal_velocity") && e.contains("(0, inf)"), "{e}");
    let e = impact(&scene, 1.0, 0.0, &ImpactOptions { rayleigh_fraction: 2.0, ..ImpactOptions::default() }).unwrap_err().to_string();
    assert!(e.contains("rayleigh_fraction") && e.contains("(0, 1]"), "{e}");
}

#[test]
fn the_adaptive_integrator_lands_on_the_stick_slip_switches_and_converges() {
    // Dormand-Prince with the stick-slip switches located, against Verlet at 2e-4 of the Rayleigh step
    // (its own error there about 3e-5, docs/benchmarks.md), over the micro-slip regime and into gross
    // sliding; and its own convergence with the tolerance at 15 deg, where three switches follow.
    let scene = alumina();
    let adaptive = |theta: f64, tol: f64| {
        let (v_n, v_t) = (SPEED * theta.to_radians().cos(), SPEED * theta.to_radians().sin());
        impact(&scene, v_n, v_t, &ImpactOptions { solver: ObliqueSolver::Adaptive(tol), rayleigh_fraction: 0.5, ..ImpactOptions::default() }).unwrap()
    };
    for theta in [3.0f64, 10.0, 15.0, 20.0, 25.0, 45.0] {
        let (v_n, v_t) = (SPEED * theta.to_radians().cos(), SPEED * theta.to_radians().sin());
        let fine = impact(&scene, v_n, v_t, &ImpactOptions { rayleigh_fraction: 2e-4, ..ImpactOptions::default() }).unwrap();
        let a = adaptive(theta, 1e-10);
        assert!((a.tangential_restitution() - fine.tangential_restitution()).abs() < 1e-4, "{theta} deg: {a:?} against {fine:?}");
        assert!((a.angular_velocity_out - fine.angular_velocity_out).abs() < 1e-4 * 632.0, "{theta} deg: spin");
        assert!((a.dissipated_energy - a.kinetic_energy_lost).abs() < 1e-6 * a.kinetic_energy_lost, "{theta} deg: energy");
    }
    let reference = adaptive(15.0, 1e-12).tangential_velocity_out;
    let errors: Vec<f64> = [1e-6, 1e-8, 1e-10].iter().map(|&tol| (adaptive(15.0, tol).tangential_velocity_out - reference).abs()).collect();
    assert!(errors[0] < 1e-5 && errors[1] < 1e-7 && errors[2] < 1e-9, "errors at tolerances 1e-6, 1e-8, 1e-10: {errors:?}");
    // No rolling friction in it: refused by name.
    let e = impact(&scene, 1.0, 1.0, &ImpactOptions { solver: ObliqueSolver::Adaptive(1e-8), rolling_friction: 0.1, ..ImpactOptions::default() })
        .unwrap_err();
    assert!(e.to_string().contains("rolling_friction"), "{e}");
}

#[test]
fn an_adhesive_sphere_sticks_where_its_normal_velocity_is_below_the_sticking_velocity_at_any_angle() {
    // JKR on 000 Table 5's materials (V_s = 0.655982 m/s, the law's own sticking velocity by its energy
    // balance, `powderfmu analyze`). In this model the normal dynamics do not depend on the tangential
    // ones, so the normal rebound is the same at every angle for one normal velocity (to the bit, Verlet),
    // e = (1 - V_s^2 / v_n^2)^(1/2) (the adaptive integrator, to 1e-6), and the sphere sticks where
    // v cos(theta) < V_s.
    let mut s = Scene::new(ModelKind::Jkr, 2.45e-6, 1350.0, 1.2e9, 0.33);
    s.wall_youngs_modulus = Some(166e9);
    s.wall_poisson_ratio = 0.28;
    s.surface_energy = 0.24;
    let v_s: f64 = 0.655_982;
    let exact = ImpactOptions { solver: ObliqueSolver::Adaptive(1e-10), rayleigh_fraction: 0.5, ..ImpactOptions::default() };
    let e = impact(&s, 1.0, 0.0, &exact).unwrap().normal_velocity_out;
    assert!((e - (1.0 - v_s * v_s).sqrt()).abs() < 1e-6, "e = {e}");
    let straight = impact(&s, 1.0, 0.0, &ImpactOptions::default()).unwrap();
    for v_t in [0.3, 1.0] {
        let o = impact(&s, 1.0, v_t, &ImpactOptions::default()).unwrap();
        assert_eq!(o.normal_velocity_out, straight.normal_velocity_out, "v_t = {v_t}");
        assert!(o.tangential_velocity_out < v_t && o.angular_velocity_out > 0.0);
    }
    let held = impact(&s, 0.99 * v_s, 1.0, &ImpactOptions::default()).unwrap_err();
    assert!(matches!(held, powderfmu::impact::oblique::ObliqueError::Sticks(_)), "{held}");
    assert!(impact(&s, 1.01 * v_s, 1.0, &ImpactOptions::default()).is_ok());
}

/// The smallest normal velocity [m/s] at which the sphere leaves the wall at normal incidence (bisection).
fn sticking_velocity(s: &Scene) -> f64 {
    let (mut lo, mut hi): (f64, f64) = (1e-3, 20.0);
    for _ in 0..40 {
        let mid = (lo * hi).sqrt();
        match impact(s, mid, 0.0, &ImpactOptions::default()) {
            Ok(_) => hi = mid,
            Err(powderfmu::impact::oblique::ObliqueError::Sticks(_)) => lo = mid,
            Err(e) => panic!("{e}"),
        }
    }
    hi
}

#[test]
fn the_critical_sticking_speed_of_every_adhesive_law_grows_as_one_over_cos_theta_and_the_held_sphere_says_where_it_goes() {
    // 000 Table 5's sphere on silicon (the default scene) under JKR, Nan's and Pasha's laws, mu = 0.3: the
    // normal dynamics do not depend on the tangential ones in these laws, so a sphere sticks where
    // v cos(theta) is below the normal sticking velocity, at any angle.
    for model in [ModelKind::Jkr, ModelKind::Nan, ModelKind::Pasha] {
        let mut s = Scene::from_json(include_str!("../scenes/ammonium_fluorescein_on_silicon.json")).unwrap();
        s.contact_model = model;
        s.friction_coefficient = 0.3;
        let v_c = sticking_velocity(&s);
        for theta in [30.0f64, 60.0] {
            let v = v_c / theta.to_radians().cos();
            let (v_n, v_t) = (0.99 * v * theta.to_radians().cos(), 0.99 * v * theta.to_radians().sin());
            match impact(&s, v_n, v_t, &ImpactOptions::default()) {
                Err(powderfmu::impact::oblique::ObliqueError::Sticks(held)) => {
                    // Held, it moves along the wall (rolling on a sticking contact or sliding), never back.
                    assert!(held.tangential_velocity > 0.0 && held.tangential_velocity < v_t, "{model:?} {theta}: {held:?}");
                    assert!(held.mechanism().contains("along the wall"), "{}", held.mechanism());
                }
                other => panic!("{model:?} at {theta} deg, 0.99 of the critical speed: {other:?}"),
            }
            let (v_n, v_t) = (1.01 * v * theta.to_radians().cos(), 1.01 * v * theta.to_radians().sin());
            assert!(impact(&s, v_n, v_t, &ImpactOptions::default()).is_ok(), "{model:?} at {theta} deg, 1.01 of the critical speed");
        }
    }
}

#[test]
fn a_contact_without_adhesion_breaks_sliding_and_an_adhesive_one_can_break_sticking() {
    // The Coulomb limit mu N falls to 0 with the contact, so a sheared Hertz contact always breaks
    // sliding; JKR's mu (N + 2 f_c) stays finite and holds the contact point as it breaks (at 1 m/s and
    // 10-45 deg on 000 Table 5's sphere).
    let alumina = alumina();
    for theta in [5.0f64, 10.0, 60.0] {
        let o = impact(&alumina, SPEED * theta.to_radians().cos(), SPEED * theta.to_radians().sin(), &ImpactOptions::default()).unwrap();
        assert!(o.sliding_at_separation, "alumina at {theta} deg");
    }
    let mut s = Scene::from_json(include_str!("../scenes/ammonium_fluorescein_on_silicon.json")).unwrap();
    s.contact_model = ModelKind::Jkr;
    s.friction_coefficient = 0.3;
    for theta in [10.0f64, 30.0, 45.0] {
        let o = impact(&s, theta.to_radians().cos(), theta.to_radians().sin(), &ImpactOptions::default()).unwrap();
        assert!(!o.sliding_at_separation, "JKR at {theta} deg: {o:?}");
    }
}
