//! Nested rules and a doubling tensor cubature whose error estimate costs no extra evaluation.
//!
//! A rule family is **nested** when every node of a level is a node of the next one. Then the
//! coarser level's value is a by-product of the finer level's evaluations (a different set of
//! weights on a subset of the same values), and the difference of the two is an error estimate
//! that costs nothing: the finer level is both the answer and its certificate.
//!
//! # The rules
//!
//! **Periodic trapezoid doubling** ([`NestedTrapezoid`]). Level $\ell$ has $N\_\ell = N_0 2^\ell$
//! nodes $\psi_j = a + jh\_\ell$, $h\_\ell = P/N\_\ell$, on one period; level $\ell + 1$ adds the
//! midpoints. An optional smooth periodic change of variables $\varphi(\psi)$ (for example a
//! clustering map) is applied once, at construction: the rule stores $\varphi(\psi_j)$ and the
//! factor $\varphi'(\psi_j)$, and
//! $$\int_a^{a+P} f(\varphi)\\,\mathrm d\varphi \approx h\_\ell\sum\_{j<N\_\ell} \varphi'(\psi_j)\\,f(\varphi(\psi_j)).$$
//! For $f$ analytic in a strip the error falls like $e^{-cN}$, so one doubling squares it
//! (roughly): the change between levels $\ell-1$ and $\ell$ is the error of level $\ell-1$, an
//! over-estimate of level $\ell$'s. The **half** variant keeps only the nodes of the first half
//! period $[a, a + P/2]$, end points with factor ½: for an integrand symmetric about
//! $a + P/2$ (as $f(\psi) = f(2a + P - \psi)$), the full-period value is twice the half sum.
//!
//! **Fejér's second rule doubling** ([`NestedFejer`]). On $[-1, 1]$, level $\ell$ has the
//! $n\_\ell - 1$ interior Chebyshev extrema $x_k = \cos(k\pi/n\_\ell)$, $n\_\ell = n_0 2^\ell$,
//! $k = 1, \dots, n\_\ell - 1$, with weights (Fejér 1933; Waldvogel, BIT 46, 2006)
//! $$w_k = \frac{4\sin\theta_k}{n}\sum\_{j=1}^{\lfloor n/2\rfloor}\frac{\sin\big((2j-1)\theta_k\big)}{2j-1},
//!   \qquad \theta_k = k\pi/n.$$
//! Doubling $n$ keeps every node ($k \to 2k$) and adds the odd $k$. The rule is interpolatory:
//! exact for polynomials of degree $\le n - 2$ (and $n - 1$ for even $n$, by symmetry), and it
//! converges geometrically for analytic integrands, at a rate close to Gauss–Legendre's for
//! integrands whose nearest singularity lies near an end point (Trefethen, SIAM Review 50, 2008).
//! Its nodes avoid the end points, where a surface parametrisation often degenerates (the
//! poles).
//!
//! # The cubature
//!
//! [`NestedCubature`] integrates $\int\\!\\!\int \mathbf f(\varphi, x)\\,\mathrm d\varphi\\,\mathrm dx$
//! ($N$ components at once) on the tensor grid of a [`NestedTrapezoid`] level $i$ and a
//! [`NestedFejer`] level $j$. It keeps, for every across node $x_k$, the raw sums
//! $S_k^{(i)} = \sum\_{m<N_i}\varphi'\_m f(\varphi_m, x_k)$ at levels $i$ and $i - 1$, so that three
//! values come from the same evaluations:
//! $$Q\_{i,j} = h_i\sum_k w^{(j)}\_k S^{(i)}\_k,\quad Q\_{i-1,j} = h\_{i-1}\sum_k w^{(j)}\_k S^{(i-1)}\_k,\quad
//!   Q\_{i,j-1} = h_i\sum\_{k} w^{(j-1)}\_k S^{(i)}\_k.$$
//! and likewise $Q\_{i-2,j}$ (a third set of line sums) and $Q\_{i,j-2}$. In each direction the
//! caller's norm measures the last two changes, $\delta_1 = \\|Q\_{\ell-1} - Q\_{\ell-2}\\|$ and
//! $\delta_2 = \\|Q\_\ell - Q\_{\ell-1}\\|$, and the error of $Q\_\ell$ is estimated by
//! $\delta_2^2/\delta_1$ ([`rate_estimate`]): the next doubling is assumed to shrink the error
//! at least as much as the last one did, true with a wide margin under geometric convergence.
//! While the larger estimate exceeds the tolerance, that direction is doubled (every earlier
//! evaluation is kept). $Q\_{i,j}$ is returned. The integrand is asked for **line sums**: the sum over a range of
//! periodic nodes (in nested order) on one across node, so a caller can hoist what depends on
//! the across coordinate only out of the inner loop.

