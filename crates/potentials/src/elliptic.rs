//! Complete elliptic integrals by the Gauss (arithmetic–geometric mean) transformation, in a
//! form with no subtraction anywhere, so that every quantity keeps full relative precision from
//! $m \to -\infty$ to $m \to 1$.
//!
//! # Parameter convention
//!
//! Everything here takes the **parameter** $m = k^2$ (not the modulus $k$), as ellip, mpmath and
//! DLMF §19.2 do, or, where precision near $m = 1$ matters, the **complementary modulus**
//! $k_c = \sqrt{1 - m}$, which the caller can often form without cancellation (for a ring or a
//! disk, $k_c$ is a ratio of two distances). With $\Delta(\theta) = \sqrt{1 - m \sin^2\theta}$:
//!
//! $$K(m) = \int_0^{\pi/2} \frac{\mathrm d\theta}{\Delta},\quad
//! E(m) = \int_0^{\pi/2} \Delta\\,\mathrm d\theta,\quad
//! \Pi(n, m) = \int_0^{\pi/2} \frac{\mathrm d\theta}{(1 - n\sin^2\theta)\\,\Delta},$$
//!
//! and the combinations that cancel in terms of $K$ and $E$ (Bulirsch's notation):
//!
//! $$B(m) = \int_0^{\pi/2}\frac{\cos^2\theta}{\Delta}\mathrm d\theta = \frac{E - (1-m)K}{m},\quad
//! D(m) = \int_0^{\pi/2}\frac{\sin^2\theta}{\Delta}\mathrm d\theta = \frac{K - E}{m},$$
//! $$C(m) = \int_0^{\pi/2}\frac{\sin^2\theta\cos^2\theta}{\Delta^3}\mathrm d\theta
//! = \frac{D - B}{m},$$
//!
//! so that $K = B + D$ and $E = B + (1 - m)D$. $D(m) = R_D(0, 1-m, 1)/3$ in Carlson's notation;
//! $C(0) = \pi/16$ and $B(0) = D(0) = \pi/4$. Finally
//!
//! $$D - C = (1 - m)\int_0^{\pi/2}\frac{\sin^4\theta}{\Delta^3}\mathrm d\theta
//! = \frac{B - (1-m)D}{m},$$
//!
//! which the disk–disk force needs; $(D - C)(0) = 3\pi/16$.
//!
//! # Method
//!
//! With $u = \cot\theta$ every integral above becomes
//! $I = \int_0^\infty \frac{\alpha + \beta u^2}{w + u^2}\\,\mathrm d\mu(u)$ with the measure
//! $\mathrm d\mu = \mathrm du / \sqrt{(u^2 + \mu^2)(u^2 + \nu^2)}$, $\mu = 1$, $\nu = k_c$:
//! $B$ is $(\alpha, \beta, w) = (0, 1, 1)$, $D$ is $(1, 0, 1)$, $\Pi$ is $(1, 1, 1 - n)$ and
//! $K = \pi / (2\\,\mathrm{AGM}(1, k_c))$. The substitution $s = (u - q/u)/2$, $q = \mu\nu$, maps
//! the pair $u, q/u$ to $\pm s$ and the measure to the same measure with
//! $(\mu, \nu) \to ((\mu + \nu)/2, \sqrt q)$; the integrand keeps its form with
//!
//! $$\alpha' = \frac{(w + q)(\alpha + \beta q)}{4w},\quad
//! \beta' = \frac{\alpha + \beta w}{2w},\quad w' = \frac{(w + q)^2}{4w},$$
//!
//! all sums of positive terms (a pole at $w = \mu^2$ stays at $\mu'^2$). The integrand of $C$,
//! $u^2 / ((u^2 + \mu^2)(u^2 + \nu^2))$, is invariant under $u \to q/u$ and becomes
//! $\tfrac14 / (s^2 + \mu'^2)$ after one step; that of $(D - C)/k_c^2$,
//! $1/((u^2 + \mu^2)(u^2 + \nu^2))$, becomes $(q + 2s^2)/(4q^2(s^2 + \mu'^2))$. Once $|\mu - \nu| \le 2^{-26}\mu$ the measure
//! equals $\mathrm du/(u^2 + M^2)$, $M = (\mu+\nu)/2$, to a relative $O(2^{-56})$, and
//!
//! $$\int_0^\infty \frac{\alpha + \beta u^2}{(w + u^2)(M^2 + u^2)}\mathrm du
//! = \frac{\pi(\alpha + \beta M\sqrt w)}{2\sqrt w\\, M (M + \sqrt w)}$$
//!
//! closes the computation. Quadratic convergence: at most 4 steps for $k_c \ge 0.1$, 7 for
//! $k_c = 10^{-9}$, 11 for $k_c = 10^{-150}$. Measured against the Carlson functions of `ellip`
//! (themselves within a few ULP of mpmath) for $10^{-100} \le k_c \le 10^3$: at most 5 ULP in
//! $K, B, D, E$ and 5.4 ULP in $\sqrt{1-n}\\,\Pi$ (see the tests).
//!
//! $\Pi$ diverges as $(1 - n)^{-1/2}$ when $n \to 1$; [`complete_pi_scaled`] returns
//! $\sqrt{1-n}\\,\Pi(n, m)$, finite there, with the limit $\pi / (2 k_c)$ at $n = 1$.

