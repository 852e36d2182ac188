//! Property tests: the rules' exactness on random polynomials and trigonometric polynomials,
//! and the adaptive integrator's tolerance on random smooth Gaussians.

use proptest::prelude::*;
use std::f64::consts::PI;
use surfgrav_quadrature::tolerance::CONVERGED_RULE_REL;
use surfgrav_quadrature::{
    AdaptiveCubature, AdaptiveOptions, GaussLegendre, PeriodicTrapezoid, Rectangle, Rule1D,
    TensorProductRule,
};

/// A polynomial in the scaled variable s = (x - m)/h of an interval, with its exact integral
/// h Σ_{k even} 2 c_k/(k+1) and the "absolute" polynomial Σ |c_k| |s|^k that measures the
/// rounding of its evaluation.
struct ScaledPolynomial<'a> {
    coefficients: &'a [f64],
    middle: f64,
    half_width: f64,
}

impl ScaledPolynomial<'_> {
    fn scaled(&self, x: f64) -> f64 {
        (x - self.middle) / self.half_width
    }

    fn value(&self, x: f64) -> f64 {
        let s = self.scaled(x);
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |sum, &c| sum * s + c)
    }

    fn absolute(&self, x: f64) -> f64 {
        let s = self.scaled(x).abs();
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |sum, &c| sum * s + c.abs())
    }

    fn exact_integral(&self) -> f64 {
        let sum: f64 = self
            .coefficients
            .iter()
            .enumerate()
            .filter(|(k, _)| k % 2 == 0)
            .map(|(k, &c)| 2.0 * c / (k as f64 + 1.0))
            .sum();
        self.half_width * sum
    }
}

