//! Overlapping or touching bodies, bad poses and bad options give typed errors, never numbers.

mod interaction_support;

use interaction_support::*;
use nalgebra::{Quaternion, UnitQuaternion};
use std::sync::Arc;
use surfgrav_interaction::{
    interact, Body, BodyShape, InteractionEngine, InteractionError, InteractionOptions,
    MethodChoice, Side, SurfaceChoice,
};
use surfgrav_potentials::{PointMass, Pose, PoseExt, Sphere, Spheroid, UniformDisk, Vec3};

fn at(x: f64, y: f64, z: f64) -> Pose {
    pose([x, y, z], [0.0; 3])
}

fn is_overlap(r: Result<impl std::fmt::Debug, InteractionError>) -> bool {
    matches!(r, Err(InteractionError::Overlap { .. }))
}

fn is_touching(r: Result<impl std::fmt::Debug, InteractionError>) -> bool {
    matches!(r, Err(InteractionError::Touching { .. }))
}

#[test]
fn overlapping_and_touching_solids_are_rejected() {
    let a = paper_spheroid();
    let b = paper_spheroid();
    let o = Pose::identity();
    assert!(is_overlap(interact(&a, &o, &b, &at(1.9, 0.0, 0.0))));
    assert!(is_touching(interact(&a, &o, &b, &at(2.0, 0.0, 0.0))));
    // Stacked along the axis: bounding spheres intersect, the bodies do not (gap 0.1).
    let stacked = interact(&a, &o, &b, &at(0.0, 0.0, 0.6)).unwrap();
    assert!(stacked.potential_energy < 0.0 && stacked.error_estimate <= 1e-12);
    assert!(is_touching(interact(&a, &o, &b, &at(0.0, 0.0, 0.5))));
    assert!(is_overlap(interact(&a, &o, &b, &at(0.0, 0.0, 0.45))));
    // Tilted: B turned 90° about x stands on its rim, touching A's top at x = 0 only if the
    // distance is c + a.
    let standing = pose([0.0, 0.0, 1.25], [std::f64::consts::FRAC_PI_2, 0.0, 0.0]);
    assert!(is_touching(interact(&a, &o, &b, &standing)));
    let lifted = pose([0.0, 0.0, 1.3], [std::f64::consts::FRAC_PI_2, 0.0, 0.0]);
    assert!(interact(&a, &o, &b, &lifted).is_ok());
    let sunk = pose([0.0, 0.0, 1.2], [std::f64::consts::FRAC_PI_2, 0.0, 0.0]);
    assert!(is_overlap(interact(&a, &o, &b, &sunk)));
}

#[test]
fn spheres_points_and_disks_are_tested_exactly() {
    let s1 = Body::sphere(Sphere::new(1.0, 1.0).unwrap()).unwrap();
    let s2 = Body::sphere(Sphere::new(0.5, 1.0).unwrap()).unwrap();
    let p = Body::point_mass(PointMass::new(1.0).unwrap());
    let o = Pose::identity();
    assert!(is_touching(interact(&s1, &o, &s2, &at(1.5, 0.0, 0.0))));
    assert!(is_overlap(interact(&s1, &o, &s2, &at(1.4, 0.0, 0.0))));
    assert!(interact(&s1, &o, &s2, &at(1.5 + 1e-12, 0.0, 0.0)).is_ok());
    assert!(is_touching(interact(&s1, &o, &p, &at(0.0, 1.0, 0.0))));
    assert!(is_overlap(interact(&p, &at(0.3, 0.2, 0.1), &s1, &o)));
    assert!(is_touching(interact(&p, &o, &p, &o)));
    let disk = Body::disk(UniformDisk::new(1.0, 1.0).unwrap()).unwrap();
    let small_disk = Body::disk(UniformDisk::new(0.5, 1.0).unwrap()).unwrap();
    assert!(is_overlap(interact(
        &disk,
        &o,
        &small_disk,
        &at(1.2, 0.3, 0.0)
    )));
    assert!(is_touching(interact(
        &disk,
        &o,
        &small_disk,
        &at(1.5, 0.0, 0.0)
    )));
    // A point on the lamina touches it; above it, it does not.
    assert!(is_touching(interact(&disk, &o, &p, &at(0.3, 0.4, 0.0))));
    assert!(interact(&disk, &o, &p, &at(0.3, 0.4, 0.01)).is_ok());
    // A disk through a spheroid, and a disk resting on its pole.
    let spheroid = paper_spheroid();
    assert!(is_overlap(interact(
        &spheroid,
        &o,
        &disk,
        &pose([0.0, 0.0, 0.0], [0.4, 0.0, 0.0])
    )));
    assert!(is_touching(interact(
        &spheroid,
        &o,
        &disk,
        &at(0.0, 0.0, 0.25)
    )));
    assert!(interact(&spheroid, &o, &disk, &at(0.0, 0.0, 0.3)).is_ok());
    // Parallel disks one above the other never touch.
    assert!(interact(&disk, &o, &small_disk, &at(0.2, 0.0, 0.05)).is_ok());
}

