//! Chung and Ooi's Tests 5 and 6 (Granular Matter 13 (2011) 643-656), as Kratos's DEM application runs them:
//! oblique impacts on a rigid plane at a constant normal velocity. Test 5: the tangential velocity swept
//! (steel and polyethylene, 10 um, v_n = 5 m/s, mu = 0.3, elastic); Test 6: the spin swept with no
//! tangential velocity (aluminium alloy and nylon, 0.1 m, v_n = 0.2 m/s, mu = 0.4, e_n = 0.5). Scenes in
//! scenes/chung_ooi_*.json; the curves and the peer (LAMMPS) in benches/chung_ooi_5_6.py and
//! tests/python/test_peers.py. What holds in closed form is asserted here: gross sliding where Maw, Barber
//! and Fawcett say, its rebound and spin, and that the normalised results depend on Poisson's ratio (and
//! e_n) alone, which is what lets the benchmark be run on any size and stiffness.

use powderfmu::impact::oblique::{impact, ImpactOptions, Lever, ObliqueOutcome, ObliqueSolver};
use powderfmu::scene::Scene;

fn scene(text: &str) -> Scene {
    Scene::from_json(text).unwrap()
}

fn steel() -> Scene {
    scene(include_str!("../scenes/chung_ooi_steel.json"))
}

fn polyethylene() -> Scene {
    scene(include_str!("../scenes/chung_ooi_polyethylene.json"))
}

fn aluminium_alloy() -> Scene {
    scene(include_str!("../scenes/chung_ooi_aluminium_alloy.json"))
}

fn nylon() -> Scene {
    scene(include_str!("../scenes/chung_ooi_nylon.json"))
}

/// The adaptive integrator (converged to 1e-10) with LAMMPS's and the closed forms' lever R.
fn exact(spin: f64) -> ImpactOptions {
    ImpactOptions { angular_velocity: spin, lever: Lever::Radius, solver: ObliqueSolver::Adaptive(1e-10), ..ImpactOptions::default() }
}

/// Test 5's normalised outputs: the incidence x = V_st / (mu V_cn), the contact point after
/// V_st' / (mu V_cn') and the spin R omega' / (mu V_cn) (negative: against the motion).
fn test5(s: &Scene, v_n: f64, x: f64) -> (ObliqueOutcome, f64, f64) {
    let mu = s.friction_coefficient;
    let r = s.particle_radius;
    let o = impact(s, v_n, x * mu * v_n, &exact(0.0)).unwrap();
    let after = (o.tangential_velocity_out - r * o.angular_velocity_out) / (mu * o.normal_velocity_out);
    let spin = -r * o.angular_velocity_out / (mu * v_n);
    (o, after, spin)
}

/// Where gross sliding begins in x: Psi_1 = 2 (1 - nu) / (2 - nu) x >= 4 chi - 1.
fn gross_sliding_from(nu: f64) -> f64 {
    let chi = (1.0 - nu) / (2.0 - nu) * (1.0 + 1.0 / 0.4);
    (4.0 * chi - 1.0) / (2.0 * (1.0 - nu) / (2.0 - nu))
}

#[test]
fn test_5_slides_throughout_where_maw_barber_fawcett_say_with_the_closed_form_rebound_and_spin() {
    for s in [steel(), polyethylene()] {
        let from = gross_sliding_from(s.particle_poisson_ratio);
        let mut sliding = 0;
        for k in 1..=28 {
            let x = 0.5 * k as f64;
            let (o, after, spin) = test5(&s, 5.0, x);
            assert!((o.normal_velocity_out / 5.0 - 1.0).abs() < 1e-8, "elastic: {o:?}");
            // Within 3 % of the threshold the contact's last instants decide; stay clear.
            if (x / from - 1.0).abs() > 0.03 {
                assert_eq!(o.slid_throughout, x >= from, "nu {}: x = {x}, gross sliding from {from}", s.particle_poisson_ratio);
            }
            if o.slid_throughout {
                sliding += 1;
                // Delta v_t = mu (1 + e) v_n, R omega' = 5/2 Delta v_t, the contact point 7/2 Delta v_t slower.
                assert!((spin + 5.0).abs() < 1e-8, "x = {x}: spin {spin}");
                assert!((after - (x - 7.0)).abs() < 1e-7, "x = {x}: contact point after {after}");
            } else {
                // Micro-slip: less spin than gross sliding gives, and some.
                assert!(spin > -5.0 && spin < 0.0, "x = {x}: spin {spin}");
            }
        }
        assert!(sliding >= 16, "{sliding} of 28 slide throughout");
    }
}

