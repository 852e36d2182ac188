//! Globally adaptive cubature of vector-valued integrands over a rectangle.
//!
//! Computes $\mathbf I = \int\_{v_0}^{v_1}\\!\int\_{u_0}^{u_1} \mathbf f(u, v)\\,\mathrm du\\,\mathrm dv$
//! for $\mathbf f$ with `N` components evaluated together (force, torque and energy of a surface
//! integral in one pass), to a requested tolerance, with an error estimate, the number of
//! integrand evaluations, and a [`Termination`] that says whether the tolerance was met.
//!
//! # Scheme
//!
//! **Rule on a rectangle.** The product of the G7–K15 pair ([`crate::gauss_kronrod`]) mapped to
//! the rectangle: $15 \times 15 = 225$ evaluations give four estimates from the same values,
//! $Q\_{KK}$ (Kronrod in both directions, degree 23 in each variable), $Q\_{GK}$ (Gauss in $u$,
//! Kronrod in $v$), $Q\_{KG}$ and $Q\_{GG}$. The rectangle's value is $Q\_{KK}$; per component,
//! with $s = Q\_{KK}[|f - \bar f|]$ the spread of the integrand about its mean,
//! $$e_u = |Q\_{KK} - Q\_{GK}|, \quad e_v = |Q\_{KK} - Q\_{KG}|, \quad
//! r = \max\bigl(|Q\_{KK} - Q\_{GG}|,\\; e_u + e_v\bigr),$$
//! $$e = \max\Bigl(r,\\; s \min\bigl(1, (200\\, r/s)^{3/2}\bigr),\\; 50\\,\epsilon\\, Q\_{KK}[|f|]\Bigr).$$
//! $r$ estimates the error of the degree-13 Gauss product, while the degree-23 Kronrod product
//! is returned: for smooth integrands the estimate exceeds the true error by orders of magnitude
//! (measured: the true error is below $10^{-2}$ of the estimate on every test integrand).
//! QUADPACK's $s\\,(200 r/s)^{3/2}$ is used only to *raise* $r$, when the rules are not yet in
//! their asymptotic regime ($r/s > 3.5 \times 10^{-7}$), where two rules can agree by
//! accident; it is never allowed to lower $r$, which is where it can be optimistic. The last
//! term is a floor for the rounding of the 225-term sums.
//!
//! **Validation by refinement.** Two rules that see the same 225 values can agree by accident
//! while both are wrong (a kink or a narrow peak between the nodes). So each estimate is
//! checked when its rectangle is bisected: the halves' sum $Q_1 + Q_2$ is far more accurate than
//! the parent's $Q$, so $\delta = |Q_1 + Q_2 - Q|$ measures the parent's true error, and each
//! half's error is raised to at least $\delta$. This bounds the halves' true error whenever
//! bisection at least halves the error (convergence order $\ge 1$). It costs little for smooth
//! integrands, where $\delta$ (the Kronrod product's own error) is far below the halves'
//! estimates: no extra evaluation at tolerance $10^{-12}$ in the tests, up to a third more at
//! $10^{-6}$. The first rectangle is always bisected once, so that no result rests on an
//! unchecked estimate, unless its error is already at the rounding floor.
//!
//! **Limits.** No estimate from finitely many samples is a guaranteed bound. In a stress test
//! of 1000 random integrands of each kind on the unit square (tolerances $10^{-12}$ to
//! $10^{-5}$): near-singular peaks $1/\sqrt{(u-u_0)^2+\varepsilon}$ and
//! $1/((u-u_0)^2+\varepsilon)$ with $\varepsilon$ from $10^{-12}$ to $10^{-2}$ never had an
//! optimistic estimate; smoothed kinks $\sqrt{(u-u_0)^2+\varepsilon}$ had one (low by a factor
//! 2.2), where a bisection happened not to reduce the error. Potential and field of a sphere's
//! surface seen from 100 random points 0.001 to 2 radii above it never had one either
//! (`tests/adaptive.rs` keeps these stress tests, smaller).
//!
//! **Adaptivity.** Globally adaptive subdivision (as QUADPACK's QAG, in two dimensions): a
//! priority queue holds the rectangles by error; the worst one is bisected, along $u$ if its
//! $e_u$ exceeds its $e_v$ (largest component of each) and along $v$ otherwise, until the total
//! error meets the tolerance, the evaluation budget would be exceeded, or no rectangle can be
//! improved (its width along the chosen direction is below $1024\\,\epsilon$ times its
//! coordinates, or its error is at the rounding floor, which bisection cannot lower).
//!
//! **Vector norm.** The error of the result is the vector $\mathbf E = \sum\_{\text{rectangles}}
//! \mathbf e$ (component by component); the integration has converged when
//! $$\max_i E_i \le \max\bigl(\tau\_{\text{abs}},\\; \tau\_{\text{rel}} \max_i |I_i|\bigr),$$
//! i.e. the tolerance is relative to the **largest component**. A component that vanishes by
//! symmetry (a torque about a symmetry axis) is thus computed to the accuracy of the others
//! instead of driving the integrator to an unreachable relative accuracy; integrands whose
//! components have different units should be scaled to comparable magnitudes by the caller.
//!
//! **Why this scheme.** The integrands of surfgrav are analytic on each parameter rectangle
//! (smooth surfaces, bodies apart), steep only when the bodies come close. A product
//! Gauss–Kronrod rule of degree 23 per variable reaches $10^{-12}$ on few rectangles, where the
//! error $O(h^8)$ of a degree-7 Genz–Malik rule (17 points) would need far finer subdivision;
//! the embedded directional estimates come for free and pick the split direction. For a smooth *periodic* direction
//! (azimuth), a fixed [`crate::TensorProductRule`] of [`crate::PeriodicTrapezoid`] ×
//! [`crate::GaussLegendre`] is spectrally accurate and cheaper still; this integrator is the
//! robust fallback, and the reference against which such fixed rules are checked.
//!
//! **Cost.** No allocation per evaluation: the rule works on stack arrays ($225 N$ values per
//! rectangle), and the queue of rectangles lives in the [`AdaptiveCubature`] value, whose
//! capacity is kept between calls. Measured (`examples/timings.rs` prints the times): a smooth
//! integrand to $10^{-12}$ in 675 evaluations; potential and field of a sphere's surface from
//! 1 radius above it to $10^{-12}$ in 17 775 evaluations, from 0.05 radius above it in 74 925.

