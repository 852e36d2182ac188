//! Bodies as the interaction engine sees them: the field a body makes (any [`Potential`]) and
//! the surface over which another body's field can be integrated, with the node tables built
//! for that surface (cached, one per resolution level).

use super::error::InteractionError;
use super::rules::{build_table, NodeTable, TableKey};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use surfgrav_potentials as potentials;
use surfgrav_potentials::{
    InertiaError, InertiaTensor, Mat3, Mesh, PointMass, Polyhedron, Potential, Sphere, Spheroid,
    Symmetry, TypedPotential, UniformDisk,
};
use surfgrav_surfaces::{EllipsoidSurface, Lamina, Real, Surface, TriangleMesh, Vec3};

/// The geometry of a body for the engine: what can be integrated over, and what its overlap
/// test uses. Body frame: centroid at the origin, an ellipsoid's $c$ axis and a disk's normal
/// along $z$.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum BodyShape {
    /// A point (no surface; others' fields are integrated over the other body, or the analytic
    /// point formula is used).
    Point,
    /// A homogeneous solid ellipsoid (sphere and spheroid included).
    Solid(EllipsoidSurface),
    /// A uniform disk in the body's x–y plane, integrated as a lamina.
    Disk(Lamina),
    /// The closed surface of a homogeneous solid of any shape, parametrised over a rectangle
    /// with exactly one periodic direction (see [`Surface`]).
    Surface(Arc<dyn Surface>),
    /// The closed triangle mesh of a homogeneous polyhedron (body frame: centroid at the
    /// origin), integrated face by face ([`surfgrav_surfaces::mesh`], [`super::mesh_pair`]).
    Mesh(Arc<TriangleMesh>),
    /// No surface is known: the body only provides its field.
    FieldOnly,
}

/// The potential a body carries; built-in kinds are kept concrete so the engine can call a
/// monomorphised loop for them (dynamic dispatch is paid only for [`Body::custom`]).
#[derive(Debug, Clone)]
pub(crate) enum SourceField {
    PointMass(PointMass),
    Sphere(Sphere),
    Spheroid(Spheroid),
    Ellipsoid(potentials::Ellipsoid),
    Disk(UniformDisk),
    Custom(Arc<dyn Potential>),
}

/// `with_field!(field, |f| expr)`: evaluates `expr` with `f` bound to the concrete potential
/// (one monomorphised copy per built-in kind, `dyn Potential` for user potentials).
macro_rules! with_field {
    ($field:expr, |$f:ident| $body:expr) => {
        match $field {
            $crate::body::SourceField::PointMass($f) => $body,
            $crate::body::SourceField::Sphere($f) => $body,
            $crate::body::SourceField::Spheroid($f) => $body,
            $crate::body::SourceField::Ellipsoid($f) => $body,
            $crate::body::SourceField::Disk($f) => $body,
            $crate::body::SourceField::Custom(custom) => {
                let $f: &dyn surfgrav_potentials::Potential = custom.as_ref();
                $body
            }
        }
    };
}
pub(crate) use with_field;

/// Directions closer than this (in sine of the angle, or relative offset) are treated as
/// exactly aligned: a few rounding errors of a rotation. A symmetry is exploited only when it
/// holds to rounding, so it never costs accuracy.
pub(crate) const ALIGNMENT: Real = 8.0 * Real::EPSILON;

/// Whether a field of this symmetry is unchanged by the reflection through the plane with
/// unit normal `normal` (body frame) through the centroid.
pub(crate) fn mirrors(symmetry: Symmetry, normal: &Vec3) -> bool {
    let along = |i: usize| {
        let off: Real = (0..3)
            .filter(|&j| j != i)
            .map(|j| normal[j] * normal[j])
            .sum();
        off.sqrt() <= ALIGNMENT
    };
    match symmetry {
        Symmetry::Spherical => true,
        Symmetry::Axisymmetric => normal.z.abs() <= ALIGNMENT || along(2),
        Symmetry::CoordinatePlanes => along(0) || along(1) || along(2),
        // None, and kinds added later: nothing assumed.
        _ => false,
    }
}

/// A body prepared for interactions: its field, its surface, its density, and a cache of the
/// surface node tables built so far (shared by every evaluation, built once per resolution
/// level; [`Body::clear_cache`] frees them).
///
/// Build it from a closed-form body ([`Body::spheroid`], [`Body::ellipsoid`], ...) or from any
/// [`Potential`] with a shape ([`Body::custom`]). Units are the potential's; the density is
/// mass per volume for a solid and mass per area for a disk.
pub struct Body {
    pub(crate) field: SourceField,
    pub(crate) shape: BodyShape,
    pub(crate) symmetry: Symmetry,
    pub(crate) density: Real,
    pub(crate) bounding_radius: Real,
    inertia: Option<InertiaTensor>,
    /// The polyhedron whose mesh is [`BodyShape::Mesh`] (its field is also `field`).
    pub(crate) polyhedron: Option<Arc<Polyhedron>>,
    tables: Mutex<HashMap<TableKey, NodeTable>>,
}

