//! The homogeneous spheroid $(x^2 + y^2)/a^2 + z^2/c^2 \le 1$ (equatorial radius $a$, polar
//! radius $c$ along z): oblate ($a > c$), prolate ($c > a$) and the sphere ($a = c$) in one
//! formula, continuous through $a = c$, from elementary functions only.
//!
//! # Formulas
//!
//! The ellipsoid's formulas ([`crate::ellipsoid`]) with $a_1 = a_2 = a$, $a_3 = c$. Let
//! $\rho^2 = x^2 + y^2$ and $\kappa \ge 0$ the confocal parameter,
//! $\rho^2/(a^2 + \kappa) + z^2/(c^2 + \kappa) = 1$ outside, $\kappa = 0$ inside. Write
//! $$A = a^2 + \kappa, \quad C = c^2 + \kappa, \quad d = a^2 - c^2 = (a - c)(a + c), \quad
//!   q = d/C \in (-1, \infty),$$
//! so that $A/C = 1 + q$. The integrals reduce to two functions of $q$:
//! $$R_F(A, A, C) = R_C(C, A) = \frac{g(q)}{\sqrt C}, \qquad
//!   g(q) = \frac{\arctan\sqrt q}{\sqrt q} \ (q > 0), \quad
//!   \frac{\operatorname{artanh}\sqrt{-q}}{\sqrt{-q}} \ (q < 0), \quad
//!   \sum\_{n \ge 0} \frac{(-q)^n}{2n + 1},$$
//! $$\tfrac23 R_D(A, A, C) = \frac{2h(q)}{C^{3/2}}, \qquad
//!   h(q) = \frac{1 - g(q)}{q} = \sum\_{n \ge 0} \frac{(-q)^n}{2n + 3},$$
//! the latter by partial fractions, $\frac{1}{(t+C)(t+A)} = \frac{1}{d}\bigl(\frac1{t+C} -
//! \frac1{t+A}\bigr)$. DLMF §19.21, $2R_D(A, C, A) + R_D(A, A, C) = 3/(A\sqrt C)$, then gives
//! $$\tfrac23 R_D(A, C, A) = \frac{m(q)}{C^{3/2}}, \qquad m(q) = \frac{1}{1 + q} - h(q).$$
//! Hence, with $s = C^{-1/2}$:
//! $$a\_{x,y} = -\tfrac32\\, GM\\, m\\, s^3\\, (x, y), \qquad a_z = -3\\,GM\\, h\\, s^3\\, z.$$
//! For the potential we use the ellipsoid's cancellation-free forms. Inside ($\kappa = 0$),
//! $$\Phi = -\frac{GM}{2}\Bigl[\bigl((a-x)(a+x) + (a-y)(a+y)\bigr) R_D(a^2, c^2, a^2) +
//!   (c - z)(c + z)\\, R_D(a^2, a^2, c^2)\Bigr],$$
//! with both constants computed once. Outside, where the secular equation
//! $w\_\rho + w_z = 1$ holds with $w\_\rho = \rho^2/A$, $w_z = z^2/C$ (and $(1+q)m = g - h$):
//! $$\Phi = -\tfrac34\\, GM\\, s\\,\bigl[(g - h)(1 + w_z) + 2h\\, w\_\rho\bigr],$$
//! a sum of positive terms ($g > h > 0$ for every $q > -1$). Far away $g \to 1$, $h \to 1/3$
//! and $\Phi \to -GM/r$; the quadrupole is $J_2 = (a^2 - c^2)/(5a^2)$.
//!
//! # Numerics (issue 2: ≤ 1e-14 in Φ, ≤ 1e-13 in a, outside, for $10^{-4} \le c/a \le 10^4$)
//!
//! - **κ in closed form.** Oblate ($d \ge 0$): $C$ is the positive root of
//!   $C^2 - \sigma C - z^2 d = 0$ with $\sigma = (\rho^2 - a^2) + z^2 + c^2$; prolate
//!   ($d < 0$, $e = -d$): $A$ is the positive root of $A^2 - \sigma' A - \rho^2 e = 0$ with
//!   $\sigma' = \rho^2 + a^2 + (z - c)(z + c)$. The roots have opposite signs, so the
//!   cancellation-free formula ($(\sigma + \sqrt D)/2$ for $\sigma \ge 0$,
//!   $2 z^2 d / (\sqrt D - \sigma)$ otherwise) gives $C$ (or $A$) to a few ulp, provided
//!   $\sigma$ is accurate: where $\rho^2 - a^2$ cancels it is computed with error-free
//!   products (at the rim of a flat body $C \approx c^2 \ll a^2$, so an error of
//!   $\varepsilon a^2$ would be fatal).
//! - **$h$ for small $|q|$** (near the sphere, and far away where $q \approx d/r^2$), where
//!   $h = (1 - g)/q$ cancels: for $|q| \le 0.01$ the series $h = \sum (-q)^n/(2n+3)$
//!   (9 terms). For $-0.71 \le q \le 2.45$ a half-angle reduction: with $u = \tan$ (or
//!   $\tanh$) of half of $\arctan\sqrt q$ (or $\operatorname{artanh}\sqrt{-q}$), i.e.
//!   $\nu = \pm u^2 = d/(\sqrt A + \sqrt C)^2$ and $w = 1 \mp u^2 = 2\sqrt C/(\sqrt A +
//!   \sqrt C)$, the doubling formula $\sqrt{|q|} = 2u/w$ turns $h$ into
//!   $$h = \tfrac14 w^2 \bigl[1 + w\\, T(\nu)\bigr], \qquad
//!   T(\nu) = \sum\_{n \ge 0} \frac{(-\nu)^n}{2n + 3}, \qquad g = 1 - q h,$$
//!   with $|\nu| \le 0.3$ (at most 32 terms, by Estrin's scheme). Beyond that range $g$ from
//!   `atan` or `ln` loses at most a factor 2 in $1 - g$ (measured: $h$ within 3 ulp).
//! - **Large $q$** (close to a flat body): $m = (g - C/A)/q$ instead of $C/A - h$.
//!   **$q \to -1$** (close to a needle): $g - h = ((A/C)g - 1)/q$, and neither $1 + q = A/C$
//!   nor $1 - \sqrt{-q} = (A/C)/(1 + \sqrt{-q})$ is formed by subtraction:
//!   $\operatorname{artanh}\sqrt{-q} = \tfrac12 \ln\bigl((1 + \sqrt{-q})^2 C/A\bigr)$.
//! - Coordinates are scaled by a power of two near the larger radius (exact), so SI magnitudes
//!   cost nothing; beyond $10^{20}$ body sizes the field is the point mass's.
//! - Batches ([`Potential::fields_into`], [`Potential::potentials_into`]) are evaluated four
//!   points at a time, in lanes, each branch of the shape functions only where a lane needs it
//!   and selected lane by lane; every result is bit for bit the point's own
//!   [`Potential::field`] (points inside the body take the scalar path).
//!
//! Measured against the Dirichlet integral at 36 digits (mpmath) over c/a from $10^{-4}$ to
//! $10^4$ (including $c = a(1 \pm 10^{-9})$ and $c = a$), gaps of $10^{-12}$ to 1 above the
//! surface, $10$ to $10^8$ body sizes and SI magnitudes: worst relative error $8\cdot10^{-16}$
//! in Φ and $1.1\cdot10^{-15}$ in the acceleration.

