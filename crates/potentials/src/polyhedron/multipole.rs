//! The exterior multipole expansion of a homogeneous polyhedron, with a rigorous truncation
//! bound: the far-field branch of [`super::Polyhedron`].
//!
//! # Formulas
//!
//! Solid harmonics without the Condon–Shortley phase, for $m \ge 0$,
//! $$R_n^m(\mathbf u) = \frac{u^n P_n^m(\cos\theta)\\,e^{im\varphi}}{(n+m)!},\qquad
//!   I_n^m(\mathbf x) = \frac{(n-m)!\\,P_n^m(\cos\theta)\\,e^{im\varphi}}{x^{n+1}},$$
//! and $X_n^{-m} = \overline{X_n^m}$. The addition theorem of the Legendre polynomials gives, for
//! $|\mathbf u| < |\mathbf x|$,
//! $$\frac{1}{|\mathbf x - \mathbf u|} = \sum\_{n\ge0} \frac{u^n}{x^{n+1}} P_n(\cos\gamma)
//!   = \sum\_{n\ge0}\sum\_{m=-n}^{n} \overline{R_n^m(\mathbf u)}\\, I_n^m(\mathbf x),$$
//! so with the moments $M_n^m = \rho\int_V R_n^m(\mathbf u - \mathbf c)\\,\mathrm dV$ about the
//! centroid $\mathbf c$,
//! $$\Phi(\mathbf p) = -G \sum\_{n\le N} \Bigl[M_n^0 I_n^0 + 2\\,\mathrm{Re}\sum\_{m=1}^{n}
//!   \overline{M_n^m}\\, I_n^m(\mathbf p - \mathbf c)\Bigr] + T_N .$$
//!
//! Recurrences in Cartesian coordinates ($\rho^2 = x^2+y^2+z^2$), from those of $P_n^m$:
//! $R_m^m = \frac{x+iy}{2m} R\_{m-1}^{m-1}$,
//! $R_n^m = \frac{(2n-1) z R\_{n-1}^m - \rho^2 R\_{n-2}^m}{(n-m)(n+m)}$;
//! $I_m^m = (2m-1)\frac{x+iy}{\rho^2} I\_{m-1}^{m-1}$,
//! $I_n^m = \frac{(2n-1) z I\_{n-1}^m - (n+m-1)(n-m-1) I\_{n-2}^m}{\rho^2}$.
//! Derivatives ($\partial\_\pm = \partial_x \pm i\partial_y$): $\partial_z I_n^m = -I\_{n+1}^m$,
//! $\partial\_+ I_n^m = -I\_{n+1}^{m+1}$, $\partial\_- I_n^m = I\_{n+1}^{m-1}$ for $m\ge1$ and
//! $\partial\_- I_n^0 = -\overline{I\_{n+1}^1}$ (the first two by induction on the recurrences;
//! the third from $\partial\_+\partial\_- = -\partial_z^2$ on harmonic functions). A unit test
//! checks the addition theorem and each derivative against finite differences.
//!
//! # Moments
//!
//! Whittaker's integral (Laplace's integral for $P_n^m$) writes each harmonic as a Fourier
//! coefficient of a power of a linear form,
//! $$R_n^m(\mathbf x) = \frac{i^{-m}}{n!}\\,\frac{1}{2\pi}\int_0^{2\pi}
//!   (z + i x\cos u + i y \sin u)^n e^{imu}\\,\mathrm du ,$$
//! and a power of a linear form integrates exactly over a tetrahedron $T$ with vertices
//! $\mathbf 0, \mathbf v_1, \mathbf v_2, \mathbf v_3$:
//! $\int_T (\boldsymbol\ell\cdot\mathbf x)^n\\,\mathrm dV = V_T\\,\frac{n!\\,3!}{(n+3)!}\\,
//! h_n(\boldsymbol\ell\cdot\mathbf v_1, \boldsymbol\ell\cdot\mathbf v_2,
//! \boldsymbol\ell\cdot\mathbf v_3)$, $h_n$ the complete homogeneous symmetric polynomial.
//! Summing signed tetrahedra with apex at $\mathbf c$ over the faces and sampling $u$ at
//! $2N+2$ equispaced angles (exact: the integrand is a trigonometric polynomial of degree
//! $\le N$) gives every moment to degree $N$ in $O(F N^2)$ operations, exact to rounding. A
//! unit test checks them against Gauss quadrature of the surface form
//! $\int_V R_n^m = \frac{1}{n+3}\sum_f d_f\int_f R_n^m\\,\mathrm dA$.
//!
//! # Truncation bound
//!
//! All mass lies within $R$ (the circumscribing radius about $\mathbf c$); with $q = R/|\mathbf
//! p - \mathbf c| < 1$ and $|P_n| \le 1$,
//! $$|T_N| \le \frac{GM}{r}\\,\frac{q^{N+1}}{1-q},\qquad
//!   |\nabla T_N| \le \frac{GM}{r^2} \sum\_{n>N} (n+1) q^n
//!   = \frac{GM}{r^2}\\,\frac{q^{N+1}\\,[(N+2) - (N+1)q]}{(1-q)^2},$$
//! the second from $|\nabla (P_n(\cos\gamma)/r^{n+1})| \le (n+1)/r^{n+2}$, which follows from
//! $(n+1)^2P_n^2 + (1-t^2)P_n'^2 \le n(n+1) + (n+1)P_n^2 \le (n+1)^2$ (the classical
//! $P_n^2 + (1-t^2)P_n'^2/(n(n+1)) \le 1$). Against the lower bounds $|\Phi| \ge GM/(r+R)$ and
//! $|\mathbf a| \ge |\mathbf a\cdot\hat{\mathbf r}| \ge GM (r-R)/(r+R)^3$ (every element pulls
//! inward radially by at least that), the degree $N$ used at a point is the smallest whose
//! relative bounds are both below [`TRUNCATION_REL`].

