//! Work–precision of the interaction engine for the founding paper's pair: two oblate
//! spheroids (a = 1, c = 0.25, m = 1, G = 1) in a common equatorial plane, centres on the x
//! axis, at separations 2.1, 2.55, 3, 7 and 30.
//!
//! For each separation it prints, as markdown tables, the relative error of the force and of
//! the energy against reference values, and the time per evaluation (one core, best of five
//! batches), for: single tables of the ladder in both parametrisations (azimuth–height and
//! polar-angle), the certified ladder at several tolerances (the engine's default method), and
//! the adaptive cubature. Reference values come from `tests/reference/interactions.json` when
//! it holds the case (an independent volume integration), otherwise from the engine's own
//! ladder converged to its rounding floor (said so in the output). It ends with the cost of
//! dynamic dispatch in the node loop.
//!
//! Run with `cargo run --release -p surfgrav-surfaces --example work_precision`.

#[path = "../tests/interaction_support/json.rs"]
mod json;

use std::hint::black_box;
use std::sync::Arc;
use std::time::Instant;
use surfgrav_potentials::{Pose, Potential, Spheroid, Vec3};
use surfgrav_quadrature::{GaussLegendre, Rule1D};
use surfgrav_surfaces::interaction::{
    integrate_over_solid, rules::azimuth_rule, Body, BodyShape, FrameMap, Interaction,
    InteractionEngine, InteractionError, InteractionOptions, MethodChoice, Parametrisation,
};
use surfgrav_surfaces::{Ellipsoid, Interval, Rule1d, SurfaceNodes};

const SEPARATIONS: [f64; 5] = [2.1, 2.55, 3.0, 7.0, 30.0];

/// Best time per call over five batches of at least 20 ms each, in microseconds.
fn time<F: FnMut()>(mut f: F) -> f64 {
    let mut reps = 1usize;
    loop {
        let t = Instant::now();
        for _ in 0..reps {
            f();
        }
        if t.elapsed().as_secs_f64() > 0.02 {
            break;
        }
        reps *= 2;
    }
    (0..5)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                f();
            }
            t.elapsed().as_secs_f64() / reps as f64 * 1e6
        })
        .fold(f64::INFINITY, f64::min)
}

struct Reference {
    force: Vec3,
    energy: f64,
    source: &'static str,
}

fn json_reference(d: f64) -> Option<Reference> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/reference/interactions.json"
    );
    let text = std::fs::read_to_string(path).ok()?;
    let root = json::parse(&text);
    let json::Json::List(cases) = root.get("cases") else {
        return None;
    };
    cases.iter().find_map(|case| {
        let is_paper = |body: &json::Json| {
            body.get("kind").text() == "spheroid"
                && body.get("equatorial_radius").number() == 1.0
                && body.get("polar_radius").number() == 0.25
                && body.get("mass").number() == 1.0
        };
        let position = case.get("position_b").vector();
        let rest = case.get("rotation_a").vector().norm() + case.get("rotation_b").vector().norm();
        (is_paper(case.get("a"))
            && is_paper(case.get("b"))
            && case.get("g").number() == 1.0
            && position == Vec3::new(d, 0.0, 0.0)
            && rest == 0.0)
            .then(|| Reference {
                force: case.get("force_on_a").vector(),
                energy: case.get("potential_energy").number(),
                source: "tests/reference/interactions.json (volume integration)",
            })
    })
}

fn run(options: InteractionOptions, a: &Body, b: &Body, pose_b: &Pose) -> Interaction {
    let mut e = InteractionEngine::new(options).expect("valid options");
    match e.interact(a, &Pose::identity(), b, pose_b) {
        Ok(r) => r,
        Err(InteractionError::ToleranceNotMet { best, .. }) => *best,
        Err(err) => panic!("{err}"),
    }
}

