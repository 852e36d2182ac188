//! The error estimate is not optimistic: for every method, parametrisation and requested
//! tolerance, the true error (against values converged far beyond it) is at most the
//! estimate, and the estimate meets the tolerance. Also snapshots of the evaluation counts
//! for the founding paper's pair, so that silent changes of the ladder show.

mod interaction_support;

use interaction_support::*;
use surfgrav_interaction::{
    Body, Interaction, InteractionOptions, MethodChoice, Parametrisation, SurfaceChoice,
};
use surfgrav_potentials::{Ellipsoid as SolidEllipsoid, Pose, Spheroid, UniformDisk};

struct Case {
    label: &'static str,
    a: Body,
    b: Body,
    pose_a: Pose,
    pose_b: Pose,
}

fn cases() -> Vec<Case> {
    let prolate = || Body::spheroid(Spheroid::new(0.5, 1.2, 0.8).unwrap()).unwrap();
    let triaxial = |a, b, c, m| Body::ellipsoid(SolidEllipsoid::new(a, b, c, m).unwrap()).unwrap();
    let mut cases = vec![];
    for (label, d) in [
        ("paper pair, gap 0.05", 2.05),
        ("paper pair 2.1", 2.1),
        ("paper pair 3", 3.0),
        ("paper pair 7", 7.0),
        ("paper pair 30", 30.0),
    ] {
        cases.push(Case {
            label,
            a: paper_spheroid(),
            b: paper_spheroid(),
            pose_a: Pose::identity(),
            pose_b: pose([d, 0.0, 0.0], [0.0; 3]),
        });
    }
    cases.push(Case {
        label: "paper pair tilted and rotated",
        a: paper_spheroid(),
        b: paper_spheroid(),
        pose_a: pose([0.0; 3], [0.1, 0.3, -0.2]),
        pose_b: pose([2.2, 0.3, 0.5], [0.6, -0.2, 0.4]),
    });
    cases.push(Case {
        label: "oblate and prolate",
        a: paper_spheroid(),
        b: prolate(),
        pose_a: Pose::identity(),
        pose_b: pose([1.6, 0.6, 1.1], [0.0, 0.8, 0.0]),
    });
    cases.push(Case {
        label: "disk above a spheroid",
        a: Body::disk(UniformDisk::new(0.8, 0.5).unwrap()).unwrap(),
        b: paper_spheroid(),
        pose_a: pose([0.2, -0.1, 0.6], [0.2, 0.1, 0.0]),
        pose_b: Pose::identity(),
    });
    cases.push(Case {
        label: "triaxial pair",
        a: triaxial(1.0, 0.6, 0.3, 1.0),
        b: triaxial(0.8, 0.7, 0.5, 1.5),
        pose_a: pose([0.0; 3], [0.3, 0.2, 0.1]),
        pose_b: pose([1.5, 1.2, -0.4], [-0.5, 0.9, 0.3]),
    });
    cases
}

fn reference(case: &Case) -> Interaction {
    let mut fine = engine(InteractionOptions {
        relative_tolerance: 1e-14,
        method: MethodChoice::FixedRules,
        ..InteractionOptions::default()
    });
    let r = best_effort(&mut fine, &case.a, &case.pose_a, &case.b, &case.pose_b);
    // Far apart, the force's rounding floor (its terms cancel 100-fold) limits the reference.
    assert!(
        r.error_estimate <= 1e-12,
        "{}: reference {:e}",
        case.label,
        r.error_estimate
    );
    r
}

#[test]
fn fixed_rule_estimates_bound_the_true_error() {
    let mut worst_ratio: f64 = 0.0;
    for case in cases() {
        let truth = reference(&case);
        for parametrisation in [
            Parametrisation::AzimuthHeight,
            Parametrisation::PolarAzimuth,
        ] {
            for tolerance in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
                for surface in [SurfaceChoice::A, SurfaceChoice::B] {
                    let mut e = engine(InteractionOptions {
                        relative_tolerance: tolerance,
                        method: MethodChoice::FixedRules,
                        surface,
                        parametrisation,
                        ..InteractionOptions::default()
                    });
                    let r = e
                        .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
                        .unwrap();
                    let err = errors(&r, &truth).max();
                    assert!(r.error_estimate <= tolerance);
                    assert!(
                        err <= r.error_estimate + truth.error_estimate,
                        "{} {parametrisation:?} over {surface:?} at {tolerance:e}: error {err:e} > estimate {:e}",
                        case.label,
                        r.error_estimate
                    );
                    worst_ratio = worst_ratio.max(err / r.error_estimate);
                }
            }
        }
    }
    println!("worst true error / estimate, fixed rules: {worst_ratio:.3}");
}

