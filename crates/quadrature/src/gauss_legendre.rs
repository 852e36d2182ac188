//! Gauss–Legendre rules of any order.
//!
//! The $n$-point rule on $[-1, 1]$ has as nodes the roots $x_1 > \dots > x_n$ of the Legendre
//! polynomial $P_n$ and the weights
//! $$w_k = \frac{2}{(1 - x_k^2)\\,P_n'(x_k)^2} = \frac{2}{\bigl(\mathrm dP_n(\cos\theta)/\mathrm d\theta\bigr)^2\_{\theta=\theta_k}},
//! \qquad x_k = \cos\theta_k,$$
//! and integrates every polynomial of degree $\le 2n - 1$ exactly. On $[a, b]$ the nodes are
//! $m + h x_k$ and the weights $h w_k$, with $m = (a + b)/2$ and $h = (b - a)/2$.
//!
//! # Algorithm
//!
//! Only the $\lceil n/2 \rceil$ non-negative roots are computed; the rule is symmetric
//! ($x\_{n+1-k} = -x_k$, equal weights) by construction, and $x = 0$ is a node of weight
//! $2/(n P\_{n-1}(0))^2$ when $n$ is odd. Each root starts from the asymptotic estimate
//! (Tricomi; Szegő, *Orthogonal Polynomials*, §6.3)
//! $$\theta_k \approx \psi_k + \frac{\cot\psi_k}{8\\,(n + \tfrac12)^2}, \qquad
//! \psi_k = \frac{(k - \tfrac14)\\,\pi}{n + \tfrac12},$$
//! and is polished by Newton's method on $P_n$, evaluated by its three-term recurrence
//! $(k+1) P\_{k+1} = (2k+1)\\,x P_k - k P\_{k-1}$ ($O(n)$ per evaluation, $O(n^2)$ per rule).
//!
//! Where the rounding of $x$ would spoil the result, the work is done in a better variable:
//!
//! - **Roots with $x > 1/2$** ($\theta < \pi/3$) are found in $\theta$. A node within
//!   $\delta$ of $1$ is only known to an absolute $\epsilon$ in $x$, i.e. to a relative
//!   $\epsilon/\delta$ in $1 - x$, and the weight formula in $x$ amplifies that error by
//!   $2x/(1 - x^2) \sim n^2$ near the ends. Here $t = 1 - x = 2\sin^2(\theta/2)$ is formed to
//!   full relative precision and $P_n$ is evaluated by Reinsch's form of the recurrence for
//!   $D_k = P_k - P\_{k-1}$:
//!   $$(k+1)\\,D\_{k+1} = k D_k - (2k+1)\\,t P_k, \qquad P\_{k+1} = P_k + D\_{k+1},$$
//!   $P_1 = 1 - t$, $D_1 = -t$, with $\mathrm dP_n/\mathrm d\theta = -n\\,(t P_n - D_n)/\sin\theta$.
//! - **Roots with $x \le 1/2$** are found in $x$ itself (a node near $0$ has full relative
//!   precision as a float), with $P_n'(x) = n\\,(x P_n - P\_{n-1})/(x^2 - 1)$.
//!
//! **Last step in twice the precision.** The rounding errors of the recurrence accumulate like
//! $\sqrt n\\,\epsilon$ (about 80 ULP in the weights at $n = 1000$ in plain arithmetic). So, once
//! Newton has converged to $10^{-12}$, $P_n$ and $P\_{n-1}$ (or $D_n$) are evaluated once more
//! by a *compensated* recurrence, in which every rounding error is captured by an error-free
//! transformation and carried in a second sequence (as Graillat, Langlois and Louvet's
//! compensated Horner scheme). With $g = P\_{n-1} - x P_n$ and $s = 1 - x^2$ (in $t$:
//! $g = tP_n - D_n$, $s = t(2 - t)$), all in double-double arithmetic, the last Newton step is
//! $\delta x = -P_n s/(n g)$, and the weight $F(x) = 2 s/(n g)^2$, computed at the float $x$, is
//! moved to the root $x + \delta x$ by its logarithmic derivative,
//! $\mathrm d\ln F/\mathrm dx = -2x/s$ (it is stationary in $P_n$ at a root, so only this
//! first-order term matters). Nodes and weights come out correctly rounded in every case
//! tested (orders 1 to 1000, see [`crate::tolerance::GAUSS_LEGENDRE_NODE_ULP`]).
//!
//! **Cost.** $O(n^2)$ operations, four roots at a time for instruction-level parallelism
//! (`examples/timings.rs` times it). A rule is built once and reused.

