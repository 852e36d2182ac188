//! Carlson's symmetric elliptic integrals $R_F$ and $R_D$, fused: one duplication loop gives
//! $R_F(x, y, z)$ and the three $R_D$ that take each argument in turn in the last slot; and
//! $R_G$ from them ([`rg`], for an ellipsoid's surface area). The workspace's one copy.
//!
//! # Definitions
//!
//! $$R_F(x, y, z) = \tfrac12 \int_0^\infty \frac{\mathrm dt}{\sqrt{(t + x)(t + y)(t + z)}},
//! \qquad
//! R_D(x, y, z) = \tfrac32 \int_0^\infty \frac{\mathrm dt}{(t + z)\sqrt{(t + x)(t + y)(t + z)}}$$
//!
//! (DLMF 19.16.1, 19.16.5). The homogeneous ellipsoid's field needs $R_F(A_1, A_2, A_3)$ and
//! $R_D(A_2, A_3, A_1)$, $R_D(A_3, A_1, A_2)$, $R_D(A_1, A_2, A_3)$ at the same arguments
//! (see [`crate::ellipsoid`]).
//!
//! # Algorithm
//!
//! Carlson's duplication step (DLMF §19.26(ii); Carlson 1995, *Numer. Algorithms* 10, 13–26)
//! $$\lambda = \sqrt{xy} + \sqrt{yz} + \sqrt{zx}, \qquad
//! (x, y, z) \leftarrow \tfrac14 (x + \lambda, y + \lambda, z + \lambda)$$
//! is symmetric in its arguments, so the three $R_D$ and $R_F$ share one sequence. Each step
//! leaves $R_F$ unchanged and peels off one term of each $R_D$:
//! $$R_D(x, y, z) = \frac{3}{\sqrt z\\,(\sqrt z + \sqrt x)(\sqrt z + \sqrt y)} +
//!   \tfrac14 R_D(x', y', z')$$
//! (using $z + \lambda = (\sqrt z + \sqrt x)(\sqrt z + \sqrt y)$). The three reciprocals of one
//! step share a single division. The differences $x - y$, … shrink by exactly 4 per step; once
//! the largest relative deviation $|Z_i| = |\mu - x_i|/\mu$ from the mean $\mu = (x+y+z)/3$ is
//! below $\tau = 0.04$, the remaining integrals are summed from their Taylor series about the
//! common mean (DLMF §19.19): with $e_2 = Z_1Z_2 + Z_2Z_3 + Z_3Z_1$, $e_3 = Z_1Z_2Z_3$ and
//! $\sum_N p_N t^N = (1 + e_2 t^2 - e_3 t^3)^{-1/2}$,
//! $$R_F = \mu^{-1/2} \sum_N \frac{p_N}{2N + 1}, \qquad
//! R_D(\cdot, \cdot, x_i) = \mu^{-3/2} \sum_N \frac{3\\, c_N(Z_i)}{2N + 3}, \quad
//! c_N = Z_i c\_{N-1} + p_N,\ c_0 = 1,$$
//! the second because the generating function of the $R_D$ terms is
//! $(1 + e_2 t^2 - e_3 t^3)^{-1/2} (1 - Z_i t)^{-1}$ (the $R_D$ weights are $\tfrac12, \tfrac12,
//! \tfrac32$ and the common mean does not cancel the first-order term). The $p_N$ follow from
//! the differential equation of their generating function,
//! $(N+1)p\_{N+1} = -N e_2 p\_{N-1} + (N - \tfrac12) e_3 p\_{N-2}$. The series is cut after
//! degree 11 (5, 7 when $|Z| \le 10^{-3}, 10^{-2}$): the truncation error, measured against
//! mpmath, is $0.33\\,|Z|^{12} \le 6\cdot 10^{-18}$. Unlike separate routines, the four series
//! share one mean, one $\mu^{-1/2}$ and one set of $p_N$.
//!
//! Accuracy, against mpmath at 30 digits: within 3.8 ulp for all four on 2,000 random triples
//! and on each of the 8,756 (out of 400,000, spread from $10^{-200}$ to $10^{200}$ with ratios
//! up to $10^{400}$) where the `ellip` crate differs from us by more than 8 ulp: ellip's own
//! $R_D$ is off by up to 11 ulp for nearly equal arguments and fails beyond ratios of about
//! $10^{150}$. Elsewhere we agree with ellip to 8 ulp. One call
//! replaces four of ellip's.

