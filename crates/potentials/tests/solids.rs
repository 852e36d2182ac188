//! The homogeneous solids (point mass, sphere, spheroid, ellipsoid) and the fused Carlson
//! integrals behind them.
//!
//! Each test checks a law, an identity or an independent evaluation that a wrong formula would
//! break: the spheroid's elementary forms against the ellipsoid's Carlson forms, a gradient
//! against finite differences, Laplace and Poisson, continuity across the surface and through
//! the sphere, the far-field J2, the symmetries, and a few values of the Dirichlet integral at
//! 36 digits.

use std::f64::consts::PI;

use surfgrav_potentials::carlson::symmetric_integrals;
use surfgrav_potentials::tolerance::{ACCELERATION_REL, FINITE_DIFFERENCE_REL, POTENTIAL_REL};
use surfgrav_potentials::{
    BodyError, Ellipsoid, Field, PointMass, Potential, Region, Sphere, Spheroid, Vec3,
};

// ---------------------------------------------------------------------------------------------
// Helpers

fn rel(value: f64, reference: f64) -> f64 {
    ((value - reference) / reference).abs()
}

/// |value − reference| / |reference|, scaled so that no square underflows or overflows.
fn rel_vec(value: &Vec3, reference: &Vec3) -> f64 {
    let s = reference.amax();
    ((value - reference) / s).norm() / (reference / s).norm()
}

/// Largest relative differences in Φ and in the acceleration between two fields.
fn field_difference(f: &Field, reference: &Field) -> (f64, f64) {
    (
        rel(f.potential, reference.potential),
        rel_vec(&f.acceleration, &reference.acceleration),
    )
}

/// Deterministic directions spread over the sphere (Fibonacci lattice).
fn directions(n: usize) -> Vec<Vec3> {
    let golden = (1.0 + 5f64.sqrt()) / 2.0;
    (0..n)
        .map(|k| {
            let z = 1.0 - 2.0 * (k as f64 + 0.5) / n as f64;
            let phi = 2.0 * PI * (k as f64 / golden).fract();
            let s = (1.0 - z * z).sqrt();
            Vec3::new(s * phi.cos(), s * phi.sin(), z)
        })
        .collect()
}

/// Directions that include the axes, the axis diagonals and grazing angles, plus a lattice.
fn probe_directions() -> Vec<Vec3> {
    let mut dirs = vec![
        Vec3::x(),
        Vec3::y(),
        Vec3::z(),
        Vec3::new(1.0, 1.0, 0.0).normalize(),
        Vec3::new(1.0, 0.0, 1e-6).normalize(),
        Vec3::new(1e-6, 0.0, 1.0).normalize(),
        Vec3::new(0.6, -0.7, 1e-9).normalize(),
    ];
    dirs.extend(directions(24));
    dirs
}

/// The point where the ray along `dir` meets the ellipsoid with `semi_axes`.
fn surface_point(semi_axes: [f64; 3], dir: &Vec3) -> Vec3 {
    let t = 1.0
        / ((dir.x / semi_axes[0]).powi(2)
            + (dir.y / semi_axes[1]).powi(2)
            + (dir.z / semi_axes[2]).powi(2))
        .sqrt();
    dir * t
}

/// Fourth-order central difference (Richardson on steps h and h/2).
fn richardson<F: Fn(f64) -> f64>(f: F, h: f64) -> f64 {
    let d = |h: f64| (f(h) - f(-h)) / (2.0 * h);
    (4.0 * d(h / 2.0) - d(h)) / 3.0
}

/// Relative disagreement between the acceleration and −∇Φ by finite differences, scaled as
/// in the conformance suite (the difference quotient's cancellation is ≈ ε|Φ|/h).
fn gradient_error(body: &dyn Potential, r: &Vec3, h: f64) -> f64 {
    let a = body.acceleration(r);
    let mut fd = Vec3::zeros();
    for i in 0..3 {
        let e = Vec3::ith(i, 1.0);
        fd[i] = -richardson(|t| body.potential(&(r + e * t)), h);
    }
    let scale = a.norm().max(body.potential(r).abs() / r.norm());
    (a - fd).norm() / scale
}

/// ∇·a by finite differences of the acceleration.
fn divergence(body: &dyn Potential, r: &Vec3, h: f64) -> f64 {
    (0..3)
        .map(|i| {
            let e = Vec3::ith(i, 1.0);
            richardson(|t| body.acceleration(&(r + e * t))[i], h)
        })
        .sum()
}

/// Spheroid shapes c/a over the required range, through the sphere.
const SPHEROID_RATIOS: [f64; 13] = [
    1e-4,
    1e-2,
    0.3,
    0.9,
    1.0 - 1e-9,
    1.0,
    1.0 + 1e-9,
    1.1,
    3.0,
    1e2,
    1e4,
    0.999,
    1.001,
];

// ---------------------------------------------------------------------------------------------
// Carlson's integrals against the `ellip` crate

/// The fused routine against ellip's separate R_F and R_D over arguments spread across 32
/// decades and nearly equal triples. Measured: the fused values are within 3.4 ulp of mpmath
/// everywhere; ellip's own R_D is off by up to 11 ulp for nearly equal arguments, hence the
/// combined tolerance of 16 ulp here (and 4 ulp against mpmath in the unit tests).
#[test]
fn fused_carlson_matches_ellip() {
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let tolerance = 16.0 * f64::EPSILON;
    let mut worst = 0.0_f64;
    for k in 0..30_000 {
        let [x, y, z] = if k % 2 == 0 {
            let base = 10f64.powf(40.0 * uniform() - 20.0);
            [0; 3].map(|_| base * 10f64.powf(16.0 * uniform() - 8.0))
        } else {
            let base = 10f64.powf(10.0 * uniform() - 5.0);
            [1e-1, 1e-4, 1e-8].map(|spread| base * (1.0 + spread * (uniform() - 0.5)))
        };
        let s = symmetric_integrals(x, y, z).unwrap();
        let reference = [
            ellip::elliprf(x, y, z).unwrap(),
            ellip::elliprd(y, z, x).unwrap(),
            ellip::elliprd(z, x, y).unwrap(),
            ellip::elliprd(x, y, z).unwrap(),
        ];
        for (value, reference) in [s.rf, s.rd[0], s.rd[1], s.rd[2]].iter().zip(reference) {
            let e = rel(*value, reference);
            worst = worst.max(e);
            assert!(
                e <= tolerance,
                "({x:e}, {y:e}, {z:e}): {value} vs ellip {reference}"
            );
        }
    }
    println!(
        "fused Carlson vs ellip: worst {:.2} ulp",
        worst / f64::EPSILON
    );
}