/// A body known only by its potential is tested on the integration nodes and centroids.
#[test]
fn bodies_of_unknown_shape_are_tested_on_the_nodes() {
    let spheroid = Spheroid::new(1.0, 0.25, 1.0).unwrap();
    let a = paper_spheroid();
    let field_only = Body::custom(Arc::new(spheroid), BodyShape::FieldOnly).unwrap();
    let o = Pose::identity();
    assert!(is_overlap(interact(
        &a,
        &o,
        &field_only,
        &at(1.5, 0.0, 0.0)
    )));
    assert!(is_overlap(interact(
        &a,
        &o,
        &field_only,
        &at(0.0, 0.0, 0.3)
    )));
    // Apart (bounding spheres intersecting): the same numbers as the built-in body.
    let stacked = at(0.3, 0.0, 0.6);
    let custom = interact(&a, &o, &field_only, &stacked).unwrap();
    let builtin = interact(&a, &o, &paper_spheroid(), &stacked).unwrap();
    assert!(errors(&custom, &builtin).max() <= custom.error_estimate + builtin.error_estimate);
    // A point mass and a field-only body: the point formula needs no surface.
    let point = Body::point_mass(PointMass::new(1.0).unwrap());
    let point_result = interact(&point, &at(0.0, 0.0, 3.0), &field_only, &o).unwrap();
    assert!(point_result.potential_energy < 0.0);
    assert!(is_overlap(interact(
        &point,
        &at(0.5, 0.0, 0.1),
        &field_only,
        &o
    )));
    // A sphere cutting into a field-only body: its centre outside, its surface inside.
    let sphere = Body::sphere(Sphere::new(0.5, 1.0).unwrap()).unwrap();
    assert!(is_overlap(interact(
        &sphere,
        &at(1.3, 0.0, 0.0),
        &field_only,
        &o
    )));
    assert!(interact(&sphere, &at(1.6, 0.0, 0.0), &field_only, &o).is_ok());
}

#[test]
fn non_finite_poses_are_rejected() {
    let a = paper_spheroid();
    let b = paper_spheroid();
    let nan_position = at(f64::NAN, 0.0, 0.0);
    assert!(matches!(
        interact(&a, &nan_position, &b, &at(3.0, 0.0, 0.0)),
        Err(InteractionError::NonFinitePose {
            body: Side::A,
            what: "position"
        })
    ));
    let bad_rotation = Pose::from_position_rotation(
        Vec3::new(3.0, 0.0, 0.0),
        UnitQuaternion::new_unchecked(Quaternion::new(f64::INFINITY, 0.0, 0.0, 0.0)),
    );
    assert!(matches!(
        interact(&a, &Pose::identity(), &b, &bad_rotation),
        Err(InteractionError::NonFinitePose {
            body: Side::B,
            what: "rotation"
        })
    ));
}

