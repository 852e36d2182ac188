//! The homogeneous triaxial ellipsoid $x^2/a^2 + y^2/b^2 + z^2/c^2 \le 1$ (semi-axes in any
//! order), by Carlson's symmetric integrals.
//!
//! # Formulas
//!
//! Write $a_1, a_2, a_3 = a, b, c$ and let $\lambda$ be the confocal parameter, the largest root
//! of
//! $$S(\lambda) = \sum_i \frac{x_i^2}{a_i^2 + \lambda} = 1$$
//! outside the body, $\lambda = 0$ inside and on it. With $A_i = a_i^2 + \lambda$, Dirichlet's
//! integral is
//! $$\Phi = -\frac{3GM}{4} \int\_\lambda^\infty \Bigl(1 - \sum_i \frac{x_i^2}{a_i^2 + u}\Bigr)
//!   \frac{\mathrm du}{\sqrt{(a_1^2 + u)(a_2^2 + u)(a_3^2 + u)}}
//!   = -\frac{3GM}{2}\Bigl[R_F(A_1, A_2, A_3) - \frac13 \sum_i x_i^2\\, R_D^{(i)}\Bigr],$$
//! $$a_i = -\frac{\partial\Phi}{\partial x_i} = -GM\\, x_i\\, R_D^{(i)}, \qquad
//!   R_D^{(i)} = R_D(A_j, A_k, A_i)$$
//! (the third argument belongs to axis $i$). The derivative of the lower limit $\lambda$ drops
//! out because the integrand vanishes at $u = \lambda$; inside, the same formula with
//! $\lambda = 0$ is the interior quadratic potential, and $\nabla^2\Phi = 4\pi G\rho$ follows
//! from $\sum_i R_D(A_j, A_k, A_i) = 3/\sqrt{A_1A_2A_3}$ (DLMF §19.21). (Dirichlet's integral:
//! e.g. Chandrasekhar, *Ellipsoidal Figures of Equilibrium*, 1969, ch. 3; the Carlson forms
//! follow from DLMF 19.16.1 and 19.16.5.)
//!
//! We evaluate the potential in forms free of cancellation. DLMF §19.21,
//! $\sum_i A_i R_D^{(i)} = 3R_F$, turns the bracket into $\tfrac13 \sum_i (A_i - x_i^2)
//! R_D^{(i)}$. Inside, $A_i - x_i^2 = (a_i - x_i)(a_i + x_i) > 0$, with the four integrals at
//! $\lambda = 0$ computed once. Outside, the secular equation $\sum_j w_j = 1$ with
//! $w_j = x_j^2/A_j$ gives $A_i - x_i^2 = A_i \sum\_{j \ne i} w_j$:
//! $$\Phi = -\frac{GM}{2} \sum_i A_i\\, R_D^{(i)} \sum\_{j \ne i} w_j,$$
//! a sum of positive terms (the bracket itself loses up to a factor $\ln(c/a)$ at the tip of
//! a needle).
//!
//! # Numerics
//!
//! - Coordinates are scaled by a power of two near the largest semi-axis (exact), so that SI
//!   magnitudes and $10^8$ body sizes stay far from overflow; beyond $10^{20}$ body sizes the
//!   field is the point mass's (relative quadrupole $< 10^{-40}$).
//! - $F_0 = \sum_i (x_i/a_i)^2 - 1$ decides inside / outside. A plain estimate settles the clear
//!   cases; within $[-10^{-9}, 2]$ it is recomputed with error-free transformations (Dekker's
//!   product, Knuth's two-sum), so its error is a few ulp of $|F_0|$ even $10^{-12}$ from the
//!   surface. Near the surface ($F_0 < 1$) the secular function is evaluated as
//!   $S(\lambda) - 1 = F_0 - \lambda \sum_i x_i^2 / (a_i^2 A_i)$, which keeps $\lambda$
//!   accurate relative to the smallest $A_i$ at the rim of a flat body (where an absolute
//!   error $\varepsilon a^2$ in $\lambda$ would spoil the acceleration).
//! - $\lambda$ comes from Newton's method on $1/S(\lambda) - 1$, which is concave and
//!   increasing ($S$ is a Stieltjes function), so from a lower bound the iterates increase
//!   monotonically and quadratically to the root. The start is Jensen's bound
//!   $\lambda \ge r^2 - \bar b$, $\bar b = \sum_i x_i^2 a_i^2 / r^2$ (from the convexity of
//!   $1/(b + \lambda)$), exact on the axes and for a sphere, within $O(a^4/r^2)$ far away. At
//!   most 24 steps are allowed; 1 to 3 are typical and 8 the most seen (a unit test keeps
//!   the histogram). The iteration stops one step after a relative change below $10^{-9}$ of
//!   the smallest $A_i$.
//! - $R_F$ and the three $R_D$ come from one fused duplication loop ([`crate::carlson`]).
//! - The field is latency-bound, not division-bound: two rewrites that keep the accuracy were
//!   measured slower against this code on the same machine (criterion, `ellipsoid/near` and
//!   `batch_of_256/ellipsoid`, alternating runs): the three reciprocals $1/A_i$ of each
//!   Newton step and of $w_i$ from one shared division, and Halley's iteration with a stop at
//!   $10^{-6}$ (fewer steps, 256 batch points: 2/3/4 steps 129/107/20 → 227/29/0, yet slower
//!   near the body and far from it).
//! - Batches ([`Potential::fields_into`], [`Potential::potentials_into`]) are evaluated eight
//!   points at a time, in lanes: each scalar operation is written once for the eight lanes so
//!   that the compiler issues it as two vector instructions on independent registers, which
//!   hides the latency of the divisions and square roots (four lanes, one register, took 22 %
//!   longer per interaction on the pose set's ellipsoid pairs). Newton's iteration and the
//!   duplication run until every lane has converged, a converged lane's values kept by
//!   selection; each lane sums the series to its own degree. Every lane performs the scalar
//!   operations in the scalar order and nothing is fused, so each result is bit for bit
//!   [`Potential::field`]'s (a unit test compares the bits over needles, disks and
//!   near-spheres, from $10^{-12}$ above the surface to $10^{19}$ body sizes, inside points and
//!   non-finite ones mixed in). A point with $F_0 \le 0$ (inside or on the body), beyond the
//!   far field, not finite, or whose $A_i$ leave $2^{\pm 300}$ is evaluated by
//!   [`Potential::field`]. On x86-64 the lane code is compiled twice, with AVX (four lanes per
//!   instruction; FMA not enabled) and without, and the CPU picks at run time.
//!
//! Measured against the Dirichlet integral at 36 digits (mpmath) for axes 3:2:1, 1:0.5:0.01,
//! 1:0.3:10⁻⁴, 10⁻⁴:2·10⁻⁴:1, nearly equal axes and SI magnitudes, from $10^{-12}$ above the
//! surface to $10^8$ body sizes: worst relative error $8\cdot10^{-16}$ in Φ and
//! $9\cdot10^{-16}$ in the acceleration.