// ---------------------------------------------------------------------------------------------
// Construction

#[test]
fn constructors_validate_and_name_the_field() {
    let not_positive = |r: Result<(), BodyError>, name: &str| match r {
        Err(BodyError::NotPositive { field, .. }) => assert_eq!(field, name),
        other => panic!("expected NotPositive({name}), got {other:?}"),
    };
    let not_finite = |r: Result<(), BodyError>, name: &str| match r {
        Err(BodyError::NotFinite { field, .. }) => assert_eq!(field, name),
        other => panic!("expected NotFinite({name}), got {other:?}"),
    };
    let out_of_range = |r: Result<(), BodyError>, what: &str| match r {
        Err(BodyError::OutOfRange { what: w, .. }) => assert_eq!(w, what),
        other => panic!("expected OutOfRange({what}), got {other:?}"),
    };
    not_positive(PointMass::new(0.0).map(drop), "mass");
    not_finite(PointMass::new(f64::NAN).map(drop), "mass");
    not_positive(Sphere::new(-1.0, 1.0).map(drop), "radius");
    not_finite(Sphere::new(1.0, f64::INFINITY).map(drop), "mass");
    not_positive(Sphere::with_density(1.0, 0.0).map(drop), "density");
    not_positive(Spheroid::new(1.0, -2.0, 1.0).map(drop), "polar_radius");
    not_finite(
        Spheroid::new(f64::NAN, 1.0, 1.0).map(drop),
        "equatorial_radius",
    );
    not_positive(Spheroid::with_density(1.0, 1.0, -3.0).map(drop), "density");
    not_finite(Ellipsoid::new(1.0, 2.0, f64::INFINITY, 1.0).map(drop), "c");
    not_positive(Ellipsoid::new(1.0, 0.0, 1.0, 1.0).map(drop), "b");
    not_positive(Ellipsoid::new(-1.0, 1.0, 1.0, 1.0).map(drop), "a");
    not_finite(
        Ellipsoid::with_density(1.0, 1.0, 1.0, f64::NAN).map(drop),
        "density",
    );
    let g_zero = |r: Result<(), BodyError>| not_positive(r, "gravitational_constant");
    g_zero(
        PointMass::new(1.0)
            .unwrap()
            .with_gravitational_constant(0.0)
            .map(drop),
    );
    g_zero(
        Sphere::new(1.0, 1.0)
            .unwrap()
            .with_gravitational_constant(-1.0)
            .map(drop),
    );
    g_zero(
        Spheroid::new(1.0, 2.0, 1.0)
            .unwrap()
            .with_gravitational_constant(0.0)
            .map(drop),
    );
    g_zero(
        Ellipsoid::new(1.0, 2.0, 3.0, 1.0)
            .unwrap()
            .with_gravitational_constant(0.0)
            .map(drop),
    );
    not_finite(
        Sphere::new(1.0, 1.0)
            .unwrap()
            .with_gravitational_constant(f64::NAN)
            .map(drop),
        "gravitational_constant",
    );
    // Derived quantities beyond the range of f64.
    out_of_range(Sphere::new(1e200, 1.0).map(drop), "volume");
    out_of_range(Sphere::new(1e100, 1e-300).map(drop), "density");
    out_of_range(Spheroid::new(1e-200, 1e-200, 1.0).map(drop), "volume");
    out_of_range(
        Ellipsoid::with_density(1.0, 1.0, 1.0, 1e308).map(drop),
        "mass",
    );
    out_of_range(
        PointMass::new(1e300)
            .unwrap()
            .with_gravitational_constant(1e10)
            .map(drop),
        "gravitational parameter G·mass",
    );
}

#[test]
fn accessors_and_derived_quantities() {
    let s = Sphere::new(2.0, 3.0)
        .unwrap()
        .with_gravitational_constant(0.5)
        .unwrap();
    assert_eq!(
        (s.radius(), s.mass(), s.gravitational_constant()),
        (2.0, 3.0, 0.5)
    );
    assert!(rel(s.volume(), 32.0 * PI / 3.0) < 4.0 * f64::EPSILON);
    assert!(rel(s.density(), 3.0 / (32.0 * PI / 3.0)) < 4.0 * f64::EPSILON);
    assert_eq!(s.bounding_radius(), 2.0);
    assert!(rel(s.gravitational_parameter(), 1.5) < f64::EPSILON);

    let o = Spheroid::with_density(2.0, 0.5, 4.0).unwrap();
    assert_eq!(
        (o.equatorial_radius(), o.polar_radius(), o.density()),
        (2.0, 0.5, 4.0)
    );
    assert!(rel(o.volume(), 4.0 / 3.0 * PI * 2.0) < 4.0 * f64::EPSILON);
    assert!(rel(o.mass(), 4.0 * o.volume()) < 4.0 * f64::EPSILON);
    assert_eq!(o.bounding_radius(), 2.0);
    assert_eq!(Spheroid::new(0.5, 3.0, 1.0).unwrap().bounding_radius(), 3.0);

    let e = Ellipsoid::new(1.0, 3.0, 2.0, 5.0).unwrap();
    assert_eq!(e.semi_axes(), [1.0, 3.0, 2.0]);
    assert!(rel(e.volume(), 8.0 * PI) < 4.0 * f64::EPSILON);
    assert!(rel(e.density(), 5.0 / (8.0 * PI)) < 4.0 * f64::EPSILON);
    assert_eq!(e.bounding_radius(), 3.0);
    assert_eq!(e.gravitational_constant(), 1.0);

    let p = PointMass::new(7.0).unwrap();
    assert_eq!((p.mass(), p.volume(), p.bounding_radius()), (7.0, 0.0, 0.0));
}

