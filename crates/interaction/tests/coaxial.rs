//! Bodies on a common axis (issue 12's "two spheroids stacked on a common axis"): where X is a
//! body of revolution and Y's field is symmetric about X's axis, the aimed rule puts its pole
//! on that axis and integrates the azimuth with 8 nodes, exactly (`aimed::coaxial_pole`).
//! Every configuration must certify 10⁻¹², agree with the independent reference (the ladder
//! at 10⁻¹³ over the other body, polar-angle form) within the two estimates, and cost what the
//! symmetric rule costs: before it, two oblate spheroids stacked at gap 0.1 took 2,338
//! evaluations (the pole was aimed at one point of the other's focal circle). A disk on the
//! axis is integrated over with 8 angles per half-range (`aimed/lamina.rs`).

use nalgebra::{UnitQuaternion, Vector3};
use surfgrav_interaction::work_precision::{independent_reference, interaction_error};
use surfgrav_interaction::{Body, Interaction, InteractionEngine};
use surfgrav_potentials::{Pose, PoseExt, Spheroid, UniformDisk, Vec3};

const TOLERANCE: f64 = 1e-12;
const REFERENCE_TOLERANCE: f64 = 1e-13;

fn oblate() -> Body {
    Body::spheroid(Spheroid::new(1.0, 0.5, 1.0).unwrap()).unwrap()
}
fn prolate() -> Body {
    Body::spheroid(Spheroid::new(0.5, 1.0, 0.8).unwrap()).unwrap()
}
fn small_oblate() -> Body {
    Body::spheroid(Spheroid::new(0.4, 0.3, 0.3).unwrap()).unwrap()
}
fn disk() -> Body {
    Body::disk(UniformDisk::new(0.9, 0.5).unwrap()).unwrap()
}

/// Checks one configuration: B on A's axis at height `z`, turned by `turn_b`; returns the
/// evaluations.
fn check(label: &str, a: &Body, b: &Body, z: f64, turn_b: UnitQuaternion<f64>) -> usize {
    let pose_b = Pose::from_position_rotation(Vec3::new(0.0, 0.0, z), turn_b);
    let result = certified_within_estimates(label, a, b, &pose_b);
    // The symmetric configuration has no sideways force.
    assert!(
        result.force_on_a.xy().norm() <= 1e-12 * result.force_on_a.norm(),
        "{label}: sideways force {:?}",
        result.force_on_a
    );
    result.evaluations
}

/// The engine's result for A at the origin and B at `pose_b`, which must certify
/// [`TOLERANCE`] and agree with the independent reference within the two estimates.
fn certified_within_estimates(label: &str, a: &Body, b: &Body, pose_b: &Pose) -> Interaction {
    let pose_a = Pose::identity();
    let result = InteractionEngine::default()
        .interact(a, &pose_a, b, pose_b)
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    assert!(result.error_estimate <= TOLERANCE, "{label}");
    let (reference, certified) =
        independent_reference(a, &pose_a, b, pose_b, REFERENCE_TOLERANCE).unwrap();
    assert!(certified, "{label}: reference not certified");
    let error = interaction_error(&result, &reference);
    assert!(
        error <= result.error_estimate + reference.error_estimate,
        "{label}: true error {error:.2e}, estimate {:.2e} + reference {:.2e}",
        result.error_estimate,
        reference.error_estimate
    );
    result
}

#[test]
fn bodies_on_a_common_axis_certify_at_the_cost_of_the_symmetric_rule() {
    let upright = UnitQuaternion::identity();
    let about_axis = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.7);
    let flipped = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI);
    let (oblate, prolate, small, disk) = (oblate(), prolate(), small_oblate(), disk());
    let (mut worst, mut worst_disk) = (0, 0);
    for gap in [0.05, 0.2, 1.0, 5.0] {
        // Heights of B's centroid for surfaces `gap` apart along the axis.
        let cases = [
            ("oblate over oblate", &oblate, &oblate, 1.0 + gap, upright),
            (
                "oblate under oblate",
                &oblate,
                &oblate,
                -(1.0 + gap),
                about_axis,
            ),
            (
                "prolate over prolate",
                &prolate,
                &prolate,
                2.0 + gap,
                flipped,
            ),
            ("prolate over oblate", &oblate, &prolate, 1.5 + gap, upright),
            (
                "small oblate over oblate",
                &oblate,
                &small,
                0.8 + gap,
                about_axis,
            ),
            ("disk over oblate", &oblate, &disk, 0.5 + gap, flipped),
            ("oblate over disk", &disk, &oblate, 0.5 + gap, upright),
        ];
        for (name, a, b, z, turn) in cases {
            let evaluations = check(&format!("{name}, gap {gap}"), a, b, z, turn);
            if name.contains("disk") {
                worst_disk = worst_disk.max(evaluations);
            } else {
                worst = worst.max(evaluations);
            }
        }
    }
    // Measured: at most 512 (prolate over oblate, gap 0.05) over the solids; the general rule
    // took 2,338 at gap 0.1 for the stacked oblate pair.
    assert!(worst <= 800, "{worst} evaluations");
    // The disk is integrated over by the aimed lamina rule, whose angular rule then has
    // 8 nodes per half-range (`COAXIAL_ANGLES`): at most 818 (gap 0.05); with the rule
    // clustered toward one point of the focal circle, 1,298.
    assert!(worst_disk <= 1000, "{worst_disk} evaluations over the disk");
}