use crate::lanes::F8;

/// $R_F(x, y, z)$ and $R_D$ with each argument in the last slot, from one duplication loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetricIntegrals {
    /// $R_F(x, y, z)$.
    pub rf: f64,
    /// $[R_D(y, z, x),\ R_D(z, x, y),\ R_D(x, y, z)]$: entry $i$ has argument $i$ last.
    pub rd: [f64; 3],
}

/// Terms of the series about the mean: degrees 0 to 11.
const SERIES_TERMS: usize = 12;

/// Largest relative deviation from the mean at which the series takes over: the truncation
/// error, measured against mpmath, is $0.33\\,\tau^{12} = 5.5 \cdot 10^{-18}$.
const SERIES_THRESHOLD: f64 = 0.04;

/// $-N/(N+1)$ and $(N - \frac12)/(N+1)$: the recurrence of the $p_N$.
const RECURRENCE: [(f64, f64); SERIES_TERMS] = {
    let mut r = [(0.0, 0.0); SERIES_TERMS];
    let mut n = 0;
    while n < SERIES_TERMS {
        let m = n as f64;
        r[n] = (-m / (m + 1.0), (m - 0.5) / (m + 1.0));
        n += 1;
    }
    r
};

/// $1/(2N + 1)$, the weights of the $R_F$ series.
const RF_WEIGHTS: [f64; SERIES_TERMS] = {
    let mut w = [0.0; SERIES_TERMS];
    let mut n = 0;
    while n < SERIES_TERMS {
        w[n] = 1.0 / (2 * n + 1) as f64;
        n += 1;
    }
    w
};

/// $3/(2N + 3)$, the weights of the $R_D$ series.
const RD_WEIGHTS: [f64; SERIES_TERMS] = {
    let mut w = [0.0; SERIES_TERMS];
    let mut n = 0;
    while n < SERIES_TERMS {
        w[n] = 3.0 / (2 * n + 3) as f64;
        n += 1;
    }
    w
};

/// More duplication steps than any argument triple needs: the relative spread falls by 4 per
/// step once the arguments are within a factor 4 of each other, and a ratio of
/// $10^{\pm 600}$ is brought there in about 12 steps.
const MAX_STEPS: usize = 64;

/// Powers of two bounding the argument ranges (exact decimal images).
const TWO_POW_300: f64 = 2.037_035_976_334_486e90;
const TWO_POW_M300: f64 = 4.909_093_465_297_727e-91;
const TWO_POW_1000: f64 = 1.071_508_607_186_267_3e301;
const TWO_POW_M960: f64 = 1.026_134_200_324_594_1e-289;

