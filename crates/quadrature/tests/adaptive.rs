//! The adaptive integrator on integrands with known integrals: the requested tolerance is met,
//! the error estimate is never below the true error, failures are reported.

use std::f64::consts::PI;
use surfgrav_quadrature::tolerance::{
    ADAPTIVE_KINK_OPTIMISTIC_RUNS, ADAPTIVE_KINK_UNDERESTIMATE_FACTOR,
};
use surfgrav_quadrature::{
    AdaptiveCubature, AdaptiveEstimate, AdaptiveOptions, QuadratureError, Rectangle, Termination,
    EVALUATIONS_PER_RECTANGLE, MINIMUM_EVALUATION_BUDGET,
};

fn options(relative_tolerance: f64) -> AdaptiveOptions {
    AdaptiveOptions {
        relative_tolerance,
        absolute_tolerance: 0.0,
        max_evaluations: 2_000_000,
    }
}

fn unit_square() -> Rectangle {
    Rectangle::new(0.0, 1.0, 0.0, 1.0).expect("valid rectangle")
}

/// Checks an estimate against the exact values: converged, every component's true error within
/// its estimate, the largest true error within the requested tolerance (relative to the largest
/// component). Returns the worst ratio true error / estimate.
fn check<const N: usize>(
    name: &str,
    estimate: &AdaptiveEstimate<N>,
    exact: &[f64; N],
    relative_tolerance: f64,
) -> f64 {
    assert!(estimate.converged(), "{name}: {estimate:?}");
    let target = relative_tolerance * exact.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let mut worst_ratio = 0.0_f64;
    let components = estimate
        .value
        .iter()
        .zip(exact)
        .zip(&estimate.error_estimate);
    for (c, ((value, exact), error_estimate)) in components.enumerate() {
        let true_error = (value - exact).abs();
        assert!(
            true_error <= *error_estimate,
            "{name}, component {c}: true error {true_error:e} above its estimate {error_estimate:e}"
        );
        assert!(
            true_error <= target,
            "{name}, component {c}: true error {true_error:e} above the tolerance {target:e}"
        );
        worst_ratio = worst_ratio.max(true_error / error_estimate);
    }
    // The integrator's own criterion, relative to its computed value.
    let computed_target =
        relative_tolerance * estimate.value.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(
        estimate.error_norm() <= computed_target,
        "{name}: {estimate:?}"
    );
    assert_eq!(
        estimate.evaluations % (2 * EVALUATIONS_PER_RECTANGLE),
        EVALUATIONS_PER_RECTANGLE
    );
    println!(
        "{name:>34}: tol {relative_tolerance:.0e}, {:6} evaluations, {:4} rectangles, \
         estimate {:.1e}, true error / estimate <= {worst_ratio:.1e}",
        estimate.evaluations,
        estimate.rectangles,
        estimate.error_norm()
    );
    worst_ratio
}

const TOLERANCES: [f64; 3] = [1e-6, 1e-9, 1e-12];

#[test]
fn smooth_vector_integrand() {
    // Over [0, 1] × [-1, 2]: e^{u+2v}, cos(3u) v², and u v (which the rule integrates exactly).
    let rectangle = Rectangle::new(0.0, 1.0, -1.0, 2.0).expect("valid rectangle");
    let e = 1.0_f64.exp();
    let exact = [
        (e - 1.0) * (4.0_f64.exp() - (-2.0_f64).exp()) / 2.0,
        (3.0_f64.sin() / 3.0) * 3.0,
        0.5 * 1.5,
    ];
    for tolerance in TOLERANCES {
        let mut integrator = AdaptiveCubature::<3>::new(options(tolerance)).expect("valid");
        let estimate = integrator
            .integrate(rectangle, |u, v, values| {
                values[0] = (u + 2.0 * v).exp();
                values[1] = (3.0 * u).cos() * v * v;
                values[2] = u * v;
            })
            .expect("finite integrand");
        check(
            "smooth e^(u+2v), cos 3u v^2, u v",
            &estimate,
            &exact,
            tolerance,
        );
    }
}

