//! The homogeneous sphere of radius $R$ and mass $M$:
//!
//! $$\Phi(r) = \begin{cases} -\dfrac{GM}{r}, & r \ge R,\\\\
//!   -\dfrac{GM\\,(3R^2 - r^2)}{2R^3}, & r \le R, \end{cases}
//! \qquad
//! \mathbf a = \begin{cases} -\dfrac{GM\\,\mathbf r}{r^3}, & r \ge R,\\\\
//!   -\dfrac{GM\\,\mathbf r}{R^3}, & r \le R. \end{cases}$$
//!
//! Both pieces agree on the surface (value and gradient); inside, $\nabla^2\Phi = 4\pi G\rho$
//! with $\rho = 3M/(4\pi R^3)$. Valid at every finite point.

use std::f64::consts::PI;

use crate::error::{positive, representable, BodyError};
use crate::point_mass::kepler_field;
use crate::{Field, Potential, Real, Region, Vec3};

/// A homogeneous solid sphere centred at the origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    radius: Real,
    mass: Real,
    density: Real,
    volume: Real,
    gravitational_constant: Real,
    gm: Real,
    radius_squared: Real,
    /// $GM/R^3$, the interior field's spring constant.
    gm_over_radius_cubed: Real,
}

impl Sphere {
    /// A sphere of `radius` and total `mass` (both positive, finite), with G = 1.
    pub fn new(radius: Real, mass: Real) -> Result<Self, BodyError> {
        let radius = positive("radius", radius)?;
        let mass = positive("mass", mass)?;
        let volume = representable("volume", 4.0 / 3.0 * PI * radius * radius * radius)?;
        let density = representable("density", mass / volume)?;
        Self::build(radius, mass, density, volume, 1.0)
    }

    /// A sphere of `radius` and uniform `density` (both positive, finite), with G = 1.
    pub fn with_density(radius: Real, density: Real) -> Result<Self, BodyError> {
        let radius = positive("radius", radius)?;
        let density = positive("density", density)?;
        let volume = representable("volume", 4.0 / 3.0 * PI * radius * radius * radius)?;
        let mass = representable("mass", density * volume)?;
        Self::build(radius, mass, density, volume, 1.0)
    }

    /// The same sphere with gravitational constant `g` (positive, finite).
    pub fn with_gravitational_constant(self, g: Real) -> Result<Self, BodyError> {
        let g = positive("gravitational_constant", g)?;
        Self::build(self.radius, self.mass, self.density, self.volume, g)
    }

    fn build(
        radius: Real,
        mass: Real,
        density: Real,
        volume: Real,
        g: Real,
    ) -> Result<Self, BodyError> {
        let gm = representable("gravitational parameter G·mass", g * mass)?;
        let gm_over_radius_cubed =
            representable("G·mass / radius³", gm / radius / radius / radius)?;
        Ok(Self {
            radius,
            mass,
            density,
            volume,
            gravitational_constant: g,
            gm,
            radius_squared: radius * radius,
            gm_over_radius_cubed,
        })
    }

    /// The radius.
    pub fn radius(&self) -> Real {
        self.radius
    }

    /// The uniform density, mass / volume.
    pub fn density(&self) -> Real {
        self.density
    }
}

impl Potential for Sphere {
    fn as_typed(&self) -> crate::TypedPotential<'_> {
        crate::TypedPotential::Sphere(self)
    }

    fn inertia(&self) -> Option<crate::InertiaTensor> {
        let r = self.radius();
        crate::InertiaTensor::solid_ellipsoid(self.mass(), r, r, r).ok()
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
        self.radius
    }

    /// On the surface within 4 units in the last place of $r^2$.
    fn region(&self, r: &Vec3) -> Region {
        let excess = r.norm_squared() - self.radius_squared;
        let band = 4.0 * Real::EPSILON * self.radius_squared;
        if excess > band {
            Region::Outside
        } else if excess < -band {
            Region::Inside
        } else {
            Region::OnSurface
        }
    }

    #[inline]
    fn field(&self, r: &Vec3) -> Field {
        let r2 = r.norm_squared();
        if r2 > self.radius_squared {
            return kepler_field(self.gm, r);
        }
        let k = self.gm_over_radius_cubed;
        Field {
            potential: -0.5 * k * (3.0 * self.radius_squared - r2),
            acceleration: r * -k,
        }
    }
}