use std::f64::consts::PI;

use crate::ellipsoid::{
    beyond_far_field, exact, excess_of, nearest_power_of_two, region_of_excess,
};
use crate::error::{positive, representable, BodyError};
use crate::lanes::{F4, LANES, M4};
use crate::point_mass::kepler_field;
use crate::{Field, Potential, Real, Region, Vec3};

/// A homogeneous spheroid centred at the origin, symmetry axis along z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spheroid {
    equatorial_radius: Real,
    polar_radius: Real,
    mass: Real,
    density: Real,
    volume: Real,
    gravitational_constant: Real,
    gm: Real,
    gm_over_scale: Real,
    gm_over_scale2: Real,
    scaled: ScaledSpheroid,
}

/// The body in units of the power of two nearest its larger radius.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ScaledSpheroid {
    inv_scale: Real,
    a: Real,
    c: Real,
    a2: Real,
    /// $a^2 - \mathrm{fl}(a^2)$, exactly.
    a2_err: Real,
    c2: Real,
    inv_a2: Real,
    inv_c2: Real,
    /// $d = a^2 - c^2$ and $1/d$ (0 for a sphere; used only where $|q| > 0.7$).
    d: Real,
    inv_d: Real,
    /// $\sqrt{|d|}$ and $1/\sqrt{|d|}$ (the latter infinite for a sphere; both used only where
    /// $|q| > 0.7$).
    sqrt_abs_d: Real,
    inv_sqrt_abs_d: Real,
    axes: [Real; 3],
    inv_axes: [Real; 3],
    inv_axes2: [Real; 3],
    /// $R_D(a^2, c^2, a^2)$ and $R_D(a^2, a^2, c^2)$: the interior field.
    rd_equatorial: Real,
    rd_polar: Real,
}

/// The functions of $q$ the field needs (see the module documentation).
#[derive(Debug, Clone, Copy)]
struct ShapeFunctions {
    h: Real,
    /// $m = 1/(1+q) - h$.
    m: Real,
    /// $g - h$.
    g_minus_h: Real,
}

