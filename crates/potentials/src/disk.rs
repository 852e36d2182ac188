//! The uniform disk: a lamina of radius $R$ in the body's x–y plane, centred on the origin, with
//! constant surface density $\sigma = M / (\pi R^2)$.
//!
//! # Potential
//!
//! $\Phi(\mathbf r) = -G\sigma \int\_{\rho' \le R} \mathrm dA' / |\mathbf r - \mathbf r'|$, defined and
//! continuous everywhere, through the lamina and across the rim. In cylindrical coordinates
//! $(\rho, z)$ scaled by $R$ (so the rim is $\rho = 1$), with
//!
//! $$S\_\pm = \sqrt{(1 \pm \rho)^2 + z^2},\quad k_c = S\_-/S\_+ = \sqrt{1 - m},\quad
//! m = \frac{4\rho}{S\_+^2},\quad \sqrt{1 - n} = \frac{|1 - \rho|}{1 + \rho},\quad
//! n = \frac{4\rho}{(1+\rho)^2},$$
//!
//! summing rings of radius $s$ (each $\Phi = -G\\,\mathrm dm\\,(2/\pi) K(m_s) / S\_+(s)$) gives the
//! classical closed form
//!
//! $$\Phi = -2G\sigma R\Big[S\_+ E(m) + \frac{1-\rho^2}{S\_+}K(m) +
//!   \frac{z^2 (1-\rho)}{(1+\rho) S\_+}\Pi(n, m)\Big] + 2\pi G\sigma R\\,|z|\\,H(1-\rho),$$
//!
//! with $H$ the step function ($H(0) = 1/2$). The step and the jump of the $\Pi$ term at
//! $\rho = 1$ cancel, so $\Phi$ is continuous at the rim. We evaluate it as
//!
//! $$\Phi = -2G\sigma R\\,\frac{B\\,(2 + 2\rho + z^2) + D\\,(2 - 2\rho + z^2) +
//!   z^2\\,\mathrm{sgn}(1-\rho)\\,P}{S\_+} + 2\pi G\sigma R\\,|z|\\,H(1-\rho),
//!   \qquad P = \sqrt{1-n}\\;\Pi(n, m),$$
//!
//! with $B$, $D$ and $P$ from [`crate::elliptic`] (all subtraction-free, $P$ finite as
//! $\rho \to 1$). On the axis the bracket reduces to $\pi(S\_+ - |z|)$, giving
//! $\Phi = -2\pi G\sigma(\sqrt{R^2 + z^2} - |z|)$.
//!
//! # Acceleration
//!
//! $\mathbf a = -\nabla\Phi$. The in-plane part comes from the rim (Gauss's theorem in the plane
//! turns $\nabla\_\parallel$ of the area integral into a line integral over the rim), and is a
//! positive integral with no cancellation:
//!
//! $$a\_\rho = -16\\,G\sigma\\,\frac{\rho\\,C(m)}{S\_+^3},\qquad C = \frac{D - B}{m}.$$
//!
//! The normal part is $G\sigma$ times the solid angle $\Omega$ the disk subtends:
//!
//! $$a_z = -\operatorname{sgn}(z)\\,G\sigma\\,\Omega,\qquad
//! \Omega = 2\pi H(1-\rho) - \frac{2|z|}{S\_+}\big[K(m) + \mathrm{sgn}(1-\rho)\\,P\big].$$
//!
//! # Conventions on the lamina and at the rim
//!
//! - **On the lamina** ($z = 0$, $\rho < R$) $a_z$ jumps by $4\pi G\sigma$ (from $+2\pi G\sigma$
//!   below to $-2\pi G\sigma$ above). We return the **average of the two sides**, $a_z = 0$, with
//!   the in-plane components and $\Phi$, which are continuous there. The same rule gives
//!   $a_z = 0$ in the plane outside the disk, where there is no jump.
//! - **At the rim** ($\rho = R$, $z = 0$) $a\_\rho$ diverges like
//!   $-2G\sigma(\ln(8R/d) - 2)$ at a distance $d$ from it, on either side (R = M = G = 1:
//!   −8.85 at $d = 10^{-6}R$, −14.71 at $10^{-10}R$). Exactly on the rim the in-plane
//!   acceleration is returned as an infinity pointing to the axis ($-\infty$ times the sign of
//!   each nonzero in-plane coordinate, 0 along a zero one), never a finite stand-in; $a_z = 0$ by
//!   the average rule, and $\Phi$ is finite and continuous there ($\Phi = -4G\sigma R$; we
//!   return its value at $d = \varepsilon R$, relative error $O(\varepsilon\ln\varepsilon)$).
//! - Near the rim the field is ill-conditioned in the position itself (a change of one ULP in
//!   $\rho$ at $\rho = R(1 \pm 10^{-9})$ changes $\mathbf a$ by ~$10^{-8}$). The signed distance
//!   $\rho - R$ is therefore formed from $x^2 + y^2 - R^2$ in double-double arithmetic, so the
//!   field is the one at the exact input point.
//!
//! # Far field
//!
//! The closed form's terms are $O(r)$ while $\Phi = O(R^2/r)$: it loses about $(r/R)^2$ in
//! relative precision. From $r \ge 2R$ we use the exterior expansion instead, exact for $r > R$:
//!
//! $$\Phi = -\frac{GM}{r}\sum\_{l \ge 0} c_l \Big(\frac{R}{r}\Big)^{2l} P\_{2l}(\cos\theta),\qquad
//! c_l = 2\binom{1/2}{l+1} = 1, -\tfrac14, \tfrac18, -\tfrac5{64}, \dots$$
//!
//! whose coefficients come from the on-axis potential
//! $-2\pi G\sigma(\sqrt{R^2+z^2} - |z|) = -\frac{GM}{z}\sum_l c_l (R/z)^{2l}$. The quadrupole
//! term is $+\frac{GMR^2}{4r^3}P_2(\cos\theta)$ (MacCullagh with $I\_{zz} = MR^2/2$,
//! $I\_{xx} = I\_{yy} = MR^2/4$). Its gradient uses
//! $\partial_z (r^{-n-1}P_n) = -(n+1) r^{-n-2} P\_{n+1}$ and
//! $\partial\_\rho (r^{-n-1}P_n) = -r^{-n-2}\sin\theta\\,P'\_{n+1}$. At $r = 2R$ the series needs 29
//! terms; at $r = 10R$, 10; at $r = 10^8 R$, 3.
//!
//! # Batches
//!
//! [`Potential::fields_into`] and [`Potential::potentials_into`] sort each sixteen points into
//! near and far ones and take them four at a time: the closed form of the near ones (its
//! quantities before and after the Gauss iteration, and the iteration itself) and the exterior
//! series of the far ones run side by side in lanes (one vector instruction per operation; two
//! groups of four interleaved), each lane frozen once its own iteration or series has stopped
//! and each branch taken as a selection, so that every result is bit for bit the point's own
//! [`Potential::field`].
//!
//! # Accuracy
//!
//! Against 50-digit evaluations (mpmath) of the formulas above, themselves checked against the
//! ring integral, at 5,400 points: $\le 4.1\times10^{-15}$ relative in $\Phi$ and
//! $\le 3.5\times10^{-15}$ in $\mathbf a$ (vector norm), the worst just inside $r = 2R$ where
//! the closed form's cancellation peaks; $\le 1.4\times10^{-15}$ near the rim
//! ($\rho = R(1 \pm 10^{-12} \dots 10^{-3})$, $0 \le |z| \le R/2$), on and near the lamina
//! and the axis, and $\le 6\times10^{-16}$ for $r \ge 2R$ out to $10^8 R$; at SI magnitudes
//! alike. Cost per [`Potential::field`]: `cargo bench -p surfgrav-potentials` (`uniform_disk` in each group).

