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

/// Relative agreement required between an analytic gradient and a central finite difference of
/// step h = 1e-4 · scale with Richardson extrapolation (error O(h⁴) ≈ 1e-16 of the curvature
/// scale, plus cancellation ≈ ε·Φ/h ≈ 1e-12).
pub const FINITE_DIFFERENCE_REL: f64 = 1e-9;
