//! A singular circle seen from the disk's rows: the exact angular singularities of each row
//! ([`CircleRows`], two pairs from a quadratic in $e^{i\varphi}$) and the radii where two of
//! them pinch the row integral's contour ([`circle_pinches`]), from which the aimed lamina
//! rule plans its angular table and its radial sides (module docs of [`super`]).

use crate::kernel::FrameMap;
use nalgebra::Complex;
use surfgrav_surfaces::Real;

/// Y's singular set where it is a circle of radius $c$ (a disk's rim, an oblate spheroid's
/// focal circle) in Y's x–y plane about Y's centroid, seen from the circles $s$ = const of
/// X's plane: the exact angular singularities of each row's integrand.
///
/// With $\mathbf d(\varphi) = M(s\cos\varphi, s\sin\varphi, 0)^{\mathsf T} + \mathbf t$ (`map`:
/// X's frame into Y's), the continued field is singular where
/// $(\mathbf d\cdot\mathbf d - c^2)^2 + 4c^2d_z^2 = 0$, that is where
/// $\mathbf d\cdot\mathbf d - c^2 + 2icd_z = 0$ or its conjugate. The columns of $M$ being
/// orthonormal, $\mathbf d\cdot\mathbf d$ is linear in $\cos\varphi$ and $\sin\varphi$, so the
/// first factor is $\alpha + \beta\cos\varphi + \gamma\sin\varphi = 0$ with
/// $\alpha = s^2 + \mathbf t\cdot\mathbf t - c^2 + 2ict_z$, $\beta = s\beta_1$, $\gamma = s\gamma_1$
/// ($\beta_1 = 2\mathbf m_1\cdot\mathbf t + 2icm\_{1z}$, $\gamma_1$ likewise with the second
/// column $\mathbf m_2$): a quadratic in $w = e^{i\varphi}$,
/// $(\beta - i\gamma)w^2 + 2\alpha w + (\beta + i\gamma) = 0$, with
/// $\varphi = \arg w - i\ln|w|$; the other factor gives the conjugates. So each row has two
/// singular pairs $\operatorname{Re}\varphi_j \pm i|\operatorname{Im}\varphi_j|$: where the
/// curve runs near the disk along a stretch, these two, not one per point of the stretch;
/// where it crosses X's plane twice, one pair near each crossing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CircleRows {
    /// $\mathbf t\cdot\mathbf t - c^2 + 2ict_z$.
    pub(super) alpha0: Complex<Real>,
    /// $\beta_1 - i\gamma_1$ and $\beta_1 + i\gamma_1$.
    pub(super) lead: Complex<Real>,
    pub(super) trail: Complex<Real>,
}

/// A row singularity: the unit phasor $(\cos\varphi_j, \sin\varphi_j)$ of its azimuth and
/// its width $|\operatorname{Im}\varphi_j|$ (at most [`NO_SINGULARITY`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RowSingularity {
    pub(crate) cos: Real,
    pub(crate) sin: Real,
    pub(crate) width: Real,
}

impl RowSingularity {
    /// No singularity near the row (a degenerate quadratic).
    pub(super) const NONE: Self = Self {
        cos: 1.0,
        sin: 0.0,
        width: NO_SINGULARITY,
    };

    pub(crate) fn azimuth(&self) -> Real {
        self.sin.atan2(self.cos)
    }

    /// The angle between this singularity's azimuth and `centre`'s, in $[0, \pi]$ (the
    /// offset on a half-range clustered toward `centre`).
    pub(super) fn offset_from(&self, centre: &Self) -> Real {
        (centre.cos * self.sin - centre.sin * self.cos)
            .atan2(centre.cos * self.cos + centre.sin * self.sin)
            .abs()
    }
}

/// The principal square root by real square roots (the library's goes through the polar
/// form: an `atan2`, a `hypot` and a `sin_cos`).
pub(super) fn principal_sqrt(z: Complex<Real>) -> Complex<Real> {
    let r = (z.re * z.re + z.im * z.im).sqrt();
    let re = (0.5 * (r + z.re)).max(0.0).sqrt();
    let im = (0.5 * (r - z.re)).max(0.0).sqrt().copysign(z.im);
    Complex::new(re, im)
}

/// The width standing for no singularity near the row ([`RowSingularity::NONE`]).
pub(super) const NO_SINGULARITY: Real = 10.0;

impl CircleRows {
    pub(crate) fn new(c: Real, map: &FrameMap) -> Self {
        let (m1, m2, t) = (map.rotation.column(0), map.rotation.column(1), &map.offset);
        let i = Complex::new(0.0, 1.0);
        let beta = Complex::new(2.0 * m1.dot(t), 2.0 * c * m1.z);
        let gamma = Complex::new(2.0 * m2.dot(t), 2.0 * c * m2.z);
        Self {
            alpha0: Complex::new(t.dot(t) - c * c, 2.0 * c * t.z),
            lead: beta - i * gamma,
            trail: beta + i * gamma,
        }
    }