use crate::rule::Interval;
use crate::QuadratureError;
use std::ops::Range;

/// Largest number of doublings a nested rule may be built with.
pub const MAX_NESTED_LEVELS: usize = 12;

/// Largest node count of a level of a [`NestedFejer`] rule ($n\_\ell \le$ this).
pub const MAX_FEJER_SUBDIVISIONS: usize = 4096;

/// The periodic trapezoid rule under doubling, nodes in nested order (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct NestedTrapezoid {
    interval: Interval,
    base: usize,
    levels: usize,
    half: bool,
    /// $\psi_j$ in nested order.
    parameters: Vec<f64>,
    /// $\varphi(\psi_j)$.
    nodes: Vec<f64>,
    /// $\varphi'(\psi_j)$ times ½ at the end points of a half rule.
    factors: Vec<f64>,
}

impl NestedTrapezoid {
    /// The plain rule on `[start, start + period)` with `base` nodes at level 0 and levels
    /// `0..=levels`; `half` keeps the first half period (then `base` must be even).
    ///
    /// # Errors
    /// [`QuadratureError::ZeroOrder`] for `base == 0`; [`QuadratureError::InvalidNesting`] for an
    /// odd `base` with `half`, or more than [`MAX_NESTED_LEVELS`] levels;
    /// [`QuadratureError::InvalidPeriod`] for a period that is not positive and finite.
    pub fn new(
        base: usize,
        levels: usize,
        start: f64,
        period: f64,
        half: bool,
    ) -> Result<Self, QuadratureError> {
        Self::with_map(base, levels, start, period, half, |psi| (psi, 1.0))
    }

    /// As [`Self::new`], after the change of variables `map`: $\psi \mapsto (\varphi(\psi),
    /// \varphi'(\psi))$, a smooth bijection of the period onto itself with
    /// $\varphi(a) = a$ (and $\varphi(a + P/2) = a + P/2$ for a half rule).
    ///
    /// # Errors
    /// As [`Self::new`]; [`QuadratureError::NonFiniteIntegral`] if the map returns a
    /// non-finite value.
    pub fn with_map<M: Fn(f64) -> (f64, f64)>(
        base: usize,
        levels: usize,
        start: f64,
        period: f64,
        half: bool,
        map: M,
    ) -> Result<Self, QuadratureError> {
        if base == 0 {
            return Err(QuadratureError::ZeroOrder);
        }
        if levels > MAX_NESTED_LEVELS || (half && base % 2 == 1) {
            return Err(QuadratureError::InvalidNesting {
                base,
                levels,
                maximum: MAX_NESTED_LEVELS,
            });
        }
        if !(period.is_finite() && period > 0.0) {
            return Err(QuadratureError::InvalidPeriod { start, period });
        }
        let interval = Interval::new(start, start + period)?;
        let finest = base << levels;
        // Nodes as multiples m of the finest step, in nested order.
        let mut multiples: Vec<usize> = Vec::new();
        let stride0 = 1usize << levels;
        let limit0 = if half { base / 2 } else { base - 1 };
        multiples.extend((0..=limit0).map(|j| j * stride0));
        for level in 1..=levels {
            let stride = 1usize << (levels - level);
            let count = base << level;
            let upper = if half { count / 2 } else { count };
            multiples.extend((1..upper).step_by(2).map(|j| j * stride));
        }
        let h = period / finest as f64;
        let mut parameters = Vec::with_capacity(multiples.len());
        let mut nodes = Vec::with_capacity(multiples.len());
        let mut factors = Vec::with_capacity(multiples.len());
        for &m in &multiples {
            let psi = start + m as f64 * h;
            let (phi, derivative) = map(psi);
            if !(phi.is_finite() && derivative.is_finite()) {
                return Err(QuadratureError::NonFiniteIntegral);
            }
            let end = half && (m == 0 || 2 * m == finest);
            parameters.push(psi);
            nodes.push(phi);
            factors.push(if end { 0.5 * derivative } else { derivative });
        }
        Ok(Self {
            interval,
            base,
            levels,
            half,
            parameters,
            nodes,
            factors,
        })
    }