use std::f64::consts::PI;

use crate::carlson::{rd_lanes, shares_division, symmetric_integrals_in_range};
use crate::error::{positive, representable, BodyError};
use crate::lanes::{F8, M8, WIDE};
use crate::point_mass::kepler_field;
use crate::{Field, Potential, Real, Region, Vec3};

/// Squared scaled distance beyond which the field is the point mass's: at $10^{20}$ body sizes
/// the quadrupole is $10^{-40}$ of the monopole.
pub(crate) const FAR_FIELD_R2: Real = 1e40;

/// Beyond $10^{20}$ body sizes, or not a number: the point mass's field applies (and carries a
/// NaN through).
#[inline]
pub(crate) fn beyond_far_field(r2: Real) -> bool {
    r2.is_nan() || r2 > FAR_FIELD_R2
}

/// Newton steps allowed for the confocal parameter; the iteration is monotone and quadratic
/// from its starting bound, and the tests record the largest count actually used.
pub(crate) const MAX_NEWTON_STEPS: usize = 24;

/// Relative size of a Newton step, against the smallest $A_i$, below which one more step could
/// not change $A_i$ by more than rounding (quadratic convergence squares it).
const NEWTON_TOLERANCE: Real = 1e-9;

/// Half-width of the band, in units of $F_0 = \sum (x_i/a_i)^2 - 1$, reported as on the surface.
pub(crate) const SURFACE_BAND: Real = 4.0 * Real::EPSILON;

/// A homogeneous triaxial ellipsoid centred at the origin with semi-axes along x, y, z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    semi_axes: [Real; 3],
    mass: Real,
    density: Real,
    volume: Real,
    gravitational_constant: Real,
    gm: Real,
    /// GM / scale, GM / scale²: convert the scaled field back.
    gm_over_scale: Real,
    gm_over_scale2: Real,
    scaled: ScaledEllipsoid,
}

/// The body in units of the power of two `scale` nearest its largest semi-axis.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ScaledEllipsoid {
    inv_scale: Real,
    axes: [Real; 3],
    axes2: [Real; 3],
    /// Approximate reciprocals of the axes (exactness restored by the remainder, see
    /// [`surface_excess`]).
    inv_axes: [Real; 3],
    inv_axes2: [Real; 3],
    min_axis2: Real,
    max_axis2: Real,
    /// $R_F(a^2, b^2, c^2)$ and the three $R_D$ at $\lambda = 0$: the interior potential.
    interior: crate::carlson::SymmetricIntegrals,
}

impl Ellipsoid {
    /// An ellipsoid with semi-axes `a`, `b`, `c` along x, y, z (any order) and total `mass`,
    /// with G = 1.
    pub fn new(a: Real, b: Real, c: Real, mass: Real) -> Result<Self, BodyError> {
        let axes = validate_axes(a, b, c)?;
        let mass = positive("mass", mass)?;
        let volume = ellipsoid_volume(axes)?;
        let density = representable("density", mass / volume)?;
        Self::build(axes, mass, density, volume, 1.0)
    }

    /// An ellipsoid with semi-axes `a`, `b`, `c` and uniform `density`, with G = 1.
    pub fn with_density(a: Real, b: Real, c: Real, density: Real) -> Result<Self, BodyError> {
        let axes = validate_axes(a, b, c)?;
        let density = positive("density", density)?;
        let volume = ellipsoid_volume(axes)?;
        let mass = representable("mass", density * volume)?;
        Self::build(axes, mass, density, volume, 1.0)
    }