use crate::gauss_kronrod::{GAUSS_7_WEIGHTS, KRONROD_15_NODES, KRONROD_15_WEIGHTS};
use crate::sum::CompensatedSum;
use crate::tensor::Rectangle;
use crate::QuadratureError;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Integrand evaluations per rectangle (the 15 × 15 Kronrod product).
pub const EVALUATIONS_PER_RECTANGLE: usize = 225;

/// The smallest evaluation budget accepted: the first rectangle and its two halves, the least
/// work after which a result can be reported as converged.
pub const MINIMUM_EVALUATION_BUDGET: usize = 3 * EVALUATIONS_PER_RECTANGLE;

/// Multiple of the machine epsilon times $\int |f|$ taken as the floor of a rectangle's error.
const ROUNDOFF_FLOOR: f64 = 50.0 * f64::EPSILON;

/// A rectangle narrower than this multiple of $\epsilon$ times its coordinates is not split.
const MINIMUM_RELATIVE_WIDTH: f64 = 1024.0 * f64::EPSILON;

/// What the adaptive integrator is asked to achieve, and the most it may spend.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveOptions {
    /// Requested relative accuracy $\tau\_{\text{rel}}$, relative to the largest component of the
    /// integral (non-negative; `0` to use the absolute tolerance alone).
    pub relative_tolerance: f64,
    /// Requested absolute accuracy $\tau\_{\text{abs}}$, in the units of the integral
    /// (non-negative; `0` to use the relative tolerance alone).
    pub absolute_tolerance: f64,
    /// The most integrand evaluations one integration may use (at least
    /// [`MINIMUM_EVALUATION_BUDGET`]). The first rectangle costs
    /// [`EVALUATIONS_PER_RECTANGLE`], each bisection twice as much.
    pub max_evaluations: usize,
}

impl Default for AdaptiveOptions {
    /// Relative $10^{-10}$, no absolute tolerance, one million evaluations.
    fn default() -> Self {
        AdaptiveOptions {
            relative_tolerance: 1e-10,
            absolute_tolerance: 0.0,
            max_evaluations: 1_000_000,
        }
    }
}