/// $R_F(x, y, z)$ and the three $R_D$ (see [`SymmetricIntegrals`]).
///
/// Returns `None` unless all three arguments are positive and finite (each $R_D$ needs its
/// last argument positive; the ellipsoid never produces a zero).
///
/// ```
/// use surfgrav_potentials::carlson::symmetric_integrals;
/// let s = symmetric_integrals(1.0, 1.0, 1.0).unwrap();
/// assert!((s.rf - 1.0).abs() < 1e-15 && (s.rd[2] - 1.0).abs() < 1e-15);
/// ```
pub fn symmetric_integrals(x: f64, y: f64, z: f64) -> Option<SymmetricIntegrals> {
    let valid = |v: f64| v.is_finite() && v > 0.0;
    if !(valid(x) && valid(y) && valid(z)) {
        return None;
    }
    // The loop copes with any ratio between the arguments (a product that leaves the range of
    // f64 falls back to separate divisions), but x + λ ≤ 4 max(x, y, z) must not overflow and
    // subnormal arguments lose bits: rescale those two extremes by a power of 4 (exact).
    let largest = x.max(y).max(z);
    let half_exponent = if largest > TWO_POW_1000 {
        -20
    } else if largest < TWO_POW_M960 {
        -((largest.log2() * 0.5).floor() as i32)
    } else {
        0
    };
    if half_exponent != 0 {
        // x = 4^-k x' gives R_F(x) = 2^k R_F(x') and R_D(x) = 2^3k R_D(x'); the factors are
        // applied one at a time so that a result beyond the range of f64 rounds gracefully.
        let down = pow2(2 * half_exponent);
        let up = pow2(half_exponent);
        let s = symmetric_integrals_in_range(x * down, y * down, z * down);
        return Some(SymmetricIntegrals {
            rf: s.rf * up,
            rd: s.rd.map(|v| v * up * up * up),
        });
    }
    Some(symmetric_integrals_in_range(x, y, z))
}

/// $R_G(x, y, z) = \tfrac{1}{4\pi}\int\_{S^2} \sqrt{x n_1^2 + y n_2^2 + z n_3^2}\\,\mathrm d\Omega$
/// (DLMF 19.16.3): the surface area of the ellipsoid with semi-axes $a, b, c$ is
/// $4\pi abc\\,R_G(a^{-2}, b^{-2}, c^{-2})$ (DLMF 19.33.1).
///
/// By DLMF 19.21.10, $2R_G = zR_F - \tfrac13(x - z)(y - z)R_D(x, y, z) + \sqrt{xy/z}$, with the
/// middle argument in the role of $z$ so that $(x - z)(y - z) \le 0$ and no term cancels;
/// $R_F$ and $R_D$ from [`symmetric_integrals`]. Within 6 ulp of mpmath (worst measured: 2.1).
///
/// Returns `None` unless all three arguments are positive and finite.
///
/// ```
/// use surfgrav_potentials::carlson::rg;
/// // R_G(x, x, x) = √x.
/// assert!((rg(4.0, 4.0, 4.0).unwrap() - 2.0).abs() < 1e-15);
/// assert_eq!(rg(0.0, 1.0, 1.0), None);
/// ```
pub fn rg(x: f64, y: f64, z: f64) -> Option<f64> {
    let mut v = [x, y, z];
    v.sort_by(f64::total_cmp);
    let [x, z, y] = v;
    let s = symmetric_integrals(x, y, z)?;
    Some(0.5 * (z * s.rf - (x - z) * (y - z) * s.rd[2] / 3.0 + (x * y / z).sqrt()))
}

/// $2^k$ for $|k| \le 1074$, as the product of two exact powers of two.
fn pow2(k: i32) -> f64 {
    let half = k / 2;
    f64::powi(2.0, half) * f64::powi(2.0, k - half)
}

/// The fused duplication for positive arguments below $2^{1000}$, not all subnormal.
///
/// This is the ellipsoid's hot path: no validation, no rescaling. Arguments within
/// $2^{\pm 300}$ share one division per step; others take three (their products could leave
/// the range of f64).
#[inline]
pub(crate) fn symmetric_integrals_in_range(x: f64, y: f64, z: f64) -> SymmetricIntegrals {
    if shares_division(x, y, z) {
        duplication::<true>(x, y, z)
    } else {
        duplication::<false>(x, y, z)
    }
}

/// Whether all three arguments lie within $2^{\pm 300}$, where one division serves the three
/// reciprocals of a duplication step (the branch [`rd_lanes`] implements).
#[inline(always)]
pub(crate) fn shares_division(x: f64, y: f64, z: f64) -> bool {
    x.min(y).min(z) >= TWO_POW_M300 && x.max(y).max(z) <= TWO_POW_300
}

