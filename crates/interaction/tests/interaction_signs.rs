//! The signs and formulas of the interaction engine against independent routes: volume
//! integrals of ρ a, ρ x × a and ρ Φ over the solid, the exact point-mass and sphere laws, and
//! the closed form for coplanar disks.

mod interaction_support;

use interaction_support::*;
use surfgrav_interaction::{Body, Method, MethodChoice, Side, SurfaceChoice};
use surfgrav_potentials::{
    Ellipsoid as SolidEllipsoid, PointMass, Pose, PoseExt, Potential, Sphere, Spheroid,
    UniformDisk, Vec3,
};
use surfgrav_surfaces::EllipsoidSurface;

struct Case {
    label: &'static str,
    shape_a: EllipsoidSurface,
    body_a: Body,
    body_b: Body,
    source_b: Box<dyn Potential>,
    pose_a: Pose,
    pose_b: Pose,
}

fn cases() -> Vec<Case> {
    let spheroid_b = Spheroid::new(1.0, 0.25, 1.3).unwrap();
    let triaxial_b = SolidEllipsoid::new(0.9, 0.6, 0.4, 0.8).unwrap();
    let disk_b = UniformDisk::new(0.8, 0.7).unwrap();
    vec![
        Case {
            label: "tilted oblate pair",
            shape_a: EllipsoidSurface::spheroid(1.0, 0.25).unwrap(),
            body_a: paper_spheroid(),
            body_b: Body::spheroid(spheroid_b).unwrap(),
            source_b: Box::new(spheroid_b),
            pose_a: pose([0.1, -0.2, 0.05], [0.2, -0.1, 0.3]),
            pose_b: pose([2.3, 0.4, 0.5], [0.5, 0.3, -0.2]),
        },
        Case {
            label: "triaxial pair",
            shape_a: EllipsoidSurface::new(0.8, 0.5, 0.3).unwrap(),
            body_a: Body::ellipsoid(SolidEllipsoid::new(0.8, 0.5, 0.3, 1.1).unwrap()).unwrap(),
            body_b: Body::ellipsoid(triaxial_b).unwrap(),
            source_b: Box::new(triaxial_b),
            pose_a: pose([0.0, 0.0, 0.0], [0.4, 0.7, -0.2]),
            pose_b: pose([1.2, -1.1, 0.6], [-0.3, 0.2, 0.9]),
        },
        Case {
            label: "prolate A beside a tilted disk",
            shape_a: EllipsoidSurface::spheroid(0.4, 0.9).unwrap(),
            body_a: Body::spheroid(Spheroid::new(0.4, 0.9, 0.6).unwrap()).unwrap(),
            body_b: Body::disk(disk_b).unwrap(),
            source_b: Box::new(disk_b),
            pose_a: pose([0.0, 0.0, 0.0], [0.3, 0.0, 0.0]),
            pose_b: pose([0.3, 1.6, 0.8], [0.9, 0.4, 0.0]),
        },
    ]
}

/// Force, torque and energy on A by the surface integrals (over A and over B) agree with
/// volume integrals of the defining formulas $\rho\int\mathbf a$, $\rho\int\mathbf x\times\mathbf a$,
/// $\rho\int\Phi$: every sign of the module docs is checked here.
#[test]
fn surface_integrals_equal_volume_integrals() {
    for case in cases() {
        let mass = case.body_a.mass();
        let (f40, m40, v40) = volume_integrals(
            &case.shape_a,
            mass,
            &case.pose_a,
            case.source_b.as_ref(),
            &case.pose_b,
            40,
        );
        let (f, m, v) = volume_integrals(
            &case.shape_a,
            mass,
            &case.pose_a,
            case.source_b.as_ref(),
            &case.pose_b,
            56,
        );
        // The reference's own convergence, measured by two resolutions.
        let reference_error = ((f - f40).norm() / f.norm())
            .max((v - v40).abs() / v.abs())
            .max((m - m40).norm() / m.norm().max(v.abs()));
        assert!(
            reference_error < 1e-12,
            "{}: volume quadrature {reference_error:e}",
            case.label
        );
        for surface in [SurfaceChoice::A, SurfaceChoice::B] {
            let mut e = engine(options(1e-12, MethodChoice::FixedRules, surface));
            let r = e
                .interact(&case.body_a, &case.pose_a, &case.body_b, &case.pose_b)
                .unwrap();
            let bound = r.error_estimate + reference_error;
            let force_error = (r.force_on_a - f).norm() / f.norm();
            let energy_error = (r.potential_energy - v).abs() / v.abs();
            let torque_error = (r.torque_on_a - m).norm() / m.norm().max(v.abs());
            assert!(
                force_error <= bound && energy_error <= bound && torque_error <= bound,
                "{} over {surface:?}: errors F {force_error:e} V {energy_error:e} M {torque_error:e} > {bound:e}",
                case.label
            );
            assert!(r.potential_energy < 0.0);
            assert!(r.error_estimate <= 1e-12);
        }
    }
}

