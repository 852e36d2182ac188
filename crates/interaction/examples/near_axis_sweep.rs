//! Random near-axial pairs (issue 12's "parallel axes, mostly axial offset"): spheroids and
//! disks of random sizes and aspects on parallel axes, axial gaps 0.02 to 1, lateral offsets
//! 0 to 0.75, B turned about the axis or flipped. Each is certified to 1e-12 and checked
//! against the independent reference (the ladder at 1e-13 over the other body); prints the
//! violations (a true error above the two estimates) and the total evaluations. The numbers
//! behind `NEAR_AXIS_AZIMUTH_RATIO` in `aimed.rs`.
//!
//! `cargo run --release -p surfgrav-interaction --example near_axis_sweep [-- SEED]`

use nalgebra::{UnitQuaternion, Vector3};
use surfgrav_interaction::work_precision::{independent_reference, interaction_error, SplitMix64};
use surfgrav_interaction::{Body, InteractionEngine};
use surfgrav_potentials::{Pose, PoseExt, Spheroid, UniformDisk, Vec3};

/// A random body of revolution and its half-height along its axis.
fn body(rng: &mut SplitMix64) -> Result<(Body, f64), Box<dyn std::error::Error>> {
    let equatorial = 0.4 + 0.8 * rng.uniform();
    let polar = 0.2 + rng.uniform();
    Ok(if rng.uniform() < 0.15 {
        (Body::disk(UniformDisk::new(equatorial, 1.0)?)?, 0.0)
    } else {
        (
            Body::spheroid(Spheroid::new(equatorial, polar, 1.0)?)?,
            polar,
        )
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let seed: u64 = std::env::args().nth(1).map_or(Ok(2026), |s| s.parse())?;
    let mut rng = SplitMix64::new(seed);
    let (mut checked, mut violations, mut failed, mut evaluations) = (0, 0, 0, 0usize);
    for i in 0..80 {
        let (a, half_a) = body(&mut rng)?;
        let (b, half_b) = body(&mut rng)?;
        let gap = [0.02, 0.1, 0.3, 1.0][i % 4];
        let flip = if rng.uniform() < 0.5 {
            UnitQuaternion::identity()
        } else {
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
        };
        let turn = UnitQuaternion::from_axis_angle(
            &Vector3::z_axis(),
            std::f64::consts::TAU * rng.uniform(),
        ) * flip;
        let offset = [0.0, 1e-3, 0.05, 0.2, 0.5][(i / 4) % 5] * (0.5 + rng.uniform());
        let phi = std::f64::consts::TAU * rng.uniform();
        let position = Vec3::new(
            offset * phi.cos(),
            offset * phi.sin(),
            half_a + half_b + gap,
        );
        let (pose_a, pose_b) = (
            Pose::identity(),
            Pose::from_position_rotation(position, turn),
        );
        let result = match InteractionEngine::default().interact(&a, &pose_a, &b, &pose_b) {
            Ok(r) => r,
            Err(e) => {
                println!("case {i} (gap {gap}, offset {offset:.3}): {e}");
                failed += 1;
                continue;
            }
        };
        let (reference, certified) = independent_reference(&a, &pose_a, &b, &pose_b, 1e-13)?;
        let error = interaction_error(&result, &reference);
        checked += 1;
        evaluations += result.evaluations;
        if !certified || error > result.error_estimate + reference.error_estimate {
            violations += 1;
            println!(
                "case {i}: true error {error:.1e}, estimate {:.1e}, reference {:.1e}",
                result.error_estimate, reference.error_estimate
            );
        }
    }
    println!("seed {seed}: {checked} checked, {violations} violations, {failed} failed, {evaluations} evaluations");
    Ok(())
}