use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;

use crate::elliptic::{gauss, gauss_lanes, Gauss};
use crate::error::{positive, representable};
use crate::lanes::{F4, LANES, M4};
use crate::{BodyError, Field, Potential, Real, Region, Vec3};
use surfgrav_quadrature::two_sum;

/// From this distance (in disk radii) on, the exterior Legendre series replaces the closed form
/// (measured: the closed form's error grows as ~(r/R)² ε and reaches 4e-15 at r = 2R; the
/// series needs 29 terms there).
const FAR_FIELD_RADII: Real = 2.0;

/// Points of a batch sorted into far and near groups together.
const SEGMENT: usize = 4 * LANES;

/// Number of terms of the exterior series kept (29 are needed at r = 2R).
const SERIES_TERMS: usize = 32;

/// A homogeneous disk of zero thickness (a lamina) in the body's x–y plane, centred on the
/// origin. Units: any consistent system; `radius` in length, `mass` in mass, G in
/// length³/(mass·time²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformDisk {
    radius: Real,
    mass: Real,
    gravitational_constant: Real,
    surface_density: Real,
    /// Gσ: the scale of the acceleration in the closed form.
    g_sigma: Real,
    /// GσR: the scale of the potential in the closed form.
    g_sigma_radius: Real,
    /// GM, for the far field.
    gm: Real,
}

impl UniformDisk {
    /// A disk of the given radius and total mass, with G = 1. Both must be positive and finite,
    /// and the surface density M/(πR²) representable.
    pub fn new(radius: Real, mass: Real) -> Result<Self, BodyError> {
        let radius = positive("radius", radius)?;
        let mass = positive("mass", mass)?;
        Self::build(radius, mass, 1.0)
    }

    /// The same disk with gravitational constant `g` (positive, finite).
    pub fn with_gravitational_constant(self, g: Real) -> Result<Self, BodyError> {
        let g = positive("gravitational_constant", g)?;
        Self::build(self.radius, self.mass, g)
    }

    fn build(radius: Real, mass: Real, g: Real) -> Result<Self, BodyError> {
        let surface_density = representable("surface_density", mass / (PI * radius) / radius)?;
        let g_sigma = representable(
            "gravitational_constant * surface_density",
            g * surface_density,
        )?;
        let g_sigma_radius = representable(
            "gravitational_constant * surface_density * radius",
            g_sigma * radius,
        )?;
        let gm = representable("gravitational_constant * mass", g * mass)?;
        Ok(Self {
            radius,
            mass,
            gravitational_constant: g,
            surface_density,
            g_sigma,
            g_sigma_radius,
            gm,
        })
    }

    /// Radius R.
    pub fn radius(&self) -> Real {
        self.radius
    }

    /// Surface density σ = M / (πR²) (mass per area).
    pub fn surface_density(&self) -> Real {
        self.surface_density
    }

    /// $(\rho - R)/R$ for a point at `rho` $= \sqrt{x^2+y^2}$, exact to a few ULP of itself even
    /// within $10^{-16}R$ of the rim.
    fn relative_rim_offset(&self, x: Real, y: Real, rho: Real) -> Real {
        let r = self.radius;
        let rho_n = rho / r;
        if (rho_n - 1.0).abs() >= 0.5 {
            return rho_n - 1.0;
        }
        // x² + y² − R² in double-double, then ρ − R = (x² + y² − R²)/(ρ + R).
        let (px, ex) = two_product(x, x);
        let (py, ey) = two_product(y, y);
        let (pr, er) = two_product(r, r);
        let (s1, f1) = two_sum(px, py);
        let (s2, f2) = two_sum(s1, -pr);
        let excess = s2 + (f1 + f2 + ex + ey - er);
        excess / (rho + r) / r
    }

    /// The closed form, for points within `FAR_FIELD_RADII` radii.
    #[inline]
    fn near_field(&self, p: &Vec3, rho: Real) -> Field {
        let near = self.near_point(p, rho);
        let g = gauss(near.kc, near.use_pi_track.then_some(near.snc));
        self.near_finish(&near, &g)
    }

    /// The closed form's quantities before the elliptic integrals.
    #[inline(always)]
    fn near_point(&self, p: &Vec3, rho: Real) -> NearPoint {
        let r = self.radius;
        let (xn, yn, zn) = (p.x / r, p.y / r, p.z / r);
        let rho_n = rho / r;
        let delta = self.relative_rim_offset(p.x, p.y, rho);
        let az = zn.abs();
        let z2 = az * az;
        let s_plus = hypot(2.0 + delta, az);
        let mut s_minus = hypot(delta, az);
        let on_rim = s_minus == 0.0;
        if on_rim {
            // Exactly on the rim: Φ is the one at ε·R from it (continuous; see the module docs),
            // the in-plane acceleration is infinite (set below).
            s_minus = Real::EPSILON;
        }
        let kc = s_minus / s_plus;
        // (1 − ρ)/(1 + ρ) = sgn(1 − ρ) √(1 − n).
        let signed_snc = -delta / (2.0 + delta);
        let snc = signed_snc.abs();
        // P = √(1−n) Π(n, m) enters multiplied by z² and |z| and not at all on the rim circle.
        let needs_pi = az > 0.0 && delta != 0.0;
        // Below 1e-20 k_c, P equals its limit π/(2 k_c) to double precision.
        let use_pi_track = needs_pi && snc > 1e-20 * kc;
        NearPoint {
            xn,
            yn,
            z: p.z,
            rho_n,
            delta,
            az,
            z2,
            s_plus,
            on_rim,
            kc,
            signed_snc,
            snc,
            needs_pi,
            use_pi_track,
        }
    }

