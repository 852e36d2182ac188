//! The uniform disk's field against the laws it must obey and the closed forms that are known
//! exactly: the gradient, Laplace's equation, the jump across the lamina, continuity through the
//! lamina and across the rim, the axis, the far field and the symmetries. (Accuracy against
//! high-precision reference values at arbitrary points is `reference_values.rs`.)

use std::f64::consts::{FRAC_PI_2, PI};

use surfgrav_potentials::tolerance::{ACCELERATION_REL, FINITE_DIFFERENCE_REL, POTENTIAL_REL};
use surfgrav_potentials::{BodyError, Potential, Region, UniformDisk, Vec3};

const RADIUS: f64 = 1.3;
const MASS: f64 = 0.8;

fn disk() -> UniformDisk {
    UniformDisk::new(RADIUS, MASS).unwrap()
}

fn sigma() -> f64 {
    MASS / (PI * RADIUS * RADIUS)
}

/// Points off the lamina in the body frame, at least `0.05 R` from the lamina and the rim
/// (for difference quotients), on both sides of the switch to the far-field series (2R).
fn probes() -> Vec<Vec3> {
    let mut points = Vec::new();
    for &(rho, z) in &[
        (0.0, 0.3),
        (0.2, -0.1),
        (0.5, 0.05),
        (0.9, -0.4),
        (1.05, 0.0),
        (1.2, 0.07),
        (1.5, -0.9),
        (1.9, 0.5),
        (1.95, 0.0),
        (2.05, 0.1),
        (0.3, 2.2),
        (3.0, -1.0),
        (0.0, -7.0),
        (20.0, 15.0),
    ] {
        for &phi in &[0.0, 0.7, 2.9] {
            let (s, c) = f64::sin_cos(phi);
            points.push(Vec3::new(rho * c, rho * s, z) * RADIUS);
        }
    }
    points
}

fn richardson<F: Fn(f64) -> f64>(f: F, h: f64) -> f64 {
    let d = |h: f64| (f(h) - f(-h)) / (2.0 * h);
    (4.0 * d(h / 2.0) - d(h)) / 3.0
}

/// Difference step: error (h/d)⁴ from the nearest singular set at d ≥ 0.05 R, round-off
/// ε|Φ|/h ≈ 1e-12.
const STEP: f64 = 1e-4 * RADIUS;

#[test]
fn acceleration_is_minus_the_gradient() {
    let body = disk();
    let h = STEP;
    for p in probes() {
        let a = body.acceleration(&p);
        let mut fd = Vec3::zeros();
        for i in 0..3 {
            let e = Vec3::ith(i, 1.0);
            fd[i] = -richardson(|t| body.potential(&(p + e * t)), h);
        }
        let scale = a.norm().max(body.potential(&p).abs() / p.norm());
        let err = (a - fd).norm() / scale;
        assert!(
            err < FINITE_DIFFERENCE_REL,
            "at {p:?}: a = {a:?}, −∇Φ ≈ {fd:?}, rel {err:.2e}"
        );
    }
}

#[test]
fn laplace_holds_off_the_lamina() {
    let body = disk();
    let h = STEP;
    for p in probes() {
        let mut divergence = 0.0;
        for i in 0..3 {
            let e = Vec3::ith(i, 1.0);
            divergence += richardson(|t| body.acceleration(&(p + e * t))[i], h);
        }
        // Scale: |a| / distance to the nearest singular set (≥ 0.05 R).
        let scale = body.acceleration(&p).norm() / (0.05 * RADIUS);
        assert!(
            (divergence / scale).abs() < FINITE_DIFFERENCE_REL,
            "∇·a = {divergence:e} at {p:?} (scale {scale:e})"
        );
    }
}