/// Duplication and series; `SHARED_DIVISION` computes the three reciprocals of a step from
/// one division (valid when all the products stay within range).
#[inline]
fn duplication<const SHARED_DIVISION: bool>(x: f64, y: f64, z: f64) -> SymmetricIntegrals {
    let (mut xn, mut yn, mut zn) = (x, y, z);
    let mu0 = (x + y + z) / 3.0;
    let (dx0, dy0) = (mu0 - x, mu0 - y);
    let spread = dx0.abs().max(dy0.abs()).max((mu0 - z).abs()) / SERIES_THRESHOLD;
    let mut mu = mu0;
    // 4^-n.
    let mut factor = 1.0;
    let mut sums = [0.0; 3];
    for _ in 0..MAX_STEPS {
        if spread * factor <= mu {
            break;
        }
        let (sx, sy, sz) = (xn.sqrt(), yn.sqrt(), zn.sqrt());
        let (pxy, pxz, pyz) = (sx + sy, sx + sz, sy + sz);
        let (sxy, sxz, syz) = (sx * sy, sx * sz, sy * sz);
        let lambda = sxy + sxz + syz;
        if SHARED_DIVISION {
            // 1/(√x (√x+√y)(√x+√z)) etc. from one division of the product of all three.
            let common = factor / (sxy * sz * (pxy * pxz * pyz));
            sums[0] += common * (syz * pyz);
            sums[1] += common * (sxz * pxz);
            sums[2] += common * (sxy * pxy);
        } else {
            sums[0] += factor / (sx * pxy * pxz);
            sums[1] += factor / (sy * pxy * pyz);
            sums[2] += factor / (sz * pxz * pyz);
        }
        xn = (xn + lambda) * 0.25;
        yn = (yn + lambda) * 0.25;
        zn = (zn + lambda) * 0.25;
        mu = (mu + lambda) * 0.25;
        factor *= 0.25;
    }
    // Deviations from the mean, from the exact shrinkage of the initial ones.
    let scale = factor / mu;
    let zx = dx0 * scale;
    let zy = dy0 * scale;
    let zz = -(zx + zy);
    let e2 = zx * zy - zz * zz;
    let e3 = zx * zy * zz;
    // As few terms as the deviations need (far from a body they are tiny).
    let deviation = zx.abs().max(zy.abs()).max(zz.abs());
    let (rf_series, rd_series) = if deviation <= 1e-3 {
        series::<6>(e2, e3, [zx, zy, zz])
    } else if deviation <= 0.01 {
        series::<8>(e2, e3, [zx, zy, zz])
    } else {
        series::<SERIES_TERMS>(e2, e3, [zx, zy, zz])
    };
    let inv_sqrt_mu = 1.0 / mu.sqrt();
    let tail = factor * inv_sqrt_mu / mu;
    SymmetricIntegrals {
        rf: rf_series * inv_sqrt_mu,
        rd: [
            3.0 * sums[0] + tail * rd_series[0],
            3.0 * sums[1] + tail * rd_series[1],
            3.0 * sums[2] + tail * rd_series[2],
        ],
    }
}

/// The series of $R_F$ and of the three $R_D$ about the common mean, through degree $K - 1$:
/// truncation $\approx 0.4\\,|Z|^K$ (measured against mpmath), below $10^{-17}$ for
/// $K = 6, 8, 12$ at $|Z| \le 10^{-3}, 10^{-2}, 0.04$.
#[inline]
fn series<const K: usize>(e2: f64, e3: f64, deviations: [f64; 3]) -> (f64, [f64; 3]) {
    // Coefficients p_N of (1 + e2 t² − e3 t³)^(−1/2), from the recurrence that its
    // differential equation gives: (N+1) p_{N+1} = −N e2 p_{N−1} + (N − ½) e3 p_{N−2}.
    let mut p = [0.0; K];
    p[0] = 1.0;
    for n in 1..K - 1 {
        let older = if n >= 2 { p[n - 2] } else { 0.0 };
        p[n + 1] = RECURRENCE[n].0 * e2 * p[n - 1] + RECURRENCE[n].1 * e3 * older;
    }
    let mut rf = 0.0;
    for n in (0..K).rev() {
        rf += p[n] * RF_WEIGHTS[n];
    }
    // R_D: Σ 3 c_N/(2N+3) with c_N = Z c_{N−1} + p_N, the three chains interleaved.
    let mut c = [0.0; 3];
    let mut rd = [0.0; 3];
    for n in 0..K {
        for i in 0..3 {
            c[i] = deviations[i] * c[i] + p[n];
            rd[i] += c[i] * RD_WEIGHTS[n];
        }
    }
    (rf, rd)
}

