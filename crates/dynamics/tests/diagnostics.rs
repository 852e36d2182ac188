//! Conservation diagnostics: statistics against direct computation, and the paper-point scene.

mod common;

use common::{paper_point, Kepler};
use surfgrav_dynamics::{
    angular_momentum, total_energy, CompensatedSum, ConservationMonitor, FixedScheme, FixedStep,
    Integrator, SeriesAccumulator,
};
use surfgrav_potentials::{Real, Vec3};

#[test]
fn compensated_sum_keeps_small_terms() {
    let mut sum = CompensatedSum::default();
    for x in [1e16, 1.0, -1e16, 1e-3] {
        sum.add(x);
    }
    assert_eq!(sum.value(), 1.001);
    assert_eq!(1e16 + 1.0 - 1e16 + 1e-3, 1e-3); // what plain summation gives
}

/// Streaming statistics equal the two-pass formulas; the slope of exactly linear data is exact.
#[test]
fn series_statistics_match_two_pass_formulas() {
    let times: Vec<Real> = (0..1000).map(|k| 0.1 * k as Real).collect();
    let values: Vec<Real> = times
        .iter()
        .map(|t| 1e-9 + 3e-12 * t + 1e-10 * (7.3 * t).sin())
        .collect();
    let mut acc = SeriesAccumulator::default();
    for (t, x) in times.iter().zip(&values) {
        acc.push(*t, *x);
    }
    let stats = acc.statistics();
    let n = values.len() as Real;
    let mean = values.iter().sum::<Real>() / n;
    let var = values.iter().map(|x| (x - mean).powi(2)).sum::<Real>() / (n - 1.0);
    let t_mean = times.iter().sum::<Real>() / n;
    let slope = times
        .iter()
        .zip(&values)
        .map(|(t, x)| (t - t_mean) * (x - mean))
        .sum::<Real>()
        / times.iter().map(|t| (t - t_mean).powi(2)).sum::<Real>();
    assert_eq!(stats.count, 1000);
    assert!((stats.mean - mean).abs() < 1e-14 * mean.abs());
    assert!((stats.standard_deviation - var.sqrt()).abs() < 1e-12 * var.sqrt());
    assert!((stats.standard_error - var.sqrt() / n.sqrt()).abs() < 1e-12 * var.sqrt());
    assert!((stats.slope - slope).abs() < 1e-12 * slope.abs());

    let mut linear = SeriesAccumulator::default();
    for t in &times {
        linear.push(*t, 2.0 - 0.5 * t);
    }
    assert!((linear.statistics().slope + 0.5).abs() < 1e-14);
}

/// The paper-point scene, RK4 dt = 0.1, t = 300: E0 = 2·½·0.2² − 1/7, J0 = 2·3.5·0.2 = 1.4;
/// the compensated sum of the per-step changes telescopes to E_N − E0.
#[test]
fn paper_point_conservation() {
    let (model, initial) = paper_point();
    let e0 = total_energy(&model, &initial).unwrap();
    assert!((e0 - (0.04 - 1.0 / 7.0)).abs() < 1e-16);
    let j0 = angular_momentum(&model, &initial);
    assert!((j0 - Vec3::new(0.0, 0.0, -1.4)).norm() < 1e-15);
    let mut monitor = ConservationMonitor::new(&model);
    let mut integrator = FixedStep::new(FixedScheme::RungeKutta4, 0.1).unwrap();
    let summary = integrator
        .integrate(&model, &initial, 0.0, 300.0, &mut |s| monitor.observe(s))
        .unwrap();
    assert_eq!(summary.steps, 3000);
    assert_eq!(summary.force_evaluations, 4 * 3000 + 1);
    let energy = monitor.energy().unwrap();
    let momentum = monitor.angular_momentum().unwrap();
    let e_last = total_energy(&model, &summary.last.state).unwrap();
    println!(
        "paper-point RK4 dt 0.1: ΔE mean {:.3e} σ {:.3e} s.e. {:.3e} slope {:.3e} max drift {:.3e}",
        energy.step_changes.mean,
        energy.step_changes.standard_deviation,
        energy.step_changes.standard_error,
        energy.step_changes.slope,
        energy.max_relative_drift
    );
    println!(
        "                         ΔJ mean {:.3e} σ {:.3e} s.e. {:.3e} slope {:.3e} max drift {:.3e}",
        momentum.step_changes.mean,
        momentum.step_changes.standard_deviation,
        momentum.step_changes.standard_error,
        momentum.step_changes.slope,
        momentum.max_relative_drift
    );
    assert_eq!(energy.step_changes.count, 3000);
    assert_eq!(energy.initial, e0);
    assert_eq!(energy.last, e_last);
    assert!((energy.step_changes.sum - (e_last - e0)).abs() < 1e-15);
    assert!((momentum.initial - 1.4).abs() < 1e-15);
    // RK4 does not conserve E exactly; at dt = 0.1 on this orbit the drift is small but non-zero.
    assert!(energy.max_relative_drift > 0.0 && energy.max_relative_drift < 1e-5);
    assert!(momentum.max_relative_drift < 1e-5);
}

/// Leapfrog conserves the angular momentum of a central force to round-off, step by step.
#[test]
fn leapfrog_conserves_angular_momentum() {
    let kepler = Kepler::new(0.5);
    let mut monitor = ConservationMonitor::new(&kepler.model);
    let mut integrator = FixedStep::new(FixedScheme::Leapfrog, kepler.period() / 200.0).unwrap();
    integrator
        .integrate(
            &kepler.model,
            &kepler.initial_state(),
            0.0,
            50.0 * kepler.period(),
            &mut |s| monitor.observe(s),
        )
        .unwrap();
    let momentum = monitor.angular_momentum().unwrap();
    let energy = monitor.energy().unwrap();
    println!(
        "leapfrog 50 orbits: max |ΔJ/J| {:.3e}, max |ΔE/E| {:.3e}, σ(ΔE) {:.3e}",
        momentum.max_relative_drift,
        energy.max_relative_drift,
        energy.step_changes.standard_deviation
    );
    assert!(momentum.max_relative_drift < 1e-13);
    assert!(energy.max_relative_drift < 1e-2);
}

/// The one-call run gives the same numbers as the separate monitors.
#[test]
fn run_with_diagnostics_gathers_everything() {
    let (model, initial) = paper_point();
    let mut integrator = FixedStep::new(FixedScheme::RungeKutta4, 0.1).unwrap();
    let mut count = 0;
    let report = surfgrav_dynamics::run_with_diagnostics(
        &mut integrator,
        &model,
        &initial,
        0.0,
        300.0,
        &mut |_| count += 1,
    )
    .unwrap();
    assert_eq!(count, 3001);
    assert_eq!(report.summary.steps, 3000);
    assert_eq!(report.energy.step_changes.count, 3000);
    assert!((report.orbit.radial_period.unwrap() - 47.6177).abs() < 5e-5);
    assert!((report.angular_momentum.initial - 1.4).abs() < 1e-15);
}
