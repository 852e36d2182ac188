//! The local (interior, regular) expansion of a polyhedron's field about a point outside it:
//! valid in a ball that avoids the body's circumscribing sphere, so that a partner body inside
//! that ball sees the field at a few hundred operations per point instead of a sum over every
//! face.
//!
//! # Formulas
//!
//! With the solid harmonics of [`super::multipole`] and the derivative operators $\partial^{(j,k)}
//! = \partial\_+^k\partial_z^{j-k}$ ($k \ge 0$) and $\partial\_-^{|k|}\partial_z^{j-|k|}$ ($k <
//! 0$), $\partial\_\pm = \partial_x \pm i\partial_y$, the irregular harmonics are $I_n^m =
//! (-1)^n\partial^{(n,m)}(1/r)$ and, on harmonic functions (where $\partial\_+\partial\_- =
//! -\partial_z^2$), Taylor's operator is $e^{\mathbf u\cdot\nabla} = \sum\_{j,k}
//! \overline{R_j^k(\mathbf u)}\\,\partial^{(j,k)}$ (apply both sides to $1/r$: it is the addition
//! theorem $1/|\mathbf x - \mathbf u| = \sum \overline{R_j^k(\mathbf u)} I_j^k(\mathbf x)$ with
//! $\mathbf u \to -\mathbf u$; the $I_j^k$ are independent, so the identity holds on every
//! harmonic function). Hence, with $\mathbf X$ the expansion centre $\mathbf c$ less the centroid,
//! $$\Sigma(\mathbf c + \mathbf u) = \sum\_{n \le P}\sum_m \overline{M_n^m}\\, I_n^m(\mathbf X +
//!   \mathbf u) = \sum\_{j\le N}\sum\_{k} \overline{R_j^k(\mathbf u)}\\, L_j^k,\qquad
//!   L_j^k = \sum\_{n\le P}\sum\_{m} \overline{M_n^m}\\,(-1)^{j}\\,\sigma\_{km}\\,
//!   I\_{n+j}^{m+k}(\mathbf X),$$
//! $\sigma\_{km} = (-1)^{\min(|k|,|m|)}$ when $k$ and $m$ have opposite signs, else 1 (from
//! $\partial\_+\partial\_- = -\partial_z^2$). $\Phi = -G\Sigma$. The gradient's coefficients are
//! the $L$ of one degree more: $\partial_z \to L\_{j+1}^k$, $\partial\_+ \to \pm L\_{j+1}^{k+1}$,
//! $\partial\_- \to \pm L\_{j+1}^{k-1}$ (minus when the operator lowers $|k|$).
//!
//! # Truncation bound
//!
//! All mass lies within $R$ of the centroid; let $D = |\mathbf X|$, $r$ the ball's radius,
//! $\rho = D - R$ and $q = r/\rho < 1$. Two truncations, each bounded for every $|\mathbf u|\le
//! r$ (in units of $GM$):
//!
//! - **Local degree $N$.** A mass element at distance $\ge\rho$ from $\mathbf c$ contributes
//!   $\sum\_{j} |\mathbf u|^j P_j(\cos\gamma)/x^{j+1}$; with $|P_j| \le 1$ and $|\nabla(u^jP_j)|
//!   \le \sqrt{j(j+1)}\\,u^{j-1}$ (from $(1-t^2)P_j'^2 \le j(j+1)(1-P_j^2)$), the tail is at most
//!   $\frac{1}{\rho}\frac{q^{N+1}}{1-q}$ in $\Phi$ and $\frac{1}{\rho^2}\frac{q^N[(N+2) -
//!   (N+1)q]}{(1-q)^2}$ in $\mathbf a$.
//! - **Source degree $P$.** The exterior terms $n > P$ left out of $L$ change the local sum by
//!   at most the sum over $j \le N$ of the bidegree-$(n,j)$ parts of $1/|\mathbf X + \mathbf u -
//!   \mathbf x'|$. By Banach's theorem (a symmetric multilinear form on a real Hilbert space has
//!   the norm of its polynomial) each is at most $\binom{n+j}{n}R^n r^j/D^{n+j+1}$, which sum
//!   over $j$ to $R^n/(D-r)^{n+1}$: so with $q' = R/(D - r)$ the bound is
//!   $\frac{1}{D-r}\frac{q'^{P+1}}{1-q'}$ in $\Phi$ and $\frac{1}{(D-r)^2}\frac{q'^{P+1}[(P+2) -
//!   (P+1)q']}{(1-q')^2}$ in $\mathbf a$ (differentiating in $r$).
//!
//! Relative to the lower bounds $|\Phi| \ge 1/(D + r + R)$ and $|\mathbf a| \ge \min\_{s = D\pm
//! r}(s-R)/(s+R)^3$ (every element pulls toward the centroid's side by at least that; the
//! function is unimodal in $s$), the degrees chosen are the smallest whose sum of bounds is
//! below the caller's relative bound, $P$ taking a tenth of it.
//!
//! # Rounding
//!
//! The moments carry an absolute rounding of about $\varepsilon/n!$ (module [`super::reach`]), and
//! the series in $L$ re-sums $I_n^m(\mathbf X + \mathbf u)$, at most $(2n-1)!!/(D-r)^{n+1}$: the
//! same $\varepsilon(2R/(D-r))^n$ per degree as the exterior expansion at the ball's nearest
//! point. So the expansion is offered only when $D - r \ge$ [`REACH_RADII`] $R$, like the
//! exterior one.