/// Per-point quantities from which the shape functions are computed, all obtained without
/// cancellation.
#[derive(Debug, Clone, Copy)]
struct ConfocalRatios {
    /// $q = d/C$.
    q: Real,
    /// $C/A = 1/(1 + q)$ and $A/C$.
    c_over_a: Real,
    a_over_c: Real,
    /// $C$.
    big_c: Real,
    /// $\sqrt C$ and $1/\sqrt C$.
    sqrt_c: Real,
    inv_sqrt_c: Real,
    /// $1/(\sqrt A + \sqrt C)$.
    inv_sum: Real,
}

/// Below this $|q|$ the plain series in $q$ (9 terms) is used.
const PLAIN_SERIES_Q: Real = 0.01;
/// $q$ range of the half-angle series: $|\nu| \le 0.3$.
const HALF_ANGLE_Q_MIN: Real = -0.71;
const HALF_ANGLE_Q_MAX: Real = 2.45;

impl Spheroid {
    /// A spheroid with `equatorial_radius` $a$ (x, y), `polar_radius` $c$ (z) and total
    /// `mass`, with G = 1. Oblate if $a > c$, prolate if $a < c$, a sphere if equal.
    pub fn new(equatorial_radius: Real, polar_radius: Real, mass: Real) -> Result<Self, BodyError> {
        let a = positive("equatorial_radius", equatorial_radius)?;
        let c = positive("polar_radius", polar_radius)?;
        let mass = positive("mass", mass)?;
        let volume = spheroid_volume(a, c)?;
        let density = representable("density", mass / volume)?;
        Self::build(a, c, mass, density, volume, 1.0)
    }

    /// A spheroid with the given radii and uniform `density`, with G = 1.
    pub fn with_density(
        equatorial_radius: Real,
        polar_radius: Real,
        density: Real,
    ) -> Result<Self, BodyError> {
        let a = positive("equatorial_radius", equatorial_radius)?;
        let c = positive("polar_radius", polar_radius)?;
        let density = positive("density", density)?;
        let volume = spheroid_volume(a, c)?;
        let mass = representable("mass", density * volume)?;
        Self::build(a, c, mass, density, volume, 1.0)
    }

    /// The same spheroid with gravitational constant `g` (positive, finite).
    pub fn with_gravitational_constant(self, g: Real) -> Result<Self, BodyError> {
        let g = positive("gravitational_constant", g)?;
        Self::build(
            self.equatorial_radius,
            self.polar_radius,
            self.mass,
            self.density,
            self.volume,
            g,
        )
    }

    fn build(
        equatorial_radius: Real,
        polar_radius: Real,
        mass: Real,
        density: Real,
        volume: Real,
        g: Real,
    ) -> Result<Self, BodyError> {
        let gm = representable("gravitational parameter G·mass", g * mass)?;
        let scale = nearest_power_of_two(equatorial_radius.max(polar_radius));
        let inv_scale = 1.0 / scale;
        let a = equatorial_radius * inv_scale;
        let c = polar_radius * inv_scale;
        let (a2, a2_err) = exact::square(a);
        let c2 = c * c;
        let d = (a - c) * (a + c);
        let gm_over_scale = representable("G·mass / size", gm / scale)?;
        let gm_over_scale2 = representable("G·mass / size²", gm_over_scale / scale)?;
        let mut scaled = ScaledSpheroid {
            inv_scale,
            a,
            c,
            a2,
            a2_err,
            c2,
            inv_a2: 1.0 / a2,
            inv_c2: 1.0 / c2,
            d,
            inv_d: if d == 0.0 { 0.0 } else { 1.0 / d },
            sqrt_abs_d: d.abs().sqrt(),
            inv_sqrt_abs_d: 1.0 / d.abs().sqrt(),
            axes: [a, a, c],
            inv_axes: [1.0 / a, 1.0 / a, 1.0 / c],
            inv_axes2: [1.0 / a2, 1.0 / a2, 1.0 / c2],
            rd_equatorial: 0.0,
            rd_polar: 0.0,
        };
        // Interior: κ = 0, A = a², C = c².
        let f = scaled.shape_functions(&ConfocalRatios {
            q: d / c2,
            c_over_a: c2 / a2,
            a_over_c: a2 / c2,
            big_c: c2,
            sqrt_c: c,
            inv_sqrt_c: 1.0 / c,
            inv_sum: 1.0 / (a + c),
        });
        let inv_c3 = 1.0 / (c * c2);
        scaled.rd_equatorial = 1.5 * f.m * inv_c3;
        scaled.rd_polar = 3.0 * f.h * inv_c3;
        Ok(Self {
            equatorial_radius,
            polar_radius,
            mass,
            density,
            volume,
            gravitational_constant: g,
            gm,
            gm_over_scale,
            gm_over_scale2,
            scaled,
        })
    }

