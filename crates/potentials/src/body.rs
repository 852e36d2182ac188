use crate::{Ellipsoid, PointMass, Polyhedron, Real, Sphere, Spheroid, UniformDisk, Vec3};
use nalgebra::{Translation3, UnitQuaternion};

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

/// The symmetries of a body's field (and, for a homogeneous body, of its matter) in its body
/// frame, centroid at the origin. An engine uses them to halve or quarter its nodes and to
/// recognise central pairs; a field reports only what holds exactly (to rounding).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Symmetry {
    /// None known (the default for a user's potential).
    #[default]
    None,
    /// Mirror-symmetric about the three body coordinate planes (a triaxial ellipsoid).
    CoordinatePlanes,
    /// A body of revolution about the body $z$ axis that is also mirror-symmetric about the
    /// $x$–$y$ plane (a spheroid, a disk): symmetric about every plane containing $z$.
    Axisymmetric,
    /// Symmetric about every plane through the centroid (a point mass, a sphere).
    Spherical,
}

/// What kind of body a potential is: one of the closed-form kinds of this crate, or
/// [`TypedPotential::Custom`] for anything else. Fast paths match on it (a closed form for a
/// pair, a monomorphised loop); everything else goes through the [`Potential`] trait, so a
/// user's type works wherever a built-in one does, only without the kind-specific shortcuts
/// it does not declare.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum TypedPotential<'a> {
    /// A point mass.
    PointMass(&'a PointMass),
    /// A homogeneous sphere.
    Sphere(&'a Sphere),
    /// A homogeneous spheroid (symmetry axis $z$).
    Spheroid(&'a Spheroid),
    /// A homogeneous triaxial ellipsoid.
    Ellipsoid(&'a Ellipsoid),
    /// A uniform disk in the $x$–$y$ plane.
    Disk(&'a UniformDisk),
    /// A homogeneous polyhedron.
    Polyhedron(&'a Polyhedron),
    /// Any other potential: only its trait methods are known.
    Custom,
}

impl TypedPotential<'_> {
    /// The field's symmetry for this kind ([`Symmetry::None`] for a custom potential).
    pub fn symmetry(&self) -> Symmetry {
        match self {
            Self::PointMass(_) | Self::Sphere(_) => Symmetry::Spherical,
            Self::Spheroid(_) | Self::Disk(_) => Symmetry::Axisymmetric,
            Self::Ellipsoid(e) => {
                let [a, b, c] = e.semi_axes();
                if a == b && b == c {
                    Symmetry::Spherical
                } else if a == b {
                    Symmetry::Axisymmetric
                } else {
                    Symmetry::CoordinatePlanes
                }
            }
            Self::Polyhedron(_) | Self::Custom => Symmetry::None,
        }
    }

    /// Radius of the set where the exterior potential, continued into the body, is singular
    /// (its focal set: $\sqrt{a\_{\max}^2 - a\_{\min}^2}$ for an ellipsoid, 0 for a point or a
    /// sphere, the radius for a disk); `None` when unknown (a polyhedron, a custom potential).
    pub fn singular_radius(&self) -> Option<Real> {
        let focal = |mut s: [Real; 3]| {
            s.sort_by(Real::total_cmp);
            ((s[2] - s[0]) * (s[2] + s[0])).sqrt()
        };
        match self {
            Self::PointMass(_) | Self::Sphere(_) => Some(0.0),
            Self::Spheroid(s) => Some(focal([
                s.equatorial_radius(),
                s.equatorial_radius(),
                s.polar_radius(),
            ])),
            Self::Ellipsoid(e) => Some(focal(e.semi_axes())),
            Self::Disk(d) => Some(d.radius()),
            Self::Polyhedron(_) | Self::Custom => None,
        }
    }

    /// The cost of one field evaluation relative to a spheroid's (measured on the engine's
    /// node loop: a point or a sphere 0.2, a spheroid 1, a triaxial ellipsoid 3, a disk 3.5;
    /// a polyhedron 1.6 per face, [`crate::polyhedron::FIELD_COST_PER_FACE`]); 1 for a custom
    /// potential.
    pub fn field_cost(&self) -> Real {
        match self {
            Self::PointMass(_) | Self::Sphere(_) => 0.2,
            Self::Polyhedron(p) => p.field_cost(),
            Self::Spheroid(_) | Self::Custom => 1.0,
            Self::Ellipsoid(_) => 3.0,
            Self::Disk(_) => 3.5,
        }
    }
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

    /// Fields at many body-frame points: `out[k]` becomes the field at `points[k]` (for the
    /// shorter of the two slices). The default evaluates [`Potential::field`] point by point;
    /// a kind overrides it where several points evaluated together are faster. The engine's
    /// node loops call it on blocks of points, so a user's own potential gets the batched path
    /// by overriding this one method.
    fn fields_into(&self, points: &[Vec3], out: &mut [Field]) {
        for (field, r) in out.iter_mut().zip(points) {
            *field = self.field(r);
        }
    }

    /// Potentials at many body-frame points, as [`Potential::fields_into`] (default: point by
    /// point through [`Potential::potential`]).
    fn potentials_into(&self, points: &[Vec3], out: &mut [Real]) {
        for (potential, r) in out.iter_mut().zip(points) {
            *potential = self.potential(r);
        }
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

    /// The typed view: which closed-form kind this is, [`TypedPotential::Custom`] (the
    /// default) for any other. A wrapper around a built-in kind should stay `Custom` and report
    /// the kind's properties through [`Self::symmetry`], [`Self::singular_radius`] and
    /// [`Self::field_cost`] instead: a typed view promises that the value *is* that kind.
    fn as_typed(&self) -> TypedPotential<'_> {
        TypedPotential::Custom
    }

    /// The field's symmetries in the body frame (by default the typed view's:
    /// [`Symmetry::None`] for a custom potential). Report only what holds to rounding: an
    /// engine evaluates half or a quarter of its nodes on the strength of it.
    fn symmetry(&self) -> Symmetry {
        self.as_typed().symmetry()
    }

    /// Radius of the set where the exterior potential, continued into the body, is singular
    /// (by default the typed view's; `None`: unknown, an engine then assumes the bounding
    /// radius). The convergence of a surface integral in this field depends on the distance
    /// to that set, so a small true radius lets an engine predict a cheaper rule.
    fn singular_radius(&self) -> Option<Real> {
        self.as_typed().singular_radius()
    }

    /// The cost of one [`Self::field`] evaluation relative to a homogeneous spheroid's (by
    /// default the typed view's; 1 for a custom potential). An engine uses it to choose which
    /// body's surface to integrate over.
    fn field_cost(&self) -> Real {
        self.as_typed().field_cost()
    }
}

/// Where a body is in the world: nalgebra's [`Isometry3`](nalgebra::Isometry3), whose
/// translation is the world position of the centroid and whose rotation takes body-frame
/// vectors to world-frame vectors. [`PoseExt`] adds this crate's vocabulary (the position as a
/// vector, points to and from the body frame) and [`Pose::new`](nalgebra::Isometry3::new)
/// takes a position and a rotation vector (axis × angle, radians).
///
/// ```
/// use surfgrav_potentials::{Pose, PoseExt, Vec3};
/// let pose = Pose::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2));
/// assert_eq!(pose.position(), Vec3::new(1.0, 0.0, 0.0));
/// let r = pose.to_world(&Vec3::new(1.0, 0.0, 0.0));
/// assert!((r - Vec3::new(1.0, 1.0, 0.0)).norm() < 1e-15);
/// ```
pub type Pose = nalgebra::Isometry3<Real>;

/// What a [`Pose`] offers beyond nalgebra's `Isometry3`, in this crate's words. The maps are
/// those of the isometry on points, computed in the same order
/// ($\mathbf r\_{\rm world} = R\\,\mathbf r\_{\rm body} + \mathbf t$,
/// $\mathbf r\_{\rm body} = R^{-1}(\mathbf r\_{\rm world} - \mathbf t)$), so they agree bit for bit with
/// [`Isometry3::transform_point`](nalgebra::Isometry3::transform_point) and
/// [`Isometry3::inverse_transform_point`](nalgebra::Isometry3::inverse_transform_point).
pub trait PoseExt {
    /// A pose from the world position of the centroid and the body → world rotation.
    fn from_position_rotation(position: Vec3, rotation: UnitQuaternion<Real>) -> Self;

    /// World position of the centroid (the translation).
    fn position(&self) -> Vec3;

    /// World point → body-frame point.
    fn to_body(&self, r_world: &Vec3) -> Vec3;

    /// Body-frame point → world point.
    fn to_world(&self, r_body: &Vec3) -> Vec3;
}

impl PoseExt for Pose {
    #[inline]
    fn from_position_rotation(position: Vec3, rotation: UnitQuaternion<Real>) -> Self {
        Self::from_parts(Translation3::from(position), rotation)
    }

    #[inline]
    fn position(&self) -> Vec3 {
        self.translation.vector
    }

    #[inline]
    fn to_body(&self, r_world: &Vec3) -> Vec3 {
        self.rotation
            .inverse_transform_vector(&(r_world - self.translation.vector))
    }

    #[inline]
    fn to_world(&self, r_body: &Vec3) -> Vec3 {
        self.rotation * r_body + self.translation.vector
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    /// The former `Pose` struct's formulas, kept here to prove the isometry maps the same
    /// points to the same bits.
    fn old_to_body(position: &Vec3, rotation: &UnitQuaternion<Real>, r: &Vec3) -> Vec3 {
        rotation.inverse_transform_vector(&(r - position))
    }
    fn old_to_world(position: &Vec3, rotation: &UnitQuaternion<Real>, r: &Vec3) -> Vec3 {
        rotation * r + position
    }

    fn bits(v: &Vec3) -> [u64; 3] {
        [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
    }

    #[test]
    fn isometry_maps_match_the_former_pose_bit_for_bit() {
        let poses = [
            (Vec3::zeros(), Vec3::zeros()),
            (Vec3::new(2.55, 0.0, 0.0), Vec3::new(0.0, 0.0, 0.7)),
            (Vec3::new(-1.3, 4.1e3, 7.0e-3), Vec3::new(0.3, -1.1, 2.9)),
            (
                Vec3::new(1.5e11, -2.0e10, 3.3e9),
                Vec3::new(-3.0, 0.1, 0.05),
            ),
            (Vec3::new(1e-9, 1e-9, -1e-9), Vec3::new(1e-8, 0.0, 3.1)),
        ];
        let points = [
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(-0.25, 1e-7, 9.5e4),
            Vec3::new(1.5e11, -2.0e10, 3.3e9),
            Vec3::new(0.0, 0.0, 0.0),
        ];
        let mut checked = 0;
        for (position, rotation_vector) in poses {
            let rotation = UnitQuaternion::from_scaled_axis(rotation_vector);
            let pose = Pose::new(position, rotation_vector);
            let parts = Pose::from_position_rotation(position, rotation);
            assert_eq!(pose, parts);
            assert_eq!(bits(&pose.position()), bits(&position));
            for r in &points {
                let body = old_to_body(&position, &rotation, r);
                let world = old_to_world(&position, &rotation, r);
                assert_eq!(bits(&pose.to_body(r)), bits(&body));
                assert_eq!(bits(&pose.to_world(r)), bits(&world));
                let p = Point3::from(*r);
                assert_eq!(bits(&pose.inverse_transform_point(&p).coords), bits(&body));
                assert_eq!(bits(&pose.transform_point(&p).coords), bits(&world));
                assert_eq!(bits(&(pose * p).coords), bits(&world));
                checked += 1;
            }
        }
        assert_eq!(checked, 20);
        assert_eq!(Pose::default(), Pose::identity());
    }
}