    /// The closed form from the point's quantities and its elliptic integrals.
    #[inline(always)]
    fn near_finish(&self, near: &NearPoint, g: &Gauss) -> Field {
        let NearPoint {
            xn,
            yn,
            z,
            rho_n,
            delta,
            az,
            z2,
            s_plus,
            on_rim,
            kc,
            signed_snc,
            needs_pi,
            use_pi_track,
            ..
        } = *near;
        let p_scaled = if !needs_pi {
            0.0
        } else if use_pi_track {
            g.pi_scaled
        } else {
            FRAC_PI_2 / kc
        };
        let signed_p = if needs_pi {
            p_scaled.copysign(signed_snc)
        } else {
            0.0
        };
        let step = if delta < 0.0 {
            1.0
        } else if delta == 0.0 {
            0.5
        } else {
            0.0
        };

        let bracket =
            (g.b * (2.0 + 2.0 * rho_n + z2) + g.d * (z2 - 2.0 * delta) + z2 * signed_p) / s_plus;
        let v = 2.0 * bracket - 2.0 * PI * az * step;
        let omega = 2.0 * PI * step - 2.0 * az / s_plus * (g.k + signed_p);
        let radial_over_rho = -16.0 * g.c / (s_plus * s_plus * s_plus);
        let side = if z > 0.0 {
            1.0
        } else if z < 0.0 {
            -1.0
        } else {
            0.0
        };
        if on_rim {
            // a_ρ = −∞ toward the axis; a component along which the rim point has no offset is
            // 0 (not ∞·0 = NaN), and a_z = 0 by the average rule.
            let inward = |c: Real| {
                if c == 0.0 {
                    0.0
                } else {
                    -Real::INFINITY.copysign(c)
                }
            };
            return Field {
                potential: -self.g_sigma_radius * v,
                acceleration: Vec3::new(inward(xn), inward(yn), 0.0),
            };
        }
        Field {
            potential: -self.g_sigma_radius * v,
            acceleration: Vec3::new(
                self.g_sigma * radial_over_rho * xn,
                self.g_sigma * radial_over_rho * yn,
                -self.g_sigma * side * omega,
            ),
        }
    }

    /// [`UniformDisk::near_point`] for [`LANES`] points side by side (`rho` their
    /// $\sqrt{x^2+y^2}$): the same operations in the same order, lane by lane, the branches
    /// taken as selections (the rim offset's double-double form where any lane lies within half
    /// a radius of the rim; [`hypot`]'s library fallback lane by lane where needed).
    #[inline(always)]
    fn near_lanes(&self, p: &[Vec3; LANES], rho: F4) -> NearLanes {
        let r = self.radius;
        let x = F4::new(std::array::from_fn(|l| p[l].x));
        let y = F4::new(std::array::from_fn(|l| p[l].y));
        let z = F4::new(std::array::from_fn(|l| p[l].z));
        let (xn, yn, zn) = (x / r, y / r, z / r);
        let rho_n = rho / r;
        // relative_rim_offset: ρ_n − 1 unless |ρ_n − 1| < 1/2 (or is not a number).
        let coarse = rho_n - 1.0;
        let far_from_rim = F4::splat(0.5).le(coarse.abs());
        let delta = if far_from_rim.all() {
            coarse
        } else {
            let (px, ex) = two_square_lanes(x);
            let (py, ey) = two_square_lanes(y);
            let (pr, er) = two_product(r, r);
            let (s1, f1) = two_sum_lanes(px, py);
            let (s2, f2) = two_sum_lanes(s1, F4::splat(-pr));
            let excess = s2 + ((((f1 + f2) + ex) + ey) - er);
            far_from_rim.select(coarse, excess / (rho + r) / r)
        };
        let az = zn.abs();
        let z2 = az * az;
        let s_plus = hypot_lanes(2.0 + delta, az);
        let s_minus = hypot_lanes(delta, az);
        // s_minus is a square root or a hypot: zero or positive or not a number.
        let on_rim = s_minus.le(F4::splat(0.0));
        let s_minus = on_rim.select(F4::splat(Real::EPSILON), s_minus);
        let kc = s_minus / s_plus;
        let signed_snc = -delta / (2.0 + delta);
        let snc = signed_snc.abs();
        let needs_pi = az
            .gt(F4::splat(0.0))
            .and(M4::from_flags(std::array::from_fn(|l| delta.0[l] != 0.0)));
        let use_pi_track = needs_pi.and(snc.gt(1e-20 * kc));
        NearLanes {
            xn,
            yn,
            z,
            rho_n,
            delta,
            az,
            z2,
            s_plus,
            on_rim,
            kc,
            signed_snc,
            snc,
            needs_pi,
            use_pi_track,
        }
    }