#[test]
fn peaked_near_a_corner() {
    // 1/(c + u + v)² with c = 10⁻³: a peak of height 10⁶ at the corner (0, 0).
    let c = 1e-3_f64;
    let exact = [((c + 1.0) * (c + 1.0) / (c * (c + 2.0))).ln()];
    for tolerance in TOLERANCES {
        let mut integrator = AdaptiveCubature::<1>::new(options(tolerance)).expect("valid");
        let estimate = integrator
            .integrate(unit_square(), |u, v, values| {
                values[0] = (c + u + v).powi(-2);
            })
            .expect("finite integrand");
        check("corner peak 1/(c+u+v)^2", &estimate, &exact, tolerance);
    }
}

#[test]
fn lorentzian_peak_near_a_corner() {
    // 1/((u-u0)² + a²) · 1/((v-v0)² + a²), a = 0.01, centred at (0.02, 0.03).
    let (a, u0, v0) = (0.01_f64, 0.02_f64, 0.03_f64);
    let factor = |x0: f64| (((1.0 - x0) / a).atan() + (x0 / a).atan()) / a;
    let exact = [factor(u0) * factor(v0)];
    for tolerance in TOLERANCES {
        let mut integrator = AdaptiveCubature::<1>::new(options(tolerance)).expect("valid");
        let estimate = integrator
            .integrate(unit_square(), |u, v, values| {
                values[0] = 1.0 / (((u - u0).powi(2) + a * a) * ((v - v0).powi(2) + a * a));
            })
            .expect("finite integrand");
        check(
            "Lorentzian peak at (0.02, 0.03)",
            &estimate,
            &exact,
            tolerance,
        );
    }
}

#[test]
fn near_singular_kink_near_an_edge() {
    // 1/√((u-u0)² + ε) cos v and its smoothed kink √((u-u0)² + ε) cos v, u0 = 0.01, ε = 10⁻⁸.
    let (u0, epsilon) = (0.01_f64, 1e-8_f64);
    let root = epsilon.sqrt();
    let inverse = ((1.0 - u0) / root).asinh() + (u0 / root).asinh();
    let smooth_abs = |x: f64| 0.5 * (x * (x * x + epsilon).sqrt() + epsilon * (x / root).asinh());
    let kink = smooth_abs(1.0 - u0) - smooth_abs(-u0);
    let sine = 1.0_f64.sin();
    for tolerance in TOLERANCES {
        let mut integrator = AdaptiveCubature::<1>::new(options(tolerance)).expect("valid");
        let estimate = integrator
            .integrate(unit_square(), |u, v, values| {
                values[0] = v.cos() / ((u - u0).powi(2) + epsilon).sqrt();
            })
            .expect("finite integrand");
        check(
            "1/sqrt((u-u0)^2+eps) cos v",
            &estimate,
            &[inverse * sine],
            tolerance,
        );
        let estimate = integrator
            .integrate(unit_square(), |u, v, values| {
                values[0] = v.cos() * ((u - u0).powi(2) + epsilon).sqrt();
            })
            .expect("finite integrand");
        check(
            "sqrt((u-u0)^2+eps) cos v",
            &estimate,
            &[kink * sine],
            tolerance,
        );
    }
}

#[test]
fn oscillatory() {
    // 1 + cos(a u + b v + c) over the unit square, a = 60, b = 45 (about 10 and 7 periods): the
    // oscillating part must be resolved to the tolerance times the mean. (The oscillating part
    // alone integrates to 6.5e-4 of its ∫|f|, so a relative 1e-12 on it would ask for 6.5e-16 of
    // ∫|f|: below rounding, and reported as such by `tolerance_below_rounding_is_reported`.)
    let (a, b, c) = (60.0_f64, 45.0_f64, 0.5_f64);
    let oscillating = ((a + c).cos() + (b + c).cos() - (a + b + c).cos() - c.cos()) / (a * b);
    for tolerance in TOLERANCES {
        let mut integrator = AdaptiveCubature::<2>::new(options(tolerance)).expect("valid");
        let estimate = integrator
            .integrate(unit_square(), |u, v, values| {
                let wave = (a * u + b * v + c).cos();
                values[0] = 1.0 + wave;
                values[1] = 1.0 - wave;
            })
            .expect("finite integrand");
        let exact = [1.0 + oscillating, 1.0 - oscillating];
        check(
            "oscillatory 1 +- cos(60u+45v+0.5)",
            &estimate,
            &exact,
            tolerance,
        );
    }
}

