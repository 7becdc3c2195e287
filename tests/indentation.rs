//! The ball indentation test on a small prepared bed: the whole load-unload cycle, the communication
//! step changing nothing, saved states continuing bit for bit, and bad set-ups refused by name.

use powderfmu::bed::file::{self, BedFile};
use powderfmu::bed::indentation::{projected_area, DepthOrigin, Indentation, Motion, Setup, Shortcut, TestState, PLATEAU};
use powderfmu::bed::prepare;
use powderfmu::bed::walls::Wall;
use powderfmu::bed::{AnyEngine, BedError, BedScene};
use std::sync::OnceLock;

/// A soft bed of 800 spheres about 18 mean diameters high in a 7 mm die, prepared once for every test:
/// Gamma = 0.5 J/m^2, the walls' contact for the indenter and 004 Eq. 3.49's friction limit, the bed the
/// measured figures in these tests' comments were taken on (the Ch. 5 defaults are now 1.0 J/m^2, the
/// particles' material and EDEM's friction limit).
fn bed() -> &'static (BedFile, BedScene) {
    static BED: OnceLock<(BedFile, BedScene)> = OnceLock::new();
    BED.get_or_init(|| {
        let scene = BedScene::from_json(
            r#"{"particle_particle": {"particle_youngs_modulus": 55e6, "surface_energy": 0.5, "jkr_friction_limit": "pull_off"}, "indenter_material": "wall", "particle_count": 800, "die_diameter": 0.007}"#,
        )
        .unwrap();
        let (engine, _) = prepare::prepare(&scene, &mut |_| {}).unwrap();
        (file::decode(&file::encode(&engine.to_file(&scene).unwrap()).unwrap()).unwrap(), scene)
    })
}

fn engine() -> (AnyEngine, BedScene) {
    AnyEngine::from_file(&bed().0, None).unwrap()
}

/// A 4 mm indenter (4 mean diameters) to 0.2 r at 0.05 m/s.
fn setup() -> Setup {
    Setup {
        indenter_diameter: 0.004,
        indentation_speed: 0.05,
        max_penetration: 0.2 * 0.002,
        constraint_factor: 3.0,
        constraint_factor_standard_error: 0.0,
        motion: Motion::Prescribed,
        shortcut: None,
        plateau: PLATEAU,
        depth_origin: DepthOrigin::FirstTouch,
    }
}

/// Runs the prescribed test in communication steps of `h` until done; the readings at each step.
fn run(test: &mut Indentation, h: f64) -> Vec<powderfmu::bed::indentation::Reading> {
    let mut out = vec![];
    for _ in 0..100_000 {
        test.advance(h, None).unwrap();
        let r = test.reading();
        out.push(r);
        if r.state == TestState::Done {
            return out;
        }
    }
    panic!("the test never ended");
}

