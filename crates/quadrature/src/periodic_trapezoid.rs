//! The trapezoid rule for periodic integrands.
//!
//! For $f$ of period $P$, the $n$-point rule on one period $[a, a + P)$ is
//! $$\int_a^{a+P} f(x)\\,\mathrm dx \approx h \sum\_{j=0}^{n-1} f(a + jh), \qquad h = P/n.$$
//! It integrates every trigonometric polynomial $e^{2\pi i k x/P}$ with $|k| < n$ exactly
//! ($k = \pm n$ aliases to the constant), so for $f$ analytic in a strip
//! $|\operatorname{Im} x| < \sigma$ the error falls like $e^{-2\pi\sigma n/P}$ (Trefethen and
//! Weideman, SIAM Review 56, 2014): far faster than Gauss–Legendre for a smooth periodic
//! direction such as the azimuth of a body of revolution. For a non-periodic integrand it is only
//! first-order accurate: use [`crate::GaussLegendre`] there.

use crate::rule::{Interval, Rule1D};
use crate::QuadratureError;

/// The $n$-point periodic trapezoid rule on one period $[a, a + P)$: nodes $a + jP/n$, equal
/// weights $P/n$.
#[derive(Debug, Clone, PartialEq)]
pub struct PeriodicTrapezoid {
    interval: Interval,
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl PeriodicTrapezoid {
    /// The rule of `points` nodes on `[start, start + period)`.
    ///
    /// # Errors
    /// [`QuadratureError::ZeroOrder`] for `points == 0`, [`QuadratureError::InvalidPeriod`] for a
    /// period that is not positive and finite, or too small next to `start` for the nodes
    /// $a + jP/n$ to be distinct floats below $a + P$; [`QuadratureError::InvalidInterval`] when
    /// `start` is not finite or `start + period` does not exceed `start` in floating point.
    pub fn new(points: usize, start: f64, period: f64) -> Result<Self, QuadratureError> {
        if points == 0 {
            return Err(QuadratureError::ZeroOrder);
        }
        if !(period.is_finite() && period > 0.0) {
            return Err(QuadratureError::InvalidPeriod { start, period });
        }
        let interval = Interval::new(start, start + period)?;
        let step = period / points as f64;
        let nodes: Vec<f64> = (0..points).map(|j| start + j as f64 * step).collect();
        let distinct = nodes.windows(2).all(|pair| pair[0] < pair[1]);
        if !(distinct && nodes[points - 1] < interval.end()) {
            return Err(QuadratureError::InvalidPeriod { start, period });
        }
        let weights = vec![step; points];
        Ok(PeriodicTrapezoid {
            interval,
            nodes,
            weights,
        })
    }

    /// The number of points $n$.
    pub fn points(&self) -> usize {
        self.nodes.len()
    }

    /// The period $P$.
    pub fn period(&self) -> f64 {
        self.interval.length()
    }
}

impl Rule1D for PeriodicTrapezoid {
    fn interval(&self) -> Interval {
        self.interval
    }

    fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    fn weights(&self) -> &[f64] {
        &self.weights
    }
}
