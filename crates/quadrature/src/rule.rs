//! What every one-dimensional rule shares: an interval, nodes and weights.
//!
//! A rule $\\{(x_i, w_i)\\}\_{i=1}^{n}$ on $[a, b]$ approximates
//! $$\int_a^b f(x)\\,\mathrm dx \approx \sum\_{i=1}^{n} w_i\\, f(x_i).$$
//! The nodes and weights are computed once, by the rule's constructor, and stored as plain
//! slices, so that the same table serves every integrand (a body's surface-node table is built
//! from them once and reused for every force evaluation).

use crate::QuadratureError;
use std::f64::consts::TAU;
use thiserror::Error;

/// A finite interval $[a, b]$ with $a < b$ and a finite length $b - a$ (for a periodic rule: one
/// period $[a, a + P)$; for a surface: the range of one parameter). The workspace's one interval
/// type: `surfgrav_surfaces::Interval` is this one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    start: f64,
    end: f64,
}

/// Why [`Interval::new`] refused its ends (converts into [`QuadratureError::InvalidInterval`]).
#[derive(Debug, Clone, Copy, PartialEq, Error)]
#[error("an interval needs finite ends with start < end and a finite length end - start, got [{start}, {end}]")]
pub struct InvalidInterval {
    /// The start given.
    pub start: f64,
    /// The end given.
    pub end: f64,
}

impl From<InvalidInterval> for QuadratureError {
    fn from(error: InvalidInterval) -> Self {
        QuadratureError::InvalidInterval {
            lower: error.start,
            upper: error.end,
        }
    }
}

impl Interval {
    /// $[-1, 1]$, on which rules are usually tabulated.
    pub const SYMMETRIC_UNIT: Interval = Interval {
        start: -1.0,
        end: 1.0,
    };

    /// $[0, 1]$.
    pub const UNIT: Interval = Interval {
        start: 0.0,
        end: 1.0,
    };

    /// $[0, 2\pi]$, one turn of an azimuth.
    pub const FULL_TURN: Interval = Interval {
        start: 0.0,
        end: TAU,
    };

    /// The interval `[start, end]`.
    ///
    /// # Errors
    /// [`InvalidInterval`] unless both ends are finite, `start < end` and the length
    /// `end - start` is finite.
    pub fn new(start: f64, end: f64) -> Result<Self, InvalidInterval> {
        let valid = start.is_finite() && end.is_finite() && start < end;
        if valid && (end - start).is_finite() {
            Ok(Interval { start, end })
        } else {
            Err(InvalidInterval { start, end })
        }
    }

    /// The lower end $a$.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// The upper end $b$.
    pub fn end(&self) -> f64 {
        self.end
    }

    /// The length $b - a$ (positive and finite).
    pub fn length(&self) -> f64 {
        self.end - self.start
    }

    /// The midpoint $(a + b)/2$, computed without overflow.
    pub fn midpoint(&self) -> f64 {
        0.5 * self.start + 0.5 * self.end
    }

    /// Half the length, $(b - a)/2$.
    pub fn half_width(&self) -> f64 {
        0.5 * self.length()
    }

    /// Whether `x` lies in the closed interval $[a, b]$.
    pub fn contains(&self, x: f64) -> bool {
        self.start <= x && x <= self.end
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