    /// The equatorial radius $a$ (semi-axes along x and y).
    pub fn equatorial_radius(&self) -> Real {
        self.equatorial_radius
    }

    /// The polar radius $c$ (semi-axis along z).
    pub fn polar_radius(&self) -> Real {
        self.polar_radius
    }

    /// The uniform density, mass / volume.
    pub fn density(&self) -> Real {
        self.density
    }

    /// The confocal parameter κ at `r` (0 inside and on the body), in length units squared.
    pub fn confocal_parameter(&self, r: &Vec3) -> Real {
        let s = &self.scaled;
        let p = r * s.inv_scale;
        let scale = 1.0 / s.inv_scale;
        if beyond_far_field(p.norm_squared()) {
            return (p.norm_squared() - s.a2.min(s.c2)) * scale * scale;
        }
        match s.confocal(&p) {
            Some((big_a, big_c)) => {
                let kappa = if s.d >= 0.0 {
                    big_c - s.c2
                } else {
                    big_a - s.a2
                };
                kappa * scale * scale
            }
            None => 0.0,
        }
    }
}

fn spheroid_volume(a: Real, c: Real) -> Result<Real, BodyError> {
    representable("volume", 4.0 / 3.0 * PI * a * a * c)
}

impl ScaledSpheroid {
    /// $(A, C)$ outside the body, `None` inside or on it.
    #[inline]
    fn confocal(&self, p: &Vec3) -> Option<(Real, Real)> {
        let rho2 = p.x * p.x + p.y * p.y;
        let z2 = p.z * p.z;
        if self.d >= 0.0 {
            let mut rho2_minus_a2 = rho2 - self.a2;
            if rho2_minus_a2.abs() < 0.5 * self.a2 {
                // ρ² − a² cancels: error-free squares make it exact but for one rounding.
                let (x2, x2_err) = exact::square(p.x);
                let (y2, y2_err) = exact::square(p.y);
                let (sum, sum_err) = exact::sum(x2, y2);
                rho2_minus_a2 = (sum - self.a2) + (((sum_err + x2_err) + y2_err) - self.a2_err);
            }
            let sigma = rho2_minus_a2 + (z2 + self.c2);
            let t = 4.0 * z2 * self.d;
            let root = (sigma * sigma + t).sqrt();
            let c_big = if sigma >= 0.0 {
                0.5 * (sigma + root)
            } else {
                t / (2.0 * (root - sigma))
            };
            (c_big > self.c2).then_some((c_big + self.d, c_big))
        } else {
            let e = -self.d;
            let z2_minus_c2 = (p.z - self.c) * (p.z + self.c);
            let sigma = (rho2 + self.a2) + z2_minus_c2;
            let t = 4.0 * rho2 * e;
            let root = (sigma * sigma + t).sqrt();
            let a_big = if sigma >= 0.0 {
                0.5 * (sigma + root)
            } else {
                t / (2.0 * (root - sigma))
            };
            (a_big > self.a2).then_some((a_big, a_big + e))
        }
    }

    /// $h$, $m$, $g - h$ at one point.
    #[inline]
    fn shape_functions(&self, r: &ConfocalRatios) -> ShapeFunctions {
        let q = r.q;
        if q.abs() <= PLAIN_SERIES_Q {
            // h = Σ (−q)ⁿ/(2n+3); truncation 0.01⁹/21 < 1e-19.
            let h = estrin16(-q, &SERIES[..9]);
            let g = 1.0 - q * h;
            return ShapeFunctions {
                h,
                m: r.c_over_a - h,
                g_minus_h: g - h,
            };
        }
        if (HALF_ANGLE_Q_MIN..=HALF_ANGLE_Q_MAX).contains(&q) {
            let w = 2.0 * r.sqrt_c * r.inv_sum;
            let nu = self.d * r.inv_sum * r.inv_sum;
            let h = 0.25 * w * w * (1.0 + w * half_angle_series(nu));
            let g = 1.0 - q * h;
            return ShapeFunctions {
                h,
                m: r.c_over_a - h,
                g_minus_h: g - h,
            };
        }
        // √|q| = √|d|/√C, 1/√|q| = √C/√|d|, 1/q = C/d: no division.
        let t = self.sqrt_abs_d * r.inv_sqrt_c;
        let inv_t = r.sqrt_c * self.inv_sqrt_abs_d;
        let inv_q = r.big_c * self.inv_d;
        if q > 0.0 {
            let g = t.atan() * inv_t;
            let h = (1.0 - g) * inv_q;
            ShapeFunctions {
                h,
                m: (g - r.c_over_a) * inv_q,
                g_minus_h: g - h,
            }
        } else {
            // artanh t = ½ ln((1+t)/(1−t)) = ½ ln((1+t)² C/A), as 1 − t² = 1 + q = A/C; the
            // argument exceeds 10 here (q < −0.71), so the logarithm is well conditioned.
            let g = 0.5 * ((1.0 + t) * (1.0 + t) * r.c_over_a).ln() * inv_t;
            let h = (1.0 - g) * inv_q;
            ShapeFunctions {
                h,
                m: r.c_over_a - h,
                g_minus_h: (g * r.a_over_c - 1.0) * inv_q,
            }
        }
    }
}