/// a_z jumps by −4πGσ from below to above the lamina; on it we return the average of the two
/// sides (a_z = 0) with the continuous in-plane components and potential.
#[test]
fn normal_acceleration_jumps_by_four_pi_g_sigma() {
    let body = disk();
    let expected = -4.0 * PI * sigma();
    for rho in [0.0, 0.1, 0.5, 0.9, 0.999] {
        for phi in [0.0, 1.0] {
            let (s, c) = f64::sin_cos(phi);
            let (x, y) = (rho * RADIUS * c, rho * RADIUS * s);
            // The smooth part of a_z changes by O(|z|/(R − ρ)) ≲ 1e-15 between the sides.
            let z = 1e-18 * RADIUS;
            let above = body.field(&Vec3::new(x, y, z));
            let below = body.field(&Vec3::new(x, y, -z));
            let on = body.field(&Vec3::new(x, y, 0.0));
            let jump = above.acceleration.z - below.acceleration.z;
            assert!(
                ((jump - expected) / expected).abs() < ACCELERATION_REL,
                "ρ = {rho}: jump {jump:e}, expected {expected:e}"
            );
            assert_eq!(on.acceleration.z, 0.0);
            let mean = (above.acceleration + below.acceleration) / 2.0;
            let scale = above.acceleration.norm();
            assert!((on.acceleration - mean).norm() / scale < ACCELERATION_REL);
            for side in [above, below] {
                assert!(
                    ((side.potential - on.potential) / on.potential).abs() < POTENTIAL_REL,
                    "Φ not continuous through the lamina at ρ = {rho}"
                );
            }
            assert_eq!(body.region(&Vec3::new(x, y, 0.0)), Region::OnSurface);
            assert_eq!(body.region(&Vec3::new(x, y, z)), Region::Outside);
        }
    }
    // Outside the disk in its plane there is no jump: a_z is continuous and zero.
    for rho in [1.001, 1.5, 3.0] {
        let (above, on) = (
            body.field(&Vec3::new(rho * RADIUS, 0.0, 1e-15 * RADIUS)),
            body.field(&Vec3::new(rho * RADIUS, 0.0, 0.0)),
        );
        assert_eq!(on.acceleration.z, 0.0);
        assert!(above.acceleration.z.abs() < 1e-12 * above.acceleration.norm());
        assert_eq!(
            body.region(&Vec3::new(rho * RADIUS, 0.0, 0.0)),
            Region::Outside
        );
    }
}

/// Φ is continuous across the rim: the inner and outer closed forms meet (a wrong sign of the
/// Π term or of the |z| step would leave a jump of order 2πGσ|z|), and the symmetric mean
/// across the rim equals the value on it (the rim's leading singular term d·ln d is odd in d).
#[test]
fn potential_is_continuous_across_the_rim() {
    let body = disk();
    for z in [0.0, 1e-9, 1e-3, 0.2, -0.6] {
        let on = body.potential(&Vec3::new(RADIUS, 0.0, z * RADIUS));
        for d in [1e-13, 1e-10, 1e-7] {
            let inner = body.field(&Vec3::new(RADIUS * (1.0 - d), 0.0, z * RADIUS));
            let outer = body.field(&Vec3::new(RADIUS * (1.0 + d), 0.0, z * RADIUS));
            // Lipschitz bound with the in-plane acceleration at the ends; its mean over the
            // segment exceeds the end values by at most a factor 1 + 1/ln(1/d) (logarithmic
            // peak at the rim). A jump of 2πGσR|z| would exceed this by orders of magnitude.
            let slope = inner.acceleration.x.abs().max(outer.acceleration.x.abs());
            let step = (outer.potential - inner.potential).abs();
            assert!(
                step <= 1.5 * 2.0 * d * RADIUS * slope + POTENTIAL_REL * on.abs(),
                "z = {z}, d = {d}: Φ jumps by {step:e}"
            );
            if d == 1e-13 {
                // The rest of the symmetric mean is O(d² Φ'') ≤ d²/|z| ≈ 1e-17.
                let mean = 0.5 * (inner.potential + outer.potential);
                assert!(
                    (mean - on).abs() <= POTENTIAL_REL * on.abs(),
                    "z = {z}: mean {mean:e} vs rim {on:e}"
                );
            }
        }
    }
}