use nalgebra::Complex;

use super::multipole::{self, index};
use super::reach::{REACH_DEGREE, REACH_RADII};
use super::Polyhedron;
use crate::{Field, Real, Vec3};

type C64 = Complex<Real>;

/// Highest local degree offered: beyond it the exterior expansion or the direct sum is cheaper.
pub const LOCAL_MAX_DEGREE: usize = 40;

/// Share of the relative bound given to the source (exterior) truncation.
const SOURCE_SHARE: Real = 0.1;

/// The field of a polyhedron inside a ball outside it, by its local expansion (module docs):
/// built by [`Polyhedron::local_expansion`], evaluated by [`LocalExpansion::field`].
#[derive(Debug, Clone)]
pub struct LocalExpansion {
    centre: Vec3,
    radius: Real,
    degree: usize,
    source_degree: usize,
    bound: Real,
    gravitational_constant: Real,
    /// The source's circumscribing radius: the expansion's length unit.
    unit: Real,
    /// Per $(n, m)$, $m$-major ($m = 0..N$, then $n = m..N$): the coefficients of Σ and of its
    /// three derivatives (weights and the ball's scale folded in), and the recurrence's
    /// factors $(2n-1)/((n-m)(n+m))$ and $1/((n-m)(n+m))$.
    terms: Vec<Term>,
}

#[derive(Debug, Clone, Copy)]
struct Term {
    coefficients: [C64; 4],
    a: Real,
    b: Real,
}

/// The local expansion's relative bounds on Φ and |a| (module docs) for a ball of radius `r`
/// at `d` from the centroid of a body of circumscribing radius `big_r`, at local degree `n`
/// and source degree `p`: (local part, source part) of each, as (Φ, a) pairs.
fn relative_bounds(d: Real, r: Real, big_r: Real, n: usize, p: usize) -> [(Real, Real); 2] {
    let rho = d - big_r;
    let q = r / rho;
    let s = d - r;
    let qs = big_r / s;
    let phi_min = 1.0 / (d + r + big_r);
    let pull = |s: Real| (s - big_r) / (s + big_r).powi(3);
    let acc_min = pull(d - r).min(pull(d + r));
    let (nf, pf) = (n as Real, p as Real);
    let local_phi = q.powi(n as i32 + 1) / (1.0 - q) / rho;
    let local_acc =
        q.powi(n as i32) * ((nf + 2.0) - (nf + 1.0) * q) / (1.0 - q).powi(2) / (rho * rho);
    let source_phi = qs.powi(p as i32 + 1) / (1.0 - qs) / s;
    let source_acc =
        qs.powi(p as i32 + 1) * ((pf + 2.0) - (pf + 1.0) * qs) / (1.0 - qs).powi(2) / (s * s);
    [
        (local_phi / phi_min, local_acc / acc_min),
        (source_phi / phi_min, source_acc / acc_min),
    ]
}