/// $T(\nu) = \sum\_{n \ge 0} (-\nu)^n/(2n + 3)$ for $|\nu| \le 0.3$, to within
/// $10^{-17}$ relative.
#[inline]
fn half_angle_series(nu: Real) -> Real {
    if nu.abs() < 0.05 {
        // Truncation 0.05¹⁶/35 < 1e-22.
        estrin16(-nu, &SERIES[..16])
    } else {
        // Truncation 0.3³²/67 < 1e-18.
        estrin32(-nu)
    }
}

/// $1/(2n + 3)$, $n = 0, \dots, 31$.
const SERIES: [Real; 32] = {
    let mut c = [0.0; 32];
    let mut n = 0;
    while n < 32 {
        c[n] = 1.0 / (2 * n + 3) as Real;
        n += 1;
    }
    c
};

/// Estrin's scheme for up to 16 coefficients `c` (missing ones are zero).
#[inline]
fn estrin16(x: Real, c: &[Real]) -> Real {
    let coefficient = |i: usize| c.get(i).copied().unwrap_or(0.0);
    let mut v = [0.0; 8];
    for (i, vi) in v.iter_mut().enumerate() {
        *vi = coefficient(2 * i) + coefficient(2 * i + 1) * x;
    }
    let x2 = x * x;
    let x4 = x2 * x2;
    let x8 = x4 * x4;
    let v01 = v[0] + v[1] * x2;
    let v23 = v[2] + v[3] * x2;
    let v45 = v[4] + v[5] * x2;
    let v67 = v[6] + v[7] * x2;
    (v01 + v23 * x4) + (v45 + v67 * x4) * x8
}

/// Estrin's scheme for all 32 coefficients of [`SERIES`].
#[inline]
fn estrin32(x: Real) -> Real {
    let x2 = x * x;
    let x4 = x2 * x2;
    let x8 = x4 * x4;
    let x16 = x8 * x8;
    estrin16(x, &SERIES[..16]) + estrin16(x, &SERIES[16..]) * x16
}

