use thiserror::Error;

/// Why a rule could not be built or an integration could not be carried out.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum QuadratureError {
    /// A rule was asked for zero nodes.
    #[error("a quadrature rule needs at least one node; ask for order (number of points) >= 1")]
    ZeroOrder,
    /// A Gauss–Legendre order above [`crate::MAX_GAUSS_LEGENDRE_ORDER`] was asked for.
    #[error(
        "Gauss-Legendre order {order} is above the supported maximum {maximum} (construction \
         costs O(order^2)); split the interval into panels of a lower order instead"
    )]
    OrderTooLarge {
        /// The order asked for.
        order: usize,
        /// The largest supported order.
        maximum: usize,
    },
    /// The bounds of an interval were not finite, not increasing, or spanned an overflowing width.
    #[error(
        "interval [{lower}, {upper}] is invalid: the bounds must be finite with lower < upper \
         and a finite width upper - lower"
    )]
    InvalidInterval {
        /// The lower bound given.
        lower: f64,
        /// The upper bound given.
        upper: f64,
    },
    /// A periodic rule was given a period that is not a positive finite number, or one too
    /// small next to its start for the nodes to be distinct floats.
    #[error(
        "the period must be a positive finite number, large enough next to the start for the \
         nodes to be distinct; got period {period} with start {start}"
    )]
    InvalidPeriod {
        /// The start of the period interval given.
        start: f64,
        /// The period given.
        period: f64,
    },
    /// The requested tolerances of an adaptive integration were negative, NaN or infinite, or
    /// both zero.
    #[error(
        "tolerances must be finite and non-negative with at least one of them positive, got \
         relative {relative}, absolute {absolute}"
    )]
    InvalidTolerance {
        /// The relative tolerance given.
        relative: f64,
        /// The absolute tolerance given.
        absolute: f64,
    },
    /// The evaluation budget of an adaptive integration cannot pay for the first rectangle and
    /// its halves.
    #[error(
        "the evaluation budget {max_evaluations} is below the minimum of {minimum} evaluations \
         (one rectangle and its two halves); raise max_evaluations"
    )]
    EvaluationBudgetTooSmall {
        /// The budget given.
        max_evaluations: usize,
        /// The smallest budget accepted.
        minimum: usize,
    },
    /// The integrand returned NaN or an infinity.
    #[error(
        "the integrand returned {value} in component {component} at (u, v) = ({u}, {v}); \
         integrable singularities must be removed by a change of variables before integrating"
    )]
    NonFiniteIntegrand {
        /// First coordinate of the offending point.
        u: f64,
        /// Second coordinate of the offending point.
        v: f64,
        /// Index of the offending component of the integrand.
        component: usize,
        /// The value returned.
        value: f64,
    },
    /// A nested rule was asked for an impossible family: an odd base for a half periodic rule,
    /// a Fejér base below 2, or too many levels.
    #[error(
        "nested rule with base {base} and {levels} levels is not available: a half periodic \
         rule needs an even base, a Fejer rule a base of at least 2, and at most {maximum} levels \
         (Fejer: at most 4096 subdivisions)"
    )]
    InvalidNesting {
        /// Level-0 size given.
        base: usize,
        /// Levels asked for.
        levels: usize,
        /// The largest number of levels.
        maximum: usize,
    },
    /// The integral or its error estimate overflowed although every integrand value was finite.
    #[error("the integral or its error estimate overflowed; rescale the integrand")]
    NonFiniteIntegral,
    /// Newton's method failed to converge to a Legendre root (a defect of this crate: please
    /// report the order).
    #[error("Newton's method did not converge to root {root_index} of the Legendre polynomial of order {order}")]
    LegendreRootNotConverged {
        /// The order of the rule.
        order: usize,
        /// The index of the root (counted from x = 1).
        root_index: usize,
    },
}
