//! Any potential with any surface: a triaxial ellipsoid's field on a spheroid's surface, and a
//! user-defined potential (two point masses, a "dumbbell") on an ellipsoid's surface, through
//! the engine and through the generic (monomorphised) node loop. Each result is checked
//! against an independent value.
//!
//! Run with `cargo run --release -p surfgrav-interaction --example pair_any_potential`.

use std::sync::Arc;
use surfgrav_interaction::{
    integrate_over_solid, Body, BodyShape, FrameMap, InteractionEngine, InteractionOptions,
    MethodChoice, SurfaceChoice,
};
use surfgrav_potentials::{
    Ellipsoid as SolidEllipsoid, Field, Pose, PoseExt, Potential, Region, Spheroid, Vec3,
};
use surfgrav_quadrature::{GaussLegendre, PeriodicTrapezoid, Rule1D};
use surfgrav_surfaces::{BorrowedRule, EllipsoidSurface, Interval, SurfaceNodes};

/// Two point masses at ±`half_length` along the body x axis: a user's own potential.
#[derive(Debug, Clone, Copy)]
struct Dumbbell {
    mass_each: f64,
    half_length: f64,
}

impl Dumbbell {
    fn ends(&self) -> [Vec3; 2] {
        [Vec3::x() * self.half_length, -Vec3::x() * self.half_length]
    }
}

impl Potential for Dumbbell {
    fn mass(&self) -> f64 {
        2.0 * self.mass_each
    }
    fn gravitational_constant(&self) -> f64 {
        1.0
    }
    fn volume(&self) -> f64 {
        0.0
    }
    fn bounding_radius(&self) -> f64 {
        self.half_length
    }
    fn region(&self, r: &Vec3) -> Region {
        if self.ends().iter().any(|e| e == r) {
            Region::OnSurface
        } else {
            Region::Outside
        }
    }
    fn field(&self, r: &Vec3) -> Field {
        let mut field = Field {
            potential: 0.0,
            acceleration: Vec3::zeros(),
        };
        for end in self.ends() {
            let d = r - end;
            let distance = d.norm();
            field.potential -= self.mass_each / distance;
            field.acceleration -= d * (self.mass_each / distance.powi(3));
        }
        field
    }
}