    /// The number of levels above level 0.
    pub fn levels(&self) -> usize {
        self.levels
    }

    /// Nodes of level 0 over a full period.
    pub fn base(&self) -> usize {
        self.base
    }

    /// Whether only the first half period is kept.
    pub fn is_half(&self) -> bool {
        self.half
    }

    /// The period's interval.
    pub fn interval(&self) -> Interval {
        self.interval
    }

    /// Number of stored nodes of `level` (the first ones in nested order).
    pub fn count(&self, level: usize) -> usize {
        let full = self.base << level.min(self.levels);
        if self.half {
            full / 2 + 1
        } else {
            full
        }
    }

    /// The step $h\_\ell = P/N\_\ell$ that multiplies the sum at `level`.
    pub fn step(&self, level: usize) -> f64 {
        self.interval.length() / (self.base << level.min(self.levels)) as f64
    }

    /// $\varphi(\psi_j)$, in nested order.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// $\psi_j$ (before the map), in nested order.
    pub fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    /// $\varphi'(\psi_j)$ (halved at a half rule's end points), in nested order.
    pub fn factors(&self) -> &[f64] {
        &self.factors
    }
}

/// Fejér's second rule on an interval under doubling, nodes in nested order, weights per
/// level (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct NestedFejer {
    interval: Interval,
    base: usize,
    levels: usize,
    nodes: Vec<f64>,
    /// `weights[level][k]` for the first `count(level)` nodes.
    weights: Vec<Vec<f64>>,
}

impl NestedFejer {
    /// The rule on `interval` with $n_0 =$ `base` subdivisions at level 0 ($n_0 - 1$ nodes) and
    /// levels `0..=levels`.
    ///
    /// # Errors
    /// [`QuadratureError::InvalidNesting`] for `base < 2`, more than [`MAX_NESTED_LEVELS`]
    /// levels, or a finest level above [`MAX_FEJER_SUBDIVISIONS`].
    pub fn new(base: usize, levels: usize, interval: Interval) -> Result<Self, QuadratureError> {
        if base < 2 || levels > MAX_NESTED_LEVELS || (base << levels) > MAX_FEJER_SUBDIVISIONS {
            return Err(QuadratureError::InvalidNesting {
                base,
                levels,
                maximum: MAX_NESTED_LEVELS,
            });
        }
        let finest = base << levels;
        let mut multiples: Vec<usize> = (1..base).map(|k| k << levels).collect();
        for level in 1..=levels {
            let stride = 1usize << (levels - level);
            multiples.extend((1..(base << level)).step_by(2).map(|k| k * stride));
        }
        let mid = interval.midpoint();
        let half = interval.half_width();
        let nodes: Vec<f64> = multiples
            .iter()
            .map(|&m| {
                let x = (std::f64::consts::PI * m as f64 / finest as f64).cos();
                (mid + half * x).clamp(interval.start(), interval.end())
            })
            .collect();
        let mut weights = Vec::with_capacity(levels + 1);
        for level in 0..=levels {
            let n = base << level;
            let count = n - 1;
            let stride = 1usize << (levels - level);
            let w: Vec<f64> = multiples[..count]
                .iter()
                .map(|&m| half * fejer_weight(n, m / stride))
                .collect();
            weights.push(w);
        }
        Ok(Self {
            interval,
            base,
            levels,
            nodes,
            weights,
        })
    }

    /// The number of levels above level 0.
    pub fn levels(&self) -> usize {
        self.levels
    }

    /// Subdivisions $n_0$ of level 0.
    pub fn base(&self) -> usize {
        self.base
    }

    /// The interval.
    pub fn interval(&self) -> Interval {
        self.interval
    }

