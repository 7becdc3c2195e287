//! The DEM bed engine (issue 6): physics checks against the single-impact unit and the conservation
//! laws, rest without creep, Janssen's saturation in a column, consolidation to the target stress, and
//! the errors of bad input. Beds here are small and soft (E = 55 MPa instead of 55 GPa) so the steps are
//! long and the tests quick; the engine is the same.

use powderfmu::bed::file;
use powderfmu::bed::particles::Particles;
use powderfmu::bed::prepare::{self, bed_height, DIE, FLOOR};
use powderfmu::bed::stress::{bagi, Region};
use powderfmu::bed::walls::Wall;
use powderfmu::bed::{AnyEngine, BedScene, Isa, Vec3};
use powderfmu::impact::{Contact, Solver, Sphere, State, WallMotion};
use powderfmu::law::damping::NormalDamping;
use powderfmu::law::params::Effective;
use powderfmu::law::{AnyLaw, Branch};
use powderfmu::scene::Scene;
use powderfmu::with_engine;
use serde_json::{json, Value};

/// A soft glass-like bed scene (Table 5.1 sizes, E = 55 MPa), with overrides.
fn soft(extra: Value) -> BedScene {
    let mut s = json!({
        "particle_particle": {"particle_youngs_modulus": 55e6},
        "particle_count": 300,
        "die_diameter": 0.01,
        "settle_energy_ratio": 1e-6,
    });
    for (k, v) in extra.as_object().unwrap() {
        s[k] = v.clone();
    }
    BedScene::from_json(&s.to_string()).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

// ---------------------------------------------------------------------------------------------------
// Two spheres against the single-impact unit.

/// Relative rebound speed / impact speed of two equal spheres meeting head-on at `v`, in the engine.
fn engine_collision(law: &Value, radius: f64, v: f64, rayleigh_fraction: f64) -> f64 {
    let scene = BedScene::from_json(
        &json!({
            "particle_particle": law,
            "size_distribution": {"diameters": [2.0 * radius], "frequencies": [1.0]},
            "gravity": 0.0,
            "rayleigh_fraction": rayleigh_fraction,
            "rolling_friction": 0.0,
        })
        .to_string(),
    )
    .unwrap();
    let mut p = Particles::default();
    let gap = 1e-3 * radius;
    p.push(Vec3::new(-(radius + gap), 0.0, 0.0), radius, scene.density, 0);
    p.push(Vec3::new(radius + gap, 0.0, 0.0), radius, scene.density, 0);
    p.velocity[0] = Vec3::new(0.5 * v, 0.0, 0.0);
    p.velocity[1] = Vec3::new(-0.5 * v, 0.0, 0.0);
    let mut e = AnyEngine::build(&scene, p, vec![]).unwrap();
    let mut touched = false;
    for _ in 0..10_000_000 {
        e.step();
        let p = e.particles();
        let distance = p.position[1][0] - p.position[0][0];
        touched |= distance < 2.0 * radius;
        // Well beyond any neck (the JKR neck reaches tens of nanometres here).
        if touched && distance > 2.1 * radius {
            return (p.velocity[1][0] - p.velocity[0][0]) / v;
        }
    }
    panic!("the spheres never separated");
}

/// The same collision as the single-impact unit computes it: a sphere of mass m* on the pair's law
/// (contact_partner = particle), integrated by the unit's adaptive solver.
fn unit_collision(law: &Value, radius: f64, v: f64) -> f64 {
    let mut map = law.as_object().unwrap().clone();
    map.insert("particle_radius".into(), radius.into());
    map.insert("contact_partner".into(), "particle".into());
    let s = Scene::from_map(&map).unwrap();
    let eff = Effective::from_scene(&s).unwrap();
    let contact = Contact::new(AnyLaw::from_scene(&s).unwrap(), NormalDamping::from_scene(&s, eff.mass), 1e-3 * radius, v);
    let mut sp = Sphere::new(eff.mass, 0.0, contact, Solver::Adaptive, 1e-11);
    let wall = WallMotion { t0: 0.0, position: 0.0, velocity: 0.0 };
    let mut y = State::new(1e-3 * radius, -v, 0.0);
    sp.accept(&wall, 0.0, &y);
    let (mut t, dt) = (0.0, 1e-3 * radius / v);
    while !(y.velocity > 0.0 && sp.contact.accepted.branch == Branch::Separated) {
        sp.advance(&wall, t, t + dt, &mut y).unwrap();
        t += dt;
        assert!(t < 1.0, "the unit's sphere never left");
    }
    y.velocity / v
}

#[test]
fn two_sphere_collision_matches_the_single_impact_unit() {
    // 000 Table 5 material (Nan, damped), Hertz and JKR of the same material; 5 um spheres at 1 m/s.
    let base = json!({"particle_density": 1350.0, "particle_youngs_modulus": 1.2e9, "particle_poisson_ratio": 0.33,
        "particle_yield_pressure": 30e6, "restitution_coefficient": 0.5, "friction_coefficient": 0.0});
    for (model, gamma) in [("nan", 0.24), ("hertz", 0.0), ("jkr", 0.24)] {
        let mut law = base.clone();
        law["contact_model"] = model.into();
        law["surface_energy"] = gamma.into();
        let (r, v) = (5e-6, 4.0);
        let unit = unit_collision(&law, r, v);
        assert!(unit > 0.01 && unit < 1.0, "{model}: unit restitution {unit}");
        // Velocity Verlet at 2 %, 0.5 % and 0.125 % of the Rayleigh time against the unit's adaptive
        // integration: within 2 % at the coarsest, converging to 0.2 %. (The adhesive jumps at contact
        // and at the JKR neck's rupture make Verlet first order.)
        let errors: Vec<f64> = [0.02, 0.005, 0.00125].iter().map(|&f| rel(engine_collision(&law, r, v, f), unit)).collect();
        assert!(errors[0] < 2e-2, "{model}: errors {errors:?}");
        assert!(errors[2] < 2e-3, "{model}: errors {errors:?}");
        assert!(errors[2] <= errors[0] || errors[2] < 5e-4, "{model}: errors {errors:?}");
    }
}

// ---------------------------------------------------------------------------------------------------
// Conservation.

/// A cloud of spheres with random velocities and friction, Nan law with adhesion.
fn cloud(walls: Vec<Wall>) -> AnyEngine {
    let scene = soft(json!({"particle_particle": {"contact_model": "nan", "particle_youngs_modulus": 55e6,
        "particle_yield_pressure": 5e6, "friction_coefficient": 0.3}, "gravity": 0.0}));
    let mut p = Particles::default();
    let mut k = 0u64;
    let mut next = || {
        k = k.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (k >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for i in 0..6 {
        for j in 0..6 {
            for l in 0..6 {
                p.push(Vec3::new(i as f64 * 1.1e-3, j as f64 * 1.1e-3, l as f64 * 1.1e-3), 0.45e-3 + 0.05e-3 * next(), scene.density, 4);
                let n = p.len() - 1;
                p.velocity[n] = Vec3::new(next(), next(), next());
                p.angular_velocity[n] = Vec3::new(100.0 * next(), 100.0 * next(), 100.0 * next());
            }
        }
    }
    AnyEngine::build(&scene, p, walls).unwrap()
}

#[test]
fn momentum_is_conserved_to_round_off_without_walls() {
    let mut e = cloud(vec![]);
    let p0 = e.particles().momentum();
    let scale: f64 = e.particles().mass.iter().zip(&e.particles().velocity).map(|(m, v)| m * v.iter().map(|c| c.abs()).sum::<f64>()).sum();
    let mut contacts = 0;
    for _ in 0..2000 {
        e.step();
        contacts += e.contact_statistics().0;
    }
    assert!(contacts > 1000, "the cloud must collide ({contacts} contact-steps)");
    let p1 = e.particles().momentum();
    for c in 0..3 {
        assert!((p1[c] - p0[c]).abs() < 1e-13 * scale, "component {c}: {} -> {}", p0[c], p1[c]);
    }
}

#[test]
fn in_a_closed_box_momentum_changes_only_by_the_walls_impulse() {
    let (lo, hi) = (-1.0e-3, 6.5e-3);
    let walls = vec![
        Wall::plane("x-", Vec3::new(lo, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0)),
        Wall::plane("x+", Vec3::new(hi, 0.0, 0.0), Vec3::new(-1.0, 0.0, 0.0)),
        Wall::plane("y-", Vec3::new(0.0, lo, 0.0), Vec3::new(0.0, 1.0, 0.0)),
        Wall::plane("y+", Vec3::new(0.0, hi, 0.0), Vec3::new(0.0, -1.0, 0.0)),
        Wall::plane("z-", Vec3::new(0.0, 0.0, lo), Vec3::new(0.0, 0.0, 1.0)),
        Wall::plane("z+", Vec3::new(0.0, 0.0, hi), Vec3::new(0.0, 0.0, -1.0)),
    ];
    let mut e = cloud(walls);
    let p0 = e.particles().momentum();
    let dt = e.dt();
    let wall_sum = |e: &AnyEngine| e.walls().iter().fold([0.0; 3], |a, w| [a[0] + w.force[0], a[1] + w.force[1], a[2] + w.force[2]]);
    let mut impulse = [0.0; 3];
    let mut before = wall_sum(&e);
    let mut wall_hits = 0.0;
    for _ in 0..4000 {
        e.step();
        let after = wall_sum(&e);
        for c in 0..3 {
            // Velocity Verlet: each step's momentum change is dt/2 (F_n + F_n+1); the particles get minus
            // the walls' share.
            impulse[c] -= 0.5 * dt * (before[c] + after[c]);
        }
        wall_hits += after.iter().map(|f| f.abs()).sum::<f64>();
        before = after;
    }
    assert!(wall_hits > 0.0, "the walls must be hit");
    let p1 = e.particles().momentum();
    let scale = e.particles().mass.iter().sum::<f64>() * 1.0;
    for c in 0..3 {
        assert!((p1[c] - p0[c] - impulse[c]).abs() < 1e-12 * scale, "component {c}: change {} vs wall impulse {}", p1[c] - p0[c], impulse[c]);
    }
}

// ---------------------------------------------------------------------------------------------------
// Prepared beds.

fn prepared(scene: &BedScene) -> (AnyEngine, prepare::Report) {
    prepare::prepare(scene, &mut |_| {}).unwrap()
}

#[test]
fn consolidation_reaches_its_target_within_5_percent_in_the_piston_and_inside_the_bed() {
    // A bed about 20 diameters high, so the middle half is thick against the spheres.
    let scene = soft(json!({"particle_count": 800, "die_diameter": 0.007}));
    let (mut e, report) = prepared(&scene);
    let target = scene.consolidation_stress;
    assert!(rel(report.consolidation_stress, target) < 0.05, "piston {} Pa vs {target} Pa", report.consolidation_stress);
    // Bagi's vertical stress in the middle of the bed (independent of the piston's force) agrees too.
    let inside = report.stress_at_target.unwrap().get(2, 2);
    assert!(rel(inside, target) < 0.05, "Bagi sigma_zz {inside} Pa vs {target} Pa");
    // After unloading and relaxation the piston is clear, the bed is at rest and keeps a residual stress
    // far below the target.
    assert_eq!(e.walls()[prepare::PISTON].force, Vec3::zeros());
    let h = bed_height(e.particles());
    let d = scene.size_distribution.mean_diameter();
    let after = bagi(&mut e, &Region { radius: 0.5 * scene.die_diameter - 2.0 * d, z_low: 0.25 * h, z_high: 0.75 * h }).get(2, 2);
    assert!(after < 0.5 * target, "residual {after} Pa");
}

#[test]
fn a_bed_at_rest_stays_at_rest_for_1e5_steps() {
    let scene = soft(json!({"particle_count": 150, "die_diameter": 0.008}));
    let (mut e, _) = prepared(&scene);
    let d = scene.size_distribution.mean_diameter();
    let weight: f64 = e.particles().mass.iter().sum::<f64>() * scene.gravity;
    // The preparation stops at a kinetic energy of 1e-6 W d, where a last sphere may still be rolling
    // into place (with Gamma = 1 J/m^2 one moves 1.2 % d in the next 2e4 steps, then the bed's energy
    // falls to 1e-25 W d): at rest means far below that.
    for _ in 0..20 {
        if e.particles().kinetic_energy() < 1e-15 * weight * d {
            break;
        }
        e.run(10_000);
    }
    assert!(e.particles().kinetic_energy() < 1e-15 * weight * d, "the bed never came to rest");
    let x0 = e.particles().position.clone();
    e.run(100_000);
    let p = e.particles();
    let drift =
        p.position.iter().zip(&x0).map(|(a, b)| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()).fold(0.0, f64::max);
    assert!(drift < 1e-3 * d, "largest displacement over 1e5 steps: {drift:e} m ({:.2e} d)", drift / d);
    let ke = p.kinetic_energy();
    assert!(ke < 1e-6 * weight * d, "kinetic energy {ke:e} J");
    // The floor carries the weight (the die is frictionless here), on average over the last steps.
    let mut floor = 0.0;
    for _ in 0..2000 {
        e.step();
        floor += -e.walls()[FLOOR].force[2] / 2000.0;
    }
    assert!(rel(floor, weight) < 1e-2, "floor {floor} N vs weight {weight} N");
}

#[test]
fn a_settled_column_follows_janssen_saturation() {
    // A narrow die with wall friction: the wall carries part of the weight, and the floor's share falls
    // with the height as Janssen's sigma_v = rho g D / (4 mu K) (1 - exp(-4 mu K z / D)) says.
    let mu_w = 0.5;
    // Janssen's analysis is for a cohesionless material: no surface energy here.
    let scene = soft(json!({"particle_count": 700, "die_diameter": 0.005, "die_height": 0.15,
        "particle_particle": {"particle_youngs_modulus": 55e6, "surface_energy": 0.0},
        "particle_wall": {"friction_coefficient": mu_w}}));
    let particles = prepare::fill(&scene).unwrap();
    let mut e = AnyEngine::build(&scene, particles, prepare::die(&scene)).unwrap();
    // Settle (no piston), then lower the floor by a tenth of a diameter, slowly: the column slides down
    // the die as Janssen assumes, with the wall friction mobilized upwards everywhere.
    let weight: f64 = e.particles().mass.iter().sum::<f64>() * scene.gravity;
    let d = scene.size_distribution.mean_diameter();
    let settle = |e: &mut AnyEngine| loop {
        e.run(2000);
        if e.particles().kinetic_energy() < 1e-7 * weight * d && e.time() > 0.05 {
            break;
        }
        assert!(e.time() < 2.0, "the column did not settle");
    };
    settle(&mut e);
    let speed = 2e-3;
    e.walls_mut()[FLOOR].velocity = Vec3::new(0.0, 0.0, -speed);
    e.run((0.1 * d / speed / e.dt()) as u64);
    e.walls_mut()[FLOOR].velocity = Vec3::zeros();
    settle(&mut e);
    let h = bed_height(e.particles());
    let floor = e.walls()[FLOOR].force[2].abs();
    let wall_vertical = e.walls()[DIE].force[2].abs();
    // The die wall carries a real share of the weight by friction, and the two add up to it.
    assert!(rel(floor + wall_vertical, weight) < 0.02, "floor {floor} + wall {wall_vertical} vs weight {weight}");
    assert!(floor < 0.9 * weight, "floor {floor} N of {weight} N: the wall carries too little");
    // Janssen: sigma_v(depth) = rho_b g lambda (1 - exp(-depth / lambda)), lambda = D / (4 mu K), so the
    // floor carries the fraction (lambda / H)(1 - exp(-H / lambda)) of the weight. The floor force is
    // exact (a wall reaction), so lambda is taken from it; slice-by-slice stresses in a column five
    // spheres wide scatter by 20-30 % from seed to seed, the floor fraction by a few per cent.
    let area = std::f64::consts::PI * 0.25 * scene.die_diameter.powi(2);
    let rho_b = weight / (scene.gravity * area * h);
    let die_r = 0.5 * scene.die_diameter;
    let fraction = floor / weight;
    let lambda = {
        let share = |l: f64| l / h * (1.0 - (-h / l).exp());
        let (mut lo, mut hi) = (1e-6 * h, 1e3 * h);
        for _ in 0..200 {
            let mid = (lo * hi).sqrt();
            if share(mid) < fraction {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    };
    // Saturation: the column is several lambda deep.
    assert!(h > 3.0 * lambda, "lambda {lambda} m in a column {h} m high (floor carries {fraction})");
    // Below three lambda the stress is saturated at rho_b g lambda (Bagi over the whole lower region), far
    // below the hydrostatic stress there.
    let deep = bagi(&mut e, &Region { radius: die_r, z_low: d, z_high: (h - 3.0 * lambda).max(2.0 * d) }).get(2, 2);
    let saturated = rho_b * scene.gravity * lambda;
    assert!(rel(deep, saturated) < 0.25, "sigma_zz below 3 lambda: {deep} Pa, Janssen's saturation {saturated} Pa");
    assert!(deep < 0.5 * rho_b * scene.gravity * (h - 0.5 * (h - 3.0 * lambda)), "sigma_zz {deep} Pa is not saturated");
    // The friction it implies, D / (4 lambda K) with K the ratio of horizontal to vertical stress in the
    // column, is what the wall can give: mobilized, and at most mu_w.
    let mid = bagi(&mut e, &Region { radius: die_r, z_low: 0.2 * h, z_high: 0.8 * h });
    let k = 0.5 * (mid.get(0, 0) + mid.get(1, 1)) / mid.get(2, 2);
    assert!(k > 0.2 && k < 1.5, "K = {k}");
    let mu_mobilized = scene.die_diameter / (4.0 * lambda * k);
    assert!(mu_mobilized > 0.2 * mu_w && mu_mobilized <= mu_w, "mobilized wall friction {mu_mobilized} (K = {k}, mu_w = {mu_w})");
}

// ---------------------------------------------------------------------------------------------------
// Threads, memory across rebuilds, files.

#[test]
fn two_threads_are_deterministic_and_agree_with_one_to_round_off() {
    let run = |threads: usize| {
        let scene = soft(json!({"threads": threads, "particle_count": 200, "die_diameter": 0.008}));
        let mut e = AnyEngine::build(&scene, prepare::fill(&scene).unwrap(), prepare::die(&scene)).unwrap();
        e.run(3000);
        e.particles().position.clone()
    };
    let a = run(2);
    let b = run(2);
    assert_eq!(a, b, "two runs on two threads must be bitwise equal");
    let one = run(1);
    let worst = a.iter().zip(&one).map(|(x, y)| (0..3).map(|c| (x[c] - y[c]).abs()).fold(0.0, f64::max)).fold(0.0, f64::max);
    assert!(worst < 1e-9, "1 vs 2 threads differ by {worst:e} m");
}

#[test]
fn contact_memory_survives_list_rebuilds_and_bed_files() {
    let scene = soft(json!({"particle_count": 150, "die_diameter": 0.008}));
    let (e, _) = prepared(&scene);
    let dir = std::env::temp_dir().join(format!("powderfmu-bed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bed.bed");
    file::save(&path, &e, &scene).unwrap();
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "no temporary file left behind");
    let (mut back, _) = file::load(&path, None).unwrap();
    // The reloaded bed continues exactly where the saved one goes on.
    let mut e = e;
    e.run(300);
    back.run(300);
    assert_eq!(e.particles().position, back.particles().position, "a reloaded bed must continue bit for bit");
    // Rebuilding the Verlet list at every step keeps every contact's memory: the motion changes only by
    // the order of summation.
    let (mut again, _) = file::load(&path, None).unwrap();
    let (mut every, _) = file::load(&path, None).unwrap();
    for _ in 0..300 {
        again.step();
        every.rebuild();
        every.step();
    }
    let d = scene.size_distribution.mean_diameter();
    let worst = again
        .particles()
        .position
        .iter()
        .zip(&every.particles().position)
        .map(|(a, b)| (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    assert!(worst < 1e-12 * d, "rebuilding at every step moved a sphere by {worst:e} m");
    let springs = with_engine!(&every, x => x.memory.spring.iter().filter(|s| **s != Vec3::zeros()).count());
    assert!(springs > 50, "the bed must have loaded tangential springs ({springs})");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_bed_in_motion_saved_at_any_step_continues_bit_for_bit() {
    // Settling spheres collide and part: a contact with memory may have moved beyond the list's range
    // since the last build. The reloaded engine must still hold it, as the saving engine does.
    let scene = soft(json!({"particle_count": 300, "die_diameter": 0.008}));
    let (mut e, _) = prepare::prepare_until(&scene, "fill", &mut |_| {}).unwrap();
    for moment in 0..40 {
        e.run(500);
        let (mut back, _) = AnyEngine::from_file(&file::decode(&file::encode(&e.to_file(&scene).unwrap()).unwrap()).unwrap(), None).unwrap();
        e.run(150);
        back.run(150);
        assert_eq!(e.particles().position, back.particles().position, "saved at moment {moment}");
    }
}

#[test]
fn a_saved_contact_beyond_the_list_range_is_kept_on_loading() {
    // Two touching spheres of a prepared bed, one moved 3 skins away in the file: as a contact that
    // parted since the saving engine's last list build. Loading keeps it in the list with its memory.
    let scene = soft(json!({"particle_count": 150, "die_diameter": 0.008}));
    let (e, _) = prepared(&scene);
    let mut f = e.to_file(&scene).unwrap();
    let p = e.particles();
    let gap = |i: usize, j: usize| -> [f64; 3] { [0, 1, 2].map(|c| p.position[j][c] - p.position[i][c]) };
    let length = |d: [f64; 3]| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let (i, j) = (0..p.len())
        .flat_map(|i| (i + 1..p.len()).map(move |j| (i, j)))
        .find(|&(i, j)| length(gap(i, j)) < 0.999 * (p.radius[i] + p.radius[j]))
        .expect("a touching pair");
    let skin = with_engine!(&e, x => x.list.skin);
    let d = gap(i, j);
    for c in 0..3 {
        f.position[j][c] += 3.0 * skin * d[c] / length(d);
    }
    let (back, _) = AnyEngine::from_file(&file::decode(&file::encode(&f).unwrap()).unwrap(), None).unwrap();
    assert!(with_engine!(&back, x => x.list.row(i).contains(&(j as u32))), "the pair ({i}, {j}) is in the list");
}

#[test]
fn a_preparation_resumed_from_a_bed_file_after_any_phase_ends_bit_for_bit_where_one_run_ends() {
    let scene = soft(json!({"particle_count": 150, "die_diameter": 0.008}));
    let (whole, _) = prepared(&scene);
    for phase in ["fill", "settle", "consolidate", "unload"] {
        let (part, _) = prepare::prepare_until(&scene, phase, &mut |_| {}).unwrap();
        let (saved, _) = AnyEngine::from_file(&file::decode(&file::encode(&part.to_file(&scene).unwrap()).unwrap()).unwrap(), None).unwrap();
        assert_eq!(prepare::phase_done(&saved, &scene), phase, "the phase a bed went through is read from its piston");
        let (rest, report) = prepare::resume(saved, &scene, "relax", &mut |_| {}).unwrap();
        let after: Vec<&str> = report.phases.iter().map(|p| p.0).collect();
        let index = prepare::PHASES.iter().position(|&p| p == phase).unwrap();
        assert_eq!(after, prepare::PHASES[index + 1..].to_vec(), "resumed after {phase}");
        assert_eq!(rest.time(), whole.time(), "resumed after {phase}");
        assert_eq!(rest.particles().position, whole.particles().position, "resumed after {phase}: not the same bed");
    }
    // A checkpoint taken within a phase (as `bed prepare` writes them) names the phase before it and
    // the preparation goes on from there to a bed of the same height within 2 %.
    for within in ["settle", "consolidate", "unload"] {
        let mut checkpoint = None;
        prepare::prepare_until(&scene, within, &mut |p| {
            if p.phase == within && p.fraction < 0.99 && checkpoint.is_none() && p.time > 0.0 {
                checkpoint = Some(file::encode(&p.bed.to_file(&scene).unwrap()).unwrap());
            }
        })
        .unwrap();
        let (saved, _) = AnyEngine::from_file(&file::decode(&checkpoint.expect("a checkpoint within the phase")).unwrap(), None).unwrap();
        let index = prepare::PHASES.iter().position(|&p| p == within).unwrap();
        assert_eq!(prepare::phase_done(&saved, &scene), prepare::PHASES[index - 1], "a checkpoint within {within}");
        let (rest, report) = prepare::resume(saved, &scene, "relax", &mut |_| {}).unwrap();
        assert_eq!(report.phases.first().unwrap().0, within);
        let (h, h_whole) = (bed_height(rest.particles()), bed_height(whole.particles()));
        assert!(rel(h, h_whole) < 0.02, "resumed within {within}: bed {h} m high vs {h_whole} m");
    }
}

#[test]
fn an_indenter_added_to_a_prepared_bed_keeps_every_contact_and_feels_the_bed() {
    let scene = soft(json!({"particle_count": 150, "die_diameter": 0.008}));
    let (e, _) = prepared(&scene);
    let dir = std::env::temp_dir().join(format!("powderfmu-indenter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bed.bed");
    file::save(&path, &e, &scene).unwrap();
    let (mut plain, _) = file::load(&path, None).unwrap();
    let (mut with, _) = file::load(&path, None).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let d = scene.size_distribution.mean_diameter();
    let top = bed_height(with.particles());
    let radius = 1.5 * d;
    let springs = |e: &AnyEngine| with_engine!(e, x => x.memory.spring.iter().filter(|s| **s != Vec3::zeros()).count());
    let loaded = springs(&with);
    assert!(loaded > 50, "the prepared bed must have loaded tangential springs ({loaded})");
    // Clear of the bed, the indenter changes nothing: every contact keeps its memory.
    with.add_wall(
        &scene,
        Wall::sphere("indenter", Vec3::new(0.0, 0.0, top + radius + 0.5 * d), radius),
        &scene.particle_wall,
        scene.wall_rolling_friction,
    )
    .unwrap();
    assert_eq!(springs(&with), loaded, "adding a wall must keep every tangential spring");
    plain.run(300);
    with.run(300);
    let worst = plain
        .particles()
        .position
        .iter()
        .zip(&with.particles().position)
        .map(|(a, b)| (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max);
    assert!(worst < 1e-12 * d, "an indenter clear of the bed moved a sphere by {worst:e} m");
    assert_eq!(with.walls().last().unwrap().force, Vec3::zeros());
    // Lowered into the bed by 0.3 d, it is pushed back up.
    let v = 0.02;
    with.walls_mut().last_mut().unwrap().velocity = Vec3::new(0.0, 0.0, -v);
    let steps = ((0.8 * d) / (v * with.dt())).ceil() as u64;
    with.run(steps);
    let force = with.walls().last().unwrap().force;
    assert!(force[2] > 0.0, "the bed must push the indenter up: {force:?} N");
}

#[test]
fn bad_bed_files_are_refused_by_what_is_wrong() {
    let scene = soft(json!({"particle_count": 20, "die_diameter": 0.008}));
    let e = AnyEngine::build(&scene, prepare::fill(&scene).unwrap(), prepare::die(&scene)).unwrap();
    let bytes = file::encode(&e.to_file(&scene).unwrap()).unwrap();
    let err = |b: &[u8]| file::decode(b).unwrap_err().to_string();
    assert!(err(&bytes[..bytes.len() - 10]).contains("truncated"));
    let mut other = bytes.clone();
    other[8] = 9;
    assert!(err(&other).contains("format version 9"));
    // The bincode files of earlier releases are refused by name, not read as garbage.
    other[8] = 2;
    let old = err(&other);
    assert!(old.contains("format version 2") && old.contains("bincode") && old.contains("bed prepare"), "{old}");
    assert!(err(b"hello, not a bed at all").contains("magic"));
    let mut flipped = bytes.clone();
    let mid = bytes.len() / 2;
    flipped[mid] ^= 0x55;
    assert!(err(&flipped).contains("checksum"));
    assert!(file::decode(&bytes).is_ok());
    // A write that cannot happen leaves nothing behind.
    let missing = std::env::temp_dir().join("powderfmu-no-such-dir-xyz").join("bed.bed");
    assert!(file::save(&missing, &e, &scene).is_err());
    assert!(!missing.exists());
}

#[test]
fn bad_scenes_are_refused_by_name() {
    let build = |extra: Value| -> String {
        let scene = soft(extra);
        match prepare::fill(&scene)
            .map_err(|e| e.to_string())
            .and_then(|p| AnyEngine::build(&scene, p, prepare::die(&scene)).map(|_| ()).map_err(|e| e.to_string()))
        {
            Ok(()) => "ok".into(),
            Err(e) => e,
        }
    };
    // Too many spheres for the die.
    let e = build(json!({"particle_count": 100000, "die_height": 0.02}));
    assert!(e.contains("insertion impossible") && e.contains("die_height"), "{e}");
    // A time step above the stability limit.
    let e = build(json!({"time_step": 1e-3}));
    assert!(e.contains("time_step") && e.contains("stability limit"), "{e}");
    // Unknown keys, and law keys the bed sets itself.
    let e = BedScene::from_json(r#"{"particle_cuont": 5}"#).unwrap_err().to_string();
    assert!(e.contains("particle_cuont"), "{e}");
    let e = BedScene::from_json(r#"{"particle_particle": {"particle_radius": 1e-3}}"#).unwrap_err().to_string();
    assert!(e.contains("particle_radius"), "{e}");
    let e = BedScene::from_json(r#"{"particle_particle": {"particle_youngs_modulus": -5}}"#).unwrap_err().to_string();
    assert!(e.contains("particle_youngs_modulus"), "{e}");
    // What the indenter is made of: one of two names.
    let e = BedScene::from_json(r#"{"indenter_material": "steel"}"#).unwrap_err().to_string();
    assert!(e.contains("indenter_material") && e.contains("steel") && e.contains("particle, wall"), "{e}");
    let e = BedScene::from_json(r#"{"indenter_material": 1}"#).unwrap_err().to_string();
    assert!(e.contains("indenter_material") && e.contains("particle, wall"), "{e}");
}

/// 004 Sec. 5.1.3's defaults: Table 5.3's interface energy 0.5 J/m^2 is EDEM's surface energy gamma,
/// the work of adhesion Gamma = 2 gamma of 004 Eq. 3.41; the indenter is Material 1 without cohesion;
/// the friction limited as EDEM's JKR limits it.
#[test]
fn the_default_bed_reads_table_5_3_as_edem_takes_it() {
    let s = BedScene::default();
    assert_eq!(s.particle_particle["surface_energy"], json!(1.0));
    assert_eq!(s.particle_wall["surface_energy"], json!(0.0));
    let pair = s.indenter_pair();
    assert_eq!(pair["surface_energy"], json!(0.0));
    assert_eq!(pair["friction_coefficient"], json!(0.15));
    assert_eq!(pair["restitution_coefficient"], json!(0.5));
    assert_eq!(pair["wall_youngs_modulus"], json!(55e9));
    assert_eq!(pair["wall_poisson_ratio"], json!(0.25));
    assert_eq!(s.indenter_rolling_friction(), 0.1);
    // EDEM's friction limit on the JKR contacts; another law's scene does not get the key.
    assert_eq!(s.particle_particle["jkr_friction_limit"], json!("repulsive"));
    let hertz = BedScene::from_json(r#"{"particle_particle": {"contact_model": "hertz"}}"#).unwrap();
    assert!(!hertz.particle_particle.contains_key("jkr_friction_limit"));
    let given = BedScene::from_json(r#"{"particle_particle": {"jkr_friction_limit": "pull_off"}}"#).unwrap();
    assert_eq!(given.particle_particle["jkr_friction_limit"], json!("pull_off"));
    // The scene a bed file stores says it, and reads back the same.
    let again = BedScene::from_stored_json(&s.to_json().to_string()).unwrap();
    assert_eq!(again, s);
    // A bed stored before the key existed was packed with 004 Eq. 3.49's limit, and keeps it.
    let mut old = s.to_json();
    for pair in ["particle_particle", "particle_wall"] {
        old[pair].as_object_mut().unwrap().remove("jkr_friction_limit");
    }
    let loaded = BedScene::from_stored_json(&old.to_string()).unwrap();
    assert_eq!(loaded.particle_particle["jkr_friction_limit"], json!("pull_off"));
    assert_eq!(loaded.particle_wall["jkr_friction_limit"], json!("pull_off"));
}

#[test]
fn a_colliding_cloud_steps_to_the_same_bits_with_every_instruction_set_this_cpu_has() {
    // Spin, friction, adhesion and sliding: every branch of the kernel (tests/bed_isa.rs does the same
    // through the command-line tool on the shipped bed, for every law).
    let digest = |isa: Isa| {
        let mut e = cloud(vec![]);
        e.set_isa(isa).unwrap();
        assert_eq!(e.isa(), isa);
        e.run(1500);
        e.state_digest()
    };
    let baseline = digest(Isa::Baseline);
    for isa in [Isa::Avx2, Isa::Avx512] {
        if isa.available() {
            assert_eq!(digest(isa), baseline, "{}", isa.name());
        } else {
            // Not this CPU's: refused by name, and the engine keeps running the baseline.
            let mut e = cloud(vec![]);
            let refused = e.set_isa(isa).unwrap_err();
            assert!(refused.contains(isa.name()), "{refused}");
        }
    }
}

/// A changed scene on a running bed (`AnyEngine::set_scene`, behind `bed indent --change`): a pair that
/// never touched takes the changed law's initial history (Pasha's alpha_0 = 8/9 f_ce / k_e depends on the
/// interface energy), a pair that touched keeps its memory, and a change of law is refused.
#[test]
fn a_changed_scene_keeps_the_memory_and_renews_the_untouched_pairs() {
    let law =
        |gamma: f64| json!({"contact_model": "pasha", "particle_youngs_modulus": 55e6, "particle_yield_pressure": 2e6, "surface_energy": gamma});
    let scene_of = |gamma: f64| {
        BedScene::from_json(
            &json!({"particle_particle": law(gamma), "size_distribution": {"diameters": [1e-3], "frequencies": [1.0]}, "gravity": 0.0, "skin": 1e-4})
                .to_string(),
        )
        .unwrap()
    };
    let mut p = Particles::default();
    // 0 and 1 pressed together; 2 near 1 within the list's skin (0.1 mm) but apart.
    p.push(Vec3::new(0.0, 0.0, 0.0), 0.5e-3, 2456.0, 0);
    p.push(Vec3::new(0.999e-3, 0.0, 0.0), 0.5e-3, 2456.0, 0);
    p.push(Vec3::new(2.03e-3, 0.0, 0.0), 0.5e-3, 2456.0, 0);
    let mut e = AnyEngine::build(&scene_of(0.5), p, vec![]).unwrap();
    e.step();
    let slot =
        |e: &AnyEngine, i: usize, j: u32| with_engine!(e, inner => inner.list.start[i] as usize + inner.list.row(i).binary_search(&j).unwrap());
    let (touched, apart) = (slot(&e, 0, 1), slot(&e, 1, 2));
    let history = |e: &AnyEngine, k: usize| with_engine!(e, inner => format!("{:?}", inner.memory.history[k]));
    let initial = |e: &AnyEngine| with_engine!(e, inner => format!("{:?}", inner.pairs[0].initial));
    let (kept, old_initial) = (history(&e, touched), initial(&e));
    assert_eq!(history(&e, apart), old_initial, "the apart pair never touched");
    assert_ne!(kept, old_initial, "the pressed pair has a history");
    e.set_scene(&scene_of(0.0)).unwrap();
    assert_ne!(initial(&e), old_initial, "alpha_0 follows the interface energy");
    assert_eq!(history(&e, apart), initial(&e), "an untouched pair takes the changed law's initial history");
    assert_eq!(history(&e, touched), kept, "a touched pair keeps its memory");
    let hertz = BedScene::from_json(&json!({"particle_particle": {"contact_model": "hertz", "particle_youngs_modulus": 55e6}, "size_distribution": {"diameters": [1e-3], "frequencies": [1.0]}, "gravity": 0.0}).to_string()).unwrap();
    assert!(e.set_scene(&hertz).is_err(), "another law's tables do not fit this engine");
}

/// A Pasha pair (and a sphere on a floor) that let go keeps its plastic history until its surfaces are farther apart than the
/// forgetting distance, whatever the skin: beyond the skin but within the forgetting distance it stays in
/// the list at a rebuild with its memory; beyond the forgetting distance it forgets at the next force
/// loop, and the next rebuild drops it (docs/bed.md, "What a contact remembers").
#[test]
fn a_pair_forgets_at_the_forgetting_distance_not_at_the_skin() {
    let (skin, forget) = (1e-5, 1e-4);
    let scene = BedScene::from_json(
        &json!({"particle_particle": {"contact_model": "pasha", "particle_youngs_modulus": 55e6, "particle_yield_pressure": 2e6, "surface_energy": 0.5},
                "size_distribution": {"diameters": [1e-3], "frequencies": [1.0]}, "gravity": 0.0, "skin": skin, "forgetting_distance": forget})
        .to_string(),
    )
    .unwrap();
    let mut p = Particles::default();
    p.push(Vec3::new(0.0, 0.0, 0.0), 0.5e-3, 2456.0, 0);
    p.push(Vec3::new(0.995e-3, 0.0, 0.0), 0.5e-3, 2456.0, 0);
    let mut e = AnyEngine::build(&scene, p, vec![]).unwrap();
    assert_eq!(e.forgetting_distance(), forget);
    e.step();
    let history = |e: &AnyEngine| with_engine!(e, x => x.list.row(0).binary_search(&1).ok().map(|k| (format!("{:?}", x.memory.history[x.list.start[0] as usize + k]), format!("{:?}", x.pairs[0].initial))));
    let (pressed, initial) = history(&e).expect("the pressed pair is listed");
    assert_ne!(pressed, initial, "the pressed pair yielded and remembers it");
    // Apart by 5 skins, half the forgetting distance: still listed after a rebuild, still remembering.
    let place = |e: &mut AnyEngine, gap: f64| {
        with_engine!(e, x => {
            x.particles.position[1] = Vec3::new(1e-3 + gap, 0.0, 0.0);
            x.particles.velocity[1] = Vec3::new(0.0, 0.0, 0.0);
            x.particles.velocity[0] = Vec3::new(0.0, 0.0, 0.0);
        })
    };
    place(&mut e, 5e-5);
    e.rebuild();
    e.compute_forces();
    // (The law broke the contact, `established` false; its plastic memory alpha_max stays.)
    let alpha_max = |h: &str| h[h.find("alpha_max").expect("Pasha's history has alpha_max")..].to_string();
    let (apart, _) = history(&e).expect("beyond the skin, within the forgetting distance, the pair stays listed");
    assert_eq!(alpha_max(&apart), alpha_max(&pressed), "beyond the skin, within the forgetting distance, it remembers");
    assert_ne!(alpha_max(&apart), alpha_max(&initial));
    // Beyond the forgetting distance: forgotten at the force loop, dropped by the next rebuild.
    place(&mut e, 1.5e-4);
    e.compute_forces();
    assert_eq!(history(&e), Some((initial.clone(), initial.clone())), "beyond the forgetting distance the pair forgets");
    e.rebuild();
    assert_eq!(history(&e), None, "a pair that forgot and is beyond the skin leaves the list");
    // A wall contact alike: a sphere pressed on a floor, lifted beyond the skin but within the forgetting
    // distance, keeps its contact with its memory at a rebuild; lifted beyond it, forgets and is dropped.
    let mut p = Particles::default();
    p.push(Vec3::new(0.0, 0.0, 0.495e-3), 0.5e-3, 2456.0, 0);
    let floor = Wall::plane("floor", Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
    let mut w = AnyEngine::build(&scene, p, vec![floor]).unwrap();
    w.step();
    let wall_history = |e: &AnyEngine| with_engine!(e, x => x.wall_contacts[0].particle.binary_search(&0).ok().map(|k| format!("{:?}", x.wall_contacts[0].memory.history[k])));
    let on_floor = wall_history(&w).expect("the pressed sphere is in the floor's list");
    assert_ne!(alpha_max(&on_floor), alpha_max(&initial), "it yielded on the floor");
    let lift = |e: &mut AnyEngine, gap: f64| {
        with_engine!(e, x => {
            x.particles.position[0] = Vec3::new(0.0, 0.0, 0.5e-3 + gap);
            x.particles.velocity[0] = Vec3::new(0.0, 0.0, 0.0);
        })
    };
    lift(&mut w, 5e-5);
    w.rebuild();
    w.compute_forces();
    let apart = wall_history(&w).expect("beyond the skin, within the forgetting distance, the wall contact stays listed");
    assert_eq!(alpha_max(&apart), alpha_max(&on_floor));
    lift(&mut w, 1.5e-4);
    w.compute_forces();
    w.rebuild();
    assert_eq!(wall_history(&w), None, "beyond the forgetting distance the wall contact forgets and leaves the list");
    // A forgetting distance within the necks' reach is refused by name.
    let reach = with_engine!(&e, x => x.reach());
    let refused = e.set_forgetting_distance(0.5 * reach).unwrap_err();
    assert!(refused.contains("forgetting_distance"), "{refused}");
}
