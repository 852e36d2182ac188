//! Choosing an integrator by name, as a command line or a scene file does.
//!
//! | name | method | setting | order | force evaluations per step |
//! |---|---|---|---|---|
//! | `rk4` | classical Runge–Kutta | fixed step | 4 | 4 |
//! | `leapfrog` | kick–drift–kick, symplectic | fixed step | 2 | 1 |
//! | `yoshida4` | triple-jump composition of leapfrog, symplectic | fixed step | 4 | 3 |
//! | `yoshida6` | Yoshida's 7-stage composition, symplectic | fixed step | 6 | 7 |
//! | `yoshida8` | triple jump of `yoshida6`, symplectic | fixed step | 8 | 21 |
//! | `dopri5` | Dormand–Prince 5(4), adaptive | tolerance | 5 | 6 |
//! | `dop853` | DOP853, adaptive, dense output of order 7 | tolerance | 8 | 12 |
//!
//! ```
//! use surfgrav_dynamics::IntegratorKind;
//!
//! let kind: IntegratorKind = "dop853".parse().unwrap();
//! assert!(kind.is_adaptive());
//! let integrator = kind.build(0.1, 1e-12).unwrap(); // the step is ignored by adaptive kinds
//! assert_eq!(integrator.name(), "dop853");
//! let error = "rk45".parse::<IntegratorKind>().unwrap_err();
//! assert!(error.to_string().contains("rk4, leapfrog, yoshida4"));
//! ```

use crate::integrate::{Adaptive, EmbeddedPair, FixedScheme, FixedStep, Integrator};
use std::fmt;
use std::str::FromStr;
use surfgrav_potentials::Real;
use thiserror::Error;

/// An integrator chosen by name. [`IntegratorKind::build`] makes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum IntegratorKind {
    /// `rk4`: classical fourth-order Runge–Kutta, fixed step (the founding paper's).
    Rk4,
    /// `leapfrog`: kick–drift–kick, order 2, fixed step, symplectic.
    Leapfrog,
    /// `yoshida4`: order 4, fixed step, symplectic.
    Yoshida4,
    /// `yoshida6`: order 6, fixed step, symplectic.
    Yoshida6,
    /// `yoshida8`: order 8 (triple jump of `yoshida6`), fixed step, symplectic.
    Yoshida8,
    /// `dopri5`: adaptive Dormand–Prince 5(4).
    Dopri5,
    /// `dop853`: adaptive DOP853 with dense output of order 7.
    Dop853,
}

/// Why a name or a setting does not give an integrator.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum IntegratorChoiceError {
    /// The name is not one of [`IntegratorKind::NAMES`].
    #[error("unknown integrator '{name}'; valid names: {}", IntegratorKind::NAMES.join(", "))]
    UnknownName {
        /// The rejected name.
        name: String,
    },
    /// A fixed-step kind got a step that is not positive and finite.
    #[error("the step of integrator '{kind}' must be positive and finite, got {value}")]
    InvalidStep {
        /// The integrator.
        kind: IntegratorKind,
        /// The rejected step.
        value: Real,
    },
    /// An adaptive kind got a tolerance that is not positive and finite.
    #[error("the tolerance of integrator '{kind}' must be positive and finite, got {value}")]
    InvalidTolerance {
        /// The integrator.
        kind: IntegratorKind,
        /// The rejected tolerance.
        value: Real,
    },
}

impl IntegratorKind {
    /// Every kind, in the order of [`IntegratorKind::NAMES`].
    pub const ALL: [IntegratorKind; 7] = [
        IntegratorKind::Rk4,
        IntegratorKind::Leapfrog,
        IntegratorKind::Yoshida4,
        IntegratorKind::Yoshida6,
        IntegratorKind::Yoshida8,
        IntegratorKind::Dopri5,
        IntegratorKind::Dop853,
    ];

    /// The valid names.
    pub const NAMES: [&'static str; 7] = [
        "rk4", "leapfrog", "yoshida4", "yoshida6", "yoshida8", "dopri5", "dop853",
    ];

    /// The name (`rk4`, ..., `dop853`); the same as the built integrator's
    /// [`Integrator::name`].
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// True for the adaptive kinds (`dopri5`, `dop853`), which take a tolerance; the others take
    /// a fixed step.
    pub fn is_adaptive(self) -> bool {
        matches!(self, IntegratorKind::Dopri5 | IntegratorKind::Dop853)
    }

    /// True for the symplectic kinds (`leapfrog`, `yoshida4/6/8`).
    pub fn is_symplectic(self) -> bool {
        matches!(
            self,
            IntegratorKind::Leapfrog
                | IntegratorKind::Yoshida4
                | IntegratorKind::Yoshida6
                | IntegratorKind::Yoshida8
        )
    }

    /// Order of accuracy.
    pub fn order(self) -> u32 {
        match self {
            IntegratorKind::Leapfrog => 2,
            IntegratorKind::Rk4 | IntegratorKind::Yoshida4 => 4,
            IntegratorKind::Dopri5 => 5,
            IntegratorKind::Yoshida6 => 6,
            IntegratorKind::Yoshida8 | IntegratorKind::Dop853 => 8,
        }
    }

    /// Builds the integrator. A fixed-step kind uses `step` (time units) and ignores
    /// `tolerance`; an adaptive kind uses `tolerance` as both its relative and its absolute
    /// tolerance (the mixed error test $|e_i| \le \mathrm{tol}\,(1 + |y_i|)$ per component of
    /// positions and velocities) and ignores `step`. The used value must be positive and finite.
    pub fn build(
        self,
        step: Real,
        tolerance: Real,
    ) -> Result<Box<dyn Integrator>, IntegratorChoiceError> {
        let valid = |x: Real| x.is_finite() && x > 0.0;
        if self.is_adaptive() {
            if !valid(tolerance) {
                return Err(IntegratorChoiceError::InvalidTolerance {
                    kind: self,
                    value: tolerance,
                });
            }
            let pair = if self == IntegratorKind::Dop853 {
                EmbeddedPair::Dop853
            } else {
                EmbeddedPair::DormandPrince54
            };
            let adaptive = Adaptive::new(tolerance, tolerance)
                .map_err(|_| IntegratorChoiceError::InvalidTolerance {
                    kind: self,
                    value: tolerance,
                })?
                .with_pair(pair);
            return Ok(Box::new(adaptive));
        }
        if !valid(step) {
            return Err(IntegratorChoiceError::InvalidStep {
                kind: self,
                value: step,
            });
        }
        let scheme = match self {
            IntegratorKind::Leapfrog => FixedScheme::Leapfrog,
            IntegratorKind::Yoshida4 => FixedScheme::Yoshida4,
            IntegratorKind::Yoshida6 => FixedScheme::Yoshida6,
            IntegratorKind::Yoshida8 => FixedScheme::TripleJump8,
            _ => FixedScheme::RungeKutta4,
        };
        let fixed =
            FixedStep::new(scheme, step).map_err(|_| IntegratorChoiceError::InvalidStep {
                kind: self,
                value: step,
            })?;
        Ok(Box::new(fixed))
    }
}

impl fmt::Display for IntegratorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for IntegratorKind {
    type Err = IntegratorChoiceError;

    /// Exact, case-sensitive match of one of [`IntegratorKind::NAMES`].
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|kind| kind.name() == name)
            .ok_or_else(|| IntegratorChoiceError::UnknownName {
                name: name.to_string(),
            })
    }
}
