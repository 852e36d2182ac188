//! The lamina's node tables: area and rim identities, the 2-D divergence theorem, the exact
//! on-axis force and energy of a point mass, and the engine's combination formulas.

mod common;

use common::tolerance::{ACCELERATION_REL, POTENTIAL_REL};
use common::{
    gauss_legendre, point_mass_acceleration, point_mass_potential, rel, rel_vec, trapezoid,
    SplitMix, Vec3,
};
use std::f64::consts::PI;
use surfgrav_surfaces::{Lamina, LaminaNodes, NodeTableError};

fn nodes(radius: f64, n_angle: usize, n_radial: usize, n_rim: usize) -> LaminaNodes {
    let (angle, radial, rim) = (
        trapezoid(n_angle),
        gauss_legendre(n_radial),
        trapezoid(n_rim),
    );
    Lamina::new(radius)
        .unwrap()
        .nodes(angle.rule(), radial.rule(), rim.rule())
        .unwrap()
}

#[test]
fn area_and_rim_identities() {
    let mut rng = SplitMix(41);
    for _ in 0..20 {
        let radius = rng.uniform(0.1, 5.0);
        let r2 = radius * radius;
        // Small rules suffice: the identities involve polynomials in s of degree ≤ 3 and the
        // first Fourier modes in φ.
        let (na, nr, nrim) = (
            3 + rng.next_u64() as usize % 8,
            2,
            3 + rng.next_u64() as usize % 8,
        );
        let t = nodes(radius, na, nr, nrim);
        assert_eq!(t.area_points().len(), na * nr);
        assert_eq!(t.area_weights().len(), na * nr);
        assert_eq!(t.rim_points().len(), nrim);
        assert_eq!(t.normal(), Vec3::z());
        assert_eq!(t.centre(), Vec3::zeros());
        // ∬ dA = πR², ∬ r dA = 0, ∬ s² dA = πR⁴/2.
        let area = t.integrate_area(|_| 1.0);
        assert!(rel(area, PI * r2) < POTENTIAL_REL, "{area}");
        assert!(rel(Lamina::new(radius).unwrap().area(), PI * r2) < POTENTIAL_REL);
        let centroid = t.integrate_area_vector(|r| *r);
        assert!(centroid.norm() < POTENTIAL_REL * radius * area);
        let polar_moment = t.integrate_area(|r| r.norm_squared());
        assert!(rel(polar_moment, PI * r2 * r2 / 2.0) < POTENTIAL_REL);
        // All area nodes lie in the closed disk, rim nodes on the circle.
        assert!(t
            .area_points()
            .iter()
            .all(|r| r.z == 0.0 && r.norm() <= radius));
        assert!(t
            .rim_points()
            .iter()
            .all(|r| rel(r.norm(), radius) < POTENTIAL_REL));
        // ∮ ν dl = 0, ∮ r·ν dl = 2πR² (∇·r = 2 in the plane), ∮ x ν_x dl = πR²,
        // ∮ (r × ν) dl = 0 (no torque about the axis).
        let total_normal = t.integrate_rim(|_| 1.0);
        assert!(total_normal.norm() < POTENTIAL_REL * 2.0 * PI * radius);
        let divergence = t.integrate_rim_flux(|r| *r);
        assert!(rel(divergence, 2.0 * PI * r2) < POTENTIAL_REL);
        let x_flux = t.integrate_rim_flux(|r| Vec3::new(r.x, 0.0, 0.0));
        assert!(rel(x_flux, PI * r2) < POTENTIAL_REL);
        let axial_torque: Vec3 = t.rim_iter().map(|(r, nu)| r.cross(nu)).sum();
        assert!(axial_torque.norm() < POTENTIAL_REL * 2.0 * PI * r2);
        // Each weighted normal is outward, in the plane, of length R × (angle weight).
        for (r, nu) in t.rim_iter() {
            assert!(nu.dot(r) > 0.0 && nu.z == 0.0);
            assert!(rel(nu.norm(), radius * 2.0 * PI / nrim as f64) < POTENTIAL_REL);
        }
    }
}

#[test]
fn divergence_theorem_in_the_plane_for_a_point_mass() {
    // ∬ ∇∥Φ dA = ∮ Φ ν dl, with ∇Φ = −a, for point masses above, below and beside the disk.
    let radius = 1.0;
    let t = nodes(radius, 96, 40, 96);
    let mut rng = SplitMix(42);
    for _ in 0..20 {
        let p = loop {
            let candidate = rng.unit_vector() * rng.uniform(2.1, 6.0);
            if candidate.norm() > 2.1 * radius {
                break candidate;
            }
        };
        let in_plane = |v: Vec3| Vec3::new(v.x, v.y, 0.0);
        let area_side = t.integrate_area_vector(|r| -in_plane(point_mass_acceleration(1.0, &p, r)));
        let rim_side = t.integrate_rim(|r| point_mass_potential(1.0, &p, r));
        assert!(rim_side.z == 0.0);
        assert!(
            rel_vec(&rim_side, &area_side) < ACCELERATION_REL,
            "{rim_side} vs {area_side}"
        );
    }
}