impl std::fmt::Debug for Body {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Body")
            .field("field", &self.field)
            .field("shape", &self.shape)
            .field("density", &self.density)
            .field("bounding_radius", &self.bounding_radius)
            .field("inertia", &self.inertia)
            .field("cached_tables", &self.cached_tables())
            .finish()
    }
}

impl Clone for Body {
    fn clone(&self) -> Self {
        let tables = self.tables.lock().map(|t| t.clone()).unwrap_or_default();
        Self {
            field: self.field.clone(),
            shape: self.shape.clone(),
            symmetry: self.symmetry,
            density: self.density,
            bounding_radius: self.bounding_radius,
            inertia: self.inertia,
            polyhedron: self.polyhedron.clone(),
            tables: Mutex::new(tables),
        }
    }
}

/// At most this many node tables are kept per body; beyond it the cache is emptied (a body
/// typically needs a handful).
const MAX_CACHED_TABLES: usize = 64;

impl Body {
    fn assemble(field: SourceField, shape: BodyShape) -> Result<Self, InteractionError> {
        let (mass, potential_radius, inertia, symmetry) = {
            let p = field_ref(&field);
            (p.mass(), p.bounding_radius(), p.inertia(), p.symmetry())
        };
        let (density, shape_radius) = match &shape {
            BodyShape::Point | BodyShape::FieldOnly => (Real::NAN, 0.0),
            BodyShape::Solid(e) => (mass / e.volume(), e.bounding_radius()),
            BodyShape::Disk(l) => (mass / l.area(), l.radius()),
            BodyShape::Surface(s) => {
                let volume = s.enclosed_volume().unwrap_or_else(|| {
                    // The volume by the divergence theorem on a fine table.
                    super::rules::surface_volume(s.as_ref()).unwrap_or(Real::NAN)
                });
                (mass / volume, s.bounding_radius())
            }
            BodyShape::Mesh(m) => (mass / m.volume(), m.bounding_radius()),
        };
        let needs_density = !matches!(shape, BodyShape::Point | BodyShape::FieldOnly);
        if needs_density && !(density.is_finite() && density > 0.0) {
            return Err(InteractionError::NonFiniteResult {
                what: "density (mass over volume or area)",
            });
        }
        Ok(Self {
            field,
            shape,
            symmetry,
            density,
            bounding_radius: potential_radius.max(shape_radius),
            inertia,
            polyhedron: None,
            tables: Mutex::new(HashMap::new()),
        })
    }

    /// A point mass (no surface).
    pub fn point_mass(body: PointMass) -> Self {
        Self {
            field: SourceField::PointMass(body),
            shape: BodyShape::Point,
            symmetry: Symmetry::Spherical,
            density: Real::NAN,
            bounding_radius: 0.0,
            inertia: None,
            polyhedron: None,
            tables: Mutex::new(HashMap::new()),
        }
    }

    /// A homogeneous sphere.
    pub fn sphere(body: Sphere) -> Result<Self, InteractionError> {
        let shape = BodyShape::Solid(EllipsoidSurface::sphere(body.radius())?);
        Self::assemble(SourceField::Sphere(body), shape)
    }

    /// A homogeneous spheroid (symmetry axis z).
    pub fn spheroid(body: Spheroid) -> Result<Self, InteractionError> {
        let shape = BodyShape::Solid(EllipsoidSurface::spheroid(
            body.equatorial_radius(),
            body.polar_radius(),
        )?);
        Self::assemble(SourceField::Spheroid(body), shape)
    }

    /// A homogeneous triaxial ellipsoid (semi-axes along x, y, z).
    pub fn ellipsoid(body: potentials::Ellipsoid) -> Result<Self, InteractionError> {
        let [a, b, c] = body.semi_axes();
        let shape = BodyShape::Solid(EllipsoidSurface::new(a, b, c)?);
        Self::assemble(SourceField::Ellipsoid(body), shape)
    }

    /// A uniform disk (lamina in the body x–y plane).
    pub fn disk(body: UniformDisk) -> Result<Self, InteractionError> {
        let shape = BodyShape::Disk(Lamina::new(body.radius())?);
        Self::assemble(SourceField::Disk(body), shape)
    }