#[test]
fn bad_options_and_bodies_are_rejected() {
    for tolerance in [0.0, -1e-12, 1.0, f64::NAN, f64::INFINITY] {
        let options = InteractionOptions {
            relative_tolerance: tolerance,
            ..Default::default()
        };
        assert!(matches!(
            InteractionEngine::new(options),
            Err(InteractionError::InvalidTolerance { .. })
        ));
    }
    let tiny_budget = InteractionOptions {
        max_evaluations: 10,
        ..Default::default()
    };
    assert!(matches!(
        InteractionEngine::new(tiny_budget),
        Err(InteractionError::BudgetTooSmall { .. })
    ));

    let a = paper_spheroid();
    let other_g = Body::spheroid(
        Spheroid::new(1.0, 0.25, 1.0)
            .unwrap()
            .with_gravitational_constant(2.0)
            .unwrap(),
    )
    .unwrap();
    assert!(matches!(
        interact(&a, &Pose::identity(), &other_g, &at(3.0, 0.0, 0.0)),
        Err(InteractionError::GravitationalConstantMismatch { .. })
    ));
    let p = Body::point_mass(PointMass::new(1.0).unwrap());
    let mut fixed = engine(options(
        1e-12,
        MethodChoice::FixedRules,
        SurfaceChoice::Automatic,
    ));
    assert!(matches!(
        fixed.interact(&p, &Pose::identity(), &p, &at(1.0, 0.0, 0.0)),
        Err(InteractionError::NoSurface { .. })
    ));
    let mut over_a = engine(options(1e-12, MethodChoice::FixedRules, SurfaceChoice::A));
    assert!(matches!(
        over_a.interact(&p, &Pose::identity(), &a, &at(3.0, 0.0, 0.0)),
        Err(InteractionError::NoSurface { .. })
    ));
}

/// A tolerance that cannot be met within the budget is an error carrying the best result,
/// whose estimate exceeds the tolerance.
#[test]
fn an_unmet_tolerance_is_reported_with_the_best_result() {
    // A spheroid in the plane of a disk, 10⁻³ from its rim, where the disk's field has a
    // logarithmic singularity: far more nodes than the budget allows.
    let a = paper_spheroid();
    let b = Body::disk(UniformDisk::new(1.0, 1.0).unwrap()).unwrap();
    let mut e = engine(InteractionOptions {
        max_evaluations: 2_000,
        method: MethodChoice::FixedRules,
        surface: SurfaceChoice::A,
        ..Default::default()
    });
    match e.interact(&a, &Pose::identity(), &b, &at(2.001, 0.0, 0.0)) {
        Err(InteractionError::ToleranceNotMet {
            tolerance,
            error_estimate,
            evaluations,
            best,
        }) => {
            assert_eq!(tolerance, 1e-12);
            assert!(error_estimate > tolerance);
            assert!(evaluations <= 2_000);
            assert_eq!(best.error_estimate, error_estimate);
            assert!(best.potential_energy.is_finite() && best.potential_energy < 0.0);
            let message = InteractionError::ToleranceNotMet {
                tolerance,
                error_estimate,
                evaluations,
                best,
            }
            .to_string();
            assert!(!message.contains('\n'), "{message}");
        }
        other => panic!("expected ToleranceNotMet, got {other:?}"),
    }
    // A tolerance below the rounding floor stops as soon as two levels agree to rounding.
    let mut strict = engine(InteractionOptions {
        relative_tolerance: 1e-17,
        ..Default::default()
    });
    match strict.interact(&a, &Pose::identity(), &paper_spheroid(), &at(3.0, 0.0, 0.0)) {
        Err(InteractionError::ToleranceNotMet {
            evaluations, best, ..
        }) => {
            assert!(evaluations < 5_000, "{evaluations}");
            assert!(best.error_estimate < 1e-13);
        }
        other => panic!("expected ToleranceNotMet, got {other:?}"),
    }
}