use crate::lanes::{F4, LANES, M4};
use std::f64::consts::FRAC_PI_2;

use thiserror::Error;

/// Why an elliptic integral was not evaluated.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum EllipticError {
    /// An argument lies outside the domain the function supports.
    #[error("{name} = {value} is outside the supported domain {domain}")]
    OutOfDomain {
        /// The argument's name (`m`, `n`, `complementary_modulus`, ...).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The supported domain, in words.
        domain: &'static str,
    },
}

/// Stop the AGM once $|\mu - \nu| \le$ this times $\mu$: the measure is then flat to
/// $(2^{-26})^2/16 \approx 2^{-56}$.
const AGM_TOLERANCE: f64 = 1.0 / 67_108_864.0; // 2^-26

/// Convergence needs 11 steps at k_c = 1e-150; this bound only guards against a logic error.
const MAX_STEPS: usize = 64;

/// Smallest and largest complementary modulus (and √(1−n)) accepted by the public functions;
/// inside this range no intermediate quantity overflows or underflows.
const SCALE_LIMIT: f64 = 1e150;

/// One integrand $(\alpha + \beta u^2)/(w + u^2)$ carried through the Gauss transformation.
#[derive(Clone, Copy)]
struct Track {
    alpha: f64,
    beta: f64,
}

impl Track {
    /// The update for a track whose pole sits at $w = \mu^2$ (it stays at $\mu'^2$).
    /// `h = (μ+ν)/(4μ)`, `half_inv_mu2 = 1/(2μ²)`.
    #[inline(always)]
    fn step_at_mu(&mut self, q: f64, mu2: f64, h: f64, half_inv_mu2: f64) {
        let alpha = h * (self.alpha + self.beta * q);
        let beta = half_inv_mu2 * (self.alpha + self.beta * mu2);
        self.alpha = alpha;
        self.beta = beta;
    }

    /// $\int (\alpha + \beta u^2)/((w + u^2)(M^2 + u^2))\\,\mathrm du$ without the factor
    /// $\pi / (2\sqrt w M (M + \sqrt w))$.
    #[inline(always)]
    fn numerator(&self, m_sqrt_w: f64) -> f64 {
        self.alpha + self.beta * m_sqrt_w
    }
}

/// The complete integrals of one parameter, all from one AGM sequence: the building block of the
/// ring, disk and disk–disk formulas. Fields are the integrals defined in the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompleteEllipticIntegrals {
    /// $K(m)$.
    pub k: f64,
    /// $E(m) = B + (1 - m) D$.
    pub e: f64,
    /// $B(m) = (E - (1 - m)K)/m$.
    pub b: f64,
    /// $D(m) = (K - E)/m$.
    pub d: f64,
    /// $C(m) = (D - B)/m$.
    pub c: f64,
    /// $D(m) - C(m) = (B - (1-m)D)/m$.
    pub d_minus_c: f64,
}

impl CompleteEllipticIntegrals {
    /// The integrals for the complementary modulus $k_c = \sqrt{1 - m}$, accurate to a few ULP
    /// however close $m$ is to 1. Domain: $10^{-150} \le k_c \le 10^{150}$.
    pub fn from_complementary_modulus(kc: f64) -> Result<Self, EllipticError> {
        check_scale("complementary_modulus", kc, false)?;
        Ok(gauss(kc, None).integrals(kc))
    }

