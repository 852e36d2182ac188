//! The refinement strategies: given the integrated body X, the source Y and their
//! [`Placement`], each computes a certified [`Interaction`] (or a typed error carrying its
//! best result) by its own sequence of rules. One trait, [`Strategy`], one file per strategy:
//!
//! - [`ladder`]: the ladder of fixed tables (and one table of it, uncertified);
//! - [`aimed_ladder`]: the same ladder on the aimed rule's grids ([`super::aimed`]);
//! - [`nested_doubling`]: the nested doubling rule ([`super::nested`]);
//! - [`adaptive`]: the adaptive G7–K15 cubature of `surfgrav-quadrature`.
//!
//! The engine picks one from the options ([`super::MethodChoice`]); the integrand at a node
//! is the kernel's ([`super::kernel`]), shared by all of them.

pub(crate) mod adaptive;
pub(crate) mod aimed_ladder;
pub(crate) mod ladder;
pub(crate) mod nested_doubling;

use super::body::Body;
use super::error::InteractionError;
use super::options::{Interaction, InteractionOptions, Request};
use super::surface_choice::Placement;

/// One surface integral to refine: X's surface in Y's field, what is asked for, and the
/// budget of field evaluations it may spend.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Problem<'a> {
    /// The integrated body.
    pub(crate) x: &'a Body,
    /// The source body.
    pub(crate) y: &'a Body,
    /// Where they are, in X's integration frame.
    pub(crate) placement: &'a Placement,
    /// The engine's options (tolerance, parametrisation).
    pub(crate) options: &'a InteractionOptions,
    /// What the caller needs; a strategy may compute more.
    pub(crate) request: Request,
    /// The most field evaluations this strategy may spend.
    pub(crate) budget: usize,
}

/// A way of refining a surface integral until it meets the tolerance. Implementors keep
/// their workspaces between calls (the engine owns one of each).
pub(crate) trait Strategy {
    /// The certified result, or [`InteractionError::ToleranceNotMet`] with the best one.
    fn refine(&mut self, problem: &Problem<'_>) -> Result<Interaction, InteractionError>;
}