// ---------------------------------------------------------------------------------------------
// Point mass and sphere

#[test]
fn point_mass_is_kepler_everywhere_but_the_origin() {
    let body = PointMass::new(3.0)
        .unwrap()
        .with_gravitational_constant(2.0)
        .unwrap();
    // |r|² underflows at 1e-160 and overflows at 1e160.
    // (Light and heavy masses keep GM/r² itself within range.)
    let light = PointMass::new(6e-20).unwrap();
    let heavy = PointMass::new(6e100).unwrap();
    for (body, gm, r) in [
        (&body, 6.0, Vec3::new(1.0, 2.0, -2.0)),
        (&light, 6e-20, Vec3::new(1e-160, 0.0, -2e-160)),
        (&heavy, 6e100, Vec3::new(0.0, -1e160, 1e160)),
    ] {
        let f = body.field(&r);
        // |r| without underflow or overflow of |r|².
        let d = r.amax() * (r / r.amax()).norm();
        assert!(rel(f.potential, -gm / d) < 4.0 * f64::EPSILON, "Φ at {r:?}");
        let expected = -r / d * (gm / d / d);
        assert!(
            rel_vec(&f.acceleration, &expected) < 8.0 * f64::EPSILON,
            "a at {r:?}"
        );
        assert_eq!(body.region(&r), Region::Outside);
    }
    let origin = body.field(&Vec3::zeros());
    assert_eq!(origin.potential, f64::NEG_INFINITY);
    assert_eq!(origin.acceleration, Vec3::zeros());
    assert_eq!(body.region(&Vec3::zeros()), Region::OnSurface);
}

#[test]
fn sphere_piecewise_formula() {
    let (radius, mass, g) = (1.5, 2.0, 0.7);
    let body = Sphere::new(radius, mass)
        .unwrap()
        .with_gravitational_constant(g)
        .unwrap();
    let gm = g * mass;
    for dir in directions(20) {
        for factor in [0.0, 0.3, 0.999_999, 1.000_001, 2.0, 1e8] {
            let r = dir * (radius * factor);
            let d = r.norm();
            let f = body.field(&r);
            let (phi, a) = if d > radius {
                (-gm / d, -r * (gm / d.powi(3)))
            } else {
                let k = gm / radius.powi(3);
                (-0.5 * k * (3.0 * radius * radius - d * d), -r * k)
            };
            assert!(rel(f.potential, phi) < 4.0 * f64::EPSILON, "Φ at {r:?}");
            if factor > 0.0 {
                assert!(
                    rel_vec(&f.acceleration, &a) < 8.0 * f64::EPSILON,
                    "a at {r:?}"
                );
            } else {
                assert_eq!(f.acceleration, Vec3::zeros());
            }
        }
    }
    // Both pieces meet on the surface.
    let inside = body.field(&Vec3::new(radius * (1.0 - 1e-15), 0.0, 0.0));
    let outside = body.field(&Vec3::new(radius * (1.0 + 1e-15), 0.0, 0.0));
    let (dphi, da) = field_difference(&inside, &outside);
    assert!(
        dphi < 1e-14 && da < 1e-14,
        "jump at the surface: {dphi:e}, {da:e}"
    );
}

#[test]
fn region_is_decided_to_a_few_ulp() {
    let sphere = Sphere::new(2.0, 1.0).unwrap();
    let spheroid = Spheroid::new(2.0, 0.5, 1.0).unwrap();
    let ellipsoid = Ellipsoid::new(2.0, 1.0, 0.5, 1.0).unwrap();
    let cases: [(&dyn Potential, [f64; 3]); 3] = [
        (&sphere, [2.0, 2.0, 2.0]),
        (&spheroid, [2.0, 2.0, 0.5]),
        (&ellipsoid, [2.0, 1.0, 0.5]),
    ];
    for (body, axes) in cases {
        for dir in probe_directions() {
            let s = surface_point(axes, &dir);
            assert_eq!(body.region(&(s * (1.0 + 1e-13))), Region::Outside, "{s:?}");
            assert_eq!(body.region(&(s * (1.0 - 1e-13))), Region::Inside, "{s:?}");
            assert_eq!(body.region(&(s * 0.5)), Region::Inside);
            assert_eq!(body.region(&(s * 1e30)), Region::Outside);
        }
        // Exactly representable surface points.
        for (i, axis) in axes.iter().enumerate() {
            assert_eq!(body.region(&Vec3::ith(i, *axis)), Region::OnSurface);
            assert_eq!(body.region(&Vec3::ith(i, -axis)), Region::OnSurface);
        }
        assert_eq!(body.region(&Vec3::zeros()), Region::Inside);
    }
}

// ---------------------------------------------------------------------------------------------
// Spheroid: the elementary forms against the ellipsoid's Carlson forms