    /// The integrals for the parameter $m = k^2$, $1 - 10^{300} \le m < 1$. Near $m = 1$ prefer
    /// [`Self::from_complementary_modulus`] when $1 - m$ is known more precisely than $m$.
    pub fn from_parameter(m: f64) -> Result<Self, EllipticError> {
        if !(1.0 - SCALE_LIMIT * SCALE_LIMIT..1.0).contains(&m) {
            return Err(EllipticError::OutOfDomain {
                name: "m",
                value: m,
                domain: "1 - 1e300 <= m < 1",
            });
        }
        Self::from_complementary_modulus((1.0 - m).sqrt())
    }
}

/// $K(m)$, for $1 - 10^{300} \le m < 1$.
pub fn complete_k(m: f64) -> Result<f64, EllipticError> {
    Ok(CompleteEllipticIntegrals::from_parameter(m)?.k)
}

/// $E(m)$, for $1 - 10^{300} \le m \le 1$ ($E(1) = 1$).
pub fn complete_e(m: f64) -> Result<f64, EllipticError> {
    if m == 1.0 {
        return Ok(1.0);
    }
    Ok(CompleteEllipticIntegrals::from_parameter(m)?.e)
}

/// $\Pi(n, m)$ for $1 - 10^{300} \le n < 1$ and $1 - 10^{300} \le m < 1$ (no principal values).
pub fn complete_pi(n: f64, m: f64) -> Result<f64, EllipticError> {
    if !(1.0 - SCALE_LIMIT * SCALE_LIMIT..1.0).contains(&n) {
        return Err(EllipticError::OutOfDomain {
            name: "n",
            value: n,
            domain: "1 - 1e300 <= n < 1",
        });
    }
    let kc = CompleteEllipticIntegrals::from_parameter(m).map(|_| (1.0 - m).sqrt())?;
    let snc = (1.0 - n).sqrt();
    Ok(complete_pi_scaled(snc, kc)? / snc)
}

/// $\sqrt{1 - n}\\;\Pi(n, m)$ from $\sqrt{1-n}$ and $k_c = \sqrt{1 - m}$: finite as $n \to 1$,
/// where it tends to $\pi / (2 k_c)$ (returned for `sqrt_one_minus_n == 0`). Domain:
/// $10^{-150} \le k_c \le 10^{150}$, $\sqrt{1-n} = 0$ or $10^{-150} \le \sqrt{1-n} \le 10^{150}$.
pub fn complete_pi_scaled(sqrt_one_minus_n: f64, kc: f64) -> Result<f64, EllipticError> {
    check_scale("complementary_modulus", kc, false)?;
    check_scale("sqrt_one_minus_n", sqrt_one_minus_n, true)?;
    if sqrt_one_minus_n == 0.0 {
        return Ok(FRAC_PI_2 / kc);
    }
    Ok(gauss(kc, Some(sqrt_one_minus_n)).pi_scaled)
}

fn check_scale(name: &'static str, value: f64, zero_allowed: bool) -> Result<(), EllipticError> {
    let ok = (zero_allowed && value == 0.0) || ((1.0 / SCALE_LIMIT..=SCALE_LIMIT).contains(&value));
    if ok {
        Ok(())
    } else {
        Err(EllipticError::OutOfDomain {
            name,
            value,
            domain: if zero_allowed {
                "0 or 1e-150 ..= 1e150"
            } else {
                "1e-150 ..= 1e150"
            },
        })
    }
}

/// The raw results of one Gauss iteration; see [`gauss`].
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Gauss {
    /// $K$.
    pub k: f64,
    /// $B$.
    pub b: f64,
    /// $D$.
    pub d: f64,
    /// $C$.
    pub c: f64,
    /// $D - C$.
    pub d_minus_c: f64,
    /// $\sqrt{1-n}\\,\Pi(n, m)$ if requested, else 0.
    pub pi_scaled: f64,
}

impl Gauss {
    fn integrals(&self, kc: f64) -> CompleteEllipticIntegrals {
        CompleteEllipticIntegrals {
            k: self.k,
            e: self.b + kc * kc * self.d,
            b: self.b,
            d: self.d,
            c: self.c,
            d_minus_c: self.d_minus_c,
        }
    }
}