impl Polyhedron {
    /// The (local, source) degrees of [`Self::local_expansion`] for a ball of `radius` whose
    /// centre is `distance` from the centroid, meeting `relative_bound`; `None` where the ball
    /// comes within [`REACH_RADII`] circumscribing radii of the centroid (near contact), or the
    /// degrees would exceed [`LOCAL_MAX_DEGREE`] or the stored moments.
    pub fn local_expansion_degrees(
        &self,
        distance: Real,
        radius: Real,
        relative_bound: Real,
    ) -> Option<(usize, usize)> {
        let big_r = self.circumscribing_radius;
        let usable = radius >= 0.0
            && relative_bound > 0.0
            && distance - radius >= REACH_RADII * big_r
            && distance.is_finite();
        if !usable {
            return None;
        }
        let p = (0..=REACH_DEGREE).find(|&p| {
            let [_, (phi, acc)] = relative_bounds(distance, radius, big_r, 0, p);
            phi <= SOURCE_SHARE * relative_bound && acc <= SOURCE_SHARE * relative_bound
        })?;
        let n = (0..=LOCAL_MAX_DEGREE).find(|&n| {
            let [(lp, la), (sp, sa)] = relative_bounds(distance, radius, big_r, n, p);
            lp + sp <= relative_bound && la + sa <= relative_bound
        })?;
        Some((n, p))
    }

    /// The local expansion of this body's field about body-frame `centre`, valid within
    /// `radius` of it, with truncation bounds relative to $|\Phi|$ and $|\mathbf a|$ below
    /// `relative_bound` everywhere in that ball (module docs); `None` where
    /// [`Self::local_expansion_degrees`] is. The first call builds the degree-60 moments.
    pub fn local_expansion(
        &self,
        centre: &Vec3,
        radius: Real,
        relative_bound: Real,
    ) -> Option<LocalExpansion> {
        let x = centre - self.centroid;
        let (degree, source_degree) =
            self.local_expansion_degrees(x.norm(), radius, relative_bound)?;
        let mp = self.reach_multipole();
        let unit = mp.radius;
        let xs = x / unit;
        // Rows over m = -n..n (entry n² + n + m): I_n^m(X) to degree P + N, conj(M_n^m), and
        // conj(M_n^m) (-1)^m for the mixed-sign terms.
        let top = source_degree + degree;
        let mut irr = vec![C64::new(0.0, 0.0); index(top, top) + 1];
        multipole::irregular(&xs, top, &mut irr);
        let full = |n: usize, at: &dyn Fn(usize, usize) -> C64| -> Vec<C64> {
            (0..=n)
                .flat_map(|i| {
                    let row: Vec<C64> = (0..=2 * i)
                        .map(|e| {
                            let m = e as i64 - i as i64;
                            if m >= 0 {
                                at(i, m as usize)
                            } else {
                                at(i, (-m) as usize).conj()
                            }
                        })
                        .collect();
                    row
                })
                .collect()
        };
        let irr = full(top, &|n, m| irr[index(n, m)]);
        let moments = full(source_degree, &|n, m| mp.moments[index(n, m)].conj());
        let alternating: Vec<C64> = (0..=source_degree)
            .flat_map(|n| (0..=2 * n).map(move |e| (n, e)))
            .zip(&moments)
            .map(|((n, e), c)| if (n + e) % 2 == 1 { -c } else { *c })
            .collect();
        // L_j^k, k ≥ 0 (L_j^{-k} is its conjugate: the field is real).
        let mut l = vec![C64::new(0.0, 0.0); index(degree, degree) + 1];
        for j in 0..=degree {
            for k in 0..=j {
                let mut sum = C64::new(0.0, 0.0);
                for n in 0..=source_degree {
                    // Entry (n, m) of the moments at n² + n + m; (n + j, m + k) of irr at
                    // (n+j)² + (n+j) + m + k.
                    let row = n * n + n;
                    let irow = (n + j) * (n + j) + (n + j) + k;
                    let at = |m: i64| (row as i64 + m) as usize;
                    let iat = |m: i64| (irow as i64 + m) as usize;
                    let (n, k) = (n as i64, k as i64);
                    // σ = 1 for m ≥ 0, (-1)^k for m < -k, (-1)^m for -k ≤ m < 0.
                    sum += dot(&moments[at(0)..=at(n)], &irr[iat(0)..=iat(n)]);
                    let far = dot(
                        &moments[at(-n)..at(-n.min(k))],
                        &irr[iat(-n)..iat(-n.min(k))],
                    );
                    sum += if k % 2 == 1 { -far } else { far };
                    let m0 = -n.min(k);
                    sum += dot(&alternating[at(m0)..at(0)], &irr[iat(m0)..iat(0)]);
                }
                l[index(j, k)] = if j % 2 == 1 { -sum } else { sum };
            }
        }
        let l_at = |j: usize, k: i64| {
            if k >= 0 {
                l[index(j, k as usize)]
            } else {
                l[index(j, (-k) as usize)].conj()
            }
        };
        // Coefficients in the ball's unit v = u / radius: R_j^k(u / R) = s^j R_j^k(v).
        let s = radius / unit;
        let half = 0.5;
        let minus_half_i = C64::new(0.0, -0.5);
        let mut terms = Vec::with_capacity(index(degree, degree) + 1);
        for k in 0..=degree {
            for j in k..=degree {
                let w = if k == 0 { 1.0 } else { 2.0 };
                let scale = w * s.powi(j as i32);
                let phi = l_at(j, k as i64) * scale;
                let (gx, gy, gz) = if j < degree {
                    let up = l_at(j + 1, k as i64 + 1);
                    let (gx, gy) = if k == 0 {
                        (C64::new(up.re, 0.0), C64::new(up.im, 0.0))
                    } else {
                        let down = l_at(j + 1, k as i64 - 1);
                        ((up - down) * half, (up + down) * minus_half_i)
                    };
                    (gx * scale, gy * scale, l_at(j + 1, k as i64) * scale)
                } else {
                    Default::default()
                };
                let (a, b) = if j > k {
                    let inv = 1.0 / ((j - k) * (j + k)) as Real;
                    ((2 * j - 1) as Real * inv, inv)
                } else {
                    (0.0, 0.0)
                };
                terms.push(Term {
                    coefficients: [phi, gx, gy, gz],
                    a,
                    b,
                });
            }
        }
        let [(lp, la), (sp, sa)] = relative_bounds(
            x.norm(),
            radius,
            self.circumscribing_radius,
            degree,
            source_degree,
        );
        Some(LocalExpansion {
            centre: *centre,
            radius,
            degree,
            source_degree,
            bound: (lp + sp).max(la + sa),
            gravitational_constant: self.gravitational_constant,
            unit,
            terms,
        })
    }
}

