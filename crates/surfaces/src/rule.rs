//! One-dimensional quadrature rules, borrowed from whoever built them.
//!
//! A [`BorrowedRule`] is a view of nodes $x_i$ and weights $w_i$ that integrate on a declared interval
//! $[p, q]$: $\int_p^q f(x)\\,\mathrm dx \approx \sum_i w_i f(x_i)$. The node-table builders map it
//! affinely onto the parameter interval $[t_0, t_1]$ they need,
//!
//! $$ t_i = t_0 + (x_i - p)\\,\frac{t_1 - t_0}{q - p}, \qquad
//!    W_i = w_i\\,\frac{t_1 - t_0}{q - p}, $$
//!
//! so one Gauss–Legendre rule on $[-1, 1]$ and one trapezoid rule on $[0, 1)$ serve every body.
//! This crate does not build rules itself (that is `surfgrav-quadrature`'s job); any rule works.
//!
//! Rule choice: in a periodic direction use the periodic trapezoid rule ($x_i = i/N$,
//! $w_i = 1/N$ on $[0, 1]$, the end point left out), which converges geometrically for smooth
//! periodic integrands; in the other direction use Gauss–Legendre.

use crate::{Interval, NodeTableError, Real};

/// A borrowed 1-D quadrature rule with the interval it integrates over. Validated on creation:
/// at least one node, one weight per node, everything finite, every node inside the interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BorrowedRule<'a> {
    nodes: &'a [Real],
    weights: &'a [Real],
    interval: Interval,
}

impl<'a> BorrowedRule<'a> {
    /// A rule integrating over `interval` with the given nodes and weights.
    pub fn new(
        nodes: &'a [Real],
        weights: &'a [Real],
        interval: Interval,
    ) -> Result<Self, NodeTableError> {
        if nodes.is_empty() {
            return Err(NodeTableError::EmptyRule);
        }
        if nodes.len() != weights.len() {
            return Err(NodeTableError::LengthMismatch {
                nodes: nodes.len(),
                weights: weights.len(),
            });
        }
        for (index, (&node, &weight)) in nodes.iter().zip(weights).enumerate() {
            if !node.is_finite() {
                return Err(NodeTableError::NotFinite {
                    what: "node",
                    index,
                    value: node,
                });
            }
            if !weight.is_finite() {
                return Err(NodeTableError::NotFinite {
                    what: "weight",
                    index,
                    value: weight,
                });
            }
            if !interval.contains(node) {
                return Err(NodeTableError::NodeOutsideInterval {
                    index,
                    node,
                    start: interval.start(),
                    end: interval.end(),
                });
            }
        }
        Ok(Self {
            nodes,
            weights,
            interval,
        })
    }

    /// The nodes, on [`BorrowedRule::interval`].
    pub fn nodes(&self) -> &'a [Real] {
        self.nodes
    }

    /// The weights, for [`BorrowedRule::interval`].
    pub fn weights(&self) -> &'a [Real] {
        self.weights
    }

    /// The interval the rule integrates over.
    pub fn interval(&self) -> Interval {
        self.interval
    }

    /// Number of nodes (at least one).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Always false: a validated rule has nodes. Present for API symmetry with slices.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The nodes and weights mapped affinely onto `target` (see the module docs). Nodes are
    /// clamped into `target` so rounding cannot push one past an end.
    pub fn mapped_to(&self, target: Interval) -> impl Iterator<Item = (Real, Real)> + 'a {
        let source = self.interval;
        // Ratio of lengths computed as a quotient of the two lengths; both are finite and
        // positive for validated intervals of moderate size.
        let scale = target.length() / source.length();
        let (p, t0, t1) = (source.start(), target.start(), target.end());
        self.nodes
            .iter()
            .zip(self.weights)
            .map(move |(&x, &w)| ((t0 + (x - p) * scale).clamp(t0, t1), w * scale))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_malformed_rules() {
        let i = Interval::UNIT;
        assert_eq!(
            BorrowedRule::new(&[], &[], i),
            Err(NodeTableError::EmptyRule)
        );
        assert_eq!(
            BorrowedRule::new(&[0.5], &[0.5, 0.5], i),
            Err(NodeTableError::LengthMismatch {
                nodes: 1,
                weights: 2
            })
        );
        assert!(matches!(
            BorrowedRule::new(&[0.5, f64::NAN], &[0.5, 0.5], i),
            Err(NodeTableError::NotFinite {
                what: "node",
                index: 1,
                ..
            })
        ));
        assert!(matches!(
            BorrowedRule::new(&[0.5], &[f64::INFINITY], i),
            Err(NodeTableError::NotFinite {
                what: "weight",
                index: 0,
                ..
            })
        ));
        assert!(matches!(
            BorrowedRule::new(&[0.5, 1.5], &[0.5, 0.5], i),
            Err(NodeTableError::NodeOutsideInterval { index: 1, .. })
        ));
    }

    #[test]
    fn rejects_bad_intervals() {
        for (a, b) in [
            (1.0, 1.0),
            (2.0, 1.0),
            (f64::NAN, 1.0),
            (0.0, f64::INFINITY),
        ] {
            assert!(matches!(
                Interval::new(a, b).map_err(NodeTableError::from),
                Err(NodeTableError::InvalidInterval { .. })
            ));
        }
    }

    #[test]
    fn mapping_preserves_exactness_for_cubics() {
        // Two-point Gauss–Legendre on [-1, 1] is exact for cubics; mapped onto [2, 5] it must
        // integrate x³ exactly: (5⁴ − 2⁴)/4 = 152.25.
        let x = 1.0 / 3.0_f64.sqrt();
        let nodes = [-x, x];
        let weights = [1.0, 1.0];
        let rule = BorrowedRule::new(&nodes, &weights, Interval::SYMMETRIC_UNIT).unwrap();
        let target = Interval::new(2.0, 5.0).unwrap();
        let integral: f64 = rule.mapped_to(target).map(|(t, w)| w * t.powi(3)).sum();
        assert!(
            (integral - 152.25).abs() <= crate::tolerance::POTENTIAL_REL * 152.25,
            "{integral}"
        );
        assert!(rule.mapped_to(target).all(|(t, _)| target.contains(t)));
    }
}
