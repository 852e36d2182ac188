//! Fixed rules: Gauss–Legendre, periodic trapezoid, tensor products.

use std::f64::consts::PI;
use surfgrav_quadrature::tolerance::{CONVERGED_RULE_REL, WEIGHT_SUM_REL};
use surfgrav_quadrature::{
    GaussLegendre, Interval, InvalidInterval, PeriodicTrapezoid, QuadratureError, Rule1D,
    TensorProductRule, MAX_GAUSS_LEGENDRE_ORDER,
};

/// $\int_a^b ((x - m)/h)^k\\,dx = h \cdot 2/(k+1)$ for even k, 0 for odd k.
fn scaled_monomial_integral(half_width: f64, power: usize) -> f64 {
    if power % 2 == 1 {
        0.0
    } else {
        half_width * 2.0 / (power as f64 + 1.0)
    }
}

/// Neumaier's compensated sum, so that the tests measure the rules' nodes and weights rather
/// than the rounding of a long plain sum.
fn accurate_sum(terms: impl IntoIterator<Item = f64>) -> f64 {
    let (mut sum, mut compensation) = (0.0_f64, 0.0_f64);
    for term in terms {
        let next = sum + term;
        compensation += if sum.abs() >= term.abs() {
            (sum - next) + term
        } else {
            (term - next) + sum
        };
        sum = next;
    }
    sum + compensation
}

/// Error of the rule on the scaled monomial ((x - m)/h)^k, relative to h (the size of ∫|f|).
fn monomial_error<R: Rule1D>(rule: &R, power: usize) -> f64 {
    let interval = rule.interval();
    let (middle, half) = (interval.midpoint(), interval.half_width());
    let terms = rule.nodes().iter().zip(rule.weights());
    let computed = accurate_sum(terms.map(|(&x, &w)| w * ((x - middle) / half).powi(power as i32)));
    (computed - scaled_monomial_integral(half, power)).abs() / half
}

#[test]
fn gauss_legendre_is_exact_to_degree_two_n_minus_one() {
    let mut worst = 0.0_f64;
    for order in [1, 2, 3, 4, 5, 8, 13, 20, 50, 100, 257] {
        let rule = GaussLegendre::new(order, -0.3, 2.1).expect("valid rule");
        for power in 0..2 * order {
            worst = worst.max(monomial_error(&rule, power));
        }
    }
    println!("worst relative error on degree <= 2n-1: {worst:.2e}");
    // The plain sum of Rule1D::integrate agrees to rounding.
    let rule = GaussLegendre::new(20, -0.3, 2.1).expect("valid rule");
    let plain = rule.integrate(|x| x * x);
    let exact = (2.1_f64.powi(3) + 0.3_f64.powi(3)) / 3.0;
    assert!(
        (plain - exact).abs() <= CONVERGED_RULE_REL * exact,
        "{plain}"
    );
    assert!(worst <= CONVERGED_RULE_REL, "{worst:e}");
}

#[test]
fn gauss_legendre_is_not_exact_at_degree_two_n() {
    // The test above can fail: degree 2n is integrated with an O(1) relative error for small n.
    for order in 1..=5 {
        let rule = GaussLegendre::new(order, -0.3, 2.1).expect("valid rule");
        let error = monomial_error(&rule, 2 * order);
        assert!(error > 1e-3, "order {order}: error {error:e}");
    }
}

#[test]
fn gauss_legendre_weights_sum_to_the_width() {
    for order in [1, 2, 7, 100, 1000, 3000] {
        for (lower, upper) in [(-1.0, 1.0), (0.0, PI), (-7.5, -2.25), (1e6, 1e6 + 3.0)] {
            let rule = GaussLegendre::new(order, lower, upper).expect("valid rule");
            let sum = accurate_sum(rule.weights().iter().copied());
            let width = upper - lower;
            assert!(
                (sum - width).abs() <= WEIGHT_SUM_REL * width,
                "order {order} on [{lower}, {upper}]: sum {sum}"
            );
            let nodes = rule.nodes();
            assert_eq!(nodes.len(), order);
            assert!(nodes.windows(2).all(|pair| pair[0] < pair[1]));
            assert!(nodes[0] > lower && nodes[order - 1] < upper);
        }
    }
}

#[test]
fn mapped_rule_equals_a_rule_built_on_the_interval() {
    let standard = GaussLegendre::standard(37).expect("valid rule");
    let interval = Interval::new(2.0, 5.5).expect("valid interval");
    let mapped = standard.mapped_to(interval);
    let direct = GaussLegendre::new(37, 2.0, 5.5).expect("valid rule");
    assert_eq!(mapped, direct);
    assert_eq!(mapped.interval(), interval);
    assert_eq!(mapped.order(), 37);
    assert_eq!(mapped.standard_nodes(), standard.standard_nodes());
    // Weights scale by the half width.
    assert_eq!(mapped.weights()[0], 1.75 * standard.weights()[0]);
}