use crate::rule::{Interval, Rule1D};
use crate::twofold::{split, two_product_small_integer, two_product_split, two_sum, TwoFold};
use crate::QuadratureError;
use std::f64::consts::PI;

/// The largest order [`GaussLegendre::new`] accepts. Construction costs $O(n^2)$ operations
/// (a million times more at this maximum than at $n = 20$); beyond a few hundred points,
/// panels of lower order are usually the better rule.
pub const MAX_GAUSS_LEGENDRE_ORDER: usize = 20_000;

/// Plain Newton stops after a step below this fraction of the variable's scale: by quadratic
/// convergence (error after a step $s$ about $s^2/2$ relative) the point is then within
/// $10^{-12}$ of the root, and the final compensated step lands within rounding of it.
const NEWTON_RELATIVE_STEP: f64 = 1e-6;
/// Newton iterations allowed per root before giving up (a defect, reported as an error).
const NEWTON_MAX_ITERATIONS: usize = 40;

/// The $n$-point Gauss–Legendre rule on $[a, b]$, exact for polynomials of degree $\le 2n-1$.
///
/// Nodes are stored in increasing order; symmetric nodes have bit-identical weights.
#[derive(Debug, Clone, PartialEq)]
pub struct GaussLegendre {
    interval: Interval,
    standard_nodes: Vec<f64>,
    standard_weights: Vec<f64>,
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// The rule of `order` points on `[lower, upper]`.
    ///
    /// # Errors
    /// [`QuadratureError::ZeroOrder`] for `order == 0`, [`QuadratureError::OrderTooLarge`] above
    /// [`MAX_GAUSS_LEGENDRE_ORDER`], [`QuadratureError::InvalidInterval`] for a bad interval.
    pub fn new(order: usize, lower: f64, upper: f64) -> Result<Self, QuadratureError> {
        let interval = Interval::new(lower, upper)?;
        Self::on_interval(order, interval)
    }

    /// The rule of `order` points on $[-1, 1]$.
    ///
    /// # Errors
    /// As [`GaussLegendre::new`].
    pub fn standard(order: usize) -> Result<Self, QuadratureError> {
        Self::on_interval(order, Interval::SYMMETRIC_UNIT)
    }

    /// The rule of `order` points on `interval`.
    ///
    /// # Errors
    /// As [`GaussLegendre::new`].
    pub fn on_interval(order: usize, interval: Interval) -> Result<Self, QuadratureError> {
        if order == 0 {
            return Err(QuadratureError::ZeroOrder);
        }
        if order > MAX_GAUSS_LEGENDRE_ORDER {
            return Err(QuadratureError::OrderTooLarge {
                order,
                maximum: MAX_GAUSS_LEGENDRE_ORDER,
            });
        }
        let (half_nodes, half_weights) = non_negative_roots(order)?;
        let mut standard_nodes = Vec::with_capacity(order);
        let mut standard_weights = Vec::with_capacity(order);
        // Negative half: mirror the positive roots (largest magnitude first).
        for (&x, &w) in half_nodes.iter().zip(&half_weights).rev() {
            if x > 0.0 {
                standard_nodes.push(-x);
                standard_weights.push(w);
            }
        }
        for (&x, &w) in half_nodes.iter().zip(&half_weights) {
            standard_nodes.push(x);
            standard_weights.push(w);
        }
        let mut rule = GaussLegendre {
            interval,
            nodes: Vec::new(),
            weights: Vec::new(),
            standard_nodes,
            standard_weights,
        };
        rule.map_to(interval);
        Ok(rule)
    }