/// Probe points for a body with semi-axes `axes`: near the surface (relative gaps 1e-12 … 1),
/// far (10 … 1e8 body sizes) and inside.
fn probes(axes: [f64; 3]) -> Vec<Vec3> {
    let size = axes.iter().cloned().fold(0.0, f64::max);
    let mut points = Vec::new();
    for dir in probe_directions() {
        let s = surface_point(axes, &dir);
        for gap in [1e-12, 1e-9, 1e-6, 1e-3, 0.1, 1.0] {
            points.push(s * (1.0 + gap));
        }
        for factor in [10.0, 1e3, 1e5, 1e8] {
            points.push(dir * (factor * size));
        }
        for factor in [0.0, 0.5, 0.999] {
            points.push(s * factor);
        }
    }
    points
}

/// Two independent evaluations: elementary functions of q (spheroid) and Newton plus the fused
/// duplication (ellipsoid with a = b). Agreement to the issue-2 tolerances everywhere, inside
/// included, for c/a from 1e-4 to 1e4 through the sphere.
#[test]
fn spheroid_matches_ellipsoid_with_equal_axes() {
    let mut worst = (0.0_f64, 0.0_f64);
    for ratio in SPHEROID_RATIOS {
        let (a, c, m) = (1.3, 1.3 * ratio, 0.7);
        let spheroid = Spheroid::new(a, c, m).unwrap();
        let ellipsoid = Ellipsoid::new(a, a, c, m).unwrap();
        for r in probes([a, a, c]) {
            let (dphi, da) = field_difference(&spheroid.field(&r), &ellipsoid.field(&r));
            worst = (worst.0.max(dphi), worst.1.max(da));
            assert!(
                dphi <= POTENTIAL_REL && (da <= ACCELERATION_REL || r == Vec3::zeros()),
                "c/a = {ratio}, r = {r:?}: ΔΦ/Φ = {dphi:e}, Δa/a = {da:e}"
            );
        }
    }
    println!(
        "spheroid vs ellipsoid: worst ΔΦ/Φ {:.1e}, Δa/a {:.1e}",
        worst.0, worst.1
    );
}

/// The same formula serves oblate, prolate and the sphere: at c = a(1 ± 1e-9) the field
/// differs from the sphere's by O(1e-9) (the J2 term), and at c = a it is the sphere's.
#[test]
fn spheroid_is_continuous_through_the_sphere() {
    let sphere = Sphere::new(1.0, 1.0).unwrap();
    let exact = Spheroid::new(1.0, 1.0, 1.0).unwrap();
    let ellipsoid = Ellipsoid::new(1.0, 1.0, 1.0, 1.0).unwrap();
    for r in probes([1.0; 3]) {
        if r == Vec3::zeros() {
            continue;
        }
        let reference = sphere.field(&r);
        for body in [&exact as &dyn Potential, &ellipsoid] {
            let (dphi, da) = field_difference(&body.field(&r), &reference);
            assert!(
                dphi <= 8.0 * f64::EPSILON && da <= 16.0 * f64::EPSILON,
                "{r:?}"
            );
        }
        for c in [1.0 - 1e-9, 1.0 + 1e-9] {
            let near = Spheroid::new(1.0, c, 1.0).unwrap().field(&r);
            let (dphi, da) = field_difference(&near, &reference);
            assert!(dphi < 1e-9 && da < 2e-9, "c = {c}, {r:?}: {dphi:e}, {da:e}");
        }
    }
}

/// Far away Φ → −GM/r [1 − J2 (a/r)² P2(cos θ)] with J2 = (a² − c²)/(5a²).
#[test]
fn spheroid_far_field_has_the_right_j2() {
    for ratio in [1e-4, 0.5, 0.99, 1.01, 2.0, 1e4] {
        let (a, c, gm) = (1.0, ratio, 1.0);
        let body = Spheroid::new(a, c, gm).unwrap();
        let size = a.max(c);
        let j2 = (a * a - c * c) / (5.0 * a * a);
        for dir in directions(16) {
            let r = dir * (100.0 * size);
            let d = r.norm();
            let p2 = 0.5 * (3.0 * dir.z * dir.z - 1.0);
            let quadrupole = gm / d * j2 * (a / d).powi(2) * p2;
            let excess = body.potential(&r) + gm / d;
            // Next multipole: (size/r)² = 1e-4 of the quadrupole; rounding: ε GM/r.
            let tol = 1e-3 * quadrupole.abs() + 1e-14 * gm / d;
            assert!(
                (excess - quadrupole).abs() <= tol,
                "c/a = {ratio} at {r:?}: Φ + GM/r = {excess:e}, J2 term {quadrupole:e}"
            );
            // At 1e8 sizes the field is Kepler's to round-off.
            let r_far = dir * (1e8 * size);
            let f = body.field(&r_far);
            let kepler = -gm / r_far.norm();
            assert!(rel(f.potential, kepler) <= POTENTIAL_REL);
            let a_kepler = -r_far * (gm / r_far.norm().powi(3));
            assert!(rel_vec(&f.acceleration, &a_kepler) <= ACCELERATION_REL);
        }
    }
}