    /// The same ellipsoid with gravitational constant `g` (positive, finite).
    pub fn with_gravitational_constant(self, g: Real) -> Result<Self, BodyError> {
        let g = positive("gravitational_constant", g)?;
        Self::build(self.semi_axes, self.mass, self.density, self.volume, g)
    }

    fn build(
        semi_axes: [Real; 3],
        mass: Real,
        density: Real,
        volume: Real,
        g: Real,
    ) -> Result<Self, BodyError> {
        let gm = representable("gravitational parameter G·mass", g * mass)?;
        let largest = semi_axes[0].max(semi_axes[1]).max(semi_axes[2]);
        let scale = nearest_power_of_two(largest);
        let inv_scale = 1.0 / scale;
        let axes = semi_axes.map(|v| v * inv_scale);
        let axes2 = axes.map(|v| v * v);
        let interior = symmetric_integrals_in_range(axes2[0], axes2[1], axes2[2]);
        let gm_over_scale = representable("G·mass / size", gm / scale)?;
        let gm_over_scale2 = representable("G·mass / size²", gm_over_scale / scale)?;
        Ok(Self {
            semi_axes,
            mass,
            density,
            volume,
            gravitational_constant: g,
            gm,
            gm_over_scale,
            gm_over_scale2,
            scaled: ScaledEllipsoid {
                inv_scale,
                axes,
                axes2,
                inv_axes: axes.map(|v| 1.0 / v),
                inv_axes2: axes2.map(|v| 1.0 / v),
                min_axis2: axes2[0].min(axes2[1]).min(axes2[2]),
                max_axis2: axes2[0].max(axes2[1]).max(axes2[2]),
                interior,
            },
        })
    }

    /// The semi-axes along x, y, z, as given.
    pub fn semi_axes(&self) -> [Real; 3] {
        self.semi_axes
    }

    /// The uniform density, mass / volume.
    pub fn density(&self) -> Real {
        self.density
    }

    /// The confocal parameter $\lambda$ at `r` (0 inside and on the body), in the body's
    /// length unit squared.
    pub fn confocal_parameter(&self, r: &Vec3) -> Real {
        let s = &self.scaled;
        let p = r * s.inv_scale;
        let x2 = [p.x * p.x, p.y * p.y, p.z * p.z];
        let r2 = x2[0] + x2[1] + x2[2];
        let (excess, ratio2) = excess_of(&p, &s.axes, &s.inv_axes, &s.inv_axes2);
        if excess <= 0.0 {
            return 0.0;
        }
        let scale = 1.0 / s.inv_scale;
        if beyond_far_field(r2) {
            return (r2 - s.max_axis2).max(0.0) * scale * scale;
        }
        s.confocal_parameter(&x2, &ratio2, excess, r2).0 * scale * scale
    }
}

impl ScaledEllipsoid {
    /// Newton on $1/S(\lambda) - 1$ from a lower bound; returns λ and the steps taken.
    #[inline]
    fn confocal_parameter(
        &self,
        x2: &[Real; 3],
        ratio2: &[Real; 3],
        excess: Real,
        r2: Real,
    ) -> (Real, usize) {
        let near = excess < 1.0;
        // Jensen's inequality for the convex 1/(b + λ) gives S(λ) ≥ r²/(b̄ + λ) with
        // b̄ = Σ x_i² a_i² / r², hence λ ≥ r² − b̄: a lower bound, exact on the axes, for a
        // sphere, and to O(a⁴/r²) far away.
        let weighted = x2[0] * self.axes2[0] + x2[1] * self.axes2[1] + x2[2] * self.axes2[2];
        let mut lambda = (r2 - weighted / r2).max(0.0);
        let mut steps = 0;
        while steps < MAX_NEWTON_STEPS {
            steps += 1;
            let inv = [
                1.0 / (self.axes2[0] + lambda),
                1.0 / (self.axes2[1] + lambda),
                1.0 / (self.axes2[2] + lambda),
            ];
            let w = [x2[0] * inv[0], x2[1] * inv[1], x2[2] * inv[2]];
            let s = w[0] + w[1] + w[2];
            let u = w[0] * inv[0] + w[1] * inv[1] + w[2] * inv[2];
            let f = if near {
                excess - lambda * (ratio2[0] * inv[0] + ratio2[1] * inv[1] + ratio2[2] * inv[2])
            } else {
                s - 1.0
            };
            let step = s * f / u;
            lambda += step;
            if step.abs() <= NEWTON_TOLERANCE * (lambda + self.min_axis2) {
                break;
            }
        }
        (lambda.max(0.0), steps)
    }
}

impl Ellipsoid {
    /// [`Potential::field`] kept out of line, so that the lane code it would otherwise be
    /// inlined beside stays small enough for the compiler to vectorise whole.
    #[inline(never)]
    fn field_outlined(&self, r: &Vec3) -> Field {
        self.field(r)
    }