#[test]
fn tolerance_below_rounding_is_reported() {
    // ∫∫ cos(60u + 45v + 0.5) = -6.5e-4 with ∫|f| = 0.64: a relative 1e-13 would need the sum of
    // 225-point rules to better than 50 ε ∫|f| per rectangle.
    let mut integrator = AdaptiveCubature::<1>::new(options(1e-13)).expect("valid");
    let estimate = integrator
        .integrate(unit_square(), |u, v, values| {
            values[0] = (60.0 * u + 45.0 * v + 0.5).cos();
        })
        .expect("finite integrand");
    println!("{estimate:?}");
    assert!(!estimate.converged());
    assert_eq!(estimate.termination, Termination::SubdivisionLimitReached);
}

/// Potential and field integrals of a unit sphere's surface seen from a point `r0` outside:
/// ∫ dA / |r - r0| = 4π/|r0| and ∫ (r0 - r)/|r0 - r|³ dA = 4π r0/|r0|³ (a shell acts as a
/// point), in the parametrisation u = φ ∈ [0, 2π], v = θ ∈ [0, π], dA = sin θ dφ dθ.
fn sphere_shell_integrand(r0: [f64; 3]) -> impl FnMut(f64, f64, &mut [f64; 4]) {
    move |phi, theta, values| {
        let (sin_theta, cos_theta) = theta.sin_cos();
        let (sin_phi, cos_phi) = phi.sin_cos();
        let r = [sin_theta * cos_phi, sin_theta * sin_phi, cos_theta];
        let d = [r0[0] - r[0], r0[1] - r[1], r0[2] - r[2]];
        let distance = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        values[0] = sin_theta / distance;
        let cube = sin_theta / (distance * distance * distance);
        for k in 0..3 {
            values[k + 1] = d[k] * cube;
        }
    }
}

fn sphere_shell_exact(r0: [f64; 3]) -> [f64; 4] {
    let distance = (r0[0] * r0[0] + r0[1] * r0[1] + r0[2] * r0[2]).sqrt();
    let cube = 4.0 * PI / distance.powi(3);
    [
        4.0 * PI / distance,
        r0[0] * cube,
        r0[1] * cube,
        r0[2] * cube,
    ]
}

#[test]
fn surface_integral_of_a_sphere_far_and_near() {
    let rectangle = Rectangle::new(0.0, 2.0 * PI, 0.0, PI).expect("valid rectangle");
    // |r0| = 2 (far), then 1.05 off-axis (close: a peak of width ~0.05 on the surface). The y
    // component of the field vanishes: it is held to the accuracy of the largest component.
    for r0 in [[1.2, 0.0, 1.6], [0.63, 0.0, 0.84]] {
        for tolerance in TOLERANCES {
            let mut integrator = AdaptiveCubature::<4>::new(options(tolerance)).expect("valid");
            let estimate = integrator
                .integrate(rectangle, sphere_shell_integrand(r0))
                .expect("finite integrand");
            check(
                "sphere shell potential and field",
                &estimate,
                &sphere_shell_exact(r0),
                tolerance,
            );
        }
    }
}