    /// Number of nodes of `level`, $n_0 2^\ell - 1$ (the first ones in nested order).
    pub fn count(&self, level: usize) -> usize {
        (self.base << level.min(self.levels)) - 1
    }

    /// All nodes, in nested order.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// The weights of `level` for its [`Self::count`] nodes.
    pub fn weights(&self, level: usize) -> &[f64] {
        &self.weights[level.min(self.levels)]
    }
}

/// Fejér's second-rule weight of node $k$ of the $n$-subdivision rule on $[-1, 1]$, the sum
/// done by rotating $e^{i(2j-1)\theta}$ (rounding grows like $\sqrt n\\,\epsilon$).
fn fejer_weight(n: usize, k: usize) -> f64 {
    let theta = std::f64::consts::PI * k as f64 / n as f64;
    let (s1, c1) = theta.sin_cos();
    let (s2, c2) = (2.0 * theta).sin_cos();
    let (mut s, mut c) = (s1, c1);
    let mut sum = 0.0;
    for j in 1..=n / 2 {
        sum += s / (2 * j - 1) as f64;
        // Every 32 terms, recompute exactly to stop the recurrence's drift.
        if j % 32 == 0 {
            let angle = (2 * j + 1) as f64 * theta;
            (s, c) = angle.sin_cos();
        } else {
            (s, c) = (s * c2 + c * s2, c * c2 - s * s2);
        }
    }
    4.0 * s1 * sum / n as f64
}

/// A nested tensor grid: the periodic direction and the direction across.
#[derive(Debug, Clone, PartialEq)]
pub struct NestedTensorRule {
    /// The periodic (azimuth) rule.
    pub periodic: NestedTrapezoid,
    /// The rule across.
    pub across: NestedFejer,
}

/// Levels of a [`NestedTensorRule`] (each at least 2, so that two coarser levels exist).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NestedLevels {
    /// Level of the periodic rule.
    pub periodic: usize,
    /// Level of the rule across.
    pub across: usize,
}

/// The result of a [`NestedCubature`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NestedEstimate<const N: usize> {
    /// $Q\_{i,j}$.
    pub value: [f64; N],
    /// $|Q\_{i,j} - Q\_{i-1,j}|$ per component.
    pub periodic_change: [f64; N],
    /// $|Q\_{i,j} - Q\_{i,j-1}|$ per component.
    pub across_change: [f64; N],
    /// The estimated error of $Q\_{i,j}$ in the caller's norm (the larger direction's).
    pub error_estimate: f64,
    /// Integrand evaluations (as counted by the line sums).
    pub evaluations: usize,
    /// The levels of the returned value.
    pub levels: NestedLevels,
    /// Whether the estimate met the tolerance.
    pub converged: bool,
}

/// The error estimate of the finest of three nested levels from the changes
/// $\delta_1 = \\|Q\_{\ell-1} - Q\_{\ell-2}\\|$ and $\delta_2 = \\|Q\_\ell - Q\_{\ell-1}\\|$:
/// $$ e = \delta_2^2/\delta_1 \quad (\text{and } e = \delta_2 \text{ if } \delta_1 = \delta_2 = 0 \text{, else } +\infty \text{ if } \delta_1 = 0).$$
/// It assumes only that the next doubling shrinks the error at least as much as the last one
/// did ($e\_\ell/e\_{\ell-1} \le e\_{\ell-1}/e\_{\ell-2}$), which holds for algebraic convergence
/// (equality) and with a wide margin for geometric convergence, where each doubling squares
/// the error (then the true error is $\approx\delta_2^3/\delta_1^2$). A change that grows
/// ($\delta_2 > \delta_1$: not yet converging) gives $e > \delta_2$.
pub fn rate_estimate(coarser_change: f64, change: f64) -> f64 {
    if change == 0.0 {
        0.0
    } else if coarser_change > 0.0 {
        change * (change / coarser_change)
    } else {
        f64::INFINITY
    }
}