#[test]
fn a_prescribed_test_loads_unloads_and_gives_the_hardness_at_the_turn() {
    let (engine, scene) = engine();
    let s = setup();
    let mut test = Indentation::new(engine, scene, s, None, None).unwrap();
    let readings = run(&mut test, 2e-4);
    let states: Vec<TestState> = readings.iter().map(|r| r.state).collect();
    let first_unloading = states.iter().position(|&x| x == TestState::Unloading).expect("an unloading phase");
    assert!(states[..first_unloading].iter().all(|&x| x == TestState::Loading));
    assert!(states[first_unloading..states.len() - 1].iter().all(|&x| x == TestState::Unloading));
    let rec = &test.record;
    // Turned at the step that reaches max_penetration.
    let step = s.indentation_speed * test.engine.dt();
    assert!(rec.h_max >= s.max_penetration * (1.0 - 1e-9) && rec.h_max < s.max_penetration + step, "h_max {}", rec.h_max);
    assert!(rec.f_max > 0.0, "the bed must resist the indenter");
    // This bed lets go of the indenter within three steps of the turn (the force falls below 0.75 F_0 at
    // the third: the damping force changes sign with the velocity at the turn, and the bed recovers
    // about a micrometre), too fast for a tangent to the upper unloading curve: it is vertical, h_c =
    // h_max, and the outputs say so.
    let last = readings.last().unwrap();
    assert_eq!(rec.contact_depth, None);
    assert!(rec.unloading.len() < 3, "{:?}", rec.unloading);
    assert!(!last.contact_depth_from_tangent && last.contact_depth == rec.h_max);
    // F_max of the hardness is the loading curve's force at h_max read over its last tenth, below the
    // largest sample of the fluctuating force and close to it.
    assert_eq!(last.turn_force, rec.turn_force(s.indenter_diameter));
    assert!(last.turn_force <= rec.f_max && last.turn_force > 0.8 * rec.f_max, "F at the turn {} N, largest sample {} N", last.turn_force, rec.f_max);
    assert_eq!(last.hardness, last.turn_force / projected_area(s.indenter_diameter, rec.h_max));
    assert_eq!(last.unconfined_yield_strength, last.hardness / 3.0);
    // Its standard error is the force at the turn's (here h_c = h_max): 0 where the last tenth of the
    // loading holds fewer than 8 samples, as on this short test.
    assert_eq!(last.hardness_standard_error, rec.hardness_after_turn_error(s.indenter_diameter));
    let turn_samples = rec.loading.iter().filter(|p| p.0 >= rec.h_max * (1.0 - powderfmu::bed::indentation::TURN_FIT)).count();
    assert_eq!(
        last.hardness_standard_error == 0.0,
        turn_samples < 8,
        "{turn_samples} samples: {} +- {} Pa",
        last.hardness,
        last.hardness_standard_error
    );
    assert_eq!(last.unconfined_yield_strength_standard_error, last.hardness_standard_error / 3.0);
    assert_eq!(last.contacts, 0, "done means the indenter has left the bed");
    // Once done, the prescribed test no longer steps the bed: a host's later steps change nothing.
    let (steps, done) = (test.record.steps, test.reading());
    test.advance(5e-3, None).unwrap();
    assert_eq!(test.record.steps, steps);
    assert_eq!(test.reading(), done);
    // During loading hardness is F / A(h) and the bin under the indenter is in compression.
    let mid = &readings[first_unloading / 2];
    assert!((mid.hardness - mid.force / mid.projected_area).abs() <= 1e-12 * mid.hardness.abs());
    assert_eq!(mid.hardness_standard_error, 0.0, "one sample while loading");
    let loaded: Vec<_> = readings[first_unloading / 2..first_unloading].iter().collect();
    let mean_hyd = loaded.iter().map(|r| r.hydrostatic_stress).sum::<f64>() / loaded.len() as f64;
    assert!(mean_hyd > 0.0, "compression under the indenter: {mean_hyd} Pa");
}

#[test]
fn the_communication_step_changes_nothing_but_when_results_are_read() {
    let (e1, s1) = engine();
    let (e2, s2) = engine();
    let mut a = Indentation::new(e1, s1, setup(), None, None).unwrap();
    let mut b = Indentation::new(e2, s2, setup(), None, None).unwrap();
    run(&mut a, 2e-4);
    run(&mut b, 3.7e-5);
    assert_eq!(a.record.f_max, b.record.f_max);
    assert_eq!(a.record.h_max, b.record.h_max);
    assert_eq!(a.record.contact_depth, b.record.contact_depth);
}

#[test]
fn a_saved_test_continues_bit_for_bit() {
    // On two threads too: each sphere's forces are summed in the order of the partition over threads,
    // which the restored engine must rebuild from where the running one last built its list.
    // Saved 6 ms in, after the running engine has rebuilt its list: without that rebuild restored, the
    // velocities then differed in their last bits within the next 2 ms.
    for shortcut in [None, Some(Shortcut { zone: 1.0, release: 0.01 })] {
        saved_test_continues_bit_for_bit(Setup { shortcut, ..setup() }, 1, 20);
    }
    saved_test_continues_bit_for_bit(setup(), 2, 60);
}