impl AdaptiveOptions {
    /// Checks the options.
    ///
    /// # Errors
    /// [`QuadratureError::InvalidTolerance`] unless both tolerances are finite and non-negative
    /// and one of them is positive; [`QuadratureError::EvaluationBudgetTooSmall`] below
    /// [`MINIMUM_EVALUATION_BUDGET`].
    pub fn validate(&self) -> Result<(), QuadratureError> {
        let (relative, absolute) = (self.relative_tolerance, self.absolute_tolerance);
        let valid = |tolerance: f64| tolerance.is_finite() && tolerance >= 0.0;
        if !(valid(relative) && valid(absolute) && (relative > 0.0 || absolute > 0.0)) {
            return Err(QuadratureError::InvalidTolerance { relative, absolute });
        }
        if self.max_evaluations < MINIMUM_EVALUATION_BUDGET {
            return Err(QuadratureError::EvaluationBudgetTooSmall {
                max_evaluations: self.max_evaluations,
                minimum: MINIMUM_EVALUATION_BUDGET,
            });
        }
        Ok(())
    }
}

/// Why an adaptive integration stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Termination {
    /// The error estimate meets the requested tolerance.
    Converged,
    /// Another bisection would exceed [`AdaptiveOptions::max_evaluations`]; the tolerance was
    /// not met.
    EvaluationBudgetExhausted,
    /// No rectangle can be improved: each is too narrow to bisect (near a singularity) or its
    /// error is already at the rounding floor (a tolerance below what double precision
    /// delivers for this integrand); the tolerance was not met.
    SubdivisionLimitReached,
}

/// The outcome of an adaptive integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveEstimate<const N: usize> {
    /// The integral of each component.
    pub value: [f64; N],
    /// The estimated absolute error of each component (an upper estimate: see the module docs).
    pub error_estimate: [f64; N],
    /// Integrand evaluations used (each computes all `N` components).
    pub evaluations: usize,
    /// Rectangles in the final subdivision.
    pub rectangles: usize,
    /// Why the integration stopped.
    pub termination: Termination,
}

impl<const N: usize> AdaptiveEstimate<N> {
    /// Whether the requested tolerance was met.
    pub fn converged(&self) -> bool {
        self.termination == Termination::Converged
    }

    /// The largest component of the error estimate, $\max_i E_i$.
    pub fn error_norm(&self) -> f64 {
        max_norm(&self.error_estimate)
    }
}

/// An adaptive integrator for integrands with `N` components, holding its reusable workspace.
///
/// ```
/// use surfgrav_quadrature::{AdaptiveCubature, AdaptiveOptions, Rectangle};
///
/// let options = AdaptiveOptions { relative_tolerance: 1e-12, ..AdaptiveOptions::default() };
/// let mut integrator = AdaptiveCubature::<2>::new(options)?;
/// let square = Rectangle::new(0.0, 1.0, 0.0, 1.0)?;
/// // ∫∫ (1, u v) over the unit square = (1, 1/4).
/// let estimate = integrator.integrate(square, |u, v, values: &mut [f64; 2]| {
///     values[0] = 1.0;
///     values[1] = u * v;
/// })?;
/// assert!(estimate.converged());
/// assert!((estimate.value[1] - 0.25).abs() <= 1e-12);
/// # Ok::<(), surfgrav_quadrature::QuadratureError>(())
/// ```
#[derive(Debug, Clone)]
pub struct AdaptiveCubature<const N: usize> {
    options: AdaptiveOptions,
    active: BinaryHeap<Region<N>>,
    unsplittable: Vec<Region<N>>,
}

impl<const N: usize> AdaptiveCubature<N> {
    /// An integrator with these options and an empty workspace.
    ///
    /// # Errors
    /// As [`AdaptiveOptions::validate`].
    pub fn new(options: AdaptiveOptions) -> Result<Self, QuadratureError> {
        options.validate()?;
        Ok(AdaptiveCubature {
            options,
            active: BinaryHeap::new(),
            unsplittable: Vec::new(),
        })
    }

    /// The current options.
    pub fn options(&self) -> &AdaptiveOptions {
        &self.options
    }

    /// Replaces the options, keeping the workspace.
    ///
    /// # Errors
    /// As [`AdaptiveOptions::validate`]; the old options stay in force on error.
    pub fn set_options(&mut self, options: AdaptiveOptions) -> Result<(), QuadratureError> {
        options.validate()?;
        self.options = options;
        Ok(())
    }