    /// The fields at [`WIDE`] points, each bit for bit [`Potential::field`]'s where the lane
    /// took the lane path, and which lanes did (the others' entries are meaningless).
    ///
    /// A lane outside the body, within the far-field limit and whose $A_i$ suit the shared
    /// division of the duplication takes the lane path: the excess $F_0$, Newton's iteration
    /// and the duplication run the scalar operations side by side, a converged lane frozen
    /// while the others go on. Any other lane (inside or on the body, beyond the far field,
    /// not a number, extreme $A_i$) carries a placeholder, and the caller evaluates that point
    /// with [`Potential::field`].
    #[inline(always)]
    fn field_lanes(&self, points: [Vec3; WIDE]) -> ([Field; WIDE], [bool; WIDE]) {
        let s = &self.scaled;
        let coordinate = |i: usize| F8::new(points.map(|r| r[i])) * s.inv_scale;
        let p = [coordinate(0), coordinate(1), coordinate(2)];
        let mut x2 = [p[0] * p[0], p[1] * p[1], p[2] * p[2]];
        let mut r2 = x2[0] + x2[1] + x2[2];
        // `excess_of`, lane by lane: the plain estimate, refined near the surface.
        let estimate = p[0] * p[0] * s.inv_axes2[0]
            + p[1] * p[1] * s.inv_axes2[1]
            + p[2] * p[2] * s.inv_axes2[2]
            - 1.0;
        let refine = F8::splat(-1e-9)
            .le(estimate)
            .and(estimate.le(F8::splat(2.0)));
        let mut excess = estimate;
        let mut ratio2 = [F8::splat(0.0); 3];
        if refine.any() {
            let (refined, ratios) = surface_excess_lanes(&p, &s.axes, &s.inv_axes);
            excess = refine.select(refined, excess);
            for i in 0..3 {
                ratio2[i] = refine.select(ratios[i], ratio2[i]);
            }
        }
        // Outside and within the far-field limit (`beyond_far_field` is false).
        let mut live = r2
            .le(F8::splat(FAR_FIELD_R2))
            .and(excess.gt(F8::splat(0.0)));
        if !live.all() {
            // A placeholder outside the body (on the x axis, two semi-axes out).
            let placeholder = F8::splat(4.0 * s.axes2[0]);
            x2[0] = live.select(x2[0], placeholder);
            x2[1] = live.select(x2[1], F8::splat(0.0));
            x2[2] = live.select(x2[2], F8::splat(0.0));
            r2 = live.select(r2, placeholder);
            excess = live.select(excess, F8::splat(3.0));
        }
        let lambda = s.confocal_parameter_lanes(&x2, &ratio2, excess, r2, live);
        let mut big_a = [
            s.axes2[0] + lambda,
            s.axes2[1] + lambda,
            s.axes2[2] + lambda,
        ];
        live = live.and(M8::from_flags(std::array::from_fn(|l| {
            shares_division(big_a[0].0[l], big_a[1].0[l], big_a[2].0[l])
        })));
        if !live.all() {
            for a in &mut big_a {
                *a = live.select(*a, F8::splat(1.0));
            }
        }
        let rd = rd_lanes(big_a[0], big_a[1], big_a[2]);
        let w = [x2[0] / big_a[0], x2[1] / big_a[1], x2[2] / big_a[2]];
        let phi = -0.5
            * (big_a[0] * rd[0] * (w[1] + w[2])
                + big_a[1] * rd[1] * (w[0] + w[2])
                + big_a[2] * rd[2] * (w[0] + w[1]));
        let potential = phi * self.gm_over_scale;
        let acceleration = [
            -p[0] * rd[0] * self.gm_over_scale2,
            -p[1] * rd[1] * self.gm_over_scale2,
            -p[2] * rd[2] * self.gm_over_scale2,
        ];
        let fields = std::array::from_fn(|l| Field {
            potential: potential.0[l],
            acceleration: Vec3::new(
                acceleration[0].0[l],
                acceleration[1].0[l],
                acceleration[2].0[l],
            ),
        });
        (fields, live.flags())
    }
}

impl ScaledEllipsoid {
    /// [`ScaledEllipsoid::confocal_parameter`] for [`WIDE`] points side by side, each lane's
    /// result bit for bit the scalar one: the same operations in the same order, a lane frozen
    /// once its step is below the tolerance (or from the start where `live` is false, its
    /// result then meaningless), the loop ending when all are.
    #[inline(always)]
    fn confocal_parameter_lanes(
        &self,
        x2: &[F8; 3],
        ratio2: &[F8; 3],
        excess: F8,
        r2: F8,
        live: M8,
    ) -> F8 {
        let near = excess.lt(F8::splat(1.0));
        let weighted = x2[0] * self.axes2[0] + x2[1] * self.axes2[1] + x2[2] * self.axes2[2];
        let mut lambda = (r2 - weighted / r2).max(F8::splat(0.0));
        let mut done = live.not();
        for _ in 0..MAX_NEWTON_STEPS {
            if done.all() {
                break;
            }
            let inv = [
                1.0 / (self.axes2[0] + lambda),
                1.0 / (self.axes2[1] + lambda),
                1.0 / (self.axes2[2] + lambda),
            ];
            let w = [x2[0] * inv[0], x2[1] * inv[1], x2[2] * inv[2]];
            let s = w[0] + w[1] + w[2];
            let u = w[0] * inv[0] + w[1] * inv[1] + w[2] * inv[2];
            let f = near.select(
                excess - lambda * (ratio2[0] * inv[0] + ratio2[1] * inv[1] + ratio2[2] * inv[2]),
                s - 1.0,
            );
            let step = s * f / u;
            let next = lambda + step;
            let converged = step.abs().le(NEWTON_TOLERANCE * (next + self.min_axis2));
            lambda = done.select(lambda, next);
            done = done.or(converged);
        }
        lambda.max(F8::splat(0.0))
    }
}

