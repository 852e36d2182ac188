//! Time per interaction (force + both torques + energy, certified to the default 1e-12) for the
//! paper's pair of oblate spheroids (a = 1, c = 0.25, m = 1, common equatorial plane) at the
//! separations of issue 3, with warm node-table caches; and the cost of a cold first call
//! (node tables built) separately; the nested doubling rule, the force-only evaluation and
//! single fixed tables beside them. Accuracy is proven by the tests, and the error of each
//! rule is printed by the `work_precision` example, not here.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use surfgrav_interaction::{Body, InteractionEngine, InteractionOptions, MethodChoice};
use surfgrav_potentials::{Pose, Spheroid, UniformDisk, Vec3};

fn paper_body() -> Body {
    Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap()
}

fn interaction(c: &mut Criterion) {
    let (a, b) = (paper_body(), paper_body());
    let pose_a = Pose::identity();
    let mut engine = InteractionEngine::default();
    let mut group = c.benchmark_group("paper_pair_1e-12");
    for separation in [2.1, 2.55, 3.0, 7.0, 30.0] {
        let pose_b = Pose::new(Vec3::new(separation, 0.0, 0.0), Vec3::zeros());
        engine.interact(&a, &pose_a, &b, &pose_b).unwrap();
        group.bench_function(format!("separation_{separation}"), |bench| {
            bench.iter(|| {
                engine
                    .interact(black_box(&a), &pose_a, black_box(&b), &pose_b)
                    .unwrap()
            })
        });
    }
    group.finish();

    // The same pair by the other rules at the same tolerance: the nested doubling rule, the
    // force-only evaluation (for integrator stages), and the cheapest single fixed tables
    // reaching the nested rule's true error (from the work_precision example's summary).
    let mut group = c.benchmark_group("paper_pair_rules_1e-12");
    let mut nested = InteractionEngine::new(InteractionOptions {
        method: MethodChoice::Nested,
        ..InteractionOptions::default()
    })
    .unwrap();
    for separation in [2.1, 2.55, 3.0, 7.0, 30.0] {
        let pose_b = Pose::new(Vec3::new(separation, 0.0, 0.0), Vec3::zeros());
        nested.interact(&a, &pose_a, &b, &pose_b).unwrap();
        group.bench_function(format!("nested_separation_{separation}"), |bench| {
            bench.iter(|| {
                nested
                    .interact(black_box(&a), &pose_a, black_box(&b), &pose_b)
                    .unwrap()
            })
        });
        group.bench_function(format!("force_only_separation_{separation}"), |bench| {
            bench.iter(|| {
                engine
                    .force(black_box(&a), &pose_a, black_box(&b), &pose_b)
                    .unwrap()
            })
        });
    }
    for (separation, transverse) in [(2.1, 17u16), (2.55, 12), (3.0, 10), (7.0, 10), (30.0, 5)] {
        let pose_b = Pose::new(Vec3::new(separation, 0.0, 0.0), Vec3::zeros());
        let mut single = InteractionEngine::new(InteractionOptions {
            method: MethodChoice::FixedLevel(transverse),
            ..InteractionOptions::default()
        })
        .unwrap();
        single.interact(&a, &pose_a, &b, &pose_b).unwrap();
        group.bench_function(
            format!("single_table_t{transverse}_separation_{separation}"),
            |bench| {
                bench.iter(|| {
                    single
                        .interact(black_box(&a), &pose_a, black_box(&b), &pose_b)
                        .unwrap()
                })
            },
        );
    }
    group.finish();

    let mut group = c.benchmark_group("paper_pair_1e-12_tilted");
    // Off the symmetry planes: B tilted and lifted, so no mirror plane halves the work.
    let pose_b = Pose::new(Vec3::new(2.4, 1.1, 0.5), Vec3::new(0.3, -0.2, 0.4));
    engine.interact(&a, &pose_a, &b, &pose_b).unwrap();
    group.bench_function("tilted_no_symmetry", |bench| {
        bench.iter(|| {
            engine
                .interact(black_box(&a), &pose_a, black_box(&b), &pose_b)
                .unwrap()
        })
    });
    group.finish();

    let mut group = c.benchmark_group("cold_first_call");
    group.bench_function("paper_pair_separation_3", |bench| {
        let pose_b = Pose::new(Vec3::new(3.0, 0.0, 0.0), Vec3::zeros());
        bench.iter(|| {
            let (a, b) = (paper_body(), paper_body());
            InteractionEngine::default()
                .interact(&a, &pose_a, &b, &pose_b)
                .unwrap()
        })
    });
    group.finish();

    let disk = || Body::disk(UniformDisk::new(1.0, 1.0).unwrap()).unwrap();
    let (da, db) = (disk(), disk());
    let pose_b = Pose::new(Vec3::new(2.5, 0.0, 0.0), Vec3::zeros());
    c.bench_function("coplanar_disks_closed_form", |bench| {
        bench.iter(|| {
            engine
                .interact(black_box(&da), &pose_a, black_box(&db), &pose_b)
                .unwrap()
        })
    });
}

criterion_group!(benches, interaction);
criterion_main!(benches);
