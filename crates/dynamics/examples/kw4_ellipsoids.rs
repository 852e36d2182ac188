//! Error against cost of every integrator on 1999 KW4 as two triaxial ellipsoids (the full
//! two-body problem in 3-D), and the time of 10 mutual orbits with DOP853 at 1e-12.
//!
//! Inputs (Ho et al. 2021, the SIANS input file; SI units here, G = 6.674e-11): masses
//! 2.353e12 and 0.135e12 kg; semi-axes 766 × 747.5 × 673.5 m and 285 × 231.5 × 174.5 m;
//! relative orbit a = 2548 m, e = 0.0004, i = 156.1°, Ω = 105.4°, ϖ = 319.7°, M = 0;
//! Tait–Bryan angles (3.2, 0, 0)° and (0, 0, 0)°, read here as a yaw about the orbit normal
//! from the orbit frame (x toward the secondary, z along the orbit normal): the primary's long
//! axis 3.2° off the line of centres, the secondary's along it; spins 2.2728 and 0.3611 rad/h
//! about the c axes (the secondary's is synchronous: n = 0.3607 rad/h).
//!
//! `cargo run --release -p surfgrav-dynamics --example kw4_ellipsoids [orbits | toml]` (`toml`
//! prints the initial state as scene-file keys: the `kw4-ellipsoids` preset's numbers)

use std::time::Instant;
use surfgrav_dynamics::{
    state_from_elements, true_anomaly, Adaptive, BodyState, Elements, EngineModel, FixedScheme,
    FixedStep, Integrator, TwoBodyState,
};
use surfgrav_interaction::{Body, InteractionOptions};
use surfgrav_potentials::{Ellipsoid, Real, Vec3};

const G: Real = 6.674e-11;
const HOUR: Real = 3600.0;

fn scene() -> (EngineModel, TwoBodyState, Real) {
    let (m_a, m_b) = (2.353e12, 0.135e12);
    let body = |a, b, c, m| {
        Body::ellipsoid(
            Ellipsoid::new(a, b, c, m)
                .unwrap()
                .with_gravitational_constant(G)
                .unwrap(),
        )
        .unwrap()
    };
    let model = EngineModel::new(
        body(766.0, 747.5, 673.5, m_a),
        body(285.0, 231.5, 174.5, m_b),
        InteractionOptions::default(),
    )
    .unwrap();
    let mu = G * (m_a + m_b);
    let (node, varpi): (Real, Real) = (105.4f64.to_radians(), 319.7f64.to_radians());
    let elements = Elements {
        semi_major_axis: 2548.0,
        eccentricity: 0.0004,
        inclination: 156.1f64.to_radians(),
        node,
        pericentre: varpi - node,
    };
    let frame = [Vec3::x(), Vec3::y(), Vec3::z()];
    let (r, v) = state_from_elements(&elements, true_anomaly(0.0, 0.0004), mu, &frame);
    // Orbit frame: x toward B, z along the orbit normal.
    let z = r.cross(&v).normalize();
    let x = r.normalize();
    let orbit = nalgebra::UnitQuaternion::from_rotation_matrix(
        &nalgebra::Rotation3::from_basis_unchecked(&[x, z.cross(&x), z]),
    );
    let attitude = |yaw_deg: Real| {
        orbit * nalgebra::UnitQuaternion::from_scaled_axis(Vec3::z() * yaw_deg.to_radians())
    };
    let place = |position: Vec3, velocity: Vec3, yaw: Real, rate_per_hour: Real| {
        let mut b = BodyState::new(position, velocity);
        b.orientation = attitude(yaw);
        b.angular_velocity = b.orientation * Vec3::z() * (rate_per_hour / HOUR);
        b
    };
    let total = m_a + m_b;
    let start = TwoBodyState::new(
        place(-r * (m_b / total), -v * (m_b / total), 3.2, 2.2728),
        place(r * (m_a / total), v * (m_a / total), 0.0, 0.3611),
    );
    let period = 2.0 * std::f64::consts::PI * (2548.0f64.powi(3) / mu).sqrt();
    (model, start, period)
}