impl Spheroid {
    /// The fields at [`LANES`] points side by side, each bit for bit [`Potential::field`]'s
    /// where the lane took the lane path, and which lanes did (the others' entries are
    /// meaningless): a lane outside the body and within the far-field limit takes it; the
    /// confocal parameter and the shape functions run the scalar operations lane by lane (each
    /// branch of the shape functions only when a lane needs it, and selected per lane).
    #[inline(always)]
    fn field_lanes(&self, points: [Vec3; LANES]) -> ([Field; LANES], [bool; LANES]) {
        let s = &self.scaled;
        let coordinate = |i: usize| F4::new(std::array::from_fn(|l| points[l][i] * s.inv_scale));
        let (px, py, pz) = (coordinate(0), coordinate(1), coordinate(2));
        let rho2 = px * px + py * py;
        let z2 = pz * pz;
        let r2 = rho2 + z2;
        let far = M4::from_flags(std::array::from_fn(|l| beyond_far_field(r2.0[l])));
        let inside = (rho2 * s.inv_a2 + z2 * s.inv_c2).lt(F4::splat(1.0 - 1e-9));
        let zero = F4::splat(0.0);
        let (big_a, big_c, outside) = if s.d >= 0.0 {
            let mut rho2_minus_a2 = rho2 - s.a2;
            let cancels = rho2_minus_a2.abs().lt(F4::splat(0.5 * s.a2));
            if cancels.any() {
                let (x2, x2_err) = exact::lanes::square(px);
                let (y2, y2_err) = exact::lanes::square(py);
                let (sum, sum_err) = exact::lanes::sum(x2, y2);
                let exact = (sum - s.a2) + (((sum_err + x2_err) + y2_err) - s.a2_err);
                rho2_minus_a2 = cancels.select(exact, rho2_minus_a2);
            }
            let sigma = rho2_minus_a2 + (z2 + s.c2);
            let t = 4.0 * z2 * s.d;
            let root = (sigma * sigma + t).sqrt();
            let c_big = zero
                .le(sigma)
                .select(0.5 * (sigma + root), t / (2.0 * (root - sigma)));
            (c_big + s.d, c_big, c_big.gt(F4::splat(s.c2)))
        } else {
            let e = -s.d;
            let z2_minus_c2 = (pz - s.c) * (pz + s.c);
            let sigma = (rho2 + s.a2) + z2_minus_c2;
            let t = 4.0 * rho2 * e;
            let root = (sigma * sigma + t).sqrt();
            let a_big = zero
                .le(sigma)
                .select(0.5 * (sigma + root), t / (2.0 * (root - sigma)));
            (a_big, a_big + e, a_big.gt(F4::splat(s.a2)))
        };
        let taken = outside.and(far.not()).and(inside.not()).flags();
        let sqrt_c = big_c.sqrt();
        let sqrt_a = big_a.sqrt();
        let inv_sqrt_c = 1.0 / sqrt_c;
        let inv_sum = 1.0 / (sqrt_a + sqrt_c);
        let inv_a = 1.0 / big_a;
        let inv_c = inv_sqrt_c * inv_sqrt_c;
        let q = s.d * inv_c;
        let c_over_a = big_c * inv_a;
        let a_over_c = big_a * inv_c;
        // ScaledSpheroid::shape_functions, branch by branch.
        let series = q.abs().le(F4::splat(PLAIN_SERIES_Q));
        let half = series
            .not()
            .and(F4::splat(HALF_ANGLE_Q_MIN).le(q))
            .and(q.le(F4::splat(HALF_ANGLE_Q_MAX)));
        let closed = series.not().and(half.not());
        let (mut h, mut m, mut g_minus_h) = (zero, zero, zero);
        if series.any() {
            let hs = estrin16_lanes(-q, &SERIES[..9]);
            let g = 1.0 - q * hs;
            h = series.select(hs, h);
            m = series.select(c_over_a - hs, m);
            g_minus_h = series.select(g - hs, g_minus_h);
        }
        if half.any() {
            let w = 2.0 * sqrt_c * inv_sum;
            let nu = s.d * inv_sum * inv_sum;
            let minus_nu = -nu;
            let small = nu.abs().lt(F4::splat(0.05));
            let mut series_nu = zero;
            if small.any() {
                series_nu = small.select(estrin16_lanes(minus_nu, &SERIES[..16]), series_nu);
            }
            if small.not().any() {
                let x2 = minus_nu * minus_nu;
                let x4 = x2 * x2;
                let x8 = x4 * x4;
                let x16 = x8 * x8;
                let long = estrin16_lanes(minus_nu, &SERIES[..16])
                    + estrin16_lanes(minus_nu, &SERIES[16..]) * x16;
                series_nu = small.select(series_nu, long);
            }
            let hh = 0.25 * w * w * (1.0 + w * series_nu);
            let g = 1.0 - q * hh;
            h = half.select(hh, h);
            m = half.select(c_over_a - hh, m);
            g_minus_h = half.select(g - hh, g_minus_h);
        }
        if closed.any() {
            let t = s.sqrt_abs_d * inv_sqrt_c;
            let inv_t = sqrt_c * s.inv_sqrt_abs_d;
            let inv_q = big_c * s.inv_d;
            let positive = q.gt(zero);
            // The scalar atan and ln, lane by lane, on the lanes of this branch only.
            let g = F4::new(std::array::from_fn(|l| {
                if !closed.flags()[l] {
                    0.0
                } else if positive.flags()[l] {
                    t.0[l].atan() * inv_t.0[l]
                } else {
                    0.5 * ((1.0 + t.0[l]) * (1.0 + t.0[l]) * c_over_a.0[l]).ln() * inv_t.0[l]
                }
            }));
            let hc = (1.0 - g) * inv_q;
            let mc = positive.select((g - c_over_a) * inv_q, c_over_a - hc);
            let gc = positive.select(g - hc, (g * a_over_c - 1.0) * inv_q);
            h = closed.select(hc, h);
            m = closed.select(mc, m);
            g_minus_h = closed.select(gc, g_minus_h);
        }
        let w_z = z2 * inv_c;
        let w_rho = rho2 * inv_a;
        let phi = -0.75 * inv_sqrt_c * (g_minus_h * (1.0 + w_z) + 2.0 * h * w_rho);
        let k = inv_sqrt_c * inv_c;
        let kr = -1.5 * m * k;
        let kz = -3.0 * h * k;
        let fields = std::array::from_fn(|l| Field {
            potential: phi.0[l] * self.gm_over_scale,
            acceleration: Vec3::new(kr.0[l] * px.0[l], kr.0[l] * py.0[l], kz.0[l] * pz.0[l])
                * self.gm_over_scale2,
        });
        (fields, taken)
    }

    /// [`Potential::field`] kept out of line, beside the lane code.
    #[inline(never)]
    fn field_outlined(&self, r: &Vec3) -> Field {
        self.field(r)
    }
}

