use crate::{Real, Vec3};
use nalgebra::UnitQuaternion;

/// Potential and acceleration at one point, computed together (they share the expensive part:
/// the confocal parameter, the elliptic integrals).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    /// Φ, negative (see the crate conventions). Units: G · mass / length.
    pub potential: Real,
    /// a = −∇Φ, pointing toward the body. Units: G · mass / length².
    pub acceleration: Vec3,
}

/// Where a point lies relative to a body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Region {
    /// Strictly inside a solid (never for a disk or a point mass).
    Inside,
    /// On the surface of a solid, on the lamina of a disk, or at a point mass.
    OnSurface,
    /// Outside.
    Outside,
}

/// The field of a body, evaluated in the body's own frame.
///
/// Implementations are plain structs with validated constructors. The trait is object safe so a
/// scene read from a file can hold `Box<dyn Potential>`; hot loops stay generic over `P: Potential`
/// so the formula inlines.
pub trait Potential: std::fmt::Debug + Send + Sync {
    /// Total mass.
    fn mass(&self) -> Real;

    /// The gravitational constant this body was built with (1 unless set).
    fn gravitational_constant(&self) -> Real;

    /// Volume of a solid; 0 for a lamina or a point mass.
    fn volume(&self) -> Real;

    /// Radius of the smallest origin-centred sphere that contains the body.
    fn bounding_radius(&self) -> Real;

    /// Inside / on / outside, for a point in the body frame.
    fn region(&self, r: &Vec3) -> Region;

    /// Potential and acceleration at `r` (body frame). Total on finite points.
    fn field(&self, r: &Vec3) -> Field;

    /// Potential only. Implementations override this where it is cheaper than [`Potential::field`].
    fn potential(&self, r: &Vec3) -> Real {
        self.field(r).potential
    }

    /// Acceleration only.
    fn acceleration(&self, r: &Vec3) -> Vec3 {
        self.field(r).acceleration
    }

    /// Field at a world-frame point, for the body placed by `pose`: the point is taken into the
    /// body frame, the acceleration is rotated back into the world frame.
    fn field_in_world(&self, pose: &Pose, r_world: &Vec3) -> Field {
        let local = pose.to_body(r_world);
        let f = self.field(&local);
        Field {
            potential: f.potential,
            acceleration: pose.rotation * f.acceleration,
        }
    }

    /// The inertia tensor about the centroid in the body frame ([`crate::inertia`]); `None` for
    /// a body that cannot rotate (a point mass) or whose mass distribution is unknown (the
    /// default: a user's potential supplies its own to be integrated with rotation).
    fn inertia(&self) -> Option<crate::InertiaTensor> {
        None
    }

    /// G times the mass, the gravitational parameter μ.
    fn gravitational_parameter(&self) -> Real {
        self.gravitational_constant() * self.mass()
    }
}

/// Where a body is in the world: the position of its centroid and the rotation that takes
/// body-frame vectors to world-frame vectors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// World position of the centroid.
    pub position: Vec3,
    /// Body frame → world frame.
    pub rotation: UnitQuaternion<Real>,
}

impl Default for Pose {
    fn default() -> Self {
        Self::identity()
    }
}

impl Pose {
    /// The body frame coincides with the world frame.
    pub fn identity() -> Self {
        Self {
            position: Vec3::zeros(),
            rotation: UnitQuaternion::identity(),
        }
    }

    /// A pose from a position and a rotation vector (axis × angle, radians).
    pub fn new(position: Vec3, rotation_vector: Vec3) -> Self {
        Self {
            position,
            rotation: UnitQuaternion::from_scaled_axis(rotation_vector),
        }
    }

    /// World point → body-frame point.
    pub fn to_body(&self, r_world: &Vec3) -> Vec3 {
        self.rotation
            .inverse_transform_vector(&(r_world - self.position))
    }

    /// Body-frame point → world point.
    pub fn to_world(&self, r_body: &Vec3) -> Vec3 {
        self.rotation * r_body + self.position
    }
}