    /// A homogeneous polyhedron, integrated over as its triangle mesh and acting by its
    /// Werner–Scheeres field (and, far enough away, by its certified exterior expansion at the
    /// engine's tolerance; [`super::mesh_pair`]). The body frame is the polyhedron's own,
    /// moved to its centroid if the mesh's origin is elsewhere (by more than $10^{-12}$ of its
    /// size; the mesh is then rebuilt and validated again); the orientation is kept.
    ///
    /// # Errors
    /// A mesh that no longer validates after the move (it cannot, for a valid one).
    pub fn polyhedron(body: Polyhedron) -> Result<Self, InteractionError> {
        let centroid = body.centroid();
        let body = if centroid.norm() > 1e-12 * body.circumscribing_radius() {
            let mesh = Mesh {
                vertices: body.vertices().iter().map(|v| v - centroid).collect(),
                faces: body.faces().iter().map(|f| f.map(|i| i as usize)).collect(),
            };
            Polyhedron::with_mass(&mesh, body.mass())
                .and_then(|p| {
                    p.with_gravitational_constant(body.gravitational_constant())
                        .map_err(Into::into)
                })
                .map_err(|_| InteractionError::NonFiniteResult {
                    what: "polyhedron moved to its centroid",
                })?
        } else {
            body
        };
        let mesh = TriangleMesh::new(body.vertices().to_vec(), body.faces().to_vec());
        let body = Arc::new(body);
        let mut out = Self::assemble(
            SourceField::Custom(body.clone()),
            BodyShape::Mesh(Arc::new(mesh)),
        )?;
        out.polyhedron = Some(body);
        Ok(out)
    }

    /// The polyhedron of a body built by [`Body::polyhedron`].
    pub fn as_polyhedron(&self) -> Option<&Polyhedron> {
        self.polyhedron.as_deref()
    }

    /// Any potential with the shape of the matter that makes it. The shape must describe a
    /// homogeneous body of the potential's mass (its density is mass over the shape's volume,
    /// or area for a disk); [`BodyShape::FieldOnly`] when no surface is known, in which case
    /// the other body's surface is integrated over. A [`BodyShape::Point`] or a spherical
    /// [`BodyShape::Solid`] tells the engine it may use the point formula, which relies only
    /// on the body's mass being spherically symmetric.
    ///
    /// Each evaluation calls the potential through dynamic dispatch, once per node (a few
    /// nanoseconds next to tens for a closed-form field); the generic
    /// [`integrate_over_solid`](super::integrate_over_solid) gives a monomorphised loop for a
    /// user's own type. What the potential reports about itself decides the fast paths, as
    /// for the built-in kinds: its [`Potential::symmetry`] (mirror halving of the nodes, the
    /// point formula when [`Symmetry::Spherical`]), [`Potential::singular_radius`] (the start
    /// resolution and the surface choice) and [`Potential::field_cost`] (the surface choice);
    /// by default nothing is assumed (no symmetry, the bounding radius, the cost of a spheroid).
    pub fn custom(
        potential: Arc<dyn Potential>,
        shape: BodyShape,
    ) -> Result<Self, InteractionError> {
        Self::assemble(SourceField::Custom(potential), shape)
    }

    /// The same body with the inertia tensor `tensor` (body frame, about the centroid; units
    /// mass · length²), for a user's body whose potential does not give one
    /// ([`Potential::inertia`]) or to override it. Rotational dynamics needs it.
    ///
    /// # Errors
    /// A tensor that is not a physical inertia tensor ([`InertiaTensor::new`]); a point mass,
    /// which cannot rotate.
    pub fn with_inertia(mut self, tensor: Mat3) -> Result<Self, InertiaError> {
        if matches!(self.shape, BodyShape::Point) {
            return Err(InertiaError::PointMass);
        }
        self.inertia = Some(InertiaTensor::new(tensor)?);
        Ok(self)
    }

    /// The inertia tensor about the centroid in the body frame: the closed form of a built-in
    /// body, the one given by [`Body::with_inertia`] or by a custom potential, `None` for a point
    /// mass (which cannot rotate) and a custom body that gave none.
    pub fn inertia(&self) -> Option<&InertiaTensor> {
        self.inertia.as_ref()
    }

    /// The body's field.
    pub fn potential(&self) -> &dyn Potential {
        field_ref(&self.field)
    }

    /// The body's shape.
    pub fn shape(&self) -> &BodyShape {
        &self.shape
    }

    /// Total mass.
    pub fn mass(&self) -> Real {
        self.potential().mass()
    }

    /// Density of the homogeneous body: mass per volume for a solid, per area for a disk; NaN
    /// for a point or a field-only body.
    pub fn density(&self) -> Real {
        self.density
    }

    /// Radius of the smallest centroid-centred sphere containing the body (and its shape).
    pub fn bounding_radius(&self) -> Real {
        self.bounding_radius
    }

