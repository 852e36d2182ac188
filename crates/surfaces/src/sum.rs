//! Compensated (Kahan–Babuška–Neumaier) summation for node sums.
//!
//! A surface integral is a sum of $10^3$–$10^5$ terms that largely cancel (the force on a
//! distant body is a small difference of $\Phi\\,\mathbf W$ terms of size $|\Phi|\\,$area). Naive
//! summation leaves an error of about $\sqrt N\\,\epsilon\\,\sum_k|t_k|$ (measured: $2\times10^{-14}$
//! relative for the area of a sphere from 9216 nodes); the compensated sum carries the rounding
//! error of each addition in a second accumulator,
//!
//! $$ t = s + x,\qquad c \mathrel{+}= \begin{cases}(s - t) + x & |s| \ge |x|\\\\ (x - t) + s & \text{otherwise}\end{cases},
//!    \qquad s = t, $$
//!
//! and returns $s + c$, with an error of about $\epsilon\\,|\sum_k t_k| + N\epsilon^2\sum_k|t_k|$,
//! independent of $N$ in practice, for four extra floating-point operations per term.

use crate::{Real, Vec3};

/// A compensated running sum of reals.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CompensatedSum {
    sum: Real,
    compensation: Real,
}

impl CompensatedSum {
    /// An empty sum (zero).
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one term.
    #[inline]
    pub fn add(&mut self, x: Real) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.compensation += (self.sum - t) + x;
        } else {
            self.compensation += (x - t) + self.sum;
        }
        self.sum = t;
    }

    /// The sum so far.
    #[inline]
    pub fn value(&self) -> Real {
        self.sum + self.compensation
    }
}

impl FromIterator<Real> for CompensatedSum {
    fn from_iter<I: IntoIterator<Item = Real>>(iter: I) -> Self {
        let mut s = Self::new();
        iter.into_iter().for_each(|x| s.add(x));
        s
    }
}

/// A compensated running sum of 3-vectors (component by component).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CompensatedSum3 {
    components: [CompensatedSum; 3],
}

impl CompensatedSum3 {
    /// An empty sum (the zero vector).
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one term.
    #[inline]
    pub fn add(&mut self, x: &Vec3) {
        for (s, &xi) in self.components.iter_mut().zip(x.iter()) {
            s.add(xi);
        }
    }

    /// The sum so far.
    #[inline]
    pub fn value(&self) -> Vec3 {
        Vec3::new(
            self.components[0].value(),
            self.components[1].value(),
            self.components[2].value(),
        )
    }
}

impl FromIterator<Vec3> for CompensatedSum3 {
    fn from_iter<I: IntoIterator<Item = Vec3>>(iter: I) -> Self {
        let mut s = Self::new();
        iter.into_iter().for_each(|x| s.add(&x));
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_what_naive_summation_loses() {
        // 1 + 1e-16 · 10⁶: naive summation keeps 1 (each tiny term is rounded away); the exact
        // sum is 1 + 1e-10.
        let terms = std::iter::once(1.0).chain(std::iter::repeat_n(1e-16, 1_000_000));
        let naive: Real = terms.clone().sum();
        assert_eq!(naive, 1.0);
        let compensated: CompensatedSum = terms.collect();
        assert!((compensated.value() - (1.0 + 1e-10)).abs() <= Real::EPSILON);
        // Large cancelling terms: 1e16 + 1 − 1e16 = 1.
        let s: CompensatedSum = [1e16, 1.0, -1e16].into_iter().collect();
        assert_eq!(s.value(), 1.0);
        let v: CompensatedSum3 = [
            Vec3::new(1e16, 0.0, 1.0),
            Vec3::new(1.0, 2.0, 1e-20),
            Vec3::new(-1e16, 0.0, -1.0),
        ]
        .into_iter()
        .collect();
        assert_eq!(v.value(), Vec3::new(1.0, 2.0, 1e-20));
    }
}
