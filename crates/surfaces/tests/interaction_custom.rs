//! User-defined bodies: any potential with a shape, or with any closed surface, in a scene of
//! `Body` values held without generics.

mod interaction_support;

use interaction_support::*;
use std::sync::Arc;
use surfgrav_potentials::{Ellipsoid as SolidEllipsoid, Pose, Potential, Spheroid, UniformDisk};
use surfgrav_surfaces::interaction::{
    interact, Body, BodyShape, InteractionError, MethodChoice, SurfaceChoice,
};
use surfgrav_surfaces::{EllipsoidSurface, Surface};

/// A custom body (a built-in potential seen through `dyn Potential`, with a generic
/// `dyn Surface`) gives the built-in body's interaction, integrated over either body.
#[test]
fn custom_potentials_and_surfaces_match_the_built_in_bodies() {
    let field = Spheroid::new(0.9, 0.4, 1.2).unwrap();
    let surface: Arc<dyn Surface> = Arc::new(
        EllipsoidSurface::spheroid(0.9, 0.4)
            .unwrap()
            .polar_azimuth(),
    );
    let custom = Body::custom(Arc::new(field), BodyShape::Surface(surface)).unwrap();
    let builtin = Body::spheroid(field).unwrap();
    assert!((custom.density() - builtin.density()).abs() <= 1e-12 * builtin.density());
    let other = Body::ellipsoid(SolidEllipsoid::new(1.0, 0.6, 0.3, 0.7).unwrap()).unwrap();
    let pose_a = pose([0.0; 3], [0.3, -0.2, 0.1]);
    let pose_b = pose([1.3, 1.4, 0.5], [0.2, 0.6, -0.4]);
    let reference = interact(&builtin, &pose_a, &other, &pose_b).unwrap();
    for surface_choice in [SurfaceChoice::A, SurfaceChoice::B] {
        let mut e = engine(options(1e-12, MethodChoice::FixedRules, surface_choice));
        let r = e.interact(&custom, &pose_a, &other, &pose_b).unwrap();
        let err = errors(&r, &reference).max();
        assert!(
            err <= r.error_estimate + reference.error_estimate,
            "{surface_choice:?}: {err:e}"
        );
    }
    // Adaptive over the user surface too.
    let mut adaptive = engine(options(1e-10, MethodChoice::Adaptive, SurfaceChoice::A));
    let r = adaptive
        .interact(&custom, &pose_a, &other, &pose_b)
        .unwrap();
    assert!(errors(&r, &reference).max() <= r.error_estimate + reference.error_estimate);
}

/// A scene holds bodies of different kinds in one `Vec<Body>`; every pair is evaluated and
/// the total force vanishes.
#[test]
fn a_scene_of_mixed_bodies_conserves_momentum() {
    let user: Arc<dyn Potential> = Arc::new(SolidEllipsoid::new(0.7, 0.5, 0.4, 1.0).unwrap());
    let scene: Vec<(Body, Pose)> = vec![
        (paper_spheroid(), pose([0.0; 3], [0.0; 3])),
        (
            Body::disk(UniformDisk::new(0.6, 0.8).unwrap()).unwrap(),
            pose([2.5, 0.3, 0.4], [0.3, 0.0, 0.0]),
        ),
        (
            Body::custom(
                user,
                BodyShape::Solid(EllipsoidSurface::new(0.7, 0.5, 0.4).unwrap()),
            )
            .unwrap(),
            pose([0.2, 2.6, -0.5], [0.0, 0.4, 0.9]),
        ),
    ];
    let mut total = surfgrav_potentials::Vec3::zeros();
    let mut scale: f64 = 0.0;
    let mut worst_estimate: f64 = 0.0;
    for i in 0..scene.len() {
        for j in i + 1..scene.len() {
            let r = interact(&scene[i].0, &scene[i].1, &scene[j].0, &scene[j].1).unwrap();
            total += r.force_on_a + r.force_on_b;
            scale = scale.max(r.force_on_a.norm());
            worst_estimate = worst_estimate.max(r.error_estimate);
        }
    }
    assert!(total.norm() <= 4.0 * f64::EPSILON * scale);
    assert!(worst_estimate <= 1e-12);
    // Printing a body does not dump its node tables.
    let text = format!("{:?}", scene[0].0);
    assert!(
        text.len() < 2_000 && text.contains("cached_tables"),
        "{text}"
    );
}

/// A custom body must describe a body with positive density.
#[test]
fn custom_bodies_need_a_sensible_shape() {
    let field: Arc<dyn Potential> = Arc::new(Spheroid::new(1.0, 0.5, 1.0).unwrap());
    assert!(Body::custom(field.clone(), BodyShape::FieldOnly).is_ok());
    let flat = Body::custom(field, BodyShape::Point).unwrap();
    assert!(!flat.has_surface());
    assert!(matches!(
        engine(options(1e-12, MethodChoice::FixedRules, SurfaceChoice::A)).interact(
            &flat,
            &Pose::identity(),
            &paper_spheroid(),
            &pose([3.0, 0.0, 0.0], [0.0; 3])
        ),
        Err(InteractionError::NoSurface { .. })
    ));
}