    /// The same rule moved to another interval, without recomputing the Legendre roots.
    pub fn mapped_to(&self, interval: Interval) -> Self {
        let mut rule = self.clone();
        rule.map_to(interval);
        rule
    }

    /// The number of points $n$.
    pub fn order(&self) -> usize {
        self.standard_nodes.len()
    }

    /// The nodes on $[-1, 1]$, increasing.
    pub fn standard_nodes(&self) -> &[f64] {
        &self.standard_nodes
    }

    /// The weights on $[-1, 1]$ (summing to 2).
    pub fn standard_weights(&self) -> &[f64] {
        &self.standard_weights
    }

    fn map_to(&mut self, interval: Interval) {
        let (midpoint, half_width) = (interval.midpoint(), interval.half_width());
        self.interval = interval;
        self.nodes.clear();
        self.weights.clear();
        for (&x, &w) in self.standard_nodes.iter().zip(&self.standard_weights) {
            // Clamp: rounding of midpoint + half_width * x must not leave [a, b].
            let node = (midpoint + half_width * x).clamp(interval.start(), interval.end());
            self.nodes.push(node);
            self.weights.push(half_width * w);
        }
    }
}

impl Rule1D for GaussLegendre {
    fn interval(&self) -> Interval {
        self.interval
    }

    fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    fn weights(&self) -> &[f64] {
        &self.weights
    }
}

/// Roots polished together, for instruction-level parallelism in the recurrences.
const LANES: usize = 4;

/// The non-negative roots of $P_n$ in increasing order, with their weights on $[-1, 1]$.
fn non_negative_roots(order: usize) -> Result<(Vec<f64>, Vec<f64>), QuadratureError> {
    let pairs = order / 2;
    let nu = order as f64 + 0.5;
    // Initial estimates θ_k, k = 1..pairs (decreasing x).
    let guesses: Vec<f64> = (1..=pairs)
        .map(|k| {
            let psi = (k as f64 - 0.25) * PI / nu;
            psi + 1.0 / (8.0 * nu * nu * psi.tan())
        })
        .collect();
    let near_one = guesses.partition_point(|&theta| theta < PI / 3.0);
    let coefficients = Recurrence::new(order);
    let mut nodes = Vec::with_capacity(order.div_ceil(2));
    let mut weights = Vec::with_capacity(order.div_ceil(2));
    for (chunk_index, chunk) in guesses[..near_one].chunks(LANES).enumerate() {
        let thetas = padded(chunk);
        let thetas = newton_in_theta(&coefficients, thetas).ok_or(
            QuadratureError::LegendreRootNotConverged {
                order,
                root_index: chunk_index * LANES + 1,
            },
        )?;
        for &(node, weight) in &polish_near_one(&coefficients, thetas)[..chunk.len()] {
            nodes.push(node);
            weights.push(weight);
        }
    }
    for (chunk_index, chunk) in guesses[near_one..].chunks(LANES).enumerate() {
        let xs = padded(chunk).map(f64::cos);
        let xs =
            newton_in_x(&coefficients, xs).ok_or(QuadratureError::LegendreRootNotConverged {
                order,
                root_index: near_one + chunk_index * LANES + 1,
            })?;
        for &(node, weight) in &polish_in_x(&coefficients, xs)[..chunk.len()] {
            nodes.push(node);
            weights.push(weight);
        }
    }
    if order % 2 == 1 {
        // x = 0 is a root: P_n(0) = 0 exactly in the recurrence, and P_n'(0) = n P_{n-1}(0).
        let (node, weight) = polish_in_x(&coefficients, [0.0; LANES])[0];
        nodes.push(node);
        weights.push(weight);
    }
    nodes.reverse();
    weights.reverse();
    Ok((nodes, weights))
}