/// The three $R_D$ of [`symmetric_integrals_in_range`] for eight argument triples at once,
/// lane $l$ at $(x_l, y_l, z_l)$, each bit for bit the scalar result.
///
/// Every lane must satisfy [`shares_division`] (a caller substitutes a placeholder such as
/// $(1, 1, 1)$ for a lane it evaluates otherwise). The lanes run the scalar loop's operations in
/// the same order, side by side ([`crate::lanes`]); a lane whose duplication has converged
/// keeps its values (selected, not recomputed) while the others go on, and the series is summed
/// to the largest degree any lane needs, each lane's terms beyond its own degree skipped. $R_F$
/// is not formed (the ellipsoid's field does not use it).
#[inline(always)]
pub(crate) fn rd_lanes(x: F8, y: F8, z: F8) -> [F8; 3] {
    let (mut xn, mut yn, mut zn) = (x, y, z);
    let mu0 = (x + y + z) / 3.0;
    let (dx0, dy0) = (mu0 - x, mu0 - y);
    let spread = dx0.abs().max(dy0.abs()).max((mu0 - z).abs()) / SERIES_THRESHOLD;
    let mut mu = mu0;
    let mut factor = F8::splat(1.0);
    let mut sums = [F8::splat(0.0); 3];
    for _ in 0..MAX_STEPS {
        // The scalar loop's exit test, negated (a NaN keeps a lane going, as there).
        let active = (spread * factor).le(mu).not();
        if !active.any() {
            break;
        }
        let (sx, sy, sz) = (xn.sqrt(), yn.sqrt(), zn.sqrt());
        let (pxy, pxz, pyz) = (sx + sy, sx + sz, sy + sz);
        let (sxy, sxz, syz) = (sx * sy, sx * sz, sy * sz);
        let lambda = sxy + sxz + syz;
        let common = factor / (sxy * sz * (pxy * pxz * pyz));
        sums[0] = active.select(sums[0] + common * (syz * pyz), sums[0]);
        sums[1] = active.select(sums[1] + common * (sxz * pxz), sums[1]);
        sums[2] = active.select(sums[2] + common * (sxy * pxy), sums[2]);
        xn = active.select((xn + lambda) * 0.25, xn);
        yn = active.select((yn + lambda) * 0.25, yn);
        zn = active.select((zn + lambda) * 0.25, zn);
        mu = active.select((mu + lambda) * 0.25, mu);
        factor = active.select(factor * 0.25, factor);
    }
    // Deviations from the mean and the degree each lane's series needs, as in `duplication`.
    let scale = factor / mu;
    let zx = dx0 * scale;
    let zy = dy0 * scale;
    let zz = -(zx + zy);
    let e2 = zx * zy - zz * zz;
    let e3 = zx * zy * zz;
    let deviation = zx.abs().max(zy.abs()).max(zz.abs());
    let low = deviation.le(F8::splat(1e-3));
    let middle = deviation.le(F8::splat(0.01));
    let degree = low.select(
        F8::splat(6.0),
        middle.select(F8::splat(8.0), F8::splat(SERIES_TERMS as f64)),
    );
    // Three fixed-degree instantiations (fully unrolled): the lowest that covers every lane.
    let deviations = [zx, zy, zz];
    let rd_series = if !middle.all() {
        series_lanes::<SERIES_TERMS>(e2, e3, deviations, degree)
    } else if !low.all() {
        series_lanes::<8>(e2, e3, deviations, degree)
    } else {
        series_lanes::<6>(e2, e3, deviations, degree)
    };
    let inv_sqrt_mu = 1.0 / mu.sqrt();
    let tail = factor * inv_sqrt_mu / mu;
    [
        3.0 * sums[0] + tail * rd_series[0],
        3.0 * sums[1] + tail * rd_series[1],
        3.0 * sums[2] + tail * rd_series[2],
    ]
}

