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
    #[error(
        "the step of integrator '{kind}' must be positive and finite, got {value}; give a \
         positive step in time units (e.g. 0.1, the paper's RK4 step)"
    )]
    InvalidStep {
        /// The integrator.
        kind: IntegratorKind,
        /// The rejected step.
        value: Real,
    },
    /// An adaptive kind got a tolerance outside
    /// [[`IntegratorKind::MIN_TOLERANCE`], [`IntegratorKind::MAX_TOLERANCE`]) (not finite, not
    /// positive, below what double precision can meet, or not below 1).
    #[error(
        "the tolerance of integrator '{kind}' must be in [{min:e}, {max}), got {value:e}; \
         below {min:e} double-precision rounding of the state is as large as the error asked \
         for, so the step control cannot meet it: use a tolerance from {min:e} (tightest) to \
         1e-6 (loose)",
        min = IntegratorKind::MIN_TOLERANCE,
        max = IntegratorKind::MAX_TOLERANCE
    )]
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

    /// The smallest tolerance an adaptive kind accepts, $10^{-15} \approx 4.5\\,\epsilon$
    /// ($\epsilon = 2.2\times10^{-16}$).
    ///
    /// A step is accepted when every component's error estimate is at most
    /// $\mathrm{tol}\\,(1 + |y_i|)$. The new state $y + h\sum_i b_i k_i$ is itself rounded to
    /// about $\epsilon/2$ relative, and the estimate (a difference of two such sums over 7 or 12
    /// stages) carries a few $\epsilon$ of rounding, so below a few $\epsilon$ the estimate is
    /// rounding noise and the tolerance cannot be met: the controller either shrinks the step
    /// without gain or, at very small tolerances, overflows (tolerance $10^{-300}$ fails at
    /// $t = 0$ with a non-finite state). Measured on one Kepler orbit (e = 0, 0.5, 0.9; test
    /// `choice::smallest_tolerance_works_on_kepler`): at $10^{-15}$ both kinds complete, with
    /// position errors $6\times10^{-14}$–$10^{-13}$ (dopri5) and $3\times10^{-15}$–
    /// $1.8\times10^{-13}$ (dop853); below it the error stops improving consistently (e = 0.9:
    /// dop853 $2.5\times10^{-13}$ at $10^{-16}$, $4\times10^{-13}$ at $10^{-20}$), while dopri5
    /// needs 84 000–113 000 steps at $10^{-20}$ instead of 1 200–2 400.
    pub const MIN_TOLERANCE: Real = 1e-15;

    /// The tolerances accepted are below this: a relative error of 1 is no accuracy at all.
    pub const MAX_TOLERANCE: Real = 1.0;

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
    /// tolerance (the mixed error test $|e_i| \le \mathrm{tol}\\,(1 + |y_i|)$ per component of
    /// positions and velocities) and ignores `step`. The step must be positive and finite, the
    /// tolerance in [[`Self::MIN_TOLERANCE`], [`Self::MAX_TOLERANCE`]).
    pub fn build(
        self,
        step: Real,
        tolerance: Real,
    ) -> Result<Box<dyn Integrator>, IntegratorChoiceError> {
        let valid = |x: Real| x.is_finite() && x > 0.0;
        if self.is_adaptive() {
            if !(Self::MIN_TOLERANCE..Self::MAX_TOLERANCE).contains(&tolerance) {
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