/// The first `LANES` entries of `chunk`, the last one repeated to fill the lanes.
fn padded(chunk: &[f64]) -> [f64; LANES] {
    let mut lanes = [chunk[chunk.len() - 1]; LANES];
    lanes[..chunk.len()].copy_from_slice(chunk);
    lanes
}

/// The coefficients of the recurrence, $k = 1, \dots, n-1$:
/// $P\_{k+1} = \alpha_k x P_k - \beta_k P\_{k-1}$ with $\alpha_k = (2k+1)/(k+1)$,
/// $\beta_k = k/(k+1)$, and $1/(k+1)$ for the compensated form.
struct Recurrence {
    order: usize,
    alpha: Vec<f64>,
    beta: Vec<f64>,
    reciprocal: Vec<f64>,
}

impl Recurrence {
    fn new(order: usize) -> Self {
        let steps = 1..order;
        Recurrence {
            order,
            alpha: steps
                .clone()
                .map(|k| (2 * k + 1) as f64 / (k + 1) as f64)
                .collect(),
            beta: steps.clone().map(|k| k as f64 / (k + 1) as f64).collect(),
            reciprocal: steps.map(|k| 1.0 / (k + 1) as f64).collect(),
        }
    }
}

/// Newton's method in $\theta$ on several roots at once, with the plain Reinsch recurrence.
fn newton_in_theta(coefficients: &Recurrence, mut thetas: [f64; LANES]) -> Option<[f64; LANES]> {
    let n = coefficients.order as f64;
    for _ in 0..NEWTON_MAX_ITERATIONS {
        let mut t = [0.0; LANES];
        let mut value = [0.0; LANES];
        let mut difference = [0.0; LANES];
        for lane in 0..LANES {
            let half_sine = (0.5 * thetas[lane]).sin();
            t[lane] = 2.0 * half_sine * half_sine; // 1 - cos θ to full relative precision
            value[lane] = 1.0 - t[lane];
            difference[lane] = -t[lane];
        }
        for (k, (&alpha, &beta)) in (1..).zip(coefficients.alpha.iter().zip(&coefficients.beta)) {
            let _: usize = k;
            for lane in 0..LANES {
                difference[lane] = beta * difference[lane] - alpha * t[lane] * value[lane];
                value[lane] += difference[lane];
            }
        }
        let mut converged = true;
        for lane in 0..LANES {
            // dP_n/dθ = -n (t P_n - D_n) / sin θ.
            let derivative = -n * (t[lane] * value[lane] - difference[lane]) / thetas[lane].sin();
            let step = value[lane] / derivative;
            thetas[lane] -= step;
            converged &= step.abs() <= NEWTON_RELATIVE_STEP * thetas[lane];
        }
        if thetas.iter().any(|theta| !theta.is_finite()) {
            return None;
        }
        if converged {
            return Some(thetas);
        }
    }
    None
}

/// Newton's method in $x$ on several roots at once, with the plain three-term recurrence.
fn newton_in_x(coefficients: &Recurrence, mut xs: [f64; LANES]) -> Option<[f64; LANES]> {
    let n = coefficients.order as f64;
    for _ in 0..NEWTON_MAX_ITERATIONS {
        let mut previous = [1.0; LANES];
        let mut value = xs;
        for (&alpha, &beta) in coefficients.alpha.iter().zip(&coefficients.beta) {
            for lane in 0..LANES {
                let next = alpha * xs[lane] * value[lane] - beta * previous[lane];
                previous[lane] = value[lane];
                value[lane] = next;
            }
        }
        let mut converged = true;
        for lane in 0..LANES {
            let x = xs[lane];
            // P_n'(x) = n (x P_n - P_{n-1}) / (x^2 - 1).
            let derivative = n * (x * value[lane] - previous[lane]) / (x * x - 1.0);
            let step = value[lane] / derivative;
            xs[lane] -= step;
            converged &= step.abs() <= NEWTON_RELATIVE_STEP;
        }
        if xs.iter().any(|x| !x.is_finite()) {
            return None;
        }
        if converged {
            return Some(xs);
        }
    }
    None
}