    /// [`UniformDisk::near_finish`] for [`LANES`] points side by side: the same operations in
    /// the same order, lane by lane; the lanes on the rim circle lane by lane.
    #[inline(always)]
    fn near_finish_lanes(&self, near: &NearLanes, g: &[Gauss; LANES]) -> [Field; LANES] {
        let lane = |f: fn(&Gauss) -> Real| F4::new(std::array::from_fn(|l| f(&g[l])));
        let (k, b, d, c, pi_scaled) = (
            lane(|g| g.k),
            lane(|g| g.b),
            lane(|g| g.d),
            lane(|g| g.c),
            lane(|g| g.pi_scaled),
        );
        let zero = F4::splat(0.0);
        let NearLanes {
            xn,
            yn,
            z,
            rho_n,
            delta,
            az,
            z2,
            s_plus,
            on_rim,
            kc,
            signed_snc,
            needs_pi,
            use_pi_track,
            ..
        } = *near;
        let p_scaled = needs_pi.select(use_pi_track.select(pi_scaled, FRAC_PI_2 / kc), zero);
        let signed_p = needs_pi.select(
            F4::new(std::array::from_fn(|l| {
                p_scaled.0[l].copysign(signed_snc.0[l])
            })),
            zero,
        );
        let delta_zero = M4::from_flags(std::array::from_fn(|l| delta.0[l] == 0.0));
        let step = delta
            .lt(zero)
            .select(F4::splat(1.0), delta_zero.select(F4::splat(0.5), zero));
        let bracket =
            (b * (2.0 + 2.0 * rho_n + z2) + d * (z2 - 2.0 * delta) + z2 * signed_p) / s_plus;
        let v = 2.0 * bracket - 2.0 * PI * az * step;
        let omega = 2.0 * PI * step - 2.0 * az / s_plus * (k + signed_p);
        let radial_over_rho = -16.0 * c / (s_plus * s_plus * s_plus);
        let side = z
            .gt(zero)
            .select(F4::splat(1.0), z.lt(zero).select(F4::splat(-1.0), zero));
        let potential = -self.g_sigma_radius * v;
        let ax = self.g_sigma * radial_over_rho * xn;
        let ay = self.g_sigma * radial_over_rho * yn;
        let az_field = -self.g_sigma * side * omega;
        let rim = on_rim.flags();
        std::array::from_fn(|l| {
            if rim[l] {
                // As near_finish: a_ρ = −∞ toward the axis, 0 along a zero offset, a_z = 0.
                let inward = |c: Real| {
                    if c == 0.0 {
                        0.0
                    } else {
                        -Real::INFINITY.copysign(c)
                    }
                };
                return Field {
                    potential: potential.0[l],
                    acceleration: Vec3::new(inward(xn.0[l]), inward(yn.0[l]), 0.0),
                };
            }
            Field {
                potential: potential.0[l],
                acceleration: Vec3::new(ax.0[l], ay.0[l], az_field.0[l]),
            }
        })
    }

    /// [`UniformDisk::far_field`] for up to `G` groups of [`LANES`] points (`Some((point,
    /// dist))`) side by side: the same terms in the same order, each lane's sums frozen once its
    /// own series has stopped; the entries of the `None` lanes are meaningless. The groups'
    /// recurrences are independent chains, so two groups interleave in the processor (one
    /// group's series is a chain of dependent multiplications and subtractions).
    #[inline(always)]
    fn far_field_lanes<const G: usize>(
        &self,
        points: &[[Option<(Vec3, Real)>; LANES]; G],
    ) -> [[Field; LANES]; G] {
        let tables = series_tables();
        let zero = F4::splat(0.0);
        let dist: [F4; G] = std::array::from_fn(|g| {
            F4::new(std::array::from_fn(|l| points[g][l].map_or(1.0, |p| p.1)))
        });
        let u: [F4; G] = std::array::from_fn(|g| {
            F4::new(std::array::from_fn(|l| points[g][l].map_or(0.0, |p| p.0.z))) / dist[g]
        });
        let t: [F4; G] = std::array::from_fn(|g| {
            let ratio = self.radius / dist[g];
            ratio * ratio
        });
        let (mut p_even, mut p_odd) = ([F4::splat(1.0); G], u);
        let mut d_odd = [F4::splat(1.0); G];
        let (mut sum_potential, mut sum_axial, mut sum_radial) = ([zero; G], [zero; G], [zero; G]);
        let mut t_power = [F4::splat(1.0); G];
        let mut active: [M4; G] = std::array::from_fn(|g| {
            M4::from_flags(std::array::from_fn(|l| points[g][l].is_some()))
        });
        for l in 0..SERIES_TERMS {
            let k = 2 * l + 1;
            let mut any = false;
            for g in 0..G {
                let c = tables.coefficient[l] * t_power[g];
                let on = active[g];
                sum_potential[g] = on.select(sum_potential[g] + c * p_even[g], sum_potential[g]);
                sum_axial[g] = on.select(
                    sum_axial[g] + c * tables.odd_degree[l] * p_odd[g],
                    sum_axial[g],
                );
                sum_radial[g] = on.select(sum_radial[g] + c * d_odd[g], sum_radial[g]);
                let done = (c.abs() * (tables.odd_degree[l] + 1.0)).lt(F4::splat(1e-17));
                active[g] = on.and(done.not());
                any |= active[g].any();
            }
            if !any {
                break;
            }
            for g in 0..G {
                let p_next_even = tables.rec_a[k] * u[g] * p_odd[g] - tables.rec_b[k] * p_even[g];
                let p_next_odd =
                    tables.rec_a[k + 1] * u[g] * p_next_even - tables.rec_b[k + 1] * p_odd[g];
                d_odd[g] = d_odd[g] + tables.rec_c[k + 1] * p_next_even;
                p_even[g] = p_next_even;
                p_odd[g] = p_next_odd;
                t_power[g] = t_power[g] * t[g];
            }
        }
        std::array::from_fn(|g| {
            let gm_over_r = self.gm / dist[g];
            let gm_over_r2 = gm_over_r / dist[g];
            std::array::from_fn(|l| {
                let p = points[g][l].map_or(Vec3::zeros(), |p| p.0);
                let (dist, gm_over_r, gm_over_r2) = (dist[g].0[l], gm_over_r.0[l], gm_over_r2.0[l]);
                Field {
                    potential: -gm_over_r * sum_potential[g].0[l],
                    acceleration: Vec3::new(
                        -gm_over_r2 * (p.x / dist) * sum_radial[g].0[l],
                        -gm_over_r2 * (p.y / dist) * sum_radial[g].0[l],
                        -gm_over_r2 * sum_axial[g].0[l],
                    ),
                }
            })
        })
    }