/// The error estimate of the finest of three nested levels when the convergence is known to be
/// geometric in the node count (an integrand analytic in a wide strip or Bernstein ellipse,
/// such as a far body's field): with $e\_\ell \approx C\rho^{-n\_\ell}$ and $n\_\ell$ doubling,
/// $\delta_1 \approx e\_{\ell-2}$, $\delta_2 \approx e\_{\ell-1}$ and
/// $e\_\ell \approx \delta_2\\,(\delta_2/\delta_1)^2$; returned (edge cases as
/// [`rate_estimate`]) is
/// $$ e = \delta_2\\,(\delta_2/\delta_1)^{p}, $$
/// with the caller's exponent $1 \le p \le 2$: $p = 1$ is [`rate_estimate`]; $p < 2$ keeps a
/// margin for a prefactor $C$ that grows with the level. Only as honest as the assumption: a
/// caller must show, by tests over its integrands, that the true error stays below it.
pub fn geometric_estimate(coarser_change: f64, change: f64, exponent: f64) -> f64 {
    if change == 0.0 {
        0.0
    } else if coarser_change > 0.0 {
        let ratio = change / coarser_change;
        // A change that does not shrink: no faster than the matched estimate.
        let p = if ratio < 1.0 {
            exponent.clamp(1.0, 2.0)
        } else {
            1.0
        };
        change * ratio.powf(p)
    } else {
        f64::INFINITY
    }
}

/// The doubling cubature's workspace (raw line sums at three periodic levels), reused across
/// calls: after the first calls at a given size it allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct NestedCubature<const N: usize> {
    /// Level i, i - 1 and i - 2 line sums.
    lines: [Vec<[f64; N]>; 3],
}

fn weighted<const N: usize>(lines: &[[f64; N]], weights: &[f64], step: f64) -> [f64; N] {
    let mut q = [0.0; N];
    for (line, &w) in lines.iter().zip(weights) {
        for (q, &s) in q.iter_mut().zip(line) {
            *q += w * s;
        }
    }
    q.map(|x| x * step)
}

fn change<const N: usize>(a: &[f64; N], b: &[f64; N]) -> [f64; N] {
    let mut d = [0.0; N];
    for ((d, &a), &b) in d.iter_mut().zip(a).zip(b) {
        *d = (a - b).abs();
    }
    d
}

impl<const N: usize> NestedCubature<N> {
    /// Appends lines `lines` at periodic level `i`, keeping the level `i - 1` and `i - 2`
    /// partial sums.
    fn add_lines<L>(
        &mut self,
        p: &NestedTrapezoid,
        lines: Range<usize>,
        i: usize,
        line: &mut L,
    ) -> usize
    where
        L: FnMut(usize, usize, &[usize], &mut [[f64; N]]) -> usize,
    {
        let mut spent = 0;
        let ends = [p.count(i - 2), p.count(i - 1), p.count(i)];
        for k in lines {
            let mut sums = [[0.0; N]; 3];
            spent += line(k, 0, &ends, &mut sums);
            let [coarser, coarse, fine] = sums;
            self.lines[0].push(fine);
            self.lines[1].push(coarse);
            self.lines[2].push(coarser);
        }
        spent
    }

    /// An empty workspace.
    pub fn new() -> Self {
        Self {
            lines: [Vec::new(), Vec::new(), Vec::new()],
        }
    }

    /// Integrates from the levels `start` (clamped to `2..=` the rule's levels), doubling a
    /// direction, within `max_evaluations`, while the error estimate of either direction
    /// exceeds `tolerance`. A direction's estimate is [`rate_estimate`] of its last two
    /// changes, each measured by `norm(finer, coarser)`, the caller's relative distance
    /// between two values (return 0 for values equal to rounding). The direction with the
    /// larger estimate is doubled.
    ///
    /// `line(k, range, out)` must **add** to `out` the sum over periodic nodes `m` in `range`
    /// (indices into [`NestedTrapezoid::nodes`]) of `factors()[m]` times the integrand at
    /// (`periodic.nodes()[m]`, `across.nodes()[k]`), and return the number of integrand
    /// evaluations it spent.
    ///
    /// # Errors
    /// [`QuadratureError::NonFiniteIntegral`] when a line sum is not finite;
    /// [`QuadratureError::InvalidNesting`] when a rule has fewer than 2 levels.
    pub fn integrate<L, E>(
        &mut self,
        rule: &NestedTensorRule,
        start: NestedLevels,
        tolerance: f64,
        max_evaluations: usize,
        line: L,
        norm: E,
    ) -> Result<NestedEstimate<N>, QuadratureError>
    where
        L: FnMut(usize, Range<usize>, &mut [f64; N]) -> usize,
        E: FnMut(&[f64; N], &[f64; N]) -> f64,
    {
        self.integrate_with(
            rule,
            start,
            tolerance,
            max_evaluations,
            line,
            norm,
            rate_estimate,
        )
    }

