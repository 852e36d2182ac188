//! The engine against `tests/reference/interactions.json`: force, torques and mutual energy by
//! an independent route (volume integration of the defining formulas, Newton's theorem for
//! spheres; `tests/reference/interactions.py`). Each case is held to
//! max(10⁻¹², 10 × its stated accuracy): forces relative to |F_A|, the energy to |V|, torques
//! to max(|M|, |V|) (a torque's natural scale), and within the engine's own error estimate
//! (plus 10 × the reference's accuracy). Every case runs with the default engine and with
//! the fixed rules over each body that has a surface. Skips with a notice only if the file is
//! absent.

mod interaction_support;

use interaction_support::json::{parse, Json};
use interaction_support::*;
use surfgrav_interaction::{Body, InteractionOptions, MethodChoice, SurfaceChoice};
use surfgrav_potentials::{Ellipsoid as SolidEllipsoid, Pose, Sphere, Spheroid, UniformDisk, Vec3};

fn body(spec: &Json, g: f64) -> Body {
    let mass = spec.get("mass").number();
    match spec.get("kind").text() {
        "sphere" => Body::sphere(
            Sphere::new(spec.get("radius").number(), mass)
                .unwrap()
                .with_gravitational_constant(g)
                .unwrap(),
        )
        .unwrap(),
        "spheroid" => Body::spheroid(
            Spheroid::new(
                spec.get("equatorial_radius").number(),
                spec.get("polar_radius").number(),
                mass,
            )
            .unwrap()
            .with_gravitational_constant(g)
            .unwrap(),
        )
        .unwrap(),
        "ellipsoid" => Body::ellipsoid(
            SolidEllipsoid::new(
                spec.get("a").number(),
                spec.get("b").number(),
                spec.get("c").number(),
                mass,
            )
            .unwrap()
            .with_gravitational_constant(g)
            .unwrap(),
        )
        .unwrap(),
        "disk" => Body::disk(
            UniformDisk::new(spec.get("radius").number(), mass)
                .unwrap()
                .with_gravitational_constant(g)
                .unwrap(),
        )
        .unwrap(),
        other => panic!("unknown body kind {other}"),
    }
}

/// Checks every case of a reference file; returns the worst error and where.
fn check(text: &str) -> (f64, String) {
    let root = parse(text);
    let Json::List(cases) = root.get("cases") else {
        panic!("no cases")
    };
    assert!(!cases.is_empty());
    let mut worst: (f64, String) = (0.0, String::new());
    for case in cases {
        let label = case.get("label").text();
        let g = case.get("g").number();
        let a = body(case.get("a"), g);
        let b = body(case.get("b"), g);
        let pose_a = Pose::new(Vec3::zeros(), case.get("rotation_a").vector());
        let pose_b = Pose::new(
            case.get("position_b").vector(),
            case.get("rotation_b").vector(),
        );
        let force = case.get("force_on_a").vector();
        let torque_a = case.get("torque_on_a").vector();
        let torque_b = case.get("torque_on_b").vector();
        let energy = case.get("potential_energy").number();
        let accuracy = case.get("estimated_relative_accuracy").number();
        let allowed = (10.0 * accuracy).max(1e-12);
        let mut runs = vec![(
            "automatic",
            engine(InteractionOptions::default()).interact(&a, &pose_a, &b, &pose_b),
        )];
        for (name, surface, present) in [
            ("over A", SurfaceChoice::A, a.has_surface()),
            ("over B", SurfaceChoice::B, b.has_surface()),
        ] {
            if present {
                let mut e = engine(options(1e-12, MethodChoice::FixedRules, surface));
                runs.push((name, e.interact(&a, &pose_a, &b, &pose_b)));
            }
        }
        for (name, run) in runs {
            let r = run.unwrap_or_else(|e| panic!("{label} ({name}): {e}"));
            let v = energy.abs();
            let errs = [
                (r.force_on_a - force).norm() / force.norm(),
                (r.potential_energy - energy).abs() / v,
                (r.torque_on_a - torque_a).norm() / torque_a.norm().max(v),
                (r.torque_on_b - torque_b).norm() / torque_b.norm().max(v),
            ];
            let err = errs.iter().fold(0.0f64, |m, &e| m.max(e));
            println!(
                "{label} ({name}, {}): F {:.1e} V {:.1e} M_A {:.1e} M_B {:.1e}; estimate {:.1e}, reference {accuracy:.1e}",
                r.method, errs[0], errs[1], errs[2], errs[3], r.error_estimate
            );
            if err > worst.0 {
                worst = (err, format!("{label} ({name})"));
            }
            assert!(
                err <= allowed,
                "{label} ({name}): error {err:e} > {allowed:e}"
            );
            // The engine's own estimate is not optimistic against the independent values.
            assert!(
                err <= r.error_estimate + 10.0 * accuracy,
                "{label} ({name}): error {err:e} > estimate {:e}",
                r.error_estimate
            );
            assert!(r.error_estimate <= 1e-12);
        }
    }
    worst
}

#[test]
fn engine_matches_the_reference_interactions() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/reference/interactions.json"
    );
    let Ok(text) = std::fs::read_to_string(path) else {
        println!("NOTICE: {path} is absent; reference interaction test skipped");
        return;
    };
    let (worst, label) = check(&text);
    println!("worst: {worst:.2e} in {label}");
}

/// The reader and the checks on a hand-made file: two spheres (Newton's law, exact) and a
/// deliberately wrong copy that must fail.
#[test]
fn the_checker_reads_the_schema_and_catches_errors() {
    // Spheres of masses 2 and 3, G = 0.5, B at (3, 4, 0): F_A = G m m d / |d|³, V = −G m m / |d|.
    let file = |energy: &str| {
        format!(
            r#"{{"method": "hand", "cases": [{{"label": "two spheres", "a": {{"kind": "sphere", "radius": 1.0, "mass": 2.0}},
            "b": {{"kind": "sphere", "radius": 0.5, "mass": 3.0}}, "g": 0.5, "position_b": [3.0, 4.0, 0.0],
            "rotation_a": [0.1, 0.2, 0.3], "rotation_b": [0.0, 0.0, 0.0],
            "force_on_a": ["7.2e-2", "9.6e-2", "0.0e+00"], "torque_on_a": ["0", "0", "0"],
            "torque_on_b": ["0", "0", "0"], "potential_energy": "{energy}",
            "estimated_relative_accuracy": 1e-20, "flag": true, "none": null}}]}}"#
        )
    };
    let (worst, _) = check(&file("-6.0e-1"));
    assert!(worst <= 1e-12, "{worst:e}");
    let wrong = std::panic::catch_unwind(|| check(&file("-6.0000001e-1")));
    assert!(wrong.is_err(), "a wrong energy must fail the check");
}
