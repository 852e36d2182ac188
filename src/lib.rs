//! # surfgrav
//!
//! Exact gravitational interaction of extended rigid bodies by Conway's (2016) surface
//! integrals. This facade re-exports the workspace crates:
//!
//! - [`potentials`]: closed-form fields of homogeneous bodies;
//! - [`surfaces`]: body surfaces and their area vectors;
//! - [`interaction`]: the interaction engine (force, torques, mutual energy of two bodies);
//! - [`quadrature`]: quadrature rules as data;
//! - [`dynamics`]: two-body motion, translation and rotation in 3-D;
//! - [`scenarios`]: scene files, presets, runs, outputs and the command-line tool;
//! - [`nalgebra`]: the linear-algebra types of the API (`Vector3`, `Matrix3`,
//!   `UnitQuaternion`).
//!
//! The README follows; its Rust examples are compiled and run as doctests.
#![doc = include_str!("../README.md")]
pub use nalgebra;
pub use surfgrav_dynamics as dynamics;
pub use surfgrav_interaction as interaction;
pub use surfgrav_potentials as potentials;
pub use surfgrav_quadrature as quadrature;
pub use surfgrav_scenarios as scenarios;
pub use surfgrav_surfaces as surfaces;
