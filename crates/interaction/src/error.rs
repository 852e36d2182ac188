//! Why an interaction could not be computed.

use surfgrav_potentials::DiskPairError;
use surfgrav_quadrature::QuadratureError;
use surfgrav_surfaces::{NodeTableError, ShapeError};
use thiserror::Error;

/// Which of the two bodies of an interaction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// Body A (its centroid is the origin of the command-line tool's world frame).
    A,
    /// Body B.
    B,
}

impl Side {
    /// The other body.
    pub fn other(self) -> Side {
        match self {
            Side::A => Side::B,
            Side::B => Side::A,
        }
    }
}

impl std::fmt::Display for Side {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Side::A => "A",
            Side::B => "B",
        })
    }
}

/// Why an interaction could not be evaluated. Nothing is ever computed for overlapping or
/// touching bodies, and no NaN is ever returned in its place.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InteractionError {
    /// A pose has a NaN or infinite position component or rotation entry.
    #[error("the pose of body {body} has a non-finite {what}; give finite numbers")]
    NonFinitePose {
        /// The body whose pose is bad.
        body: Side,
        /// `"position"` or `"rotation"`.
        what: &'static str,
    },
    /// The bodies overlap: one's matter enters the other.
    #[error(
        "bodies A and B overlap (centroids {separation} apart); move them apart: the surface \
         integrals hold only for bodies whose matter is disjoint"
    )]
    Overlap {
        /// Distance between the centroids.
        separation: f64,
    },
    /// The bodies touch (to rounding): the integrands are singular at the contact point.
    #[error("bodies A and B touch (centroids {separation} apart); separate them by a finite gap")]
    Touching {
        /// Distance between the centroids.
        separation: f64,
    },
    /// The two bodies were built with different gravitational constants.
    #[error(
        "the bodies have different gravitational constants ({a} and {b}); build both with the \
         same G"
    )]
    GravitationalConstantMismatch {
        /// G of body A.
        a: f64,
        /// G of body B.
        b: f64,
    },
    /// A requested relative tolerance that is not in (0, 1).
    #[error("the relative tolerance must be a finite number in (0, 1), got {tolerance}")]
    InvalidTolerance {
        /// The rejected tolerance.
        tolerance: f64,
    },
    /// An evaluation budget too small to run the chosen method at all.
    #[error("the evaluation budget {max_evaluations} is too small; allow at least {minimum}")]
    BudgetTooSmall {
        /// The budget given.
        max_evaluations: usize,
        /// The least the method needs.
        minimum: usize,
    },
    /// The integration was asked to run over a body that has no surface (a point mass, or a
    /// body given only by its potential), or neither body has one.
    #[error("no surface to integrate over: {reason}")]
    NoSurface {
        /// What was asked for.
        reason: &'static str,
    },
    /// The requested tolerance was not met within the evaluation budget or the finest
    /// resolution level. The best result is attached, with its (larger) error estimate.
    #[error(
        "the requested relative tolerance {tolerance:e} was not met: error estimate \
         {error_estimate:e} after {evaluations} potential evaluations; relax the tolerance or \
         raise the evaluation budget"
    )]
    ToleranceNotMet {
        /// The tolerance asked for.
        tolerance: f64,
        /// The error estimate reached.
        error_estimate: f64,
        /// Potential evaluations spent.
        evaluations: usize,
        /// The best result obtained (its `error_estimate` exceeds the tolerance).
        best: Box<super::Interaction>,
    },
    /// A result component overflowed or was not finite although the inputs were.
    #[error("the interaction is not representable in these units ({what}); rescale the inputs")]
    NonFiniteResult {
        /// What overflowed.
        what: &'static str,
    },
    /// A shape derived from a body could not be built.
    #[error(transparent)]
    Shape(#[from] ShapeError),
    /// A node table could not be built.
    #[error(transparent)]
    NodeTable(#[from] NodeTableError),
    /// A quadrature rule could not be built or the adaptive integrator failed.
    #[error(transparent)]
    Quadrature(#[from] QuadratureError),
    /// The closed form for coplanar disks rejected its input.
    #[error(transparent)]
    DiskPair(#[from] DiskPairError),
}

impl From<surfgrav_quadrature::InvalidInterval> for InteractionError {
    fn from(error: surfgrav_quadrature::InvalidInterval) -> Self {
        InteractionError::NodeTable(error.into())
    }
}