    /// Integrates `integrand` over `rectangle`.
    ///
    /// `integrand(u, v, values)` must write the `N` components of $\mathbf f(u, v)$ into
    /// `values` (which holds zeros on entry). Not meeting the tolerance is not an error: it is
    /// reported by [`AdaptiveEstimate::termination`], with the best value and its error estimate.
    ///
    /// # Errors
    /// [`QuadratureError::NonFiniteIntegrand`] as soon as the integrand returns NaN or an
    /// infinity; [`QuadratureError::NonFiniteIntegral`] if the sums overflow.
    pub fn integrate<F>(
        &mut self,
        rectangle: Rectangle,
        mut integrand: F,
    ) -> Result<AdaptiveEstimate<N>, QuadratureError>
    where
        F: FnMut(f64, f64, &mut [f64; N]),
    {
        self.active.clear();
        self.unsplittable.clear();
        let bounds = Bounds::from(rectangle);
        let first = apply_rule(bounds, &mut integrand)?;
        let mut evaluations = EVALUATIONS_PER_RECTANGLE;
        let (mut running_value, mut running_error) = (first.value, first.error);
        self.active.push(first);
        // The first rectangle's estimate is only trusted once its halves have confirmed it
        // (unless it is already at the rounding floor: e.g. a polynomial the rule integrates
        // exactly).
        let mut confirmed = self.active.peek().is_some_and(Region::limited_by_rounding);
        let termination = loop {
            if confirmed && max_norm(&running_error) <= self.target(&running_value) {
                // Confirm with freshly summed totals (the running ones drift by rounding).
                (running_value, running_error) = self.totals();
                if max_norm(&running_error) <= self.target(&running_value) {
                    break Termination::Converged;
                }
            }
            if evaluations + 2 * EVALUATIONS_PER_RECTANGLE > self.options.max_evaluations {
                break Termination::EvaluationBudgetExhausted;
            }
            let Some(worst) = self.active.pop() else {
                break Termination::SubdivisionLimitReached;
            };
            let halves = worst.bounds.bisect(worst.split_along_u);
            let Some((first_half, second_half)) = halves.filter(|_| !worst.limited_by_rounding())
            else {
                self.unsplittable.push(worst);
                continue;
            };
            let mut first = apply_rule(first_half, &mut integrand)?;
            let mut second = apply_rule(second_half, &mut integrand)?;
            evaluations += 2 * EVALUATIONS_PER_RECTANGLE;
            for c in 0..N {
                // Validation by refinement: the halves' sum is far more accurate than the parent
                // value, so their difference measures the parent's true error, which bounds the
                // halves' error whenever bisection at least halves it.
                let refined = first.value[c] + second.value[c];
                let discrepancy = (refined - worst.value[c]).abs();
                first.raise_error(c, discrepancy);
                second.raise_error(c, discrepancy);
                running_value[c] += refined - worst.value[c];
                running_error[c] += (first.error[c] + second.error[c]) - worst.error[c];
            }
            confirmed = true;
            self.active.push(first);
            self.active.push(second);
        };
        let (value, error_estimate) = self.totals();
        if !(value.iter().all(|v| v.is_finite()) && error_estimate.iter().all(|e| e.is_finite())) {
            return Err(QuadratureError::NonFiniteIntegral);
        }
        // The loop stops on the running totals; the fresh ones decide (a run stopped by the
        // budget may in fact have converged), but never on an unconfirmed first estimate.
        let termination = if confirmed && max_norm(&error_estimate) <= self.target(&value) {
            Termination::Converged
        } else if termination == Termination::Converged {
            Termination::EvaluationBudgetExhausted
        } else {
            termination
        };
        Ok(AdaptiveEstimate {
            value,
            error_estimate,
            evaluations,
            rectangles: self.active.len() + self.unsplittable.len(),
            termination,
        })
    }

    /// $\max(\tau\_{\text{abs}}, \tau\_{\text{rel}} \max_i |I_i|)$.
    fn target(&self, value: &[f64; N]) -> f64 {
        self.options
            .absolute_tolerance
            .max(self.options.relative_tolerance * max_norm(value))
    }