/// $\sum_i a_i b_i$ over two rows of equal length.
#[inline]
fn dot(a: &[C64], b: &[C64]) -> C64 {
    // Four independent accumulators: the additions do not wait on each other.
    let mut s = [0.0; 4];
    let (pairs_a, pairs_b) = (a.chunks_exact(2), b.chunks_exact(2));
    let (rest_a, rest_b) = (pairs_a.remainder(), pairs_b.remainder());
    for (x, y) in pairs_a.zip(pairs_b) {
        s[0] += x[0].re * y[0].re - x[0].im * y[0].im;
        s[1] += x[0].re * y[0].im + x[0].im * y[0].re;
        s[2] += x[1].re * y[1].re - x[1].im * y[1].im;
        s[3] += x[1].re * y[1].im + x[1].im * y[1].re;
    }
    for (x, y) in rest_a.iter().zip(rest_b) {
        s[0] += x.re * y.re - x.im * y.im;
        s[1] += x.re * y.im + x.im * y.re;
    }
    C64::new(s[0] + s[2], s[1] + s[3])
}

impl LocalExpansion {
    /// Centre of the ball (the polyhedron's body frame).
    pub fn centre(&self) -> Vec3 {
        self.centre
    }

    /// Radius of the ball within which the bound holds.
    pub fn radius(&self) -> Real {
        self.radius
    }

    /// Local degree $N$.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Degree $P$ of the exterior moments translated.
    pub fn source_degree(&self) -> usize {
        self.source_degree
    }

    /// The truncation bound relative to $|\Phi|$ and to $|\mathbf a|$, valid in the ball (at
    /// most the bound asked for).
    pub fn relative_bound(&self) -> Real {
        self.bound
    }

    /// Whether body-frame `p` lies in the ball where the bound holds.
    pub fn contains(&self, p: &Vec3) -> bool {
        (p - self.centre).norm() <= self.radius
    }