    /// As [`Self::integrate`], with the error estimate of a direction from its last two
    /// changes given by `estimate(δ₁, δ₂)` instead of [`rate_estimate`] (for example
    /// [`geometric_estimate`] where the integrand is known to converge geometrically).
    ///
    /// # Errors
    /// As [`Self::integrate`].
    #[allow(clippy::too_many_arguments)]
    pub fn integrate_with<L, E, R>(
        &mut self,
        rule: &NestedTensorRule,
        start: NestedLevels,
        tolerance: f64,
        max_evaluations: usize,
        mut line: L,
        mut norm: E,
        estimate_of: R,
    ) -> Result<NestedEstimate<N>, QuadratureError>
    where
        L: FnMut(usize, Range<usize>, &mut [f64; N]) -> usize,
        E: FnMut(&[f64; N], &[f64; N]) -> f64,
        R: Fn(f64, f64) -> f64,
    {
        self.integrate_converted(
            rule,
            start,
            tolerance,
            max_evaluations,
            |k: usize, start: usize, ends: &[usize], outs: &mut [[f64; N]]| {
                if let ([end], [out]) = (ends, &mut *outs) {
                    return line(k, start..*end, out);
                }
                // The running sum continues from segment to segment, as the line would be
                // summed in one pass.
                let mut running = [0.0; N];
                let mut spent = 0;
                let mut from = start;
                for (&end, out) in ends.iter().zip(outs) {
                    spent += line(k, from..end, &mut running);
                    for (o, &r) in out.iter_mut().zip(&running) {
                        *o += r;
                    }
                    from = end;
                }
                spent
            },
            |_: &[f64; N]| (),
            |a: &[f64; N], b: &[f64; N], _: &(), _: &()| norm(a, b),
            estimate_of,
        )
        .map(|(estimate, ())| estimate)
    }