    /// The row of radius `s`: its two singularities, the narrower first.
    pub(crate) fn at(&self, s: Real) -> [RowSingularity; 2] {
        let none = RowSingularity::NONE;
        // w = e^{iφ}: the phasor w/|w| and the width |ln|w||.
        let of_w = |w: Complex<Real>| {
            let squared = w.re * w.re + w.im * w.im;
            if squared > 0.0 && squared.is_finite() {
                let modulus = squared.sqrt();
                RowSingularity {
                    cos: w.re / modulus,
                    sin: w.im / modulus,
                    width: (0.5 * squared.ln()).abs().min(NO_SINGULARITY),
                }
            } else {
                none
            }
        };
        let size = |z: Complex<Real>| z.re.abs() + z.im.abs();
        // a w² + 2 b w + c = 0.
        let (a, b, c) = (self.lead * s, self.alpha0 + s * s, self.trail * s);
        let scale = size(a) + size(b) + size(c);
        // Not positive, or NaN (a non-finite map is refused before the plan).
        let roots = if scale.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            [none, none]
        } else if size(a) <= 1e-14 * scale {
            // Linear (Y's circle about X's axis, or the centre row): w = −c/(2b).
            [
                if size(b) > 0.0 {
                    of_w(-c / (2.0 * b))
                } else {
                    none
                },
                none,
            ]
        } else {
            // (−b ± √(b² − ac))/a: the larger root without cancellation, the other from
            // their product c/a.
            let root = principal_sqrt(b * b - a * c);
            let big = if (b.conj() * root).re >= 0.0 {
                -(b + root)
            } else {
                -(b - root)
            };
            if size(big) > 0.0 {
                [of_w(big / a), of_w(c / big)]
            } else {
                [none, none]
            }
        };
        if roots[1].width < roots[0].width {
            [roots[1], roots[0]]
        } else {
            roots
        }
    }
}

/// The radii $s$ (complex) where the row integral over a singular circle of radius `c` is
/// singular: where two of a row's angular singularities ([`CircleRows`]) meet and pinch the
/// row's contour. A single singularity crossing the real angle does not make the row integral
/// singular (the contour moves around it); two meeting from either side do. They meet where
/// the quadratic of one factor has a double root (its discriminant vanishes: with
/// $\sigma = s^2$, $(\alpha_0 + \sigma)^2 = \sigma(\beta_1 - i\gamma_1)(\beta_1 + i\gamma_1)$),
/// or where a root of one factor meets one of the other (a point of the circle itself in X's
/// plane, continued: X's plane meets Y's, $m\_{1z}x + m\_{2z}y + t_z = 0$, on the circle
/// $x^2 + y^2 + 2x\\,\mathbf m_1\cdot\mathbf t + 2y\\,\mathbf m_2\cdot\mathbf t + \mathbf t\cdot\mathbf t = c^2$).
/// Each as $\pm\sqrt{\sigma}$; returns the radii and their count (at most 8).
pub(super) fn circle_pinches(
    c: Real,
    rows: &CircleRows,
    map: &FrameMap,
) -> ([Complex<Real>; 8], usize) {
    let mut out = [Complex::new(0.0, 0.0); 8];
    let mut len = 0;
    let mut push = |sigma: Complex<Real>| {
        if sigma.re.is_finite() && sigma.im.is_finite() {
            let root = principal_sqrt(sigma);
            out[len] = root;
            out[len + 1] = -root;
            len += 2;
        }
    };
    // σ² + (2α₀ − lead·trail)σ + α₀² = 0.
    let (a0, product) = (rows.alpha0, rows.lead * rows.trail);
    let half = a0 - 0.5 * product;
    let root = principal_sqrt(half * half - a0 * a0);
    push(-half + root);
    push(-half - root);
    // The line of the two planes and the circle: x = p₀ + λ n⊥, |p₀| along the line's normal.
    let (m1, m2, t) = (map.rotation.column(0), map.rotation.column(1), &map.offset);
    let normal = nalgebra::Vector2::new(m1.z, m2.z);
    let norm = normal.norm();
    if norm > 1e-12 {
        let n = normal / norm;
        let along = nalgebra::Vector2::new(-n.y, n.x);
        let p0 = -t.z / norm * n;
        let g = nalgebra::Vector2::new(m1.dot(t), m2.dot(t));
        // λ² + 2λ g·n⊥ + (|p₀|² + 2 g·p₀ + t·t − c²) = 0.
        let b = g.dot(&along);
        let constant = p0.norm_squared() + 2.0 * g.dot(&p0) + t.dot(t) - c * c;
        let disc = principal_sqrt(Complex::new(b * b - constant, 0.0));
        for lambda in [-b + disc, -b - disc] {
            push(lambda * lambda + p0.norm_squared());
        }
    }
    (out, len)
}