#[test]
fn on_axis_point_mass_force_and_energy_are_exact() {
    // A point mass μ = G m at height h on the axis: the disk's field there is
    // −2πGσ(1 − h/√(h² + R²)) ẑ, so the disk feels F = +2πσμ(1 − h/√(h² + R²)) ẑ, and the mutual
    // energy is U = −2πσμ(√(R² + h²) − h).
    let (radius, mass, mu) = (1.5, 2.0, 0.7);
    let sigma = mass / (PI * radius * radius);
    let t = nodes(radius, 8, 40, 8);
    for h in [0.3, 1.0, 3.0, -2.0] {
        let p = Vec3::new(0.0, 0.0, h);
        let root = (h * h + radius * radius).sqrt();
        let exact_force = Vec3::z() * (2.0 * PI * sigma * mu * (h.signum() - h / root));
        let exact_energy = -2.0 * PI * sigma * mu * (root - h.abs());
        let n = t.normal();
        let normal_part = sigma * t.integrate_area(|r| point_mass_acceleration(mu, &p, r).dot(&n));
        let in_plane_part = -sigma * t.integrate_rim(|r| point_mass_potential(mu, &p, r));
        let force = n * normal_part + in_plane_part;
        let energy = sigma * t.integrate_area(|r| point_mass_potential(mu, &p, r));
        assert!(
            rel_vec(&force, &exact_force) < ACCELERATION_REL,
            "h {h}: {force} vs {exact_force}"
        );
        assert!(
            rel(energy, exact_energy) < POTENTIAL_REL,
            "h {h}: {energy} vs {exact_energy}"
        );
    }
}

#[test]
fn engine_combination_equals_the_plain_area_integrals_in_any_frame() {
    // F = σ n̂ Σ w (a·n̂) − σ Σ Φ ν and M = σ Σ w (a·n̂)(r − c)×n̂ (about the centre) equal the
    // plain area integrals σ Σ w a and σ Σ w (r − c)×a; computed in a rotated, shifted frame
    // they are the rotated body-frame results.
    let (radius, sigma, mu) = (1.0, 0.9, 1.3);
    let body = nodes(radius, 96, 40, 96);
    let mut rng = SplitMix(43);
    for _ in 0..10 {
        let p = rng.unit_vector() * rng.uniform(2.1, 6.0);
        let rotation = rng.rotation();
        let offset = rng.unit_vector() * rng.uniform(0.0, 5.0);
        let moved = body.transformed(&rotation, &offset).unwrap();
        assert!((moved.centre() - offset).norm() < POTENTIAL_REL * offset.norm().max(1.0));
        assert!((moved.normal() - rotation * Vec3::z()).norm() < POTENTIAL_REL);
        assert_eq!(moved.area_weights(), body.area_weights());
        let mut results = Vec::new();
        for (t, source) in [(&body, p), (&moved, rotation * p + offset)] {
            let (n, c) = (t.normal(), t.centre());
            let acc = |r: &Vec3| point_mass_acceleration(mu, &source, r);
            let phi = |r: &Vec3| point_mass_potential(mu, &source, r);
            let force =
                n * (sigma * t.integrate_area(|r| acc(r).dot(&n))) - t.integrate_rim(phi) * sigma;
            let torque = t.integrate_area_vector(|r| (r - c).cross(&n) * acc(r).dot(&n)) * sigma;
            let plain_force = t.integrate_area_vector(acc) * sigma;
            let plain_torque = t.integrate_area_vector(|r| (r - c).cross(&acc(r))) * sigma;
            let energy = sigma * t.integrate_area(phi);
            assert!(
                rel_vec(&force, &plain_force) < ACCELERATION_REL,
                "{force} vs {plain_force}"
            );
            assert!(
                rel_vec(&torque, &plain_torque) < ACCELERATION_REL,
                "{torque} vs {plain_torque}"
            );
            // No torque about the disk's own axis.
            assert!(torque.dot(&n).abs() < ACCELERATION_REL * torque.norm());
            results.push((force, torque, energy));
        }
        let ((f0, m0, u0), (f1, m1, u1)) = (results[0], results[1]);
        assert!(rel_vec(&f1, &(rotation * f0)) < ACCELERATION_REL);
        assert!(rel_vec(&m1, &(rotation * m0)) < ACCELERATION_REL);
        assert!(rel(u1, u0) < POTENTIAL_REL);
    }
}

#[test]
fn transform_into_reuses_storage_and_refuses_non_finite_input() {
    let body = nodes(1.0, 16, 8, 16);
    let mut rng = SplitMix(44);
    let (rotation, offset) = (rng.rotation(), Vec3::new(1.0, -1.0, 0.5));
    let mut out = body.transformed(&rotation, &offset).unwrap();
    let ptr = out.area_points().as_ptr();
    body.transform_into(&rotation.inverse(), &offset, &mut out)
        .unwrap();
    assert_eq!(out.area_points().as_ptr(), ptr);
    let before = out.clone();
    assert_eq!(
        body.transform_into(&rotation, &Vec3::new(0.0, f64::INFINITY, 0.0), &mut out),
        Err(NodeTableError::NonFiniteTransform)
    );
    assert_eq!(out, before);
}
