//! Test helpers: small quadrature rules, a deterministic random generator, and references
//! computed independently of the node tables.
//!
//! Gauss–Legendre comes from `surfgrav-quadrature`, whose nodes and weights are tested against
//! mpmath there.

#![allow(dead_code)]

use nalgebra::{Rotation3, Vector3};
use std::f64::consts::PI;
use surfgrav_quadrature::{GaussLegendre, Rule1D};
use surfgrav_surfaces::{BorrowedRule, Interval};

/// The workspace tolerance policy.
#[allow(unused_imports)]
pub use surfgrav_potentials::tolerance;

pub type Vec3 = Vector3<f64>;

/// An owned 1-D rule with its interval.
#[derive(Debug, Clone)]
pub struct OwnedRule {
    pub nodes: Vec<f64>,
    pub weights: Vec<f64>,
    pub interval: Interval,
}

impl OwnedRule {
    pub fn rule(&self) -> BorrowedRule<'_> {
        BorrowedRule::new(&self.nodes, &self.weights, self.interval).expect("valid test rule")
    }
}

/// Gauss–Legendre on [-1, 1], from the quadrature crate (tested there against mpmath).
pub fn gauss_legendre(n: usize) -> OwnedRule {
    let rule = GaussLegendre::standard(n).expect("a valid order");
    OwnedRule {
        nodes: rule.nodes().to_vec(),
        weights: rule.weights().to_vec(),
        interval: Interval::SYMMETRIC_UNIT,
    }
}

/// The periodic trapezoid rule on [0, 1]: nodes i/N, weights 1/N (end point left out).
pub fn trapezoid(n: usize) -> OwnedRule {
    OwnedRule {
        nodes: (0..n).map(|i| i as f64 / n as f64).collect(),
        weights: vec![1.0 / n as f64; n],
        interval: Interval::UNIT,
    }
}

/// splitmix64: a deterministic generator for "random" shapes and points.
pub struct SplitMix(pub u64);

impl SplitMix {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }

    /// A uniformly distributed unit vector.
    pub fn unit_vector(&mut self) -> Vec3 {
        let z = self.uniform(-1.0, 1.0);
        let phi = self.uniform(0.0, 2.0 * PI);
        let s = (1.0 - z * z).sqrt();
        Vec3::new(s * phi.cos(), s * phi.sin(), z)
    }

    /// A random rotation (random axis, angle in [0, π)).
    pub fn rotation(&mut self) -> Rotation3<f64> {
        let axis = self.unit_vector();
        Rotation3::from_scaled_axis(axis * self.uniform(0.0, PI))
    }
}

/// Confocal parameter λ ≥ 0 of an exterior point: Σ x_i²/(a_i² + λ) = 1, by bisection.
pub fn confocal_lambda(semi_axes: &Vec3, r0: &Vec3) -> f64 {
    let f = |lambda: f64| -> f64 {
        (0..3)
            .map(|i| r0[i] * r0[i] / (semi_axes[i] * semi_axes[i] + lambda))
            .sum::<f64>()
            - 1.0
    };
    assert!(f(0.0) > 0.0, "reference needs an exterior point");
    let (mut lo, mut hi) = (0.0, r0.norm_squared());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// ∮ dS / |r − r0| over the ellipsoid with `semi_axes`, for an exterior point r0: equal to
/// −∇_{r0} ∫ dV/|r − r0| = 2π abc x0_i ∫_λ^∞ du / ((a_i² + u) Δ(u)), Δ = √Π(a_j² + u) (the
/// classical exterior attraction of a homogeneous ellipsoid divided by −Gρ). The 1-D integral is
/// done by Gauss–Legendre in t after u = λ + L(1/t² − 1), L = min_j a_j² + λ, which makes the
/// integrand 2L t² / ((L + α_i t²) √Π(L + α_j t²)) with α_j = a_j² + λ − L ≥ 0: analytic on [0, 1].
/// Independent of the surface parametrisations and of Carlson's functions.
pub fn inverse_distance_flux(semi_axes: &Vec3, r0: &Vec3, n: usize) -> Vec3 {
    let lambda = confocal_lambda(semi_axes, r0);
    let sq = semi_axes.map(|a| a * a);
    let l = sq.min() + lambda;
    let alpha = sq.map(|s| (s + lambda - l).max(0.0));
    let gl = gauss_legendre(n);
    let mut integral = Vec3::zeros();
    for (&x, &w) in gl.nodes.iter().zip(&gl.weights) {
        let t = 0.5 * (x + 1.0);
        let t2 = t * t;
        let root = alpha.iter().map(|a| l + a * t2).product::<f64>().sqrt();
        for i in 0..3 {
            integral[i] += 0.5 * w * 2.0 * l * t2 / ((l + alpha[i] * t2) * root);
        }
    }
    let abc = semi_axes.product();
    r0.component_mul(&integral) * (2.0 * PI * abc)
}

/// ∫ f dV over the ellipsoid, by r = t (a sinθ cosφ, b sinθ sinφ, c cosθ), dV = abc t² sinθ:
/// Gauss–Legendre in t and θ, trapezoid in φ. Independent of the surface tables.
pub fn volume_integral<T, F>(
    semi_axes: &Vec3,
    n_radial: usize,
    n_polar: usize,
    n_azimuth: usize,
    mut f: F,
) -> T
where
    T: std::ops::Add<Output = T> + std::ops::Mul<f64, Output = T> + Default,
    F: FnMut(&Vec3) -> T,
{
    let radial = gauss_legendre(n_radial);
    let polar = gauss_legendre(n_polar);
    let abc = semi_axes.product();
    let mut total = T::default();
    for (&xt, &wt) in radial.nodes.iter().zip(&radial.weights) {
        let t = 0.5 * (xt + 1.0);
        for (&xp, &wp) in polar.nodes.iter().zip(&polar.weights) {
            let theta = 0.5 * PI * (xp + 1.0);
            let (st, ct) = theta.sin_cos();
            for k in 0..n_azimuth {
                let phi = 2.0 * PI * k as f64 / n_azimuth as f64;
                let (sp, cp) = phi.sin_cos();
                let r = Vec3::new(
                    semi_axes[0] * st * cp,
                    semi_axes[1] * st * sp,
                    semi_axes[2] * ct,
                ) * t;
                let weight =
                    0.5 * wt * 0.5 * PI * wp * 2.0 * PI / n_azimuth as f64 * abc * t * t * st;
                total = total + f(&r) * weight;
            }
        }
    }
    total
}

/// Potential of a point mass (G M = `mu`) at `p`: −μ/|r − p|.
pub fn point_mass_potential(mu: f64, p: &Vec3, r: &Vec3) -> f64 {
    -mu / (r - p).norm()
}

/// Acceleration of a point mass at `p`: −μ (r − p)/|r − p|³.
pub fn point_mass_acceleration(mu: f64, p: &Vec3, r: &Vec3) -> Vec3 {
    let d = r - p;
    let n = d.norm();
    -d * (mu / (n * n * n))
}

/// |a − b| / |b| for vectors.
pub fn rel_vec(a: &Vec3, b: &Vec3) -> f64 {
    (a - b).norm() / b.norm()
}

/// |a − b| / |b|.
pub fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}
