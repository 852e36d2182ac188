//! Interaction models: force = −∇_A V, Newton's third law via the integrator, typed errors.

mod common;

use common::Kepler;
use surfgrav_dynamics::interpolate::state_between;
use surfgrav_dynamics::tolerance::ORDER_OF_CONVERGENCE;
use surfgrav_dynamics::{
    CentralPair, FixedScheme, FixedStep, Integrator, InteractionError, InteractionModel,
    PointMasses, Sample,
};
use surfgrav_potentials::tolerance::FINITE_DIFFERENCE_REL;
use surfgrav_potentials::{Pose, PoseExt, Real, Vec3};

fn pose(x: Real, y: Real, z: Real) -> Pose {
    Pose::from(Vec3::new(x, y, z))
}

/// Fourth-order central difference of V with respect to A's position.
fn gradient_a(model: &dyn InteractionModel, a: &Pose, b: &Pose, h: Real) -> Vec3 {
    let mut g = Vec3::zeros();
    for i in 0..3 {
        let v = |s: Real| {
            let mut p = *a;
            p.translation.vector[i] += s * h;
            model.potential_energy(&p, b).unwrap()
        };
        g[i] = (-v(2.0) + 8.0 * v(1.0) - 8.0 * v(-1.0) + v(-2.0)) / (12.0 * h);
    }
    g
}

#[test]
fn force_is_minus_gradient_of_energy() {
    let point = PointMasses::new(2.0, 3.0, 0.7).unwrap();
    let pair = CentralPair::new(
        2.0,
        3.0,
        |r: Real| -1.0 / r - 0.1 / (r * r),
        |r: Real| 1.0 / (r * r) + 0.2 / (r * r * r),
    )
    .unwrap();
    let (a, b) = (pose(0.3, -1.0, 0.2), pose(-1.5, 1.1, 0.9));
    let d = (b.position() - a.position()).norm();
    for model in [&point as &dyn InteractionModel, &pair] {
        let force = model.force_on_a(&a, &b).unwrap();
        let fd = -gradient_a(model, &a, &b, 1e-3 * d);
        let rel = (force - fd).norm() / force.norm();
        assert!(rel < FINITE_DIFFERENCE_REL, "relative difference {rel:e}");
        // Attraction: the force on A points toward B.
        assert!(force.dot(&(b.position() - a.position())) > 0.0);
    }
    let expected = -0.7 * 6.0 / d;
    assert!((point.potential_energy(&a, &b).unwrap() - expected).abs() < 1e-15);
}

#[test]
fn model_errors_are_typed() {
    let point = PointMasses::new(1.0, 1.0, 1.0).unwrap();
    let here = pose(1.0, 2.0, 3.0);
    assert_eq!(
        point.force_on_a(&here, &here),
        Err(InteractionError::Coincident)
    );
    let pair = CentralPair::new(1.0, 1.0, |r: Real| -1.0 / r, |r: Real| 1.0 / (r * r))
        .unwrap()
        .with_contact_distance(2.0)
        .unwrap();
    assert!(matches!(
        pair.potential_energy(&pose(0.0, 0.0, 0.0), &pose(1.5, 0.0, 0.0)),
        Err(InteractionError::Overlap { .. })
    ));
    let nan = CentralPair::new(1.0, 1.0, |_r: Real| Real::NAN, |_r: Real| Real::NAN).unwrap();
    assert!(matches!(
        nan.force_on_a(&pose(0.0, 0.0, 0.0), &pose(1.5, 0.0, 0.0)),
        Err(InteractionError::NotFinite {
            quantity: "force",
            ..
        })
    ));
    assert!(CentralPair::new(-1.0, 1.0, |r: Real| r, |r: Real| r).is_none());
    assert!(pair.contact_distance(&here, &here) == Some(2.0));
    assert!(point.contact_distance(&here, &here).is_none());
}

