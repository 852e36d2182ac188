//! The issue-13 targets, certified 1e-10: the Didymos standard pair (1,996-face radar primary
//! with the triaxial secondary 103.6778 × 79.7526 × 66.4605 m, both 2103.98576788771879 kg/m³,
//! 1180 m apart, G = 6.67408e-11) and the KW4 pair (Alpha 9168 faces at 1970 kg/m³, Beta 2292
//! faces at 2810 kg/m³, 2540 m apart). Prints, per pair and surface, the time per evaluation,
//! the field evaluations, the estimate, and the error against a reference at 1e-13 over the
//! same surface and over the other surface.
//!
//! `cargo run --release -p surfgrav-interaction --example polyhedron_pairs` (`RAYON_NUM_THREADS=1`
//! for the serial cost; CPU time is printed beside wall time, the mesh rule's node loop runs
//! in parallel over chunks of faces).
//!
//! `-- --field-cost` measures one field evaluation (`Potential::field`, serial) of each
//! polyhedron and of a homogeneous spheroid and a triaxial ellipsoid of the same size, at
//! 1.05 to 12 circumscribing radii, and prints the ratio to the spheroid's and the
//! polyhedron's ns per face: the figures behind `Polyhedron`'s `Potential::field_cost`.

use std::path::PathBuf;
use std::time::Instant;
use surfgrav_interaction::{
    Body, Interaction, InteractionEngine, InteractionOptions, SurfaceChoice,
};
use surfgrav_potentials::{
    Ellipsoid, LengthUnit, Mesh, Polyhedron, Pose, Potential, Spheroid, Vec3,
};

const G: f64 = 6.67408e-11;

fn shapes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/shapes")
}

/// CPU seconds of this process so far (user + system, /proc/self/stat; clock ticks of 10 ms):
/// a machine shared with other work inflates wall time, not this.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit(')').next().unwrap_or("");
    let fields: Vec<&str> = after.split_whitespace().collect();
    let tick = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    // Fields 14 and 15 of the file (utime, stime) are 11 and 12 after the command name.
    (tick(11) + tick(12)) / 100.0
}

fn error(r: &Interaction, reference: &Interaction) -> f64 {
    let v = reference.potential_energy.abs();
    let df = (r.force_on_a - reference.force_on_a).norm() / reference.force_on_a.norm();
    let dv = (r.potential_energy - reference.potential_energy).abs() / v;
    let dma = (r.torque_on_a - reference.torque_on_a).norm() / reference.torque_on_a.norm().max(v);
    let dmb = (r.torque_on_b - reference.torque_on_b).norm() / reference.torque_on_b.norm().max(v);
    df.max(dv).max(dma).max(dmb)
}

fn run(name: &str, a: &Body, b: &Body, pose_b: &Pose) {
    let pose_a = Pose::identity();
    for surface in [SurfaceChoice::Automatic, SurfaceChoice::A, SurfaceChoice::B] {
        let options = |tol: f64, surface| InteractionOptions {
            relative_tolerance: tol,
            surface,
            ..InteractionOptions::default()
        };
        let mut engine = InteractionEngine::new(options(1e-10, surface)).unwrap();
        let first = Instant::now();
        let r = match engine.interact(a, &pose_a, b, pose_b) {
            Ok(r) => r,
            Err(e) => {
                println!("{name} {surface:?}: {e}");
                continue;
            }
        };
        let first = first.elapsed();
        // Enough repeats for 0.5 s of work: the CPU clock ticks every 10 ms.
        let t = Instant::now();
        engine.interact(a, &pose_a, b, pose_b).unwrap();
        let once = t.elapsed().as_secs_f64();
        let repeats = ((0.5 / once.max(1e-6)).ceil() as u32).clamp(10, 2000);
        let t = Instant::now();
        let cpu = cpu_seconds();
        for _ in 0..repeats {
            engine.interact(a, &pose_a, b, pose_b).unwrap();
        }
        let per = t.elapsed() / repeats;
        let cpu_per = (cpu_seconds() - cpu) / repeats as f64;
        let mut reference = InteractionEngine::new(options(1e-13, surface)).unwrap();
        let fine = reference.interact(a, &pose_a, b, pose_b);
        let mut other = InteractionEngine::new(options(
            1e-13,
            match r.integrated_over {
                Some(surfgrav_interaction::Side::A) => SurfaceChoice::B,
                _ => SurfaceChoice::A,
            },
        ))
        .unwrap();
        let across = other.interact(a, &pose_a, b, pose_b);
        println!(
            "{name} {surface:?}: over {:?} ({}), {:.2} ms wall, {:.2} ms CPU per evaluation ({repeats} repeats; first {:.1} ms wall), {} evaluations, level {:?}, estimate {:.2e}",
            r.integrated_over,
            r.method,
            per.as_secs_f64() * 1e3,
            cpu_per * 1e3,
            first.as_secs_f64() * 1e3,
            r.evaluations,
            r.level,
            r.error_estimate
        );
        match fine {
            Ok(f) => println!(
                "    vs 1e-13 same surface: {:.2e} (its estimate {:.1e}, {} evaluations)",
                error(&r, &f),
                f.error_estimate,
                f.evaluations
            ),
            Err(e) => println!("    reference same surface: {e}"),
        }
        match across {
            Ok(f) => println!(
                "    vs 1e-13 other surface: {:.2e}; V_AB - V_BA: {:.2e} relative; F {:?} M_A {:?} V {:e}",
                error(&r, &f),
                (r.potential_energy - f.potential_energy).abs() / f.potential_energy.abs(),
                r.force_on_a.as_slice(),
                r.torque_on_a.as_slice(),
                r.potential_energy
            ),
            Err(e) => println!("    reference other surface: {e}"),
        }
    }
}