/// The last Newton step and the weight of roots with $x > 1/2$, in twice the working precision.
///
/// The point is $t = 1 - x = 2\sin^2(\theta/2)$, taken as exact. With $P = P_n$, $D = D_n$ from the
/// compensated Reinsch recurrence, $g = P\_{n-1} - xP_n = tP - D$ and $s = 1 - x^2 = t(2 - t)$:
/// $P_n'(x) = n g / s$, the root is $t + \delta t$ with $\delta t = P s/(n g)$, and the weight
/// $F(t) = 2 s / (n g)^2$ is moved to the root by its logarithmic derivative
/// $\mathrm d\ln F/\mathrm dt = 2(1 - t)/s$.
fn polish_near_one(coefficients: &Recurrence, thetas: [f64; LANES]) -> [(f64, f64); LANES] {
    let ts = thetas.map(|theta| {
        let half_sine = (0.5 * theta).sin();
        2.0 * half_sine * half_sine
    });
    let (values, differences) = compensated_reinsch(coefficients, ts);
    let n = coefficients.order as f64;
    std::array::from_fn(|lane| {
        let (t, value) = (ts[lane], values[lane]);
        let t_twofold = TwoFold::from_f64(t);
        let g = t_twofold.mul(value).sub(differences[lane]);
        let one_minus_x_squared = t_twofold.mul(TwoFold::new(2.0, -t));
        let n_g = g.mul_f64(n);
        let weight_at_t = one_minus_x_squared.mul_f64(2.0).div(n_g.mul(n_g));
        let step = value.value() * one_minus_x_squared.value() / n_g.value();
        let correction = 2.0 * (1.0 - t) / one_minus_x_squared.value() * step;
        let weight = weight_at_t.high + (weight_at_t.low + weight_at_t.high * correction);
        // x = 1 - (t + δt).
        let node = TwoFold::new(1.0, -t).add(TwoFold::from_f64(-step)).value();
        (node, weight)
    })
}

/// The last Newton step and the weight of roots with $x \le 1/2$, in twice the working
/// precision: with $g = P\_{n-1} - xP_n$ and $s = 1 - x^2$, $P_n'(x) = n g/s$, the step is
/// $\delta x = -P s/(n g)$ and the weight $F(x) = 2 s/(n g)^2$ is moved to the root by
/// $\mathrm d\ln F/\mathrm dx = -2x/s$.
fn polish_in_x(coefficients: &Recurrence, xs: [f64; LANES]) -> [(f64, f64); LANES] {
    let (values, previouses) = compensated_three_term(coefficients, xs);
    let n = coefficients.order as f64;
    std::array::from_fn(|lane| {
        let (x, value) = (xs[lane], values[lane]);
        let x_twofold = TwoFold::from_f64(x);
        let g = previouses[lane].sub(x_twofold.mul(value));
        let one_minus_x_squared = TwoFold::from_f64(1.0).sub(x_twofold.mul(x_twofold));
        let n_g = g.mul_f64(n);
        let weight_at_x = one_minus_x_squared.mul_f64(2.0).div(n_g.mul(n_g));
        let step = -value.value() * one_minus_x_squared.value() / n_g.value();
        let correction = -2.0 * x / one_minus_x_squared.value() * step;
        let weight = weight_at_x.high + (weight_at_x.low + weight_at_x.high * correction);
        (x + step, weight)
    })
}