    /// As [`Self::integrate_with`], with each level's value turned by `convert` into the
    /// caller's form (for example physical quantities in another frame) once per iteration,
    /// and the changes measured by `norm(finer, coarser, converted finer, converted coarser)`:
    /// five conversions on the first iteration (the value and the two coarser levels in each
    /// direction) and three after a doubling (two of the five are the last iteration's),
    /// instead of two per `norm` call, for a caller whose conversion costs more than the norm.
    /// Returns the estimate and the converted value.
    ///
    /// The integrand is asked for **nested line sums**: `line(k, start, ends, outs)` must add
    /// to `outs[s]` the sum over periodic nodes `start..ends[s]` (`ends` increasing) of
    /// `factors()[m]` times the integrand at (`periodic.nodes()[m]`, `across.nodes()[k]`), and
    /// return the evaluations spent: a new line's three periodic levels come from one call, so
    /// a caller can evaluate the whole line before summing.
    ///
    /// # Errors
    /// As [`Self::integrate`].
    #[allow(clippy::too_many_arguments)]
    pub fn integrate_converted<L, C, V, E, R>(
        &mut self,
        rule: &NestedTensorRule,
        start: NestedLevels,
        tolerance: f64,
        max_evaluations: usize,
        mut line: L,
        mut convert: C,
        mut norm: E,
        estimate_of: R,
    ) -> Result<(NestedEstimate<N>, V), QuadratureError>
    where
        L: FnMut(usize, usize, &[usize], &mut [[f64; N]]) -> usize,
        C: FnMut(&[f64; N]) -> V,
        E: FnMut(&[f64; N], &[f64; N], &V, &V) -> f64,
        R: Fn(f64, f64) -> f64,
    {
        let (p, a) = (&rule.periodic, &rule.across);
        for (base, levels) in [(p.base(), p.levels()), (a.base(), a.levels())] {
            if levels < 2 {
                return Err(QuadratureError::InvalidNesting {
                    base,
                    levels,
                    maximum: MAX_NESTED_LEVELS,
                });
            }
        }
        let mut i = start.periodic.clamp(2, p.levels());
        let mut j = start.across.clamp(2, a.levels());
        for lines in &mut self.lines {
            lines.clear();
        }
        let mut evaluations = self.add_lines(p, 0..a.count(j), i, &mut line);
        // After a doubling, the two coarser levels in the doubled direction are the last
        // iteration's value and its first coarser level, bit for bit (the same line sums and
        // weights): their conversions are carried over.
        let mut carried: Option<(bool, V, V)> = None;
        loop {
            if self.lines[0].iter().flatten().any(|x| !x.is_finite()) {
                return Err(QuadratureError::NonFiniteIntegral);
            }
            let fine = &self.lines[0];
            let value = weighted(fine, a.weights(j), p.step(i));
            let periodic_1 = weighted(&self.lines[1], a.weights(j), p.step(i - 1));
            let periodic_2 = weighted(&self.lines[2], a.weights(j), p.step(i - 2));
            let across_1 = weighted(fine, a.weights(j - 1), p.step(i));
            let across_2 = weighted(fine, a.weights(j - 2), p.step(i));
            let v = convert(&value);
            let (p1, p2, a1, a2) = match carried.take() {
                Some((true, old_value, old_periodic_1)) => (
                    old_value,
                    old_periodic_1,
                    convert(&across_1),
                    convert(&across_2),
                ),
                Some((false, old_value, old_across_1)) => (
                    convert(&periodic_1),
                    convert(&periodic_2),
                    old_value,
                    old_across_1,
                ),
                None => (
                    convert(&periodic_1),
                    convert(&periodic_2),
                    convert(&across_1),
                    convert(&across_2),
                ),
            };
            let ep = estimate_of(
                norm(&periodic_1, &periodic_2, &p1, &p2),
                norm(&value, &periodic_1, &v, &p1),
            );
            let ea = estimate_of(
                norm(&across_1, &across_2, &a1, &a2),
                norm(&value, &across_1, &v, &a1),
            );
            let estimate = ep.max(ea);
            let result = |converged| NestedEstimate {
                value,
                periodic_change: change(&value, &periodic_1),
                across_change: change(&value, &across_1),
                error_estimate: estimate,
                evaluations,
                levels: NestedLevels {
                    periodic: i,
                    across: j,
                },
                converged,
            };
            if estimate <= tolerance {
                return Ok((result(true), v));
            }
            let can_p = i < p.levels();
            let can_a = j < a.levels();
            let refine_periodic = match (can_p, can_a) {
                (false, false) => return Ok((result(false), v)),
                (true, false) => true,
                (false, true) => false,
                (true, true) => ep >= ea,
            };
            // The doubling's cost at the evaluations per node seen so far (a caller may
            // evaluate mirrored lines).
            let per_node = evaluations as f64 / (p.count(i) * a.count(j)).max(1) as f64;
            let new_nodes = if refine_periodic {
                (p.count(i + 1) - p.count(i)) * a.count(j)
            } else {
                (a.count(j + 1) - a.count(j)) * p.count(i)
            };
            if evaluations as f64 + new_nodes as f64 * per_node > max_evaluations as f64 {
                return Ok((result(false), v));
            }
            carried = Some(if refine_periodic {
                (true, v, p1)
            } else {
                (false, v, a1)
            });
            if refine_periodic {
                let range = p.count(i)..p.count(i + 1);
                let [fine, coarse, coarser] = &mut self.lines;
                for (k, ((f, c), cc)) in fine
                    .iter_mut()
                    .zip(coarse.iter_mut())
                    .zip(coarser.iter_mut())
                    .enumerate()
                {
                    *cc = *c;
                    *c = *f;
                    evaluations += line(k, range.start, &[range.end], std::slice::from_mut(f));
                }
                i += 1;
            } else {
                evaluations += self.add_lines(p, a.count(j)..a.count(j + 1), i, &mut line);
                j += 1;
            }
        }
    }
}
