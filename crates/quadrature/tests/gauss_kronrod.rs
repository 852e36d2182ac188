//! The G7–K15 constants against the committed mpmath values, and their degrees of exactness.

mod common;

use common::gauss_legendre_reference;
use surfgrav_quadrature::gauss_kronrod::{GAUSS_7_WEIGHTS, KRONROD_15_NODES, KRONROD_15_WEIGHTS};
use surfgrav_quadrature::tolerance::CONVERGED_RULE_REL;
use surfgrav_quadrature::GaussLegendre;

#[test]
fn constants_are_the_nearest_doubles_to_the_reference() {
    let reference = gauss_legendre_reference();
    let pair = reference.field("kronrod_15");
    assert_eq!(pair.field("gauss_order").as_usize(), 7);
    // The file lists the non-negative half, increasing; the constants are the full rule.
    let nodes = pair.field("kronrod_nodes").f64_vec();
    let weights = pair.field("kronrod_weights").f64_vec();
    let gauss_weights = pair.field("gauss_weights").f64_vec();
    assert_eq!((nodes.len(), weights.len(), gauss_weights.len()), (8, 8, 4));
    for p in 0..8 {
        assert_eq!(KRONROD_15_NODES[7 + p], nodes[p], "node {p}");
        assert_eq!(KRONROD_15_NODES[7 - p], -nodes[p], "node -{p}");
        assert_eq!(KRONROD_15_WEIGHTS[7 + p], weights[p], "weight {p}");
        assert_eq!(KRONROD_15_WEIGHTS[7 - p], weights[p], "weight -{p}");
    }
    for p in 0..4 {
        assert_eq!(GAUSS_7_WEIGHTS[3 + p], gauss_weights[p]);
        assert_eq!(GAUSS_7_WEIGHTS[3 - p], gauss_weights[p]);
    }
}

#[test]
fn embedded_gauss_rule_is_the_seven_point_gauss_legendre_rule() {
    let gauss = GaussLegendre::standard(7).expect("valid order");
    for j in 0..7 {
        assert_eq!(KRONROD_15_NODES[2 * j + 1], gauss.standard_nodes()[j]);
        assert_eq!(GAUSS_7_WEIGHTS[j], gauss.standard_weights()[j]);
    }
}

/// Relative error of a rule on x^power over [-1, 1] (against ∫|x^power| = 2/(power+1)).
fn monomial_error(nodes: &[f64], weights: &[f64], power: i32) -> f64 {
    let computed: f64 = nodes
        .iter()
        .zip(weights)
        .map(|(x, w)| w * x.powi(power))
        .sum();
    let exact = if power % 2 == 1 {
        0.0
    } else {
        2.0 / (power as f64 + 1.0)
    };
    (computed - exact).abs() / (2.0 / (power as f64 + 1.0))
}

#[test]
fn kronrod_is_exact_to_degree_23_and_gauss_to_degree_13() {
    let gauss_nodes: Vec<f64> = (0..7).map(|j| KRONROD_15_NODES[2 * j + 1]).collect();
    for power in 0..=23 {
        let error = monomial_error(&KRONROD_15_NODES, &KRONROD_15_WEIGHTS, power);
        assert!(error <= CONVERGED_RULE_REL, "Kronrod, x^{power}: {error:e}");
    }
    for power in 0..=13 {
        let error = monomial_error(&gauss_nodes, &GAUSS_7_WEIGHTS, power);
        assert!(error <= CONVERGED_RULE_REL, "Gauss, x^{power}: {error:e}");
    }
    // And no further: the checks above can fail.
    assert!(monomial_error(&KRONROD_15_NODES, &KRONROD_15_WEIGHTS, 24) > 1e-9);
    assert!(monomial_error(&gauss_nodes, &GAUSS_7_WEIGHTS, 14) > 1e-6);
}