#[test]
fn adaptive_estimates_bound_the_true_error() {
    let mut worst_ratio: f64 = 0.0;
    for case in cases().into_iter().filter(|c| !c.label.contains("30")) {
        let truth = reference(&case);
        for tolerance in [1e-6, 1e-9, 1e-12] {
            let mut e = engine(InteractionOptions {
                relative_tolerance: tolerance,
                method: MethodChoice::Adaptive,
                ..InteractionOptions::default()
            });
            let r = e
                .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
                .unwrap();
            let err = errors(&r, &truth).max();
            assert!(r.error_estimate <= tolerance);
            assert!(
                err <= r.error_estimate + truth.error_estimate,
                "{} adaptive at {tolerance:e}: error {err:e} > estimate {:e}",
                case.label,
                r.error_estimate
            );
            worst_ratio = worst_ratio.max(err / r.error_estimate);
        }
    }
    println!("worst true error / estimate, adaptive: {worst_ratio:.3}");
}

/// Evaluation counts of the default engine for the founding paper's pair (snapshot: a change
/// of the ladder, the clustering or the start prediction shows here).
#[test]
fn evaluation_counts_for_the_paper_pair() {
    let mut counts = vec![];
    for d in [2.1, 2.55, 3.0, 7.0, 30.0] {
        let r = surfgrav_interaction::interact(
            &paper_spheroid(),
            &Pose::identity(),
            &paper_spheroid(),
            &pose([d, 0.0, 0.0], [0.0; 3]),
        )
        .unwrap();
        counts.push(r.evaluations);
    }
    assert_eq!(counts, SNAPSHOT, "evaluation counts changed: {counts:?}");
}

const SNAPSHOT: [usize; 5] = [506, 262, 210, 128, 110];

/// The nested doubling rule's estimate (rate estimate δ₂²/δ₁ per direction) bounds the true
/// error for every case above plus the paper pair at gap 10⁻³ (near contact), over the
/// tolerances 10⁻⁴ … 10⁻¹², integrating over either body.
#[test]
fn nested_estimates_bound_the_true_error() {
    let mut all = cases();
    all.push(Case {
        label: "paper pair, gap 1e-3",
        a: paper_spheroid(),
        b: paper_spheroid(),
        pose_a: Pose::identity(),
        pose_b: pose([2.001, 0.0, 0.0], [0.0; 3]),
    });
    all.push(Case {
        label: "paper pair, gap 1e-3, B lifted 0.1 and tilted",
        a: paper_spheroid(),
        b: paper_spheroid(),
        pose_a: Pose::identity(),
        pose_b: pose([2.0, 0.0, 0.1], [0.0, 0.2, 0.0]),
    });
    let mut worst_ratio: f64 = 0.0;
    for case in all {
        let truth = reference(&case);
        for tolerance in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
            for surface in [SurfaceChoice::A, SurfaceChoice::B] {
                let mut e = engine(InteractionOptions {
                    relative_tolerance: tolerance,
                    method: MethodChoice::Nested,
                    surface,
                    ..InteractionOptions::default()
                });
                let r = e
                    .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
                    .unwrap();
                let err = errors(&r, &truth).max();
                assert!(r.error_estimate <= tolerance);
                assert!(
                    err <= r.error_estimate + truth.error_estimate,
                    "{} nested over {surface:?} at {tolerance:e}: error {err:e} > estimate {:e}",
                    case.label,
                    r.error_estimate
                );
                worst_ratio = worst_ratio.max(err / r.error_estimate);
            }
        }
    }
    println!("worst true error / estimate, nested: {worst_ratio:.3}");
}

