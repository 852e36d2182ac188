//! Gauss–Legendre nodes and weights against 25-digit mpmath values
//! (tests/reference/gauss_legendre.py → tests/reference/gauss_legendre.json).
//!
//! Run with `--nocapture` to see the worst error of each order in ULP.

mod common;

use common::{gauss_legendre_reference, ulp_distance};
use surfgrav_quadrature::tolerance::{GAUSS_LEGENDRE_NODE_ULP, GAUSS_LEGENDRE_WEIGHT_ULP};
use surfgrav_quadrature::GaussLegendre;

#[test]
fn nodes_and_weights_match_mpmath_within_a_few_ulp() {
    let reference = gauss_legendre_reference();
    let rules = reference.field("gauss_legendre").array();
    assert!(rules.len() >= 10, "reference file holds too few orders");
    let mut largest_order = 0;
    println!("order  worst node ULP  worst weight ULP");
    for rule in rules {
        let order = rule.field("order").as_usize();
        largest_order = largest_order.max(order);
        let reference_nodes = rule.field("nodes").f64_vec();
        let reference_weights = rule.field("weights").f64_vec();
        assert_eq!(reference_nodes.len(), order.div_ceil(2));
        let computed = GaussLegendre::standard(order).expect("valid order");
        let nodes = computed.standard_nodes();
        let weights = computed.standard_weights();
        assert_eq!(nodes.len(), order);
        // The non-negative half, increasing, is the tail of the computed (increasing) list.
        let offset = order / 2;
        let (mut worst_node, mut worst_weight) = (0.0_f64, 0.0_f64);
        for (i, (&x, &w)) in reference_nodes.iter().zip(&reference_weights).enumerate() {
            worst_node = worst_node.max(ulp_distance(nodes[offset + i], x));
            worst_weight = worst_weight.max(ulp_distance(weights[offset + i], w));
        }
        println!("{order:5}  {worst_node:14.2}  {worst_weight:16.2}");
        assert!(
            worst_node <= GAUSS_LEGENDRE_NODE_ULP,
            "order {order}: a node is {worst_node} ULP off"
        );
        assert!(
            worst_weight <= GAUSS_LEGENDRE_WEIGHT_ULP,
            "order {order}: a weight is {worst_weight} ULP off"
        );
    }
    assert!(largest_order >= 1000, "the reference must reach order 1000");
}

#[test]
fn rule_is_exactly_symmetric() {
    for order in [1, 2, 7, 64, 333, 1000] {
        let rule = GaussLegendre::standard(order).expect("valid order");
        let (nodes, weights) = (rule.standard_nodes(), rule.standard_weights());
        for i in 0..order {
            assert_eq!(nodes[i], -nodes[order - 1 - i], "order {order}, node {i}");
            assert_eq!(
                weights[i],
                weights[order - 1 - i],
                "order {order}, weight {i}"
            );
        }
        assert!(nodes.windows(2).all(|pair| pair[0] < pair[1]));
    }
}
