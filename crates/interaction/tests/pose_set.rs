//! Accuracy over the seeded random-pose set of the work–precision benchmark (issue 12; the
//! example `pose_benchmark` times it): spheroid, ellipsoid and disk pairs at random attitudes
//! and directions, at gaps of 0.05, 0.2, 1 and 5 times the smaller bounding radius, certified
//! to 10⁻¹².
//!
//! 48 cases (two per pair of kinds and gap) and one regression case. Every case must certify the tolerance, and its true error against an independent reference
//! (the ladder at 10⁻¹³ over the other body's surface, in the polar-angle form) must lie within
//! the engine's estimate plus the reference's own estimate: the estimate bounds the error, which
//! is what certification promises. Nothing here is timed.

use surfgrav_interaction::work_precision::{
    independent_reference, interaction_error, pose_set, PoseCase,
};
use surfgrav_interaction::Interaction;
use surfgrav_interaction::InteractionEngine;

/// The requested tolerance (the engine's default).
const TOLERANCE: f64 = 1e-12;

/// The reference's tolerance: ten times tighter than the result checked.
const REFERENCE_TOLERANCE: f64 = 1e-13;

/// The independent reference for `case`, which must certify.
fn certified_reference(case: &PoseCase) -> Interaction {
    let (reference, certified) = independent_reference(
        &case.a,
        &case.pose_a,
        &case.b,
        &case.pose_b,
        REFERENCE_TOLERANCE,
    )
    .unwrap();
    assert!(certified, "{}: reference not certified", case.label);
    reference
}

