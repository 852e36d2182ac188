//! Closed-form gravitational fields of homogeneous bodies, including polyhedra (triangle
//! meshes of real asteroids, [`Polyhedron`]).
//!
//! # Conventions
//!
//! These hold for every type in this crate (the founding paper mixes signs; we do not):
//!
//! - **Potential** $\Phi(\mathbf r) = -G \int \rho\\, \mathrm dV' / |\mathbf r - \mathbf r'|$: negative,
//!   tending to $-GM/r$ far away (as in galpy, gala and REBOUND).
//! - **Acceleration** $\mathbf a = -\nabla\Phi$: the acceleration of a test particle, pointing toward
//!   the body.
//! - **G** is a parameter of each body, 1 by default (the paper's unit-less setting); any consistent
//!   unit system follows from the value the user gives (SI: `6.674_30e-11`).
//! - **Homogeneous bodies**: `mass` is the total mass; the density of a solid is mass / volume, the
//!   surface density of a disk is mass / (π R²).
//! - **Body frame**: centroid at the origin; a spheroid's symmetry axis and an ellipsoid's `c` axis
//!   along z; a disk in the x–y plane. Placing a body in the world is done once, by
//!   [`Pose`] and [`Potential::field_in_world`].
//!
//! Evaluation is total: every finite point gets a finite field, inside solids (the interior
//! quadratic potential) and through a disk's lamina alike. The one exception is a point mass
//! evaluated at its own position, documented on [`PointMass`].
//!
//! Numerical policy: every formula keeps full double precision (≤ 1e-14 relative in Φ,
//! ≤ 1e-13 in the acceleration, outside the body) over shapes from c/a = 1e-4 to 1e4, out to
//! 1e8 body radii and at SI magnitudes; the tests in `tests/` prove it against committed
//! high-precision reference values. A [`Polyhedron`] sums thousands of face terms and is held
//! to 1e-13 relative in Φ and the acceleration, from on its surface to 1e6 radii and inside
//! ([`tolerance::POLYHEDRON_REL`]; measured ≤ 3.3e-15 on the cube).

mod body;
mod error;
mod lanes;

pub mod carlson;
pub mod disk;
pub mod disk_pair;
pub mod ellipsoid;
pub mod elliptic;
pub mod inertia;
pub mod point_mass;
pub mod polyhedron;
pub mod sphere;
pub mod spheroid;
pub mod tolerance;

pub use body::{Field, Pose, PoseExt, Potential, Region, Symmetry, TypedPotential};
pub use disk::*;
pub use disk_pair::*;
pub use ellipsoid::*;
pub use error::BodyError;
pub use inertia::{InertiaError, InertiaTensor, Mat3};
pub use point_mass::*;
pub use polyhedron::{LengthUnit, Mesh, MeshError, Polyhedron, PolyhedronError, PrincipalFrame};
pub use sphere::*;
pub use spheroid::*;

/// The floating-point type of the framework.
pub type Real = f64;

/// A 3-vector in a body or world frame.
pub type Vec3 = nalgebra::Vector3<Real>;