fn validate_axes(a: Real, b: Real, c: Real) -> Result<[Real; 3], BodyError> {
    Ok([positive("a", a)?, positive("b", b)?, positive("c", c)?])
}

fn ellipsoid_volume(axes: [Real; 3]) -> Result<Real, BodyError> {
    representable("volume", 4.0 / 3.0 * PI * axes[0] * axes[1] * axes[2])
}

/// The power of two nearest `v` (positive, finite), so that scaling by it is exact.
pub(crate) fn nearest_power_of_two(v: Real) -> Real {
    let exponent = v.log2().round().clamp(-1000.0, 1000.0) as i32;
    let half = exponent / 2;
    Real::powi(2.0, half) * Real::powi(2.0, exponent - half)
}

impl crate::lanes::Batched for Ellipsoid {
    #[inline(always)]
    fn batch<T>(&self, points: &[Vec3], out: &mut [T], pick: impl Fn(Field) -> T) {
        crate::lanes::batch_lanes(self, points, out, pick);
    }
}

impl crate::lanes::LaneField<WIDE> for Ellipsoid {
    #[inline(always)]
    fn field_lanes(&self, points: [Vec3; WIDE]) -> ([Field; WIDE], [bool; WIDE]) {
        Ellipsoid::field_lanes(self, points)
    }

    #[inline(always)]
    fn field_outlined(&self, r: &Vec3) -> Field {
        Ellipsoid::field_outlined(self, r)
    }
}

impl Potential for Ellipsoid {
    fn as_typed(&self) -> crate::TypedPotential<'_> {
        crate::TypedPotential::Ellipsoid(self)
    }

    fn inertia(&self) -> Option<crate::InertiaTensor> {
        let [a, b, c] = self.semi_axes();
        crate::InertiaTensor::solid_ellipsoid(self.mass(), a, b, c).ok()
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
        self.semi_axes[0]
            .max(self.semi_axes[1])
            .max(self.semi_axes[2])
    }

    /// On the surface when $|\sum (x_i/a_i)^2 - 1| \le 4\varepsilon$, computed with
    /// error-free transformations.
    fn region(&self, r: &Vec3) -> Region {
        let s = &self.scaled;
        let p = r * s.inv_scale;
        if beyond_far_field(p.norm_squared()) {
            return Region::Outside;
        }
        region_of_excess(excess_of(&p, &s.axes, &s.inv_axes, &s.inv_axes2).0)
    }

    #[inline]
    fn field(&self, r: &Vec3) -> Field {
        let s = &self.scaled;
        let p = r * s.inv_scale;
        let x2 = [p.x * p.x, p.y * p.y, p.z * p.z];
        let r2 = x2[0] + x2[1] + x2[2];
        if beyond_far_field(r2) {
            return kepler_field(self.gm, r);
        }
        let (excess, ratio2) = excess_of(&p, &s.axes, &s.inv_axes, &s.inv_axes2);
        if excess <= 0.0 {
            // Φ = −(GM/2) Σ (a_i² − x_i²) R_D⁽ⁱ⁾ (DLMF §19.21): positive terms inside.
            let rd = s.interior.rd;
            let depth = |i: usize| (s.axes[i] - p[i]) * (s.axes[i] + p[i]);
            let phi = -0.5 * (depth(0) * rd[0] + depth(1) * rd[1] + depth(2) * rd[2]);
            return Field {
                potential: phi * self.gm_over_scale,
                acceleration: Vec3::new(-p.x * rd[0], -p.y * rd[1], -p.z * rd[2])
                    * self.gm_over_scale2,
            };
        }
        let (lambda, _) = s.confocal_parameter(&x2, &ratio2, excess, r2);
        let big_a = [
            s.axes2[0] + lambda,
            s.axes2[1] + lambda,
            s.axes2[2] + lambda,
        ];
        let rd = symmetric_integrals_in_range(big_a[0], big_a[1], big_a[2]).rd;
        let w = [x2[0] / big_a[0], x2[1] / big_a[1], x2[2] / big_a[2]];
        let phi = -0.5
            * (big_a[0] * rd[0] * (w[1] + w[2])
                + big_a[1] * rd[1] * (w[0] + w[2])
                + big_a[2] * rd[2] * (w[0] + w[1]));
        Field {
            potential: phi * self.gm_over_scale,
            acceleration: Vec3::new(-p.x * rd[0], -p.y * rd[1], -p.z * rd[2]) * self.gm_over_scale2,
        }
    }

    /// Four points at a time through one lane-interleaved evaluation (AVX where the CPU has it),
    /// each result bit for bit [`Potential::field`]'s.
    fn fields_into(&self, points: &[Vec3], out: &mut [Field]) {
        crate::lanes::fields_into(self, points, out);
    }

    /// As [`Potential::fields_into`], keeping the potentials.
    fn potentials_into(&self, points: &[Vec3], out: &mut [Real]) {
        crate::lanes::potentials_into(self, points, out);
    }
}