fn polynomial_for<'a, R: Rule1D>(rule: &R, coefficients: &'a [f64]) -> ScaledPolynomial<'a> {
    ScaledPolynomial {
        coefficients,
        middle: rule.interval().midpoint(),
        half_width: rule.interval().half_width(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn gauss_legendre_is_exact_on_random_polynomials_of_degree_below_two_n(
        order in 1_usize..=40,
        lower in -10.0_f64..10.0,
        width in 0.01_f64..20.0,
        coefficients in prop::collection::vec(-1.0_f64..1.0, 80),
    ) {
        let rule = GaussLegendre::new(order, lower, lower + width).expect("valid rule");
        let polynomial = polynomial_for(&rule, &coefficients[..2 * order]);
        let computed = rule.integrate(|x| polynomial.value(x));
        let scale = rule.integrate(|x| polynomial.absolute(x));
        let error = (computed - polynomial.exact_integral()).abs();
        // Nodes are stored as absolute x, rounded to ε|x|; in the scaled variable that is
        // ε|x|/h, so a narrow interval far from 0 (width 0.01 at x = −10: ×2000) cannot be
        // integrated more accurately than this amplification allows, whatever the rule.
        let amplification = (lower.abs().max((lower + width).abs()) / (width / 2.0)).max(1.0);
        prop_assert!(error <= CONVERGED_RULE_REL * scale * amplification,
            "error {error:e}, scale {scale:e}, amplification {amplification:e}");
    }

    #[test]
    fn tensor_rule_is_exact_on_random_products_of_polynomials(
        u_order in 1_usize..=12,
        v_order in 1_usize..=12,
        u_lower in -3.0_f64..3.0,
        v_lower in -3.0_f64..3.0,
        u_width in 0.1_f64..5.0,
        v_width in 0.1_f64..5.0,
        u_coefficients in prop::collection::vec(-1.0_f64..1.0, 24),
        v_coefficients in prop::collection::vec(-1.0_f64..1.0, 24),
    ) {
        let u_rule = GaussLegendre::new(u_order, u_lower, u_lower + u_width).expect("valid");
        let v_rule = GaussLegendre::new(v_order, v_lower, v_lower + v_width).expect("valid");
        let p = polynomial_for(&u_rule, &u_coefficients[..2 * u_order]);
        let q = polynomial_for(&v_rule, &v_coefficients[..2 * v_order]);
        let tensor = TensorProductRule::new(&u_rule, &v_rule);
        let computed = tensor.integrate(|u, v| p.value(u) * q.value(v));
        let scale = tensor.integrate(|u, v| p.absolute(u) * q.absolute(v));
        let error = (computed - p.exact_integral() * q.exact_integral()).abs();
        prop_assert!(error <= CONVERGED_RULE_REL * scale, "error {error:e}, scale {scale:e}");
    }

    #[test]
    fn trapezoid_is_exact_on_random_trigonometric_polynomials_below_n(
        points in 1_usize..=16,
        start in -1.0_f64..1.0,
        period in 1.0_f64..8.0,
        cosines in prop::collection::vec(-1.0_f64..1.0, 16),
        sines in prop::collection::vec(-1.0_f64..1.0, 16),
    ) {
        // f(x) = Σ_{k<n} a_k cos(2πk(x - a)/P) + b_k sin(2πk(x - a)/P): integral P a_0.
        let rule = PeriodicTrapezoid::new(points, start, period).expect("valid rule");
        let f = |x: f64| {
            let phase = 2.0 * PI * (x - start) / period;
            (0..points)
                .map(|k| {
                    let k_phase = k as f64 * phase;
                    cosines[k] * k_phase.cos() + sines[k] * k_phase.sin()
                })
                .sum::<f64>()
        };
        let computed = rule.integrate(f);
        let scale = period * (0..points).map(|k| cosines[k].abs() + sines[k].abs()).sum::<f64>();
        let error = (computed - period * cosines[0]).abs();
        prop_assert!(error <= CONVERGED_RULE_REL * scale, "error {error:e}, scale {scale:e}");
    }
}

/// ∫_0^1 (g(u), (u - 1/2) g(u)) du for g(u) = exp(-(u - centre)²/(2σ²)), by a 200-point
/// Gauss–Legendre rule (checked against 300 points, so the reference is converged).
fn gaussian_moments(centre: f64, sigma: f64) -> [f64; 2] {
    let moments = |order: usize| {
        let rule = GaussLegendre::new(order, 0.0, 1.0).expect("valid rule");
        let g = |u: f64| (-(u - centre).powi(2) / (2.0 * sigma * sigma)).exp();
        [rule.integrate(g), rule.integrate(|u| (u - 0.5) * g(u))]
    };
    let (coarse, fine) = (moments(200), moments(300));
    for (a, b) in coarse.iter().zip(&fine) {
        assert!(
            (a - b).abs() <= CONVERGED_RULE_REL * coarse[0],
            "reference not converged"
        );
    }
    fine
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn adaptive_meets_the_tolerance_on_random_gaussians(
        u_centre in -0.2_f64..1.2,
        v_centre in -0.2_f64..1.2,
        u_sigma in 0.05_f64..1.0,
        v_sigma in 0.05_f64..1.0,
        log_tolerance in -12.0_f64..-6.0,
    ) {
        let tolerance = 10f64.powf(log_tolerance);
        let mut integrator = AdaptiveCubature::<3>::new(AdaptiveOptions {
            relative_tolerance: tolerance,
            absolute_tolerance: 0.0,
            max_evaluations: 1_000_000,
        })
        .expect("valid options");
        let square = Rectangle::new(0.0, 1.0, 0.0, 1.0).expect("valid rectangle");
        let estimate = integrator
            .integrate(square, |u, v, values| {
                let g = (-(u - u_centre).powi(2) / (2.0 * u_sigma * u_sigma)
                    - (v - v_centre).powi(2) / (2.0 * v_sigma * v_sigma))
                    .exp();
                values[0] = g;
                values[1] = (u - 0.5) * g;
                values[2] = 0.1;
            })
            .expect("finite integrand");
        let [u_zeroth, u_first] = gaussian_moments(u_centre, u_sigma);
        let [v_zeroth, _] = gaussian_moments(v_centre, v_sigma);
        let exact = [u_zeroth * v_zeroth, u_first * v_zeroth, 0.1];
        let target = tolerance * exact.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        prop_assert!(estimate.converged(), "{estimate:?}");
        let components = estimate.value.iter().zip(&exact).zip(&estimate.error_estimate);
        for (c, ((value, exact), error_estimate)) in components.enumerate() {
            let error = (value - exact).abs();
            prop_assert!(error <= target, "component {c}: error {error:e}, target {target:e}");
            prop_assert!(
                error <= *error_estimate,
                "component {c}: error {error:e} above estimate {error_estimate:e}"
            );
        }
    }
}