fn show(v: &Vec3) -> String {
    format!("[{:.15e}, {:.15e}, {:.15e}]", v.x, v.y, v.z)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // 1. A triaxial ellipsoid's potential integrated over a spheroid's surface.
    let spheroid = Body::spheroid(Spheroid::new(1.0, 0.25, 1.0)?)?;
    let triaxial_field = SolidEllipsoid::new(1.2, 0.8, 0.5, 2.0)?;
    let triaxial = Body::ellipsoid(triaxial_field)?;
    let pose_a = Pose::identity();
    let pose_b = Pose::new(Vec3::new(2.4, 0.5, 0.3), Vec3::new(0.2, -0.4, 0.7));
    let mut over_spheroid = InteractionEngine::new(InteractionOptions {
        method: MethodChoice::FixedRules,
        surface: SurfaceChoice::A,
        ..InteractionOptions::default()
    })?;
    let r = over_spheroid.interact(&spheroid, &pose_a, &triaxial, &pose_b)?;
    println!("triaxial field on the spheroid's surface ({}):", r.method);
    println!("  force on A  {}", show(&r.force_on_a));
    println!("  torque on A {}", show(&r.torque_on_a));
    println!("  torque on B {}", show(&r.torque_on_b));
    println!(
        "  V = {:.15e}, estimate {:.1e}, {} evaluations",
        r.potential_energy, r.error_estimate, r.evaluations
    );
    // Independent check: the spheroid's field on the ellipsoid's surface.
    let mut over_triaxial = InteractionEngine::new(InteractionOptions {
        method: MethodChoice::FixedRules,
        surface: SurfaceChoice::B,
        ..InteractionOptions::default()
    })?;
    let check = over_triaxial.interact(&spheroid, &pose_a, &triaxial, &pose_b)?;
    let force_gap = (r.force_on_a - check.force_on_a).norm() / r.force_on_a.norm();
    let energy_gap = ((r.potential_energy - check.potential_energy) / r.potential_energy).abs();
    println!("  over the ellipsoid instead: force differs by {force_gap:.1e}, energy by {energy_gap:.1e}");
    assert!(force_gap <= r.error_estimate + check.error_estimate);
    assert!(energy_gap <= r.error_estimate + check.error_estimate);

    // 2. A user-defined potential with an ellipsoid's surface, through the engine: the dumbbell
    //    has no surface, so the engine integrates over the ellipsoid.
    let dumbbell = Dumbbell {
        mass_each: 0.5,
        half_length: 0.6,
    };
    let user = Body::custom(Arc::new(dumbbell), BodyShape::FieldOnly)?;
    let ellipsoid_field = SolidEllipsoid::new(1.0, 0.7, 0.4, 1.5)?;
    let ellipsoid = Body::ellipsoid(ellipsoid_field)?;
    let pose_e = Pose::new(Vec3::zeros(), Vec3::new(0.1, 0.2, 0.3));
    let pose_d = Pose::new(Vec3::new(0.4, 2.3, 0.2), Vec3::new(0.0, 0.0, 0.9));
    let mut engine = InteractionEngine::default();
    let r = engine.interact(&ellipsoid, &pose_e, &user, &pose_d)?;
    // Exact: each point mass m feels m a_E(p); the ellipsoid feels the opposite.
    let mut force_on_ellipsoid = Vec3::zeros();
    let mut energy = 0.0;
    for end in dumbbell.ends() {
        let p = pose_d.to_world(&end);
        let f = ellipsoid_field.field_in_world(&pose_e, &p);
        force_on_ellipsoid -= f.acceleration * dumbbell.mass_each;
        energy += f.potential * dumbbell.mass_each;
    }
    let force_gap = (r.force_on_a - force_on_ellipsoid).norm() / force_on_ellipsoid.norm();
    let energy_gap = ((r.potential_energy - energy) / energy).abs();
    println!(
        "user dumbbell on the ellipsoid's surface ({}, {} evaluations):",
        r.method, r.evaluations
    );
    println!("  force on the ellipsoid {}", show(&r.force_on_a));
    println!("  against the point masses in the ellipsoid's field: force {force_gap:.1e}, energy {energy_gap:.1e} (estimate {:.1e})", r.error_estimate);
    // The exact values carry the closed form's own accuracy.
    let exact_accuracy = surfgrav_interaction::ANALYTIC_RELATIVE_ERROR;
    assert!(force_gap <= r.error_estimate + exact_accuracy);
    assert!(energy_gap <= r.error_estimate + exact_accuracy);

    // 3. The same pairing through the generic loop, monomorphised for `Dumbbell`, with a node
    //    table built once from rules of the quadrature crate.
    let shape = EllipsoidSurface::new(1.0, 0.7, 0.4)?;
    let azimuth = PeriodicTrapezoid::new(64, 0.0, 1.0)?;
    let height = GaussLegendre::new(40, -1.0, 1.0)?;
    let table = SurfaceNodes::with_periodic_rule(
        &shape.azimuth_height(),
        BorrowedRule::new(azimuth.nodes(), azimuth.weights(), Interval::UNIT)?,
        BorrowedRule::new(height.nodes(), height.weights(), Interval::SYMMETRIC_UNIT)?,
    )?;
    let map = FrameMap::between(&pose_e, &pose_d)?;
    let integrals = integrate_over_solid(&table, 1.5 / shape.volume(), &dumbbell, &map);
    let force_world = pose_e.rotation * integrals.force;
    println!(
        "generic loop, {} nodes: force differs from the exact one by {:.1e}; the two torque forms by {:.1e}",
        integrals.evaluations,
        (force_world - force_on_ellipsoid).norm() / force_on_ellipsoid.norm(),
        (integrals.torque - integrals.torque_gradient_form).norm() / integrals.torque.norm()
    );
    Ok(())
}