/// Rotating the point about z changes nothing but the rounding of the rotated coordinates
/// (≈ 2ε|r|), which moves a by at most 8πGρ · 2ε|r| (see the continuity test): near the rim
/// of a disk that conditioning term dominates.
#[test]
fn spheroid_is_axisymmetric() {
    for ratio in [1e-4, 0.5, 1.0, 3.0, 1e4] {
        let body = Spheroid::new(1.0, ratio, 1.0).unwrap();
        let four_pi_g_rho = 4.0 * PI / body.volume();
        for r in probes([1.0, 1.0, ratio]) {
            if r == Vec3::zeros() {
                continue;
            }
            let f = body.field(&r);
            let shift = 2.0 * f64::EPSILON * r.norm();
            let a_bound = ACCELERATION_REL + 2.0 * four_pi_g_rho * shift / f.acceleration.norm();
            for angle in [0.3, 2.0, -1.1] {
                let rot = nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), angle);
                let g = body.field(&(rot * r));
                let back = Field {
                    potential: g.potential,
                    acceleration: rot.inverse() * g.acceleration,
                };
                let (dphi, da) = field_difference(&back, &f);
                assert!(
                    dphi <= POTENTIAL_REL && da <= a_bound,
                    "c/a = {ratio} at {r:?}: {dphi:e}, {da:e} (bound {a_bound:e})"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Laws of the potential for extreme shapes (the conformance suite covers moderate ones)

/// Gradient, Laplace outside and Poisson inside by Richardson-extrapolated differences, for
/// disks, needles and flat triaxial bodies, at SI magnitudes too.
#[test]
fn extreme_shapes_obey_gradient_laplace_and_poisson() {
    let bodies: Vec<(Box<dyn Potential>, [f64; 3])> = vec![
        (
            Box::new(Spheroid::new(1.0, 1e-4, 1.0).unwrap()),
            [1.0, 1.0, 1e-4],
        ),
        (
            Box::new(Spheroid::new(1.0, 1e4, 1.0).unwrap()),
            [1.0, 1.0, 1e4],
        ),
        (
            Box::new(Spheroid::new(1.0, 1.0 + 1e-9, 1.0).unwrap()),
            [1.0, 1.0, 1.0 + 1e-9],
        ),
        (
            Box::new(Ellipsoid::new(1.0, 0.5, 1e-4, 1.0).unwrap()),
            [1.0, 0.5, 1e-4],
        ),
        (
            Box::new(Ellipsoid::new(1e-4, 2e-4, 1.0, 1.0).unwrap()),
            [1e-4, 2e-4, 1.0],
        ),
        (
            Box::new(
                Spheroid::new(6.378e6, 6.357e6, 5.97e24)
                    .unwrap()
                    .with_gravitational_constant(6.674e-11)
                    .unwrap(),
            ),
            [6.378e6, 6.378e6, 6.357e6],
        ),
    ];
    for (body, axes) in &bodies {
        let body = body.as_ref();
        let four_pi_g_rho = 4.0 * PI * body.gravitational_constant() * body.mass() / body.volume();
        for dir in directions(24) {
            let s = surface_point(*axes, &dir);
            // Along the outward normal the distance to the (convex) body is exactly the offset,
            // and the field varies on that scale: steps of 2e-3 of it (truncation ≈ 1e-11,
            // cancellation ≈ 500 ε).
            let normal = Vec3::new(
                s.x / axes[0].powi(2),
                s.y / axes[1].powi(2),
                s.z / axes[2].powi(2),
            )
            .normalize();
            let local = axes.iter().cloned().fold(f64::INFINITY, f64::min);
            for gap in [0.5, 3.0] {
                let r = s + normal * (gap * local);
                let h = 2e-3 * gap * local;
                let e = gradient_error(body, &r, h);
                assert!(
                    e <= FINITE_DIFFERENCE_REL,
                    "{axes:?} at {r:?}: gradient {e:e}"
                );
                let div = divergence(body, &r, h);
                let scale = body.acceleration(&r).norm() / (gap * local);
                assert!(
                    div.abs() <= FINITE_DIFFERENCE_REL * scale,
                    "{axes:?} at {r:?}: Laplace {div:e} (scale {scale:e})"
                );
            }
            let r = s * 0.5;
            let h = 1e-2 * local;
            let div = divergence(body, &r, h);
            assert!(
                rel(div, -four_pi_g_rho) <= FINITE_DIFFERENCE_REL,
                "{axes:?} at {r:?}: Poisson ∇·a = {div:e}, −4πGρ = {:e}",
                -four_pi_g_rho
            );
        }
    }
}

/// Φ and a are continuous across the surface: points 1e-12 (relative) inside and outside
/// agree to what the field's derivatives allow. Inside, the Hessian's eigenvalues lie in
/// [0, 4πGρ]; across the surface it jumps by 4πGρ n nᵀ; so |Δa| ≤ 8πGρ |Δr| and
/// |ΔΦ| ≤ |a| |Δr| (to first order). Near the rim of a disk 4πGρ|Δr|/|a| is ≈ 1e-8.
#[test]
fn field_is_continuous_across_the_surface() {
    let mut bodies: Vec<(Box<dyn Potential>, [f64; 3])> = Vec::new();
    for ratio in SPHEROID_RATIOS {
        bodies.push((
            Box::new(Spheroid::new(1.0, ratio, 1.0).unwrap()),
            [1.0, 1.0, ratio],
        ));
    }
    for axes in [
        [3.0, 2.0, 1.0],
        [1.0, 0.5, 1e-4],
        [1e-4, 2e-4, 1.0],
        [1.0, 1.0 + 1e-9, 1.0],
    ] {
        bodies.push((
            Box::new(Ellipsoid::new(axes[0], axes[1], axes[2], 1.0).unwrap()),
            axes,
        ));
    }
    for (body, axes) in &bodies {
        let four_pi_g_rho = 4.0 * PI * body.gravitational_constant() * body.mass() / body.volume();
        for dir in probe_directions() {
            let s = surface_point(*axes, &dir);
            let (r_in, r_out) = (s * (1.0 - 1e-12), s * (1.0 + 1e-12));
            let step = (r_out - r_in).norm();
            let (inside, outside) = (body.field(&r_in), body.field(&r_out));
            let a = outside.acceleration.norm();
            let phi_bound = 1.1 * a * step / outside.potential.abs() + POTENTIAL_REL;
            let a_bound = 2.0 * four_pi_g_rho * step / a + ACCELERATION_REL;
            let (dphi, da) = field_difference(&inside, &outside);
            assert!(
                dphi <= phi_bound && da <= a_bound,
                "{axes:?} at {s:?}: ΔΦ/Φ {dphi:e} (bound {phi_bound:e}), Δa/a {da:e} (bound {a_bound:e})"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Ellipsoid

/// Relabelling the axes together with the coordinates changes nothing.
#[test]
fn ellipsoid_is_invariant_under_axis_permutations() {
    for axes in [
        [3.0, 2.0, 1.0],
        [1.0, 0.5, 1e-4],
        [1.0, 1.0 + 1e-9, 1.0 - 1e-9],
    ] {
        let body = Ellipsoid::new(axes[0], axes[1], axes[2], 1.0).unwrap();
        let perm = [2, 0, 1];
        let rotated = Ellipsoid::new(axes[perm[0]], axes[perm[1]], axes[perm[2]], 1.0).unwrap();
        for r in probes(axes) {
            let f = body.field(&r);
            let g = rotated.field(&Vec3::new(r[perm[0]], r[perm[1]], r[perm[2]]));
            assert!(
                rel(g.potential, f.potential) <= POTENTIAL_REL,
                "{axes:?} at {r:?}"
            );
            if r != Vec3::zeros() {
                let a = Vec3::new(
                    f.acceleration[perm[0]],
                    f.acceleration[perm[1]],
                    f.acceleration[perm[2]],
                );
                assert!(
                    rel_vec(&g.acceleration, &a) <= ACCELERATION_REL,
                    "{axes:?} at {r:?}"
                );
            }
        }
    }
}

/// Nearly equal axes are no special case: within 1e-9 of the sphere.
#[test]
fn ellipsoid_with_nearly_equal_axes_is_nearly_the_sphere() {
    let sphere = Sphere::new(1.0, 1.0).unwrap();
    let body = Ellipsoid::new(1.0, 1.0 + 1e-9, 1.0 - 1e-9, 1.0).unwrap();
    for r in probes([1.0; 3]) {
        if r == Vec3::zeros() {
            continue;
        }
        let (dphi, da) = field_difference(&body.field(&r), &sphere.field(&r));
        assert!(dphi < 1e-9 && da < 3e-9, "{r:?}: {dphi:e}, {da:e}");
    }
}

/// The confocal parameter solves the secular equation and is zero inside.
#[test]
fn confocal_parameter_solves_the_secular_equation() {
    let ellipsoid = Ellipsoid::new(3.0, 1e-3, 1.0, 1.0).unwrap();
    let spheroid = Spheroid::new(1.0, 1e-3, 1.0).unwrap();
    let prolate = Spheroid::new(1.0, 1e3, 1.0).unwrap();
    let check = |axes: [f64; 3], lambda_of: &dyn Fn(&Vec3) -> f64| {
        for r in probes(axes) {
            let lambda = lambda_of(&r);
            let f0: f64 = (0..3).map(|i| (r[i] / axes[i]).powi(2)).sum::<f64>() - 1.0;
            if f0 < -1e-10 {
                assert_eq!(lambda, 0.0, "inside at {r:?}");
            } else if f0 > 1e-10 {
                let s: f64 = (0..3)
                    .map(|i| r[i] * r[i] / (axes[i] * axes[i] + lambda))
                    .sum();
                assert!((s - 1.0).abs() < 1e-14, "S(λ) − 1 = {:e} at {r:?}", s - 1.0);
            }
        }
    };
    check([3.0, 1e-3, 1.0], &|r| ellipsoid.confocal_parameter(r));
    check([1.0, 1.0, 1e-3], &|r| spheroid.confocal_parameter(r));
    check([1.0, 1.0, 1e3], &|r| prolate.confocal_parameter(r));
}

// ---------------------------------------------------------------------------------------------
// Reference values: the Dirichlet integral at 36 digits

#[derive(Clone, Copy)]
enum Shape {
    Spheroid,
    Ellipsoid,
}

/// One body, one point, and the field there from
/// $\Phi = -\tfrac34 GM \int\_\lambda^\infty (1 - \sum x_i^2/(a_i^2 + u))\\, \mathrm du /
/// \sqrt{\prod (a_i^2 + u)}$ and $a_i = -\tfrac32 GM x_i \int\_\lambda^\infty \mathrm du /
/// ((a_i^2 + u)\sqrt{\prod(a_j^2 + u)})$, evaluated with mpmath 1.3 (`quad`, tanh-sinh, 36
/// digits, λ by bisection and Newton at 36 digits, quadrature error estimates below 1e-37)
/// at the exact binary values of the inputs, then rounded to the nearest f64. The points are
/// the hardest of a sweep of 6,348: 1e-12 off the rim of a c/a = 1e-4 disk and beyond the tip
/// of a c/a = 1e4 needle, c = a(1 ± 1e-9), SI magnitudes, 1e8 body sizes.
struct Reference {
    body: Shape,
    semi_axes: [f64; 3],
    g: f64,
    mass: f64,
    point: [f64; 3],
    potential: f64,
    acceleration: [f64; 3],
}

const REFERENCES: [Reference; 24] = [
    // disk c/a = 1e-4, 1e-12 outside the rim
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 0.0001],
        g: 1.0,
        mass: 1.0,
        point: [0.7648421872852534, 0.6442176872383353, 6.12323399574289e-17],
        potential: -1.1780972392043298,
        acceleration: [
            -1.8018874989734632,
            -1.5177089032870268,
            -1.8364979905409645e-12,
        ],
    },
    // disk, 1e-12 above the pole
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 0.0001],
        g: 1.0,
        mass: 1.0,
        point: [0.0, 0.0, 0.00010000000000010001],
        potential: -2.355894525531262,
        acceleration: [0.0, 0.0, -2.999528821094893],
    },
    // disk, 1e-6 off the edge at 1.2 rad
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 0.0001],
        g: 1.0,
        mass: 1.0,
        point: [0.764804712846993, 0.6441861229544241, 9.999510036789932e-07],
        potential: -1.1782126514998665,
        acceleration: [
            -1.8017969066909383,
            -1.5176325984600962,
            -0.0296923192081134,
        ],
    },
    // disk, 1e8 sizes
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 0.0001],
        g: 1.0,
        mass: 1.0,
        point: [0.7648421872844885, 0.644217687237691, 100000000.0],
        potential: -9.999999999999999e-09,
        acceleration: [
            -7.648421872844883e-25,
            -6.442176872376908e-25,
            -9.999999999999997e-17,
        ],
    },
    // needle c/a = 1e4, 1e-12 beyond the tip
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 10000.0],
        g: 1.0,
        mass: 1.0,
        point: [0.0, 0.0, 10000.00000001],
        potential: -0.00014999998664209723,
        acceleration: [0.0, 0.0, -2.6710163071680644e-07],
    },
    // needle, 1e-12 off the side
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 10000.0],
        g: 1.0,
        mass: 1.0,
        point: [1.000000000001, 0.0, 6.12323399574289e-17],
        potential: -0.0014105231466105008,
        acceleration: [-0.00014999998664461846, 0.0, -1.6355441548631072e-27],
    },
    // needle, 1e-3 off the side
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 10000.0],
        g: 1.0,
        mass: 1.0,
        point: [0.7656069894667751, 0.6448618712291837, 3.2359607028220547],
        potential: -0.0014103730895791184,
        acceleration: [
            -0.00011461170013870635,
            -9.653610329195104e-05,
            -8.642430580258068e-11,
        ],
    },
    // oblate c = a(1 − 1e-9)
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 0.999999999],
        g: 1.0,
        mass: 1.0,
        point: [0.5408250974368258, 0.4555306954338511, 0.7071067815401011],
        potential: -0.9999999993999998,
        acceleration: [
            -0.5408250961388452,
            -0.45553069434057714,
            -0.7071067806915725,
        ],
    },
    // prolate c = a(1 + 1e-9)
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 1.000000001],
        g: 1.0,
        mass: 1.0,
        point: [7.6560703023738e-09, 6.448619055697907e-09, 1.001000001001],
        potential: -0.9990009984008004,
        acceleration: [
            -7.633147946825997e-09,
            -6.429311821967149e-09,
            -0.9980029952041998,
        ],
    },
    // sphere c = a
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 1.0],
        g: 1.0,
        mass: 1.0,
        point: [8.413264060129374e-09, 7.086394559614602e-09, 1.1],
        potential: -0.909090909090909,
        acceleration: [
            -6.321009812268498e-09,
            -5.324113117666866e-09,
            -0.8264462809917352,
        ],
    },
    // oblate c/a = 0.5
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 0.5],
        g: 1.0,
        mass: 1.0,
        point: [3.8242147606333785e-09, 3.2210916572768913e-09, 0.5000005],
        potential: -1.4183983615122213,
        acceleration: [
            -5.42425723842326e-09,
            -4.568788844566663e-09,
            -1.5815994292893072,
        ],
    },
    // prolate c/a = 2
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 2.0],
        g: 1.0,
        mass: 1.0,
        point: [
            1.529685904253351e-08,
            1.2884366629107562e-08,
            2.0000019999999994,
        ],
        potential: -0.6198259604680211,
        acceleration: [
            -9.481314497628367e-09,
            -7.986001032868513e-09,
            -0.5206895133058854,
        ],
    },
    // prolate c/a = 1.1, 1e-12 beyond the pole
    Reference {
        body: Shape::Spheroid,
        semi_axes: [1.0, 1.0, 1.1],
        g: 1.0,
        mass: 1.0,
        point: [0.0, 0.0, 1.1000000000011],
        potential: -0.9432479537431389,
        acceleration: [0.0, 0.0, -0.924854501760781],
    },
    // Earth-like, SI, 6 km up
    Reference {
        body: Shape::Spheroid,
        semi_axes: [6400000.0, 6400000.0, 6378240.0],
        g: 6.674e-11,
        mass: 6e+24,
        point: [0.048832253796580405, 0.04113083996468377, 6384618.239999999],
        potential: -62634174.91913826,
        acceleration: [
            -7.452395837366973e-08,
            -6.277066420425622e-08,
            -9.783520152538197,
        ],
    },
    // Earth-like, SI, 10 radii
    Reference {
        body: Shape::Spheroid,
        semi_axes: [6400000.0, 6400000.0, 6378240.0],
        g: 6.674e-11,
        mass: 6e+24,
        point: [0.4894989998620726, 0.4122993198321223, 64000000.0],
        potential: -6256790.053630299,
        acceleration: [
            -7.47676899089566e-10,
            -6.297595644438079e-10,
            -0.09775969009114707,
        ],
    },
    // SI disk, 1e-12 outside the rim
    Reference {
        body: Shape::Spheroid,
        semi_axes: [6400000.0, 6400000.0, 640.0],
        g: 6.674e-11,
        mass: 6e+24,
        point: [4894989.99862562, 4122993.1983253453, 3.918869757275449e-10],
        potential: -73712071.63546595,
        acceleration: [
            -17.615913820588382,
            -14.837679522320567,
            -1.7954279157158596e-11,
        ],
    },
    // SI needle, 1e8 sizes
    Reference {
        body: Shape::Spheroid,
        semi_axes: [6400000.0, 6400000.0, 64000000000.0],
        g: 6.674e-11,
        mass: 6e+24,
        point: [48949899986.20726, 41229931983.21223, 6.4e+18],
        potential: -6.256874999999999e-05,
        acceleration: [
            -7.477378063383801e-32,
            -6.298108659117699e-32,
            -9.776367187499998e-24,
        ],
    },
    // triaxial 3:2:1
    Reference {
        body: Shape::Ellipsoid,
        semi_axes: [3.0, 2.0, 1.0],
        g: 1.0,
        mass: 1.0,
        point: [1.5245018667941779, 1.7153459788021197, 0.07850509355429203],
        potential: -0.474744460938314,
        acceleration: [
            -0.1191403535728419,
            -0.22913080434110428,
            -0.022630869822782115,
        ],
    },
    // flat triaxial, 1e-9 off the rim
    Reference {
        body: Shape::Ellipsoid,
        semi_axes: [1.0, 0.5, 0.01],
        g: 1.0,
        mass: 1.0,
        point: [1.000000001, 0.0, 0.0],
        potential: -1.34376164791372,
        acceleration: [-3.722739823557134, 0.0, 0.0],
    },
    // needle-like triaxial, 1e-12 beyond the tip
    Reference {
        body: Shape::Ellipsoid,
        semi_axes: [0.0001, 0.0002, 1.0],
        g: 1.0,
        mass: 1.0,
        point: [0.0, 0.0, 1.000000000001],
        potential: -1.499999685048648,
        acceleration: [0.0, 0.0, -25.493918292877606],
    },
    // flat triaxial c/a = 1e-4
    Reference {
        body: Shape::Ellipsoid,
        semi_axes: [1.0, 0.3, 0.0001],
        g: 1.0,
        mass: 1.0,
        point: [
            0.0019418594254327847,
            0.002184950264324493,
            9.999715919237122e-05,
        ],
        potential: -3.9405756179246287,
        acceleration: [
            -0.009801007591241334,
            -0.06880389873077337,
            -9.996062308676532,
        ],
    },
    // nearly equal axes
    Reference {
        body: Shape::Ellipsoid,
        semi_axes: [1.0, 1.0000001, 0.9999999],
        g: 1.0,
        mass: 1.0,
        point: [0.6639153012124931, 0.7470272532987345, 0.03418869728471742],
        potential: -0.9999989777257711,
        acceleration: [
            -0.6639133094703529,
            -0.7470249225783954,
            -0.03418859882144291,
        ],
    },
    // SI triaxial, 6 km up
    Reference {
        body: Shape::Ellipsoid,
        semi_axes: [6400000.0, 6300000.0, 6350000.0],
        g: 6.674e-11,
        mass: 6e+24,
        point: [4215790.943855431, 4743542.924102651, 217094.56030294945],
        potential: -63025284.51136168,
        acceleration: [-6.512054153870476, -7.466768889561232, -0.33851101466431505],
    },
    // SI triaxial, 1e8 sizes
    Reference {
        body: Shape::Ellipsoid,
        semi_axes: [6400000.0, 6300000.0, 6350000.0],
        g: 6.674e-11,
        mass: 6e+24,
        point: [424905344208514.3, 478096937389981.2, 21880743162980.73],
        potential: -0.6256875,
        acceleration: [
            -6.490672913927364e-16,
            -7.30320501741196e-16,
            -3.342409054635622e-17,
        ],
    },
];

