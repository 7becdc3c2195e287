//! One normal-force evaluation per law, on the states of a realistic impact: each law is walked once
//! through load, unload, detachment, re-contact and reload on 004 Table 4.1's ammonium fluorescein
//! sphere on silicon, and the bench evaluates the law at all 256 recorded (overlap, history) pairs.
//! `benches/laws_table.py` turns the medians into the table of docs/benchmarks.md.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use powderfmu::law::{AnyLaw, NormalLaw};
use powderfmu::scene::{ModelKind, Scene};
use std::time::Duration;

const STATES: usize = 256;

fn scene(model: ModelKind) -> Scene {
    let mut s = Scene::new(model, 2.45e-6, 1350.0, 1.2e9, 0.3);
    s.wall_youngs_modulus = Some(182e9);
    s.particle_yield_pressure = Some(35.3e6);
    s.surface_energy = 0.2;
    s
}

/// The (overlap, history) pairs of one load / unload / detach / re-contact / reload cycle.
fn states<L: NormalLaw>(law: &L, radius: f64) -> Vec<(f64, L::History)> {
    let peak = 0.03 * radius;
    let turns = [peak, -0.004 * radius, 0.6 * peak, 0.2 * peak, 1.2 * peak];
    let per_leg = STATES / turns.len() + 1;
    let mut h = law.initial_history();
    let mut alpha = 0.0;
    let mut out = Vec::with_capacity(STATES);
    for target in turns {
        let start = alpha;
        for i in 1..=per_leg {
            alpha = start + (target - start) * i as f64 / per_leg as f64;
            out.push((alpha, h));
            h = law.evaluate(alpha, &h).history;
        }
    }
    out.truncate(STATES);
    out
}

fn bench_one<L: NormalLaw>(c: &mut Criterion, name: &str, law: &L) {
    let st = states(law, 2.45e-6);
    let mut group = c.benchmark_group("force_evaluation");
    group.throughput(Throughput::Elements(STATES as u64));
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    group.sample_size(40);
    group.bench_function(name, |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for (alpha, h) in &st {
                sum += law.evaluate(black_box(*alpha), black_box(h)).force;
            }
            sum
        })
    });
    group.finish();
}

fn laws(c: &mut Criterion) {
    for model in ModelKind::ALL {
        let law = AnyLaw::from_scene(&scene(model)).expect("Table 4.1 builds every law");
        // The concrete law, as the DEM engine will call it (no enum dispatch).
        match &law {
            AnyLaw::Nan(l) => bench_one(c, model.name(), l),
            AnyLaw::Pasha(l) => bench_one(c, model.name(), l),
            AnyLaw::PashaSimplified(l) => bench_one(c, model.name(), l),
            AnyLaw::Luding(l) => bench_one(c, model.name(), l),
            AnyLaw::ThorntonNing(l) => bench_one(c, model.name(), l),
            AnyLaw::Tomas(l) => bench_one(c, model.name(), l),
            AnyLaw::Hertz(l) => bench_one(c, model.name(), l),
            AnyLaw::Jkr(l) => bench_one(c, model.name(), l),
            AnyLaw::JkrModified(l) => bench_one(c, model.name(), l),
            AnyLaw::Linear(l) => bench_one(c, model.name(), l),
            AnyLaw::WaltonBraun(l) => bench_one(c, model.name(), l),
        }
    }
    // The run-time dispatch the FMUs use, on the main law.
    let any = AnyLaw::from_scene(&scene(ModelKind::Nan)).unwrap();
    bench_one(c, "nan_via_any_law", &any);
}

criterion_group!(benches, laws);
criterion_main!(benches);