    /// The exterior Legendre series, for points at `dist` ≥ `FAR_FIELD_RADII` radii.
    fn far_field(&self, p: &Vec3, dist: Real) -> Field {
        let tables = series_tables();
        let u = p.z / dist;
        let ratio = self.radius / dist;
        let t = ratio * ratio;
        // P_{2l}, P_{2l+1} and the derivative P'_{2l+1} at u.
        let (mut p_even, mut p_odd) = (1.0, u);
        let mut d_odd = 1.0;
        let (mut sum_potential, mut sum_axial, mut sum_radial) = (0.0, 0.0, 0.0);
        let mut t_power = 1.0;
        for l in 0..SERIES_TERMS {
            let c = tables.coefficient[l] * t_power;
            let k = 2 * l + 1; // degree of p_odd
            sum_potential += c * p_even;
            sum_axial += c * tables.odd_degree[l] * p_odd;
            sum_radial += c * d_odd;
            // |P_n| ≤ 1 and |sinθ P'_n| ≤ n: the remaining terms are below 1e-17 of the sums.
            if c.abs() * (tables.odd_degree[l] + 1.0) < 1e-17 {
                break;
            }
            // P_{k+1} = a_k u P_k − b_k P_{k−1} twice, and P'_{k+2} = P'_k + (2k+3) P_{k+1}
            // (the sums need the odd degrees' derivatives only).
            let p_next_even = tables.rec_a[k] * u * p_odd - tables.rec_b[k] * p_even;
            let p_next_odd = tables.rec_a[k + 1] * u * p_next_even - tables.rec_b[k + 1] * p_odd;
            d_odd += tables.rec_c[k + 1] * p_next_even;
            p_even = p_next_even;
            p_odd = p_next_odd;
            t_power *= t;
        }
        let gm_over_r = self.gm / dist;
        let gm_over_r2 = gm_over_r / dist;
        Field {
            potential: -gm_over_r * sum_potential,
            acceleration: Vec3::new(
                -gm_over_r2 * (p.x / dist) * sum_radial,
                -gm_over_r2 * (p.y / dist) * sum_radial,
                -gm_over_r2 * sum_axial,
            ),
        }
    }
}

/// A near-field point's quantities before its elliptic integrals (see
/// [`UniformDisk::near_point`]): scaled coordinates, the rim offset $\delta = \rho - 1$,
/// $|z|$, $z^2$, $S\_+$, whether the point is on the rim, $k_c$, $\mathrm{sgn}(1-\rho)\sqrt{1-n}$
/// and its size, and whether $\Pi$ is needed and iterated.
#[derive(Debug, Clone, Copy)]
struct NearPoint {
    xn: Real,
    yn: Real,
    z: Real,
    rho_n: Real,
    delta: Real,
    az: Real,
    z2: Real,
    s_plus: Real,
    on_rim: bool,
    kc: Real,
    signed_snc: Real,
    snc: Real,
    needs_pi: bool,
    use_pi_track: bool,
}

/// [`NearPoint`] for [`LANES`] points side by side (see [`UniformDisk::near_lanes`]).
#[derive(Clone, Copy)]
struct NearLanes {
    xn: F4,
    yn: F4,
    z: F4,
    rho_n: F4,
    delta: F4,
    az: F4,
    z2: F4,
    s_plus: F4,
    on_rim: M4,
    kc: F4,
    signed_snc: F4,
    snc: F4,
    needs_pi: M4,
    use_pi_track: M4,
}

impl crate::lanes::Batched for UniformDisk {
    /// The fields at `points` into `out`, [`SEGMENT`] points at a time: the far points of a
    /// segment gathered into groups of [`LANES`] whose exterior series run side by side, two
    /// groups at a time ([`UniformDisk::far_field_lanes`]), and the near ones into groups whose
    /// elliptic integrals iterate side by side, also two groups at a time ([`gauss_lanes`]);
    /// each result bit for bit [`Potential::field`]'s.
    #[inline(always)]
    fn batch<T>(&self, points: &[Vec3], out: &mut [T], pick: impl Fn(Field) -> T) {
        let n = points.len().min(out.len());
        let (points, out) = (&points[..n], &mut out[..n]);
        for (segment, target) in points.chunks(SEGMENT).zip(out.chunks_mut(SEGMENT)) {
            // Indices and inputs of the far and near points, in order.
            let mut far = [[None; LANES]; SEGMENT / LANES];
            let mut far_index = [0; SEGMENT];
            // Empty near lanes hold a point on the axis (its results are discarded).
            let mut near = [Vec3::new(0.0, 0.0, self.radius); SEGMENT];
            let mut near_rho = [0.0; SEGMENT];
            let mut near_index = [0; SEGMENT];
            let (mut far_count, mut near_count) = (0, 0);
            let far_limit = FAR_FIELD_RADII * self.radius;
            for (c, chunk) in segment.chunks(LANES).enumerate() {
                // ρ and r of four points side by side (Potential::field's hypot, lane by lane).
                let coordinate = |f: fn(&Vec3) -> Real| {
                    F4::new(std::array::from_fn(|l| chunk.get(l).map_or(1.0, f)))
                };
                let rho = hypot_lanes(coordinate(|r| r.x), coordinate(|r| r.y));
                let dist = hypot_lanes(rho, coordinate(|r| r.z));
                for (l, r) in chunk.iter().enumerate() {
                    let i = c * LANES + l;
                    if dist.0[l] >= far_limit {
                        far[far_count / LANES][far_count % LANES] = Some((*r, dist.0[l]));
                        far_index[far_count] = i;
                        far_count += 1;
                    } else {
                        near[near_count] = *r;
                        near_rho[near_count] = rho.0[l];
                        near_index[near_count] = i;
                        near_count += 1;
                    }
                }
            }
            let groups = far_count.div_ceil(LANES);
            let mut g = 0;
            while g < groups {
                let fields: [[Field; LANES]; 2] = if g + 1 < groups {
                    self.far_field_lanes(&[far[g], far[g + 1]])
                } else {
                    let [one] = self.far_field_lanes(&[far[g]]);
                    [one, one]
                };
                let end = far_count.min((g + 2) * LANES);
                for (j, &i) in far_index.iter().enumerate().take(end).skip(g * LANES) {
                    target[i] = pick(fields[j / LANES - g][j % LANES]);
                }
                g += 2;
            }
            let groups = near_count.div_ceil(LANES);
            let mut g = 0;
            while g < groups {
                // Not a closure: one called twice is compiled out of line, without AVX.
                macro_rules! group {
                    ($g:expr) => {
                        self.near_lanes(
                            &std::array::from_fn(|l| near[$g * LANES + l]),
                            F4::new(std::array::from_fn(|l| near_rho[$g * LANES + l])),
                        )
                    };
                }
                let fields: [[Field; LANES]; 2] = if g + 1 < groups {
                    let (first, second) = (group!(g), group!(g + 1));
                    let [i0, i1] = gauss_lanes(
                        [first.kc, second.kc],
                        [first.snc, second.snc],
                        [first.use_pi_track, second.use_pi_track],
                    );
                    [
                        self.near_finish_lanes(&first, &i0),
                        self.near_finish_lanes(&second, &i1),
                    ]
                } else {
                    let first = group!(g);
                    let [i0] = gauss_lanes([first.kc], [first.snc], [first.use_pi_track]);
                    let one = self.near_finish_lanes(&first, &i0);
                    [one, one]
                };
                let end = near_count.min((g + 2) * LANES);
                for (j, &i) in near_index.iter().enumerate().take(end).skip(g * LANES) {
                    target[i] = pick(fields[j / LANES - g][j % LANES]);
                }
                g += 2;
            }
        }
    }
}

