//! Tensor products of two one-dimensional rules on a rectangle.
//!
//! From a rule $\\{(u_i, w^u_i)\\}\_{i<n_u}$ on $[u_0, u_1]$ and a rule $\\{(v_j, w^v_j)\\}\_{j<n_v}$
//! on $[v_0, v_1]$,
//! $$\int\_{v_0}^{v_1}\\!\int\_{u_0}^{u_1} f(u, v)\\,\mathrm du\\,\mathrm dv \approx
//! \sum\_{j<n_v} \sum\_{i<n_u} w^u_i\\, w^v_j\\, f(u_i, v_j),$$
//! exact for $f = p(u)\\,q(v)$ whenever each factor is integrated exactly by its rule. The
//! $n_u n_v$ nodes $(u_i, v_j, w^u_i w^v_j)$ are built once and stored with $u$ varying fastest
//! (node $j n_u + i$), ready for a body to turn into its table of surface points and weighted
//! area vectors.

use crate::rule::{Interval, Rule1D};
use crate::QuadratureError;

/// An axis-aligned rectangle $[u_0, u_1] \times [v_0, v_1]$ in the parameter plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rectangle {
    /// The range of the first parameter.
    pub u: Interval,
    /// The range of the second parameter.
    pub v: Interval,
}

impl Rectangle {
    /// The rectangle `[u_lower, u_upper] × [v_lower, v_upper]`.
    ///
    /// # Errors
    /// [`QuadratureError::InvalidInterval`] if either range is invalid (see [`Interval::new`]).
    pub fn new(
        u_lower: f64,
        u_upper: f64,
        v_lower: f64,
        v_upper: f64,
    ) -> Result<Self, QuadratureError> {
        Ok(Rectangle {
            u: Interval::new(u_lower, u_upper)?,
            v: Interval::new(v_lower, v_upper)?,
        })
    }

    /// The area $(u_1 - u_0)(v_1 - v_0)$ in parameter units.
    pub fn area(&self) -> f64 {
        self.u.length() * self.v.length()
    }
}

/// One node of a two-dimensional rule: the point $(u, v)$ and its weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TensorNode {
    /// First parameter of the node.
    pub u: f64,
    /// Second parameter of the node.
    pub v: f64,
    /// The product weight $w^u_i w^v_j$.
    pub weight: f64,
}

/// The tensor product of two one-dimensional rules, stored as a flat node list.
#[derive(Debug, Clone, PartialEq)]
pub struct TensorProductRule {
    rectangle: Rectangle,
    u_points: usize,
    v_points: usize,
    nodes: Vec<TensorNode>,
}

impl TensorProductRule {
    /// The product of `u_rule` (first parameter) and `v_rule` (second parameter).
    pub fn new<U, V>(u_rule: &U, v_rule: &V) -> Self
    where
        U: Rule1D + ?Sized,
        V: Rule1D + ?Sized,
    {
        let mut nodes = Vec::with_capacity(u_rule.len() * v_rule.len());
        for (&v, &v_weight) in v_rule.nodes().iter().zip(v_rule.weights()) {
            for (&u, &u_weight) in u_rule.nodes().iter().zip(u_rule.weights()) {
                nodes.push(TensorNode {
                    u,
                    v,
                    weight: u_weight * v_weight,
                });
            }
        }
        TensorProductRule {
            rectangle: Rectangle {
                u: u_rule.interval(),
                v: v_rule.interval(),
            },
            u_points: u_rule.len(),
            v_points: v_rule.len(),
            nodes,
        }
    }

    /// The nodes, $u$ varying fastest: node `j * u_points + i` is $(u_i, v_j)$.
    pub fn nodes(&self) -> &[TensorNode] {
        &self.nodes
    }

    /// The rectangle the rule integrates over.
    pub fn rectangle(&self) -> Rectangle {
        self.rectangle
    }

    /// The number of nodes along $u$.
    pub fn u_points(&self) -> usize {
        self.u_points
    }

    /// The number of nodes along $v$.
    pub fn v_points(&self) -> usize {
        self.v_points
    }

    /// The total number of nodes $n_u n_v$.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Always `false`: both factors have at least one node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// $\sum w f(u, v)$ for a scalar integrand.
    pub fn integrate<F: FnMut(f64, f64) -> f64>(&self, mut integrand: F) -> f64 {
        self.nodes
            .iter()
            .map(|node| node.weight * integrand(node.u, node.v))
            .sum()
    }

    /// $\sum w \mathbf f(u, v)$ for an integrand with `N` components, which it writes into the
    /// array it is given (zeros on entry; all components from one evaluation, no allocation).
    pub fn integrate_components<const N: usize, F>(&self, mut integrand: F) -> [f64; N]
    where
        F: FnMut(f64, f64, &mut [f64; N]),
    {
        let mut total = [0.0; N];
        for node in &self.nodes {
            let mut values = [0.0; N];
            integrand(node.u, node.v, &mut values);
            for (sum, value) in total.iter_mut().zip(&values) {
                *sum += node.weight * value;
            }
        }
        total
    }
}
