//! A sector of the die with mirror planes (`die_sector`): a bed that is mirror-symmetric about y = 0
//! steps the same in the whole die and in its half with the mirror plane, the indenter reads the whole
//! die's force from either, and a quarter bed prepares to the target stress inside its planes.

use powderfmu::bed::file;
use powderfmu::bed::indentation::{DepthOrigin, Indentation, Motion, Setup, PLATEAU};
use powderfmu::bed::particles::Particles;
use powderfmu::bed::prepare::{self, die, fill};
use powderfmu::bed::{AnyEngine, BedScene, Vec3};
use serde_json::{json, Value};

/// A soft, cohesive, frictional bed scene (Table 5.1 sizes, modified JKR, E = 55 MPa), with overrides.
fn soft(extra: Value) -> BedScene {
    let mut s = json!({"particle_particle": {"particle_youngs_modulus": 55e6}, "die_diameter": 0.01, "settle_energy_ratio": 1e-6});
    for (k, v) in extra.as_object().unwrap() {
        s[k] = v.clone();
    }
    BedScene::from_json(&s.to_string()).unwrap()
}

/// The half die's spheres and, after them, their mirror images in y = 0: the whole die, symmetric.
fn mirrored(half: &Particles, density: f64) -> Particles {
    let mut p = half.clone();
    for k in 0..half.len() {
        let x = half.position[k];
        p.push(Vec3::new(x[0], -x[1], x[2]), half.radius[k], density, half.species[k]);
    }
    p
}

/// The half and the whole die, from the same fill, falling and settling for `steps` steps.
fn half_and_whole(steps: u64) -> (AnyEngine, AnyEngine, usize, f64) {
    let half_scene = soft(json!({"particle_count": 150, "die_sector": 0.5}));
    let whole_scene = soft(json!({"particle_count": 300}));
    let half_p = fill(&half_scene).unwrap();
    let n = half_p.len();
    assert!(half_p.position.iter().zip(&half_p.radius).all(|(x, r)| x[1] >= *r), "the fill keeps clear of the mirror plane");
    let whole_p = mirrored(&half_p, half_scene.density);
    let mut half = AnyEngine::build(&half_scene, half_p, die(&half_scene)).unwrap();
    let mut whole = AnyEngine::build(&whole_scene, whole_p, die(&whole_scene)).unwrap();
    assert_eq!(half.dt(), whole.dt());
    // The mirror plane must carry force at some point, or the test would show nothing.
    let mut mirror_force: f64 = 0.0;
    for _ in 0..steps / 100 {
        half.run(100);
        whole.run(100);
        mirror_force = mirror_force.max(half.walls()[3].force[1].abs());
    }
    (half, whole, n, mirror_force)
}

fn largest_gap(half: &AnyEngine, whole: &AnyEngine, n: usize) -> f64 {
    let (a, b) = (half.particles(), whole.particles());
    (0..n).map(|k| (a.position[k] - b.position[k]).norm()).fold(0.0, f64::max)
}

#[test]
fn a_symmetric_bed_steps_the_same_in_the_half_die_with_its_mirror_plane() {
    // 20000 steps (43 ms): the fill falls and settles, spheres meet their images at the plane (from
    // about step 10000 on), adhesive and damped.
    let (half, whole, n, mirror_force) = half_and_whole(20_000);
    let d = 1e-3;
    assert!(mirror_force > 0.0, "no sphere met the mirror plane");
    // Only the order of the force sums differs, so the two agree to round-off grown by the dynamics
    // (measured: 1.4e-13 m at 20000 steps, 2.9e-12 m at 40000).
    let gap = largest_gap(&half, &whole, n);
    assert!(gap < 1e-9 * d, "largest difference of a sphere's position: {gap:e} m");
    // The whole die stayed symmetric: sphere n + k is the image of sphere k.
    let p = whole.particles();
    let asym =
        (0..n).map(|k| (p.position[k] - Vec3::new(p.position[n + k][0], -p.position[n + k][1], p.position[n + k][2])).norm()).fold(0.0, f64::max);
    assert!(asym < 1e-9 * d, "the whole die lost its symmetry by {asym:e} m");
    // The floor carries twice the half's force.
    let (fh, fw) = (half.walls()[prepare::FLOOR].force[2], whole.walls()[prepare::FLOOR].force[2]);
    assert!((2.0 * fh - fw).abs() <= 1e-6 * fw.abs(), "floor: half {fh} N, whole {fw} N");
}