/// Just off the axis the exact rule (8 azimuths at every level) is not used: it would not
/// resolve the offset. The near-axis rule (pole on the axis, azimuths growing with the level)
/// certifies, with more evaluations than the 336 of the exact rule at this gap (884 measured).
#[test]
fn an_offset_off_the_axis_takes_growing_azimuths() {
    let a = oblate();
    let pose_a = Pose::identity();
    let pose_b =
        Pose::from_position_rotation(Vec3::new(1e-6, 0.0, 1.1), UnitQuaternion::identity());
    let result = InteractionEngine::default()
        .interact(&a, &pose_a, &a, &pose_b)
        .unwrap();
    assert!(result.error_estimate <= TOLERANCE);
    let (reference, _) =
        independent_reference(&a, &pose_a, &a, &pose_b, REFERENCE_TOLERANCE).unwrap();
    let error = interaction_error(&result, &reference);
    assert!(
        error <= result.error_estimate + reference.error_estimate,
        "{error:.2e}"
    );
    assert!(
        result.evaluations > 500,
        "{} evaluations",
        result.evaluations
    );
}

/// Parallel axes with a small lateral offset (issue 12's "parallel axes, mostly axial
/// offset"): the pole stays on X's axis (`NEAR_AXIS` in `aimed.rs`) and the results certify
/// and agree with the reference. Two oblate spheroids at axial gap 0.1 and lateral offsets 0.05
/// to 0.3 took 2,346 to 1,894 evaluations with the pole aimed at one point of the other's
/// focal circle; on the axis, at most 1,202 (measured), bounded here by 1,500.
#[test]
fn parallel_axes_with_a_small_offset_keep_the_pole_on_the_axis() {
    let a = oblate();
    let pose_a = Pose::identity();
    for offset in [0.05, 0.1, 0.3] {
        let pose_b = Pose::from_position_rotation(
            Vec3::new(offset, 0.0, 1.1),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3),
        );
        let result = InteractionEngine::default()
            .interact(&a, &pose_a, &a, &pose_b)
            .unwrap();
        assert!(result.error_estimate <= TOLERANCE, "offset {offset}");
        let (reference, certified) =
            independent_reference(&a, &pose_a, &a, &pose_b, REFERENCE_TOLERANCE).unwrap();
        assert!(certified);
        let error = interaction_error(&result, &reference);
        assert!(
            error <= result.error_estimate + reference.error_estimate,
            "offset {offset}: true error {error:.2e}"
        );
        assert!(
            result.evaluations <= 1500,
            "offset {offset}: {} evaluations",
            result.evaluations
        );
    }
}

/// Two parallel disks 0.02 apart, slightly off a common axis (case 52 of `near_axis_sweep`,
/// seed 2026): the other disk's rim runs 0.02 under this one across its face, and the aimed
/// lamina rule climbs to its top levels. It used to certify 2.9e-15 from levels 598 and 600
/// (a step clamped at the top) with a true error of 8.3e-9; the ladder now refuses steps of
/// less than half its growth (estimate 9.6e-9 at its last level), and the engine's fallback,
/// the adaptive cubature, certifies: the result must be certified, within its estimate of
/// the true error. The reference is the
/// polar-angle table over each disk, which agree to 2e-16 in force.
#[test]
fn a_clamped_top_level_does_not_certify() {
    use nalgebra::Quaternion;
    use surfgrav_interaction::{
        InteractionError, InteractionOptions, MethodChoice, Parametrisation, SurfaceChoice,
    };
    let a = Body::disk(UniformDisk::new(0.9680432706491904, 1.0).unwrap()).unwrap();
    let b = Body::disk(UniformDisk::new(0.9368924625461992, 1.0).unwrap()).unwrap();
    let pose_a = Pose::identity();
    let turn = UnitQuaternion::from_quaternion(Quaternion::new(
        0.8725609152266854,
        0.0,
        0.0,
        0.48850532158694965,
    ));
    let pose_b = Pose::from_position_rotation(
        Vec3::new(-0.07482637871961181, 0.17382807798891306, 0.02),
        turn,
    );
    let reference = InteractionEngine::new(InteractionOptions {
        method: MethodChoice::FixedRules,
        surface: SurfaceChoice::A,
        parametrisation: Parametrisation::PolarAzimuth,
        max_evaluations: 10_000_000,
        ..Default::default()
    })
    .unwrap()
    .interact(&a, &pose_a, &b, &pose_b)
    .unwrap();
    let (result, certified) = match InteractionEngine::default().interact(&a, &pose_a, &b, &pose_b)
    {
        Ok(r) => (r, true),
        Err(InteractionError::ToleranceNotMet { best, .. }) => (*best, false),
        Err(e) => panic!("{e}"),
    };
    let error = interaction_error(&result, &reference);
    assert!(
        error <= result.error_estimate + reference.error_estimate,
        "certified {certified}: true error {error:.2e}, estimate {:.2e}",
        result.error_estimate
    );
    // The fallback certifies (measured: the adaptive cubature after the ladder's levels).
    assert!(certified, "estimate {:.2e}", result.error_estimate);
}