use nalgebra::Complex;
use rayon::prelude::*;

use crate::{Real, Vec3};

type C64 = Complex<Real>;

/// Relative truncation error allowed in Φ and in the acceleration (half an ulp).
pub(crate) const TRUNCATION_REL: Real = 1.1e-16;

/// Index of $(n, m)$, $0 \le m \le n$, in a triangular array.
#[inline]
pub(crate) fn index(n: usize, m: usize) -> usize {
    n * (n + 1) / 2 + m
}

/// Number of entries for degrees $0..=n$.
#[inline]
fn count(n: usize) -> usize {
    (n + 1) * (n + 2) / 2
}

/// $R_n^m(\mathbf u)$ for $n \le N$ into `out` (length `count(N)`): the tests' independent
/// route to the moments.
#[cfg(test)]
pub(crate) fn regular(u: &Vec3, degree: usize, out: &mut [C64]) {
    let xy = C64::new(u.x, u.y);
    let (z, r2) = (u.z, u.norm_squared());
    out[0] = C64::new(1.0, 0.0);
    for m in 0..=degree {
        let mm = index(m, m);
        if m > 0 {
            out[mm] = out[index(m - 1, m - 1)] * xy / (2 * m) as Real;
        }
        for n in m + 1..=degree {
            let prev = out[index(n - 1, m)] * ((2 * n - 1) as Real * z);
            let prev2 = if n >= m + 2 {
                out[index(n - 2, m)] * r2
            } else {
                C64::new(0.0, 0.0)
            };
            out[index(n, m)] = (prev - prev2) / ((n - m) * (n + m)) as Real;
        }
    }
}

/// $I_n^m(\mathbf x)$ for $n \le N$ into `out` (length `count(N)`).
pub(crate) fn irregular(x: &Vec3, degree: usize, out: &mut [C64]) {
    let r2 = x.norm_squared();
    let inv_r2 = 1.0 / r2;
    let xy = C64::new(x.x, x.y) * inv_r2;
    let z = x.z * inv_r2;
    out[0] = C64::new(1.0 / r2.sqrt(), 0.0);
    for m in 0..=degree {
        let mm = index(m, m);
        if m > 0 {
            out[mm] = out[index(m - 1, m - 1)] * xy * (2 * m - 1) as Real;
        }
        for n in m + 1..=degree {
            let prev = out[index(n - 1, m)] * ((2 * n - 1) as Real * z);
            let prev2 = if n >= m + 2 {
                out[index(n - 2, m)] * ((n + m - 1) * (n - m - 1)) as Real * inv_r2
            } else {
                C64::new(0.0, 0.0)
            };
            out[index(n, m)] = prev - prev2;
        }
    }
}

