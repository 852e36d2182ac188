//! The identities the engine relies on, checked against references computed without the node
//! tables: the exterior attraction of an ellipsoid (1-D quadrature), Newton's law for a sphere,
//! and 3-D volume quadratures of the force, torque and energy density.

mod common;

use common::tolerance::{ACCELERATION_REL, POTENTIAL_REL};
use common::{
    gauss_legendre, inverse_distance_flux, point_mass_acceleration, point_mass_potential, rel,
    rel_vec, trapezoid, volume_integral, SplitMix, Vec3,
};
use std::f64::consts::PI;
use surfgrav_surfaces::{EllipsoidSurface, Surface, SurfaceNodes};

/// Rules that reach ACCELERATION_REL for sources at ≥ 2.1 bounding radii (see the convergence
/// example: 36 × 12 nodes reach 1e-12 for the azimuth–height form, 36 × 20 for the polar form).
const PERIODIC: usize = 64;
const HEIGHT: usize = 24;
const POLAR: usize = 40;

fn tables(e: &EllipsoidSurface) -> [SurfaceNodes; 2] {
    let p = trapezoid(PERIODIC);
    let (h, t) = (gauss_legendre(HEIGHT), gauss_legendre(POLAR));
    [
        SurfaceNodes::with_periodic_rule(&e.azimuth_height(), p.rule(), h.rule()).unwrap(),
        SurfaceNodes::with_periodic_rule(&e.polar_azimuth(), p.rule(), t.rule()).unwrap(),
    ]
}

fn random_ellipsoid(rng: &mut SplitMix) -> EllipsoidSurface {
    EllipsoidSurface::new(
        rng.uniform(0.3, 1.5),
        rng.uniform(0.3, 1.5),
        rng.uniform(0.3, 1.5),
    )
    .unwrap()
}

/// A random exterior point at 2.1 to 8 bounding radii.
fn random_source(rng: &mut SplitMix, e: &EllipsoidSurface) -> Vec3 {
    rng.unit_vector() * (e.bounding_radius() * rng.uniform(2.1, 8.0))
}

#[test]
fn reference_attraction_is_exact_for_a_sphere() {
    // ∮ dS/|r − r0| = V r0/|r0|³ for a sphere (its exterior field is that of a point).
    let mut rng = SplitMix(21);
    for _ in 0..20 {
        let radius = rng.uniform(0.2, 3.0);
        let r0 = rng.unit_vector() * radius * rng.uniform(1.01, 10.0);
        let axes = Vec3::repeat(radius);
        let exact = r0 * (4.0 / 3.0 * PI * radius.powi(3) / r0.norm().powi(3));
        let reference = inverse_distance_flux(&axes, &r0, 200);
        assert!(
            rel_vec(&reference, &exact) < POTENTIAL_REL,
            "{reference} vs {exact}"
        );
    }
}

#[test]
fn flux_of_inverse_distance_matches_the_exterior_attraction() {
    // ∮ dS/|r − r0| = −∇_{r0} ∫ dV/|r − r0|, the attraction of the homogeneous ellipsoid per
    // unit Gρ with the sign reversed; random shapes and points, both parametrisations.
    let mut rng = SplitMix(22);
    let mut worst: f64 = 0.0;
    for _ in 0..40 {
        let e = random_ellipsoid(&mut rng);
        let r0 = random_source(&mut rng, &e);
        let reference = inverse_distance_flux(&e.semi_axes(), &r0, 200);
        for nodes in tables(&e) {
            let flux = nodes.integrate(|r| 1.0 / (r - r0).norm());
            let err = rel_vec(&flux, &reference);
            worst = worst.max(err);
            assert!(
                err < ACCELERATION_REL,
                "{e:?} r0 {r0}: {flux} vs {reference}"
            );
        }
    }
    println!("worst relative error {worst:e}");
}

