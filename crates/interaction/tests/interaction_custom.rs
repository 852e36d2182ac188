//! User-defined bodies: any potential with a shape, or with any closed surface, in a scene of
//! `Body` values held without generics.

mod interaction_support;

use interaction_support::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use surfgrav_interaction::{
    interact, Body, BodyShape, Interaction, InteractionEngine, InteractionError, Method,
    MethodChoice, Pair, PairRule, SurfaceChoice,
};
use surfgrav_potentials::{
    Ellipsoid as SolidEllipsoid, Pose, Potential, Sphere, Spheroid, Symmetry, TypedPotential,
    UniformDisk,
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

/// A user's potential: a built-in field behind a wrapper type the engine does not know
/// (`as_typed` is `Custom`), reporting the field's symmetry, singular radius and cost when
/// `report` is set, nothing otherwise.
#[derive(Debug)]
struct Wrapped<P> {
    inner: P,
    report: bool,
}

impl<P: Potential> Potential for Wrapped<P> {
    fn mass(&self) -> f64 {
        self.inner.mass()
    }
    fn gravitational_constant(&self) -> f64 {
        self.inner.gravitational_constant()
    }
    fn volume(&self) -> f64 {
        self.inner.volume()
    }
    fn bounding_radius(&self) -> f64 {
        self.inner.bounding_radius()
    }
    fn region(&self, r: &surfgrav_potentials::Vec3) -> surfgrav_potentials::Region {
        self.inner.region(r)
    }
    fn field(&self, r: &surfgrav_potentials::Vec3) -> surfgrav_potentials::Field {
        self.inner.field(r)
    }
    fn potential(&self, r: &surfgrav_potentials::Vec3) -> f64 {
        self.inner.potential(r)
    }
    fn inertia(&self) -> Option<surfgrav_potentials::InertiaTensor> {
        self.inner.inertia()
    }
    fn symmetry(&self) -> Symmetry {
        if self.report {
            self.inner.symmetry()
        } else {
            Symmetry::None
        }
    }
    fn singular_radius(&self) -> Option<f64> {
        self.report.then(|| self.inner.singular_radius()).flatten()
    }
    fn field_cost(&self) -> f64 {
        if self.report {
            self.inner.field_cost()
        } else {
            1.0
        }
    }
}

/// The spheroid of [`paper_spheroid`] as a custom body, reporting its properties or not.
fn wrapped_spheroid(report: bool) -> Body {
    let inner = Spheroid::new(1.0, 0.25, 1.0).unwrap();
    let surface = EllipsoidSurface::spheroid(1.0, 0.25).unwrap();
    Body::custom(
        Arc::new(Wrapped { inner, report }),
        BodyShape::Solid(surface),
    )
    .unwrap()
}

/// A custom potential that reports its symmetry, singular radius and cost gets the built-in
/// spheroid's fast paths: the same surface, method, evaluation count and level, and, since
/// the field values are the same numbers (through `dyn Potential` instead of a monomorphised
/// loop) summed in the same order, the same result bit for bit. Poses: the founding paper's
/// coplanar pair (both mirror symmetries: quartered tables), a pair lifted out of the plane
/// (one mirror plane) and a general pose (none); the partner is a built-in spheroid or an
/// ellipsoid; the ladder, the nested rule and the adaptive rule.
#[test]
fn a_custom_potential_that_reports_its_kind_gets_the_built_in_fast_paths() {
    let builtin = paper_spheroid();
    let custom = wrapped_spheroid(true);
    assert_eq!(custom.symmetry(), builtin.symmetry());
    assert_eq!(custom.symmetry(), Symmetry::Axisymmetric);
    assert_eq!(custom.singular_radius(), builtin.singular_radius());
    assert!(matches!(custom.typed(), TypedPotential::Custom));
    assert!(matches!(builtin.typed(), TypedPotential::Spheroid(_)));
    let partners = [
        paper_spheroid(),
        Body::ellipsoid(SolidEllipsoid::new(0.9, 0.6, 0.3, 0.7).unwrap()).unwrap(),
    ];
    let poses = [
        pose([2.3, 0.0, 0.0], [0.0; 3]),
        pose([2.2, 0.0, 0.6], [0.0; 3]),
        pose([1.9, 1.1, 0.5], [0.3, -0.2, 0.4]),
    ];
    let methods = [
        (MethodChoice::Automatic, 1e-12),
        (MethodChoice::Nested, 1e-12),
        (MethodChoice::Adaptive, 1e-8),
    ];
    let mut quartered = 0;
    for partner in &partners {
        for pose_b in &poses {
            for (method, tolerance) in methods {
                for builtin_is_a in [true, false] {
                    let order = |own: &'static str| -> [&Body; 2] {
                        let body = if own == "custom" { &custom } else { &builtin };
                        if builtin_is_a {
                            [body, partner]
                        } else {
                            [partner, body]
                        }
                    };
                    let ([a, b], [ca, cb]) = (order("builtin"), order("custom"));
                    let options = options(tolerance, method, SurfaceChoice::Automatic);
                    let expected = engine(options)
                        .interact(a, &Pose::identity(), b, pose_b)
                        .unwrap();
                    let got = engine(options)
                        .interact(ca, &Pose::identity(), cb, pose_b)
                        .unwrap();
                    let case = format!("{method:?} {pose_b:?}");
                    assert_eq!(got.method, expected.method, "{case}");
                    assert_eq!(got.integrated_over, expected.integrated_over, "{case}");
                    assert_eq!(got.evaluations, expected.evaluations, "{case}");
                    assert_eq!(got.level, expected.level, "{case}");
                    assert_eq!(got.force_on_a, expected.force_on_a, "{case}");
                    assert_eq!(got.torque_on_a, expected.torque_on_a, "{case}");
                    assert_eq!(got.torque_on_b, expected.torque_on_b, "{case}");
                    assert_eq!(got.potential_energy, expected.potential_energy, "{case}");
                    assert_eq!(got.error_estimate, expected.error_estimate, "{case}");
                    // Without the reported symmetry the coplanar pair costs 4 times more.
                    let silent = engine(options)
                        .interact(&wrapped_spheroid(false), &Pose::identity(), partner, pose_b)
                        .unwrap();
                    if silent.evaluations > expected.evaluations {
                        quartered += 1;
                    }
                }
            }
        }
    }
    // The symmetric poses (two of three) save evaluations under every method and partner
    // order where the custom body's field is the one integrated in.
    assert!(quartered > 0, "no case used the reported symmetry");
}

