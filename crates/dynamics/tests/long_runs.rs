//! Issue 6's long-run and conservation targets for the dynamics: the adaptive integrator's
//! energy error on paper-2s, Brouwer's law for its round-off, and bounded energy error of a
//! symplectic integrator over many radial periods of paper-2s. (The 1e5-orbit point-mass run is
//! `symplectic_energy_error_is_bounded_long` in tests/integrators.rs.)
//!
//! Slow variants are `#[ignore]`d; run them with
//! `cargo test --release -p surfgrav-dynamics --test long_runs -- --ignored --nocapture`.

mod common;

use common::{paper_2s, paper_2s_initial, Kepler};
use surfgrav_dynamics::tolerance::ENERGY_DRIFT_FACTOR;
use surfgrav_dynamics::{
    run_with_diagnostics, total_energy, Adaptive, BodyState, EmbeddedPair, FixedScheme, FixedStep,
    Integrator, TwoBodyState,
};
use surfgrav_potentials::{Real, Vec3};

/// Issue 6: the adaptive integrator keeps max |E − E0|/|E0| ≤ 1e-13 on paper-2s.
const PAPER_2S_ADAPTIVE_ENERGY: Real = 1e-13;

/// DOP853 at rtol = atol = 1e-15 over t = 300, with the tabulated V(r) and with the direct
/// surface integral (engine tolerance 1e-12) at every stage. Measured when written: table
/// 3.9e-14 (766 steps, 9,193 evaluations, 2 ms), direct 5.6e-14 (same steps, 0.3 s release);
/// at 1e-14 both are 5.8e-13 (truncation, ten times per decade of tolerance).
#[test]
fn paper_2s_adaptive_energy_error() {
    for interpolate in [true, false] {
        let model = paper_2s(interpolate);
        let mut integrator = Adaptive::dop853(1e-15, 1e-15).unwrap();
        let report = run_with_diagnostics(
            &mut integrator,
            &model,
            &paper_2s_initial(),
            0.0,
            300.0,
            &mut |_| {},
        )
        .unwrap();
        let drift = report.energy.max_relative_drift;
        println!(
            "paper-2s dop853 tol 1e-15, {}: max |dE/E| {drift:.2e}, {} steps, {} evaluations, ψ_p {:.6}°",
            if interpolate { "table" } else { "direct" },
            report.summary.steps,
            report.summary.force_evaluations,
            report.orbit.precession_angle_deg.unwrap()
        );
        assert!(drift <= PAPER_2S_ADAPTIVE_ENERGY, "{drift:e}");
        assert!((report.orbit.precession_angle_deg.unwrap() - 18.9638).abs() < 1e-4);
    }
}

/// Relative energy errors of `members` copies of a Kepler orbit (μ = 1, a = 1, eccentricity
/// `e`), each rotated by 0.1 rad more (the same orbit, different rounding), integrated by `pair`
/// at the fixed step period/`steps_per_orbit`, at the checkpoints 2^k orbits, k = 0..=`levels`.
/// Returns (orbits, root mean square over the members) per checkpoint.
fn kepler_energy_rms(
    pair: EmbeddedPair,
    e: Real,
    steps_per_orbit: usize,
    levels: u32,
    members: usize,
) -> Vec<(Real, Real)> {
    let kepler = Kepler::new(e);
    let h = kepler.period() / steps_per_orbit as Real;
    let mut sums = vec![0.0; levels as usize + 1];
    for m in 0..members {
        let (s, c) = (0.1 * m as Real).sin_cos();
        let rotate = |v: Vec3| Vec3::new(c * v.x - s * v.y, s * v.x + c * v.y, 0.0);
        let start = kepler.initial_state();
        let mut state = TwoBodyState::new(
            BodyState::new(rotate(start.body_a.position), rotate(start.body_a.velocity)),
            BodyState::new(rotate(start.body_b.position), rotate(start.body_b.velocity)),
        );
        let e0 = total_energy(&kepler.model, &state).unwrap();
        // A tolerance no step can fail and the step fixed at h: round-off, not the controller,
        // is what is measured (the truncation error at these steps is below 1e-17 per orbit).
        let mut integrator = Adaptive::new(1e3, 1e3)
            .unwrap()
            .with_pair(pair)
            .with_initial_step(h)
            .unwrap()
            .with_max_step(h)
            .unwrap();
        let mut done = 0.0;
        for (k, sum) in sums.iter_mut().enumerate() {
            let orbits = (1u64 << k) as Real;
            let summary = integrator
                .integrate(
                    &kepler.model,
                    &state,
                    0.0,
                    (orbits - done) * kepler.period(),
                    &mut |_| {},
                )
                .unwrap();
            state = summary.last.state;
            done = orbits;
            let error = (total_energy(&kepler.model, &state).unwrap() - e0) / e0;
            *sum += error * error / members as Real;
        }
    }
    sums.iter()
        .enumerate()
        .map(|(k, sum)| ((1u64 << k) as Real, sum.sqrt()))
        .collect()
}

/// Least-squares slope of log(rms) against log(orbits) over the checkpoints from `from` orbits.
fn growth_exponent(series: &[(Real, Real)], from: Real) -> Real {
    let points: Vec<(Real, Real)> = series
        .iter()
        .filter(|(t, _)| *t >= from)
        .map(|(t, r)| (t.ln(), r.ln()))
        .collect();
    let n = points.len() as Real;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    sxy / sxx
}

