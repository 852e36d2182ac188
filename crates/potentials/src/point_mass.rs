//! A point mass: $\Phi = -GM/r$, $\mathbf a = -GM\\,\mathbf r / r^3$.
//!
//! Also the far-field limit every solid falls back to beyond $10^{20}$ body sizes, where the
//! quadrupole is below $10^{-40}$ of the monopole.

use crate::error::{positive, representable, BodyError};
use crate::{Field, Potential, Real, Region, Vec3};

/// A point mass at the origin of its frame.
///
/// At the origin itself the potential is $-\infty$ and the acceleration is taken as zero (the
/// direction is undefined); [`Potential::region`] reports [`Region::OnSurface`] there and only
/// there, so callers can detect the singular point. Elsewhere the field is finite except where
/// $GM/r^2$ itself exceeds the range of `f64`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMass {
    mass: Real,
    gravitational_constant: Real,
    gm: Real,
}

impl PointMass {
    /// A point mass of `mass` (positive, finite), with G = 1.
    pub fn new(mass: Real) -> Result<Self, BodyError> {
        let mass = positive("mass", mass)?;
        Ok(Self {
            mass,
            gravitational_constant: 1.0,
            gm: mass,
        })
    }

    /// The same body with gravitational constant `g` (positive, finite).
    pub fn with_gravitational_constant(self, g: Real) -> Result<Self, BodyError> {
        let g = positive("gravitational_constant", g)?;
        let gm = representable("gravitational parameter G·mass", g * self.mass)?;
        Ok(Self {
            gravitational_constant: g,
            gm,
            ..self
        })
    }
}

impl Potential for PointMass {
    fn as_typed(&self) -> crate::TypedPotential<'_> {
        crate::TypedPotential::PointMass(self)
    }

    fn mass(&self) -> Real {
        self.mass
    }

    fn gravitational_constant(&self) -> Real {
        self.gravitational_constant
    }

    fn volume(&self) -> Real {
        0.0
    }

    fn bounding_radius(&self) -> Real {
        0.0
    }

    fn region(&self, r: &Vec3) -> Region {
        if r.iter().all(|&v| v == 0.0) {
            Region::OnSurface
        } else {
            Region::Outside
        }
    }

    #[inline]
    fn field(&self, r: &Vec3) -> Field {
        kepler_field(self.gm, r)
    }
}

/// $-GM/r$ and $-GM\\,\hat{\mathbf r}/r^2$, without spurious overflow or underflow of $r^2$ or
/// $r^3$ for any finite `r`; at `r = 0`, $-\infty$ and a zero acceleration.
#[inline]
pub(crate) fn kepler_field(gm: Real, r: &Vec3) -> Field {
    let r2 = r.norm_squared();
    if r2.is_normal() {
        let inv_r = 1.0 / r2.sqrt();
        let potential = -gm * inv_r;
        // (r/r)·(Φ/r): no intermediate smaller than the result itself (GM/r³ could underflow).
        return Field {
            potential,
            acceleration: (r * inv_r) * (potential * inv_r),
        };
    }
    kepler_field_rescaled(gm, r)
}

/// The rare cases of [`kepler_field`]: $r^2$ overflowed, underflowed or is zero.
#[cold]
fn kepler_field_rescaled(gm: Real, r: &Vec3) -> Field {
    if r.iter().all(|&v| v == 0.0) {
        return Field {
            potential: Real::NEG_INFINITY,
            acceleration: Vec3::zeros(),
        };
    }
    // A power of two brings r² into range exactly.
    let largest = r.amax();
    let scale = if largest > 1.0 {
        Real::powi(2.0, -600)
    } else {
        Real::powi(2.0, 600)
    };
    let scaled = r * scale;
    let inv_scaled = 1.0 / scaled.norm();
    let unit = scaled * inv_scaled;
    let inv_r = inv_scaled * scale;
    let potential = -gm * inv_r;
    Field {
        potential,
        acceleration: unit * (potential * inv_r),
    }
}
