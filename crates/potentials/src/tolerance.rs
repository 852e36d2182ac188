//! The tolerance policy of the test suites, in one place.
//!
//! Every accuracy test in the workspace takes its tolerance from here, so that a loosened
//! tolerance shows in one diff. Each constant says why it has its value.

/// Relative error allowed in a potential Φ at any point outside a body, against a
/// high-precision reference (issue 2's requirement: about 45 ULP; the closed forms are built to
/// reach a few ULP, the margin covers the error of evaluating the reference point itself).
pub const POTENTIAL_REL: f64 = 1e-14;

/// Relative error allowed in the acceleration vector (norm of the error over norm of the
/// reference) outside a body. One order above Φ because the acceleration is a difference
/// quotient of κ-dependent terms near the sphere limit and near a disk's rim.
pub const ACCELERATION_REL: f64 = 1e-13;

/// Relative error allowed in the coplanar disk–disk force and energy (issue 2).
pub const DISK_PAIR_REL: f64 = 1e-14;

/// Relative agreement required between an analytic gradient and a fourth-order (Richardson)
/// central difference of step h = 1e-3 × the distance to the nearest singularity d: truncation
/// O((h/d)⁴) ≈ 1e-12, cancellation ≈ ε·|Φ|/h ≤ 5e-11 of |∇Φ| at the closest probes (d = r/21).
pub const FINITE_DIFFERENCE_REL: f64 = 1e-9;