#[test]
fn matches_the_dirichlet_integral_at_hard_points() {
    let mut worst = (0.0_f64, 0.0_f64);
    for (k, reference) in REFERENCES.iter().enumerate() {
        let [a, b, c] = reference.semi_axes;
        let (m, g) = (reference.mass, reference.g);
        let body: Box<dyn Potential> = match reference.body {
            Shape::Spheroid => Box::new(
                Spheroid::new(a, c, m)
                    .unwrap()
                    .with_gravitational_constant(g)
                    .unwrap(),
            ),
            Shape::Ellipsoid => Box::new(
                Ellipsoid::new(a, b, c, m)
                    .unwrap()
                    .with_gravitational_constant(g)
                    .unwrap(),
            ),
        };
        let r = Vec3::from(reference.point);
        let f = body.field(&r);
        let dphi = rel(f.potential, reference.potential);
        let da = rel_vec(&f.acceleration, &Vec3::from(reference.acceleration));
        worst = (worst.0.max(dphi), worst.1.max(da));
        assert!(
            dphi <= POTENTIAL_REL && da <= ACCELERATION_REL,
            "reference {k} ({:?} at {r:?}): ΔΦ/Φ {dphi:e}, Δa/a {da:e}",
            reference.semi_axes
        );
    }
    println!(
        "against the Dirichlet integral: worst ΔΦ/Φ {:.1e}, Δa/a {:.1e}",
        worst.0, worst.1
    );
}