#[test]
fn evaluation_counts_are_stable() {
    // Snapshot of the work done, so that a change in the scheme shows. Update deliberately.
    let mut integrator = AdaptiveCubature::<1>::new(options(1e-10)).expect("valid");
    let polynomial = integrator
        .integrate(unit_square(), |u, v, values| {
            values[0] = u.powi(5) * v.powi(9)
        })
        .expect("finite");
    assert_eq!(polynomial.evaluations, 225);
    assert_eq!(polynomial.rectangles, 1);
    let peak = integrator
        .integrate(unit_square(), |u, v, values| {
            values[0] = (1e-3 + u + v).powi(-2)
        })
        .expect("finite");
    let mut shell = AdaptiveCubature::<4>::new(options(1e-10)).expect("valid");
    let rectangle = Rectangle::new(0.0, 2.0 * PI, 0.0, PI).expect("valid rectangle");
    let near = shell
        .integrate(rectangle, sphere_shell_integrand([0.63, 0.0, 0.84]))
        .expect("finite");
    println!(
        "snapshot: corner peak {} evaluations, near sphere {} evaluations",
        peak.evaluations, near.evaluations
    );
    assert_eq!(peak.evaluations, SNAPSHOT_CORNER_PEAK);
    assert_eq!(near.evaluations, SNAPSHOT_NEAR_SPHERE);
}

const SNAPSHOT_CORNER_PEAK: usize = 16_875;
const SNAPSHOT_NEAR_SPHERE: usize = 47_475;

#[test]
fn exhausted_budget_is_reported_with_an_honest_estimate() {
    let c = 1e-3_f64;
    let exact = ((c + 1.0) * (c + 1.0) / (c * (c + 2.0))).ln();
    let budget = 5 * EVALUATIONS_PER_RECTANGLE;
    let mut integrator = AdaptiveCubature::<1>::new(AdaptiveOptions {
        relative_tolerance: 1e-12,
        absolute_tolerance: 0.0,
        max_evaluations: budget,
    })
    .expect("valid");
    let estimate = integrator
        .integrate(unit_square(), |u, v, values| {
            values[0] = (c + u + v).powi(-2)
        })
        .expect("finite integrand");
    assert!(!estimate.converged());
    assert_eq!(estimate.termination, Termination::EvaluationBudgetExhausted);
    assert!(estimate.evaluations <= budget);
    assert!(estimate.error_norm() > 1e-12 * exact);
    assert!((estimate.value[0] - exact).abs() <= estimate.error_estimate[0]);
}

#[test]
fn non_integrable_singularity_is_not_reported_as_converged() {
    // 1/r² about an interior point (not a node) diverges logarithmically: the integrator must
    // give up and say so, not return a number as if converged.
    let mut integrator = AdaptiveCubature::<1>::new(AdaptiveOptions {
        max_evaluations: 200_000,
        ..options(1e-10)
    })
    .expect("valid");
    let estimate = integrator
        .integrate(unit_square(), |u, v, values| {
            values[0] = 1.0 / ((u - 1.0 / 3.0).powi(2) + (v - 1.0 / 3.0).powi(2));
        })
        .expect("finite at every node");
    assert!(!estimate.converged());
    assert_eq!(estimate.termination, Termination::EvaluationBudgetExhausted);
}

#[test]
fn jump_stops_at_the_subdivision_limit() {
    // A step along u = 1/3 (between nodes at every level): bisection along u shrinks the error
    // in proportion to the width, until the rectangle is too narrow to split.
    let mut integrator = AdaptiveCubature::<1>::new(options(1e-15)).expect("valid");
    let estimate = integrator
        .integrate(unit_square(), |u, _, values| {
            values[0] = if u < 1.0 / 3.0 { 1.0 } else { 0.0 };
        })
        .expect("finite integrand");
    println!("{estimate:?}");
    assert!(!estimate.converged());
    assert_eq!(estimate.termination, Termination::SubdivisionLimitReached);
    assert!((estimate.value[0] - 1.0 / 3.0).abs() <= estimate.error_estimate[0]);
}

#[test]
fn absolute_tolerance_alone_applies_to_a_vanishing_integral() {
    // ∫∫ sin(2π u) v = 0: a relative tolerance alone would be unreachable; an absolute one is met.
    let mut integrator = AdaptiveCubature::<1>::new(AdaptiveOptions {
        relative_tolerance: 0.0,
        absolute_tolerance: 1e-13,
        max_evaluations: 100_000,
    })
    .expect("valid");
    let estimate = integrator
        .integrate(unit_square(), |u, v, values| {
            values[0] = (2.0 * PI * u).sin() * v
        })
        .expect("finite integrand");
    assert!(estimate.converged());
    assert!(estimate.value[0].abs() <= 1e-13);
    assert!(estimate.value[0].abs() <= estimate.error_estimate[0]);
}