fn saved_test_continues_bit_for_bit(setup: Setup, threads: usize, steps_before: usize) {
    let (engine, scene) = AnyEngine::from_file(&bed().0, Some(threads)).unwrap();
    let mut test = Indentation::new(engine, scene, setup, None, None).unwrap();
    // A step of the test's own, which the saved state must keep.
    let dt = 0.7 * test.engine.dt();
    test.engine.set_time_step(&test.scene, dt).unwrap();
    for _ in 0..steps_before {
        test.advance(1e-4, None).unwrap();
    }
    let bytes = test.save().unwrap();
    let mut back = Indentation::restore(&bytes, Some(threads)).unwrap();
    assert_eq!(back.engine.dt(), dt);
    // What a host reads right after restoring is what it read when it saved.
    assert_eq!(back.reading(), test.reading());
    for _ in 0..20 {
        test.advance(1e-4, None).unwrap();
        back.advance(1e-4, None).unwrap();
    }
    assert_eq!(test.engine.particles().position, back.engine.particles().position);
    assert_eq!(test.engine.particles().velocity, back.engine.particles().velocity, "{threads} thread(s)");
    assert_eq!(test.engine.particles().angular_velocity, back.engine.particles().angular_velocity);
    assert_eq!(test.engine.particles().held, back.engine.particles().held);
    assert_eq!(test.record, back.record);
    assert_eq!(test.reading(), back.reading());
}

#[test]
fn a_saved_test_keeps_its_own_indenter_and_die_walls() {
    // An indenter ten times softer than the bed's walls and die walls five times softer: the bed file
    // alone would bring both back with the bed's own keys.
    let (engine, scene) = engine();
    let mut soft = scene.particle_wall.clone();
    soft.insert("wall_youngs_modulus".into(), serde_json::json!(1.82e10));
    let mut die = scene.particle_wall.clone();
    die.insert("wall_youngs_modulus".into(), serde_json::json!(3.64e10));
    let mut test = Indentation::new(engine, scene, setup(), None, Some(&soft)).unwrap();
    test.set_die_walls(&die).unwrap();
    for _ in 0..20 {
        test.advance(1e-4, None).unwrap();
    }
    assert!(test.reading().force > 0.0, "the indenter must be in the bed when the state is saved");
    let mut back = Indentation::restore(&test.save().unwrap(), None).unwrap();
    for _ in 0..20 {
        test.advance(1e-4, None).unwrap();
        back.advance(1e-4, None).unwrap();
    }
    assert_eq!(test.engine.particles().position, back.engine.particles().position);
    assert_eq!(test.reading(), back.reading());
}

/// The hardness after unloading, F_max / A(h_c).
fn final_hardness(test: &mut Indentation) -> f64 {
    run(test, 2e-4).last().unwrap().hardness
}

#[test]
fn the_fast_fidelity_holds_the_far_spheres_still_and_keeps_the_hardness() {
    let (e_full, s_full) = engine();
    let mut full = Indentation::new(e_full, s_full, setup(), None, None).unwrap();
    let h_full = final_hardness(&mut full);
    // A zone wider than the bed holds nothing: the same run, bit for bit.
    let (e_wide, s_wide) = engine();
    let mut wide = Indentation::new(e_wide, s_wide, Setup { shortcut: Some(Shortcut { zone: 1e3, release: 0.01 }), ..setup() }, None, None).unwrap();
    assert!(wide.engine.particles().held.iter().all(|&h| !h));
    assert_eq!(final_hardness(&mut wide), h_full);
    assert_eq!(wide.engine.particles().position, full.engine.particles().position);
    // The narrowest zone (the bin and two diameters around it) holds the lower part of this bed; never
    // released, a held sphere never moves.
    let (e_never, s_never) = engine();
    let start = e_never.particles().position.clone();
    let mut never =
        Indentation::new(e_never, s_never, Setup { shortcut: Some(Shortcut { zone: 1.0, release: f64::INFINITY }), ..setup() }, None, None).unwrap();
    let held: Vec<usize> = (0..start.len()).filter(|&i| never.engine.particles().held[i]).collect();
    assert!(held.len() > start.len() / 4, "{} of {} spheres held", held.len(), start.len());
    final_hardness(&mut never);
    for &i in &held {
        assert_eq!(never.engine.particles().position[i], start[i], "a held sphere moved");
    }
    // Released when the force on one changes by 0.1 sigma_c d^2, some of them (200 of 569, measured).
    let (e_fast, s_fast) = engine();
    let mut fast = Indentation::new(e_fast, s_fast, Setup { shortcut: Some(Shortcut { zone: 1.0, release: 0.1 }), ..setup() }, None, None).unwrap();
    let h_fast = final_hardness(&mut fast);
    let released = held.iter().filter(|&&i| !fast.engine.particles().held[i]).count();
    assert!(released > 0 && released < held.len(), "{released} of {} released", held.len());
    // The peak force is the measure here: F_max / A(h_c) also moves with the tangent over the first
    // micrometres of unloading, where single contacts of this small bed decide. Measured: never
    // released -1.0 %, released when disturbed +0.5 %.
    let (f_full, f_fast) = (full.record.f_max, fast.record.f_max);
    assert!((f_fast - f_full).abs() < 0.03 * f_full, "F_max fast {f_fast} N vs full {f_full} N");
    assert!((never.record.f_max - f_full).abs() < 0.03 * f_full, "F_max never released {} N vs full {f_full} N", never.record.f_max);
    assert!(h_fast > 0.0);
}