impl Potential for UniformDisk {
    fn as_typed(&self) -> crate::TypedPotential<'_> {
        crate::TypedPotential::Disk(self)
    }

    fn inertia(&self) -> Option<crate::InertiaTensor> {
        crate::InertiaTensor::uniform_disk(self.mass(), self.radius()).ok()
    }

    fn mass(&self) -> Real {
        self.mass
    }

    fn gravitational_constant(&self) -> Real {
        self.gravitational_constant
    }

    /// A lamina has no volume.
    fn volume(&self) -> Real {
        0.0
    }

    fn bounding_radius(&self) -> Real {
        self.radius
    }

    /// `OnSurface` on the closed lamina ($z = 0$, $\rho \le R$), `Outside` elsewhere.
    fn region(&self, r: &Vec3) -> Region {
        if r.z == 0.0 && self.relative_rim_offset(r.x, r.y, r.x.hypot(r.y)) <= 0.0 {
            Region::OnSurface
        } else {
            Region::Outside
        }
    }

    /// Four points at a time, the near ones' closed form and the far ones' series side by side
    /// (AVX where the CPU has it), each result bit for bit [`Potential::field`]'s.
    fn fields_into(&self, points: &[Vec3], out: &mut [Field]) {
        crate::lanes::fields_into(self, points, out);
    }

    /// As [`Potential::fields_into`], keeping the potentials.
    fn potentials_into(&self, points: &[Vec3], out: &mut [Real]) {
        crate::lanes::potentials_into(self, points, out);
    }

    fn field(&self, r: &Vec3) -> Field {
        let rho = hypot(r.x, r.y);
        let dist = hypot(rho, r.z);
        if dist >= FAR_FIELD_RADII * self.radius {
            self.far_field(r, dist)
        } else {
            self.near_field(r, rho)
        }
    }
}

/// $\sqrt{a^2 + b^2}$ to about one ULP: the sum of the squares and its square root, where the
/// squares neither overflow nor lose digits to underflow ($2^{-970} \le a^2 + b^2 \le$ the
/// largest double; the rounding of a square below the normal range is then below $2^{-53}$ of
/// the sum), otherwise (and for non-finite input) the library's `hypot`. The library's
/// correctly rounded `hypot` switches the rounding mode on every call, which made it the
/// largest single cost of the field.
#[inline]
fn hypot(a: Real, b: Real) -> Real {
    // 2^-970.
    const SMALLEST: Real = Real::MIN_POSITIVE * (1u64 << 52) as Real;
    let sum = a * a + b * b;
    if (SMALLEST..=Real::MAX).contains(&sum) {
        sum.sqrt()
    } else {
        a.hypot(b)
    }
}

/// Coefficients of the exterior series and of the Legendre recurrence, built once.
struct SeriesTables {
    /// $c_l = 2\binom{1/2}{l+1}$.
    coefficient: [Real; SERIES_TERMS],
    /// $2l + 1$ as a float.
    odd_degree: [Real; SERIES_TERMS],
    /// $(2k+1)/(k+1)$: $P\_{k+1} = a_k u P_k - b_k P\_{k-1}$.
    rec_a: [Real; 2 * SERIES_TERMS + 2],
    /// $k/(k+1)$.
    rec_b: [Real; 2 * SERIES_TERMS + 2],
    /// $2k + 1$: $P'\_{k+1} = P'\_{k-1} + (2k+1) P_k$.
    rec_c: [Real; 2 * SERIES_TERMS + 2],
}

fn series_tables() -> &'static SeriesTables {
    static TABLES: OnceLock<SeriesTables> = OnceLock::new();
    TABLES.get_or_init(|| {
        let mut coefficient = [0.0; SERIES_TERMS];
        let mut odd_degree = [0.0; SERIES_TERMS];
        // c_0 = 1, c_l / c_{l−1} = −(2l − 1)/(2l + 2): exact dyadic rationals, rounded once
        // each when they no longer fit (l ≥ 22).
        let (mut numerator, mut denominator) = (1u128, 1u128);
        for l in 0..SERIES_TERMS {
            if l > 0 {
                numerator *= 2 * l as u128 - 1;
                denominator *= 2 * l as u128 + 2;
                let common = gcd(numerator, denominator);
                numerator /= common;
                denominator /= common;
            }
            let sign = if l % 2 == 0 { 1.0 } else { -1.0 };
            coefficient[l] = sign * ratio_to_f64(numerator, denominator);
            odd_degree[l] = (2 * l + 1) as Real;
        }
        let mut rec_a = [0.0; 2 * SERIES_TERMS + 2];
        let mut rec_b = [0.0; 2 * SERIES_TERMS + 2];
        let mut rec_c = [0.0; 2 * SERIES_TERMS + 2];
        for k in 0..rec_a.len() {
            rec_a[k] = (2 * k + 1) as Real / (k + 1) as Real;
            rec_b[k] = k as Real / (k + 1) as Real;
            rec_c[k] = (2 * k + 1) as Real;
        }
        SeriesTables {
            coefficient,
            odd_degree,
            rec_a,
            rec_b,
            rec_c,
        }
    })
}

fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// `numerator / denominator` correctly rounded when the denominator is a power of two (it is
/// for the series coefficients) and the numerator fits in 2^113.
fn ratio_to_f64(numerator: u128, denominator: u128) -> Real {
    debug_assert!(denominator.is_power_of_two());
    let shift = denominator.trailing_zeros() as i32;
    // u128 → f64 rounds to nearest; the power-of-two scaling is exact.
    numerator as Real * (2.0 as Real).powi(-shift)
}

/// `a·b = p + e` exactly.
#[inline]
fn two_product(a: Real, b: Real) -> (Real, Real) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// [`two_product`]`(a, a)` lane by lane: $a^2$ and its rounding error. The error is exact
/// and unique, so Dekker's product (Veltkamp's split, no fused operation) gives the fused
/// multiply–add's bits wherever neither overflows nor underflows ($2^{-480} \le |a| \le
/// 2^{480}$ in every lane); elsewhere the multiply–add lane by lane.
#[inline(always)]
fn two_square_lanes(a: F4) -> (F4, F4) {
    const SPLIT: Real = 134_217_729.0; // 2^27 + 1
    const LOW: Real = 3.203_332_952_292_961_5e-145; // 2^-480
    const HIGH: Real = 3.121_748_550_315_992_2e144; // 2^480
    let p = a * a;
    let size = a.abs();
    if F4::splat(LOW).le(size).and(size.le(F4::splat(HIGH))).all() {
        let t = SPLIT * a;
        let hi = t - (t - a);
        let lo = a - hi;
        let e1 = p - hi * hi;
        let e2 = e1 - lo * hi;
        let e3 = e2 - hi * lo;
        return (p, lo * lo - e3);
    }
    (
        p,
        F4::new(std::array::from_fn(|l| a.0[l].mul_add(a.0[l], -p.0[l]))),
    )
}

