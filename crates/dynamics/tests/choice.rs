//! Integrators chosen by name: names round-trip, unknown names list the valid ones, settings are
//! validated, and each built integrator is the one named.

mod common;

use common::Kepler;
use surfgrav_dynamics::{IntegratorChoiceError, IntegratorKind, Termination};
use surfgrav_potentials::Real;

#[test]
fn names_round_trip() {
    assert_eq!(IntegratorKind::ALL.len(), IntegratorKind::NAMES.len());
    for (kind, name) in IntegratorKind::ALL.into_iter().zip(IntegratorKind::NAMES) {
        assert_eq!(kind.to_string(), name);
        assert_eq!(name.parse::<IntegratorKind>().unwrap(), kind);
        let integrator = kind.build(0.01, 1e-10).unwrap();
        assert_eq!(integrator.name(), name);
    }
    assert_eq!(
        IntegratorKind::ALL.map(|k| k.is_adaptive()),
        [false, false, false, false, false, true, true]
    );
    assert_eq!(
        IntegratorKind::ALL.map(|k| k.order()),
        [4, 2, 4, 6, 8, 5, 8]
    );
}

#[test]
fn unknown_names_list_the_valid_ones() {
    for bad in ["", "RK4", "rk45", "dop", "yoshida8 ", "verner"] {
        let error = bad.parse::<IntegratorKind>().unwrap_err();
        assert_eq!(
            error,
            IntegratorChoiceError::UnknownName {
                name: bad.to_string()
            }
        );
        assert_eq!(
            error.to_string(),
            format!(
                "unknown integrator '{bad}'; valid names: rk4, leapfrog, yoshida4, yoshida6, yoshida8, dopri5, dop853"
            )
        );
    }
}

#[test]
fn settings_are_validated() {
    for bad in [0.0, -0.1, Real::NAN, Real::INFINITY, -Real::INFINITY] {
        for kind in IntegratorKind::ALL {
            // The setting a kind uses is checked; the other one is ignored.
            if kind.is_adaptive() {
                assert!(matches!(
                    kind.build(0.1, bad),
                    Err(IntegratorChoiceError::InvalidTolerance { .. })
                ));
                assert!(kind.build(bad, 1e-10).is_ok());
            } else {
                assert!(matches!(
                    kind.build(bad, 1e-10),
                    Err(IntegratorChoiceError::InvalidStep { .. })
                ));
                assert!(kind.build(0.1, bad).is_ok());
            }
        }
    }
    let message = IntegratorKind::Rk4
        .build(-1.0, 1e-10)
        .err()
        .unwrap()
        .to_string();
    assert_eq!(
        message,
        "the step of integrator 'rk4' must be positive and finite, got -1; give a positive step \
         in time units (e.g. 0.1, the paper's RK4 step)"
    );
}

/// Tolerances below what double precision can meet, and not below 1, are refused up front with
/// the allowed range in the message (1e-300 used to fail only at t = 0 with a non-finite
/// state).
#[test]
fn unreachable_tolerances_are_refused() {
    let min = IntegratorKind::MIN_TOLERANCE;
    for kind in [IntegratorKind::Dopri5, IntegratorKind::Dop853] {
        for bad in [
            1e-300,
            Real::MIN_POSITIVE,
            1e-16,
            min * (1.0 - 1e-15),
            1.0,
            2.0,
        ] {
            let error = kind.build(0.1, bad).err().unwrap();
            assert_eq!(
                error,
                IntegratorChoiceError::InvalidTolerance { kind, value: bad }
            );
            let message = error.to_string();
            assert!(message.contains("must be in [1e-15, 1)"), "{message}");
            assert!(message.contains("use a tolerance from 1e-15"), "{message}");
        }
        assert!(kind.build(0.1, min).is_ok());
        assert!(kind.build(0.1, 0.5).is_ok());
    }
    assert_eq!(
        IntegratorKind::Dop853
            .build(0.1, 1e-300)
            .err()
            .unwrap()
            .to_string(),
        "the tolerance of integrator 'dop853' must be in [1e-15, 1), got 1e-300; below 1e-15 \
         double-precision rounding of the state is as large as the error asked for, so the step \
         control cannot meet it: use a tolerance from 1e-15 (tightest) to 1e-6 (loose)"
    );
}

/// The smallest allowed tolerance works: both adaptive kinds complete one Kepler orbit at
/// e = 0, 0.5 and 0.9 with the position error of a tight run (measured 3e-15 … 1.8e-13; bound
/// 1e-12, 5–300 times that) and a step count of the order of tolerance 1e-14's (measured
/// ≤ 2 442 steps, bound 5 000; a controller chasing rounding would take far more).
#[test]
fn smallest_tolerance_works_on_kepler() {
    for e in [0.0, 0.5, 0.9] {
        let kepler = Kepler::new(e);
        for kind in [IntegratorKind::Dopri5, IntegratorKind::Dop853] {
            let mut integrator = kind
                .build(Real::NAN, IntegratorKind::MIN_TOLERANCE)
                .unwrap();
            let summary = integrator
                .integrate(
                    &kepler.model,
                    &kepler.initial_state(),
                    0.0,
                    kepler.period(),
                    &mut |_| {},
                )
                .unwrap();
            let error = kepler.position_error(&summary.last);
            println!(
                "e = {e}, {kind}: error {error:.2e}, {} steps",
                summary.steps
            );
            assert_eq!(summary.termination, Termination::Completed);
            assert!(error < 1e-12, "e = {e}, {kind}: {error:e}");
            assert!(summary.steps < 5000, "e = {e}, {kind}: {}", summary.steps);
        }
    }
}

/// Every built integrator integrates one Kepler orbit (e = 0.5) to the accuracy its order and
/// setting give: fixed steps of 2π/2000, tolerance 1e-10.
#[test]
fn every_kind_integrates_kepler() {
    let kepler = Kepler::new(0.5);
    for kind in IntegratorKind::ALL {
        let mut integrator = kind.build(kepler.period() / 2000.0, 1e-10).unwrap();
        let summary = integrator
            .integrate(
                &kepler.model,
                &kepler.initial_state(),
                0.0,
                kepler.period(),
                &mut |_| {},
            )
            .unwrap();
        assert_eq!(summary.termination, Termination::Completed);
        let error = kepler.position_error(&summary.last);
        println!(
            "{kind}: error {error:.2e}, {} steps, {} evaluations",
            summary.steps, summary.force_evaluations
        );
        // Leapfrog at 2000 steps per orbit: 4.4e-4 (order 2); the others are below 2.2e-8.
        assert!(error < 1e-3, "{kind}: {error:e}");
        if kind != IntegratorKind::Leapfrog {
            assert!(error < 1e-6, "{kind}: {error:e}");
        }
    }
}
