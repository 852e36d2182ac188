//! Two coplanar, non-coaxial uniform disks: the mutual potential energy and the force in closed
//! form (Conway 2016, eqs. 151–152; quoted in the founding paper, section "Tests for two coplanar
//! disks").
//!
//! # Formulas
//!
//! Disks A and B (radii $R_A$, $R_B$, masses $m_A$, $m_B$) lie in one plane with their centres a
//! distance $r \ge R_A + R_B$ apart. With $\alpha = R_A/r$, $\beta = R_B/r$ and
//!
//! $$k\_\pm^2 = \frac{1 \pm (\alpha^2 - \beta^2) - \sqrt{\mathcal D}}{2},\qquad
//! \mathcal D = \big(1 - (\alpha+\beta)^2\big)\big(1 - (\alpha-\beta)^2\big),$$
//!
//! the mutual potential energy and the radial force on B (along the unit vector from A to B) are
//!
//! $$V = -\frac{G m_A m_B}{r}\\,u,\qquad F = -\frac{\mathrm dV}{\mathrm dr}
//!   = -\frac{G m_A m_B}{r^2}\\,f,$$
//!
//! both shape factors tending to 1 far away ($u = 1 + (R_A^2 + R_B^2)/(8r^2) + \dots$): $V < 0$,
//! $F < 0$ (attraction). The paper prints $u$ correctly (its $U = -V$) but $f$ with the wrong
//! sign: its expression tends to $-1$. The correct one is minus the printed one,
//!
//! $$f = \frac{8}{\pi^2 k\_{c+}^2 k\_{c-}^2}\Big[\tfrac13 \big(B\_+ + 2k\_{c+}^2 D\_+\big)
//!   \big(B\_- + 2k\_{c-}^2 D\_-\big) - B\_+ B\_-\Big],$$
//!
//! with $K\_\pm = K(k\_\pm^2)$ etc. (parameter convention, see [`crate::elliptic`]) and
//! $k\_{c\pm}^2 = 1 - k\_\pm^2$; $f = u - r\\,\mathrm du/\mathrm dr$, which the tests check.
//!
//! # Numerics
//!
//! Written in $K, E$ the printed $u$ loses digits as $(r/R)^2$ (1e-13 at $r = 30R$, 1e-10 at
//! $r = 1000R$), and both factors lose $\ln(R_A/R_B)$ near contact when the radii differ. We use
//! instead the subtraction-free integrals $B, C, D$ and $D - C$ of [`crate::elliptic`], the
//! identities $k\_+^2 k\_{c-}^2 = \alpha^2$, $k\_-^2 k\_{c+}^2 = \beta^2$, and rearrangements in which
//! only small terms are subtracted (A is the larger disk; $u$ and $f$ are symmetric in A, B):
//!
//! $$\tfrac{\pi^2}{4}u = 2B\_+K\_- - \frac{2k\_+^2k\_-^2 B\_- C\_+}{k\_{c-}^2} -
//!   \xi^2 (1 + k\_+^2) B\_+ C\_- - k\_-^2 D\_+ C\_- +
//!   \frac{k\_+^2 \xi^2}{9 k\_{c-}^2}\big(k\_{c+}^2 C\_+ + 2B\_+\big)\big(k\_{c-}^2 C\_- + 2B\_-\big),$$
//! $$\tfrac{3\pi^2}{16}f = \frac{D\_+ B\_-}{k\_{c-}^2} + 2D\_+D\_- - \xi^2 B\_+\frac{D\_- - C\_-}{k\_{c-}^2},
//!   \qquad \xi^2 = \frac{k\_-^2}{k\_{c+}^2} = \frac{\beta^2}{k\_{c+}^4}.$$
//!
//! The moduli come without cancellation from the gap $g = r - R_A - R_B$:
//! $k\_+^2 = 2\alpha^2 / (1 + \alpha^2 - \beta^2 + \sqrt{\mathcal D})$,
//! $k\_-^2 = 2\beta^2 / (1 - \alpha^2 + \beta^2 + \sqrt{\mathcal D})$,
//! $k\_{c\pm}^2 = (1 \mp (\alpha^2 - \beta^2) + \sqrt{\mathcal D})/2$,
//! $\mathcal D = \frac{g}{r}(1 + \alpha + \beta)\frac{g + 2R_B}{r}(1 + \alpha - \beta)$,
//! $1 - \alpha^2 + \beta^2 = \frac{g + R_B}{r}\cdot\frac{r + R_A}{r} + \beta^2$, and so on.
//!
//! # Domain
//!
//! $r \ge R_A + R_B$. **Touching disks** ($r = R_A + R_B$ exactly) are accepted: the moduli stay
//! below 1 ($k\_+^2 = R_A/(R_A + R_B)$, $k\_-^2 = R_B/(R_A+R_B)$), $V$ and $F$ are finite and
//! continuous there (the first singular term of $V$ is $\propto g^{5/2}$). Overlapping disks,
//! non-finite separations and, for the vector form, separations out of the common plane are
//! typed errors.
//!
//! # Accuracy
//!
//! Against `tests/reference/disk_pair.json` (an independent 40-digit route: the lens-area
//! convolution, see `tests/reference/disk_pair.py`), 82 cases with radius ratios 1 to 1/100 and
//! SI magnitudes, from touching to $r = 10^8 (R_A + R_B)$: worst $1.1\times10^{-15}$ relative in
//! $F$ and $f$ (at a gap of $10^{-9}$), $6.3\times10^{-16}$ in $V$ and $u$; the test holds them
//! to [`crate::tolerance::DISK_PAIR_REL`].