#[test]
fn non_finite_integrand_is_an_error() {
    let mut integrator = AdaptiveCubature::<2>::new(options(1e-8)).expect("valid");
    let result = integrator.integrate(unit_square(), |u, _, values| {
        values[0] = 1.0;
        values[1] = if u > 0.9 { f64::NAN } else { u };
    });
    match result {
        Err(QuadratureError::NonFiniteIntegrand { u, component, .. }) => {
            assert!(u > 0.9);
            assert_eq!(component, 1);
        }
        other => panic!("NaN not reported: {other:?}"),
    }
    let overflow = integrator.integrate(unit_square(), |_, _, values| {
        values[0] = f64::MAX;
        values[1] = 0.0;
    });
    assert_eq!(overflow, Err(QuadratureError::NonFiniteIntegral));
}

#[test]
fn invalid_options_are_rejected() {
    for (relative, absolute) in [
        (0.0, 0.0),
        (-1e-8, 0.0),
        (f64::NAN, 1e-8),
        (1e-8, f64::INFINITY),
    ] {
        let options = AdaptiveOptions {
            relative_tolerance: relative,
            absolute_tolerance: absolute,
            ..AdaptiveOptions::default()
        };
        assert!(matches!(
            AdaptiveCubature::<1>::new(options),
            Err(QuadratureError::InvalidTolerance { .. })
        ));
    }
    let small_budget = AdaptiveOptions {
        max_evaluations: MINIMUM_EVALUATION_BUDGET - 1,
        ..AdaptiveOptions::default()
    };
    assert!(matches!(
        AdaptiveCubature::<1>::new(small_budget),
        Err(QuadratureError::EvaluationBudgetTooSmall { .. })
    ));
    let mut integrator = AdaptiveCubature::<1>::new(AdaptiveOptions::default()).expect("valid");
    assert!(integrator.set_options(small_budget).is_err());
    assert_eq!(*integrator.options(), AdaptiveOptions::default());
}

#[test]
fn reusing_the_workspace_gives_identical_results() {
    let mut integrator = AdaptiveCubature::<1>::new(options(1e-10)).expect("valid");
    let peak = |u: f64, v: f64, values: &mut [f64; 1]| values[0] = (1e-3 + u + v).powi(-2);
    let first = integrator.integrate(unit_square(), peak).expect("finite");
    let other = integrator
        .integrate(unit_square(), |u, _, values| values[0] = u.exp())
        .expect("finite");
    let again = integrator.integrate(unit_square(), peak).expect("finite");
    assert_eq!(first, again);
    assert_ne!(first.value, other.value);
}

/// A reproducible uniform variate in [0, 1) (64-bit linear congruential generator).
fn uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*state >> 11) as f64 / (1_u64 << 53) as f64
}

/// Runs `cases` random integrations of f(u) cos v over the unit square, where `family` draws
/// (u0, ε) and returns the exact ∫₀¹ f and f; returns the number of optimistic estimates and
/// the worst ratio of true error to estimate among them. Converged runs must meet the tolerance
/// unless their estimate was optimistic.
fn stress(family: impl Fn(f64, f64) -> (f64, Box<dyn Fn(f64) -> f64>), seed: u64) -> (usize, f64) {
    let mut state = seed;
    let (mut optimistic, mut worst) = (0, 0.0_f64);
    for _ in 0..300 {
        let u0 = uniform(&mut state);
        let epsilon = 10f64.powf(-12.0 + 10.0 * uniform(&mut state));
        let tolerance = 10f64.powf(-12.0 + 7.0 * uniform(&mut state));
        let (exact_u, f) = family(u0, epsilon);
        let exact = exact_u * 1.0_f64.sin();
        let mut integrator = AdaptiveCubature::<1>::new(options(tolerance)).expect("valid");
        let estimate = integrator
            .integrate(unit_square(), |u, v, values| values[0] = f(u) * v.cos())
            .expect("finite integrand");
        assert!(estimate.converged(), "u0 {u0}, ε {epsilon}: {estimate:?}");
        let error = (estimate.value[0] - exact).abs();
        if error > estimate.error_estimate[0] {
            optimistic += 1;
            worst = worst.max(error / estimate.error_estimate[0]);
        } else {
            assert!(
                error <= tolerance * exact,
                "u0 {u0}, ε {epsilon}: {estimate:?}"
            );
        }
    }
    (optimistic, worst)
}