#[test]
fn bad_orders_and_intervals_are_rejected() {
    assert_eq!(GaussLegendre::standard(0), Err(QuadratureError::ZeroOrder));
    assert!(matches!(
        GaussLegendre::standard(MAX_GAUSS_LEGENDRE_ORDER + 1),
        Err(QuadratureError::OrderTooLarge { .. })
    ));
    for (lower, upper) in [
        (1.0, 1.0),
        (2.0, 1.0),
        (f64::NAN, 1.0),
        (0.0, f64::INFINITY),
        (-f64::MAX, f64::MAX),
    ] {
        assert!(
            matches!(
                GaussLegendre::new(3, lower, upper),
                Err(QuadratureError::InvalidInterval { .. })
            ),
            "[{lower}, {upper}] accepted"
        );
    }
    assert_eq!(
        PeriodicTrapezoid::new(0, 0.0, 1.0),
        Err(QuadratureError::ZeroOrder)
    );
    for period in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            PeriodicTrapezoid::new(4, 0.0, period),
            Err(QuadratureError::InvalidPeriod { .. })
        ));
    }
    // A period lost in the rounding of start + period.
    assert!(matches!(
        PeriodicTrapezoid::new(4, 1e20, 1.0),
        Err(QuadratureError::InvalidInterval { .. })
    ));
    // A period so small next to the start that nodes would coincide (spacing 1e-3 at 1e15,
    // where doubles are 0.125 apart).
    assert!(matches!(
        PeriodicTrapezoid::new(1000, 1e15, 1.0),
        Err(QuadratureError::InvalidPeriod { .. })
    ));
    assert!(PeriodicTrapezoid::new(1000, 1e3, 1.0).is_ok());
    let message = GaussLegendre::new(3, 2.0, 1.0).unwrap_err().to_string();
    assert!(message.contains("lower < upper"), "{message}");
}

#[test]
fn interval_reports_its_geometry() {
    let interval = Interval::new(-2.0, 6.0).expect("valid interval");
    assert_eq!(
        (interval.start(), interval.end(), interval.length()),
        (-2.0, 6.0, 8.0)
    );
    assert_eq!((interval.midpoint(), interval.half_width()), (2.0, 4.0));
    // No overflow in the midpoint of a huge interval.
    let huge = Interval::new(1e308, 1.5e308).expect("valid interval");
    assert_eq!(huge.midpoint(), 1.25e308);
    assert_eq!(
        Interval::SYMMETRIC_UNIT,
        Interval::new(-1.0, 1.0).expect("valid")
    );
    assert_eq!(Interval::UNIT, Interval::new(0.0, 1.0).expect("valid"));
    assert_eq!(Interval::FULL_TURN.length(), std::f64::consts::TAU);
    // Closed at both ends.
    assert!(interval.contains(-2.0) && interval.contains(6.0) && !interval.contains(6.5));
    assert!(!interval.contains(f64::NAN));
    // A refused interval says which ends, and converts into the crate's error.
    let refused = Interval::new(2.0, 1.0).unwrap_err();
    assert_eq!(
        refused,
        InvalidInterval {
            start: 2.0,
            end: 1.0
        }
    );
    assert_eq!(
        QuadratureError::from(refused),
        QuadratureError::InvalidInterval {
            lower: 2.0,
            upper: 1.0
        }
    );
    // An overflowing length is refused.
    assert!(Interval::new(-f64::MAX, f64::MAX).is_err());
}

#[test]
fn high_order_rule_is_valid() {
    // Beyond the reference data: the largest orders still integrate polynomials exactly.
    let rule = GaussLegendre::new(4000, 0.0, 2.0).expect("valid rule");
    for power in [0, 1, 2, 101, 1000, 7999] {
        let error = monomial_error(&rule, power);
        assert!(error <= CONVERGED_RULE_REL, "power {power}: {error:e}");
    }
}

#[test]
fn trapezoid_integrates_trigonometric_polynomials_below_n_exactly() {
    let points = 9;
    let rule = PeriodicTrapezoid::new(points, -1.0, 2.0 * PI).expect("valid rule");
    assert_eq!(rule.points(), points);
    assert_eq!(rule.period(), 2.0 * PI);
    for k in 1..points {
        let k = k as f64;
        let cosine = rule.integrate(|x| (k * x).cos());
        let sine = rule.integrate(|x| (k * x).sin());
        assert!(cosine.abs() <= CONVERGED_RULE_REL, "cos {k}x: {cosine:e}");
        assert!(sine.abs() <= CONVERGED_RULE_REL, "sin {k}x: {sine:e}");
    }
    let constant = rule.integrate(|_| 1.0);
    assert!((constant - 2.0 * PI).abs() <= CONVERGED_RULE_REL * 2.0 * PI);
    // Aliasing: cos(n x) is seen as a constant, so the rule fails at k = n.
    let aliased = rule.integrate(|x| (points as f64 * x).cos());
    assert!(aliased.abs() > 1.0, "{aliased}");
}