/// The nested rule far away (gap ratio from 8 on: coarser start and the geometric estimate
/// δ₂(δ₂/δ₁)^1.5, see `NESTED_GEOMETRIC_GAP`): spheroids c/a 0.01 … 100 (B the paper's
/// spheroid or A's twin), separations 10 to 10⁸ sizes, B in the equatorial plane, at 53° and
/// on the axis, and a generic pose. At every tolerance (10⁻⁶, 10⁻⁹, 10⁻¹²) the estimate
/// bounds the true error plus the 10⁻¹⁴ ladder reference's own estimate. At 10⁻¹² both sit at
/// their rounding floors, which for the flattest bodies was underestimated until the
/// potential form's floor counted the rounding of Φ itself (see `CANCELLATION_RATIO`): then
/// 47 of the 2016 cases of the full grid had errors up to 2.6·10⁻¹³ against estimates near
/// 10⁻¹⁵.
#[test]
fn nested_far_field_estimates_bound_the_true_error() {
    far_field_grid(&[0.01, 0.25, 1.0, 100.0], &[10.0, 30.0, 1e3, 1e8]);
}

/// The grid behind `NESTED_GEOMETRIC_GAP`'s figures (2016 cases, about a second in release):
/// `cargo test --release -p surfgrav-interaction --test interaction_estimates -- --ignored --nocapture`
#[test]
#[ignore]
fn nested_far_field_estimates_full_grid() {
    far_field_grid(
        &[0.01, 0.1, 0.25, 1.0, 4.0, 100.0],
        &[10.0, 20.0, 30.0, 100.0, 1e3, 1e5, 1e8],
    );
}

fn far_field_grid(ratios: &[f64], separations: &[f64]) {
    let mut worst_ratio: f64 = 0.0;
    let mut cases = 0;
    let mut evaluations = 0;
    for &ratio in ratios {
        for rb in [0.25, ratio] {
            let a = Body::spheroid(Spheroid::new(1.0, ratio, 1.0).unwrap()).unwrap();
            let b = Body::spheroid(Spheroid::new(1.0, rb, 2.0).unwrap()).unwrap();
            let size = f64::max(ratio, 1.0).max(rb.max(1.0));
            for &separation in separations {
                let d = separation * size;
                for (direction, rotation) in [
                    ([1.0f64, 0.0, 0.0], [0.0; 3]),
                    ([0.6, 0.0, 0.8], [0.0; 3]),
                    ([0.0, 0.0, 1.0], [0.0; 3]),
                    ([0.5, 0.4, 0.3], [0.3, -0.5, 0.2]),
                ] {
                    let norm = (direction[0] * direction[0]
                        + direction[1] * direction[1]
                        + direction[2] * direction[2])
                        .sqrt();
                    let pose_b = pose(direction.map(|x| d * x / norm), rotation);
                    let case = Case {
                        label: "far",
                        a: a.clone(),
                        b: b.clone(),
                        pose_a: Pose::identity(),
                        pose_b,
                    };
                    // At 10⁸ sizes the reference's force is limited by its rounding floor
                    // (up to 10⁻¹¹ for the needle): its own estimate is added below.
                    let mut fine = engine(InteractionOptions {
                        relative_tolerance: 1e-14,
                        method: MethodChoice::FixedRules,
                        max_evaluations: 20_000_000,
                        ..InteractionOptions::default()
                    });
                    let truth =
                        best_effort(&mut fine, &case.a, &case.pose_a, &case.b, &case.pose_b);
                    assert!(
                        truth.error_estimate <= 1e-10,
                        "reference {:e}",
                        truth.error_estimate
                    );
                    for tolerance in [1e-6, 1e-9, 1e-12] {
                        for surface in [SurfaceChoice::A, SurfaceChoice::B] {
                            let mut e = engine(InteractionOptions {
                                relative_tolerance: tolerance,
                                method: MethodChoice::Nested,
                                surface,
                                ..InteractionOptions::default()
                            });
                            let r = e
                                .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
                                .unwrap();
                            let err = errors(&r, &truth).max();
                            let what = format!(
                                "c/a {ratio} and {rb}, {separation} sizes along {direction:?} over {surface:?} at {tolerance:e}"
                            );
                            assert!(r.error_estimate <= tolerance, "{what}");
                            assert!(
                                err <= tolerance + truth.error_estimate,
                                "{what}: error {err:e}"
                            );
                            assert!(
                                err <= r.error_estimate + truth.error_estimate,
                                "{what}: error {err:e} > estimate {:e} (reference's {:e})",
                                r.error_estimate,
                                truth.error_estimate
                            );
                            worst_ratio = worst_ratio
                                .max((err - truth.error_estimate).max(0.0) / r.error_estimate);
                            cases += 1;
                            evaluations += r.evaluations;
                        }
                    }
                }
            }
        }
    }
    println!("{cases} cases, {evaluations} evaluations; worst (true error - reference estimate) / estimate: {worst_ratio:.3}");
}