/// Relative position error (m) and attitude errors (rad) of `s` against `reference`.
fn error(s: &TwoBodyState, reference: &TwoBodyState) -> (Real, Real) {
    let position = (s.relative_position() - reference.relative_position()).norm();
    let attitude = s
        .body_a
        .orientation
        .angle_to(&reference.body_a.orientation)
        .max(s.body_b.orientation.angle_to(&reference.body_b.orientation));
    (position, attitude)
}

/// Prints the initial state as scene-file body keys (the `kw4-ellipsoids` preset's numbers).
fn print_bodies(start: &TwoBodyState) {
    for (name, b) in [("body_a", &start.body_a), ("body_b", &start.body_b)] {
        let v = |x: Vec3| format!("[{:?}, {:?}, {:?}]", x.x, x.y, x.z);
        println!("[{name}]");
        println!("position = {}", v(b.position));
        println!("velocity = {}", v(b.velocity));
        println!("orientation = {}", v(b.orientation.scaled_axis()));
        println!("angular_velocity = {}\n", v(b.angular_velocity));
    }
}

fn main() {
    if std::env::args().nth(1).as_deref() == Some("toml") {
        print_bodies(&scene().1);
        return;
    }
    let orbits: Real = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1.0);
    let (model, start, period) = scene();
    println!(
        "KW4 ellipsoids: period {:.1} s ({:.3} h), path: {:?}",
        period,
        period / HOUR,
        surfgrav_dynamics::InteractionModel::motion_path(&model, &start)
    );
    let t_end = orbits * period;
    let started = Instant::now();
    let mut dop = Adaptive::dop853(1e-12, 1e-12).unwrap();
    let ten = dop
        .integrate(&model, &start, 0.0, 10.0 * period, &mut |_| {})
        .unwrap();
    println!(
        "10 orbits, DOP853 1e-12: {:.2} s wall, {} steps, {} evaluations ({:.1} us each)",
        started.elapsed().as_secs_f64(),
        ten.steps,
        ten.force_evaluations,
        started.elapsed().as_secs_f64() * 1e6 / ten.force_evaluations as Real
    );
    let reference = Adaptive::dop853(1e-14, 1e-14)
        .unwrap()
        .integrate(&model, &start, 0.0, t_end, &mut |_| {})
        .unwrap()
        .last
        .state;
    println!("\n{orbits} orbit(s) against DOP853 at 1e-14:");
    println!("| integrator | setting | evaluations | seconds | position error (m) | attitude error (rad) |");
    println!("|---|---|---:|---:|---:|---:|");
    let report = |name: &str, setting: String, integrator: &mut dyn Integrator| {
        let t = Instant::now();
        let s = integrator
            .integrate(&model, &start, 0.0, t_end, &mut |_| {})
            .unwrap();
        let (p, a) = error(&s.last.state, &reference);
        println!(
            "| {name} | {setting} | {} | {:.3} | {p:.2e} | {a:.2e} |",
            s.force_evaluations,
            t.elapsed().as_secs_f64()
        );
    };
    for tolerance in [1e-6, 1e-8, 1e-10, 1e-12] {
        report(
            "dop853",
            format!("tol {tolerance:e}"),
            &mut Adaptive::dop853(tolerance, tolerance).unwrap(),
        );
        report(
            "dopri5",
            format!("tol {tolerance:e}"),
            &mut Adaptive::new(tolerance, tolerance).unwrap(),
        );
    }
    for (scheme, steps) in [
        (FixedScheme::RungeKutta4, [50.0, 100.0, 200.0]),
        (FixedScheme::Leapfrog, [100.0, 200.0, 400.0]),
        (FixedScheme::Yoshida4, [50.0, 100.0, 200.0]),
        (FixedScheme::Yoshida6, [25.0, 50.0, 100.0]),
        (FixedScheme::TripleJump8, [10.0, 20.0, 40.0]),
    ] {
        for per_orbit in steps {
            let h = period / per_orbit;
            report(
                scheme.name(),
                format!("{per_orbit} steps/orbit"),
                &mut FixedStep::new(scheme, h).unwrap(),
            );
        }
    }
}