/// A custom potential that reports nothing still works, by the generic path: no mirror
/// halving, the bounding radius as its singular radius, a spheroid's cost. Its results agree
/// with the built-in spheroid's within the two error estimates, and it never spends fewer
/// evaluations than the built-in body's fast path on the symmetric coplanar pair.
#[test]
fn a_custom_potential_that_reports_nothing_takes_the_generic_path() {
    let builtin = paper_spheroid();
    let silent = wrapped_spheroid(false);
    assert_eq!(silent.symmetry(), Symmetry::None);
    assert_eq!(silent.singular_radius(), builtin.singular_radius());
    let partner = paper_spheroid();
    for pose_b in [
        pose([2.3, 0.0, 0.0], [0.0; 3]),
        pose([1.9, 1.1, 0.5], [0.3, -0.2, 0.4]),
    ] {
        for surface in [SurfaceChoice::A, SurfaceChoice::B] {
            let options = options(1e-12, MethodChoice::Automatic, surface);
            let expected = engine(options)
                .interact(&builtin, &Pose::identity(), &partner, &pose_b)
                .unwrap();
            let got = engine(options)
                .interact(&silent, &Pose::identity(), &partner, &pose_b)
                .unwrap();
            let err = errors(&got, &expected).max();
            assert!(
                err <= got.error_estimate + expected.error_estimate,
                "{surface:?} {pose_b:?}: {err:e}"
            );
            assert!(got.evaluations >= expected.evaluations);
        }
    }
    // The silent body's field is integrated in without mirror halving.
    let coplanar = pose([2.3, 0.0, 0.0], [0.0; 3]);
    let options = options(1e-12, MethodChoice::FixedRules, SurfaceChoice::B);
    let fast = engine(options)
        .interact(&builtin, &Pose::identity(), &partner, &coplanar)
        .unwrap();
    let slow = engine(options)
        .interact(&silent, &Pose::identity(), &partner, &coplanar)
        .unwrap();
    assert!(slow.evaluations > fast.evaluations);
}

