//! A polyhedron far from a solid partner: the integral over the partner's surface in the
//! polyhedron's expansion is certified at the default tolerance however far apart they are.
//! (The truncation term of the estimate once took the potential form's amplification, d/s,
//! while the engine sums the acceleration form far away: a unit cube with a (1, 0.7, 0.4)
//! ellipsoid missed 1e-12 from 300 apart, 5.1e-12 at 1000, 5.1e-11 at 1e4.)

use surfgrav_interaction::{Body, InteractionEngine, InteractionOptions, SurfaceChoice};
use surfgrav_potentials::{Ellipsoid, Mesh, Polyhedron, Pose, Vec3};

#[test]
fn a_far_cube_and_ellipsoid_are_certified_over_either_surface_and_agree() {
    let cube = Body::polyhedron(Polyhedron::with_mass(&Mesh::cube(1.0), 2.0).unwrap()).unwrap();
    let ellipsoid = Body::ellipsoid(Ellipsoid::new(1.0, 0.7, 0.4, 1.5).unwrap()).unwrap();
    for distance in [30.0, 300.0, 1e3, 1e4] {
        let pose_b = Pose::new(Vec3::new(distance, 0.0, 0.0), Vec3::new(0.2, 0.3, 0.1));
        let run = |surface| {
            let options = InteractionOptions {
                surface,
                ..InteractionOptions::default()
            };
            let mut engine = InteractionEngine::new(options).unwrap();
            engine
                .interact(&cube, &Pose::identity(), &ellipsoid, &pose_b)
                .unwrap_or_else(|e| panic!("{distance} apart over {surface:?}: {e}"))
        };
        let (auto, over_cube, over_ellipsoid) = (
            run(SurfaceChoice::Automatic),
            run(SurfaceChoice::A),
            run(SurfaceChoice::B),
        );
        for r in [&auto, &over_cube, &over_ellipsoid] {
            assert!(
                r.error_estimate <= 1e-12,
                "{distance}: {}",
                r.error_estimate
            );
        }
        // Two independent surfaces: their forces differ by no more than the two estimates
        // (each relative to |F|) plus a few ulps of the sums.
        let gap =
            (over_cube.force_on_a - over_ellipsoid.force_on_a).norm() / over_cube.force_on_a.norm();
        let allowed = over_cube.error_estimate + over_ellipsoid.error_estimate + 1e-15;
        assert!(gap <= allowed, "{distance}: {gap:e} > {allowed:e}");
        // Far away the force tends to the point masses' G m_A m_B / d^2, to O((R/d)^2).
        let point = 2.0 * 1.5 / (distance * distance);
        let bound = 3.0 * (1.75_f64 / distance).powi(2);
        assert!(
            (auto.force_on_a.x / point - 1.0).abs() <= bound,
            "{distance}"
        );
    }
}