fn main() {
    let a = Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap();
    let b = Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap();
    let mut summary = vec![];
    for d in SEPARATIONS {
        let pose_b = Pose::new(Vec3::new(d, 0.0, 0.0), Vec3::zeros());
        let reference = json_reference(d).unwrap_or_else(|| {
            let r = run(
                InteractionOptions { relative_tolerance: 1e-15, max_evaluations: 50_000_000, ..Default::default() },
                &a,
                &b,
                &pose_b,
            );
            Reference {
                force: r.force_on_a,
                energy: r.potential_energy,
                source: "the engine's ladder converged to its rounding floor (no independent value yet)",
            }
        });
        println!("\n### Separation {d}\n\nReference: {}.\n", reference.source);
        println!(
            "| method | evaluations | µs / evaluation | force error | energy error | estimate |"
        );
        println!("|---|---:|---:|---:|---:|---:|");
        let row = |label: String, options: InteractionOptions| {
            let r = run(options, &a, &b, &pose_b);
            let micros = time(|| {
                black_box(run(options, &a, &b, &pose_b));
            });
            let ef = (r.force_on_a - reference.force).norm() / reference.force.norm();
            let ev = ((r.potential_energy - reference.energy) / reference.energy).abs();
            println!(
                "| {label} | {} | {micros:.1} | {ef:.1e} | {ev:.1e} | {:.1e} |",
                r.evaluations, r.error_estimate
            );
            (r, micros, ef.max(ev))
        };
        for (name, parametrisation, levels) in [
            (
                "AH",
                Parametrisation::AzimuthHeight,
                [2u16, 4, 6, 8, 10, 13, 16, 20],
            ),
            (
                "PA",
                Parametrisation::PolarAzimuth,
                [2u16, 4, 6, 8, 10, 13, 16, 20],
            ),
        ] {
            for t in levels {
                row(
                    format!("{name} single table, t = {t}"),
                    InteractionOptions {
                        method: MethodChoice::FixedLevel(t),
                        parametrisation,
                        ..Default::default()
                    },
                );
            }
        }
        let mut certified = None;
        for (name, parametrisation) in [
            ("AH", Parametrisation::AzimuthHeight),
            ("PA", Parametrisation::PolarAzimuth),
        ] {
            for tolerance in [1e-6, 1e-9, 1e-12] {
                let (_, micros, err) = row(
                    format!("{name} ladder, tolerance {tolerance:.0e}"),
                    InteractionOptions {
                        relative_tolerance: tolerance,
                        parametrisation,
                        ..Default::default()
                    },
                );
                if name == "AH" && tolerance == 1e-12 {
                    certified = Some((micros, err));
                }
            }
        }
        let mut adaptive = None;
        for tolerance in [1e-6, 1e-9, 1e-12] {
            let (r, micros, err) = row(
                format!("adaptive, tolerance {tolerance:.0e}"),
                InteractionOptions {
                    relative_tolerance: tolerance,
                    method: MethodChoice::Adaptive,
                    ..Default::default()
                },
            );
            if tolerance == 1e-12 {
                adaptive = Some((micros, err, r.evaluations));
            }
        }
        summary.push((d, certified, adaptive));
    }
    println!("\n### Summary: force + torque + energy to 10⁻¹² (certified)\n");
    println!("| separation | ladder µs | ladder error | adaptive µs | adaptive error | adaptive / ladder |");
    println!("|---:|---:|---:|---:|---:|---:|");
    for (d, certified, adaptive) in summary {
        let (lt, le) = certified.unwrap_or((f64::NAN, f64::NAN));
        let (at, ae, _) = adaptive.unwrap_or((f64::NAN, f64::NAN, 0));
        println!(
            "| {d} | {lt:.1} | {le:.1e} | {at:.1} | {ae:.1e} | {:.1} |",
            at / lt
        );
    }

    // Dynamic dispatch: the same node loop over one table, monomorphised for `Spheroid` and
    // through `dyn Potential`.
    let shape = Ellipsoid::spheroid(1.0, 0.25).unwrap();
    let (phi, w) = azimuth_rule(40, 0.8, false);
    let g = GaussLegendre::new(24, -0.25, 0.25).unwrap();
    let table = SurfaceNodes::with_periodic_rule(
        &shape.azimuth_height(),
        Rule1d::new(&phi, &w, Interval::FULL_TURN).unwrap(),
        Rule1d::new(g.nodes(), g.weights(), Interval::new(-0.25, 0.25).unwrap()).unwrap(),
    )
    .unwrap();
    let spheroid = Spheroid::new(1.0, 0.25, 1.0).unwrap();
    let dynamic: Arc<dyn Potential> = Arc::new(spheroid);
    let map = FrameMap::between(
        &Pose::identity(),
        &Pose::new(Vec3::new(3.0, 0.0, 0.0), Vec3::zeros()),
    )
    .unwrap();
    let density = 1.0 / shape.volume();
    // Interleaved rounds, best of each (the machine's clock varies between runs).
    let (mut generic, mut dispatched) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..5 {
        generic = generic.min(time(|| {
            black_box(integrate_over_solid(&table, density, &spheroid, &map));
        }));
        dispatched = dispatched.min(time(|| {
            black_box(integrate_over_solid(
                &table,
                density,
                dynamic.as_ref(),
                &map,
            ));
        }));
    }
    println!(
        "\nNode loop over {} nodes: {:.1} ns/node monomorphised, {:.1} ns/node through dyn Potential ({:+.1} %).",
        table.len(),
        generic * 1e3 / table.len() as f64,
        dispatched * 1e3 / table.len() as f64,
        (dispatched / generic - 1.0) * 100.0
    );
    let custom = Body::custom(dynamic, BodyShape::Solid(shape)).unwrap();
    let pose_b = Pose::new(Vec3::new(3.0, 0.0, 0.0), Vec3::zeros());
    let builtin_time = time(|| {
        black_box(run(InteractionOptions::default(), &a, &b, &pose_b));
    });
    // Over A, so the custom field is what the loop evaluates: dynamic dispatch per node and no
    // symmetry known for a user's field (all nodes evaluated).
    let over_a = InteractionOptions {
        surface: surfgrav_surfaces::interaction::SurfaceChoice::A,
        ..Default::default()
    };
    let custom_time = time(|| {
        black_box(run(over_a, &a, &custom, &pose_b));
    });
    let no_symmetry = InteractionOptions {
        exploit_symmetry: false,
        ..over_a
    };
    let builtin_no_symmetry = time(|| {
        black_box(run(no_symmetry, &a, &b, &pose_b));
    });
    println!(
        "Engine at separation 3, over A: built-in B {builtin_time:.1} µs; built-in B without the mirror symmetries {builtin_no_symmetry:.1} µs; the same spheroid as a custom B (dyn, no symmetry known) {custom_time:.1} µs."
    );
}
