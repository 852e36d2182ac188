//! ns per `field()` (potential + acceleration together) for each body, at points that exercise
//! each code path: near the surface, at the paper's separations, and far away. For the
//! polyhedron (KW4 Alpha, 9168 faces) the throughput is per face: criterion's "elem/s" is faces
//! per second, so ns per face per point is its reciprocal.

use std::hint::black_box;

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use surfgrav_potentials::{
    Ellipsoid, LengthUnit, Mesh, PointMass, Polyhedron, Potential, Sphere, Spheroid, UniformDisk,
    Vec3,
};

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

/// The ellipsoid's batched `fields_into` (four lanes at a time) against the point-by-point loop
/// it replaces (the trait's default, writing into the same buffer), ns per point over 256
/// points: the `bench_batch` points, points 0.1 to 1 body sizes above the surface (an engine's
/// nodes near contact), and KW4 Beta's surface points in Alpha's field (Alpha 766 x 747.5 x
/// 673.5 m; Beta a 300 m ball 2548 m away, its points in all directions).
fn bench_ellipsoid_fields_into(c: &mut Criterion) {
    let unit = Ellipsoid::new(1.0, 0.7, 0.4, 1.0).unwrap();
    let spread: Vec<Vec3> = (0..256)
        .map(|k| {
            let t = k as f64 / 256.0;
            let dir = Vec3::new((7.0 * t).cos(), (7.0 * t).sin(), 2.0 * t - 1.0).normalize();
            dir * (1.05 + 3.0 * t)
        })
        .collect();
    let [a, b, cc] = unit.semi_axes();
    let near: Vec<Vec3> = (0..256)
        .map(|k| {
            let t = k as f64 / 256.0;
            let dir = Vec3::new((11.0 * t).cos(), (11.0 * t).sin(), 2.0 * t - 1.0).normalize();
            let surface =
                1.0 / ((dir.x / a).powi(2) + (dir.y / b).powi(2) + (dir.z / cc).powi(2)).sqrt();
            // 0.1 to 1 body sizes (the largest semi-axis) above the surface.
            dir * (surface + a * (0.1 + 0.9 * ((17.0 * t).fract())))
        })
        .collect();
    let alpha = Ellipsoid::new(766.0, 747.5, 673.5, 2.353e12)
        .unwrap()
        .with_gravitational_constant(6.674_30e-11)
        .unwrap();
    let beta_centre = Vec3::new(2548.0 * 0.8, 2548.0 * 0.6, 40.0);
    let kw4: Vec<Vec3> = (0..256)
        .map(|k| {
            let t = (k as f64 + 0.5) / 256.0;
            let z = 1.0 - 2.0 * t;
            let phi = 2.0 * std::f64::consts::PI * (k as f64 * 0.618_033_988_749_895).fract();
            let s = (1.0 - z * z).sqrt();
            beta_centre + Vec3::new(s * phi.cos(), s * phi.sin(), z) * 300.0
        })
        .collect();
    let mut group = c.benchmark_group("batch_of_256");
    group.throughput(Throughput::Elements(256));
    for (label, body, points) in [
        ("ellipsoid", &unit, &spread),
        ("ellipsoid_near", &unit, &near),
        ("ellipsoid_kw4", &alpha, &kw4),
    ] {
        let mut out = vec![body.field(&points[0]); points.len()];
        group.bench_function(format!("{label}_point_by_point"), |bench| {
            bench.iter(|| {
                for (slot, r) in out.iter_mut().zip(black_box(points)) {
                    *slot = black_box(body).field(r);
                }
            })
        });
        group.bench_function(format!("{label}_fields_into"), |bench| {
            bench.iter(|| black_box(body).fields_into(black_box(points), &mut out))
        });
    }
    group.finish();
}

