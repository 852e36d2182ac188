//! Contact events and failed runs: typed outcomes carrying the time.

use surfgrav_dynamics::{
    Adaptive, BodyState, CentralPair, DynamicsError, EmbeddedPair, FixedScheme, FixedStep,
    Integrator, InteractionError, PointMasses, Termination, TwoBodyState,
};
use surfgrav_potentials::{Real, Vec3};

/// Two unit masses at rest, separation `r0` along x.
fn at_rest(r0: Real) -> TwoBodyState {
    TwoBodyState::new(
        BodyState::new(Vec3::new(-0.5 * r0, 0.0, 0.0), Vec3::zeros()),
        BodyState::new(Vec3::new(0.5 * r0, 0.0, 0.0), Vec3::zeros()),
    )
}

/// Radial fall from rest at r0 under μ = G(m_A + m_B): the time to reach r is
/// $t = \sqrt{r_0^3/(2\mu)}\\,[\sqrt{x(1-x)} + \arccos\sqrt x]$, $x = r/r_0$.
fn fall_time(r0: Real, r: Real, mu: Real) -> Real {
    let x = r / r0;
    (r0 * r0 * r0 / (2.0 * mu)).sqrt() * ((x * (1.0 - x)).sqrt() + x.sqrt().acos())
}

/// Spheres of radius 0.5 (contact distance 1) falling from rest at separation 3.
#[test]
fn contact_is_located_in_time_and_place() {
    let model = CentralPair::new(1.0, 1.0, |r: Real| -1.0 / r, |r: Real| 1.0 / (r * r))
        .unwrap()
        .with_contact_distance(1.0)
        .unwrap();
    let expected = fall_time(3.0, 1.0, 2.0);
    for (mut integrator, tolerance) in [
        (
            Box::new(FixedStep::new(FixedScheme::RungeKutta4, 0.01).unwrap())
                as Box<dyn Integrator>,
            1e-8,
        ),
        (Box::new(Adaptive::new(1e-12, 1e-14).unwrap()), 1e-10),
        (Box::new(Adaptive::dop853(1e-12, 1e-14).unwrap()), 1e-10),
    ] {
        let mut last_seen = 0.0;
        let summary = integrator
            .integrate(&model, &at_rest(3.0), 0.0, 10.0, &mut |s| {
                last_seen = s.time
            })
            .unwrap();
        let Termination::Contact(event) = summary.termination.clone() else {
            panic!("{}: no contact reported", integrator.name());
        };
        println!(
            "{}: contact at t = {:.12} (exact {expected:.12}), separation {:.15}",
            integrator.name(),
            event.sample.time,
            event.separation
        );
        assert!((event.sample.time - expected).abs() < tolerance);
        assert!((event.separation - 1.0).abs() < 1e-12);
        assert_eq!(event.contact_distance, 1.0);
        assert!((event.direction - Vec3::x()).norm() < 1e-15);
        assert_eq!(last_seen, event.sample.time);
        assert_eq!(summary.last, event.sample);
    }
}

#[test]
fn overlap_at_start_is_an_error_at_the_start_time() {
    let model = CentralPair::new(1.0, 1.0, |r: Real| -1.0 / r, |r: Real| 1.0 / (r * r))
        .unwrap()
        .with_contact_distance(1.0)
        .unwrap();
    let mut integrator = FixedStep::new(FixedScheme::Leapfrog, 0.1).unwrap();
    let error = integrator
        .integrate(&model, &at_rest(0.5), 2.0, 3.0, &mut |_| {})
        .unwrap_err();
    assert!(matches!(
        error,
        DynamicsError::Interaction {
            time: 2.0,
            source: InteractionError::Overlap { .. }
        }
    ));
}