/// $K, B, D, C$ for the complementary modulus `kc`, and $\sqrt{1-n}\\,\Pi(n, m)$ when
/// `sqrt_one_minus_n` is given (it must be positive). No argument checks: `kc` and
/// `sqrt_one_minus_n` must lie in $[10^{-150}, 10^{150}]$ (the callers in this crate guarantee
/// it).
#[inline]
pub(crate) fn gauss(kc: f64, sqrt_one_minus_n: Option<f64>) -> Gauss {
    let mut mu = 1.0_f64;
    let mut nu = kc;
    let mut b = Track {
        alpha: 0.0,
        beta: 1.0,
    };
    let mut d = Track {
        alpha: 1.0,
        beta: 0.0,
    };
    // C is (1/4)/(s² + μ₁²) after the first step.
    let mut c = Track {
        alpha: 0.25,
        beta: 0.0,
    };
    // D − C is k_c² (q + 2s²)/(4q²(s² + μ₁²)) after the first step, with q = k_c.
    let mut d_minus_c = Track {
        alpha: 0.25 * kc,
        beta: 0.5,
    };
    let want_pi = sqrt_one_minus_n.is_some();
    let snc = sqrt_one_minus_n.unwrap_or(1.0);
    let mut p = Track {
        alpha: snc,
        beta: snc,
    };
    let mut w = snc * snc;

    // First step (C starts after it).
    let mut steps = 0;
    loop {
        let q = mu * nu;
        let mu2 = mu * mu;
        let inv_mu = 1.0 / mu;
        let h = 0.25 * (mu + nu) * inv_mu;
        let half_inv_mu2 = 0.5 * inv_mu * inv_mu;
        b.step_at_mu(q, mu2, h, half_inv_mu2);
        d.step_at_mu(q, mu2, h, half_inv_mu2);
        if steps > 0 {
            c.step_at_mu(q, mu2, h, half_inv_mu2);
            d_minus_c.step_at_mu(q, mu2, h, half_inv_mu2);
        }
        if want_pi {
            let quarter_inv_w = 0.25 / w;
            let wq = w + q;
            let alpha = wq * (p.alpha + p.beta * q) * quarter_inv_w;
            let beta = 2.0 * (p.alpha + p.beta * w) * quarter_inv_w;
            p = Track { alpha, beta };
            w = wq * wq * quarter_inv_w;
        }
        mu = 0.5 * (mu + nu);
        nu = q.sqrt();
        steps += 1;
        if (mu - nu).abs() <= AGM_TOLERANCE * mu || steps >= MAX_STEPS {
            break;
        }
    }

    let m = 0.5 * (mu + nu);
    // Tracks with the pole at μ²: √w = μ.
    let scale_mu = std::f64::consts::PI / (2.0 * mu * m * (m + mu));
    let m_mu = m * mu;
    let pi_scaled = if want_pi {
        let sw = w.sqrt();
        std::f64::consts::PI * p.numerator(m * sw) / (2.0 * sw * m * (m + sw))
    } else {
        0.0
    };
    Gauss {
        k: FRAC_PI_2 / m,
        b: scale_mu * b.numerator(m_mu),
        d: scale_mu * d.numerator(m_mu),
        c: scale_mu * c.numerator(m_mu),
        d_minus_c: scale_mu * d_minus_c.numerator(m_mu),
        pi_scaled,
    }
}