/// [`estrin16`] lane by lane.
#[inline(always)]
fn estrin16_lanes(x: F4, c: &[Real]) -> F4 {
    let coefficient = |i: usize| c.get(i).copied().unwrap_or(0.0);
    let v: [F4; 8] = std::array::from_fn(|i| coefficient(2 * i) + coefficient(2 * i + 1) * x);
    let x2 = x * x;
    let x4 = x2 * x2;
    let x8 = x4 * x4;
    let v01 = v[0] + v[1] * x2;
    let v23 = v[2] + v[3] * x2;
    let v45 = v[4] + v[5] * x2;
    let v67 = v[6] + v[7] * x2;
    (v01 + v23 * x4) + (v45 + v67 * x4) * x8
}

impl crate::lanes::Batched for Spheroid {
    #[inline(always)]
    fn batch<T>(&self, points: &[Vec3], out: &mut [T], pick: impl Fn(Field) -> T) {
        crate::lanes::batch_lanes(self, points, out, pick);
    }
}

impl crate::lanes::LaneField<LANES> for Spheroid {
    #[inline(always)]
    fn field_lanes(&self, points: [Vec3; LANES]) -> ([Field; LANES], [bool; LANES]) {
        Spheroid::field_lanes(self, points)
    }

    #[inline(always)]
    fn field_outlined(&self, r: &Vec3) -> Field {
        Spheroid::field_outlined(self, r)
    }
}