/// $(P_n(x), P\_{n-1}(x))$ to about twice the working precision, for several points: the
/// three-term recurrence with every rounding error captured by an error-free transformation and
/// carried in a second, low-order sequence (compensated evaluation, as in Graillat, Langlois and
/// Louvet's compensated Horner scheme).
fn compensated_three_term(
    coefficients: &Recurrence,
    xs: [f64; LANES],
) -> ([TwoFold; LANES], [TwoFold; LANES]) {
    let x_splits = xs.map(split);
    let (mut previous, mut previous_low) = ([1.0; LANES], [0.0; LANES]);
    let (mut current, mut current_low) = (xs, [0.0; LANES]);
    for (k, &reciprocal) in (1..coefficients.order).zip(&coefficients.reciprocal) {
        let (odd, k_float, k_next) = ((2 * k + 1) as f64, k as f64, (k + 1) as f64);
        for lane in 0..LANES {
            // (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}, term by term with exact errors.
            let x = xs[lane];
            let (a, a_error) = two_product_split(x, x_splits[lane], current[lane]);
            let (b, b_error) = two_product_small_integer(odd, a);
            let (c, c_error) = two_product_small_integer(k_float, previous[lane]);
            let (s, s_error) = two_sum(b, -c);
            let (quotient, remainder) = divide_with_remainder(s, k_next, reciprocal);
            let low = (odd * (x * current_low[lane] + a_error) + b_error
                - c_error
                - k_float * previous_low[lane]
                + s_error)
                * reciprocal
                + remainder;
            previous[lane] = current[lane];
            previous_low[lane] = current_low[lane];
            current[lane] = quotient;
            current_low[lane] = low;
        }
    }
    (
        std::array::from_fn(|lane| TwoFold::new(current[lane], current_low[lane])),
        std::array::from_fn(|lane| TwoFold::new(previous[lane], previous_low[lane])),
    )
}

/// $(P_n, D_n = P_n - P\_{n-1})$ at $x = 1 - t$ to about twice the working precision, for several
/// points: Reinsch's recurrence, compensated as in [`compensated_three_term`].
fn compensated_reinsch(
    coefficients: &Recurrence,
    ts: [f64; LANES],
) -> ([TwoFold; LANES], [TwoFold; LANES]) {
    let t_splits = ts.map(split);
    let mut value = [0.0; LANES];
    let mut value_low = [0.0; LANES];
    for lane in 0..LANES {
        (value[lane], value_low[lane]) = two_sum(1.0, -ts[lane]);
    }
    let (mut difference, mut difference_low) = (ts.map(|t| -t), [0.0; LANES]);
    for (k, &reciprocal) in (1..coefficients.order).zip(&coefficients.reciprocal) {
        let (odd, k_float, k_next) = ((2 * k + 1) as f64, k as f64, (k + 1) as f64);
        for lane in 0..LANES {
            // (k+1) D_{k+1} = k D_k - (2k+1) t P_k;  P_{k+1} = P_k + D_{k+1}.
            let t = ts[lane];
            let (a, a_error) = two_product_split(t, t_splits[lane], value[lane]);
            let (b, b_error) = two_product_small_integer(odd, a);
            let (c, c_error) = two_product_small_integer(k_float, difference[lane]);
            let (s, s_error) = two_sum(c, -b);
            let (quotient, remainder) = divide_with_remainder(s, k_next, reciprocal);
            let low = (k_float * difference_low[lane] - odd * (t * value_low[lane] + a_error)
                + c_error
                - b_error
                + s_error)
                * reciprocal
                + remainder;
            difference[lane] = quotient;
            difference_low[lane] = low;
            let (sum, sum_error) = two_sum(value[lane], quotient);
            value[lane] = sum;
            value_low[lane] += low + sum_error;
        }
    }
    (
        std::array::from_fn(|lane| TwoFold::new(value[lane], value_low[lane])),
        std::array::from_fn(|lane| TwoFold::new(difference[lane], difference_low[lane])),
    )
}

/// `(q, r)` with `q ≈ s / divisor` and `s / divisor = q + r` to about twice the working
/// precision, given `reciprocal ≈ 1 / divisor` (the divisor is an integer below $2^{26}$).
#[inline(always)]
fn divide_with_remainder(s: f64, divisor: f64, reciprocal: f64) -> (f64, f64) {
    let quotient = s * reciprocal;
    let (product, product_error) = two_product_small_integer(divisor, quotient);
    let remainder = (s - product) - product_error;
    (quotient, remainder * reciprocal)
}
