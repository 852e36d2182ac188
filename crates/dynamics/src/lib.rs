//! Two-body motion of extended rigid bodies: interaction models, integrators, conservation
//! diagnostics and orbit analysis.
//!
//! - [`state`]: the two-body state (positions, velocities, orientations, spins) and trajectory
//!   samples.
//! - [`engine_model`]: models backed by the surface-integral engine ([`EngineModel`]) and the
//!   tabulated central-force fast path ([`SceneModel`]).
//! - [`model`]: the [`InteractionModel`] trait (force on A, mutual energy, contact distance) with
//!   point masses and closure-defined central pairs.
//! - [`integrate`]: the [`Integrator`] trait; fixed-step RK4, leapfrog and symplectic
//!   compositions of order 4, 6 and 8 ([`FixedStep`]); adaptive Dormand–Prince 5(4) and DOP853
//!   ([`Adaptive`], [`EmbeddedPair`]); contact events and typed failures.
//! - [`interpolant`]: a central pair tabulated once as a piecewise Chebyshev interpolant of
//!   $V(r)$, forces from its exact derivative.
//! - [`interpolate`]: dense output between samples (quintic Hermite).
//! - [`diagnostics`]: energy, angular momentum and the statistics of their per-step changes.
//! - [`orbit`]: apsides, radial and azimuthal periods, precession of the relative orbit.
//! - [`choice`]: integrators by name ([`IntegratorKind`]: `rk4`, `leapfrog`, `yoshida4`,
//!   `yoshida6`, `yoshida8`, `dopri5`, `dop853`), as the command line chooses them.
//! - [`run`]: integrate and gather every diagnostic in one call.
//! - [`tolerance`]: the accuracy requirements the tests hold this crate to.
//!
//! - [`spin`]: spin rates, obliquities, libration and the mutual orbit's osculating elements.
//! - [`rigid`]: the full two-body problem, translation and rotation in 3-D (Euler's equations,
//!   the geometric splitting of Dullweber, Leimkuhler & McLachlan, Runge–Kutta on the full state).
//!
//! Which equations a run integrates is decided by the model's [`MotionPath`] at the start: the
//! translation-only path only where a symmetry that the motion preserves keeps every torque at
//! zero for the whole run (spheres and points; coaxial axisymmetric bodies spinning about their
//! common axis and moving in their common equatorial plane); rotation otherwise.
//!
//! ```
//! use surfgrav_dynamics::{
//!     BodyState, FixedScheme, FixedStep, Integrator, OrbitAnalyser, PointMasses, TwoBodyState,
//! };
//! use surfgrav_potentials::Vec3;
//!
//! // The paper-point scene: two unit point masses, G = 1.
//! let model = PointMasses::new(1.0, 1.0, 1.0).unwrap();
//! let initial = TwoBodyState::new(
//!     BodyState::new(Vec3::new(-3.5, 0.0, 0.0), Vec3::new(0.0, 0.2, 0.0)),
//!     BodyState::new(Vec3::new(3.5, 0.0, 0.0), Vec3::new(0.0, -0.2, 0.0)),
//! );
//! let mut integrator = FixedStep::new(FixedScheme::RungeKutta4, 0.1).unwrap();
//! let mut orbit = OrbitAnalyser::new();
//! integrator
//!     .integrate(&model, &initial, 0.0, 300.0, &mut |sample| orbit.observe(sample))
//!     .unwrap();
//! let report = orbit.report();
//! assert!((report.radial_period.unwrap() - 47.6177).abs() < 1e-4);
//! assert!((report.minimum_separation.unwrap() - 2.72222).abs() < 1e-5);
//! ```

pub mod choice;
pub mod diagnostics;
pub mod engine_model;
pub mod integrate;
pub mod interpolant;
pub mod interpolate;
pub mod model;
pub mod orbit;
pub mod rigid;
pub mod run;
pub mod spin;
pub mod state;
mod tableau;
pub mod tolerance;

pub use choice::{IntegratorChoiceError, IntegratorKind};
pub use diagnostics::{
    angular_momentum, kinetic_energy, spin_angular_momentum, total_energy, CompensatedSum,
    ConservationMonitor, ConservationStatistics, SeriesAccumulator, SeriesStatistics,
};
pub use engine_model::{
    EngineModel, EngineModelError, SceneModel, SceneSettings, TableReport, ALIGNMENT_SINE,
};
pub use integrate::{
    Adaptive, ContactEvent, DynamicsError, EmbeddedPair, EscapeEvent, FixedScheme, FixedStep,
    Integrator, RunSummary, Termination,
};
pub use interpolant::{reachable_separations, InterpolantError, InterpolatedCentralPair};
pub use model::{CentralPair, InteractionError, InteractionModel, MotionPath, PointMasses, Wrench};
pub use orbit::{Apsis, OrbitAnalyser, OrbitReport};
pub use run::{run_with_diagnostics, RunReport};
pub use spin::{
    libration_deg, long_axis, obliquity_deg, osculating_elements, state_from_elements,
    true_anomaly, BodySpinReport, Elements, OrbitElementsReport, Range, SpinOrbitAnalyser,
    SpinOrbitReport,
};
pub use state::{BodyState, Sample, TwoBodyState};