/// Serial ns per `field` call of `body` over `points` (best of five passes: the machine is
/// shared, the fastest pass is the least disturbed).
fn ns_per_field(body: &dyn Potential, points: &[Vec3]) -> f64 {
    let mut best = f64::INFINITY;
    let mut sink = 0.0;
    for _ in 0..5 {
        let t = Instant::now();
        for p in points {
            sink += body.field(p).potential;
        }
        best = best.min(t.elapsed().as_secs_f64() * 1e9 / points.len() as f64);
    }
    assert!(sink.is_finite());
    best
}

/// Points at `radii` circumscribing radii from the centroid, in a fixed spread of directions.
fn shell(centre: &Vec3, radius: f64, radii: f64, count: usize) -> Vec<Vec3> {
    // Fibonacci sphere: deterministic and even.
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = golden * i as f64;
            centre + Vec3::new(r * phi.cos(), r * phi.sin(), z) * (radius * radii)
        })
        .collect()
}

/// The `--field-cost` table (module docs).
fn field_cost(polyhedra: &[(&str, &Polyhedron)]) {
    println!("field cost: ns per Potential::field (serial, best of 5), ratio to the spheroid's");
    println!("| body | faces | radii | ns | ns/face | / spheroid | / ellipsoid | spheroid ns | ellipsoid ns |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (name, p) in polyhedra {
        let radius = p.circumscribing_radius();
        let mass = p.mass();
        let spheroid = Spheroid::new(radius, 0.6 * radius, mass)
            .unwrap()
            .with_gravitational_constant(G)
            .unwrap();
        let ellipsoid = Ellipsoid::new(radius, 0.8 * radius, 0.6 * radius, mass)
            .unwrap()
            .with_gravitational_constant(G)
            .unwrap();
        let faces = p.faces().len();
        for radii in [1.05, 1.5, 2.5, 5.0, 7.0, 12.0] {
            let count = (2_000_000 / faces).clamp(200, 20_000);
            let points = shell(&p.centroid(), radius, radii, count);
            let at_origin = shell(&Vec3::zeros(), radius, radii, 20_000);
            let ns = ns_per_field(*p, &points);
            let s = ns_per_field(&spheroid, &at_origin);
            let e = ns_per_field(&ellipsoid, &at_origin);
            println!(
                "| {name} | {faces} | {radii} | {ns:.0} | {:.1} | {:.1} | {:.1} | {s:.0} | {e:.0} |",
                ns / faces as f64,
                ns / s,
                ns / e
            );
        }
    }
}

