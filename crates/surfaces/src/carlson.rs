//! Carlson's symmetric elliptic integrals $R_F$, $R_D$, $R_G$, for the surface area of a
//! triaxial ellipsoid (private; the potentials crate has its own, this crate does not depend on it).
//!
//! Duplication algorithm (B. C. Carlson, Numer. Algorithms 10 (1995) 13–26; DLMF §19.36(i)):
//! the arguments are replaced by $(x + \lambda)/4$, … with
//! $\lambda = \sqrt{x}\sqrt{y} + \sqrt{y}\sqrt{z} + \sqrt{z}\sqrt{x}$ until they agree to
//! $\epsilon^{1/6}$, then a fifth-order Taylor series closes the sum (error below
//! $\epsilon$). Arguments must be non-negative and finite, at most one of them zero.

use crate::Real;

/// Safeguard on the number of duplication steps. Each step divides the spread of the arguments by
/// 4 while their mean tends to a positive limit, so the stopping test is met within a few tens of
/// steps for any finite positive arguments; the cap only keeps a NaN from looping.
const MAX_STEPS: usize = 200;

/// $R_F(x, y, z) = \tfrac12 \int_0^\infty [(t+x)(t+y)(t+z)]^{-1/2}\\,\mathrm dt$.
pub(crate) fn rf(x: Real, y: Real, z: Real) -> Real {
    let (x0, y0) = (x, y);
    let (mut x, mut y, mut z) = (x, y, z);
    let a0 = (x + y + z) / 3.0;
    let mut a = a0;
    // (3ε)^{-1/6} · max |A₀ − arg|
    let q = (3.0 * Real::EPSILON).powf(-1.0 / 6.0)
        * (a0 - x).abs().max((a0 - y).abs()).max((a0 - z).abs());
    let mut scale = 1.0; // 4^{-n}
    for _ in 0..MAX_STEPS {
        if q * scale < a.abs() {
            break;
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        a = 0.25 * (a + lambda);
        scale *= 0.25;
    }
    let big_x = (a0 - x0) * scale / a;
    let big_y = (a0 - y0) * scale / a;
    let big_z = -(big_x + big_y);
    let e2 = big_x * big_y - big_z * big_z;
    let e3 = big_x * big_y * big_z;
    (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / a.sqrt()
}

/// $R_D(x, y, z) = \tfrac32 \int_0^\infty [(t+x)(t+y)]^{-1/2}(t+z)^{-3/2}\\,\mathrm dt$.
pub(crate) fn rd(x: Real, y: Real, z: Real) -> Real {
    let (x0, y0) = (x, y);
    let (mut x, mut y, mut z) = (x, y, z);
    let a0 = (x + y + 3.0 * z) / 5.0;
    let mut a = a0;
    let q = (0.25 * Real::EPSILON).powf(-1.0 / 6.0)
        * (a0 - x).abs().max((a0 - y).abs()).max((a0 - z).abs());
    let mut scale = 1.0; // 4^{-m}
    let mut sum = 0.0;
    for _ in 0..MAX_STEPS {
        if q * scale < a.abs() {
            break;
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        sum += scale / (sz * (z + lambda));
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        a = 0.25 * (a + lambda);
        scale *= 0.25;
    }
    let big_x = (a0 - x0) * scale / a;
    let big_y = (a0 - y0) * scale / a;
    let big_z = -(big_x + big_y) / 3.0;
    let xy = big_x * big_y;
    let z2 = big_z * big_z;
    let e2 = xy - 6.0 * z2;
    let e3 = (3.0 * xy - 8.0 * z2) * big_z;
    let e4 = 3.0 * (xy - z2) * z2;
    let e5 = xy * z2 * big_z;
    let series = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0
        - 3.0 * e4 / 22.0
        - 9.0 * e2 * e3 / 52.0
        + 3.0 * e5 / 26.0;
    scale * series / (a * a.sqrt()) + 3.0 * sum
}

/// $R_G(x, y, z) = \tfrac{1}{4\pi}\int\_{S^2} \sqrt{x n_1^2 + y n_2^2 + z n_3^2}\\,\mathrm d\Omega$,
/// by DLMF 19.21.10 with the middle argument in the role of $z$ so that $(x - z)(y - z) \le 0$
/// and no cancellation occurs. Requires positive arguments.
pub(crate) fn rg(x: Real, y: Real, z: Real) -> Real {
    let mut v = [x, y, z];
    v.sort_by(|p, q| p.total_cmp(q));
    let (x, z, y) = (v[0], v[1], v[2]);
    0.5 * (z * rf(x, y, z) - (x - z) * (y - z) * rd(x, y, z) / 3.0 + (x * y / z).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    use crate::tolerance::POTENTIAL_REL;

    fn rel(a: Real, b: Real) -> Real {
        ((a - b) / b).abs()
    }

    #[test]
    fn closed_forms() {
        // R_F(x, x, x) = x^{-1/2}, R_D(x, x, x) = x^{-3/2}, R_G(x, x, x) = x^{1/2}.
        for x in [1e-6, 0.3, 1.0, 7.0, 1e8] {
            assert!(rel(rf(x, x, x), 1.0 / x.sqrt()) < POTENTIAL_REL);
            assert!(rel(rd(x, x, x), x.powf(-1.5)) < POTENTIAL_REL);
            assert!(rel(rg(x, x, x), x.sqrt()) < POTENTIAL_REL);
        }
        // R_F(0, y, y) = π/(2√y); R_F(0, 1, 2) = K(m = 1/2)/√2 = 1.3110287771460599 (DLMF 19.20.2
        // and homogeneity).
        assert!(rel(rf(0.0, 1.0, 1.0), PI / 2.0) < POTENTIAL_REL);
        assert!(rel(rf(0.0, 1.0, 2.0), 1.311_028_777_146_059_9) < POTENTIAL_REL);
        // R_D(0, y, y) = 3π/(4 y^{3/2}) (DLMF 19.20.19).
        assert!(rel(rd(0.0, 1.0, 1.0), 0.75 * PI) < POTENTIAL_REL);
        // R_G(0, y, y) = (π/4)√y (DLMF 19.20.4).
        assert!(rel(rg(0.0, 1.0, 1.0), PI / 4.0) < POTENTIAL_REL);
    }
}