use std::f64::consts::PI;

use thiserror::Error;

use crate::elliptic::{gauss, Gauss};
use crate::{Potential, Real, UniformDisk, Vec3};

/// Why a disk–disk interaction could not be evaluated.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum DiskPairError {
    /// The two disks were built with different gravitational constants.
    #[error(
        "the disks have different gravitational constants ({a} and {b}); build both with the same G"
    )]
    GravitationalConstantMismatch {
        /// G of disk A.
        a: f64,
        /// G of disk B.
        b: f64,
    },
    /// The separation is NaN, infinite or negative.
    #[error("the centre separation must be a finite non-negative number, got {separation}")]
    InvalidSeparation {
        /// The rejected separation (for a vector, its in-plane length or the offending component).
        separation: f64,
    },
    /// The disks overlap: their centres are closer than the sum of the radii.
    #[error("the disks overlap: centre separation {separation} < sum of the radii {contact}")]
    Overlap {
        /// The centre separation given.
        separation: f64,
        /// The smallest separation allowed, R_A + R_B (touching).
        contact: f64,
    },
    /// The separation vector leaves the common plane of the disks (z ≠ 0).
    #[error("the separation vector must lie in the disks' common plane (z = 0), got z = {z}")]
    NotCoplanar {
        /// The z component given.
        z: f64,
    },
    /// G m_A m_B, or a result, is not representable in these units.
    #[error("{what} is not representable ({value}); rescale the units")]
    OutOfRange {
        /// What overflowed or underflowed.
        what: &'static str,
        /// The value.
        value: f64,
    },
}

/// The interaction of two coplanar uniform disks at one centre separation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoplanarDiskInteraction {
    /// Centre separation r (length).
    pub separation: Real,
    /// Mutual potential energy V (negative; G · mass² / length).
    pub potential_energy: Real,
    /// Radial force on B along the unit vector from A to B, $-\mathrm dV/\mathrm dr$ (negative:
    /// attraction; G · mass² / length²). The force on A is its opposite.
    pub radial_force: Real,
    /// $u = -V r / (G m_A m_B)$, 1 for point masses.
    pub energy_shape_factor: Real,
    /// $f = -F r^2 / (G m_A m_B)$, 1 for point masses.
    pub force_shape_factor: Real,
}

/// Forces on both disks for a separation vector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoplanarDiskForces {
    /// Scalar interaction at the separation's length.
    pub interaction: CoplanarDiskInteraction,
    /// Force on disk A (toward B when attracting).
    pub force_on_a: Vec3,
    /// Force on disk B; exactly `-force_on_a`.
    pub force_on_b: Vec3,
}

/// Two uniform disks lying in one plane, ready to be evaluated at any separation: the closed
/// form of the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoplanarDiskPair {
    radius_a: Real,
    radius_b: Real,
    /// G m_A m_B.
    gravitational_mass_product: Real,
}

impl CoplanarDiskPair {
    /// The pair (A, B). Both disks must have the same gravitational constant.
    pub fn new(a: &UniformDisk, b: &UniformDisk) -> Result<Self, DiskPairError> {
        let (ga, gb) = (a.gravitational_constant(), b.gravitational_constant());
        if ga != gb {
            return Err(DiskPairError::GravitationalConstantMismatch { a: ga, b: gb });
        }
        let product = ga * a.mass() * b.mass();
        if !(product.is_normal() && product > 0.0) {
            return Err(DiskPairError::OutOfRange {
                what: "G m_A m_B",
                value: product,
            });
        }
        Ok(Self {
            radius_a: a.radius(),
            radius_b: b.radius(),
            gravitational_mass_product: product,
        })
    }

    /// The separation at which the disks touch, $R_A + R_B$.
    pub fn contact_separation(&self) -> Real {
        self.radius_a + self.radius_b
    }