fn main() {
    let didymos = Mesh::read_vertex_facet_csv(
        shapes().join("Didymos_A_vert_met.csv"),
        shapes().join("Didymos_A_facet.csv"),
        LengthUnit::Metres,
    )
    .unwrap();
    // The published 2103.98576788771879 kg/m³ to double precision.
    let density = 2_103.985_767_887_719;
    let primary = Polyhedron::with_density(&didymos, density)
        .unwrap()
        .with_gravitational_constant(G)
        .unwrap();
    println!(
        "Didymos: {} faces, circumscribing radius {:.1} m",
        primary.faces().len(),
        primary.circumscribing_radius()
    );
    let max_x = primary
        .vertices()
        .iter()
        .map(|v| v.x)
        .fold(f64::NEG_INFINITY, f64::max);
    let didymos_polyhedron = primary.clone();
    let primary = Body::polyhedron(primary).unwrap();
    let secondary = Body::ellipsoid(
        Ellipsoid::with_density(103.6778, 79.7526, 66.4605, density)
            .unwrap()
            .with_gravitational_constant(G)
            .unwrap(),
    )
    .unwrap();
    if std::env::args().any(|a| a == "--near") {
        let pose = Pose::new(Vec3::new(max_x + 103.6778 * 1.05, 0.0, 0.0), Vec3::zeros());
        near(
            "Didymos near contact",
            &primary,
            &secondary,
            &pose,
            &[1e-10, 1e-12],
        );
    }
    let pose = Pose::new(Vec3::new(1180.0, 0.0, 0.0), Vec3::zeros());
    if std::env::args().any(|a| a == "--levels") {
        levels("Didymos", &primary, &secondary, &pose, SurfaceChoice::A);
    }
    if std::env::args().any(|a| a == "--work-precision") {
        work_precision("Didymos", &primary, &secondary, &pose);
    }
    if !std::env::args().any(|a| a == "--field-cost") {
        run("Didymos", &primary, &secondary, &pose);
    }

    let alpha = Mesh::read_obj(shapes().join("kw4_alpha.obj"), LengthUnit::Kilometres).unwrap();
    let beta = Mesh::read_obj(shapes().join("kw4_beta.obj"), LengthUnit::Kilometres).unwrap();
    let alpha = Polyhedron::with_density(&alpha, 1970.0)
        .unwrap()
        .with_gravitational_constant(G)
        .unwrap();
    let beta = Polyhedron::with_density(&beta, 2810.0)
        .unwrap()
        .with_gravitational_constant(G)
        .unwrap();
    println!(
        "KW4: Alpha R = {:.1} m, Beta R = {:.1} m",
        alpha.circumscribing_radius(),
        beta.circumscribing_radius()
    );
    if std::env::args().any(|a| a == "--field-cost") {
        field_cost(&[
            ("Didymos", &didymos_polyhedron),
            ("KW4 Beta", &beta),
            ("KW4 Alpha", &alpha),
        ]);
        return;
    }
    let alpha = Body::polyhedron(alpha).unwrap();
    let beta = Body::polyhedron(beta).unwrap();
    if std::env::args().any(|a| a == "--near") {
        let pose = Pose::new(Vec3::new(0.6, 0.0, 0.8) * 1800.0, Vec3::new(-0.5, 0.1, 0.9));
        near("KW4 1800 m", &alpha, &beta, &pose, &[1e-10, 1e-13]);
        return;
    }
    let pose = Pose::new(Vec3::new(2540.0, 0.0, 0.0), Vec3::zeros());
    if std::env::args().any(|a| a == "--levels") {
        levels("KW4", &alpha, &beta, &pose, SurfaceChoice::B);
        levels("KW4", &alpha, &beta, &pose, SurfaceChoice::A);
    }
    if std::env::args().any(|a| a == "--work-precision") {
        work_precision("KW4", &alpha, &beta, &pose);
    }
    run("KW4", &alpha, &beta, &pose);
}