/// Point masses falling head-on (no contact distance): the adaptive step collapses near the
/// collision time $t_c = (\pi/2)\sqrt{r_0^3/(2\mu)}$ and the floor stops the run there.
#[test]
fn step_floor_reports_the_time() {
    let model = PointMasses::new(1.0, 1.0, 1.0).unwrap();
    let collision = fall_time(3.0, 0.0, 2.0);
    for pair in [EmbeddedPair::DormandPrince54, EmbeddedPair::Dop853] {
        let mut integrator = Adaptive::new(1e-10, 1e-12)
            .unwrap()
            .with_pair(pair)
            .with_min_step(1e-9)
            .unwrap();
        let error = integrator
            .integrate(&model, &at_rest(3.0), 0.0, 10.0, &mut |_| {})
            .unwrap_err();
        println!("{}: {error}", pair.name());
        let DynamicsError::StepSizeTooSmall {
            time,
            step,
            min_step,
        } = error
        else {
            panic!("expected a step-floor error, got {error:?}");
        };
        assert!(step < min_step);
        assert!((time - collision).abs() < 1e-4, "{time} vs {collision}");
    }
}

/// A force so strong the state overflows: a typed non-finite error with the time.
#[test]
fn non_finite_state_is_an_error() {
    let model = CentralPair::new(1.0, 1.0, |_r: Real| 0.0, |_r: Real| Real::MAX / 4.0).unwrap();
    let mut integrator = FixedStep::new(FixedScheme::Leapfrog, 0.5).unwrap();
    let error = integrator
        .integrate(&model, &at_rest(3.0), 0.0, 100.0, &mut |_| {})
        .unwrap_err();
    println!("{error}");
    match error {
        DynamicsError::NonFinite { time }
        | DynamicsError::Interaction {
            time,
            source: InteractionError::NotFinite { .. },
        } => assert!((0.0..100.0).contains(&time)),
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn invalid_parameters_are_rejected() {
    assert!(FixedStep::new(FixedScheme::RungeKutta4, 0.0).is_err());
    assert!(FixedStep::new(FixedScheme::RungeKutta4, Real::NAN).is_err());
    assert!(Adaptive::new(-1.0, 1e-12).is_err());
    assert!(Adaptive::new(1e-10, 1e-12)
        .unwrap()
        .with_min_step(-1.0)
        .is_err());
    let model = PointMasses::new(1.0, 1.0, 1.0).unwrap();
    let mut integrator = FixedStep::new(FixedScheme::RungeKutta4, 0.1).unwrap();
    assert!(integrator
        .integrate(&model, &at_rest(3.0), 1.0, 1.0, &mut |_| {})
        .is_err());
    assert!(PointMasses::new(0.0, 1.0, 1.0).is_none());
}

/// A grazing orbit: pericentre 1e-3 above the contact distance. Coarse steps overshoot into
/// overlap at intermediate stages; that is no contact, and the run must complete.
#[test]
fn grazing_orbit_is_not_a_contact() {
    let model = CentralPair::new(1.0, 1.0, |r: Real| -1.0 / r, |r: Real| 1.0 / (r * r))
        .unwrap()
        .with_contact_distance(1.0)
        .unwrap();
    // μ = 2, pericentre r_p = 1 + 1e-3, e = 0.8: start at apocentre r_a = r_p (1 + e)/(1 − e).
    let (rp, e, mu): (Real, Real, Real) = (1.0 + 1e-3, 0.8, 2.0);
    let a = rp / (1.0 - e);
    let ra = a * (1.0 + e);
    let va = (mu * (1.0 - e) / ra).sqrt();
    let initial = TwoBodyState::new(
        BodyState::new(
            Vec3::new(-0.5 * ra, 0.0, 0.0),
            Vec3::new(0.0, -0.5 * va, 0.0),
        ),
        BodyState::new(Vec3::new(0.5 * ra, 0.0, 0.0), Vec3::new(0.0, 0.5 * va, 0.0)),
    );
    let period = 2.0 * std::f64::consts::PI * (a * a * a / mu).sqrt();
    for (mut integrator, exact_evaluations) in [
        (
            Box::new(FixedStep::new(FixedScheme::RungeKutta4, period / 200.0).unwrap())
                as Box<dyn Integrator>,
            Some(4 * 200 + 1),
        ),
        (Box::new(Adaptive::new(1e-9, 1e-12).unwrap()), None),
        (Box::new(Adaptive::dop853(1e-9, 1e-12).unwrap()), None),
    ] {
        let mut closest = Real::INFINITY;
        let summary = integrator
            .integrate(&model, &initial, 0.0, period, &mut |s| {
                closest = closest.min(s.state.separation())
            })
            .unwrap();
        println!(
            "{}: {:?}, closest sample {closest:.9}, evaluations {} ({} rejected)",
            integrator.name(),
            summary.termination,
            summary.force_evaluations,
            summary.rejected_steps
        );
        assert_eq!(summary.termination, Termination::Completed);
        assert!(closest > 1.0);
        if let Some(n) = exact_evaluations {
            // The subdivision path was taken (more evaluations than plain steps).
            assert!(summary.force_evaluations > n);
        }
    }
}

/// A model that reports a torque is refused at the start with a clear message.
#[test]
fn torques_are_refused() {
    use surfgrav_dynamics::InteractionModel;
    use surfgrav_potentials::Pose;
    struct Twisting(PointMasses, Real);
    impl InteractionModel for Twisting {
        fn mass_a(&self) -> Real {
            self.0.mass_a()
        }
        fn mass_b(&self) -> Real {
            self.0.mass_b()
        }
        fn force_on_a(&self, a: &Pose, b: &Pose) -> Result<Vec3, InteractionError> {
            self.0.force_on_a(a, b)
        }
        fn potential_energy(&self, a: &Pose, b: &Pose) -> Result<Real, InteractionError> {
            self.0.potential_energy(a, b)
        }
        fn torques(&self, _a: &Pose, _b: &Pose) -> Result<Option<(Vec3, Vec3)>, InteractionError> {
            Ok(Some((Vec3::new(0.0, 0.0, self.1), Vec3::zeros())))
        }
    }
    let point = PointMasses::new(1.0, 1.0, 1.0).unwrap();
    let mut integrator = FixedStep::new(FixedScheme::RungeKutta4, 0.1).unwrap();
    // |F| r = 1/3 at separation 3: a torque of 1e-3 is refused, 1e-13 is round-off.
    let error = integrator
        .integrate(&Twisting(point, 1e-3), &at_rest(3.0), 0.0, 1.0, &mut |_| {})
        .unwrap_err();
    println!("{error}");
    assert!(matches!(
        error,
        DynamicsError::TorquesNotSupported { time: 0.0, .. }
    ));
    assert!(error.to_string().contains("inertia tensors"));
    assert!(integrator
        .integrate(
            &Twisting(point, 1e-13),
            &at_rest(3.0),
            0.0,
            1.0,
            &mut |_| {}
        )
        .is_ok());
}

/// Evenly spaced output stops at the contact: every emitted time is at or before the contact
/// time, every emitted state is clear of overlap (to the contact's round-off), for the default
/// (Hermite) path and DOP853's own dense output; a bad interval is a typed error.
#[test]
fn even_output_stops_at_contact() {
    let model = CentralPair::new(1.0, 1.0, |r: Real| -1.0 / r, |r: Real| 1.0 / (r * r))
        .unwrap()
        .with_contact_distance(1.0)
        .unwrap();
    let expected = fall_time(3.0, 1.0, 2.0);
    for mut integrator in [
        Box::new(FixedStep::new(FixedScheme::RungeKutta4, 0.01).unwrap()) as Box<dyn Integrator>,
        Box::new(Adaptive::dop853(1e-12, 1e-12).unwrap()),
    ] {
        let mut emitted: Vec<(Real, Real)> = Vec::new();
        let summary = integrator
            .integrate_with_output(
                &model,
                &at_rest(3.0),
                0.0,
                10.0,
                0.25,
                &mut |_| {},
                &mut |t, state| emitted.push((t, state.separation())),
            )
            .unwrap();
        let Termination::Contact(event) = summary.termination else {
            panic!("{}: no contact", integrator.name());
        };
        let (last_time, _) = *emitted.last().unwrap();
        println!(
            "{}: {} outputs, last at {last_time}, contact at {:.12}",
            integrator.name(),
            emitted.len(),
            event.sample.time
        );
        assert_eq!(emitted.len(), (expected / 0.25) as usize + 1);
        assert!(last_time <= event.sample.time);
        assert!(emitted.iter().all(|(_, r)| *r >= 1.0 - 1e-12));
        assert!(integrator
            .integrate_with_output(
                &model,
                &at_rest(3.0),
                0.0,
                1.0,
                0.0,
                &mut |_| {},
                &mut |_, _| {}
            )
            .is_err());
    }
}