/// The disk's batched `fields_into` (the elliptic integrals of four points iterated side by
/// side) against the point-by-point loop, ns per point over 256 points: another disk's face
/// 0.05 to 0.5 radii above this one and tilted by 0.6 rad (the nodes of a disk–disk pair near
/// contact: near field, rim and axis included), and the `bench_batch` points (1.05 to 4
/// radii, near and far field mixed).
fn bench_disk_fields_into(c: &mut Criterion) {
    let disk = UniformDisk::new(1.0, 1.0).unwrap();
    let (sin, cos) = 0.6f64.sin_cos();
    let face: Vec<Vec3> = (0..256)
        .map(|k| {
            let t = (k as f64 + 0.5) / 256.0;
            let s = t.sqrt();
            let phi = 2.0 * std::f64::consts::PI * (k as f64 * 0.618_033_988_749_895).fract();
            let (x, y) = (s * phi.cos(), s * phi.sin());
            Vec3::new(0.3 + x * cos, y, 0.05 + 0.45 * t + x * sin)
        })
        .collect();
    let spread: Vec<Vec3> = (0..256)
        .map(|k| {
            let t = k as f64 / 256.0;
            let dir = Vec3::new((7.0 * t).cos(), (7.0 * t).sin(), 2.0 * t - 1.0).normalize();
            dir * (1.05 + 3.0 * t)
        })
        .collect();
    let mut group = c.benchmark_group("batch_of_256");
    group.throughput(Throughput::Elements(256));
    for (label, points) in [("disk_face", &face), ("disk_spread", &spread)] {
        let mut out = vec![disk.field(&points[0]); points.len()];
        group.bench_function(format!("{label}_point_by_point"), |bench| {
            bench.iter(|| {
                for (slot, r) in out.iter_mut().zip(black_box(points)) {
                    *slot = black_box(&disk).field(r);
                }
            })
        });
        group.bench_function(format!("{label}_fields_into"), |bench| {
            bench.iter(|| black_box(&disk).fields_into(black_box(points), &mut out))
        });
    }
    group.finish();
}

/// The spheroid's batched `fields_into` against the point-by-point loop, ns per point over
/// 256 points: the `bench_batch` points and points 0.1 to 1 body sizes above the surface, for
/// the paper's oblate spheroid (c/a = 0.25) and a prolate one (a/c = 0.25).
fn bench_spheroid_fields_into(c: &mut Criterion) {
    let mut group = c.benchmark_group("batch_of_256");
    group.throughput(Throughput::Elements(256));
    for (label, a, cc) in [
        ("spheroid_oblate", 1.0, 0.25),
        ("spheroid_prolate", 0.25, 1.0),
    ] {
        let body = Spheroid::new(a, cc, 1.0).unwrap();
        let spread: Vec<Vec3> = (0..256)
            .map(|k| {
                let t = k as f64 / 256.0;
                let dir = Vec3::new((7.0 * t).cos(), (7.0 * t).sin(), 2.0 * t - 1.0).normalize();
                dir * (1.05 + 3.0 * t)
            })
            .collect();
        let near: Vec<Vec3> = (0..256)
            .map(|k| {
                let t = k as f64 / 256.0;
                let dir = Vec3::new((11.0 * t).cos(), (11.0 * t).sin(), 2.0 * t - 1.0).normalize();
                let surface =
                    1.0 / ((dir.x / a).powi(2) + (dir.y / a).powi(2) + (dir.z / cc).powi(2)).sqrt();
                dir * (surface + 0.1 + 0.9 * ((17.0 * t).fract()))
            })
            .collect();
        for (kind, points) in [("spread", &spread), ("near", &near)] {
            let mut out = vec![body.field(&points[0]); points.len()];
            group.bench_function(format!("{label}_{kind}_point_by_point"), |bench| {
                bench.iter(|| {
                    for (slot, r) in out.iter_mut().zip(black_box(points)) {
                        *slot = black_box(&body).field(r);
                    }
                })
            });
            group.bench_function(format!("{label}_{kind}_fields_into"), |bench| {
                bench.iter(|| black_box(&body).fields_into(black_box(points), &mut out))
            });
        }
    }
    group.finish();
}