/// F_max of the prescribed test with this set-up and indenter contact (none: the bed's walls').
fn peak_force(setup: Setup, indenter: Option<serde_json::Map<String, serde_json::Value>>) -> f64 {
    let (engine, scene) = engine();
    let mut test = Indentation::new(engine, scene, setup, None, indenter.as_ref()).unwrap();
    run(&mut test, 1e-3);
    test.record.f_max
}

#[test]
fn the_hardness_does_not_depend_on_the_indenter_stiffness() {
    // 004 Sec. 6.2.1. The bed's walls are steel; an indenter 3.3 times stiffer than the spheres
    // (E = 55 MPa) and a rigid one: measured +0.12 % and -0.001 % in F_max.
    let steel = peak_force(setup(), None);
    for e in [serde_json::json!(1.82e8), serde_json::Value::Null] {
        let mut pair = bed().1.particle_wall.clone();
        pair.insert("wall_youngs_modulus".into(), e.clone());
        let f = peak_force(setup(), Some(pair));
        assert!((f / steel - 1.0).abs() < 0.01, "indenter E = {e}: F_max {f} N vs {steel} N with steel");
    }
}

#[test]
fn the_hardness_is_rate_independent_when_slow_and_rises_when_fast() {
    // 004 Ch. 7. On this bed (about 18 d high, 4 mm indenter) gamma* = (v / H)(d / g)^(1/2) is 0.014 and
    // 0.028 at 0.025 and 0.05 m/s (F_max 4 % apart, measured), 0.28 and 0.56 at 0.5 and 1 m/s (2.1 and
    // 4.6 times F_max at 0.05 m/s). The threshold lies between 0.05 and 0.1 m/s (+21 %).
    let slow = peak_force(Setup { indentation_speed: 0.025, ..setup() }, None);
    let base = peak_force(setup(), None);
    let fast = peak_force(Setup { indentation_speed: 0.5, ..setup() }, None);
    let faster = peak_force(Setup { indentation_speed: 1.0, ..setup() }, None);
    assert!((slow / base - 1.0).abs() < 0.05, "F_max {slow} N at 0.025 m/s vs {base} N at 0.05 m/s");
    assert!(fast > 1.5 * base && faster > fast, "F_max {base}, {fast}, {faster} N at 0.05, 0.5, 1 m/s");
}

#[test]
fn the_input_motion_follows_the_inputs() {
    let (engine, scene) = engine();
    let s = Setup { motion: Motion::Input, ..setup() };
    let mut test = Indentation::new(engine, scene, s, Some(-1e-4), None).unwrap();
    assert!((test.depth() + 1e-4).abs() < 1e-15);
    // Down at 0.05 m/s for 6 ms from 0.1 mm above the surface: 0.2 mm deep.
    let (h, v) = (1e-4, 0.05);
    for k in 0..60 {
        let depth = -1e-4 + v * h * k as f64;
        test.advance(h, Some((depth, v))).unwrap();
    }
    assert!((test.depth() - 2e-4).abs() < 1e-9, "depth {}", test.depth());
    assert_eq!(test.reading().state, TestState::Loading);
    assert!(test.force() > 0.0);
}

fn refused(setup: Setup, start: f64, name: &str) {
    let (engine, scene) = engine();
    match Indentation::new(engine, scene, setup, Some(start), None) {
        Err(BedError::Param(e)) => assert_eq!(e.parameter(), Some(name), "{e}"),
        Err(other) => panic!("{name}: expected a parameter error, got {other}"),
        Ok(_) => panic!("{name}: expected an error"),
    }
}