#[test]
fn force_of_a_point_mass_on_a_sphere_is_newtonian() {
    // F = −ρ ∮ Φ dS with Φ = −μ/|r − p|; exact F = M μ p/|p|³ (toward the point mass).
    let (radius, density, mu) = (0.8, 2.5, 3.0);
    let sphere = EllipsoidSurface::sphere(radius).unwrap();
    let mass = density * sphere.volume();
    let mut rng = SplitMix(23);
    for d in [2.1, 3.0, 7.0] {
        let p = rng.unit_vector() * (d * radius);
        let exact = p * (mass * mu / p.norm().powi(3));
        for nodes in tables(&sphere) {
            let force = -density * nodes.integrate(|r| point_mass_potential(mu, &p, r));
            assert!(
                rel_vec(&force, &exact) < ACCELERATION_REL,
                "{force} vs {exact}"
            );
            // A sphere feels no torque from a point mass.
            let torque = -density * nodes.integrate_moment(|r| point_mass_potential(mu, &p, r));
            assert!(
                torque.norm() < ACCELERATION_REL * radius * exact.norm(),
                "{torque}"
            );
        }
    }
}

#[test]
fn surface_integrals_equal_volume_integrals_for_a_point_mass() {
    // Force ρ∫a dV = −ρ∮Φ dS, torque ρ∫r×a dV = −ρ∮Φ r×dS, energy ρ∫Φ dV =
    // (ρ/3)∮[Φ r + ½|r|² a]·dS (Φ harmonic inside the body), each against a 3-D quadrature.
    let density = 1.7;
    let mu = 2.0;
    let mut rng = SplitMix(24);
    let mut worst = [0.0f64; 3];
    for _ in 0..8 {
        let e = random_ellipsoid(&mut rng);
        let p = random_source(&mut rng, &e);
        let phi = |r: &Vec3| point_mass_potential(mu, &p, r);
        let acc = |r: &Vec3| point_mass_acceleration(mu, &p, r);
        let axes = e.semi_axes();
        let force_volume: Vec3 = volume_integral(&axes, 24, 32, 48, acc) * density;
        let torque_volume: Vec3 =
            volume_integral(&axes, 24, 32, 48, |r| r.cross(&acc(r))) * density;
        let energy_volume: f64 = volume_integral(&axes, 24, 32, 48, phi) * density;
        for nodes in tables(&e) {
            let force = -density * nodes.integrate(phi);
            let torque = -density * nodes.integrate_moment(phi);
            let energy = density / 3.0
                * nodes.integrate_flux(|r| r * phi(r) + acc(r) * (0.5 * r.norm_squared()));
            worst[0] = worst[0].max(rel_vec(&force, &force_volume));
            worst[1] = worst[1].max(rel_vec(&torque, &torque_volume));
            worst[2] = worst[2].max(rel(energy, energy_volume));
            assert!(
                rel_vec(&force, &force_volume) < ACCELERATION_REL,
                "force {force} vs {force_volume}"
            );
            assert!(
                rel_vec(&torque, &torque_volume) < ACCELERATION_REL,
                "torque {torque} vs {torque_volume}"
            );
            assert!(
                rel(energy, energy_volume) < ACCELERATION_REL,
                "energy {energy} vs {energy_volume}"
            );
        }
    }
    println!(
        "worst relative errors: force {:e}, torque {:e}, energy {:e}",
        worst[0], worst[1], worst[2]
    );
}

#[test]
fn the_two_parametrisations_agree() {
    let mut rng = SplitMix(25);
    for _ in 0..30 {
        let e = random_ellipsoid(&mut rng);
        let p = random_source(&mut rng, &e);
        let phi = |r: &Vec3| point_mass_potential(1.0, &p, r);
        let [height, polar] = tables(&e);
        assert_eq!(
            e.azimuth_height().enclosed_volume(),
            e.polar_azimuth().enclosed_volume()
        );
        assert!(rel(height.enclosed_volume(), polar.enclosed_volume()) < POTENTIAL_REL);
        let (fh, fp) = (height.integrate(phi), polar.integrate(phi));
        assert!(rel_vec(&fh, &fp) < ACCELERATION_REL, "{fh} vs {fp}");
        let (mh, mp) = (height.integrate_moment(phi), polar.integrate_moment(phi));
        assert!(rel_vec(&mh, &mp) < ACCELERATION_REL, "{mh} vs {mp}");
        // Same surface: every node of either table satisfies the ellipsoid equation.
        for nodes in [&height, &polar] {
            for r in nodes.points() {
                let level = r.component_div(&e.semi_axes()).norm_squared();
                assert!((level - 1.0).abs() < POTENTIAL_REL);
            }
        }
    }
}
