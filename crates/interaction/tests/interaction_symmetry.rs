//! The mirror symmetries the engine exploits (half node sets whose sums are completed by their
//! mirror images) change nothing but the cost: every method gives the same force, torques and
//! energy with `exploit_symmetry` on and off, for poses with two, one and no mirror planes,
//! near (gap 0.1), at the founding paper's separations and beyond the far-field switch
//! (60 radii, where the acceleration form of the force is summed).

mod interaction_support;

use interaction_support::*;
use surfgrav_interaction::{Body, InteractionOptions, MethodChoice};
use surfgrav_potentials::{Pose, Spheroid, UniformDisk};

/// A fixed table sums the same nodes either way, in another order: the difference is
/// rounding of sums of a few hundred terms (measured at most 3.2e-16 over these cases); a
/// wrong sign in a mirror image's contribution shows as 1e-2 or more.
const SAME_NODES: f64 = 1e-14;

#[test]
fn symmetric_and_full_node_sets_agree() {
    let prolate = || Body::spheroid(Spheroid::new(0.5, 1.2, 0.8).unwrap()).unwrap();
    let disk = || Body::disk(UniformDisk::new(0.9, 0.7).unwrap()).unwrap();
    let mut cases: Vec<(String, Body, Pose)> = vec![];
    for d in [2.1, 3.0, 30.0, 60.0] {
        // Two mirror planes (the paper's pair), one (B's axis tilted in the x-z plane), none.
        cases.push((
            format!("paper pair {d}"),
            paper_spheroid(),
            pose([d, 0.0, 0.0], [0.0; 3]),
        ));
        cases.push((
            format!("prolate tilted in x-z, {d}"),
            prolate(),
            pose([d + 0.3, 0.0, 0.0], [0.0, 0.5, 0.0]),
        ));
        cases.push((
            format!("prolate, no symmetry, {d}"),
            prolate(),
            pose([d + 0.3, 0.4, 0.2], [0.3, 0.5, 0.1]),
        ));
        // A lamina, above the plane and tilted (its own mirror-completed sums).
        cases.push((
            format!("disk above, tilted, {d}"),
            disk(),
            pose([d, 0.0, 0.5], [0.0, 0.4, 0.0]),
        ));
    }
    let mut worst: f64 = 0.0;
    for (label, b, pose_b) in &cases {
        let a = paper_spheroid();
        for method in [
            MethodChoice::FixedLevel(12),
            MethodChoice::FixedRules,
            MethodChoice::Nested,
        ] {
            let run = |exploit_symmetry| {
                let options = InteractionOptions {
                    method,
                    exploit_symmetry,
                    ..InteractionOptions::default()
                };
                best_effort(&mut engine(options), &a, &Pose::identity(), b, pose_b)
            };
            let (half, full) = (run(true), run(false));
            let difference = errors(&half, &full).max();
            let bound = match method {
                MethodChoice::FixedLevel(_) => SAME_NODES,
                // Certified results: each within its own estimate of the truth.
                _ => half.error_estimate + full.error_estimate,
            };
            if matches!(method, MethodChoice::FixedLevel(_)) {
                worst = worst.max(difference);
            }
            assert!(
                difference <= bound,
                "{label}, {method:?}: symmetric and full differ by {difference:e} (bound {bound:e}; evaluations {} vs {})",
                half.evaluations,
                full.evaluations
            );
        }
    }
    println!("largest fixed-table difference: {worst:e}");
}