    /// Whether the engine can integrate over this body's surface.
    pub fn has_surface(&self) -> bool {
        matches!(
            self.shape,
            BodyShape::Solid(_) | BodyShape::Disk(_) | BodyShape::Surface(_) | BodyShape::Mesh(_)
        )
    }

    /// Whether the body's matter is spherically symmetric (a point mass, a sphere, or a field
    /// that reports [`Symmetry::Spherical`]), so that its interaction with any body outside it
    /// is that of a point mass.
    pub fn is_spherically_symmetric(&self) -> bool {
        let by_shape = match &self.shape {
            BodyShape::Point => true,
            BodyShape::Solid(e) => {
                let [a, b, c] = [e.x_semi_axis(), e.y_semi_axis(), e.z_semi_axis()];
                a == b && b == c
            }
            _ => false,
        };
        by_shape || self.symmetry == Symmetry::Spherical
    }

    /// The typed view of the body's field ([`Potential::as_typed`]): a built-in kind, or
    /// [`TypedPotential::Custom`].
    pub fn typed(&self) -> TypedPotential<'_> {
        self.potential().as_typed()
    }

    /// The symmetry of the body's field, as its potential reports it ([`Potential::symmetry`]).
    pub fn symmetry(&self) -> Symmetry {
        self.symmetry
    }

    /// Radius of the set where the body's exterior potential, continued inward, is singular:
    /// the potential's own report ([`Potential::singular_radius`]), else the focal set of the
    /// body's ellipsoid or disk shape (the shape describes the homogeneous matter that makes
    /// the field), else the bounding radius.
    pub fn singular_radius(&self) -> Real {
        if let Some(radius) = self.potential().singular_radius() {
            return radius;
        }
        match &self.shape {
            BodyShape::Point => 0.0,
            BodyShape::Solid(e) => {
                let mut s = [e.x_semi_axis(), e.y_semi_axis(), e.z_semi_axis()];
                s.sort_by(Real::total_cmp);
                ((s[2] - s[0]) * (s[2] + s[0])).sqrt()
            }
            BodyShape::Disk(l) => l.radius(),
            BodyShape::Surface(_) | BodyShape::FieldOnly | BodyShape::Mesh(_) => {
                self.bounding_radius
            }
        }
    }

    /// The radius of the body's equator when its field is axisymmetric or spherical and its
    /// shape is known (a point 0, an ellipsoid its $x$ semi-axis, a disk its radius): two such
    /// bodies with parallel axes touch edge to edge at the sum. `None` otherwise.
    pub fn equatorial_radius(&self) -> Option<Real> {
        if !matches!(self.symmetry, Symmetry::Axisymmetric | Symmetry::Spherical) {
            return None;
        }
        match &self.shape {
            BodyShape::Point => Some(0.0),
            BodyShape::Solid(e) if e.x_semi_axis() == e.y_semi_axis() => Some(e.x_semi_axis()),
            BodyShape::Disk(l) => Some(l.radius()),
            _ => None,
        }
    }

    /// Whether the surface is a body of revolution about z (a spheroid, sphere or disk), so the
    /// engine may turn its node tables about z to face the other body.
    pub(crate) fn is_axisymmetric_surface(&self) -> bool {
        match &self.shape {
            BodyShape::Solid(e) => e.x_semi_axis() == e.y_semi_axis(),
            BodyShape::Disk(_) => true,
            _ => false,
        }
    }

    /// Empties the node-table cache.
    pub fn clear_cache(&self) {
        if let Ok(mut t) = self.tables.lock() {
            t.clear();
        }
    }

    /// Number of node tables currently cached.
    pub fn cached_tables(&self) -> usize {
        self.tables.lock().map(|t| t.len()).unwrap_or(0)
    }

    /// The node table for `key`, built on first use.
    pub(crate) fn table(&self, key: TableKey) -> Result<NodeTable, InteractionError> {
        if let Ok(cache) = self.tables.lock() {
            if let Some(t) = cache.get(&key) {
                return Ok(t.clone());
            }
        }
        let table = build_table(&self.shape, key)?;
        if let Ok(mut cache) = self.tables.lock() {
            if cache.len() >= MAX_CACHED_TABLES {
                cache.clear();
            }
            cache.insert(key, table.clone());
        }
        Ok(table)
    }
}

pub(crate) fn field_ref(field: &SourceField) -> &dyn Potential {
    match field {
        SourceField::PointMass(p) => p,
        SourceField::Sphere(p) => p,
        SourceField::Spheroid(p) => p,
        SourceField::Ellipsoid(p) => p,
        SourceField::Disk(p) => p,
        SourceField::Custom(p) => p.as_ref(),
    }
}