/// The $R_D$ series of [`series`] through degree $K - 1$ for the lanes, each lane's terms
/// from its own `degree` on skipped (its sums then stop where the scalar loop stops).
#[inline(always)]
fn series_lanes<const K: usize>(e2: F8, e3: F8, deviations: [F8; 3], degree: F8) -> [F8; 3] {
    let mut p = [F8::splat(0.0); K];
    p[0] = F8::splat(1.0);
    for n in 1..K - 1 {
        let older = if n >= 2 { p[n - 2] } else { F8::splat(0.0) };
        p[n + 1] = RECURRENCE[n].0 * e2 * p[n - 1] + RECURRENCE[n].1 * e3 * older;
    }
    let mut c = [F8::splat(0.0); 3];
    let mut rd = [F8::splat(0.0); 3];
    for (n, &p_n) in p.iter().enumerate() {
        let live = F8::splat(n as f64).lt(degree);
        for i in 0..3 {
            let next_c = deviations[i] * c[i] + p_n;
            rd[i] = live.select(rd[i] + next_c * RD_WEIGHTS[n], rd[i]);
            c[i] = live.select(next_c, c[i]);
        }
    }
    rd
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative error in units of the machine epsilon.
    fn ulps(value: f64, reference: f64) -> f64 {
        ((value - reference) / reference).abs() / f64::EPSILON
    }

    /// Deterministic arguments spread over `[10^-range, 10^range]`.
    fn arguments(n: usize, range: f64) -> Vec<[f64; 3]> {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n)
            .map(|_| [0; 3].map(|_| 10f64.powf(range * (2.0 * uniform() - 1.0))))
            .collect()
    }

    #[test]
    fn equal_arguments_are_powers() {
        for x in [1e-200, 0.3, 1.0, 7.0, 1e200] {
            let s = symmetric_integrals(x, x, x).unwrap();
            assert!(
                ulps(s.rf, 1.0 / x.sqrt()) <= 2.0,
                "R_F({x}, {x}, {x}) = {}",
                s.rf
            );
            for rd in s.rd {
                assert!(
                    ulps(rd, 1.0 / (x * x.sqrt())) <= 2.0,
                    "R_D({x}, {x}, {x}) = {rd}"
                );
            }
        }
    }

    /// The sum rules of DLMF §19.21 tie the three R_D to each other and to R_F; the series and the
    /// duplication sums enter both differently, so an error in either breaks them.
    #[test]
    fn dlmf_identities_hold_over_wide_arguments() {
        for [x, y, z] in arguments(20_000, 40.0) {
            let s = symmetric_integrals(x, y, z).unwrap();
            let [rdx, rdy, rdz] = s.rd;
            // Σ R_D = 3/√(xyz), evaluated without overflow.
            let sum = rdx + rdy + rdz;
            let expected = 3.0 / (x.sqrt() * y.sqrt() * z.sqrt());
            assert!(ulps(sum, expected) <= 8.0, "19.21.7 at {x:e}, {y:e}, {z:e}");
            // x R_D(y,z,x) + y R_D(z,x,y) + z R_D(x,y,z) = 3 R_F.
            let weighted = x * rdx + y * rdy + z * rdz;
            assert!(
                ulps(weighted, 3.0 * s.rf) <= 8.0,
                "19.21.8 at {x:e}, {y:e}, {z:e}"
            );
        }
    }

    /// R_F(x, y, y) = R_C(x, y), elementary (DLMF §19.2(iv)).
    #[test]
    fn two_equal_arguments_give_the_elementary_rc() {
        for (x, y) in [
            (0.5_f64, 2.0_f64),
            (1e-6, 1.0),
            (1.0, 1.0 + 1e-6),
            (3.0, 0.25),
            (1e6, 1.0),
        ] {
            let rc = if x < y {
                ((y - x) / x).sqrt().atan() / (y - x).sqrt()
            } else {
                // artanh t = ½ ln((1 + t)/(1 − t)) with 1 − t² = y/x, free of cancellation.
                let t = ((x - y) / x).sqrt();
                0.5 * ((1.0 + t) * (1.0 + t) * x / y).ln() / (x - y).sqrt()
            };
            let s = symmetric_integrals(x, y, y).unwrap();
            assert!(
                ulps(s.rf, rc) <= 8.0,
                "R_F({x}, {y}, {y}) = {}, R_C = {rc}",
                s.rf
            );
        }
    }

    /// Homogeneity, R_F(kx) = k^{-1/2} R_F(x) and R_D(kx) = k^{-3/2} R_D(x), exercised through
    /// the rescaling of extreme arguments (k a power of 4, so the reference is exact).
    #[test]
    fn homogeneity_through_rescaling() {
        let base = symmetric_integrals(0.7, 2.0, 0.05).unwrap();
        for k in [-505, -490, -330, -300, 300, 330, 490, 505] {
            let scale = 4f64.powi(k);
            let s = symmetric_integrals(0.7 * scale, 2.0 * scale, 0.05 * scale).unwrap();
            let root = 2f64.powi(k);
            assert!(ulps(s.rf * root, base.rf) <= 2.0, "R_F at 4^{k}");
            if 3 * k.abs() > 1000 {
                // R_D itself is beyond the range of f64.
                continue;
            }
            for i in 0..3 {
                let rescaled = s.rd[i] * root * root * root;
                assert!(ulps(rescaled, base.rd[i]) <= 2.0, "R_D[{i}] at 4^{k}");
            }
        }
    }

    /// Values of mpmath 1.3 (`elliprf`, `elliprd` at 30 digits) at argument ratios up to
    /// 10^300, where the duplication sums, not the series, carry the result.
    #[test]
    fn extreme_ratios_match_mpmath() {
        let cases: [([f64; 3], [f64; 4]); 3] = [
            (
                [
                    1.859_428_755_429_706_7e107,
                    1.649_825_022_989_359_3e-126,
                    3.336_578_651_079_886e-194,
                ],
                [
                    6.254_415_928_792_957e-52,
                    1.005_345_120_816_225_4e-158,
                    4.216_902_862_001_317e72,
                    2.965_253_702_160_244_2e106,
                ],
            ),
            (
                [
                    5.930_676_264_102_37e-153,
                    2.125_547_254_363_421e171,
                    1.321_061_190_207_642_3e66,
                ],
                [
                    2.657_268_746_179_076e-84,
                    7.351_437_958_388_435e-43,
                    3.719_858_715_587_191e-255,
                    4.925_643_072_657_718e-152,
                ],
            ),
            // R_D(x, y, 1e300) ≈ 1e-450 underflows to zero: checked separately below.
            (
                [1e-300, 1.0, 1e300],
                [3.467_740_583_102_267_6e-148, 3.0, 3e-150, 0.0],
            ),
        ];
        for ([x, y, z], reference) in cases {
            let s = symmetric_integrals(x, y, z).unwrap();
            let got = [s.rf, s.rd[0], s.rd[1], s.rd[2]];
            for i in 0..4 {
                if reference[i] == 0.0 {
                    assert!(
                        got[i] < 1e-300,
                        "({x:e}, {y:e}, {z:e}) entry {i}: {}",
                        got[i]
                    );
                    continue;
                }
                assert!(
                    ulps(got[i], reference[i]) <= 4.0,
                    "({x:e}, {y:e}, {z:e}) entry {i}: {} vs mpmath {}",
                    got[i],
                    reference[i]
                );
            }
        }
    }

    /// R_G against mpmath 1.3 at 30 digits:
    /// `mpmath.mp.dps = 30; mpmath.elliprg(mpf(x), mpf(y), mpf(z))` with the f64 arguments below
    /// (the first three are (a⁻², b⁻², c⁻²) of the paper's spheroid a = 1, c = 0.25, of semi-axes
    /// 1, 2, 3 and of a needle-thin spheroid c = 100). Tolerance 6 ulp: R_F and R_D are within
    /// 3.8 ulp (module docs), the three terms have the same sign (no cancellation) and add at
    /// most five roundings (two products, a division, two sums); the halving is exact.
    #[test]
    fn rg_matches_mpmath() {
        let cases = [
            ([1.0, 1.0, 16.0], 2.266_388_580_125_985),
            ([1.0, 0.25, 1.0 / 9.0], 0.648_319_601_083_095_8),
            ([1.0, 1.0, 1e-4], 0.785_437_102_891_104_5),
            ([1e-6, 1.0, 1e6], 500.001_948_515_159_2),
            ([0.3, 0.3, 0.3], 0.547_722_557_505_166_1),
            ([2.5, 1e-3, 7.0], 1.686_512_944_603_276),
        ];
        let mut worst: f64 = 0.0;
        for ([x, y, z], reference) in cases {
            for [p, q, r] in [[x, y, z], [z, x, y], [y, z, x], [y, x, z]] {
                let value = rg(p, q, r).unwrap();
                worst = worst.max(ulps(value, reference));
                assert!(
                    ulps(value, reference) <= 6.0,
                    "R_G({p}, {q}, {r}) = {value} vs mpmath {reference}"
                );
            }
        }
        println!("R_G: worst {worst:.2} ulp from mpmath");
        assert_eq!(rg(-1.0, 1.0, 1.0), None);
        assert_eq!(rg(1.0, f64::NAN, 1.0), None);
    }

    /// The lanes give the scalar R_D bit for bit, with lanes of different step counts and
    /// series degrees side by side (ratios up to 10^24, nearly equal triples, equal ones).
    #[test]
    fn rd_lanes_are_the_scalar_rd_bit_for_bit() {
        let mut triples = arguments(4_000, 12.0);
        triples.extend(arguments(1_000, 1e-3).iter().map(|t| t.map(|v| v * 7.0)));
        triples.extend(arguments(1_000, 1e-6));
        triples.extend([[1.0; 3], [2.5; 3], [1.0, 1.0, 1.0 + 1e-15]]);
        triples.extend([[1e-10, 1e10, 1.0], [4.0, 1e-30, 1e-30]]);
        let mut degrees = [0usize; 3];
        // The width the ellipsoid's field uses.
        for chunk in triples.chunks_exact(crate::lanes::WIDE) {
            let lane = |i: usize| F8::new(std::array::from_fn(|l| chunk[l][i]));
            let rd = rd_lanes(lane(0), lane(1), lane(2));
            for (l, &[x, y, z]) in chunk.iter().enumerate() {
                let reference = symmetric_integrals_in_range(x, y, z).rd;
                for i in 0..3 {
                    assert_eq!(
                        rd[i].0[l].to_bits(),
                        reference[i].to_bits(),
                        "R_D[{i}]({x:e}, {y:e}, {z:e}) lane {l}: {} vs {}",
                        rd[i].0[l],
                        reference[i]
                    );
                }
                let mu = (x + y + z) / 3.0;
                let spread = [x, y, z].map(|v| ((mu - v) / mu).abs());
                degrees[usize::from(spread.iter().any(|&d| d > 1e-3))
                    + usize::from(spread.iter().any(|&d| d > 1e-2))] += 1;
            }
        }
        // The three series degrees were all met directly (no duplication step) somewhere.
        assert!(degrees.iter().all(|&n| n > 0), "{degrees:?}");
    }

    #[test]
    fn invalid_arguments_are_rejected() {
        for [x, y, z] in [
            [0.0, 1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, f64::NAN],
            [f64::INFINITY, 1.0, 1.0],
        ] {
            assert_eq!(symmetric_integrals(x, y, z), None);
        }
    }
}
