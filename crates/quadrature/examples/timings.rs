//! Rough timings of rule construction and integration (work against precision).
//!
//! `cargo run --release -p surfgrav-quadrature --example timings`
//!
//! Prints the median of several runs; on a shared machine expect ±30 %.

use std::f64::consts::PI;
use std::hint::black_box;
use std::time::{Duration, Instant};
use surfgrav_quadrature::{
    AdaptiveCubature, AdaptiveOptions, GaussLegendre, PeriodicTrapezoid, QuadratureError,
    Rectangle, TensorProductRule,
};

/// Median wall time of `runs` calls of `work`.
fn median_time(runs: usize, mut work: impl FnMut()) -> Duration {
    let mut times: Vec<Duration> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            work();
            start.elapsed()
        })
        .collect();
    times.sort();
    times[runs / 2]
}

fn micros(duration: Duration) -> f64 {
    duration.as_secs_f64() * 1e6
}

/// The potential and field of a unit spherical shell seen from `r0` (4 components), in
/// (azimuth, polar angle); exact values 4π/|r0| and 4π r0/|r0|³.
fn shell(r0: [f64; 3]) -> impl FnMut(f64, f64, &mut [f64; 4]) {
    move |phi, theta, values| {
        let (sin_theta, cos_theta) = theta.sin_cos();
        let (sin_phi, cos_phi) = phi.sin_cos();
        let d = [
            r0[0] - sin_theta * cos_phi,
            r0[1] - sin_theta * sin_phi,
            r0[2] - cos_theta,
        ];
        let distance = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        values[0] = sin_theta / distance;
        let cube = sin_theta / (distance * distance * distance);
        values[1] = d[0] * cube;
        values[2] = d[1] * cube;
        values[3] = d[2] * cube;
    }
}

fn main() -> Result<(), QuadratureError> {
    println!("Gauss-Legendre construction (nodes and weights correctly rounded):");
    for order in [10, 100, 1000] {
        let runs = if order == 1000 { 21 } else { 201 };
        let time = median_time(runs, || {
            black_box(GaussLegendre::standard(black_box(order)).expect("valid order"));
        });
        println!("  n = {order:5}: {:9.1} µs", micros(time));
    }

    let azimuth = PeriodicTrapezoid::new(64, 0.0, 2.0 * PI)?;
    let polar = GaussLegendre::new(32, 0.0, PI)?;
    let time = median_time(201, || {
        black_box(TensorProductRule::new(&azimuth, &polar));
    });
    println!(
        "Tensor rule 64 (trapezoid) x 32 (Gauss-Legendre): built in {:.1} µs",
        micros(time)
    );
    let tensor = TensorProductRule::new(&azimuth, &polar);
    let r0 = [1.2, 0.0, 1.6];
    let time = median_time(201, || {
        black_box(tensor.integrate_components(shell(black_box(r0))));
    });
    let exact_potential = 2.0 * PI;
    let potential = tensor.integrate_components(shell(r0))[0];
    println!(
        "  shell at |r0| = 2, 2048 nodes: {:.1} µs, potential relative error {:.1e}",
        micros(time),
        (potential - exact_potential).abs() / exact_potential
    );

    println!("Adaptive G7-K15 cubature (evaluations, time, true relative error):");
    let square = Rectangle::new(0.0, 1.0, -1.0, 2.0)?;
    let sphere = Rectangle::new(0.0, 2.0 * PI, 0.0, PI)?;
    for tolerance in [1e-6, 1e-9, 1e-12] {
        let options = AdaptiveOptions {
            relative_tolerance: tolerance,
            ..AdaptiveOptions::default()
        };
        // Smooth: e^(u + 2v) on [0, 1] x [-1, 2].
        let mut smooth = AdaptiveCubature::<1>::new(options)?;
        let exact = (1.0_f64.exp() - 1.0) * (4.0_f64.exp() - (-2.0_f64).exp()) / 2.0;
        let integrand = |u: f64, v: f64, values: &mut [f64; 1]| values[0] = (u + 2.0 * v).exp();
        let estimate = smooth.integrate(square, integrand)?;
        let time = median_time(51, || {
            black_box(smooth.integrate(square, integrand).expect("finite"));
        });
        println!(
            "  tol {tolerance:.0e}  smooth e^(u+2v):           {:7} evaluations {:9.1} µs  error {:.1e}",
            estimate.evaluations,
            micros(time),
            (estimate.value[0] - exact).abs() / exact
        );
        for (name, r0) in [("far", [1.2, 0.0, 1.6]), ("near", [0.63, 0.0, 0.84])] {
            let mut integrator = AdaptiveCubature::<4>::new(options)?;
            let estimate = integrator.integrate(sphere, shell(r0))?;
            let time = median_time(11, || {
                black_box(integrator.integrate(sphere, shell(r0)).expect("finite"));
            });
            let distance = (r0[0] * r0[0] + r0[2] * r0[2]).sqrt();
            let exact = 4.0 * PI / distance;
            println!(
                "  tol {tolerance:.0e}  sphere shell, {name:4} (|r0| = {distance:.2}): {:7} evaluations {:9.1} µs  error {:.1e}",
                estimate.evaluations,
                micros(time),
                (estimate.value[0] - exact).abs() / exact
            );
        }
    }
    Ok(())
}