// ---------------------------------------------------------------------------------------------
// Robustness

/// Every finite point gets a finite field, for extreme shapes and magnitudes.
#[test]
fn field_is_total_on_finite_points() {
    let bodies: Vec<Box<dyn Potential>> = vec![
        Box::new(Sphere::new(1.0, 1.0).unwrap()),
        Box::new(Spheroid::new(1.0, 1e-100, 1.0).unwrap()),
        Box::new(Spheroid::new(1e-50, 1e50, 1.0).unwrap()),
        Box::new(Spheroid::new(1e100, 1e100, 1.0).unwrap()),
        Box::new(Ellipsoid::new(1.0, 1e-60, 1e-60, 1.0).unwrap()),
        Box::new(Ellipsoid::new(1e-100, 1e-90, 1e-95, 1.0).unwrap()),
        Box::new(Ellipsoid::new(1.0, 1e-150, 1e-140, 1.0).unwrap()),
    ];
    let mut points = vec![Vec3::zeros()];
    for dir in probe_directions() {
        for d in [1e-300, 1e-120, 1e-60, 1e-9, 1.0, 1e9, 1e60, 1e120, 1e300] {
            points.push(dir * d);
        }
    }
    for body in &bodies {
        for r in &points {
            let f = body.field(r);
            assert!(
                f.potential.is_finite() && f.potential < 0.0,
                "{body:?} at {r:?}: Φ = {}",
                f.potential
            );
            assert!(
                f.acceleration.iter().all(|v| v.is_finite()),
                "{body:?} at {r:?}: {f:?}"
            );
            if r.norm() > 1e8 * body.bounding_radius() {
                assert_eq!(body.region(r), Region::Outside, "{body:?} at {r:?}");
            }
        }
    }
}