    /// The fields at body-frame `points` into `out` (same length), four points at a time
    /// (each coefficient loaded once for four points): equal bit for bit to [`Self::field`]
    /// point by point, the same operations in the same order per point.
    pub fn fields_into(&self, points: &[Vec3], out: &mut [Field]) {
        assert_eq!(points.len(), out.len(), "one output per point");
        let mut quads = points.chunks_exact(4);
        let mut outs = out.chunks_exact_mut(4);
        for (p, o) in (&mut quads).zip(&mut outs) {
            o.copy_from_slice(&self.field4([&p[0], &p[1], &p[2], &p[3]]));
        }
        for (p, o) in quads.remainder().iter().zip(outs.into_remainder()) {
            *o = self.field(p);
        }
    }

    fn field4(&self, p: [&Vec3; 4]) -> [Field; 4] {
        const L: usize = 4;
        let (mut x, mut y, mut z, mut r2) = ([0.0; L], [0.0; L], [0.0; L], [0.0; L]);
        for l in 0..L {
            let v = (p[l] - self.centre) / self.radius;
            (x[l], y[l], z[l], r2[l]) = (v.x, v.y, v.z, v.norm_squared());
        }
        let mut acc = [[0.0; L]; 4];
        let (mut dre, mut dim) = ([1.0; L], [0.0; L]);
        let mut at = 0;
        for m in 0..=self.degree {
            if m > 0 {
                let f = 0.5 / m as Real;
                for l in 0..L {
                    let re = dre[l] * x[l] - dim[l] * y[l];
                    let im = dre[l] * y[l] + dim[l] * x[l];
                    (dre[l], dim[l]) = (re * f, im * f);
                }
            }
            let (mut p2re, mut p2im) = ([0.0; L], [0.0; L]);
            let (mut pre, mut pim) = (dre, dim);
            for n in m..=self.degree {
                let t = &self.terms[at];
                at += 1;
                if n > m {
                    for l in 0..L {
                        let (s1, s2) = (t.a * z[l], t.b * r2[l]);
                        let re = pre[l] * s1 - p2re[l] * s2;
                        let im = pim[l] * s1 - p2im[l] * s2;
                        (p2re[l], p2im[l]) = (pre[l], pim[l]);
                        (pre[l], pim[l]) = (re, im);
                    }
                }
                for (s, c) in acc.iter_mut().zip(&t.coefficients) {
                    for l in 0..L {
                        s[l] += pre[l] * c.re + pim[l] * c.im;
                    }
                }
            }
        }
        let g = self.gravitational_constant;
        let inv = 1.0 / self.unit;
        std::array::from_fn(|l| Field {
            potential: -g * acc[0][l] * inv,
            acceleration: Vec3::new(acc[1][l], acc[2][l], acc[3][l]) * (g * inv * inv),
        })
    }

    /// The field at body-frame `p` (meaningful within the ball: [`Self::contains`]).
    #[inline]
    pub fn field(&self, p: &Vec3) -> Field {
        let v = (p - self.centre) / self.radius;
        let xy = C64::new(v.x, v.y);
        let (z, r2) = (v.z, v.norm_squared());
        let mut acc = [0.0; 4];
        let mut diagonal = C64::new(1.0, 0.0);
        let mut at = 0;
        for m in 0..=self.degree {
            if m > 0 {
                diagonal = diagonal * xy * (0.5 / m as Real);
            }
            let (mut prev2, mut prev) = (C64::new(0.0, 0.0), diagonal);
            for n in m..=self.degree {
                let t = &self.terms[at];
                at += 1;
                let cur = if n == m {
                    prev
                } else {
                    let c = prev * (t.a * z) - prev2 * (t.b * r2);
                    prev2 = prev;
                    prev = c;
                    c
                };
                // Re(conj(R) C) = R.re C.re + R.im C.im.
                for (s, c) in acc.iter_mut().zip(&t.coefficients) {
                    *s += cur.re * c.re + cur.im * c.im;
                }
            }
        }
        let g = self.gravitational_constant;
        let inv = 1.0 / self.unit;
        Field {
            potential: -g * acc[0] * inv,
            acceleration: Vec3::new(acc[1], acc[2], acc[3]) * (g * inv * inv),
        }
    }
}