/// Inside / on / outside from $F_0 = \sum (x_i/a_i)^2 - 1$.
pub(crate) fn region_of_excess(excess: Real) -> Region {
    if excess > SURFACE_BAND {
        Region::Outside
    } else if excess < -SURFACE_BAND {
        Region::Inside
    } else {
        Region::OnSurface
    }
}

/// $F_0 = \sum_i (x_i/a_i)^2 - 1$ and the ratios $(x_i/a_i)^2$ (rounded).
///
/// A plain estimate (error a few ε) settles the clear cases, inside below $-10^{-9}$ and
/// far outside above 2 (the ratios are then not needed and returned as zeros); in between,
/// [`surface_excess`] computes $F_0$ to a few ulp.
#[inline]
pub(crate) fn excess_of(
    p: &Vec3,
    axes: &[Real; 3],
    inv_axes: &[Real; 3],
    inv_axes2: &[Real; 3],
) -> (Real, [Real; 3]) {
    let estimate =
        p.x * p.x * inv_axes2[0] + p.y * p.y * inv_axes2[1] + p.z * p.z * inv_axes2[2] - 1.0;
    if (-1e-9..=2.0).contains(&estimate) {
        surface_excess(&[p.x, p.y, p.z], axes, inv_axes)
    } else {
        (estimate, [0.0; 3])
    }
}

/// $F_0 = \sum_i (x_i/a_i)^2 - 1$ to a few ulp of $|F_0|$ (plus $O(\varepsilon^2)$), and the
/// rounded ratios $(x_i/a_i)^2$.
///
/// `inv_axes` need only approximate $1/a_i$: the exact remainder $x - \hat q a$ of the
/// approximate quotient $\hat q$ restores the lost bits. Needs $|x_i| \lesssim 10^{150}\\,a_i$
/// (no overflow in Dekker's splitting).
#[inline]
fn surface_excess(x: &[Real; 3], axes: &[Real; 3], inv_axes: &[Real; 3]) -> (Real, [Real; 3]) {
    let mut hi = [0.0; 3];
    let mut lo = 0.0;
    for i in 0..3 {
        let q = x[i] * inv_axes[i];
        let (p, e) = exact::product(q, axes[i]);
        // x − p is exact (Sterbenz: p is within a few ulp of x).
        let correction = ((x[i] - p) - e) * inv_axes[i];
        let (sq, sq_err) = exact::square(q);
        hi[i] = sq;
        lo += sq_err + 2.0 * q * correction;
    }
    let (s01, e01) = exact::sum(hi[0], hi[1]);
    let (s012, e012) = exact::sum(s01, hi[2]);
    let (excess, e_one) = exact::sum(s012, -1.0);
    (excess + (((e01 + e012) + e_one) + lo), hi)
}

/// [`surface_excess`] for [`WIDE`] points, each lane bit for bit the scalar result (the same
/// operations in the same order, [`exact::lanes`]).
#[inline(always)]
fn surface_excess_lanes(x: &[F8; 3], axes: &[Real; 3], inv_axes: &[Real; 3]) -> (F8, [F8; 3]) {
    let mut hi = [F8::splat(0.0); 3];
    let mut lo = F8::splat(0.0);
    for i in 0..3 {
        let q = x[i] * inv_axes[i];
        let (p, e) = exact::lanes::product(q, axes[i]);
        let correction = ((x[i] - p) - e) * inv_axes[i];
        let (sq, sq_err) = exact::lanes::square(q);
        hi[i] = sq;
        lo = lo + (sq_err + 2.0 * q * correction);
    }
    let (s01, e01) = exact::lanes::sum(hi[0], hi[1]);
    let (s012, e012) = exact::lanes::sum(s01, hi[2]);
    let (excess, e_one) = exact::lanes::sum(s012, F8::splat(-1.0));
    (excess + (((e01 + e012) + e_one) + lo), hi)
}

/// Error-free transformations of floating-point sums and products (Knuth, Dekker), without
/// relying on a hardware fused multiply-add.
pub(crate) mod exact {
    use crate::Real;

    /// $2^{27} + 1$: splits a double into two halves of 26 bits.
    const SPLITTER: Real = 134_217_729.0;

    #[inline]
    fn split(a: Real) -> (Real, Real) {
        let c = SPLITTER * a;
        let hi = c - (c - a);
        (hi, a - hi)
    }

    /// `(s, e)` with `s = fl(a + b)` and `a + b = s + e` exactly.
    #[inline]
    pub(crate) fn sum(a: Real, b: Real) -> (Real, Real) {
        let s = a + b;
        let bb = s - a;
        (s, (a - (s - bb)) + (b - bb))
    }

    /// `(p, e)` with `p = fl(a b)` and `a b = p + e` exactly (no overflow, no underflow).
    #[inline]
    pub(crate) fn product(a: Real, b: Real) -> (Real, Real) {
        let p = a * b;
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }

    /// `(p, e)` with `p = fl(a²)` and `a² = p + e` exactly.
    #[inline]
    pub(crate) fn square(a: Real) -> (Real, Real) {
        let p = a * a;
        let (ah, al) = split(a);
        (p, ((ah * ah - p) + 2.0 * ah * al) + al * al)
    }