impl Potential for Spheroid {
    fn as_typed(&self) -> crate::TypedPotential<'_> {
        crate::TypedPotential::Spheroid(self)
    }

    fn inertia(&self) -> Option<crate::InertiaTensor> {
        let (a, c) = (self.equatorial_radius(), self.polar_radius());
        crate::InertiaTensor::solid_ellipsoid(self.mass(), a, a, c).ok()
    }

    fn mass(&self) -> Real {
        self.mass
    }

    fn gravitational_constant(&self) -> Real {
        self.gravitational_constant
    }

    fn volume(&self) -> Real {
        self.volume
    }

    fn bounding_radius(&self) -> Real {
        self.equatorial_radius.max(self.polar_radius)
    }

    /// On the surface when $|\rho^2/a^2 + z^2/c^2 - 1| \le 4\varepsilon$, computed with
    /// error-free transformations.
    fn region(&self, r: &Vec3) -> Region {
        let s = &self.scaled;
        let p = r * s.inv_scale;
        if beyond_far_field(p.norm_squared()) {
            return Region::Outside;
        }
        region_of_excess(excess_of(&p, &s.axes, &s.inv_axes, &s.inv_axes2).0)
    }

    /// Four points at a time through one lane-interleaved evaluation (AVX where the CPU has
    /// it), each result bit for bit [`Potential::field`]'s.
    fn fields_into(&self, points: &[Vec3], out: &mut [Field]) {
        crate::lanes::fields_into(self, points, out);
    }

    /// As [`Potential::fields_into`], keeping the potentials.
    fn potentials_into(&self, points: &[Vec3], out: &mut [Real]) {
        crate::lanes::potentials_into(self, points, out);
    }

    #[inline]
    fn field(&self, r: &Vec3) -> Field {
        let s = &self.scaled;
        let p = r * s.inv_scale;
        let rho2 = p.x * p.x + p.y * p.y;
        let z2 = p.z * p.z;
        if beyond_far_field(rho2 + z2) {
            return kepler_field(self.gm, r);
        }
        // Clearly inside (the estimate's error is a few ε): skip the confocal parameter.
        let outside = if rho2 * s.inv_a2 + z2 * s.inv_c2 < 1.0 - 1e-9 {
            None
        } else {
            s.confocal(&p)
        };
        let Some((big_a, big_c)) = outside else {
            // Φ = −(GM/2) Σ (a_i² − x_i²) R_D⁽ⁱ⁾ (DLMF §19.21): positive terms inside.
            let (rd_e, rd_p) = (s.rd_equatorial, s.rd_polar);
            let depth_e = (s.a - p.x) * (s.a + p.x) + (s.a - p.y) * (s.a + p.y);
            let depth_p = (s.c - p.z) * (s.c + p.z);
            return Field {
                potential: -0.5 * (depth_e * rd_e + depth_p * rd_p) * self.gm_over_scale,
                acceleration: Vec3::new(-rd_e * p.x, -rd_e * p.y, -rd_p * p.z)
                    * self.gm_over_scale2,
            };
        };
        let sqrt_c = big_c.sqrt();
        let sqrt_a = big_a.sqrt();
        // Three independent divisions: pipelined, they cost less latency than one division
        // and the products that would share it.
        let inv_sqrt_c = 1.0 / sqrt_c;
        let inv_sum = 1.0 / (sqrt_a + sqrt_c);
        let inv_a = 1.0 / big_a;
        let inv_c = inv_sqrt_c * inv_sqrt_c;
        let f = s.shape_functions(&ConfocalRatios {
            q: s.d * inv_c,
            c_over_a: big_c * inv_a,
            a_over_c: big_a * inv_c,
            big_c,
            sqrt_c,
            inv_sqrt_c,
            inv_sum,
        });
        let w_z = z2 * inv_c;
        let w_rho = rho2 * inv_a;
        let phi = -0.75 * inv_sqrt_c * (f.g_minus_h * (1.0 + w_z) + 2.0 * f.h * w_rho);
        let k = inv_sqrt_c * inv_c;
        let kr = -1.5 * f.m * k;
        let kz = -3.0 * f.h * k;
        Field {
            potential: phi * self.gm_over_scale,
            acceleration: Vec3::new(kr * p.x, kr * p.y, kz * p.z) * self.gm_over_scale2,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    /// Points for the batched field, in units of the larger radius: along directions spread
    /// over the sphere (with the axis and the equator), at the surface scaled by factors from
    /// inside (0.3) through the surface (1 ± 1e-12) to 1e6 body sizes, so that every branch of
    /// the shape functions, the cancelling form of $\rho^2 - a^2$ and both sides of the
    /// far-field limit occur; non-finite points follow; shuffled so that groups of four mix.
    fn batch_points(a: f64, c: f64) -> Vec<Vec3> {
        let mut state = 5u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut directions = vec![Vec3::z(), -Vec3::z(), Vec3::x(), Vec3::new(0.6, -0.8, 0.0)];
        for _ in 0..60 {
            let z = 2.0 * next() - 1.0;
            let phi = std::f64::consts::TAU * next();
            let s = (1.0 - z * z).sqrt();
            directions.push(Vec3::new(s * phi.cos(), s * phi.sin(), z));
        }
        let factors = [
            0.0,
            0.3,
            0.999,
            1.0 - 1e-12,
            1.0,
            1.0 + 1e-12,
            1.0 + 1e-9,
            1.0 + 1e-6,
            1.001,
            1.01,
            1.1,
            1.3,
            1.7,
            2.5,
            4.0,
            10.0,
            100.0,
            1e4,
            1e6,
            1e21,
        ];
        let mut points = Vec::new();
        for dir in &directions {
            let surface =
                1.0 / ((dir.x / a).powi(2) + (dir.y / a).powi(2) + (dir.z / c).powi(2)).sqrt();
            for f in factors {
                points.push(dir * (surface * f));
            }
        }
        points.push(Vec3::new(f64::NAN, 0.1, 0.2));
        points.push(Vec3::new(0.3, f64::INFINITY, 0.0));
        points.push(Vec3::new(0.3, 0.2, f64::NEG_INFINITY));
        for k in (1..points.len()).rev() {
            let j = ((next() * (k + 1) as f64) as usize).min(k);
            points.swap(k, j);
        }
        points
    }

    /// The batched field (both compilations) and potentials are the point-by-point field bit
    /// for bit, for oblate, prolate, near-spherical and spherical spheroids (SI-sized too),
    /// at every batch offset.
    #[test]
    fn batched_fields_are_the_scalar_fields_bit_for_bit() {
        let bodies = [
            (1.0, 0.25),
            (0.25, 1.0),
            (1.0, 1e-3),
            (1e-3, 1.0),
            (1.0, 1.0 - 1e-9),
            (1.0, 1.0),
            (766.0, 673.5),
        ];
        for (a, c) in bodies {
            let body = Spheroid::new(a, c, 1.3).unwrap();
            let scale = a.max(c);
            let points: Vec<Vec3> = batch_points(a / scale, c / scale)
                .iter()
                .map(|p| p * scale)
                .collect();
            let want: Vec<Field> = points.iter().map(|r| body.field(r)).collect();
            for start in 0..4 {
                let (points, want) = (&points[start..], &want[start..]);
                let blank = Field {
                    potential: 0.0,
                    acceleration: Vec3::zeros(),
                };
                let mut runs = Vec::new();
                let mut out = vec![blank; points.len()];
                body.fields_into(points, &mut out);
                runs.push(("fields_into", out.clone()));
                crate::lanes::fields_plain(&body, points, &mut out);
                runs.push(("fields_plain", out.clone()));
                for (name, got) in &runs {
                    for ((r, g), w) in points.iter().zip(got).zip(want) {
                        let equal = same(g.potential, w.potential)
                            && (0..3).all(|i| same(g.acceleration[i], w.acceleration[i]));
                        assert!(equal, "{name} ({a}, {c}) at {r:?}: {g:?} vs {w:?}");
                    }
                }
                let mut potentials = vec![0.0; points.len()];
                body.potentials_into(points, &mut potentials);
                for ((r, &g), w) in points.iter().zip(&potentials).zip(want) {
                    assert!(same(g, w.potential), "potentials_into ({a}, {c}) at {r:?}");
                }
            }
        }
    }
}