#[test]
fn bad_set_ups_are_refused_by_name() {
    refused(Setup { indenter_diameter: 0.008, ..setup() }, 0.0, "indenter_diameter");
    refused(Setup { max_penetration: 0.05, ..setup() }, 0.0, "max_penetration");
    refused(Setup { indentation_speed: -1.0, ..setup() }, 0.0, "indentation_speed");
    refused(setup(), 1e-4, "indenter_displacement");
    refused(Setup { plateau: (-0.1, 0.2), ..setup() }, 0.0, "plateau_start");
    refused(Setup { plateau: (0.2, 0.1), ..setup() }, 0.0, "plateau_end");
    // Measured from the mean surface, the first touch lies above the origin: starting at 0 is inside.
    refused(Setup { depth_origin: DepthOrigin::MeanSurface, ..setup() }, 0.0, "indenter_displacement");
    let (engine, scene) = engine();
    let mut test = Indentation::new(engine, scene, setup(), None, None).unwrap();
    let above = 10.0 * test.engine.dt();
    match test.engine.set_time_step(&test.scene, above) {
        Err(BedError::Param(e)) => assert_eq!(e.parameter(), Some("time_step"), "{e}"),
        other => panic!("a time step above the stability limit must be refused, got {:?}", other.err()),
    }
}

#[test]
fn hardness_falls_to_a_plateau_beyond_a_tenth_of_the_radius() {
    // 004 Figs. 5.2-5.3: at small depths a few spheres carry the indenter and F/A(h) is high; beyond
    // h/r of about 0.1 it levels off.
    let (engine, scene) = engine();
    let mut test = Indentation::new(engine, scene, setup(), None, None).unwrap();
    let readings = run(&mut test, 2e-5);
    let mean = |lo: f64, hi: f64| {
        let h: Vec<f64> = readings
            .iter()
            .filter(|r| r.state == TestState::Loading && r.dimensionless_depth >= lo && r.dimensionless_depth < hi)
            .map(|r| r.hardness)
            .collect();
        assert!(h.len() > 20, "{} readings in [{lo}, {hi})", h.len());
        h.iter().sum::<f64>() / h.len() as f64
    };
    let (early, plateau) = (mean(0.01, 0.05), mean(0.1, 0.2));
    let (first, second) = (mean(0.1, 0.15), mean(0.15, 0.2));
    assert!(early > 1.3 * plateau, "early {early} Pa, plateau {plateau} Pa");
    assert!((first - second).abs() < 0.25 * plateau, "halves of the plateau {first} and {second} Pa");
    // The test's own plateau (sampled every 100 engine steps, the readings here every 2e-5 s) is the
    // same mean of the same curve.
    let own = test.record.plateau(test.setup.indenter_diameter, test.setup.plateau);
    assert!(own.samples > 10, "{} samples", own.samples);
    assert!((own.mean - plateau).abs() < 0.05 * plateau, "the test's plateau {} Pa against the readings' {plateau} Pa", own.mean);
    assert_eq!(readings.last().unwrap().plateau, own);
    // Its standard error is that of a fluctuating mean: above zero, a few per cent of it here, and
    // covering the readings' own mean of the same curve within a few errors.
    assert!(own.standard_error > 0.0 && own.standard_error < 0.1 * own.mean, "{own:?}");
    assert!((own.mean - plateau).abs() < 4.0 * own.standard_error, "{own:?} against {plateau} Pa");
}

#[test]
fn the_indenter_contacts_from_its_contact_list_are_all_the_touching_spheres() {
    let (engine, scene) = engine();
    let mut test = Indentation::new(engine, scene, setup(), None, None).unwrap();
    let indenter = test.engine.walls().last().unwrap().clone();
    for _ in 0..40 {
        test.advance(2e-4, None).unwrap();
        let wall = Wall { position: test.engine.walls().last().unwrap().position, ..indenter.clone() };
        let p = test.engine.particles();
        let all = p.position.iter().zip(&p.radius).filter(|(x, r)| wall.touch(**x, **r).overlap > 0.0).count();
        assert_eq!(test.contacts(), all);
    }
    assert!(test.contacts() > 0);
}