/// A sphere's surface integral equals the point formula: $\mathbf F = m\\,\mathbf a(\mathbf c)$,
/// $V = m\\,\Phi(\mathbf c)$, no torque on the sphere.
#[test]
fn sphere_surface_integral_equals_point_formula() {
    let sphere = Body::sphere(Sphere::new(0.7, 2.0).unwrap()).unwrap();
    let others = [
        Body::spheroid(Spheroid::new(1.0, 0.3, 1.5).unwrap()).unwrap(),
        Body::ellipsoid(SolidEllipsoid::new(1.0, 0.6, 0.3, 0.5).unwrap()).unwrap(),
        Body::disk(UniformDisk::new(1.1, 0.9).unwrap()).unwrap(),
    ];
    let pose_s = pose([0.3, -0.4, 0.2], [0.1, 0.2, 0.3]);
    let pose_o = pose([1.9, 0.6, -0.7], [0.6, -0.4, 0.2]);
    for other in &others {
        let mut exact = engine(options(
            1e-12,
            MethodChoice::Automatic,
            SurfaceChoice::Automatic,
        ));
        let point = exact.interact(&sphere, &pose_s, other, &pose_o).unwrap();
        assert_eq!(point.method, Method::AnalyticPoint);
        assert_eq!(point.torque_on_a, Vec3::zeros());
        let field = other
            .potential()
            .field_in_world(&pose_o, &pose_s.position());
        assert_eq!(point.force_on_a, field.acceleration * 2.0);
        assert_eq!(point.potential_energy, field.potential * 2.0);
        let mut quadrature = engine(options(1e-12, MethodChoice::FixedRules, SurfaceChoice::A));
        let integral = quadrature
            .interact(&sphere, &pose_s, other, &pose_o)
            .unwrap();
        assert_eq!(integral.integrated_over, Some(Side::A));
        let err = errors(&integral, &point);
        assert!(
            err.max() <= integral.error_estimate + point.error_estimate,
            "{other:?}: {err:?} vs estimate {:e}",
            integral.error_estimate
        );
    }
}

/// Two point masses: Newton's law with the workspace's signs.
#[test]
fn point_masses_attract_with_negative_energy() {
    let g = 6.674_30e-11;
    let a = Body::point_mass(
        PointMass::new(3.0)
            .unwrap()
            .with_gravitational_constant(g)
            .unwrap(),
    );
    let b = Body::point_mass(
        PointMass::new(5.0)
            .unwrap()
            .with_gravitational_constant(g)
            .unwrap(),
    );
    let pose_a = pose([1.0, 2.0, 3.0], [0.0; 3]);
    let pose_b = pose([4.0, 6.0, 3.0], [0.0; 3]);
    let r = surfgrav_interaction::interact(&a, &pose_a, &b, &pose_b).unwrap();
    let gmm = g * 15.0;
    let toward_b = Vec3::new(3.0, 4.0, 0.0) / 5.0;
    assert!(
        (r.force_on_a - toward_b * (gmm / 25.0)).norm() <= tolerance::ACCELERATION_REL * gmm / 25.0
    );
    assert_eq!(r.force_on_b, -r.force_on_a);
    assert!((r.potential_energy + gmm / 5.0).abs() <= tolerance::POTENTIAL_REL * gmm / 5.0);
    assert_eq!(r.torque_on_a, Vec3::zeros());
    // (c_A − c_B) × F_A vanishes up to the rounding of F_A's direction.
    assert!(r.torque_on_b.norm() <= 4.0 * f64::EPSILON * gmm / 5.0);
    assert_eq!(r.method, Method::AnalyticPoint);
    assert_eq!(r.evaluations, 1);
}

/// Coplanar disks take the closed form: attraction along the line of centres, no torques.
#[test]
fn coplanar_disks_use_the_closed_form() {
    let da = UniformDisk::new(1.0, 1.0).unwrap();
    let db = UniformDisk::new(0.5, 2.0).unwrap();
    let a = Body::disk(da).unwrap();
    let b = Body::disk(db).unwrap();
    // Both disks in the world plane tilted by the same rotation.
    let tilt = [0.3, -0.2, 0.5];
    let pose_a = pose([0.0, 0.0, 0.0], tilt);
    let in_plane = pose_a.rotation * Vec3::new(1.2, 1.0, 0.0);
    let pose_b = Pose::new(in_plane, Vec3::from(tilt));
    let r = surfgrav_interaction::interact(&a, &pose_a, &b, &pose_b).unwrap();
    assert_eq!(r.method, Method::AnalyticDiskPair);
    let closed = surfgrav_potentials::coplanar_disk_interaction(&da, &db, in_plane.norm()).unwrap();
    assert_eq!(r.potential_energy, closed.potential_energy);
    let along = in_plane / in_plane.norm();
    assert!(
        ((r.force_on_b - along * closed.radial_force).norm()) <= 1e-15 * closed.radial_force.abs()
    );
    assert!(r.force_on_a.dot(&along) > 0.0, "A is pulled toward B");
    assert_eq!(r.torque_on_a, Vec3::zeros());
    assert_eq!(r.torque_on_b, Vec3::zeros());
}
