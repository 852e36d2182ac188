//! Closed surfaces parametrised over a rectangle, and their outward area vectors.
//!
//! A [`Surface`] maps a parameter rectangle $[u_0, u_1] \times [v_0, v_1]$ onto a closed surface in
//! the body frame, $\mathbf r(u, v)$, and gives the **area vector per unit parameter area**
//!
//! $$ \mathbf S(u, v) = \frac{\partial \mathbf r}{\partial u} \times \frac{\partial \mathbf r}{\partial v}, $$
//!
//! with the order of $u$ and $v$ chosen by each parametrisation so that $\mathbf S$ points
//! **out of** the enclosed volume. Hence, for any integrand $f$,
//!
//! $$ \oint f\\, \mathrm d\mathbf S = \int\_{v_0}^{v_1}\\!\int\_{u_0}^{u_1} f(\mathbf r(u, v))\\,
//!    \mathbf S(u, v)\\, \mathrm du\\, \mathrm dv , $$
//!
//! and a tensor quadrature rule turns it into the weighted sum that a
//! [`SurfaceNodes`](crate::SurfaceNodes) table precomputes.
//!
//! Units: $\mathbf r$ has the unit of length of the shape's sizes; $\mathbf S$ has length² per
//! unit of $u$ and $v$ (for example length per radian for the azimuth–height form, whose $v$ is
//! itself a length).
//!
//! Where a parametrisation degenerates (a pole, where a whole row of parameters maps to one point)
//! $\mathbf S$ stays finite; it may vanish there (polar-angle form) or not (azimuth–height form).

use crate::{NodeTableError, Real, Vec3};

/// The range of one surface parameter: `surfgrav_quadrature`'s [`Interval`] (finite ends,
/// start < end, finite length), the same type the rules use.
pub use surfgrav_quadrature::Interval;
use surfgrav_quadrature::InvalidInterval;

impl From<InvalidInterval> for NodeTableError {
    fn from(error: InvalidInterval) -> Self {
        NodeTableError::InvalidInterval {
            start: error.start,
            end: error.end,
        }
    }
}

/// In which parameter directions the surface closes on itself, so that
/// $\mathbf r(u_0, v) = \mathbf r(u_1, v)$ with all derivatives (for `U`). A periodic direction is
/// best integrated with the trapezoid rule, which converges geometrically for smooth periodic
/// integrands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Periodicity {
    /// Periodic in $u$ only.
    U,
    /// Periodic in $v$ only.
    V,
    /// Periodic in both (a torus).
    Both,
    /// Periodic in neither.
    Neither,
}

/// The parameter rectangle of a surface and its periodicity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParameterDomain {
    /// The range of $u$.
    pub u: Interval,
    /// The range of $v$.
    pub v: Interval,
    /// Which directions are periodic.
    pub periodicity: Periodicity,
}

/// A closed surface in its body frame, parametrised over a rectangle (see the module docs).
///
/// Object safe, so a scene can hold `Box<dyn Surface>`; node tables are built generically
/// (`S: Surface + ?Sized`), once, so dynamic dispatch never reaches an evaluation loop.
///
/// Contract (the crate's tests check it for both ellipsoid forms and a user-defined torus):
/// - [`Surface::area_vector`] equals $\partial_u \mathbf r \times \partial_v \mathbf r$ and points
///   outward;
/// - $\oint \mathrm d\mathbf S = 0$ and $\tfrac13 \oint \mathbf r \cdot \mathrm d\mathbf S$ equals
///   [`Surface::enclosed_volume`] when that is known.
///
/// Parameters outside the rectangle are clamped into it in a non-periodic direction and taken
/// modulo the period in a periodic one, so every finite parameter pair gives finite values.
pub trait Surface: std::fmt::Debug + Send + Sync {
    /// The parameter rectangle and which of its directions is periodic.
    fn parameter_domain(&self) -> ParameterDomain;

    /// The surface point $\mathbf r(u, v)$ in the body frame.
    fn point(&self, u: Real, v: Real) -> Vec3;

    /// The outward area vector per unit parameter area,
    /// $\partial_u \mathbf r \times \partial_v \mathbf r$.
    fn area_vector(&self, u: Real, v: Real) -> Vec3;

    /// Point and area vector together; implementations override it to share trigonometry.
    fn point_and_area_vector(&self, u: Real, v: Real) -> (Vec3, Vec3) {
        (self.point(u, v), self.area_vector(u, v))
    }

    /// The enclosed volume in closed form, if known.
    fn enclosed_volume(&self) -> Option<Real> {
        None
    }

    /// The surface area in closed form, if known.
    fn surface_area(&self) -> Option<Real> {
        None
    }

    /// Radius of the smallest origin-centred sphere that contains the surface.
    fn bounding_radius(&self) -> Real;
}