#[test]
fn test_5_normalised_results_depend_on_poissons_ratio_alone() {
    // The steel sphere a hundred times larger, a third as stiff, twice as dense and ten times slower:
    // the same normalised curve, micro-slip included (Hertz-Mindlin is self-similar).
    let small = steel();
    let mut large = steel();
    large.particle_radius *= 100.0;
    large.particle_youngs_modulus /= 3.0;
    large.particle_density *= 2.0;
    for x in [0.5, 1.5, 3.0, 4.5, 8.0] {
        let (_, a1, s1) = test5(&small, 5.0, x);
        let (_, a2, s2) = test5(&large, 0.5, x);
        assert!((a1 - a2).abs() < 1e-6 && (s1 - s2).abs() < 1e-6, "x = {x}: ({a1}, {s1}) against ({a2}, {s2})");
    }
    // And Poisson's ratio moves it: polyethylene's spin differs from steel's in micro-slip.
    let (_, _, s_steel) = test5(&small, 5.0, 1.5);
    let (_, _, s_poly) = test5(&polyethylene(), 5.0, 1.5);
    assert!((s_steel - s_poly).abs() > 0.05, "{s_steel} against {s_poly}");
}

/// Test 6: spin only (v_t = 0, the contact point at V_st = -R omega); returns (e_n, x, beta), x =
/// 3.5 mu (1 + e_n) V_cn / V_st and beta = -V_st' / V_st.
fn test6(s: &Scene, v_st: f64) -> (ObliqueOutcome, f64, f64, f64) {
    let (v_n, r, mu) = (0.2, s.particle_radius, s.friction_coefficient);
    let o = impact(s, v_n, 0.0, &exact(-v_st / r)).unwrap();
    let e_n = o.normal_velocity_out / v_n;
    let x = 3.5 * mu * (1.0 + e_n) * v_n / v_st;
    let beta = -(o.tangential_velocity_out - r * o.angular_velocity_out) / v_st;
    (o, e_n, x, beta)
}

#[test]
fn test_6_has_the_benchmarks_restitution_and_meets_the_gross_sliding_line() {
    for s in [aluminium_alloy(), nylon()] {
        let mut sliding = 0;
        for deg in (4..=88).step_by(4) {
            let v_st = 0.2 * (deg as f64).to_radians().tan();
            let (o, e_n, x, beta) = test6(&s, v_st);
            assert!((e_n - 0.5).abs() < 2e-4, "{deg} deg: e_n {e_n}");
            if o.slid_throughout {
                sliding += 1;
                // The contact point loses 3.5 mu (1 + e_n) V_cn: beta = x - 1.
                assert!((beta - (x - 1.0)).abs() < 1e-7, "{deg} deg: beta {beta}, x {x}");
            }
            // Damped: never a full reversal, never faster than before.
            assert!(beta > -1.0 && beta < 1.0, "{deg} deg: beta {beta}");
        }
        // Gross sliding where the spin is fast (x below about 1.2: 64-88 deg).
        assert!(sliding >= 6, "{sliding} slide throughout");
    }
}

#[test]
fn test_6_spin_and_test_5_tangential_velocity_at_the_same_contact_point_velocity_agree_where_the_contact_slides() {
    // In gross sliding only the contact point's velocity matters: a spin -V/R with no tangential velocity
    // and a tangential velocity V with no spin lose the same 3.5 mu (1 + e_n) V_cn at the contact point.
    let s = aluminium_alloy();
    let (v_n, r, v) = (0.2, s.particle_radius, 2.0);
    let spin = impact(&s, v_n, 0.0, &exact(-v / r)).unwrap();
    let slide = impact(&s, v_n, v, &exact(0.0)).unwrap();
    assert!(spin.slid_throughout && slide.slid_throughout);
    let after_spin = spin.tangential_velocity_out - r * spin.angular_velocity_out;
    let after_slide = slide.tangential_velocity_out - r * slide.angular_velocity_out;
    assert!((after_spin - after_slide).abs() < 1e-9 * v, "{after_spin} against {after_slide}");
}