/// $I_0(1) = \sum_k (1/4)^k / (k!)^2$.
fn bessel_i0_of_one() -> f64 {
    let mut term = 1.0;
    let mut sum = 1.0;
    for k in 1..30 {
        term *= 0.25 / (k as f64 * k as f64);
        sum += term;
    }
    sum
}

#[test]
fn trapezoid_converges_spectrally_for_a_smooth_periodic_integrand() {
    // ∫₀^{2π} e^{cos x} dx = 2π I₀(1); the error of the n-point rule is 4π I_n(1) + ...
    // ≈ 4π / (2^n n!): super-geometric.
    let exact = 2.0 * PI * bessel_i0_of_one();
    let errors: Vec<f64> = [2, 4, 6, 8, 16]
        .iter()
        .map(|&n| {
            let rule = PeriodicTrapezoid::new(n, 0.3, 2.0 * PI).expect("valid rule");
            (rule.integrate(|x| x.cos().exp()) - exact).abs() / exact
        })
        .collect();
    println!("relative errors for n = 2, 4, 6, 8, 16: {errors:?}");
    assert!(errors[0] > 1e-2, "n = 2 should still be inaccurate");
    assert!(errors[1] < 1e-2 && errors[2] < 1e-4 && errors[3] < 1e-6);
    assert!(errors[4] <= CONVERGED_RULE_REL);
    // Gauss-Legendre with the same 16 points on the period is far worse: the periodic rule's
    // advantage is real.
    let gauss = GaussLegendre::new(16, 0.3, 0.3 + 2.0 * PI).expect("valid rule");
    let gauss_error = (gauss.integrate(|x| x.cos().exp()) - exact).abs() / exact;
    assert!(gauss_error > 1e3 * errors[4], "{gauss_error:e}");
}

#[test]
fn tensor_rule_lists_nodes_with_u_fastest_and_integrates_products() {
    let u_rule = GaussLegendre::new(4, 0.0, 2.0).expect("valid rule");
    let v_rule = PeriodicTrapezoid::new(3, 0.0, 2.0 * PI).expect("valid rule");
    let tensor = TensorProductRule::new(&u_rule, &v_rule);
    assert_eq!(
        (tensor.u_points(), tensor.v_points(), tensor.len()),
        (4, 3, 12)
    );
    assert!(!tensor.is_empty());
    for j in 0..3 {
        for i in 0..4 {
            let node = tensor.nodes()[j * 4 + i];
            assert_eq!(node.u, u_rule.nodes()[i]);
            assert_eq!(node.v, v_rule.nodes()[j]);
            assert_eq!(node.weight, u_rule.weights()[i] * v_rule.weights()[j]);
        }
    }
    assert_eq!(tensor.rectangle().u, u_rule.interval());
    assert_eq!(tensor.rectangle().v, v_rule.interval());
    // ∫₀² u⁷ du ∫₀^{2π} (1 + cos v + sin² v) dv = 32 · 3π.
    let exact = 32.0 * 3.0 * PI;
    let computed = tensor.integrate(|u, v| u.powi(7) * (1.0 + v.cos() + v.sin().powi(2)));
    assert!(
        (computed - exact).abs() <= CONVERGED_RULE_REL * exact,
        "{computed}"
    );
    // The vector form gives the same numbers component by component.
    let components = tensor.integrate_components(|u, v, values: &mut [f64; 2]| {
        values[0] = u.powi(7) * (1.0 + v.cos() + v.sin().powi(2));
        values[1] = u;
    });
    assert_eq!(components[0], computed);
    assert!((components[1] - 2.0 * 2.0 * PI).abs() <= CONVERGED_RULE_REL * 4.0 * PI);
}

#[test]
fn tensor_rule_accepts_rules_behind_dyn() {
    let rules: Vec<Box<dyn Rule1D>> = vec![
        Box::new(PeriodicTrapezoid::new(16, 0.0, 2.0 * PI).expect("valid rule")),
        Box::new(GaussLegendre::new(12, 0.0, PI).expect("valid rule")),
    ];
    let tensor = TensorProductRule::new(rules[0].as_ref(), rules[1].as_ref());
    let area = tensor.integrate(|_, theta| theta.sin());
    assert!(
        (area - 4.0 * PI).abs() <= CONVERGED_RULE_REL * 4.0 * PI,
        "{area}"
    );
}
