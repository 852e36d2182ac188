//! Limits and closed forms: a spheroid tending to a sphere tends to the point formula; a
//! sphere integrated as a surface is the point formula; uniform disks integrated as laminas
//! match Conway's closed form; the lamina's rim form of the force matches a plain area
//! integral.

mod interaction_support;

use interaction_support::*;
use std::f64::consts::PI;
use surfgrav_interaction::{Body, Method, MethodChoice, SurfaceChoice};
use surfgrav_potentials::{Pose, PoseExt, Spheroid, UniformDisk, Vec3};
use surfgrav_quadrature::{GaussLegendre, Rule1D};

/// A spheroid with c/a = 1 − δ approaches the point formula linearly in δ (its quadrupole is
/// ∝ a² − c²), and at δ = 0 the surface integral is the point formula.
#[test]
fn spheroids_tend_to_point_masses() {
    let b = paper_spheroid();
    let pose_a = pose([0.2, 0.1, -0.3], [0.4, 0.1, -0.2]);
    let pose_b = pose([1.7, 1.5, 0.6], [0.2, -0.5, 0.3]);
    let point_like = Body::spheroid(Spheroid::new(1.0, 1.0, 1.4).unwrap()).unwrap();
    let exact = surfgrav_interaction::interact(&point_like, &pose_a, &b, &pose_b).unwrap();
    assert_eq!(exact.method, Method::AnalyticPoint);
    let mut quadrature = engine(options(1e-12, MethodChoice::FixedRules, SurfaceChoice::A));
    let sphere_surface = quadrature
        .interact(&point_like, &pose_a, &b, &pose_b)
        .unwrap();
    assert!(
        errors(&sphere_surface, &exact).max()
            <= sphere_surface.error_estimate + exact.error_estimate
    );

    let mut previous: Option<(f64, f64)> = None;
    for delta in [1e-1, 1e-2, 1e-3, 1e-4, 1e-5] {
        let a = Body::spheroid(Spheroid::new(1.0, 1.0 - delta, 1.4).unwrap()).unwrap();
        let r = quadrature.interact(&a, &pose_a, &b, &pose_b).unwrap();
        let gap = errors(&r, &exact).max();
        assert!(
            gap > r.error_estimate,
            "the shape must be visible at δ = {delta}"
        );
        if let Some((d0, g0)) = previous {
            // Linear in δ: the ratio of the gaps follows the ratio of the δ's within 20 %.
            let order = (g0 / gap).ln() / (d0 / delta).ln();
            assert!((order - 1.0).abs() < 0.2, "order {order} at δ = {delta}");
        }
        previous = Some((delta, gap));
    }
}

/// Uniform disks integrated as laminas (over either disk) match Conway's closed form from near
/// contact to far away, within the error estimate and below 10⁻¹².
#[test]
fn laminas_match_the_closed_form_for_coplanar_disks() {
    let a = Body::disk(UniformDisk::new(1.0, 1.0).unwrap()).unwrap();
    let b = Body::disk(UniformDisk::new(0.5, 2.0).unwrap()).unwrap();
    let tilt = [0.2, 0.7, -0.4];
    let pose_a = pose([0.5, -0.5, 1.0], tilt);
    let mut worst: f64 = 0.0;
    for separation in [1.6, 2.0, 4.0, 20.0] {
        let direction = pose_a.rotation * Vec3::new(0.6, 0.8, 0.0);
        let pose_b = Pose::new(pose_a.position() + direction * separation, Vec3::from(tilt));
        let closed = surfgrav_interaction::interact(&a, &pose_a, &b, &pose_b).unwrap();
        assert_eq!(closed.method, Method::AnalyticDiskPair);
        for surface in [SurfaceChoice::A, SurfaceChoice::B] {
            let mut e = engine(options(1e-12, MethodChoice::FixedRules, surface));
            let r = e.interact(&a, &pose_a, &b, &pose_b).unwrap();
            let err = errors(&r, &closed);
            worst = worst.max(err.max());
            assert!(
                err.max() <= r.error_estimate + closed.error_estimate && r.error_estimate <= 1e-12,
                "separation {separation} over {surface:?}: {err:?}, estimate {:e}",
                r.error_estimate
            );
        }
    }
    assert!(worst <= 1e-12, "{worst:e}");
}

/// A lamina's force by the rim form (σ n̂ ∬ a·n̂ dA − σ ∮ Φ ν̂ dl) and its torque equal plain
/// area integrals σ ∬ a dA and σ ∬ x × a dA computed here on a polar grid, for a disk above
/// and beside a spheroid (tilted).
#[test]
fn lamina_rim_form_equals_the_area_integral() {
    let disk = UniformDisk::new(0.8, 1.2).unwrap();
    let a = Body::disk(disk).unwrap();
    let b = paper_spheroid();
    let pose_b = pose([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]);
    for pose_a in [
        pose([0.2, 0.1, 0.9], [0.3, 0.1, 0.0]),
        pose([1.4, 1.1, 0.3], [0.0, 1.2, 0.5]),
    ] {
        let mut e = engine(options(1e-12, MethodChoice::FixedRules, SurfaceChoice::A));
        let r = e.interact(&a, &pose_a, &b, &pose_b).unwrap();
        // Plain area integrals on polar grids (Gauss–Legendre in s, trapezoid in φ), at two
        // resolutions to bound their own error.
        let area = |n: usize| {
            let sigma = disk.surface_density();
            let radial = GaussLegendre::new(n, 0.0, 0.8).unwrap();
            let n_phi = 3 * n;
            let (mut force, mut torque, mut energy) = (Vec3::zeros(), Vec3::zeros(), 0.0);
            for (&s, &ws) in radial.nodes().iter().zip(radial.weights()) {
                for k in 0..n_phi {
                    let phi = 2.0 * PI * (k as f64 + 0.5) / n_phi as f64;
                    let local = Vec3::new(s * phi.cos(), s * phi.sin(), 0.0);
                    let world = pose_a.to_world(&local);
                    let field = b.potential().field_in_world(&pose_b, &world);
                    let w = sigma * s * ws * 2.0 * PI / n_phi as f64;
                    force += field.acceleration * w;
                    torque += (world - pose_a.position()).cross(&field.acceleration) * w;
                    energy += field.potential * w;
                }
            }
            (force, torque, energy)
        };
        let (force, torque, energy) = area(80);
        let (f2, m2, v2) = area(60);
        let v = energy.abs();
        let reference_error = ((force - f2).norm() / force.norm())
            .max((torque - m2).norm() / torque.norm().max(v))
            .max((energy - v2).abs() / v);
        assert!(reference_error < 1e-12, "{reference_error:e}");
        let bound = r.error_estimate + reference_error;
        assert!((r.force_on_a - force).norm() <= bound * force.norm());
        assert!((r.torque_on_a - torque).norm() <= bound * torque.norm().max(v));
        assert!((r.potential_energy - energy).abs() <= bound * v);
        // And the spheroid's side of the same interaction agrees.
        let mut over_b = engine(options(1e-12, MethodChoice::FixedRules, SurfaceChoice::B));
        let rb = over_b.interact(&a, &pose_a, &b, &pose_b).unwrap();
        assert!(errors(&rb, &r).max() <= r.error_estimate + rb.error_estimate);
    }
}
