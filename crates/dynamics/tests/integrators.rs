//! Integrators on the Kepler problem: orders of convergence, adaptive accuracy, symplectic
//! energy behaviour, time reversibility.

mod common;

use common::Kepler;
use surfgrav_dynamics::tolerance::{
    ENERGY_DRIFT_FACTOR, KEPLER_ADAPTIVE_POSITION, ORDER_OF_CONVERGENCE, REVERSIBILITY,
};
use surfgrav_dynamics::{Adaptive, FixedScheme, FixedStep, Integrator, Sample, Termination};
use surfgrav_potentials::Real;

fn run(integrator: &mut dyn Integrator, kepler: &Kepler, t_end: Real) -> Sample {
    let summary = integrator
        .integrate(
            &kepler.model,
            &kepler.initial_state(),
            0.0,
            t_end,
            &mut |_| {},
        )
        .unwrap();
    assert_eq!(summary.termination, Termination::Completed);
    assert_eq!(summary.last.time, t_end);
    summary.last
}

/// Error after one orbit of e = 0.5 with `steps` steps.
fn one_orbit_error(scheme: FixedScheme, steps: usize) -> Real {
    let kepler = Kepler::new(0.5);
    let mut integrator = FixedStep::new(scheme, kepler.period() / steps as Real).unwrap();
    let last = run(&mut integrator, &kepler, kepler.period());
    kepler.position_error(&last)
}

#[test]
fn fixed_step_orders_of_convergence() {
    for (scheme, steps) in [
        (FixedScheme::RungeKutta4, 400),
        (FixedScheme::Leapfrog, 2000),
        (FixedScheme::Yoshida4, 400),
        (FixedScheme::Yoshida6, 200),
        (FixedScheme::TripleJump8, 200),
    ] {
        let coarse = one_orbit_error(scheme, steps);
        let fine = one_orbit_error(scheme, 2 * steps);
        let order = (coarse / fine).log2();
        println!("{scheme:?}: N = {steps}: {coarse:.3e}, 2N: {fine:.3e}, order {order:.3}");
        assert!(
            (order - scheme.order() as Real).abs() < ORDER_OF_CONVERGENCE,
            "{scheme:?}: measured order {order}"
        );
    }
}

/// Adaptive DP5(4) at tight tolerance: position error after 10 orbits of e = 0.5 ≤ 1e-10.
#[test]
fn adaptive_kepler_ten_orbits() {
    let kepler = Kepler::new(0.5);
    let mut integrator = Adaptive::new(1e-14, 1e-16).unwrap();
    let t_end = 10.0 * kepler.period();
    let mut worst: Real = 0.0;
    let summary = integrator
        .integrate(
            &kepler.model,
            &kepler.initial_state(),
            0.0,
            t_end,
            &mut |s| {
                worst = worst.max(kepler.position_error(s));
            },
        )
        .unwrap();
    let final_error = kepler.position_error(&summary.last);
    println!(
        "dopri5 rtol 1e-14: final error {final_error:.3e}, worst {worst:.3e}, steps {}, rejected {}, evaluations {}",
        summary.steps, summary.rejected_steps, summary.force_evaluations
    );
    assert!(final_error <= KEPLER_ADAPTIVE_POSITION);
    assert!(worst <= KEPLER_ADAPTIVE_POSITION);
    // Snapshot of the step count, so a silent change of the controller shows.
    assert!(
        (12_000..15_000).contains(&summary.steps),
        "steps {}",
        summary.steps
    );
}

/// Relative energy error |E − E0|/|E0| at every sample of a run.
fn energy_errors(scheme: FixedScheme, steps_per_orbit: usize, orbits: usize) -> Vec<Real> {
    let kepler = Kepler::new(0.5);
    let mut integrator = FixedStep::new(scheme, kepler.period() / steps_per_orbit as Real).unwrap();
    let energy = |s: &Sample| {
        let v = s.state.relative_velocity();
        let r = s.state.relative_position();
        // Reduced mass 1/4, μ = 1: E = μ_red (v²/2 − 1/r).
        0.25 * (0.5 * v.norm_squared() - 1.0 / r.norm())
    };
    let mut errors = Vec::with_capacity(steps_per_orbit * orbits + 1);
    let mut e0 = None;
    integrator
        .integrate(
            &kepler.model,
            &kepler.initial_state(),
            0.0,
            orbits as Real * kepler.period(),
            &mut |s| {
                let e = energy(s);
                let e0 = *e0.get_or_insert(e);
                errors.push(((e - e0) / e0).abs());
            },
        )
        .unwrap();
    errors
}