    /// The same transformations on lanes, operation for operation.
    pub(crate) mod lanes {
        use super::{split as split_scalar, SPLITTER};
        use crate::lanes::Lane;
        use crate::Real;

        #[inline(always)]
        fn split<L: Lane>(a: L) -> (L, L) {
            // SPLITTER · a, lane by lane (the constant on the right: the same product).
            let c = a * SPLITTER;
            let hi = c - (c - a);
            (hi, a - hi)
        }

        /// [`super::sum`] lane by lane.
        #[inline(always)]
        pub(crate) fn sum<L: Lane>(a: L, b: L) -> (L, L) {
            let s = a + b;
            let bb = s - a;
            (s, (a - (s - bb)) + (b - bb))
        }

        /// [`super::product`] lane by lane, by the same `b` in every lane.
        #[inline(always)]
        pub(crate) fn product<L: Lane>(a: L, b: Real) -> (L, L) {
            let p = a * b;
            let (ah, al) = split(a);
            let (bh, bl) = split_scalar(b);
            (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
        }

        /// [`super::square`] lane by lane.
        #[inline(always)]
        pub(crate) fn square<L: Lane>(a: L) -> (L, L) {
            let p = a * a;
            let (ah, al) = split(a);
            (p, ((ah * ah - p) + L::splat(2.0) * ah * al) + al * al)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic directions spread over the sphere (Fibonacci lattice).
    fn directions(n: usize) -> Vec<Vec3> {
        let golden = (1.0 + 5f64.sqrt()) / 2.0;
        (0..n)
            .map(|k| {
                let z = 1.0 - 2.0 * (k as f64 + 0.5) / n as f64;
                let phi = 2.0 * PI * (k as f64 / golden).fract();
                let s = (1.0 - z * z).sqrt();
                Vec3::new(s * phi.cos(), s * phi.sin(), z)
            })
            .collect()
    }

    /// The four components of a field as bits (a NaN equal only to the same NaN).
    fn bits(f: &Field) -> [u64; 4] {
        [
            f.potential,
            f.acceleration.x,
            f.acceleration.y,
            f.acceleration.z,
        ]
        .map(f64::to_bits)
    }

    /// Points on rays through the surface point in each direction, at `factor` times its
    /// distance, with the factors' class: `Some(true)` must take the lane path (outside, not
    /// beyond the far field), `Some(false)` must not, `None` either (within 1e-12 of the
    /// surface). A few non-finite and degenerate points follow, then a deterministic shuffle
    /// so that every chunk of lanes mixes cases.
    fn batch_points(axes: [f64; 3]) -> Vec<(Vec3, Option<bool>)> {
        let factors = [
            (0.0, Some(false)),
            (0.3, Some(false)),
            (0.999, Some(false)),
            (1.0 - 1e-12, None),
            (1.0, None),
            (1.0 + 1e-12, None),
            (1.0 + 1e-9, Some(true)),
            (1.0 + 1e-6, Some(true)),
            (1.001, Some(true)),
            (1.01, Some(true)),
            (1.1, Some(true)),
            (1.5, Some(true)),
            (2.0, Some(true)),
            (3.0, Some(true)),
            (10.0, Some(true)),
            (1e3, Some(true)),
            (1e8, Some(true)),
            (1e19, Some(true)),
            (1e21, Some(false)),
        ];
        let mut points = Vec::new();
        for dir in directions(64) {
            let t = 1.0
                / ((dir.x / axes[0]).powi(2)
                    + (dir.y / axes[1]).powi(2)
                    + (dir.z / axes[2]).powi(2))
                .sqrt();
            for (factor, class) in factors {
                // Beyond the far field at 1e20 scaled units (the scale is within a factor √2
                // of the largest semi-axis): a short ray of a flat body may fall short of it.
                let largest = axes[0].max(axes[1]).max(axes[2]);
                let class = if factor > 1e20 && t * factor < 1.5e20 * largest {
                    None
                } else {
                    class
                };
                points.push((dir * (t * factor), class));
            }
        }
        for r in [
            Vec3::new(f64::NAN, 0.0, 0.0),
            Vec3::new(1.0, f64::NAN, 1.0),
            Vec3::new(f64::INFINITY, 0.0, 0.0),
            Vec3::new(-1e300, 1e300, 0.0),
            Vec3::new(0.0, 0.0, 3.0 * axes[2]),
        ] {
            points.push((r, None));
        }
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        for k in (1..points.len()).rev() {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            points.swap(k, (state % (k as u64 + 1)) as usize);
        }
        points
    }

    /// The batched field equals the scalar one bit for bit, through every instantiation and
    /// the trait methods, over needles, disks, nearly spheres, the accuracy tests' shapes and
    /// SI magnitudes; and the lane path is the one taken wherever it should be.
    #[test]
    fn batched_fields_are_the_scalar_fields_bit_for_bit() {
        let shapes = [
            ([3.0, 2.0, 1.0], 1.0, 1.0),
            ([1.0, 0.5, 0.01], 1.0, 1.0),
            ([1.0, 0.3, 1e-4], 1.0, 1.0),
            ([1e-4, 2e-4, 1.0], 1.0, 1.0),
            ([1.0, 1.0 + 1e-9, 1.0 - 1e-9], 1.0, 1.0),
            ([1.0, 1.0, 1.0], 1.0, 1.0),
            ([1.0, 1e-4, 1e-4], 1.0, 1.0),
            ([1.0, 1.0, 1e-4], 2.0, 1.0),
            ([766.0, 747.5, 673.5], 2.353e12, 6.674_30e-11),
        ];
        let mut lane_points = 0;
        for (axes, mass, g) in shapes {
            let body = Ellipsoid::new(axes[0], axes[1], axes[2], mass)
                .unwrap()
                .with_gravitational_constant(g)
                .unwrap();
            let cases = batch_points(axes);
            let points: Vec<Vec3> = cases.iter().map(|c| c.0).collect();
            assert_ne!(points.len() % WIDE, 0, "a remainder is exercised");
            let scalar: Vec<Field> = points.iter().map(|r| body.field(r)).collect();
            let placeholder = Field {
                potential: 0.0,
                acceleration: Vec3::zeros(),
            };
            let mut runs: Vec<(&str, Vec<Field>)> = Vec::new();
            let mut out = vec![placeholder; points.len()];
            crate::lanes::fields_plain(&body, &points, &mut out);
            runs.push(("plain", out.clone()));
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx") {
                // SAFETY: AVX detected just above.
                unsafe { crate::lanes::fields_avx(&body, &points, &mut out) };
                runs.push(("avx", out.clone()));
            }
            body.fields_into(&points, &mut out);
            runs.push(("fields_into", out.clone()));
            for (name, fields) in &runs {
                for (k, (field, reference)) in fields.iter().zip(&scalar).enumerate() {
                    assert_eq!(
                        bits(field),
                        bits(reference),
                        "{name} at {:?} for {axes:?}: {field:?} vs {reference:?}",
                        points[k]
                    );
                }
            }
            let mut potentials = vec![0.0; points.len()];
            body.potentials_into(&points, &mut potentials);
            for (value, reference) in potentials.iter().zip(&scalar) {
                assert_eq!(value.to_bits(), reference.potential.to_bits());
            }
            // A shorter output takes the points it has room for and leaves the rest alone.
            let mut short = vec![placeholder; 7];
            body.fields_into(&points[..9], &mut short);
            for (field, reference) in short.iter().zip(&scalar) {
                assert_eq!(bits(field), bits(reference));
            }
            // Which lanes take the lane path.
            for chunk in cases.chunks_exact(WIDE) {
                let (_, taken) = body.field_lanes(std::array::from_fn(|l| chunk[l].0));
                for (case, taken) in chunk.iter().zip(taken) {
                    if let Some(expected) = case.1 {
                        assert_eq!(taken, expected, "lane path at {:?} for {axes:?}", case.0);
                    }
                    lane_points += usize::from(taken);
                }
            }
        }
        println!("points through the lane path: {lane_points}");
    }

    /// Newton's step count for the confocal parameter, over shapes from needles to disks and
    /// points from 1e-12 above the surface to 1e19 body sizes (a snapshot: a change of the
    /// starting bound or the stopping rule shows here).
    #[test]
    fn newton_step_count_snapshot() {
        let shapes = [
            [3.0, 2.0, 1.0],
            [1.0, 1.0, 1.0],
            [1.0, 0.5, 1e-4],
            [1e-4, 2e-4, 1.0],
            [1.0, 1.0 + 1e-9, 1.0 - 1e-9],
            [1.0, 1e-4, 1e-4],
        ];
        let mut worst = 0;
        let mut histogram = [0usize; MAX_NEWTON_STEPS + 1];
        for axes in shapes {
            let body = Ellipsoid::new(axes[0], axes[1], axes[2], 1.0).unwrap();
            let s = &body.scaled;
            for dir in directions(200) {
                let t = 1.0
                    / ((dir.x / axes[0]).powi(2)
                        + (dir.y / axes[1]).powi(2)
                        + (dir.z / axes[2]).powi(2))
                    .sqrt();
                for factor in [
                    1.0 + 1e-12,
                    1.0 + 1e-6,
                    1.001,
                    1.1,
                    2.0,
                    10.0,
                    1e3,
                    1e8,
                    1e19,
                ] {
                    let p = dir * (t * factor) * s.inv_scale;
                    let x2 = [p.x * p.x, p.y * p.y, p.z * p.z];
                    let (excess, ratio2) = surface_excess(&[p.x, p.y, p.z], &s.axes, &s.inv_axes);
                    if excess <= 0.0 {
                        continue;
                    }
                    let (lambda, steps) =
                        s.confocal_parameter(&x2, &ratio2, excess, x2[0] + x2[1] + x2[2]);
                    histogram[steps] += 1;
                    worst = worst.max(steps);
                    // The secular equation holds to rounding.
                    let sum: f64 = (0..3).map(|i| x2[i] / (s.axes2[i] + lambda)).sum();
                    assert!(
                        (sum - 1.0).abs() < 8.0 * f64::EPSILON,
                        "S(λ) − 1 = {:e} at {p:?} for {axes:?}",
                        sum - 1.0
                    );
                }
            }
        }
        println!("Newton steps histogram: {histogram:?}");
        assert!(worst <= 8, "worst Newton step count {worst}: {histogram:?}");
    }
}