/// The moments of a body about its centroid, in units of the circumscribing radius.
#[derive(Debug, Clone)]
pub(crate) struct Multipole {
    /// Expansion centre (the centroid), body frame.
    pub centre: Vec3,
    /// Circumscribing radius about `centre`: the length unit of the expansion.
    pub radius: Real,
    /// Highest degree stored.
    pub degree: usize,
    /// $\tilde M_n^m = \rho R^3 \int R_n^m(\tilde{\mathbf u})\\,\mathrm d\tilde V$, mass units.
    pub moments: Vec<C64>,
    /// $w_m\overline{M_n^m}$ ($w_0 = 1$, else 2): Σ = Σ Re($w_m\overline{M_n^m} I_n^m$).
    weighted: Vec<C64>,
    /// Per $(n', m')$, $n' \le$ `degree` + 1, the coefficients $C$ with
    /// $\partial\_{x,y,z}\Sigma = \sum \mathrm{Re}(C\_{x,y,z}\\,I\_{n'}^{m'})$: the derivative
    /// relations of the module docs gathered once (each moment of degree $n$ feeds $n' = n + 1$
    /// only, so truncating the sum at $n' \le N + 1$ is the degree-$N$ gradient).
    gradient: Vec<[C64; 3]>,
}

impl Multipole {
    /// Moments to `degree` of the homogeneous polyhedron with `density`, centred at `centre`
    /// with circumscribing radius `radius`; `faces` counter-clockwise seen from outside.
    pub fn new(
        vertices: &[Vec3],
        faces: &[[u32; 3]],
        density: Real,
        centre: Vec3,
        radius: Real,
        degree: usize,
    ) -> Self {
        let mut moments = volume_moments(vertices, faces, centre, 1.0 / radius, degree);
        let mass_scale = density * radius.powi(3);
        for m in &mut moments {
            *m *= mass_scale;
        }
        let zero = C64::new(0.0, 0.0);
        let mut weighted = vec![zero; count(degree)];
        let mut gradient = vec![[zero; 3]; count(degree + 1)];
        let half_i = C64::new(0.0, 0.5);
        for n in 0..=degree {
            for m in 0..=n {
                let w = if m == 0 { 1.0 } else { 2.0 };
                let mc = moments[index(n, m)].conj() * w;
                weighted[index(n, m)] = mc;
                // ∂x = (∂₊ + ∂₋)/2, ∂y = (∂₊ − ∂₋)/(2i); ∂₊I_n^m = −I_{n+1}^{m+1},
                // ∂₋I_n^m = I_{n+1}^{m−1} (m ≥ 1), ∂₋I_n^0 = −conj(I_{n+1}^1), ∂z I_n^m = −I_{n+1}^m;
                // Re(a conj(b)) = Re(conj(a) b) for the last ∂₋.
                let plus = &mut gradient[index(n + 1, m + 1)];
                plus[0] -= mc * 0.5;
                plus[1] += mc * half_i;
                if m >= 1 {
                    let minus = &mut gradient[index(n + 1, m - 1)];
                    minus[0] += mc * 0.5;
                    minus[1] += mc * half_i;
                } else {
                    let minus = &mut gradient[index(n + 1, 1)];
                    minus[0] += (-mc * 0.5).conj();
                    minus[1] += (-mc * half_i).conj();
                }
                gradient[index(n + 1, m)][2] -= mc;
            }
        }
        Self {
            centre,
            radius,
            degree,
            moments,
            weighted,
            gradient,
        }
    }

    /// The smallest degree whose truncation bounds, relative to the lower bounds of |Φ| and
    /// |a|, are below [`TRUNCATION_REL`] at scaled distance `r` (in units of `radius`); `None`
    /// if the stored degree does not suffice there.
    pub fn degree_needed(&self, r: Real) -> Option<usize> {
        degree_for(1.0 / r, self.degree)
    }