/// A user's pair rule that never applies, counting how often it is asked.
#[derive(Debug, Default)]
struct Abstaining {
    asked: AtomicUsize,
}

impl PairRule for Abstaining {
    fn interact(&self, _: &Pair<'_>) -> Result<Option<Interaction>, InteractionError> {
        self.asked.fetch_add(1, Ordering::Relaxed);
        Ok(None)
    }
}

/// The pair dispatcher is a chain: a user's rule is asked first, once per interaction; when
/// it abstains the built-in closed forms and then the surface integral answer exactly as
/// without it; a pair with no surface and no closed form is the typed `NoSurface` error.
#[test]
fn pair_rules_are_asked_first_and_fall_through() {
    let rule = Arc::new(Abstaining::default());
    let mut chained = InteractionEngine::default().with_pair_rule(rule.clone());
    let mut plain = InteractionEngine::default();
    let sphere = Body::sphere(Sphere::new(0.5, 2.0).unwrap()).unwrap();
    let spheroid = paper_spheroid();
    let pose_b = pose([1.9, 1.1, 0.5], [0.3, -0.2, 0.4]);
    for (a, b, method) in [
        (&sphere, &spheroid, Method::AnalyticPoint),
        (&spheroid, &spheroid, Method::SurfaceOverA),
    ] {
        let expected = plain.interact(a, &Pose::identity(), b, &pose_b).unwrap();
        let got = chained.interact(a, &Pose::identity(), b, &pose_b).unwrap();
        assert_eq!(got.method, method);
        assert_eq!(got, expected);
    }
    assert_eq!(rule.asked.load(Ordering::Relaxed), 2);
    // No surface on either side and no closed form: the typed error, after asking the rule.
    let field_only = || {
        Body::custom(
            Arc::new(Wrapped {
                inner: Spheroid::new(1.0, 0.5, 1.0).unwrap(),
                report: false,
            }),
            BodyShape::FieldOnly,
        )
        .unwrap()
    };
    let far = pose([5.0, 0.0, 0.0], [0.0; 3]);
    assert!(matches!(
        chained.interact(&field_only(), &Pose::identity(), &field_only(), &far),
        Err(InteractionError::NoSurface { .. })
    ));
    assert_eq!(rule.asked.load(Ordering::Relaxed), 3);
}

/// A field-only custom potential that reports spherical symmetry gets the point formula, the
/// built-in sphere's closed form, with the same numbers bit for bit.
#[test]
fn a_reported_spherical_field_gets_the_point_formula() {
    let inner = Sphere::new(0.5, 2.0).unwrap();
    let custom = Body::custom(
        Arc::new(Wrapped {
            inner,
            report: true,
        }),
        BodyShape::FieldOnly,
    )
    .unwrap();
    assert!(custom.is_spherically_symmetric());
    let builtin = Body::sphere(inner).unwrap();
    let pose_b = pose([1.9, 1.1, 0.5], [0.3, -0.2, 0.4]);
    let expected = interact(&builtin, &Pose::identity(), &paper_spheroid(), &pose_b).unwrap();
    let got = interact(&custom, &Pose::identity(), &paper_spheroid(), &pose_b).unwrap();
    assert_eq!(got.method, Method::AnalyticPoint);
    assert_eq!(got, expected);
}