/// Brouwer's law: with the truncation error below round-off, the adaptive integrator's energy
/// error grows like √t (a random walk), not like t. DOP853, circular orbit, 200 steps per orbit,
/// 8 members, 1 to 512 orbits (10⁵ steps each): the fitted exponent of the rms over 8–512 orbits
/// is at most 0.75 (a linear drift gives 1; measured when written: 0.47, and 0.98 without the
/// coefficient correction described in the tableau module).
#[test]
fn brouwer_law_round_off_grows_like_sqrt_t() {
    let series = kepler_energy_rms(EmbeddedPair::Dop853, 0.0, 200, 9, 8);
    for (orbits, rms) in &series {
        println!("dop853 circular, {orbits:>5} orbits: rms |dE/E| {rms:.2e}");
    }
    let exponent = growth_exponent(&series, 8.0);
    println!("growth exponent over 8-512 orbits: {exponent:.3}");
    assert!(exponent <= BROUWER_EXPONENT, "{exponent}");
}

/// The largest fitted growth exponent accepted for round-off (√t gives 0.5; the rms of 8
/// members scatters by about ±25 %, which moves a fitted exponent over a factor 64 in time by
/// about ±0.1; a linear drift gives 1).
const BROUWER_EXPONENT: Real = 0.75;

/// The long version. DOP853: e = 0.5, 800 steps per orbit, 1 to 8192 orbits, 8 members
/// (measured when written: exponent 0.54, rms 7.8e-14 at 8192 orbits; 90 s optimised). DP5(4):
/// circular, 6000 steps per orbit, 1 to 64 orbits. DP5(4)'s truncation error stays below
/// round-off only at such small steps: on e = 0.5 at 6000 steps per orbit its energy error grows
/// linearly (8e-16 per orbit, the truncation of a 5th-order method), so that case says nothing
/// about round-off and is not run.
#[test]
#[ignore]
fn brouwer_law_long() {
    for (pair, e, steps, levels) in [
        (EmbeddedPair::Dop853, 0.5, 800, 13),
        (EmbeddedPair::DormandPrince54, 0.0, 6000, 6),
    ] {
        let series = kepler_energy_rms(pair, e, steps, levels, 8);
        for (orbits, rms) in &series {
            println!(
                "{} e = {e}, {orbits:>5} orbits: rms |dE/E| {rms:.2e}",
                pair.name()
            );
        }
        let exponent = growth_exponent(&series, 8.0);
        println!(
            "{}: growth exponent from 8 orbits: {exponent:.3}",
            pair.name()
        );
        assert!(exponent <= BROUWER_EXPONENT, "{exponent}");
    }
}

/// Largest |E − E0|/|E0| in the first and the last tenth of a paper-2s run of `periods` radial
/// periods (T_r ≈ 47.355) with Yoshida 4 at dt = 0.1 on the tabulated V(r).
fn paper_2s_symplectic(periods: Real) -> (Real, Real, usize) {
    let model = paper_2s(true);
    let t_end = periods * 47.354929;
    let e0 = total_energy(&model, &paper_2s_initial()).unwrap();
    let (mut first, mut last) = (0.0 as Real, 0.0 as Real);
    let mut integrator = FixedStep::new(FixedScheme::Yoshida4, 0.1).unwrap();
    let summary = integrator
        .integrate(&model, &paper_2s_initial(), 0.0, t_end, &mut |s| {
            let error = ((total_energy(&model, &s.state).unwrap() - e0) / e0).abs();
            if s.time <= 0.1 * t_end {
                first = first.max(error);
            } else if s.time >= 0.9 * t_end {
                last = last.max(error);
            }
        })
        .unwrap();
    (first, last, summary.force_evaluations)
}

/// Symplectic integration of paper-2s on the table: the energy error oscillates without drift
/// over 100 radial periods (the table is one analytic piece here, so the integrated system is
/// exactly Hamiltonian). Measured when written: 6.0e-7 in both tenths.
#[test]
fn paper_2s_symplectic_energy_is_bounded() {
    let (first, last, evaluations) = paper_2s_symplectic(100.0);
    println!("paper-2s yoshida4 dt 0.1, 100 T_r: max |dE/E| first tenth {first:.3e}, last {last:.3e}, {evaluations} evaluations");
    assert!(last <= ENERGY_DRIFT_FACTOR * first, "{first:e} -> {last:e}");
}

/// Issue 6: 1e4 radial periods of paper-2s (t ≈ 4.7e5, 4.7e6 steps, 1.4e7 evaluations).
/// Measured when written: 6.011e-7 in both tenths.
#[test]
#[ignore]
fn paper_2s_symplectic_energy_is_bounded_long() {
    let (first, last, evaluations) = paper_2s_symplectic(1e4);
    println!("paper-2s yoshida4 dt 0.1, 1e4 T_r: max |dE/E| first tenth {first:.3e}, last {last:.3e}, {evaluations} evaluations");
    assert!(last <= ENERGY_DRIFT_FACTOR * first, "{first:e} -> {last:e}");
}