#[test]
fn random_near_singular_peaks_never_get_optimistic_estimates() {
    let inverse_root = |u0: f64, epsilon: f64| -> (f64, Box<dyn Fn(f64) -> f64>) {
        let root = epsilon.sqrt();
        let exact = ((1.0 - u0) / root).asinh() + (u0 / root).asinh();
        (
            exact,
            Box::new(move |u| 1.0 / ((u - u0).powi(2) + epsilon).sqrt()),
        )
    };
    let lorentzian = |u0: f64, epsilon: f64| -> (f64, Box<dyn Fn(f64) -> f64>) {
        let root = epsilon.sqrt();
        let exact = (((1.0 - u0) / root).atan() + (u0 / root).atan()) / root;
        (exact, Box::new(move |u| 1.0 / ((u - u0).powi(2) + epsilon)))
    };
    assert_eq!(stress(inverse_root, 1).0, 0);
    assert_eq!(stress(lorentzian, 2).0, 0);
}

#[test]
fn random_kinks_rarely_get_optimistic_estimates() {
    // The documented limit: a kink between the nodes can fool the rules, and a bisection that
    // does not reduce the error escapes the validation. Rare, and never by a large factor.
    let kink = |u0: f64, epsilon: f64| -> (f64, Box<dyn Fn(f64) -> f64>) {
        let root = epsilon.sqrt();
        let primitive =
            move |x: f64| 0.5 * (x * (x * x + epsilon).sqrt() + epsilon * (x / root).asinh());
        let exact = primitive(1.0 - u0) - primitive(-u0);
        (
            exact,
            Box::new(move |u| ((u - u0).powi(2) + epsilon).sqrt()),
        )
    };
    let (optimistic, worst) = stress(kink, 3);
    println!("kinks: {optimistic} optimistic estimates in 300, worst factor {worst:.2}");
    assert!(
        optimistic <= ADAPTIVE_KINK_OPTIMISTIC_RUNS && worst <= ADAPTIVE_KINK_UNDERESTIMATE_FACTOR,
        "{optimistic} optimistic, worst factor {worst}"
    );
}

#[test]
fn random_points_near_a_sphere_get_honest_estimates() {
    // The case surfgrav meets: a body's surface integral seen from a point 0.001 to 2 radii
    // above the surface, in any direction, at tolerances 1e-12 to 1e-6.
    let rectangle = Rectangle::new(0.0, 2.0 * PI, 0.0, PI).expect("valid rectangle");
    let mut state = 4;
    for _ in 0..100 {
        let distance = 1.0 + 10f64.powf(-3.0 + 3.3 * uniform(&mut state));
        let cos_theta = 2.0 * uniform(&mut state) - 1.0;
        let sin_theta = (1.0 - cos_theta * cos_theta).sqrt();
        let phi = 2.0 * PI * uniform(&mut state);
        let r0 = [
            distance * sin_theta * phi.cos(),
            distance * sin_theta * phi.sin(),
            distance * cos_theta,
        ];
        let tolerance = 10f64.powf(-12.0 + 6.0 * uniform(&mut state));
        let mut integrator = AdaptiveCubature::<4>::new(options(tolerance)).expect("valid");
        let estimate = integrator
            .integrate(rectangle, sphere_shell_integrand(r0))
            .expect("finite integrand");
        check(
            "random point near a sphere",
            &estimate,
            &sphere_shell_exact(r0),
            tolerance,
        );
    }
}