fn potentials(c: &mut Criterion) {
    bench_ellipsoid_fields_into(c);
    bench_disk_fields_into(c);
    bench_spheroid_fields_into(c);
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

fn kw4_alpha() -> Mesh {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/shapes/kw4_alpha.obj");
    Mesh::read_obj(path, LengthUnit::Kilometres).expect("the committed KW4 Alpha mesh")
}

/// The polyhedron on a real mesh: serial ns per face per point (one `field()` call) near the
/// surface and at 3 radii, the far-field expansion, a batch of 256 points serial and in
/// parallel (`Polyhedron::fields`), and construction (validation, geometry) and the moments.
fn polyhedron(c: &mut Criterion) {
    let mesh = kw4_alpha();
    let body = Polyhedron::with_density(&mesh, 1970.0).unwrap();
    let faces = body.faces().len() as u64;
    let radius = body.circumscribing_radius();
    let centre = body.centroid();
    let dir = Vec3::new(0.36, -0.48, 0.8);
    let mut group = c.benchmark_group("polyhedron_kw4_alpha_per_face");
    group.measurement_time(Duration::from_secs(4));
    group.sample_size(20);
    group.throughput(Throughput::Elements(faces));
    for (label, k) in [("r=1.05R", 1.05), ("r=3R", 3.0)] {
        let p = centre + dir * (k * radius);
        group.bench_function(label, |b| b.iter(|| black_box(&body).field(black_box(&p))));
    }
    group.finish();

    let far = centre + dir * (10.0 * radius);
    let _ = body.field(&far); // moments built outside the timing
    let mut group = c.benchmark_group("polyhedron_kw4_alpha_far");
    group.bench_function("r=10R expansion", |b| {
        b.iter(|| black_box(&body).field(black_box(&far)))
    });
    group.finish();

    let points: Vec<Vec3> = (0..256)
        .map(|k| {
            let t = k as f64 / 256.0;
            let d = Vec3::new((7.0 * t).cos(), (7.0 * t).sin(), 2.0 * t - 1.0).normalize();
            centre + d * radius * (1.05 + 3.0 * t)
        })
        .collect();
    let mut group = c.benchmark_group("polyhedron_kw4_alpha_batch_of_256");
    group.measurement_time(Duration::from_secs(6));
    group.sample_size(10);
    group.throughput(Throughput::Elements(faces * points.len() as u64));
    group.bench_function("serial", |b| {
        b.iter(|| {
            points
                .iter()
                .map(|p| black_box(&body).field(p).potential)
                .sum::<f64>()
        })
    });
    group.bench_function("parallel", |b| b.iter(|| black_box(&body).fields(&points)));
    group.finish();

    // The local expansion over KW4 Beta's ball (296.1 m) 2540 m away, at the bound the KW4
    // pair asks at 1e-10 (6e-13): construction (moment translation), one point, and 64 points
    // four at a time (the interaction's batch).
    let ball = centre + Vec3::new(2540.0, 0.0, 0.0);
    let local = body.local_expansion(&ball, 296.1, 6e-13).unwrap();
    let inside = ball + dir * 250.0;
    let mut group = c.benchmark_group("polyhedron_kw4_alpha_local");
    group.bench_function(
        format!("build N={} P={}", local.degree(), local.source_degree()),
        |b| b.iter(|| black_box(&body).local_expansion(black_box(&ball), 296.1, 6e-13)),
    );
    group.bench_function(format!("field N={}", local.degree()), |b| {
        b.iter(|| black_box(&local).field(black_box(&inside)))
    });
    let nodes: Vec<Vec3> = (0..64)
        .map(|k| ball + Vec3::new((0.3 * k as f64).cos(), (0.3 * k as f64).sin(), 0.5) * 200.0)
        .collect();
    let mut out = vec![local.field(&inside); nodes.len()];
    group.throughput(Throughput::Elements(nodes.len() as u64));
    group.bench_function(format!("fields_into 64 points N={}", local.degree()), |b| {
        b.iter(|| black_box(&local).fields_into(black_box(&nodes), &mut out))
    });
    group.finish();

    let mut group = c.benchmark_group("polyhedron_kw4_alpha_construction");
    group.sample_size(10);
    group.bench_function("validate_and_build", |b| {
        b.iter(|| Polyhedron::with_density(black_box(&mesh), 1970.0).unwrap())
    });
    group.bench_function("build_and_moments", |b| {
        b.iter(|| {
            let body = Polyhedron::with_density(black_box(&mesh), 1970.0).unwrap();
            body.field(&far)
        })
    });
    group.finish();
}

criterion_group!(benches, potentials, polyhedron);
criterion_main!(benches);
