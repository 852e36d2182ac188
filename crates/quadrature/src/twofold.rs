//! Error-free transformations and a minimal double-double ("two-fold") number.
//!
//! Used while building rules, to evaluate recurrences and weight formulas to about twice
//! the working precision; [`two_sum`] is public (the potentials use it too). The products use Veltkamp's splitting (Dekker 1971), not a fused
//! multiply-add, so the results are the same on every target and need no CPU feature.
//!
//! - `two_sum(a, b) = (s, e)` with $s = \mathrm{fl}(a + b)$ and $a + b = s + e$ exactly (Knuth).
//! - `two_product(a, b) = (p, e)` with $p = \mathrm{fl}(ab)$ and $ab = p + e$ exactly, for
//!   $|a|, |b|$ far from overflow and underflow (the recurrences here stay within $10^{\pm 30}$).

/// $2^{27} + 1$: splits a double into two halves of at most 26 significant bits.
const SPLITTER: f64 = 134_217_729.0;

/// `a = high + low` with both halves of at most 26 significant bits.
#[inline(always)]
pub(crate) fn split(a: f64) -> (f64, f64) {
    let scaled = SPLITTER * a;
    let high = scaled - (scaled - a);
    (high, a - high)
}

/// Knuth's error-free sum: `(s, e)` with $s = \mathrm{fl}(a + b)$ and $a + b = s + e$ exactly
/// (for finite `a + b`; six additions, no branch, any magnitudes). The workspace's one copy.
///
/// ```
/// use surfgrav_quadrature::two_sum;
/// assert_eq!(two_sum(1.0, 1e-20), (1.0, 1e-20));
/// ```
#[inline(always)]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let sum = a + b;
    let b_virtual = sum - a;
    let a_virtual = sum - b_virtual;
    (sum, (a - a_virtual) + (b - b_virtual))
}

/// `(fl(a + b), error)` when $|a| \ge |b|$ or a is zero.
#[inline(always)]
fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let sum = a + b;
    (sum, b - (sum - a))
}

/// `(fl(a b), a b - fl(a b))`, exact, with `a` already split into `(a_high, a_low)`.
#[inline(always)]
pub(crate) fn two_product_split(a: f64, (a_high, a_low): (f64, f64), b: f64) -> (f64, f64) {
    let product = a * b;
    let (b_high, b_low) = split(b);
    let error = ((a_high * b_high - product) + a_high * b_low + a_low * b_high) + a_low * b_low;
    (product, error)
}

/// `(fl(m a), m a - fl(m a))`, exact, for an integer `m` with $|m| < 2^{26}$ (no need to split
/// it).
#[inline(always)]
pub(crate) fn two_product_small_integer(m: f64, a: f64) -> (f64, f64) {
    let product = m * a;
    let (a_high, a_low) = split(a);
    (product, (m * a_high - product) + m * a_low)
}

/// `(fl(a b), a b - fl(a b))`, exact.
#[inline(always)]
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    two_product_split(a, split(a), b)
}

/// An unevaluated sum `high + low` with `|low| <= ulp(high) / 2`: about 106 significant bits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TwoFold {
    pub(crate) high: f64,
    pub(crate) low: f64,
}

impl TwoFold {
    /// Normalises `high + low` (any magnitudes).
    pub(crate) fn new(high: f64, low: f64) -> Self {
        let (high, low) = two_sum(high, low);
        TwoFold { high, low }
    }

    pub(crate) fn from_f64(value: f64) -> Self {
        TwoFold {
            high: value,
            low: 0.0,
        }
    }

    /// The nearest double (to within one rounding).
    pub(crate) fn value(self) -> f64 {
        self.high + self.low
    }

    pub(crate) fn add(self, other: TwoFold) -> TwoFold {
        let (sum, error) = two_sum(self.high, other.high);
        let (high, low) = fast_two_sum(sum, error + self.low + other.low);
        TwoFold { high, low }
    }

    pub(crate) fn neg(self) -> TwoFold {
        TwoFold {
            high: -self.high,
            low: -self.low,
        }
    }

    pub(crate) fn sub(self, other: TwoFold) -> TwoFold {
        self.add(other.neg())
    }

    pub(crate) fn mul(self, other: TwoFold) -> TwoFold {
        let (product, error) = two_product(self.high, other.high);
        let error = error + (self.high * other.low + self.low * other.high);
        let (high, low) = fast_two_sum(product, error);
        TwoFold { high, low }
    }

    pub(crate) fn mul_f64(self, factor: f64) -> TwoFold {
        self.mul(TwoFold::from_f64(factor))
    }

    pub(crate) fn div(self, divisor: TwoFold) -> TwoFold {
        let first = self.high / divisor.high;
        let remainder = self.sub(divisor.mul_f64(first));
        let second = remainder.high / divisor.high;
        let remainder = remainder.sub(divisor.mul_f64(second));
        let third = remainder.high / divisor.high;
        let (high, low) = fast_two_sum(first, second);
        TwoFold::new(high, low + third)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_product_is_exact_on_a_known_case() {
        // (1 + 2^-30)^2 = 1 + 2^-29 + 2^-60: the last term is the rounding error.
        let a = 1.0 + 2f64.powi(-30);
        let (product, error) = two_product(a, a);
        assert_eq!(product, 1.0 + 2f64.powi(-29));
        assert_eq!(error, 2f64.powi(-60));
    }

    #[test]
    fn small_integer_product_is_exact() {
        let a = 1.0 + 2f64.powi(-52);
        let (product, error) = two_product_small_integer(3.0, a);
        assert_eq!(product, 3.0 + 4.0 * 2f64.powi(-52));
        assert_eq!(error, -(2f64.powi(-52)));
        assert_eq!(two_product(3.0, a), (product, error));
    }

    #[test]
    fn two_sum_recovers_the_lost_low_part() {
        let (sum, error) = two_sum(1.0, 1e-20);
        assert_eq!(sum, 1.0);
        assert_eq!(error, 1e-20);
    }

    #[test]
    fn division_reaches_twice_the_precision() {
        // 1/3 in two-fold, times 3, minus 1: residual far below one ULP of 1.
        let third = TwoFold::from_f64(1.0).div(TwoFold::from_f64(3.0));
        let residual = third.mul_f64(3.0).sub(TwoFold::from_f64(1.0));
        assert!(residual.value().abs() < 1e-31, "{residual:?}");
        assert!(third.low != 0.0);
    }
}