#[test]
fn random_poses_certify_and_estimates_bound_true_errors() {
    let mut cases = pose_set(12, &[0.05, 0.2, 1.0, 5.0], 2);
    assert_eq!(cases.len(), 48);
    // A disk pair near contact whose fixed-rule ladder, when allowed to jump levels,
    // certified 2.6e-13 with a true error of 5.8e-13 (a regression case).
    let four = pose_set(12, &[0.05], 4);
    let regression = four.iter().find(|c| c.label == "disk-disk gap 0.05 #3");
    cases.push(regression.expect("the pose set has the case").clone());
    let mut engine = InteractionEngine::default();
    let mut failures = vec![];
    for case in &cases {
        let result = engine
            .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
            .unwrap_or_else(|e| panic!("{}: {e}", case.label));
        assert!(result.error_estimate <= TOLERANCE, "{}", case.label);
        let reference = certified_reference(case);
        assert_ne!(
            reference.integrated_over, result.integrated_over,
            "{}: the reference integrates over the other body",
            case.label
        );
        let error = interaction_error(&result, &reference);
        if error > result.error_estimate + reference.error_estimate {
            failures.push(format!(
                "{}: true error {error:.2e} above estimate {:.2e} + reference {:.2e}",
                case.label, result.error_estimate, reference.error_estimate
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The requests of [`InteractionEngine::evaluate`] on the same set: a force-only and a wrench
/// evaluation certify what they return (force; force and torques) within their estimates
/// against the independent reference, leave out what was not asked for, and never cost more
/// evaluations than the full interaction (they certify less on the same levels).
#[test]
fn requests_certify_what_they_return() {
    use surfgrav_interaction::Request;
    let cases = pose_set(12, &[0.05, 0.2, 1.0, 5.0], 1);
    let mut engine = InteractionEngine::default();
    for case in &cases {
        let (a, pa, b, pb) = (&case.a, &case.pose_a, &case.b, &case.pose_b);
        let full = engine.interact(a, pa, b, pb).unwrap();
        let (reference, _) = independent_reference(a, pa, b, pb, REFERENCE_TOLERANCE).unwrap();
        let v = reference.potential_energy.abs();
        let force_error = |f: &surfgrav_potentials::Vec3| {
            (f - reference.force_on_a).norm() / reference.force_on_a.norm()
        };
        let force = engine.evaluate(a, pa, b, pb, Request::Force).unwrap();
        assert!(force.torque_on_a.is_none() && force.potential_energy.is_none());
        assert!(force.error_estimate <= TOLERANCE, "{}", case.label);
        assert!(force.evaluations <= full.evaluations, "{}", case.label);
        assert!(
            force_error(&force.force_on_a) <= force.error_estimate + reference.error_estimate,
            "{}: force-only error {:.2e} above its estimate {:.2e}",
            case.label,
            force_error(&force.force_on_a),
            force.error_estimate
        );
        let wrench = engine.evaluate(a, pa, b, pb, Request::Wrench).unwrap();
        assert!(wrench.potential_energy.is_none(), "{}", case.label);
        assert!(wrench.error_estimate <= TOLERANCE, "{}", case.label);
        assert!(wrench.evaluations <= full.evaluations, "{}", case.label);
        let (ma, mb) = (wrench.torque_on_a.unwrap(), wrench.torque_on_b.unwrap());
        let error = force_error(&wrench.force_on_a)
            .max((ma - reference.torque_on_a).norm() / reference.torque_on_a.norm().max(v))
            .max((mb - reference.torque_on_b).norm() / reference.torque_on_b.norm().max(v));
        assert!(
            error <= wrench.error_estimate + reference.error_estimate,
            "{}: wrench error {error:.2e} above its estimate {:.2e}",
            case.label,
            wrench.error_estimate
        );
        let everything = engine.evaluate(a, pa, b, pb, Request::Everything).unwrap();
        assert_eq!(everything.potential_energy, Some(full.potential_energy));
        assert_eq!(everything.evaluations, full.evaluations);
    }
}

/// Disks far from the other body (gap 5) start their fixed lamina ladder where the rim's
/// angular singularity asks (`far_lamina_start` in `strategy/ladder.rs`): before, the gap
/// formula started them 2 to 5 levels low and the four disk–disk cases of the seed-12 set
/// took 618, 740, 496 and 618 evaluations; now 284 to 332. The bound 400 sits between the two
/// (it fails if the start falls back to the gap formula); the results certify and agree with
/// the independent reference within the two estimates.
#[test]
fn far_disks_start_at_the_level_their_rim_asks_for() {
    // The example's set (the seed's draws depend on the list of gaps).
    let cases = pose_set(12, &[0.05, 0.2, 1.0, 5.0], 4);
    let mut engine = InteractionEngine::default();
    let mut checked = 0;
    for case in cases
        .iter()
        .filter(|c| c.label.starts_with("disk-disk gap 5 "))
    {
        let result = engine
            .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
            .unwrap_or_else(|e| panic!("{}: {e}", case.label));
        assert!(result.error_estimate <= TOLERANCE, "{}", case.label);
        assert!(
            result.evaluations <= 400,
            "{}: {} evaluations",
            case.label,
            result.evaluations
        );
        let reference = certified_reference(case);
        let error = interaction_error(&result, &reference);
        assert!(
            error <= result.error_estimate + reference.error_estimate,
            "{}: true error {error:.2e}",
            case.label
        );
        checked += 1;
    }
    assert_eq!(checked, 4);
}

/// An ellipsoid 0.05 from a spheroid (seed 24, spheroid-ellipsoid gap 0.05 #0): the fixed
/// tables over the ellipsoid in the polar-angle form (the independent reference's method)
/// stall and then change by far less than their rate predicts (3.4e-12, then 4.5e-14 between
/// levels 100 and 108), and at 1e-13 certified 9.0e-14 with a true error of 1.3e-13. The
/// ladder's estimate now also takes the rate before such a drop (`run_ladder`), and the error
/// against the aimed rule over the same body at 1e-14 lies within the two estimates; this
/// fails without it.
#[test]
fn fixed_tables_do_not_certify_a_stalled_change() {
    use surfgrav_interaction::{InteractionOptions, Side, SurfaceChoice};
    let cases = pose_set(24, &[0.05, 0.2, 1.0, 5.0], 4);
    let case = cases
        .iter()
        .find(|c| c.label == "spheroid-ellipsoid gap 0.05 #0")
        .expect("the pose set has the case");
    let reference = certified_reference(case);
    assert_eq!(reference.integrated_over, Some(Side::A));
    let accurate = InteractionEngine::new(InteractionOptions {
        relative_tolerance: 1e-14,
        surface: SurfaceChoice::A,
        ..InteractionOptions::default()
    })
    .unwrap()
    .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
    .unwrap();
    let error = interaction_error(&reference, &accurate);
    assert!(
        error <= reference.error_estimate + accurate.error_estimate,
        "true error {error:.2e} above the estimates {:.2e} + {:.2e}",
        reference.error_estimate,
        accurate.error_estimate
    );
}

/// The surface choice predicts a far disk's fixed lamina table from the level the ladder
/// starts it at (the rim's angular singularity, `Placement::lamina_start`), not from the gap
/// formula alone, which had it under-predicted and chosen: seed 14 disk-disk gap 5 #0 and #2
/// and seed 27 #1 took 612, 620 and 724 evaluations over the disk the choice wrongly
/// favoured, and take 324, 400 and 384 over the other. The bound 400 fails on the old
/// choice; the results certify and agree with the independent reference.
#[test]
fn far_disks_are_chosen_by_the_level_their_table_starts_at() {
    certified_within(
        &[
            (14, "disk-disk gap 5 #0"),
            (14, "disk-disk gap 5 #2"),
            (27, "disk-disk gap 5 #1"),
        ],
        400,
    );
}

/// Each of the pose sets' cases (seed, label) certifies the tolerance within `evaluations`
/// evaluations and agrees with the independent reference within the two estimates.
fn certified_within(cases: &[(u64, &str)], evaluations: usize) {
    let mut engine = InteractionEngine::default();
    for &(seed, label) in cases {
        let set = pose_set(seed, &[0.05, 0.2, 1.0, 5.0], 4);
        let case = set
            .iter()
            .find(|c| c.label == label)
            .expect("the pose set has the case");
        let result = engine
            .interact(&case.a, &case.pose_a, &case.b, &case.pose_b)
            .unwrap_or_else(|e| panic!("{seed} {label}: {e}"));
        assert!(result.error_estimate <= TOLERANCE, "{seed} {label}");
        assert!(
            result.evaluations <= evaluations,
            "{seed} {label}: {} evaluations",
            result.evaluations
        );
        let reference = certified_reference(case);
        let error = interaction_error(&result, &reference);
        assert!(
            error <= result.error_estimate + reference.error_estimate,
            "{seed} {label}: true error {error:.2e}"
        );
    }
}

/// A spheroid or an ellipsoid 1 from a disk whose side has only its fixed table (no aimed
/// lamina plan): the surface choice's penalty on the aimed rule beside a disk's rim, meant
/// against the disk's aimed lamina rule, no longer applies there (`Placement::beside_lamina`).
/// Seed 40 spheroid-disk gap 1 #2 and seed 32 ellipsoid-disk gap 1 #1 took 15,570 and 6,576
/// evaluations over the disk and take 1,656 and 2,220 over the solid; the bound 3,000 fails
/// on the old choice, and the results certify and agree with the independent reference.
#[test]
fn a_solid_beside_a_far_disk_is_not_penalised() {
    certified_within(
        &[
            (40, "spheroid-disk gap 1 #2"),
            (32, "ellipsoid-disk gap 1 #1"),
        ],
        3_000,
    );
}

/// Two disks whose rims pass near each other at two places (seed 39 disk-disk gap 0.2 #3:
/// widths 0.046 and 0.17 two radians apart on the rim row, the other rim hovering 0.03 to
/// 0.15 over the face) and two disks 0.05 apart (seed 32 #3). Each row whose other
/// singularity sets its plan is split at both (`SplitRow`), and the radial rule is planned
/// against the circle's pinches (`circle_pinches`), not every point of it as a cut. They took
/// 26,742 and 17,858 evaluations; with split rows alone 11,193 and 4,231, with the pinches
/// alone (and the radial floor, `CUT_FLOOR`) 14,200 and 9,602, with both 6,114 and 6,134:
/// the bound 8,000 fails without either.
/// The results certify and agree with the independent reference.
#[test]
fn rows_split_at_both_singularities_and_pinch_planned_radii() {
    certified_within(
        &[(39, "disk-disk gap 0.2 #3"), (32, "disk-disk gap 0.05 #3")],
        8_000,
    );
}

/// A disk beside a triaxial ellipsoid near contact, whose focal ellipse runs near the disk
/// along a stretch (seed 38 ellipsoid-disk gap 0.05 #1 and #2). Each row's angles turn toward
/// the nearer of the two row points (the nearest singular point or the one nearest the rim),
/// each table entry is planned from the stretch as its own rows see it (`entry_widths`), and
/// the point model's widths are corrected by the exact row singularities of the ellipse
/// (`EllipseRows`). They took 8,222 and 5,254 evaluations; with the turned rows and entries
/// alone 6,600 and 4,040; with the exact widths too 4,486 and 4,040 (4,882 and 4,040 since
/// the radial sides keep the stretch's own heights): the bound 5,000 fails on the old plan
/// (both) and on the turned rows alone (#1).
/// The results certify and agree with the independent reference.
#[test]
fn a_focal_ellipse_near_a_disk_is_planned_from_its_rows() {
    certified_within(
        &[
            (38, "ellipsoid-disk gap 0.05 #1"),
            (38, "ellipsoid-disk gap 0.05 #2"),
        ],
        5_000,
    );
}

/// The same near a focal ellipse whose nearest stretch is narrower than the rim samples'
/// spacing (seed 24 ellipsoid-disk gap 0.05 #0, seed 34 #1): with the exact rows' correction
/// the plan carries the stretch's margin, not the unresolved stretch's. They took 7,012 and
/// 7,632 evaluations, 7,466 and 7,484 with the exact widths under the larger margin, and take
/// 5,170 and 5,086 (4,820 and 5,086 with the radial heights widened too): the bound 5,500
/// fails on both.
#[test]
fn a_corrected_focal_ellipse_needs_no_unresolved_margin() {
    certified_within(
        &[
            (24, "ellipsoid-disk gap 0.05 #0"),
            (34, "ellipsoid-disk gap 0.05 #1"),
        ],
        5_500,
    );
}

/// A disk beside a triaxial ellipsoid whose focal ellipse runs 0.06 to 0.24 above it (seed 62
/// ellipsoid-disk gap 0.05 #0, the worst case of the pose sets 12-72): the radial sides are
/// planned against the stretch's points at their own heights. Widened by the exact rows'
/// angular ratio, they needed 0.95 of their plan, the ladder's first levels fell short and it
/// took 37,176 evaluations through six levels (1.9 ms); it takes 15,234: the bound 20,000
/// fails on the widened heights.
#[test]
fn a_focal_ellipses_radial_sides_keep_its_heights() {
    certified_within(&[(62, "ellipsoid-disk gap 0.05 #0")], 20_000);
}

/// A disk beside a prolate spheroid's equator (seed 56 spheroid-disk gap 0.2 #0: semi-axes 1
/// and 1.96, the disk's radius 0.47): the focal segment lies along the spheroid's axis, at
/// least 1 from the disk, but the ball of its half-length (1.69) about the centre reached the
/// disk, and the disk's fixed table started at level 71 for a gap it does not have: 15,924
/// evaluations (estimate 6.8e-15). From the distance to the segment itself it takes 824; the
/// bound 2,000 fails on the ball.
#[test]
fn a_disk_beside_a_focal_segment_is_placed_by_its_distance() {
    certified_within(&[(56, "spheroid-disk gap 0.2 #0")], 2_000);
}