    /// Potential (without the factor −G) and its gradient at body-frame `p`, to `degree`:
    /// returns (Σ, ∇Σ) with Φ = −G Σ and a = G ∇Σ.
    pub fn evaluate(&self, p: &Vec3, degree: usize, scratch: &mut Vec<C64>) -> (Real, Vec3) {
        let x = (p - self.centre) / self.radius;
        scratch.resize(count(degree + 1), C64::new(0.0, 0.0));
        irregular(&x, degree + 1, scratch);
        let irr = &scratch[..];
        // Re(a b) = a.re b.re − a.im b.im: real products only.
        let re = |a: &C64, b: &C64| a.re * b.re - a.im * b.im;
        let sum: Real = self.weighted[..count(degree)]
            .iter()
            .zip(irr)
            .map(|(c, i)| re(c, i))
            .sum();
        let (mut gx, mut gy, mut gz) = (0.0, 0.0, 0.0);
        for (c, i) in self.gradient[..count(degree + 1)].iter().zip(irr) {
            gx += re(&c[0], i);
            gy += re(&c[1], i);
            gz += re(&c[2], i);
        }
        let inv = 1.0 / self.radius;
        (sum * inv, Vec3::new(gx, gy, gz) * (inv * inv))
    }
}

/// $\int_V R_n^m((\mathbf u - \mathbf c)\\,s)\\,\mathrm dV$ (in units scaled by `scale`) for
/// $n \le$ `degree`, exactly to rounding, by signed tetrahedra (apex at the centre) and
/// Whittaker's integral (see the module docs).
pub(crate) fn volume_moments(
    vertices: &[Vec3],
    faces: &[[u32; 3]],
    centre: Vec3,
    scale: Real,
    degree: usize,
) -> Vec<C64> {
    let samples = 2 * degree + 2;
    let angles: Vec<(Real, Real)> = (0..samples)
        .map(|k| {
            let u = 2.0 * std::f64::consts::PI * k as Real / samples as Real;
            (u.cos(), u.sin())
        })
        .collect();
    let width = degree + 1;
    let zero = C64::new(0.0, 0.0);
    // S[k][n] = Σ_t V_t h_n(ℓ_k·v₁, ℓ_k·v₂, ℓ_k·v₃), ℓ_k·x = z + i(x cos u_k + y sin u_k).
    // Fixed chunks summed in order: the same moments, bit for bit, on every run (a rayon
    // fold/reduce splits by work stealing, and the rounding of the sums then varied).
    let chunk_sums: Vec<Vec<C64>> = faces
        .par_chunks(256)
        .map(|chunk| {
            chunk
                .iter()
                .fold(vec![zero; samples * width], |mut acc, f| {
                    let [a, b, c] = f.map(|i| (vertices[i as usize] - centre) * scale);
                    let volume = a.dot(&b.cross(&c)) / 6.0;
                    for (k, &(cu, su)) in angles.iter().enumerate() {
                        let l = |v: &Vec3| C64::new(v.z, v.x * cu + v.y * su);
                        let (la, lb, lc) = (l(&a), l(&b), l(&c));
                        let row = &mut acc[k * width..(k + 1) * width];
                        // h_n of one, two, three variables by the recurrences of Π 1/(1 − a_j t).
                        let (mut p1, mut p2, mut p3) =
                            (C64::new(1.0, 0.0), C64::new(1.0, 0.0), C64::new(1.0, 0.0));
                        row[0] += volume;
                        for entry in row.iter_mut().skip(1) {
                            p1 *= la;
                            p2 = p2 * lb + p1;
                            p3 = p3 * lc + p2;
                            *entry += p3 * volume;
                        }
                    }
                    acc
                })
        })
        .collect();
    let mut sums = vec![zero; samples * width];
    for part in &chunk_sums {
        for (xk, yk) in sums.iter_mut().zip(part) {
            *xk += yk;
        }
    }
    // ∫_V R_n^m = i^{−m} 6/(n+3)! · (1/K) Σ_k S[k][n] e^{i m u_k}.
    let mut out = vec![zero; count(degree)];
    let mut factor = 1.0; // 6/(n+3)! at n = 0
    for n in 0..=degree {
        if n > 0 {
            factor /= (n + 3) as Real;
        }
        for m in 0..=n {
            let mut c = zero;
            for (k, _) in angles.iter().enumerate() {
                let u = 2.0 * std::f64::consts::PI * ((m * k) % samples) as Real / samples as Real;
                c += sums[k * width + n] * C64::new(u.cos(), u.sin());
            }
            let i_pow = match m % 4 {
                0 => C64::new(1.0, 0.0),
                1 => C64::new(0.0, -1.0),
                2 => C64::new(-1.0, 0.0),
                _ => C64::new(0.0, 1.0),
            };
            out[index(n, m)] = c * i_pow * (factor / samples as Real);
        }
    }
    out
}