#[test]
fn the_indenter_reads_the_whole_die_from_the_half() {
    // A symmetric bed at rest, indented in both: the half's force, contacts and kinetic energy are the
    // whole die's.
    let (half, whole, _, _) = half_and_whole(20_000);
    let setup = Setup {
        indenter_diameter: 0.004,
        indentation_speed: 0.05,
        max_penetration: 2e-4,
        constraint_factor: 3.0,
        constraint_factor_standard_error: 0.0,
        motion: Motion::Prescribed,
        shortcut: None,
        plateau: PLATEAU,
        depth_origin: DepthOrigin::FirstTouch,
    };
    let mut a = Indentation::new(half, soft(json!({"particle_count": 150, "die_sector": 0.5})), setup, None, None).unwrap();
    let mut b = Indentation::new(whole, soft(json!({"particle_count": 300})), setup, None, None).unwrap();
    assert!((a.record.touch - b.record.touch).abs() < 1e-12, "first touch: half {} m, whole {} m", a.record.touch, b.record.touch);
    let mut compared = 0;
    for _ in 0..20 {
        a.advance(1e-4, None).unwrap();
        b.advance(1e-4, None).unwrap();
        let (ra, rb) = (a.reading(), b.reading());
        if rb.force != 0.0 {
            compared += 1;
            assert!((ra.force - rb.force).abs() <= 1e-6 * rb.force.abs(), "force: half {} N, whole {} N", ra.force, rb.force);
            assert_eq!(ra.contacts, rb.contacts);
            assert!((ra.hydrostatic_stress - rb.hydrostatic_stress).abs() <= 1e-6 * rb.hydrostatic_stress.abs() + 1e-9);
        }
        assert!((ra.kinetic_energy - rb.kinetic_energy).abs() <= 1e-6 * rb.kinetic_energy + 1e-18);
    }
    assert!(compared > 5, "the indenter hardly touched the bed ({compared} readings)");
}

#[test]
fn a_quarter_bed_prepares_to_the_target_inside_its_planes_and_keeps_them_in_its_file() {
    let scene = soft(json!({"particle_count": 200, "die_diameter": 0.014, "die_sector": 0.25}));
    let (engine, report) = prepare::prepare(&scene, &mut |_| {}).unwrap();
    let target = scene.consolidation_stress;
    assert!((report.consolidation_stress - target).abs() < 0.05 * target, "piston {} Pa", report.consolidation_stress);
    // Bagi's stress over the whole die's cross-section, from the quarter's spheres.
    let inside = report.stress_at_target.unwrap().get(2, 2);
    assert!((inside - target).abs() < 0.1 * target, "Bagi sigma_zz {inside} Pa vs {target} Pa");
    let p = engine.particles();
    let r_min = p.radius.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(p.position.iter().all(|x| x[0] > 0.5 * r_min && x[1] > 0.5 * r_min), "a sphere crossed a mirror plane");
    let (back, back_scene) = AnyEngine::from_file(&file::decode(&file::encode(&engine.to_file(&scene).unwrap()).unwrap()).unwrap(), None).unwrap();
    assert_eq!(back_scene.die_sector, 0.25);
    assert!(back.walls()[3].is_mirror() && back.walls()[4].is_mirror());
}

#[test]
fn a_sector_other_than_a_half_or_a_quarter_is_refused_by_name() {
    let err = BedScene::from_json(r#"{"die_sector": 0.3}"#).unwrap_err().to_string();
    assert!(err.contains("die_sector") && err.contains("0.25"), "{err}");
}