/// Evaluation counts of the nested rule at 10⁻¹² for the founding paper's pair (snapshot).
#[test]
fn nested_evaluation_counts_for_the_paper_pair() {
    let mut counts = vec![];
    for d in [2.1, 2.55, 3.0, 7.0, 30.0] {
        let mut e = engine(InteractionOptions {
            method: MethodChoice::Nested,
            ..InteractionOptions::default()
        });
        let r = e
            .interact(
                &paper_spheroid(),
                &Pose::identity(),
                &paper_spheroid(),
                &pose([d, 0.0, 0.0], [0.0; 3]),
            )
            .unwrap();
        counts.push(r.evaluations);
    }
    assert_eq!(
        counts, NESTED_SNAPSHOT,
        "evaluation counts changed: {counts:?}"
    );
}

const NESTED_SNAPSHOT: [usize; 5] = [775, 391, 323, 195, 63];

/// The force-only evaluation ([`InteractionEngine::force`]): its estimate bounds the force's
/// true error at every tolerance, and where it certifies with the same tables as the full
/// evaluation its force is the same number.
#[test]
fn force_only_estimates_bound_the_true_error() {
    let mut worst_ratio: f64 = 0.0;
    for case in cases() {
        let truth = reference(&case);
        for tolerance in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
            let options = InteractionOptions {
                relative_tolerance: tolerance,
                ..InteractionOptions::default()
            };
            let mut e = engine(options);
            let f = e
                .force(&case.a, &case.pose_a, &case.b, &case.pose_b)
                .unwrap();
            let full = engine(options)
                .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
                .unwrap();
            let scale = truth.force_on_a.norm();
            let err = (f.force_on_a - truth.force_on_a).norm() / scale;
            assert!(f.error_estimate <= tolerance);
            assert!(f.evaluations <= full.evaluations, "{}", case.label);
            assert!(
                err <= f.error_estimate + truth.error_estimate,
                "{} force only at {tolerance:e}: error {err:e} > estimate {:e}",
                case.label,
                f.error_estimate
            );
            assert_eq!(f.force_on_b, -f.force_on_a);
            if f.evaluations == full.evaluations {
                assert_eq!(f.force_on_a, full.force_on_a, "{}", case.label);
            }
            worst_ratio = worst_ratio.max(err / f.error_estimate);
        }
    }
    println!("worst true error / estimate, force only: {worst_ratio:.3}");
}

/// Two oblate spheroids side by side near contact (a = 1, c = 0.2266 and 0.25, a drawn
/// variant of the paper's pair that `surfgrav sweep` tabulates at 1e-13): the fixed tables'
/// changes 1.7e-13, 1.5e-13, then 1.2e-14 at separation 2.0014 are a slow phase that ends,
/// not a stalled change (the last level is within 1.3e-15 of the nested and aimed rules).
/// The ladder's rate guard (`run_ladder`) holds the last level back, and the next level must
/// confirm the drop rather than the rounding stop end the ladder uncertified (which it did at
/// 7 of 200 separations from 2.0005 to 2.0204, and `surfgrav sweep` then failed to tabulate
/// V(r)). Each certifies 1e-13 and lies within its estimate of the nested rule's result.
#[test]
fn a_sudden_drop_after_a_slow_phase_is_confirmed_not_dropped() {
    let a = Body::spheroid(Spheroid::new(1.0, 0.22663914433925533, 1.0).unwrap()).unwrap();
    let b = Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap();
    for separation in [2.0014, 2.0015, 2.0063, 2.0064] {
        let pose_b = pose([separation, 0.0, 0.0], [0.0; 3]);
        let at = |tolerance: f64, method: MethodChoice| {
            engine(InteractionOptions {
                relative_tolerance: tolerance,
                method,
                ..InteractionOptions::default()
            })
            .interact(&a, &Pose::identity(), &b, &pose_b)
            .unwrap_or_else(|e| panic!("{separation}: {e}"))
        };
        let result = at(1e-13, MethodChoice::Automatic);
        let nested = at(1e-13, MethodChoice::Nested);
        assert_within_estimates(&format!("{separation}"), &result, &nested);
    }
}
