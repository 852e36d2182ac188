//! Compensated summation for node sums: [`CompensatedSum`] is `surfgrav_quadrature`'s (re-exported
//! here, with the formula and its error bound in [`surfgrav_quadrature::sum`]);
//! [`CompensatedSum3`] applies it to each component of a 3-vector.

pub use surfgrav_quadrature::CompensatedSum;

use crate::Vec3;

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
    fn recovers_what_naive_summation_loses_in_each_component() {
        // Large cancelling terms: 1e16 + 1 − 1e16 = 1 in x, a tiny term kept beside 1 in z.
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