    /// Value and error summed over all rectangles (compensated summation).
    fn totals(&self) -> ([f64; N], [f64; N]) {
        let mut value = [CompensatedSum::default(); N];
        let mut error = [CompensatedSum::default(); N];
        for region in self.active.iter().chain(&self.unsplittable) {
            for c in 0..N {
                value[c].add(region.value[c]);
                error[c].add(region.error[c]);
            }
        }
        (value.map(|sum| sum.value()), error.map(|sum| sum.value()))
    }
}

/// QUADPACK's widening of an embedded-rule error estimate $e$ given the spread
/// $s = Q[|f - \bar f|]$: $s \min(1, (200\\, e/s)^{3/2})$. Used only to *raise* estimates: it
/// exceeds $e$ when $e/s > 3.5 \times 10^{-7}$, i.e. before the rules reach their asymptotic
/// regime, where two rules can agree by accident.
fn widened(error: f64, spread: f64) -> f64 {
    if spread > 0.0 {
        spread * (200.0 * error / spread).powf(1.5).min(1.0)
    } else {
        error
    }
}

/// $\max_i |x_i|$.
fn max_norm<const N: usize>(values: &[f64; N]) -> f64 {
    values
        .iter()
        .fold(0.0, |largest, value| largest.max(value.abs()))
}

/// A rectangle as plain bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Bounds {
    u_lower: f64,
    u_upper: f64,
    v_lower: f64,
    v_upper: f64,
}

impl From<Rectangle> for Bounds {
    fn from(rectangle: Rectangle) -> Self {
        Bounds {
            u_lower: rectangle.u.start(),
            u_upper: rectangle.u.end(),
            v_lower: rectangle.v.start(),
            v_upper: rectangle.v.end(),
        }
    }
}

impl Bounds {
    /// The two halves along `u` (or `v`), or `None` if the rectangle is too narrow there.
    fn bisect(self, along_u: bool) -> Option<(Bounds, Bounds)> {
        let (lower, upper) = if along_u {
            (self.u_lower, self.u_upper)
        } else {
            (self.v_lower, self.v_upper)
        };
        let middle = 0.5 * lower + 0.5 * upper;
        let scale = lower.abs().max(upper.abs());
        if !(upper - lower > MINIMUM_RELATIVE_WIDTH * scale && lower < middle && middle < upper) {
            return None;
        }
        Some(if along_u {
            (
                Bounds {
                    u_upper: middle,
                    ..self
                },
                Bounds {
                    u_lower: middle,
                    ..self
                },
            )
        } else {
            (
                Bounds {
                    v_upper: middle,
                    ..self
                },
                Bounds {
                    v_lower: middle,
                    ..self
                },
            )
        })
    }
}

/// A rectangle with its G7–K15 estimates.
#[derive(Debug, Clone, Copy)]
struct Region<const N: usize> {
    bounds: Bounds,
    value: [f64; N],
    /// The error estimate in force: the rule's, possibly raised by validation.
    error: [f64; N],
    /// The rounding floor $50\epsilon\\,Q\_{KK}[|f|]$ of each component.
    roundoff: [f64; N],
    /// $\max_i e_i$: the priority in the queue.
    error_norm: f64,
    /// Whether the error is larger along u than along v.
    split_along_u: bool,
}

impl<const N: usize> Region<N> {
    /// Raises the error of component `c` to at least `error`.
    fn raise_error(&mut self, c: usize, error: f64) {
        if error > self.error[c] {
            self.error[c] = error;
            self.error_norm = self.error_norm.max(error);
        }
    }

    /// Whether every component's error is at its rounding floor, so that bisecting cannot
    /// reduce it.
    fn limited_by_rounding(&self) -> bool {
        self.error
            .iter()
            .zip(&self.roundoff)
            .all(|(error, floor)| error <= floor)
    }
}

impl<const N: usize> PartialEq for Region<N> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl<const N: usize> Eq for Region<N> {}

impl<const N: usize> PartialOrd for Region<N> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<const N: usize> Ord for Region<N> {
    fn cmp(&self, other: &Self) -> Ordering {
        self.error_norm.total_cmp(&other.error_norm)
    }
}

