//! ns per `field()` (potential + acceleration together) for each body, at points that exercise
//! each code path: near the surface, at the paper's separations, and far away.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use surfgrav_potentials::{Ellipsoid, PointMass, Potential, Sphere, Spheroid, UniformDisk, Vec3};

fn bench_body<P: Potential>(c: &mut Criterion, name: &str, body: &P, points: &[(&str, Vec3)]) {
    let mut group = c.benchmark_group(name);
    for (label, r) in points {
        group.bench_function(*label, |b| b.iter(|| black_box(body).field(black_box(r))));
    }
    group.finish();
}

/// Throughput: ns per point over a batch of 256 independent points 1.05 to 4 sizes away (the
/// situation of a surface-integral node loop, where evaluations pipeline), reported per point.
fn bench_batch<P: Potential>(c: &mut Criterion, name: &str, body: &P, size: f64) {
    let points: Vec<Vec3> = (0..256)
        .map(|k| {
            let t = k as f64 / 256.0;
            let dir = Vec3::new((7.0 * t).cos(), (7.0 * t).sin(), 2.0 * t - 1.0).normalize();
            dir * size * (1.05 + 3.0 * t)
        })
        .collect();
    let mut group = c.benchmark_group("batch_of_256");
    group.throughput(criterion::Throughput::Elements(points.len() as u64));
    group.bench_function(name, |b| {
        b.iter(|| {
            let mut sum = Vec3::zeros();
            for r in &points {
                let f = black_box(body).field(r);
                sum += f.acceleration * f.potential;
            }
            sum
        })
    });
    group.finish();
}

fn potentials(c: &mut Criterion) {
    bench_batch(c, "sphere", &Sphere::new(1.0, 1.0).unwrap(), 1.0);
    bench_batch(
        c,
        "spheroid_oblate",
        &Spheroid::new(1.0, 0.25, 1.0).unwrap(),
        1.0,
    );
    bench_batch(
        c,
        "spheroid_prolate",
        &Spheroid::new(0.25, 1.0, 1.0).unwrap(),
        1.0,
    );
    bench_batch(
        c,
        "ellipsoid",
        &Ellipsoid::new(1.0, 0.7, 0.4, 1.0).unwrap(),
        1.0,
    );
    bench_batch(c, "uniform_disk", &UniformDisk::new(1.0, 1.0).unwrap(), 1.0);

    let points = [
        ("near", Vec3::new(0.9, 0.5, 0.3)),
        ("r=3", Vec3::new(2.0, 2.0, 0.7)),
        ("r=30", Vec3::new(20.0, 20.0, 7.0)),
        ("r=1e6", Vec3::new(6e5, 6e5, 5e5)),
        ("inside", Vec3::new(0.1, 0.2, 0.05)),
    ];
    bench_body(c, "point_mass", &PointMass::new(1.0).unwrap(), &points[..4]);
    bench_body(c, "sphere", &Sphere::new(1.0, 1.0).unwrap(), &points);
    bench_body(
        c,
        "spheroid_oblate",
        &Spheroid::new(1.0, 0.25, 1.0).unwrap(),
        &points,
    );
    bench_body(
        c,
        "spheroid_prolate",
        &Spheroid::new(0.25, 1.0, 1.0).unwrap(),
        &points,
    );
    bench_body(
        c,
        "spheroid_near_sphere",
        &Spheroid::new(1.0, 1.0 - 1e-9, 1.0).unwrap(),
        &points,
    );
    bench_body(
        c,
        "ellipsoid",
        &Ellipsoid::new(1.0, 0.7, 0.4, 1.0).unwrap(),
        &points,
    );
    let disk_points = [
        ("near", Vec3::new(0.9, 0.3, 0.1)),
        ("in_plane_outside", Vec3::new(1.5, 0.4, 0.0)),
        ("r=3", Vec3::new(2.0, 2.0, 0.7)),
        ("r=30", Vec3::new(20.0, 20.0, 7.0)),
        ("r=1e6", Vec3::new(6e5, 6e5, 5e5)),
    ];
    bench_body(
        c,
        "uniform_disk",
        &UniformDisk::new(1.0, 1.0).unwrap(),
        &disk_points,
    );

    let mut group = c.benchmark_group("construction");
    group.bench_function("spheroid", |b| {
        b.iter(|| Spheroid::new(black_box(1.0), black_box(0.25), black_box(1.0)))
    });
    group.bench_function("ellipsoid", |b| {
        b.iter(|| {
            Ellipsoid::new(
                black_box(1.0),
                black_box(0.7),
                black_box(0.4),
                black_box(1.0),
            )
        })
    });
    group.finish();
}

criterion_group!(benches, potentials);
criterion_main!(benches);