/// Symplectic methods: the energy error oscillates without secular drift. Over 2000 orbits the
/// largest error in the last tenth of the run is no larger than 1.1× the largest in the first
/// tenth; RK4 at the same cost drifts (its last-tenth error is several times its first-tenth).
#[test]
fn symplectic_energy_error_is_bounded() {
    let orbits = 2000;
    let decile_max = |errors: &[Real], k: usize| {
        let n = errors.len() / 10;
        errors[k * n..(k + 1) * n]
            .iter()
            .cloned()
            .fold(0.0, Real::max)
    };
    for (scheme, steps) in [
        (FixedScheme::Leapfrog, 200),
        (FixedScheme::Yoshida4, 100),
        (FixedScheme::Yoshida6, 100),
    ] {
        let errors = energy_errors(scheme, steps, orbits);
        let (first, last) = (decile_max(&errors, 0), decile_max(&errors, 9));
        println!("{scheme:?}: max |dE/E| first tenth {first:.3e}, last tenth {last:.3e}");
        assert!(
            last <= ENERGY_DRIFT_FACTOR * first,
            "{scheme:?} drifts: {first:e} -> {last:e}"
        );
    }
    let errors = energy_errors(FixedScheme::RungeKutta4, 100, orbits);
    let (first, last) = (decile_max(&errors, 0), decile_max(&errors, 9));
    println!("RungeKutta4: max |dE/E| first tenth {first:.3e}, last tenth {last:.3e}");
    assert!(last > 5.0 * first);
}

/// The 1e5-orbit version of the drift test (10⁷ steps, about 2 s optimised; 80 MB of errors).
#[test]
#[ignore]
fn symplectic_energy_error_is_bounded_long() {
    let errors = energy_errors(FixedScheme::Leapfrog, 100, 100_000);
    let n = errors.len() / 10;
    let first = errors[..n].iter().cloned().fold(0.0, Real::max);
    let last = errors[9 * n..].iter().cloned().fold(0.0, Real::max);
    println!("leapfrog 1e5 orbits: first tenth {first:.3e}, last tenth {last:.3e}");
    assert!(last <= ENERGY_DRIFT_FACTOR * first);
}

/// Forward N steps, reverse the velocities, N steps again, reverse: back to the start to
/// round-off for the symmetric compositions (not for RK4).
#[test]
fn compositions_are_time_reversible() {
    let kepler = Kepler::new(0.5);
    let initial = kepler.initial_state();
    let t = 3.0 * kepler.period();
    let reverse = |s: &surfgrav_dynamics::TwoBodyState| {
        let mut r = *s;
        r.body_a.velocity = -r.body_a.velocity;
        r.body_b.velocity = -r.body_b.velocity;
        r
    };
    for scheme in [
        FixedScheme::Leapfrog,
        FixedScheme::Yoshida4,
        FixedScheme::Yoshida6,
        FixedScheme::TripleJump8,
        FixedScheme::RungeKutta4,
    ] {
        let mut integrator = FixedStep::new(scheme, kepler.period() / 64.0).unwrap();
        let there = integrator
            .integrate(&kepler.model, &initial, 0.0, t, &mut |_| {})
            .unwrap()
            .last;
        let back = integrator
            .integrate(&kepler.model, &reverse(&there.state), 0.0, t, &mut |_| {})
            .unwrap()
            .last;
        let returned = reverse(&back.state);
        let error = (returned.relative_position() - initial.relative_position()).norm()
            + (returned.relative_velocity() - initial.relative_velocity()).norm();
        println!("{scheme:?}: reversal error {error:.3e}");
        if scheme == FixedScheme::RungeKutta4 {
            assert!(error > 1e-6);
        } else {
            assert!(error < REVERSIBILITY, "{scheme:?}: {error:e}");
        }
    }
}

/// Evenly spaced output of the fixed-step methods and of DP5(4) is the quintic Hermite
/// interpolant of the samples they report: it equals [`EvenOutput`] fed with those samples, bit
/// for bit (the same output loop serves both), at every output time over two orbits.
#[test]
fn even_output_is_the_hermite_interpolant_of_the_samples() {
    use surfgrav_dynamics::interpolate::EvenOutput;
    use surfgrav_dynamics::TwoBodyState;
    let kepler = Kepler::new(0.5);
    let t_end = 2.0 * kepler.period();
    // An interval that is not a multiple of the step, so most output times fall inside steps.
    let interval = 0.037;
    let mut integrators: Vec<Box<dyn Integrator>> = [
        FixedScheme::RungeKutta4,
        FixedScheme::Leapfrog,
        FixedScheme::Yoshida4,
    ]
    .into_iter()
    .map(|scheme| Box::new(FixedStep::new(scheme, 0.01).unwrap()) as Box<dyn Integrator>)
    .collect();
    integrators.push(Box::new(Adaptive::new(1e-10, 1e-12).unwrap()));
    for integrator in &mut integrators {
        let mut reference = EvenOutput::new(interval).unwrap();
        let mut expected: Vec<(Real, TwoBodyState)> = Vec::new();
        let mut emitted: Vec<(Real, TwoBodyState)> = Vec::new();
        integrator
            .integrate_with_output(
                &kepler.model,
                &kepler.initial_state(),
                0.0,
                t_end,
                interval,
                &mut |sample| reference.observe(sample, &mut |t, s| expected.push((t, *s))),
                &mut |t, s| emitted.push((t, *s)),
            )
            .unwrap();
        assert_eq!(emitted.len(), (t_end / interval) as usize + 1);
        assert_eq!(emitted, expected, "{}", integrator.name());
    }
}