#[test]
fn measured_from_the_mean_surface_the_depth_is_the_first_touch_depth_less_the_offset() {
    let (e1, s1) = engine();
    let (e2, s2) = engine();
    let mean_diameter = s1.size_distribution.mean_diameter();
    let mut touch = Indentation::new(e1, s1, setup(), None, None).unwrap();
    let mut surface = Indentation::new(e2, s2, Setup { depth_origin: DepthOrigin::MeanSurface, ..setup() }, None, None).unwrap();
    let offset = surface.reading().depth_origin_offset;
    assert_eq!(touch.reading().depth_origin_offset, 0.0);
    // The highest sphere under the indenter stands above the bed's mean surface, by less than a sphere.
    assert!(offset > 0.0 && offset < mean_diameter, "offset {offset} m");
    // The prescribed test starts at the first touch, -offset below the mean surface.
    assert!((surface.depth() + offset).abs() < 1e-15, "start depth {} m", surface.depth());
    for _ in 0..10 {
        touch.advance(2e-4, None).unwrap();
        surface.advance(2e-4, None).unwrap();
        assert!((surface.depth() + offset - touch.depth()).abs() < 1e-15);
    }
    // The same bed, the same motion: the same force until the turn (which comes offset later).
    assert_eq!(surface.force(), touch.force());
}

/// 004 Sec. 5.1.3's indenter is "a cohesionless spherical indenter made of Material 1": by default the
/// particles' friction, rolling friction and stiffness without their interface energy; 004 Ch. 6's is a
/// wall (Table 6.3: frictionless, no rolling friction). What the engine steps against the indenter is
/// read from its interaction row.
#[test]
fn the_indenter_is_made_of_the_material_the_scene_names() {
    use powderfmu::bed::IndenterMaterial;
    use powderfmu::law::NormalLaw;
    for (material, friction, rolling) in [(IndenterMaterial::Particle, 0.15, 0.1), (IndenterMaterial::Wall, 0.0, 0.0)] {
        let (engine, mut scene) = engine();
        scene.indenter_material = material;
        let test = Indentation::new(engine, scene.clone(), setup(), None, None).unwrap();
        let bed_pull_off = powderfmu::with_engine!(&test.engine, e => {
            let p = &e.pairs[0];
            p.law.pull_off_force(&p.initial)
        });
        assert!(bed_pull_off > 0.0, "the bed's spheres are cohesive");
        powderfmu::with_engine!(&test.engine, e => {
            let w = e.walls.iter().position(|w| w.name == "indenter").unwrap();
            for it in &e.wall_pairs[w] {
                assert_eq!(it.friction, friction, "{material:?}: sliding friction against the indenter");
                assert_eq!(it.rolling_friction, rolling, "{material:?}: rolling friction against the indenter");
                assert_eq!(it.law.pull_off_force(&it.initial), 0.0, "{material:?}: the indenter is cohesionless");
            }
            // The die keeps the walls' contact whatever the indenter is made of.
            let die = e.walls.iter().position(|w| w.name == "die").unwrap();
            assert!(e.wall_pairs[die].iter().all(|it| it.friction == 0.0 && it.rolling_friction == 0.0), "{material:?}: the die");
        });
    }
}

/// A bed file written before `indenter_material` existed was indented with the walls' contact: it keeps
/// it when loaded; a bed written now says which it is.
#[test]
fn a_bed_from_before_the_indenter_material_keeps_the_walls_contact() {
    use powderfmu::bed::IndenterMaterial;
    let mut old = bed().0.clone();
    let mut scene: serde_json::Value = serde_json::from_str(&old.scene).unwrap();
    assert_eq!(scene["indenter_material"], "wall", "a bed written now names its indenter's material");
    scene["indenter_material"] = "particle".into();
    old.scene = scene.to_string();
    assert_eq!(AnyEngine::from_file(&old, None).unwrap().1.indenter_material, IndenterMaterial::Particle);
    scene.as_object_mut().unwrap().remove("indenter_material");
    old.scene = scene.to_string();
    let (_, loaded) = AnyEngine::from_file(&old, None).unwrap();
    assert_eq!(loaded.indenter_material, IndenterMaterial::Wall);
    assert_eq!(loaded.indenter_pair(), loaded.particle_wall);
    assert_eq!(loaded.indenter_rolling_friction(), loaded.wall_rolling_friction);
}