/// [`gauss`] for `G` groups of [`LANES`] moduli side by side: lane $l$ of group $g$ is bit for
/// bit `gauss(kc[g][l], want_pi[g][l].then_some(sqrt_one_minus_n[g][l]))` (the same operations
/// in the same order; a lane that has converged is frozen while the others iterate, and the
/// $\Pi$ track of a lane that does not want it is computed and discarded). Same domain as
/// [`gauss`] for the lanes whose results are used. Each iteration is a chain of a division, a
/// square root and multiplications that the next one waits for; the groups' chains are
/// independent, so two groups interleave in the processor.
#[inline(always)]
pub(crate) fn gauss_lanes<const G: usize>(
    kc: [F4; G],
    sqrt_one_minus_n: [F4; G],
    want_pi: [M4; G],
) -> [[Gauss; LANES]; G] {
    let one = F4::splat(1.0);
    let zero = F4::splat(0.0);
    let mut mu = [one; G];
    let mut nu = kc;
    let (mut b_alpha, mut b_beta) = ([zero; G], [one; G]);
    let (mut d_alpha, mut d_beta) = ([one; G], [zero; G]);
    let (mut c_alpha, mut c_beta) = ([F4::splat(0.25); G], [zero; G]);
    let mut dc_alpha: [F4; G] = std::array::from_fn(|g| kc[g] * 0.25);
    let mut dc_beta = [F4::splat(0.5); G];
    let snc: [F4; G] = std::array::from_fn(|g| want_pi[g].select(sqrt_one_minus_n[g], one));
    let (mut p_alpha, mut p_beta) = (snc, snc);
    let mut w: [F4; G] = std::array::from_fn(|g| snc[g] * snc[g]);
    let mut active = [M4::from_flags([true; LANES]); G];
    let mut steps = 0;
    loop {
        for g in 0..G {
            let on = active[g];
            let (mu_g, nu_g) = (mu[g], nu[g]);
            let q = mu_g * nu_g;
            let mu2 = mu_g * mu_g;
            let inv_mu = 1.0 / mu_g;
            let h = 0.25 * (mu_g + nu_g) * inv_mu;
            let half_inv_mu2 = 0.5 * inv_mu * inv_mu;
            // Track::step_at_mu, lane by lane, kept where the lane is still iterating.
            let step = |alpha: &mut F4, beta: &mut F4| {
                let new_alpha = h * (*alpha + *beta * q);
                let new_beta = half_inv_mu2 * (*alpha + *beta * mu2);
                *alpha = on.select(new_alpha, *alpha);
                *beta = on.select(new_beta, *beta);
            };
            step(&mut b_alpha[g], &mut b_beta[g]);
            step(&mut d_alpha[g], &mut d_beta[g]);
            if steps > 0 {
                step(&mut c_alpha[g], &mut c_beta[g]);
                step(&mut dc_alpha[g], &mut dc_beta[g]);
            }
            let pi_active = on.and(want_pi[g]);
            let w_g = w[g];
            let quarter_inv_w = 0.25 / w_g;
            let wq = w_g + q;
            let alpha = wq * (p_alpha[g] + p_beta[g] * q) * quarter_inv_w;
            let beta = 2.0 * (p_alpha[g] + p_beta[g] * w_g) * quarter_inv_w;
            p_alpha[g] = pi_active.select(alpha, p_alpha[g]);
            p_beta[g] = pi_active.select(beta, p_beta[g]);
            w[g] = pi_active.select(wq * wq * quarter_inv_w, w_g);
            mu[g] = on.select(0.5 * (mu_g + nu_g), mu_g);
            nu[g] = on.select(q.sqrt(), nu_g);
        }
        steps += 1;
        if steps >= MAX_STEPS {
            break;
        }
        let mut any = false;
        for g in 0..G {
            let converged = (mu[g] - nu[g]).abs().le(mu[g] * AGM_TOLERANCE);
            active[g] = active[g].and(converged.not());
            any |= active[g].any();
        }
        if !any {
            break;
        }
    }
    // Plain loops, not `std::array::from_fn`: the compiler kept that closure out of line,
    // compiled without the caller's AVX (10 % of a disk pair's time near contact).
    let mut out = [[Gauss::default(); LANES]; G];
    for (g, out) in out.iter_mut().enumerate() {
        let (mu, w) = (mu[g], w[g]);
        let m = 0.5 * (mu + nu[g]);
        let scale_mu = std::f64::consts::PI / (2.0 * mu * m * (m + mu));
        let m_mu = m * mu;
        let sw = w.sqrt();
        let pi_scaled = want_pi[g].select(
            std::f64::consts::PI * (p_alpha[g] + p_beta[g] * (m * sw)) / (2.0 * sw * m * (m + sw)),
            zero,
        );
        let k = FRAC_PI_2 / m;
        let b = scale_mu * (b_alpha[g] + b_beta[g] * m_mu);
        let d = scale_mu * (d_alpha[g] + d_beta[g] * m_mu);
        let c = scale_mu * (c_alpha[g] + c_beta[g] * m_mu);
        let d_minus_c = scale_mu * (dc_alpha[g] + dc_beta[g] * m_mu);
        for (l, out) in out.iter_mut().enumerate() {
            *out = Gauss {
                k: k.0[l],
                b: b.0[l],
                d: d.0[l],
                c: c.0[l],
                d_minus_c: d_minus_c.0[l],
                pi_scaled: pi_scaled.0[l],
            };
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative difference in units of the double epsilon.
    fn ulps(got: f64, expected: f64) -> f64 {
        ((got - expected) / expected).abs() / f64::EPSILON
    }

    /// Complementary moduli from 1e-150 to 1e3, dense near 0 and 1.
    fn moduli() -> Vec<f64> {
        let mut v = Vec::new();
        for e in -150..=3 {
            for f in [1.0, 1.7, 3.1, 5.9] {
                v.push(f * 10f64.powi(e));
            }
        }
        for k in 1..200 {
            v.push(k as f64 / 200.0);
        }
        v.push(1.0);
        v
    }

    /// Reference values from the Carlson forms of `ellip` (R_F, R_D, R_J with the exact
    /// complementary arguments), themselves within a few ULP of mpmath.
    fn carlson(kc: f64) -> (f64, f64, f64) {
        let y = kc * kc;
        let k = ellip::elliprf(0.0, y, 1.0).unwrap();
        let d = ellip::elliprd(0.0, y, 1.0).unwrap() / 3.0;
        // B = k_c² R_D(0, 1, k_c²)/3.
        let b = y * ellip::elliprd(0.0, 1.0, y).unwrap() / 3.0;
        (k, b, d)
    }

    #[test]
    fn k_b_d_e_match_carlson_forms() {
        let mut worst: f64 = 0.0;
        for kc in moduli() {
            // y = k_c² must stay a normal number for the reference.
            if !(1e-100..=1e100).contains(&kc) {
                continue;
            }
            let g = CompleteEllipticIntegrals::from_complementary_modulus(kc).unwrap();
            let (k, b, d) = carlson(kc);
            for (got, want, what) in [(g.k, k, "K"), (g.b, b, "B"), (g.d, d, "D")] {
                let u = ulps(got, want);
                worst = worst.max(u);
                assert!(
                    u < 8.0,
                    "{what}(kc = {kc:e}): {got:e} vs {want:e}, {u:.1} ulp"
                );
            }
            let e = ellip::elliprf(0.0, kc * kc, 1.0).unwrap() * kc * kc
                + (1.0 - kc * kc) * kc * kc * ellip::elliprd(0.0, 1.0, kc * kc).unwrap() / 3.0;
            let u = ulps(g.e, e);
            assert!(u < 8.0, "E(kc = {kc:e}): {} vs {e:e}, {u:.1} ulp", g.e);
        }
        println!("worst K/B/D error: {worst:.1} ulp");
    }

    /// C = (D − B)/m where the difference is benign (m ≥ 1/2), and its Maclaurin series
    /// (π/16) ₂F₁(3/2, 3/2; 3; m) where it is not.
    #[test]
    fn c_matches_difference_and_series() {
        for kc in moduli() {
            if !(1e-100..=1e100).contains(&kc) {
                continue;
            }
            let g = CompleteEllipticIntegrals::from_complementary_modulus(kc).unwrap();
            let m = 1.0 - kc * kc;
            if m >= 0.5 {
                let (_, b, d) = carlson(kc);
                let want = (d - b) / m;
                let u = ulps(g.c, want);
                assert!(
                    u < 30.0,
                    "C(kc = {kc:e}) = {:e} vs {want:e}: {u:.1} ulp",
                    g.c
                );
                // D − C = (B − k_c² D)/m, benign for m ≥ 1/2 when k_c² D < B/2.
                if kc * kc * d < 0.5 * b {
                    let want = (b - kc * kc * d) / m;
                    let u = ulps(g.d_minus_c, want);
                    assert!(
                        u < 30.0,
                        "D−C(kc = {kc:e}): {:e} vs {want:e}: {u:.1} ulp",
                        g.d_minus_c
                    );
                }
            } else if m.abs() <= 0.25 {
                // Σ (3/2)_j² / ((3)_j j!) m^j.
                let (mut term, mut sum) = (1.0_f64, 1.0_f64);
                for j in 0..200 {
                    let j = j as f64;
                    term *= (1.5 + j) * (1.5 + j) / ((3.0 + j) * (1.0 + j)) * m;
                    sum += term;
                    if term.abs() < 1e-18 * sum.abs() {
                        break;
                    }
                }
                let want = std::f64::consts::PI / 16.0 * sum;
                let u = ulps(g.c, want);
                assert!(
                    u < 8.0,
                    "C(kc = {kc:e}) = {:e} vs {want:e}: {u:.1} ulp",
                    g.c
                );
                // D − C against the difference of the two Maclaurin series (benign for
                // |m| ≤ 1/4: D − C ≥ D/2), with D = (π/4) ₂F₁(1/2, 3/2; 2; m).
                let (mut term, mut d_series) = (1.0_f64, 1.0_f64);
                for j in 0..200 {
                    let j = j as f64;
                    term *= (0.5 + j) * (1.5 + j) / ((2.0 + j) * (1.0 + j)) * m;
                    d_series += term;
                    if term.abs() < 1e-18 * d_series.abs() {
                        break;
                    }
                }
                let want = std::f64::consts::PI / 4.0 * d_series - g.c;
                let u = ulps(g.d_minus_c, want);
                assert!(
                    u < 8.0,
                    "D−C(kc = {kc:e}): {:e} vs {want:e}: {u:.1} ulp",
                    g.d_minus_c
                );
            }
        }
    }

    #[test]
    fn pi_matches_carlson_form() {
        // Π(n, m) = R_F(0, k_c², 1) + (n/3) R_J(0, k_c², 1, 1 − n).
        let mut worst: f64 = 0.0;
        for kc in moduli() {
            if !(1e-60..=1e60).contains(&kc) {
                continue;
            }
            for snc in [1e-16, 3e-9, 1e-4, 0.01, 0.3, 0.77, 1.0, 1.5, 40.0, 1e7] {
                let nc = snc * snc;
                let n = 1.0 - nc;
                let y = kc * kc;
                let want = snc
                    * (ellip::elliprf(0.0, y, 1.0).unwrap()
                        + n / 3.0 * ellip::elliprj(0.0, y, 1.0, nc).unwrap());
                let got = complete_pi_scaled(snc, kc).unwrap();
                // The reference sums terms of opposite sign when n < 0.
                let allowance = if n < 0.0 {
                    1.0 + (n / 3.0 * ellip::elliprj(0.0, y, 1.0, nc).unwrap() * snc / want).abs()
                } else {
                    1.0
                };
                let u = ulps(got, want) / allowance;
                worst = worst.max(u);
                assert!(
                    u < 16.0,
                    "√(1−n)Π(kc = {kc:e}, √(1−n) = {snc:e}): {got:e} vs {want:e}: {u:.1} ulp"
                );
            }
        }
        println!("worst √(1−n)Π error: {worst:.1} ulp");
    }

    /// The bits of every integral of one [`Gauss`].
    fn bits(g: &Gauss) -> [u64; 6] {
        [g.k, g.b, g.d, g.c, g.d_minus_c, g.pi_scaled].map(f64::to_bits)
    }

    /// Two and three groups side by side give bit for bit the groups one at a time and the
    /// scalar [`gauss`], with lanes and groups of different iteration counts together (1 step at
    /// $k_c = 1$, 11 at $10^{-150}$), $\Pi$ wanted in some lanes only, and a group whose lanes
    /// all converge while the other group still iterates.
    #[test]
    fn interleaved_groups_are_the_single_group_bit_for_bit() {
        let lanes = |kc: [f64; LANES], snc: [f64; LANES], pi: [bool; LANES]| {
            (F4::new(kc), F4::new(snc), M4::from_flags(pi))
        };
        let groups = [
            lanes(
                [1.0, 1e-150, 0.3, 2.5e-9],
                [0.5, 1e-12, 3.0, 1e7],
                [true, false, true, true],
            ),
            lanes(
                [0.999, 1.0, 0.7, 1.2],
                [1.0, 0.2, 0.01, 7.0],
                [false, true, true, false],
            ),
            lanes(
                [1e-150, 1e-150, 1e-150, 1e-150],
                [1e-150, 0.9, 1.0, 2.0],
                [true; LANES],
            ),
            lanes(
                [5.0, 3e-40, 1e-3, 1.0],
                [1e-3, 40.0, 1.0, 1.0],
                [true, true, false, false],
            ),
        ];
        let scalar = |(kc, snc, pi): (F4, F4, M4)| -> [[u64; 6]; LANES] {
            std::array::from_fn(|l| bits(&gauss(kc.0[l], pi.flags()[l].then_some(snc.0[l]))))
        };
        let single = |(kc, snc, pi): (F4, F4, M4)| -> [[u64; 6]; LANES] {
            let [one] = gauss_lanes([kc], [snc], [pi]);
            one.map(|g| bits(&g))
        };
        for group in groups {
            let bits = scalar(group);
            let values = bits.map(|lane| lane.map(f64::from_bits));
            assert!(values.iter().flatten().all(|v| v.is_finite()), "{values:?}");
            assert_eq!(single(group), bits);
        }
        for (i, first) in groups.iter().enumerate() {
            for (j, second) in groups.iter().enumerate() {
                let pair = gauss_lanes(
                    [first.0, second.0],
                    [first.1, second.1],
                    [first.2, second.2],
                );
                assert_eq!(pair[0].map(|g| bits(&g)), single(*first), "groups {i}, {j}");
                assert_eq!(
                    pair[1].map(|g| bits(&g)),
                    single(*second),
                    "groups {i}, {j}"
                );
            }
        }
        let three = gauss_lanes(
            [groups[1].0, groups[2].0, groups[0].0],
            [groups[1].1, groups[2].1, groups[0].1],
            [groups[1].2, groups[2].2, groups[0].2],
        );
        for (result, group) in three.iter().zip([groups[1], groups[2], groups[0]]) {
            assert_eq!(result.map(|g| bits(&g)), single(group));
        }
    }

    #[test]
    fn pi_scaled_tends_to_its_limit() {
        for kc in [1e-9, 0.01, 0.5, 1.0, 7.0] {
            let limit = complete_pi_scaled(0.0, kc).unwrap();
            assert_eq!(limit, FRAC_PI_2 / kc);
            let near = complete_pi_scaled(1e-17 * kc, kc).unwrap();
            assert!(
                ((near - limit) / limit).abs() < 1e-15,
                "kc {kc}: {near} vs {limit}"
            );
        }
    }

    #[test]
    fn special_values() {
        let pi = std::f64::consts::PI;
        let g = CompleteEllipticIntegrals::from_parameter(0.0).unwrap();
        assert!(ulps(g.k, pi / 2.0) < 2.0 && ulps(g.e, pi / 2.0) < 2.0);
        assert!(ulps(g.b, pi / 4.0) < 2.0 && ulps(g.d, pi / 4.0) < 2.0);
        assert!(ulps(g.c, pi / 16.0) < 2.0);
        assert!(ulps(g.d_minus_c, 3.0 * pi / 16.0) < 2.0);
        assert_eq!(complete_e(1.0), Ok(1.0));
        // K(1/2) = Γ(1/4)² / (4√π).
        let k_half = 1.854_074_677_301_371_9;
        assert!(ulps(complete_k(0.5).unwrap(), k_half) < 2.0);
        // Π(n, 0) = π / (2√(1−n)).
        assert!(ulps(complete_pi(0.64, 0.0).unwrap(), pi / 2.0 / 0.6) < 4.0);
    }

    #[test]
    fn agrees_with_legendre_functions_of_ellip() {
        for m in [
            -1e6,
            -3.0,
            -0.2,
            0.0,
            1e-9,
            0.3,
            0.9,
            0.999_999,
            1.0 - 1e-15,
        ] {
            let k = complete_k(m).unwrap();
            let e = complete_e(m).unwrap();
            assert!(ulps(k, ellip::ellipk(m).unwrap()) < 8.0, "K({m})");
            assert!(ulps(e, ellip::ellipe(m).unwrap()) < 8.0, "E({m})");
            for n in [-5.0, 0.0, 0.5, 0.99] {
                let pi = complete_pi(n, m).unwrap();
                let want = ellip::ellippi(n, m).unwrap();
                assert!(ulps(pi, want) < 16.0, "Π({n}, {m}): {pi} vs {want}");
            }
        }
    }

    #[test]
    fn rejects_arguments_outside_the_domain() {
        assert!(complete_k(1.0).is_err());
        assert!(complete_k(f64::NAN).is_err());
        assert!(complete_k(2.0).is_err());
        assert!(complete_e(1.5).is_err());
        assert!(complete_pi(1.0, 0.5).is_err());
        assert!(complete_pi(0.5, f64::INFINITY).is_err());
        assert!(complete_pi_scaled(-1.0, 0.5).is_err());
        assert!(complete_pi_scaled(0.5, 0.0).is_err());
        assert!(CompleteEllipticIntegrals::from_complementary_modulus(1e-200).is_err());
        assert!(CompleteEllipticIntegrals::from_complementary_modulus(f64::NAN).is_err());
    }
}
