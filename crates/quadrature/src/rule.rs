//! What every one-dimensional rule shares: an interval, nodes and weights.
//!
//! A rule $\\{(x_i, w_i)\\}\_{i=1}^{n}$ on $[a, b]$ approximates
//! $$\int_a^b f(x)\\,\mathrm dx \approx \sum\_{i=1}^{n} w_i\\, f(x_i).$$
//! The nodes and weights are computed once, by the rule's constructor, and stored as plain
//! slices, so that the same table serves every integrand (a body's surface-node table is built
//! from them once and reused for every force evaluation).

use crate::QuadratureError;

/// A finite interval $[a, b]$ with $a < b$ (for a periodic rule: one period $[a, a + P)$).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    lower: f64,
    upper: f64,
}

impl Interval {
    /// The interval $[-1, 1]$ on which rules are usually tabulated.
    pub const MINUS_ONE_TO_ONE: Interval = Interval {
        lower: -1.0,
        upper: 1.0,
    };

    /// The interval `[lower, upper]`.
    ///
    /// # Errors
    /// [`QuadratureError::InvalidInterval`] unless both bounds are finite, `lower < upper` and
    /// the width `upper - lower` is finite.
    pub fn new(lower: f64, upper: f64) -> Result<Self, QuadratureError> {
        let valid = lower.is_finite() && upper.is_finite() && lower < upper;
        if valid && (upper - lower).is_finite() {
            Ok(Interval { lower, upper })
        } else {
            Err(QuadratureError::InvalidInterval { lower, upper })
        }
    }

    /// The lower bound $a$.
    pub fn lower(&self) -> f64 {
        self.lower
    }

    /// The upper bound $b$.
    pub fn upper(&self) -> f64 {
        self.upper
    }

    /// The width $b - a$ (positive and finite).
    pub fn width(&self) -> f64 {
        self.upper - self.lower
    }

    /// The midpoint $(a + b)/2$, computed without overflow.
    pub fn midpoint(&self) -> f64 {
        0.5 * self.lower + 0.5 * self.upper
    }

    /// Half the width, $(b - a)/2$.
    pub fn half_width(&self) -> f64 {
        0.5 * self.width()
    }
}

/// A one-dimensional quadrature rule stored as data: nodes $x_i$ and weights $w_i$ on an interval.
///
/// Implementors guarantee `nodes().len() == weights().len() >= 1`, nodes in increasing order
/// inside the interval (for a periodic rule, in $[a, a + P)$), and finite weights.
pub trait Rule1D {
    /// The interval the rule integrates over.
    fn interval(&self) -> Interval;

    /// The nodes $x_i$, in increasing order.
    fn nodes(&self) -> &[f64];

    /// The weights $w_i$, one per node.
    fn weights(&self) -> &[f64];

    /// The number of nodes $n$.
    fn len(&self) -> usize {
        self.nodes().len()
    }

    /// Always `false`: a rule has at least one node.
    fn is_empty(&self) -> bool {
        self.nodes().is_empty()
    }

    /// $\sum_i w_i f(x_i)$.
    fn integrate<F: FnMut(f64) -> f64>(&self, mut integrand: F) -> f64
    where
        Self: Sized,
    {
        self.nodes()
            .iter()
            .zip(self.weights())
            .map(|(&x, &w)| w * integrand(x))
            .sum()
    }
}
