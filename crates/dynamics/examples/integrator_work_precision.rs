//! Work–precision table of every integrator on the Kepler problem (e = 0.5, 10 orbits), and the
//! cost of the paper-point scene (RK4, dt = 0.1, t = 300).
//!
//! Run with `cargo run --release -p surfgrav-dynamics --example integrator_work_precision`.

use std::time::Instant;
use surfgrav_dynamics::{
    Adaptive, BodyState, ConservationMonitor, FixedScheme, FixedStep, Integrator, OrbitAnalyser,
    PointMasses, TwoBodyState,
};
use surfgrav_potentials::{Real, Vec3};

/// Relative position on the Kepler orbit a = 1, μ = 1, starting at pericentre at t = 0.
fn kepler(e: Real, t: Real) -> Vec3 {
    let m = t.rem_euclid(2.0 * std::f64::consts::PI);
    let mut big_e = m;
    for _ in 0..60 {
        big_e -= (big_e - e * big_e.sin() - m) / (1.0 - e * big_e.cos());
    }
    Vec3::new(big_e.cos() - e, (1.0 - e * e).sqrt() * big_e.sin(), 0.0)
}

fn main() {
    let e = 0.5;
    let model = PointMasses::new(0.5, 0.5, 1.0).expect("valid masses");
    let r0 = Vec3::new(1.0 - e, 0.0, 0.0);
    let v0 = Vec3::new(0.0, ((1.0 + e) / (1.0 - e)).sqrt(), 0.0);
    let initial = TwoBodyState::new(
        BodyState::new(-0.5 * r0, -0.5 * v0),
        BodyState::new(0.5 * r0, 0.5 * v0),
    );
    let t_end = 20.0 * std::f64::consts::PI;
    println!("Kepler e = 0.5, 10 orbits: integrator, setting, steps, force evaluations, position error, wall time");
    let mut runs: Vec<(String, Box<dyn Integrator>)> = Vec::new();
    for (scheme, steps) in [
        (FixedScheme::RungeKutta4, [1000, 4000, 16000]),
        (FixedScheme::Leapfrog, [4000, 16000, 64000]),
        (FixedScheme::Yoshida4, [1000, 4000, 16000]),
        (FixedScheme::Yoshida6, [500, 2000, 8000]),
        (FixedScheme::TripleJump8, [250, 1000, 4000]),
    ] {
        for n in steps {
            let integrator = FixedStep::new(scheme, t_end / n as Real).expect("valid step");
            runs.push((format!("{n} steps"), Box::new(integrator)));
        }
    }
    for tolerance in [1e-8, 1e-10, 1e-12, 1e-14] {
        let integrator = Adaptive::new(tolerance, 1e-2 * tolerance).expect("valid tolerance");
        runs.push((format!("rtol {tolerance:e}"), Box::new(integrator)));
    }
    for tolerance in [1e-8, 1e-10, 1e-12, 1e-14, 1e-15] {
        let integrator = Adaptive::dop853(tolerance, tolerance).expect("valid tolerance");
        runs.push((format!("tol {tolerance:e}"), Box::new(integrator)));
    }
    for (setting, mut integrator) in runs {
        let start = Instant::now();
        let summary = integrator
            .integrate(&model, &initial, 0.0, t_end, &mut |_| {})
            .expect("Kepler run");
        let wall = start.elapsed().as_secs_f64();
        let error = (summary.last.state.relative_position() - kepler(e, t_end)).norm();
        println!(
            "{:>13} {:>12} {:>8} {:>9} {:>10.2e} {:>9.2e} s",
            integrator.name(),
            setting,
            summary.steps,
            summary.force_evaluations,
            error,
            wall
        );
    }

    let model = PointMasses::new(1.0, 1.0, 1.0).expect("valid masses");
    let initial = TwoBodyState::new(
        BodyState::new(Vec3::new(-3.5, 0.0, 0.0), Vec3::new(0.0, 0.2, 0.0)),
        BodyState::new(Vec3::new(3.5, 0.0, 0.0), Vec3::new(0.0, -0.2, 0.0)),
    );
    let start = Instant::now();
    let mut orbit = OrbitAnalyser::new();
    let mut monitor = ConservationMonitor::new(&model);
    let summary = FixedStep::new(FixedScheme::RungeKutta4, 0.1)
        .expect("valid step")
        .integrate(&model, &initial, 0.0, 300.0, &mut |s| {
            orbit.observe(s);
            monitor.observe(s);
        })
        .expect("paper-point run");
    let wall = start.elapsed().as_secs_f64();
    let report = orbit.report();
    let energy = monitor.energy().expect("energy");
    println!(
        "paper-point RK4 dt 0.1 t 300: {} steps, {} evaluations, {:.2e} s with diagnostics; T_r {:.6}, T_psi {:.6}, psi_p {:.2e} deg, d_min {:.6}, sigma(dE) {:.2e}",
        summary.steps,
        summary.force_evaluations,
        wall,
        report.radial_period.unwrap_or(Real::NAN),
        report.azimuthal_period.unwrap_or(Real::NAN),
        report.precession_angle_deg.unwrap_or(Real::NAN),
        report.minimum_separation.unwrap_or(Real::NAN),
        energy.step_changes.standard_deviation
    );
}