/// `two_sum` lane by lane (the same six operations).
#[inline(always)]
fn two_sum_lanes(a: F4, b: F4) -> (F4, F4) {
    let sum = a + b;
    let b_virtual = sum - a;
    let a_virtual = sum - b_virtual;
    (sum, (a - a_virtual) + (b - b_virtual))
}

/// [`hypot`] lane by lane: the square root of the sum of the squares, the library's `hypot`
/// in the lanes where that sum is out of range.
#[inline(always)]
fn hypot_lanes(a: F4, b: F4) -> F4 {
    const SMALLEST: Real = Real::MIN_POSITIVE * (1u64 << 52) as Real;
    let sum = a * a + b * b;
    let in_range = F4::splat(SMALLEST)
        .le(sum)
        .and(sum.le(F4::splat(Real::MAX)));
    let root = sum.sqrt();
    if in_range.all() {
        return root;
    }
    let in_range = in_range.flags();
    F4::new(std::array::from_fn(|l| {
        if in_range[l] {
            root.0[l]
        } else {
            a.0[l].hypot(b.0[l])
        }
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points for the batched field: near the rim (offsets from 1e-16 to 0.3 radii inside and
    /// outside, heights from 0 to 1e-10 and 0.5 radii, both sides), on the axis, in the plane
    /// inside and outside, on the lamina, exactly on the rim, at the far-field switch and
    /// beyond it, far away, and non-finite points; shuffled so that each group of four
    /// mixes near, far and special lanes.
    fn batch_points(radius: f64) -> Vec<Vec3> {
        let mut points = Vec::new();
        let mut state = 3u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for offset in [0.0, 1e-16, 1e-12, 1e-8, 1e-4, 1e-2, 0.3] {
            for sign in [-1.0, 1.0] {
                for height in [0.0, 1e-300, 1e-10, 1e-3, 0.5, -0.5, -1e-10] {
                    let phi = std::f64::consts::TAU * next();
                    let s = radius * (1.0 + sign * offset);
                    points.push(Vec3::new(s * phi.cos(), s * phi.sin(), height * radius));
                }
            }
        }
        for z in [0.0, 1e-12, 0.3, 1.0, 1.99, 2.0, 5.0, -0.7] {
            points.push(Vec3::new(0.0, 0.0, z * radius));
        }
        for s in [0.0, 0.2, 0.7, 0.999, 1.3, 1.99, 2.0, 2.5, 10.0] {
            points.push(Vec3::new(0.6 * s * radius, -0.8 * s * radius, 0.0));
        }
        points.push(Vec3::new(radius, 0.0, 0.0));
        points.push(Vec3::new(0.0, -radius, 0.0));
        for _ in 0..400 {
            // Spread over 0.01 to 30 radii, in every direction.
            let r = radius * 10f64.powf(-2.0 + 3.5 * next());
            let z = 2.0 * next() - 1.0;
            let phi = std::f64::consts::TAU * next();
            let s = (1.0 - z * z).sqrt();
            points.push(Vec3::new(s * phi.cos(), s * phi.sin(), z) * r);
        }
        points.push(Vec3::new(1e8, -3e7, 2e7) * radius);
        points.push(Vec3::new(f64::NAN, 0.1, 0.2));
        points.push(Vec3::new(0.3, f64::INFINITY, 0.0));
        points.push(Vec3::new(0.3, 0.2, f64::NEG_INFINITY));
        for k in (1..points.len()).rev() {
            let j = (next() * (k + 1) as f64) as usize;
            points.swap(k, j.min(k));
        }
        points
    }

    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    /// The batched field (both compilations) is the point-by-point field bit for bit, at every
    /// batch length (so every position in a group of four and every remainder).
    #[test]
    fn batched_field_is_the_scalar_field_bit_for_bit() {
        for radius in [1.0, 3.7e3] {
            let disk = UniformDisk::new(radius, 2.5).unwrap();
            let points = batch_points(radius);
            let want: Vec<Field> = points.iter().map(|r| disk.field(r)).collect();
            for start in 0..4 {
                let points = &points[start..];
                let want = &want[start..];
                let blank = Field {
                    potential: 0.0,
                    acceleration: Vec3::zeros(),
                };
                let mut runs = Vec::new();
                let mut out = vec![blank; points.len()];
                disk.fields_into(points, &mut out);
                runs.push(("fields_into", out.clone()));
                crate::lanes::fields_plain(&disk, points, &mut out);
                runs.push(("fields_plain", out.clone()));
                let mut potentials = vec![0.0; points.len()];
                disk.potentials_into(points, &mut potentials);
                for (name, got) in &runs {
                    for ((r, g), w) in points.iter().zip(got).zip(want) {
                        let equal = same(g.potential, w.potential)
                            && (0..3).all(|i| same(g.acceleration[i], w.acceleration[i]));
                        assert!(equal, "{name} at {r:?}: {g:?} vs {w:?}");
                    }
                }
                for ((r, &g), w) in points.iter().zip(&potentials).zip(want) {
                    assert!(same(g, w.potential), "potentials_into at {r:?}");
                }
            }
        }
    }

    /// Lanes where a square sum of `hypot` leaves the normal range (heights of 1e-300 radii
    /// over the rim circle, where √(δ² + z²) underflows; a point at 1e200 radii, where ρ² + z²
    /// overflows) beside ordinary lanes: the batch is still the point-by-point field bit for bit
    /// (the library's `hypot` in those lanes only).
    #[test]
    fn batched_field_takes_the_library_hypot_lane_by_lane() {
        let disk = UniformDisk::new(1.0, 2.5).unwrap();
        let mut points = Vec::new();
        for k in 0..6 {
            let h = [1e-300, 3e-170, 1e-250, -1e-300, 2e-160, 0.0][k];
            points.push(Vec3::new(1.0, 0.0, h));
            points.push(Vec3::new(0.3 + 0.1 * k as f64, -0.4, 0.05));
            points.push(Vec3::new(0.0, -1.0, -h));
        }
        points.push(Vec3::new(1e200, 3e199, -2e199));
        points.push(Vec3::new(0.9, 0.1, 0.02));
        // On the rim at a height of 1e-300 the fallback is what tells the point from the rim.
        let scalar = disk.field(&points[0]);
        assert!(scalar.acceleration.x.is_finite(), "{scalar:?}");
        let mut out = vec![scalar; points.len()];
        disk.fields_into(&points, &mut out);
        for (r, got) in points.iter().zip(&out) {
            let want = disk.field(r);
            let equal = same(got.potential, want.potential)
                && (0..3).all(|i| same(got.acceleration[i], want.acceleration[i]));
            assert!(equal, "at {r:?}: {got:?} vs {want:?}");
        }
    }

    /// Dekker's square is the fused multiply–add's error bit for bit, inside its range and at
    /// its ends, and the multiply–add itself is taken outside it.
    #[test]
    fn lane_square_error_is_the_fused_one() {
        let mut state = 11u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut values = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            2f64.powi(-480),
            2f64.powi(480),
            -2f64.powi(480) * (1.0 - f64::EPSILON),
            2f64.powi(-481),
            1e-300,
            1e300,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            f64::INFINITY,
            f64::NAN,
        ];
        for _ in 0..4000 {
            let scale = 10f64.powf(-150.0 + 300.0 * next());
            values.push((2.0 * next() - 1.0) * scale);
            values.push(1.0 + (2.0 * next() - 1.0) * 1e-8);
        }
        for chunk in values.chunks(LANES) {
            let a = F4::new(std::array::from_fn(|l| {
                chunk.get(l).copied().unwrap_or(0.5)
            }));
            let (p, e) = two_square_lanes(a);
            for l in 0..LANES {
                let (want_p, want_e) = two_product(a.0[l], a.0[l]);
                assert!(
                    same(p.0[l], want_p) && same(e.0[l], want_e),
                    "{:e}: {:e} {:e} vs {want_p:e} {want_e:e}",
                    a.0[l],
                    p.0[l],
                    e.0[l]
                );
            }
        }
    }

    #[test]
    fn series_coefficients_are_the_binomial_ones() {
        let c = &series_tables().coefficient;
        assert_eq!(&c[..5], &[1.0, -0.25, 0.125, -5.0 / 64.0, 7.0 / 128.0]);
        // c_l = 2 binom(1/2, l+1), by the float recurrence (a few ULP).
        let mut b = 0.5;
        for (l, &cl) in c.iter().enumerate() {
            b *= (0.5 - (l + 1) as f64) / (l + 2) as f64;
            if l + 1 < c.len() {
                let want = 2.0 * b;
                let got = c[l + 1];
                assert!(
                    ((got - want) / want).abs() < 1e-14,
                    "c_{} = {got} vs {want}",
                    l + 1
                );
            }
            assert!(cl.is_finite() && cl != 0.0);
        }
    }

    #[test]
    fn rim_offset_is_exact_for_offsets_far_below_one_ulp_of_rho() {
        let disk = UniformDisk::new(3.0, 1.0).unwrap();
        // A point whose x² + y² − R² is exactly 2⁻⁵⁰ (x = 3 − tiny is not representable, so
        // build it from a Pythagorean triple scaled into 3).
        let (x, y) = (1.8_f64, 2.4_f64); // 1.8² + 2.4² = 9 in reals; in doubles off by a few ULP.
        let rho = x.hypot(y);
        let got = disk.relative_rim_offset(x, y, rho);
        // Reference in exact rational arithmetic on the doubles' values.
        let exact = exact_offset(x, y, 3.0);
        assert!(exact != 0.0, "the test point must be off the rim");
        assert!(
            ((got - exact) / exact).abs() < 1e-15,
            "offset {got:e} vs exact {exact:e}"
        );
    }

    /// The fast [`hypot`] against the library's correctly rounded one over pairs spanning
    /// $10^{-310}$ to $10^{300}$, with zeros, infinities and NaN. Bound: two ULP of the result:
    /// the squares and their sum round three times (1.5 ULP of the sum), the square root halves
    /// that and rounds once more (1.25 ULP), the library is within half an ULP of the truth.
    #[test]
    fn fast_hypot_is_within_two_ulp_of_the_library() {
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut values = vec![0.0, -0.0, 1.0, f64::MIN_POSITIVE, 5e-324, f64::MAX];
        for _ in 0..20000 {
            let exponent = -310.0 + 610.0 * next();
            let sign = if next() < 0.5 { -1.0 } else { 1.0 };
            values.push(sign * (1.0 + next()) * 10f64.powf(exponent));
        }
        for pair in values.windows(2) {
            for (a, b) in [
                (pair[0], pair[1]),
                (pair[0], pair[0] * 1e-3),
                (pair[0], 0.0),
            ] {
                let (got, want) = (hypot(a, b), a.hypot(b));
                let ulp = want * f64::EPSILON;
                assert!(
                    got == want || (got - want).abs() <= 2.0 * ulp,
                    "hypot({a:e}, {b:e}) = {got:e}, library {want:e}"
                );
            }
        }
        assert_eq!(hypot(f64::INFINITY, f64::NAN), f64::INFINITY);
        assert!(hypot(f64::NAN, 1.0).is_nan());
        assert_eq!(hypot(-f64::INFINITY, 1.0), f64::INFINITY);
        assert_eq!(hypot(1e300, 1e300), 1e300 * 2f64.sqrt());
    }

    /// (√(x²+y²) − R)/R ≈ (x² + y² − R²)/(2R²) to first order, with x², y², R² summed exactly as
    /// i128 multiples of 2^-104 (the inputs have ≤ 52 fractional bits here).
    fn exact_offset(x: f64, y: f64, r: f64) -> f64 {
        let scale = 2f64.powi(52);
        let (xi, yi, ri) = (
            (x * scale) as i128,
            (y * scale) as i128,
            (r * scale) as i128,
        );
        assert_eq!(xi as f64 / scale, x);
        assert_eq!(yi as f64 / scale, y);
        let excess = xi * xi + yi * yi - ri * ri; // in units of 2^-104
        let e = excess as f64 / (scale * scale);
        // ρ − R = e/(ρ + R) with ρ + R = 2R to relative e/R², far below 1e-15 here.
        e / (2.0 * r) / r
    }
}