impl Multipole {
    /// Hessian of Σ (Φ = −G Σ) at body-frame `p` to `degree`: the gravity-gradient tensor is
    /// G times it. Second derivatives by applying the derivative relations twice, with
    /// $I_n^{-m} = \overline{I_n^m}$.
    pub fn hessian(&self, p: &Vec3, degree: usize) -> nalgebra::Matrix3<Real> {
        let x = (p - self.centre) / self.radius;
        let mut irr = vec![C64::new(0.0, 0.0); count(degree + 2)];
        irregular(&x, degree + 2, &mut irr);
        let get = |n: usize, m: i64| {
            if m >= 0 {
                irr[index(n, m as usize)]
            } else {
                irr[index(n, (-m) as usize)].conj()
            }
        };
        let mut h = nalgebra::Matrix3::zeros();
        for n in 0..=degree {
            for m in 0..=n {
                let w = if m == 0 { 1.0 } else { 2.0 };
                let mc = self.moments[index(n, m)].conj() * w;
                for a in 0..3 {
                    for b in a..3 {
                        let mut value = C64::new(0.0, 0.0);
                        for (c1, m1) in derivative(a, m as i64) {
                            for (c2, m2) in derivative(b, m1) {
                                value += c1 * c2 * get(n + 2, m2);
                            }
                        }
                        let v = (mc * value).re;
                        h[(a, b)] += v;
                        if a != b {
                            h[(b, a)] += v;
                        }
                    }
                }
            }
        }
        h / self.radius.powi(3)
    }
}

/// ∂_axis I_n^m as a combination of I_{n+1}^{m'} (any sign of m): z: −I^m; x and y from
/// ∂_± (∂_+ I^m = ∓I^{m+1} for m ≥ 0 / m < 0, ∂_− I^m = ±I^{m−1} for m ≥ 1 / m ≤ 0).
fn derivative(axis: usize, m: i64) -> Vec<(C64, i64)> {
    let plus = if m >= 0 { -1.0 } else { 1.0 };
    let minus = if m >= 1 { 1.0 } else { -1.0 };
    match axis {
        0 => vec![
            (C64::new(plus / 2.0, 0.0), m + 1),
            (C64::new(minus / 2.0, 0.0), m - 1),
        ],
        // 1/(2i) = −i/2.
        1 => vec![
            (C64::new(0.0, -plus / 2.0), m + 1),
            (C64::new(0.0, minus / 2.0), m - 1),
        ],
        _ => vec![(C64::new(-1.0, 0.0), m)],
    }
}

/// Relative truncation bound of the Hessian at `q = R/r`, against the tidal scale GM/r³, by
/// Cauchy's estimates for harmonic functions on the ball B(p, ρ), ρ = (r − R)/2:
/// |∂_i∂_j u(p)| ≤ 36/ρ² sup_B |u| (the gradient estimate |∇u| ≤ 3/ρ′ sup|u| applied twice on
/// radius ρ/2), spectral norm ≤ 3 max entry, and sup_B |T_N| ≤ GM/r′ q′^{N+1}/(1 − q′) with
/// r′ = r − ρ, q′ = R/r′.
pub(crate) fn hessian_relative_bound(q: Real, degree: usize) -> Real {
    if q.is_nan() || q >= 1.0 {
        return Real::INFINITY;
    }
    // Lengths in units of r.
    let rho = (1.0 - q) / 2.0;
    let r1 = 1.0 - rho;
    let q1 = q / r1;
    108.0 / (rho * rho * r1) * q1.powi(degree as i32 + 1) / (1.0 - q1)
}