/// Error against cost with the automatic choice: per tolerance the evaluations, CPU ms per
/// interaction, the estimate and the true error against the reference over the other surface
/// at 1e-13 (an independent route: the other body's field over this body's surface).
pub fn work_precision(name: &str, a: &Body, b: &Body, pose_b: &Pose) {
    let pose_a = Pose::identity();
    let options = |tol: f64, surface| InteractionOptions {
        relative_tolerance: tol,
        surface,
        ..InteractionOptions::default()
    };
    let mut engine = InteractionEngine::new(options(1e-10, SurfaceChoice::Automatic)).unwrap();
    let chosen = engine
        .interact(a, &pose_a, b, pose_b)
        .unwrap()
        .integrated_over;
    let other = match chosen {
        Some(surfgrav_interaction::Side::A) => SurfaceChoice::B,
        _ => SurfaceChoice::A,
    };
    let reference = InteractionEngine::new(options(1e-13, other))
        .unwrap()
        .interact(a, &pose_a, b, pose_b)
        .unwrap();
    println!(
        "{name}: work-precision over {chosen:?}, reference over {other:?} at 1e-13 (estimate {:.1e}, {} evaluations)",
        reference.error_estimate, reference.evaluations
    );
    println!("| tolerance | evaluations | CPU ms | estimate | true error |");
    for tol in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
        let mut engine = InteractionEngine::new(options(tol, SurfaceChoice::Automatic)).unwrap();
        let r = match engine.interact(a, &pose_a, b, pose_b) {
            Ok(r) => r,
            Err(e) => {
                println!("| {tol:.0e} | {e} |");
                continue;
            }
        };
        let t = Instant::now();
        engine.interact(a, &pose_a, b, pose_b).unwrap();
        let once = t.elapsed().as_secs_f64();
        let repeats = ((0.5 / once.max(1e-6)).ceil() as u32).clamp(3, 2000);
        let cpu = cpu_seconds();
        for _ in 0..repeats {
            engine.interact(a, &pose_a, b, pose_b).unwrap();
        }
        let cpu_per = (cpu_seconds() - cpu) / repeats as f64;
        println!(
            "| {tol:.0e} | {} | {:.2} | {:.1e} | {:.1e} |",
            r.evaluations,
            cpu_per * 1e3,
            r.error_estimate,
            error(&r, &reference)
        );
    }
}

#[allow(dead_code)]
pub fn levels(name: &str, a: &Body, b: &Body, pose_b: &Pose, surface: SurfaceChoice) {
    let pose_a = Pose::identity();
    let mut reference = InteractionEngine::new(InteractionOptions {
        relative_tolerance: 1e-13,
        surface,
        ..InteractionOptions::default()
    })
    .unwrap();
    let reference = reference.interact(a, &pose_a, b, pose_b).unwrap();
    for level in 0..5u16 {
        let mut e = InteractionEngine::new(InteractionOptions {
            method: surfgrav_interaction::MethodChoice::FixedLevel(level),
            surface,
            ..InteractionOptions::default()
        })
        .unwrap();
        let t = Instant::now();
        let r = e.interact(a, &pose_a, b, pose_b).unwrap();
        println!(
            "  {name} {surface:?} level {level}: {} evaluations, {:.1} ms, true error {:.2e}",
            r.evaluations,
            t.elapsed().as_secs_f64() * 1e3,
            error(&r, &reference)
        );
    }
}

/// Near contact: the Didymos standard pair with the secondary's tip 0.05 × 103.6778 m beyond
/// the mesh's largest x, and the KW4 pair 1800 m apart (as the ignored test): per tolerance the
/// surface, evaluations, level, estimate and CPU time, and the true error against the other
/// surface at 1e-13.
pub fn near(name: &str, a: &Body, b: &Body, pose_b: &Pose, tols: &[f64]) {
    let pose_a = Pose::identity();
    let options = |tol: f64, surface| InteractionOptions {
        relative_tolerance: tol,
        surface,
        ..InteractionOptions::default()
    };
    for surface in [SurfaceChoice::Automatic, SurfaceChoice::A, SurfaceChoice::B] {
        for &tol in tols {
            let mut engine = InteractionEngine::new(options(tol, surface)).unwrap();
            let cpu = cpu_seconds();
            let r = match engine.interact(a, &pose_a, b, pose_b) {
                Ok(r) => r,
                Err(e) => {
                    println!("{name} {surface:?} {tol:.0e}: {e}");
                    continue;
                }
            };
            let cpu = cpu_seconds() - cpu;
            let other = match r.integrated_over {
                Some(surfgrav_interaction::Side::A) => SurfaceChoice::B,
                _ => SurfaceChoice::A,
            };
            let reference = InteractionEngine::new(options(1e-13, other))
                .unwrap()
                .interact(a, &pose_a, b, pose_b);
            let truth = reference.as_ref().map(|f| error(&r, f)).unwrap_or(f64::NAN);
            println!(
                "{name} {surface:?} {tol:.0e}: over {:?}, {} evaluations, level {:?}, estimate {:.2e}, true {truth:.2e}, {:.1} ms CPU (first call)",
                r.integrated_over,
                r.evaluations,
                r.level,
                r.error_estimate,
                cpu * 1e3
            );
        }
    }
}