    /// Energy, radial force and shape factors at centre separation `separation`
    /// (≥ $R_A + R_B$; touching is allowed).
    pub fn interaction(&self, separation: Real) -> Result<CoplanarDiskInteraction, DiskPairError> {
        let r = separation;
        if !(r.is_finite() && r >= 0.0) {
            return Err(DiskPairError::InvalidSeparation { separation: r });
        }
        let (big, small) = if self.radius_a >= self.radius_b {
            (self.radius_a, self.radius_b)
        } else {
            (self.radius_b, self.radius_a)
        };
        let contact = big + small;
        let gap = r - contact;
        if gap < 0.0 {
            return Err(DiskPairError::Overlap {
                separation: r,
                contact,
            });
        }
        let (u, f) = shape_factors(big, small, r, gap);
        let gm_over_r = self.gravitational_mass_product / r;
        let potential_energy = -gm_over_r * u;
        let radial_force = -(gm_over_r / r) * f;
        if !(potential_energy.is_finite() && radial_force.is_finite()) {
            return Err(DiskPairError::OutOfRange {
                what: "G m_A m_B / r²",
                value: gm_over_r / r,
            });
        }
        Ok(CoplanarDiskInteraction {
            separation: r,
            potential_energy,
            radial_force,
            energy_shape_factor: u,
            force_shape_factor: f,
        })
    }

    /// Forces on A and B for the separation vector from A's centre to B's centre, expressed in
    /// the disks' common frame (the plane of both disks is its x–y plane, so `z` must be 0).
    pub fn forces(&self, separation_vector: &Vec3) -> Result<CoplanarDiskForces, DiskPairError> {
        let d = separation_vector;
        if !(d.x.is_finite() && d.y.is_finite() && d.z.is_finite()) {
            let bad = [d.x, d.y, d.z]
                .into_iter()
                .find(|c| !c.is_finite())
                .unwrap_or(Real::NAN);
            return Err(DiskPairError::InvalidSeparation { separation: bad });
        }
        if d.z != 0.0 {
            return Err(DiskPairError::NotCoplanar { z: d.z });
        }
        let r = d.x.hypot(d.y);
        let interaction = self.interaction(r)?;
        let scale = interaction.radial_force / r;
        let force_on_b = Vec3::new(scale * d.x, scale * d.y, 0.0);
        Ok(CoplanarDiskForces {
            interaction,
            force_on_a: -force_on_b,
            force_on_b,
        })
    }
}

/// [`CoplanarDiskPair::interaction`] in one call.
pub fn coplanar_disk_interaction(
    a: &UniformDisk,
    b: &UniformDisk,
    separation: Real,
) -> Result<CoplanarDiskInteraction, DiskPairError> {
    CoplanarDiskPair::new(a, b)?.interaction(separation)
}

/// $(u, f)$ for radii `big` ≥ `small`, separation `r` and gap `r − big − small` ≥ 0.
fn shape_factors(big: Real, small: Real, r: Real, gap: Real) -> (Real, Real) {
    let alpha = big / r;
    let beta = small / r;
    // 1 − α² + β² and 1 + α² − β², from the gap.
    let one_minus = ((gap + small) / r) * ((r + big) / r) + beta * beta;
    let one_plus = ((gap + big) / r) * ((r + small) / r) + alpha * alpha;
    let sqrt_d =
        ((gap / r) * (1.0 + alpha + beta) * ((gap + 2.0 * small) / r) * (1.0 + alpha - beta))
            .sqrt();
    let m_plus = 2.0 * alpha * alpha / (one_plus + sqrt_d);
    let m_minus = 2.0 * beta * beta / (one_minus + sqrt_d);
    let kc2_plus = 0.5 * (one_minus + sqrt_d);
    let kc2_minus = 0.5 * (one_plus + sqrt_d);
    let plus: Gauss = gauss(kc2_plus.sqrt(), None);
    let minus: Gauss = gauss(kc2_minus.sqrt(), None);
    let xi2 = m_minus / kc2_plus;

    let s = 2.0 * plus.b * minus.k
        - 2.0 * m_plus * m_minus * minus.b * plus.c / kc2_minus
        - xi2 * (1.0 + m_plus) * plus.b * minus.c
        - m_minus * plus.d * minus.c
        + m_plus * xi2 / (9.0 * kc2_minus)
            * (kc2_plus * plus.c + 2.0 * plus.b)
            * (kc2_minus * minus.c + 2.0 * minus.b);
    let u = 4.0 / (PI * PI) * s;

    let t = plus.d * minus.b / kc2_minus + 2.0 * plus.d * minus.d
        - xi2 * plus.b * minus.d_minus_c / kc2_minus;
    let f = 16.0 / (3.0 * PI * PI) * t;
    (u, f)
}