/// Unequal masses: total momentum is conserved step by step (the force on B is −F_A) and the
/// centre of mass moves uniformly.
#[test]
fn momentum_is_conserved() {
    let model = PointMasses::new(1.0, 3.0, 1.0).unwrap();
    let kepler = Kepler::new(0.3);
    let mut initial = kepler.initial_state();
    initial.body_a.velocity += Vec3::new(0.1, 0.0, 0.05);
    let p0 = initial.body_a.velocity + 3.0 * initial.body_b.velocity;
    let mut worst: Real = 0.0;
    let mut integrator = FixedStep::new(FixedScheme::RungeKutta4, 0.01).unwrap();
    integrator
        .integrate(&model, &initial, 0.0, 20.0, &mut |s| {
            let p = s.state.body_a.velocity + 3.0 * s.state.body_b.velocity;
            worst = worst.max((p - p0).norm());
        })
        .unwrap();
    // Round-off only: 2000 steps of sums of O(1) terms.
    assert!(worst < 1e-13, "momentum change {worst:e}");
}

/// Dense output: between exact samples of the analytic Kepler orbit the quintic Hermite
/// interpolant has error O(h⁶): halving the step divides the mid-step error by about 64.
#[test]
fn dense_output_is_sixth_order() {
    let kepler = Kepler::new(0.5);
    let exact = |t: Real| {
        let (r, v) = kepler.relative(t);
        // Equal masses 0.5, μ = 1: r̈ = −r/|r|³, each body takes half with its sign.
        let a = -r / r.norm().powi(3);
        Sample {
            time: t,
            state: surfgrav_dynamics::TwoBodyState::new(
                surfgrav_dynamics::BodyState::new(-0.5 * r, -0.5 * v),
                surfgrav_dynamics::BodyState::new(0.5 * r, 0.5 * v),
            ),
            acceleration_a: -0.5 * a,
            acceleration_b: 0.5 * a,
        }
    };
    let error_at = |steps: usize| {
        let h = kepler.period() / steps as Real;
        let mut worst: Real = 0.0;
        for k in 0..steps {
            let (first, second) = (exact(k as Real * h), exact((k + 1) as Real * h));
            let t = (k as Real + 0.5) * h;
            let state = state_between(&first, &second, t);
            let (r, v) = kepler.relative(t);
            worst = worst.max((state.relative_position() - r).norm());
            worst = worst.max(h * (state.relative_velocity() - v).norm());
        }
        worst
    };
    let (coarse, fine) = (error_at(100), error_at(200));
    let order = (coarse / fine).log2();
    println!("dense output: {coarse:.3e} -> {fine:.3e}, order {order:.2}");
    assert!((order - 6.0).abs() < ORDER_OF_CONVERGENCE, "order {order}");
}

/// Evenly spaced output from an adaptive run lands on t0 + kΔ and follows the analytic orbit.
#[test]
fn even_output_from_adaptive_run() {
    use surfgrav_dynamics::interpolate::EvenOutput;
    use surfgrav_dynamics::Adaptive;
    let kepler = Kepler::new(0.5);
    let mut output = EvenOutput::new(0.25).unwrap();
    let mut times = Vec::new();
    let mut worst: Real = 0.0;
    let mut integrator = Adaptive::new(1e-12, 1e-14).unwrap();
    integrator
        .integrate(
            &kepler.model,
            &kepler.initial_state(),
            0.0,
            20.0,
            &mut |s| {
                output.observe(s, &mut |t, state| {
                    times.push(t);
                    worst = worst.max((state.relative_position() - kepler.relative(t).0).norm());
                })
            },
        )
        .unwrap();
    println!(
        "even output: {} points, worst error {worst:.3e}",
        times.len()
    );
    assert_eq!(times.len(), 81);
    for (k, t) in times.iter().enumerate() {
        assert_eq!(*t, 0.25 * k as Real);
    }
    assert!(worst < 1e-9);
    assert!(EvenOutput::new(0.0).is_none());
}