/// The truncation bounds of the module docs, relative to the lower bounds of |Φ| and |a|.
pub(crate) fn relative_bounds(q: Real, degree: usize) -> (Real, Real) {
    let n = degree as Real;
    let qn = q.powi(degree as i32 + 1);
    let phi = qn * (1.0 + q) / (1.0 - q);
    let acc = qn * ((n + 2.0) - (n + 1.0) * q) * ((1.0 + q) / (1.0 - q)).powi(3);
    (phi, acc)
}

/// Smallest degree ≤ `max` meeting [`TRUNCATION_REL`] at `q = R/r`.
pub(crate) fn degree_for(q: Real, max: usize) -> Option<usize> {
    // Also rejects NaN.
    if q.is_nan() || q >= 1.0 {
        return None;
    }
    (0..=max).find(|&n| {
        let (phi, acc) = relative_bounds(q, n);
        phi <= TRUNCATION_REL && acc <= TRUNCATION_REL
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum_series(x: &Vec3, u: &Vec3, degree: usize) -> Real {
        let mut rr = vec![C64::new(0.0, 0.0); count(degree)];
        let mut ii = vec![C64::new(0.0, 0.0); count(degree)];
        regular(u, degree, &mut rr);
        irregular(x, degree, &mut ii);
        let mut s = 0.0;
        for n in 0..=degree {
            for m in 0..=n {
                let w = if m == 0 { 1.0 } else { 2.0 };
                s += w * (rr[index(n, m)].conj() * ii[index(n, m)]).re;
            }
        }
        s
    }

    /// The addition theorem: the series converges to 1/|x − u| like (u/x)^(N+1).
    #[test]
    fn addition_theorem() {
        let x = Vec3::new(0.7, -0.4, 0.59);
        let u = Vec3::new(-0.12, 0.21, 0.15);
        let exact = 1.0 / (x - u).norm();
        let q = u.norm() / x.norm();
        for degree in [2, 6, 12, 30] {
            let err = (sum_series(&x, &u, degree) - exact).abs();
            let bound = q.powi(degree as i32 + 1) / (1.0 - q) / x.norm() + 1e-15 * exact;
            assert!(
                err <= bound,
                "degree {degree}: error {err:e} > bound {bound:e}"
            );
        }
        assert!((sum_series(&x, &u, 40) - exact).abs() < 1e-15 * exact);
    }

    /// The derivative relations of the module docs, against central differences.
    #[test]
    fn derivative_relations() {
        let x = Vec3::new(0.6, 0.35, -0.5);
        let degree = 6;
        let mut base = vec![C64::new(0.0, 0.0); count(degree + 1)];
        irregular(&x, degree + 1, &mut base);
        let h = 1e-5;
        let mut plus = base.clone();
        let mut minus = base.clone();
        for axis in 0..3 {
            let e = Vec3::ith(axis, h);
            irregular(&(x + e), degree + 1, &mut plus);
            irregular(&(x - e), degree + 1, &mut minus);
            for n in 0..=degree {
                for m in 0..=n {
                    let fd = (plus[index(n, m)] - minus[index(n, m)]) / (2.0 * h);
                    let p = -base[index(n + 1, m + 1)];
                    let mi = if m >= 1 {
                        base[index(n + 1, m - 1)]
                    } else {
                        -base[index(n + 1, 1)].conj()
                    };
                    let exact = match axis {
                        0 => (p + mi) * 0.5,
                        1 => (p - mi) / C64::new(0.0, 2.0),
                        _ => -base[index(n + 1, m)],
                    };
                    let scale = base[index(n + 1, 0)].norm() + exact.norm();
                    assert!(
                        (fd - exact).norm() < 1e-8 * scale,
                        "∂{axis} I_{n}^{m}: fd {fd}, formula {exact}"
                    );
                }
            }
        }
    }

    /// The simplex/Whittaker moments against the face quadrature of the homogeneity identity
    /// ∫_V R = 1/(n+3) Σ_f d_f ∫_f R dA (collapsed Gauss–Legendre, exact for degree ≤ 2q − 2).
    #[test]
    fn volume_moments_match_face_quadrature() {
        use surfgrav_quadrature::{GaussLegendre, Rule1D};
        let mesh = crate::Mesh::ellipsoid(1.0, 0.8, 0.5, 1);
        let vertices: Vec<Vec3> = mesh
            .vertices
            .iter()
            .map(|v| v + Vec3::new(0.1, -0.05, 0.02))
            .collect();
        let faces: Vec<[u32; 3]> = mesh.faces.iter().map(|f| f.map(|i| i as u32)).collect();
        let degree = 12;
        let centre = Vec3::new(0.05, 0.02, -0.03);
        let fast = volume_moments(&vertices, &faces, centre, 1.0, degree);
        let rule = GaussLegendre::new(degree / 2 + 2, 0.0, 1.0).unwrap();
        let mut slow = vec![C64::new(0.0, 0.0); count(degree)];
        let mut buf = slow.clone();
        for f in &faces {
            let [a, b, c] = f.map(|i| vertices[i as usize] - centre);
            let cross = (b - a).cross(&(c - a));
            let d = a.dot(&cross) / cross.norm();
            for (&s, &ws) in rule.nodes().iter().zip(rule.weights()) {
                for (&t, &wt) in rule.nodes().iter().zip(rule.weights()) {
                    regular(&(a + (b - a) * s + (c - b) * (s * t)), degree, &mut buf);
                    for (x, y) in slow.iter_mut().zip(&buf) {
                        *x += y * (d * cross.norm() * s * ws * wt);
                    }
                }
            }
        }
        for n in 0..=degree {
            for m in 0..=n {
                let k = index(n, m);
                let expected = slow[k] / (n + 3) as Real;
                // Compare against the size of the degree's largest moment.
                let scale = (0..=n)
                    .map(|j| slow[index(n, j)].norm())
                    .fold(0.0, Real::max)
                    / (n + 3) as Real;
                assert!(
                    (fast[k] - expected).norm() <= 1e-13 * scale,
                    "M_{n}^{m}: {} vs {}",
                    fast[k],
                    expected
                );
            }
        }
    }

    /// The Hessian by the derivative relations against central differences of the gradient.
    #[test]
    fn hessian_matches_differences_of_the_gradient() {
        let mesh = crate::Mesh::ellipsoid(1.0, 0.7, 0.4, 1);
        let faces: Vec<[u32; 3]> = mesh.faces.iter().map(|f| f.map(|i| i as u32)).collect();
        let mp = Multipole::new(&mesh.vertices, &faces, 1.0, Vec3::zeros(), 1.0, 10);
        let p = Vec3::new(2.1, -1.3, 1.7);
        let h = mp.hessian(&p, 10);
        let mut scratch = Vec::new();
        let step = 1e-5;
        for b in 0..3 {
            let e = Vec3::ith(b, step);
            let gp = mp.evaluate(&(p + e), 10, &mut scratch).1;
            let gm = mp.evaluate(&(p - e), 10, &mut scratch).1;
            let fd = (gp - gm) / (2.0 * step);
            for a in 0..3 {
                assert!(
                    (fd[a] - h[(a, b)]).abs() < 1e-8 * h.norm(),
                    "H[{a}{b}] = {}, difference {}",
                    h[(a, b)],
                    fd[a]
                );
            }
        }
        // Laplace: the trace vanishes outside.
        assert!(h.trace().abs() < 1e-14 * h.norm());
    }

    #[test]
    fn degree_choice_is_monotone_and_bounded() {
        assert_eq!(degree_for(1.0, 40), None);
        let mut last = usize::MAX;
        for r in [4.0, 8.0, 16.0, 1e3, 1e8] {
            let n = degree_for(1.0 / r, 60).unwrap();
            assert!(n <= last);
            last = n;
        }
        assert!(degree_for(1e-8, 60).unwrap() <= 2);
    }
}
