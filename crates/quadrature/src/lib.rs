//! Quadrature rules as data, and an adaptive integrator, for surface integrals over a parameter
//! rectangle.
//!
//! surfgrav evaluates the force, torque and mutual energy of two bodies as integrals over one
//! body's surface, parametrised over a rectangle $(u, v)$ (for example $u$ the azimuth, periodic,
//! and $v$ the polar angle). A body builds its table of surface nodes once, from a rule of this
//! crate, and reuses it for every evaluation; so rules are plain data computed by their
//! constructors, and evaluation loops allocate nothing.
//!
//! | Item | Integrates | Exact for / accuracy |
//! |---|---|---|
//! | [`GaussLegendre`] | $\int_a^b f\\,\mathrm dx$ with $n$ nodes | polynomials of degree $\le 2n-1$; nodes and weights correctly rounded in every test up to $n = 1000$ |
//! | [`PeriodicTrapezoid`] | one period of a periodic $f$ | $e^{ikx}$ for $\lvert k\rvert < n$; geometric convergence for analytic $f$ |
//! | [`TensorProductRule`] | $\iint f\\,\mathrm du\\,\mathrm dv$ on a rectangle | products of what its factors integrate exactly |
//! | [`NestedTensorRule`], [`NestedCubature`] | $\iint \mathbf f\\,\mathrm du\\,\mathrm dv$, periodic in $u$, by nested doubling (trapezoid × Fejér) | requested tolerance; the estimate costs no extra evaluation |
//! | [`AdaptiveCubature`] | $\iint \mathbf f\\,\mathrm du\\,\mathrm dv$, $N$ components at once | requested tolerance, with error estimate and evaluation count |
//!
//! One-dimensional rules share the [`Rule1D`] trait (an [`Interval`], nodes, weights); any two
//! make a [`TensorProductRule`].
//!
//! ```
//! use std::f64::consts::PI;
//! use surfgrav_quadrature::{GaussLegendre, PeriodicTrapezoid, TensorProductRule};
//!
//! // Area of the unit sphere: ∫₀^π ∫₀^{2π} sin θ dφ dθ = 4π.
//! let azimuth = PeriodicTrapezoid::new(16, 0.0, 2.0 * PI)?;
//! let polar = GaussLegendre::new(12, 0.0, PI)?;
//! let rule = TensorProductRule::new(&azimuth, &polar);
//! let area = rule.integrate(|_phi, theta| theta.sin());
//! assert!((area - 4.0 * PI).abs() < 1e-13);
//! # Ok::<(), surfgrav_quadrature::QuadratureError>(())
//! ```
//!
//! [`CompensatedSum`] is the workspace's one compensated (Neumaier) running sum; the other
//! crates re-export it.
//!
//! Errors: constructors validate their input and return [`QuadratureError`]; the adaptive
//! integrator reports a missed tolerance in its result ([`Termination`]) and rejects a
//! non-finite integrand value with an error.

mod error;
mod twofold;

pub mod adaptive;
pub mod gauss_kronrod;
pub mod gauss_legendre;
pub mod nested;
pub mod periodic_trapezoid;
pub mod rule;
pub mod sum;
pub mod tensor;
pub mod tolerance;

pub use adaptive::{
    AdaptiveCubature, AdaptiveEstimate, AdaptiveOptions, Termination, EVALUATIONS_PER_RECTANGLE,
    MINIMUM_EVALUATION_BUDGET,
};
pub use error::QuadratureError;
pub use gauss_legendre::{GaussLegendre, MAX_GAUSS_LEGENDRE_ORDER};
pub use nested::{
    geometric_estimate, rate_estimate, NestedCubature, NestedEstimate, NestedFejer, NestedLevels,
    NestedTensorRule, NestedTrapezoid,
};
pub use periodic_trapezoid::PeriodicTrapezoid;
pub use rule::{Interval, InvalidInterval, Rule1D};
pub use sum::CompensatedSum;
pub use tensor::{Rectangle, TensorNode, TensorProductRule};
pub use twofold::two_sum;
