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

/// Relative error allowed in a polyhedron's Φ and acceleration (norm of the error over norm of
/// the reference), at any point from on the surface out to 1e6 body radii and inside (issue
/// 13's requirement). The field is a sum over thousands of faces whose terms cancel, so it
/// cannot reach the few-ulp accuracy of the smooth closed forms; the far-field expansion takes
/// over where the cancellation would exceed this ([`crate::polyhedron::FAR_FIELD_RADII`]).
pub const POLYHEDRON_REL: f64 = 1e-13;

/// Relative difference allowed between the field of a symmetric polyhedron at a point and at
/// its mirror image. The mirror permutes the faces, so the two sums round differently: each
/// face term carries ≈ ε of its own size and the terms partly cancel (measured at 1.1 body
/// sizes: worst 6e-16 on the cube, 1.2e-15 on an octahedron, 2.8e-15 on a 320-face ellipsoid
/// mesh), so 1e-14 covers it with a factor 3 to spare.
pub const POLYHEDRON_SYMMETRY_REL: f64 = 1e-14;