/// The rim itself: the in-plane attraction is infinite there (it diverges logarithmically), so
/// it is returned as an infinity toward the axis, never a finite stand-in (it was once
/// −2Gσ(ln(8/ε) − 2) ≈ −23.0 for R = M = G = 1) and never NaN; Φ stays finite and continuous
/// (−4GσR). Just off the rim, on both sides, the field follows the logarithmic asymptote.
#[test]
fn rim_attraction_is_infinite_and_the_potential_finite() {
    // Unit radius, so that points d·R off the rim are doubles with exact offsets.
    let unit = UniformDisk::new(1.0, MASS).unwrap();
    let rim = unit.field(&Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(rim.acceleration.x, f64::NEG_INFINITY);
    assert_eq!((rim.acceleration.y, rim.acceleration.z), (0.0, 0.0));
    let exact_rim_potential = -4.0 * (MASS / PI);
    assert!(((rim.potential - exact_rim_potential) / exact_rim_potential).abs() < POTENTIAL_REL);
    // Other points of the rim circle: infinite inward along each nonzero coordinate, no NaN.
    let opposite = unit.field(&Vec3::new(-1.0, 0.0, 0.0));
    assert_eq!(opposite.acceleration, Vec3::new(f64::INFINITY, 0.0, 0.0));
    let side = unit.field(&Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(side.acceleration, Vec3::new(0.0, f64::NEG_INFINITY, 0.0));
    // Off the rim, inside and outside, in the plane: a_ρ = −2Gσ(ln(8/d) − 2)(1 + O(d ln d)).
    for d in [1e-12, 1e-10, 1e-9, 1e-6] {
        for side in [1.0f64, -1.0] {
            let x: f64 = 1.0 + side * d;
            let d = (x - 1.0).abs(); // the offset of the double actually used (exact)
            let a = unit.acceleration(&Vec3::new(x, 0.0, 0.0)).x;
            assert!(a.is_finite());
            let asymptote = -2.0 * (MASS / PI) * ((8.0 / d).ln() - 2.0);
            assert!(
                ((a - asymptote) / asymptote).abs() < 10.0 * d + POTENTIAL_REL,
                "d = {side}·{d}: {a} vs {asymptote}"
            );
        }
    }
    // The values quoted when the rim was reported (R = M = G = 1, inside): −8.85 at 1 − 1e-6,
    // −14.71 at 1 − 1e-10, to the digits quoted.
    let one = UniformDisk::new(1.0, 1.0).unwrap();
    let a6 = one.acceleration(&Vec3::new(1.0 - 1e-6, 0.0, 0.0)).x;
    let a10 = one.acceleration(&Vec3::new(1.0 - 1e-10, 0.0, 0.0)).x;
    assert!((a6 + 8.85).abs() < 5e-3, "{a6}");
    assert!((a10 + 14.71).abs() < 5e-3, "{a10}");
    assert_eq!(unit.region(&Vec3::new(1.0, 0.0, 0.0)), Region::OnSurface);
    assert_eq!(
        unit.region(&Vec3::new(1.0 + f64::EPSILON, 0.0, 0.0)),
        Region::Outside
    );
    assert_eq!(
        disk().region(&Vec3::new(RADIUS, 0.0, 0.0)),
        Region::OnSurface
    );
}

/// On the axis: Φ = −2πGσ(√(R² + z²) − |z|), a_z = −sgn(z) 2πGσ (1 − |z|/√(R² + z²)),
/// written without cancellation.
#[test]
fn axis_matches_the_elementary_closed_form() {
    let body = disk();
    let s = sigma();
    for z in [
        1e-12, 1e-6, 0.01, 0.3, 1.0, 1.99, 2.0, 2.01, 7.0, 1e3, 1e6, 1e8, -0.5, -50.0,
    ] {
        let z = z * RADIUS;
        let root = RADIUS.hypot(z);
        let phi = -2.0 * PI * s * RADIUS * RADIUS / (root + z.abs());
        let az = -z.signum() * 2.0 * PI * s * RADIUS * RADIUS / (root * (root + z.abs()));
        let f = body.field(&Vec3::new(0.0, 0.0, z));
        assert!(
            ((f.potential - phi) / phi).abs() < POTENTIAL_REL,
            "z = {z}: Φ {} vs {phi}",
            f.potential
        );
        assert!(
            (f.acceleration - Vec3::new(0.0, 0.0, az)).norm() / az.abs() < ACCELERATION_REL,
            "z = {z}: a {:?} vs {az}",
            f.acceleration
        );
    }
    // The centre: Φ = −2πGσR, a = 0 by the average rule.
    let centre = body.field(&Vec3::zeros());
    let phi0 = -2.0 * PI * s * RADIUS;
    assert!(((centre.potential - phi0) / phi0).abs() < POTENTIAL_REL);
    assert_eq!(centre.acceleration, Vec3::zeros());
}

/// Φ = −GM/r [1 − (R²/(4r²)) P₂(cos θ)] + O(GM R⁴/r⁵): the quadrupole from I_zz = MR²/2,
/// I_xx = I_yy = MR²/4 (MacCullagh). At r = 1e4 R the octupole-order rest is 1e-16.
#[test]
fn far_field_is_monopole_plus_quadrupole() {
    let body = disk();
    let gm = MASS;
    for &(r, theta) in &[(1e4, 0.3), (1e4, FRAC_PI_2), (3e4, 2.5), (1e8, 1.0)] {
        let r = r * RADIUS;
        let (s, c) = f64::sin_cos(theta);
        let p = Vec3::new(r * s * 0.6, r * s * 0.8, r * c);
        let p2 = 1.5 * c * c - 0.5;
        let phi = -gm / r * (1.0 - RADIUS * RADIUS / (4.0 * r * r) * p2);
        // The quadrupole is 2.5e-9 of Φ at 1e4 R: this checks its coefficient to 4e-6.
        let got = body.potential(&p);
        assert!(
            ((got - phi) / phi).abs() < POTENTIAL_REL,
            "r = {r}: {got} vs {phi}"
        );
        // a = −GM r/r³ − ∇Φ₂, Φ₂ = (GMR²/8)(3z² r⁻⁵ − r⁻³).
        let a = body.acceleration(&p);
        let z = p.z;
        let grad_quadrupole = (p * (1.0 - 5.0 * z * z / (r * r)) + Vec3::new(0.0, 0.0, 2.0 * z))
            * (3.0 * gm * RADIUS * RADIUS / (8.0 * r.powi(5)));
        let expected = -p * (gm / (r * r * r)) - grad_quadrupole;
        assert!(
            (a - expected).norm() / expected.norm() < ACCELERATION_REL,
            "r = {r}: {a:?} vs {expected:?}"
        );
    }
}

/// The closed form (r < 2R) and the series (r ≥ 2R) agree where they meet.
#[test]
fn closed_form_and_series_agree_at_the_switch() {
    let body = disk();
    for theta in [0.0, 0.4, 1.0, FRAC_PI_2, 2.2, 3.0] {
        let (s, c) = f64::sin_cos(theta);
        let inside = 2.0 * RADIUS * (1.0 - 1e-15);
        let outside = 2.0 * RADIUS;
        let fi = body.field(&Vec3::new(inside * s, 0.0, inside * c));
        let fo = body.field(&Vec3::new(outside * s, 0.0, outside * c));
        assert!(
            ((fi.potential - fo.potential) / fo.potential).abs() < POTENTIAL_REL,
            "θ = {theta}: Φ {} vs {}",
            fi.potential,
            fo.potential
        );
        assert!(
            (fi.acceleration - fo.acceleration).norm() / fo.acceleration.norm() < ACCELERATION_REL,
            "θ = {theta}: a {:?} vs {:?}",
            fi.acceleration,
            fo.acceleration
        );
    }
}

#[test]
fn mirror_and_rotational_symmetry() {
    let body = disk();
    for p in probes() {
        let f = body.field(&p);
        let mirrored = body.field(&Vec3::new(p.x, p.y, -p.z));
        assert_eq!(f.potential, mirrored.potential);
        assert_eq!(f.acceleration.z, -mirrored.acceleration.z);
        assert_eq!(f.acceleration.x, mirrored.acceleration.x);
        let angle: f64 = 1.234;
        let (s, c) = angle.sin_cos();
        let q = Vec3::new(c * p.x - s * p.y, s * p.x + c * p.y, p.z);
        let g = body.field(&q);
        let rotated = Vec3::new(
            c * f.acceleration.x - s * f.acceleration.y,
            s * f.acceleration.x + c * f.acceleration.y,
            f.acceleration.z,
        );
        assert!(((g.potential - f.potential) / f.potential).abs() < POTENTIAL_REL);
        assert!((g.acceleration - rotated).norm() / f.acceleration.norm() < ACCELERATION_REL);
    }
}

/// The field scales as G M / R: an SI-sized disk is the unit disk rescaled, to a few ULP.
#[test]
fn scales_with_units() {
    let (r_si, m_si, g_si) = (6.4e6, 6.0e24, 6.674e-11);
    let unit = UniformDisk::new(1.0, 1.0).unwrap();
    let si = UniformDisk::new(r_si, m_si)
        .unwrap()
        .with_gravitational_constant(g_si)
        .unwrap();
    assert_eq!(si.radius(), r_si);
    assert!(
        ((si.surface_density() - m_si / (PI * r_si * r_si)) / si.surface_density()).abs() < 1e-15
    );
    for p in probes() {
        let p = p / RADIUS;
        let f1 = unit.field(&p);
        let f2 = si.field(&(p * r_si));
        let phi = f1.potential * g_si * m_si / r_si;
        let a = f1.acceleration * (g_si * m_si / (r_si * r_si));
        assert!(((f2.potential - phi) / phi).abs() < POTENTIAL_REL, "{p:?}");
        assert!(
            (f2.acceleration - a).norm() / a.norm() < ACCELERATION_REL,
            "{p:?}"
        );
    }
}

#[test]
fn constructor_and_trait_facts() {
    let body = disk().with_gravitational_constant(2.5).unwrap();
    assert_eq!(body.mass(), MASS);
    assert_eq!(body.gravitational_constant(), 2.5);
    assert_eq!(body.volume(), 0.0);
    assert_eq!(body.bounding_radius(), RADIUS);
    assert_eq!(body.radius(), RADIUS);
    assert!(((body.surface_density() - sigma()) / sigma()).abs() < 1e-15);
    assert!(matches!(
        UniformDisk::new(-1.0, 1.0),
        Err(BodyError::NotPositive { .. })
    ));
    assert!(matches!(
        UniformDisk::new(1.0, 0.0),
        Err(BodyError::NotPositive { .. })
    ));
    assert!(matches!(
        UniformDisk::new(f64::NAN, 1.0),
        Err(BodyError::NotFinite { .. })
    ));
    assert!(disk().with_gravitational_constant(f64::INFINITY).is_err());
    assert!(UniformDisk::new(1e-200, 1.0).is_err()); // σ overflows
                                                     // Every finite point gets a finite field, however extreme.
    for p in [
        Vec3::new(1e-300, 0.0, 1e-300),
        Vec3::new(RADIUS, 0.0, 1e-300),
        Vec3::new(RADIUS * (1.0 - f64::EPSILON), 0.0, 1e-310),
        Vec3::new(1e300, -1e300, 1e300),
        Vec3::new(0.0, 0.0, -1e-320),
    ] {
        let f = body.field(&p);
        assert!(
            f.potential.is_finite() && f.acceleration.iter().all(|c| c.is_finite()),
            "{p:?}: {f:?}"
        );
    }
}