/// The G7–K15 product rule on one rectangle (225 evaluations).
fn apply_rule<const N: usize, F>(
    bounds: Bounds,
    integrand: &mut F,
) -> Result<Region<N>, QuadratureError>
where
    F: FnMut(f64, f64, &mut [f64; N]),
{
    let u_middle = 0.5 * bounds.u_lower + 0.5 * bounds.u_upper;
    let u_half = 0.5 * (bounds.u_upper - bounds.u_lower);
    let v_middle = 0.5 * bounds.v_lower + 0.5 * bounds.v_upper;
    let v_half = 0.5 * (bounds.v_upper - bounds.v_lower);
    let us = KRONROD_15_NODES.map(|x| u_middle + u_half * x);
    let vs = KRONROD_15_NODES.map(|x| v_middle + v_half * x);

    // All 225 values are kept (on the stack) for the second pass over |f - mean|.
    let mut samples = [[[0.0; N]; 15]; 15];
    let mut kronrod_kronrod = [0.0; N];
    let mut gauss_kronrod = [0.0; N]; // Gauss in u, Kronrod in v
    let mut kronrod_gauss = [0.0; N]; // Kronrod in u, Gauss in v
    let mut gauss_gauss = [0.0; N];
    for (j, &v) in vs.iter().enumerate() {
        let mut row_kronrod = [0.0; N];
        let mut row_gauss = [0.0; N];
        for (i, &u) in us.iter().enumerate() {
            let values = &mut samples[j][i];
            integrand(u, v, values);
            for (component, &value) in values.iter().enumerate() {
                if !value.is_finite() {
                    return Err(QuadratureError::NonFiniteIntegrand {
                        u,
                        v,
                        component,
                        value,
                    });
                }
                row_kronrod[component] += KRONROD_15_WEIGHTS[i] * value;
            }
            if i % 2 == 1 {
                for (row, &value) in row_gauss.iter_mut().zip(values.iter()) {
                    *row += GAUSS_7_WEIGHTS[i / 2] * value;
                }
            }
        }
        for c in 0..N {
            kronrod_kronrod[c] += KRONROD_15_WEIGHTS[j] * row_kronrod[c];
            gauss_kronrod[c] += KRONROD_15_WEIGHTS[j] * row_gauss[c];
        }
        if j % 2 == 1 {
            for c in 0..N {
                kronrod_gauss[c] += GAUSS_7_WEIGHTS[j / 2] * row_kronrod[c];
                gauss_gauss[c] += GAUSS_7_WEIGHTS[j / 2] * row_gauss[c];
            }
        }
    }
    // Q[|f|] and Q[|f - mean|] on [-1, 1]^2 (the weights sum to 4 there).
    let mean = kronrod_kronrod.map(|sum| 0.25 * sum);
    let mut absolute = [0.0; N];
    let mut deviation = [0.0; N];
    for (row, &v_weight) in samples.iter().zip(&KRONROD_15_WEIGHTS) {
        for (values, &u_weight) in row.iter().zip(&KRONROD_15_WEIGHTS) {
            let weight = u_weight * v_weight;
            for c in 0..N {
                absolute[c] += weight * values[c].abs();
                deviation[c] += weight * (values[c] - mean[c]).abs();
            }
        }
    }

    let jacobian = u_half * v_half;
    let mut value = [0.0; N];
    let mut error = [0.0; N];
    let mut roundoff = [0.0; N];
    let (mut error_along_u, mut error_along_v) = (0.0_f64, 0.0_f64);
    for c in 0..N {
        value[c] = jacobian * kronrod_kronrod[c];
        let along_u = jacobian * (kronrod_kronrod[c] - gauss_kronrod[c]).abs();
        let along_v = jacobian * (kronrod_kronrod[c] - kronrod_gauss[c]).abs();
        let both = jacobian * (kronrod_kronrod[c] - gauss_gauss[c]).abs();
        let raw = both.max(along_u + along_v);
        let spread = jacobian * deviation[c];
        roundoff[c] = ROUNDOFF_FLOOR * jacobian * absolute[c];
        error[c] = raw.max(widened(raw, spread)).max(roundoff[c]);
        error_along_u = error_along_u.max(along_u);
        error_along_v = error_along_v.max(along_v);
    }
    let split_along_u = if error_along_u != error_along_v {
        error_along_u > error_along_v
    } else {
        // No preference from the estimates (e.g. both zero): halve the longer side in parameter
        // units.
        u_half >= v_half
    };
    Ok(Region {
        bounds,
        value,
        error,
        roundoff,
        error_norm: max_norm(&error),
        split_along_u,
    })
}
