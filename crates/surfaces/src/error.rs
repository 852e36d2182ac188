use thiserror::Error;

/// Why a shape (ellipsoid, lamina) could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ShapeError {
    /// A size that must be a positive finite number was zero or negative.
    #[error("{field} must be a positive finite number, got {value}")]
    NotPositive {
        /// The parameter's name as the user knows it (`polar_radius`, `radius`, ...).
        field: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A size was NaN or infinite.
    #[error("{field} must be finite, got {value}")]
    NotFinite {
        /// The parameter's name.
        field: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A derived quantity (volume, squared semi-axis, axis ratio) overflowed or underflowed.
    #[error("{what} is not representable for these sizes ({value}); rescale the units")]
    OutOfRange {
        /// What overflowed or underflowed.
        what: &'static str,
        /// The derived value.
        value: f64,
    },
}

/// Why a quadrature rule or a node table could not be built or transformed.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum NodeTableError {
    /// An interval whose ends are not finite or not increasing.
    #[error("an interval needs finite ends with start < end, got [{start}, {end}]")]
    InvalidInterval {
        /// Given start.
        start: f64,
        /// Given end.
        end: f64,
    },
    /// A rule without nodes.
    #[error("a quadrature rule needs at least one node")]
    EmptyRule,
    /// Node and weight slices of different lengths.
    #[error(
        "a quadrature rule needs one weight per node, got {nodes} nodes and {weights} weights"
    )]
    LengthMismatch {
        /// Number of nodes.
        nodes: usize,
        /// Number of weights.
        weights: usize,
    },
    /// A node or a weight that is NaN or infinite.
    #[error("{what} {index} of the quadrature rule is not finite ({value})")]
    NotFinite {
        /// `"node"` or `"weight"`.
        what: &'static str,
        /// Its position in the rule.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A node outside the interval the rule was declared on.
    #[error("node {index} = {node} lies outside the rule's interval [{start}, {end}]")]
    NodeOutsideInterval {
        /// Its position in the rule.
        index: usize,
        /// The node.
        node: f64,
        /// Interval start.
        start: f64,
        /// Interval end.
        end: f64,
    },
    /// The tensor product has more nodes than can be addressed.
    #[error("a {first} × {second} tensor rule has too many nodes")]
    TooManyNodes {
        /// Nodes of the first rule.
        first: usize,
        /// Nodes of the second rule.
        second: usize,
    },
    /// A rotation or offset with a NaN or infinite entry.
    #[error("the frame transformation has a non-finite entry; check the rotation and offset")]
    NonFiniteTransform,
    /// [`crate::SurfaceNodes::with_periodic_rule`] on a surface that does not have exactly one
    /// periodic direction.
    #[error("the surface is periodic in {periodicity:?}, not in exactly one direction; use SurfaceNodes::new with explicit u and v rules")]
    NotSinglyPeriodic {
        /// The surface's periodicity.
        periodicity: crate::Periodicity,
    },
}