/// Parallel axes far apart, the other body up to 40° off the axis (the x–z orbit of two flat
/// spheroids in `cli_rotation`): every pose certifies. With the pole kept on the axis for
/// offsets up to half the distance to the other's singular set alone, 8 azimuths at two
/// successive levels hid the azimuthal error from the level change (the two torque forms
/// caught it: not met, estimates 1.0e-12 to 1.7e-11, at 19° to 26° and distance 5); the
/// offset is now also bounded by half X's equatorial radius.
#[test]
fn parallel_axes_far_apart_certify_in_every_direction() {
    let a = Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap();
    let mut engine = InteractionEngine::default();
    for distance in [2.0, 3.25, 5.0] {
        for degrees in 0..=40 {
            let theta = f64::from(degrees).to_radians();
            let pose_b = Pose::from_position_rotation(
                Vec3::new(distance * theta.sin(), 0.0, distance * theta.cos()),
                UnitQuaternion::identity(),
            );
            let result = engine
                .interact(&a, &Pose::identity(), &a, &pose_b)
                .unwrap_or_else(|e| panic!("distance {distance}, {degrees}°: {e}"));
            assert!(result.error_estimate <= TOLERANCE);
        }
    }
}

/// A prolate spheroid 0.02 below an oblate one on a common axis (`near_axis_sweep` seed 2,
/// case 40): the oblate spheroid's focal circle is a ring about the pole, whose polar count
/// (17) the rim weight for points passing beside a pole had cut to 14, below the nearest
/// point's 16; levels 16 and 18 then changed by 7.4e-14 with a true error of 1.2e-13. Taken
/// at full weight (`RIM_WEIGHT` in `aimed.rs`), the ring starts the ladder at 17 and the
/// estimate bounds the error; this fails without it.
#[test]
fn a_ring_about_the_pole_counts_at_full_strength() {
    let a =
        Body::spheroid(Spheroid::new(0.7025776701579083, 1.012346811581447, 1.0).unwrap()).unwrap();
    let b =
        Body::spheroid(Spheroid::new(0.981258448663338, 0.7478713111055548, 1.0).unwrap()).unwrap();
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 1.955);
    check(
        "prolate below oblate, gap 0.02",
        &a,
        &b,
        1.7802181226870017,
        turn,
    );
}

/// Two pairs of `near_axis_sweep` with an oblate spheroid's focal circle as a ring about the
/// pole (seed 10 #41: a prolate spheroid 0.1 below an oblate one, flipped; seed 13 #67: a
/// prolate spheroid above an oblate one, 1.4e-3 off its axis, gap 1): the polar rule's errors
/// oscillate from level to level, and the ladder had certified 1.1e-13 with a true error of
/// 4.0e-13 (levels 16, 18, 20 changing by 1.2e-10 then 1.1e-13) and 2.8e-13 with 4.2e-13 (its
/// first pair). With the ladder's `oscillating` estimate (`aimed_ladder.rs`) both bound the
/// true error; this fails without it.
#[test]
fn a_ring_off_the_pole_is_not_certified_by_a_zero_crossing() {
    let spheroid = |a: f64, c: f64| Body::spheroid(Spheroid::new(a, c, 1.0).unwrap()).unwrap();
    let flip = |x: f64, y: f64| {
        UnitQuaternion::from_axis_angle(
            &nalgebra::Unit::new_normalize(Vector3::new(x, y, 0.0)),
            std::f64::consts::PI,
        )
    };
    let below = certified_within_estimates(
        "prolate 0.1 below a flipped oblate",
        &spheroid(0.4492216711817286, 1.0895237792673398),
        &spheroid(0.634140627585702, 0.32201649271751137),
        &Pose::from_position_rotation(
            Vec3::new(0.0, 0.0, 1.5115402719848512),
            flip(0.8720577082670609, 0.48940305827814545),
        ),
    );
    let beside = certified_within_estimates(
        "prolate above an oblate, 1.4e-3 off its axis",
        &spheroid(0.627776563540511, 0.38523963856164095),
        &spheroid(0.6068007847339769, 1.0643539581210026),
        &Pose::from_position_rotation(
            Vec3::new(
                -0.0014240252287204035,
                8.523478000953461e-5,
                2.449593596682644,
            ),
            flip(0.17185475419479884, 0.985122298732825),
        ),
    );
    assert!(below.error_estimate <= TOLERANCE && beside.error_estimate <= TOLERANCE);
}
