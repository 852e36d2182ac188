//! Shared helpers of the interaction tests: bodies, poses, an independent volume quadrature,
//! and the error norms of `Interaction::error_estimate`.

#![allow(dead_code)]

pub mod json;

use nalgebra::UnitQuaternion;
use std::f64::consts::PI;
use surfgrav_interaction::{
    Body, Interaction, InteractionEngine, InteractionError, InteractionOptions, MethodChoice,
    SurfaceChoice,
};
use surfgrav_potentials::{Pose, PoseExt, Potential, Spheroid, Vec3};
use surfgrav_quadrature::{GaussLegendre, Rule1D};
use surfgrav_surfaces::{CompensatedSum, CompensatedSum3, EllipsoidSurface};

/// The workspace tolerance policy.
#[allow(unused_imports)]
pub use surfgrav_potentials::tolerance;

/// The founding paper's spheroid: a = 1, c = 0.25, m = 1.
pub fn paper_spheroid() -> Body {
    Body::spheroid(Spheroid::new(1.0, 0.25, 1.0).unwrap()).unwrap()
}

pub fn pose(position: [f64; 3], rotation: [f64; 3]) -> Pose {
    Pose::new(Vec3::from(position), Vec3::from(rotation))
}

pub fn engine(options: InteractionOptions) -> InteractionEngine {
    InteractionEngine::new(options).unwrap()
}

/// Options with a tolerance, a method and a surface.
pub fn options(tolerance: f64, method: MethodChoice, surface: SurfaceChoice) -> InteractionOptions {
    InteractionOptions {
        relative_tolerance: tolerance,
        method,
        surface,
        ..InteractionOptions::default()
    }
}

/// The interaction, or the best result when only the tolerance was missed.
pub fn best_effort(
    engine: &mut InteractionEngine,
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
) -> Interaction {
    match engine.interact(a, pose_a, b, pose_b) {
        Ok(r) => r,
        Err(InteractionError::ToleranceNotMet { best, .. }) => *best,
        Err(e) => panic!("interaction failed: {e}"),
    }
}

/// The error norms of `Interaction::error_estimate`: force and energy relative, torques
/// relative to max(|M|, |V|), of `x` against `reference`.
#[derive(Debug, Clone, Copy)]
pub struct Errors {
    pub force: f64,
    pub energy: f64,
    pub torque_a: f64,
    pub torque_b: f64,
}

impl Errors {
    pub fn max(&self) -> f64 {
        self.force
            .max(self.energy)
            .max(self.torque_a)
            .max(self.torque_b)
    }
}

/// Asserts that `x` lies within its own estimate plus `reference`'s of `reference` (largest
/// relative error of [`errors`]).
pub fn assert_within_estimates(label: &str, x: &Interaction, reference: &Interaction) {
    let error = errors(x, reference).max();
    assert!(
        error <= x.error_estimate + reference.error_estimate,
        "{label}: error {error:e}, estimates {:e} + {:e}",
        x.error_estimate,
        reference.error_estimate
    );
}

pub fn errors(x: &Interaction, reference: &Interaction) -> Errors {
    let v = reference.potential_energy.abs();
    Errors {
        force: (x.force_on_a - reference.force_on_a).norm() / reference.force_on_a.norm(),
        energy: (x.potential_energy - reference.potential_energy).abs() / v,
        torque_a: (x.torque_on_a - reference.torque_on_a).norm()
            / reference.torque_on_a.norm().max(v),
        torque_b: (x.torque_on_b - reference.torque_on_b).norm()
            / reference.torque_on_b.norm().max(v),
    }
}

/// Force on A, torque on A about its centroid and mutual energy, world frame, by a volume
/// quadrature over the solid ellipsoid A (Gauss–Legendre in the scaled radius and the polar
/// angle, trapezoid in azimuth) of ρ a_B, ρ x × a_B and ρ Φ_B: independent of every surface
/// formula.
pub fn volume_integrals(
    shape: &EllipsoidSurface,
    mass: f64,
    pose_a: &Pose,
    source: &dyn Potential,
    pose_b: &Pose,
    n: usize,
) -> (Vec3, Vec3, f64) {
    let density = mass / shape.volume();
    let [a, b, c] = [
        shape.x_semi_axis(),
        shape.y_semi_axis(),
        shape.z_semi_axis(),
    ];
    let radial = GaussLegendre::new(n, 0.0, 1.0).unwrap();
    let polar = GaussLegendre::new(n, 0.0, PI).unwrap();
    let n_phi = 2 * n;
    // Compensated sums: ~10⁵ terms summed naively would lose ~10⁻¹⁴.
    let mut force = CompensatedSum3::new();
    let mut torque = CompensatedSum3::new();
    let mut energy = CompensatedSum::new();
    for (&r, &wr) in radial.nodes().iter().zip(radial.weights()) {
        for (&t, &wt) in polar.nodes().iter().zip(polar.weights()) {
            let (st, ct) = t.sin_cos();
            let jacobian = a * b * c * r * r * st * wr * wt * (2.0 * PI / n_phi as f64);
            for k in 0..n_phi {
                let phi = 2.0 * PI * (k as f64 + 0.5) / n_phi as f64;
                let (sp, cp) = phi.sin_cos();
                let local = Vec3::new(a * r * st * cp, b * r * st * sp, c * r * ct);
                let world = pose_a.to_world(&local);
                let field = source.field_in_world(pose_b, &world);
                let x = world - pose_a.position();
                let w = density * jacobian;
                force.add(&(field.acceleration * w));
                torque.add(&(x.cross(&field.acceleration) * w));
                energy.add(field.potential * w);
            }
        }
    }
    (force.value(), torque.value(), energy.value())
}

/// A deterministic rotation vector from three numbers in [-1, 1].
pub fn rotation_vector(u: [f64; 3]) -> Vec3 {
    Vec3::new(u[0], u[1], u[2]) * PI
}

/// The pose of B rotated by a small rotation `delta` (rotation vector, world frame) about
/// its own centroid.
pub fn rotated(p: &Pose, delta: &Vec3) -> Pose {
    Pose::from_position_rotation(
        p.position(),
        UnitQuaternion::from_scaled_axis(*delta) * p.rotation,
    )
}

/// The pose moved by `delta`.
pub fn moved(p: &Pose, delta: &Vec3) -> Pose {
    Pose::from_position_rotation(p.position() + delta, p.rotation)
}

/// Central difference with one Richardson step: (4 D(h/2) − D(h)) / 3, D(h) = (f(h) − f(−h))/2h.
pub fn richardson<F: FnMut(f64) -> f64>(mut f: F, h: f64) -> f64 {
    let d1 = (f(h) - f(-h)) / (2.0 * h);
    let d2 = (f(0.5 * h) - f(-0.5 * h)) / h;
    (4.0 * d2 - d1) / 3.0
}
