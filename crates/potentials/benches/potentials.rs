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

fn potentials(c: &mut Criterion) {
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
