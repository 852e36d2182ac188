//! Bodies: `Sphere`, `Spheroid`, `Ellipsoid`, `Disk`, `PointMass`, all subclasses of `Body`.
//!
//! Constructors take the scene files' keyword names and are validated by the same code as the
//! command line's body specs ([`BodySpec::build`]), so a bad value gets the CLI's message
//! (`spheroid: polar_radius must be a positive finite number, got -0.25`).

use std::sync::Arc;

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use rayon::prelude::*;
use std::path::PathBuf;

use surfgrav_interaction::Body as EngineBody;
use surfgrav_potentials::{LengthUnit, Mesh, Polyhedron as PolyhedronBody, Potential, Vec3};
use surfgrav_scenarios::spec::{compact, Amount, BodyKind, BodySpec};

use crate::arrays;
use crate::errors::{compute, input, Failure, InputError};

/// What a Python body is, for messages, `repr` and the command line.
#[derive(Debug, Clone)]
pub enum Described {
    /// A closed-form body, as the CLI's `--body` spec.
    Spec(BodySpec),
    /// A homogeneous polyhedron.
    Mesh(MeshInfo),
}

/// Where a polyhedron came from and what it was given.
#[derive(Debug, Clone)]
pub struct MeshInfo {
    /// `arrays`, the OBJ file or the vertex and facet files, as given.
    pub source: String,
    /// Mass or density, as given.
    pub amount: Amount,
    /// The length unit of the input coordinates.
    pub unit: LengthUnit,
    /// The input mesh's centroid (in metres), subtracted from every vertex.
    pub centroid: Vec3,
}

/// What a Python body holds: the validated body's description (for messages and the CLI) and
/// the engine's body with its cache of surface node tables (shared by every interaction this
/// body takes part in).
#[derive(Debug)]
pub struct Core {
    /// What the body is.
    pub described: Described,
    /// The gravitational constant.
    pub g: f64,
    /// The engine's body.
    pub engine: EngineBody,
}

impl Core {
    fn new(kind: BodyKind, dimensions: Vec<f64>, amount: Amount, g: f64) -> PyResult<Self> {
        let spec = BodySpec {
            kind,
            dimensions,
            amount,
        };
        let engine = spec
            .build(g)
            .map_err(|e| InputError::new_err(e.to_string()))?
            .into_interaction_body()
            .map_err(|e| InputError::new_err(e.to_string()))?;
        Ok(Self {
            described: Described::Spec(spec),
            g,
            engine,
        })
    }

    /// The closed-form body's spec (None for a polyhedron).
    pub fn spec(&self) -> Option<&BodySpec> {
        match &self.described {
            Described::Spec(s) => Some(s),
            Described::Mesh(_) => None,
        }
    }

    /// Whether this is a point mass.
    pub fn is_point(&self) -> bool {
        self.spec().is_some_and(|s| s.kind == BodyKind::Point)
    }

    /// One line naming the body: the CLI spec, or the polyhedron's mesh and amount.
    pub fn describe(&self) -> String {
        match &self.described {
            Described::Spec(s) => s.to_string(),
            Described::Mesh(m) => {
                let p = self.engine.as_polyhedron();
                let faces = p.map_or(0, |p| p.faces().len());
                let amount = match m.amount {
                    Amount::Mass(x) => format!("mass={x}"),
                    Amount::Density(x) => format!("density={x}"),
                };
                format!("polyhedron:{},faces={faces},{amount}", m.source)
            }
        }
    }

    /// Geometric value `i` of a closed-form body's spec (its subclass's getters).
    fn dimension(&self, i: usize) -> f64 {
        self.spec()
            .and_then(|s| s.dimensions.get(i).copied())
            .unwrap_or(f64::NAN)
    }

    /// The body's potential, for field evaluation.
    fn potential(&self) -> &dyn Potential {
        self.engine.potential()
    }
}

/// How much matter: exactly one of mass and density.
fn amount(kind: &str, mass: Option<f64>, density: Option<f64>) -> PyResult<Amount> {
    match (mass, density) {
        (Some(m), None) => Ok(Amount::Mass(m)),
        (None, Some(d)) => Ok(Amount::Density(d)),
        (Some(_), Some(_)) => Err(InputError::new_err(format!(
            "give either mass or density for a {kind}, not both"
        ))),
        (None, None) => Err(InputError::new_err(format!(
            "a {kind} needs `mass` (or `density`)"
        ))),
    }
}

/// What `field` returns: the potential (N,) and the acceleration (N, 3).
type FieldArrays<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>);

/// A homogeneous body (abstract: build a `Sphere`, `Spheroid`, `Ellipsoid`, `Disk` or
/// `PointMass`). Body frame: centroid at the origin, a spheroid's symmetry axis and an
/// ellipsoid's `c` axis along z, a disk in the x–y plane.
#[pyclass(module = "surfgrav", subclass, frozen)]
#[derive(Debug)]
pub struct Body {
    pub(crate) core: Arc<Core>,
}

impl Body {
    fn init(core: Core) -> PyClassInitializer<Self> {
        PyClassInitializer::from(Body {
            core: Arc::new(core),
        })
    }
}

/// The field of `p` at every point, in parallel over chunks of points (one dynamic dispatch
/// per chunk is paid through `&dyn`; the formula dominates).
fn fields(p: &dyn Potential, points: &[[f64; 3]]) -> (Vec<f64>, Vec<f64>) {
    const CHUNK: usize = 256;
    let n = points.len();
    let mut potential = vec![0.0; n];
    let mut acceleration = vec![0.0; 3 * n];
    let serial = |phi: &mut [f64], acc: &mut [f64], pts: &[[f64; 3]]| {
        for (i, r) in pts.iter().enumerate() {
            let f = p.field(&Vec3::new(r[0], r[1], r[2]));
            phi[i] = f.potential;
            acc[3 * i..3 * i + 3].copy_from_slice(f.acceleration.as_slice());
        }
    };
    if n <= CHUNK {
        // Not worth waking the thread pool.
        serial(&mut potential, &mut acceleration, points);
        return (potential, acceleration);
    }
    potential
        .par_chunks_mut(CHUNK)
        .zip(acceleration.par_chunks_mut(3 * CHUNK))
        .zip(points.par_chunks(CHUNK))
        .for_each(|((phi, acc), pts)| serial(phi, acc, pts));
    (potential, acceleration)
}

/// The CLI's message for a field that is not finite at `points[i]`.
fn not_finite_message(core: &Core, i: usize, r: &[f64; 3], potential: f64) -> String {
    let at = format!(
        "points[{i}] = ({}, {}, {})",
        compact(r[0]),
        compact(r[1]),
        compact(r[2])
    );
    if core.potential().bounding_radius() == 0.0 {
        format!("{at} is the position of the point mass, where its potential is infinite")
    } else if core.spec().is_some_and(|s| s.kind == BodyKind::Disk) && potential.is_finite() {
        format!(
            "{at} lies on the disk's rim, where the in-plane attraction is infinite (it grows \
             like 2Gσ·ln(8R/d) at a distance d from the rim); the potential there is finite, \
             Φ = {}: move the point off the rim",
            surfgrav_scenarios::cli::significant(potential, 10)
        )
    } else {
        format!("the field at {at} is not finite for this body")
    }
}

#[pymethods]
impl Body {
    /// The field at points given in the body frame.
    ///
    /// `points` is an (N, 3) float64 numpy array. Returns `(potential, acceleration)`: an (N,)
    /// array of Φ (negative, → −GM/r far away) and an (N, 3) array of a = −∇Φ. Evaluation is
    /// total: points inside a solid get the interior potential, points in a disk's plane the
    /// lamina potential. Runs in parallel over the points with the GIL released. Raises
    /// `InputError` for an array of the wrong shape or dtype, a non-finite point, or a point
    /// where the field is infinite (a point mass's own position, a disk's rim).
    fn field<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<FieldArrays<'py>> {
        let pts = arrays::points(points, "points")?;
        let core = Arc::clone(&self.core);
        let (phi, acc) = compute(py, move || {
            let (phi, acc) = fields(core.potential(), &pts);
            let bad = (0..pts.len()).find(|&i| {
                !(phi[i].is_finite() && acc[3 * i..3 * i + 3].iter().all(|a| a.is_finite()))
            });
            match bad {
                Some(i) => Err(input(not_finite_message(&core, i, &pts[i], phi[i]))),
                None => Ok((phi, acc)),
            }
        })?;
        Ok((PyArray1::from_vec(py, phi), arrays::matrix(py, acc, 3)))
    }

    /// Total mass.
    #[getter]
    fn mass(&self) -> f64 {
        self.core.potential().mass()
    }

    /// The gravitational constant.
    #[getter(G)]
    fn gravitational_constant(&self) -> f64 {
        self.core.potential().gravitational_constant()
    }

    /// Volume density (mass per area for a disk); None for a point mass.
    #[getter]
    fn density(&self) -> Option<f64> {
        let d = self.core.engine.density();
        d.is_finite().then_some(d)
    }

    /// Volume (0 for a point mass and a disk).
    #[getter]
    fn volume(&self) -> f64 {
        self.core.potential().volume()
    }

    /// Radius of the smallest centred sphere holding the body.
    #[getter]
    fn bounding_radius(&self) -> f64 {
        self.core.engine.bounding_radius()
    }

    /// The body kind: "point", "sphere", "spheroid", "ellipsoid", "disk" or "polyhedron".
    #[getter]
    fn kind(&self) -> String {
        self.core
            .describe()
            .split(':')
            .next()
            .unwrap_or_default()
            .to_string()
    }

    /// The body as the command line's `--body`/`--a`/`--b` spec
    /// (e.g. `spheroid:equatorial=1,polar=0.25,mass=1`); G is given separately (`--g`). None
    /// for a polyhedron (the command line reads meshes from files).
    #[getter]
    fn spec(&self) -> Option<String> {
        self.core.spec().map(ToString::to_string)
    }

    /// The inertia tensor about the centroid in the body frame, a (3, 3) array; None for a
    /// point mass.
    fn inertia<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.core.engine.inertia().map(|i| {
            let m = i.tensor();
            let flat: Vec<f64> = (0..3)
                .flat_map(|r| (0..3).map(move |c| (r, c)))
                .map(|(r, c)| m[(r, c)])
                .collect();
            arrays::matrix(py, flat, 3)
        })
    }

    fn __repr__(&self) -> String {
        let g = self.core.g;
        let mut args: Vec<String> = Vec::new();
        let (name, amount) = match &self.core.described {
            Described::Spec(spec) => {
                let d = &spec.dimensions;
                let name = match spec.kind {
                    BodyKind::Point => "PointMass",
                    BodyKind::Sphere => {
                        args.push(format!("radius={}", d[0]));
                        "Sphere"
                    }
                    BodyKind::Spheroid => {
                        args.push(format!("equatorial_radius={}", d[0]));
                        args.push(format!("polar_radius={}", d[1]));
                        "Spheroid"
                    }
                    BodyKind::Ellipsoid => {
                        args.push(format!("semi_axes=({}, {}, {})", d[0], d[1], d[2]));
                        "Ellipsoid"
                    }
                    BodyKind::Disk => {
                        args.push(format!("radius={}", d[0]));
                        "Disk"
                    }
                };
                (name, spec.amount)
            }
            Described::Mesh(m) => {
                let (v, f) = self
                    .core
                    .engine
                    .as_polyhedron()
                    .map_or((0, 0), |p| (p.vertices().len(), p.faces().len()));
                args.push(format!("source={:?}", m.source));
                args.push(format!("vertices={v}"));
                args.push(format!("faces={f}"));
                ("Polyhedron", m.amount)
            }
        };
        match amount {
            Amount::Mass(m) => args.push(format!("mass={m}")),
            Amount::Density(r) => args.push(format!("density={r}")),
        }
        if g != 1.0 {
            args.push(format!("G={g}"));
        }
        format!("{name}({})", args.join(", "))
    }
}

/// A point mass.
///
/// `PointMass(mass, *, G=1.0)`.
#[pyclass(module = "surfgrav", extends = Body, frozen)]
pub struct PointMass;

#[pymethods]
impl PointMass {
    #[new]
    #[pyo3(signature = (mass, *, G = 1.0))]
    #[allow(non_snake_case)]
    fn new(mass: f64, G: f64) -> PyResult<PyClassInitializer<Self>> {
        let core = Core::new(BodyKind::Point, vec![], Amount::Mass(mass), G)?;
        Ok(Body::init(core).add_subclass(PointMass))
    }
}

/// A homogeneous sphere.
///
/// `Sphere(radius, mass=None, *, density=None, G=1.0)`: give mass or density.
#[pyclass(module = "surfgrav", extends = Body, frozen)]
pub struct Sphere;

#[pymethods]
impl Sphere {
    #[new]
    #[pyo3(signature = (radius, mass = None, *, density = None, G = 1.0))]
    #[allow(non_snake_case)]
    fn new(
        radius: f64,
        mass: Option<f64>,
        density: Option<f64>,
        G: f64,
    ) -> PyResult<PyClassInitializer<Self>> {
        let amount = amount("sphere", mass, density)?;
        let core = Core::new(BodyKind::Sphere, vec![radius], amount, G)?;
        Ok(Body::init(core).add_subclass(Sphere))
    }

    /// Radius.
    #[getter]
    fn radius(slf: &Bound<'_, Self>) -> f64 {
        slf.as_super().get().core.dimension(0)
    }
}

/// A homogeneous spheroid, symmetric about its body z axis: oblate (polar < equatorial),
/// prolate (polar > equatorial) or a sphere.
///
/// `Spheroid(equatorial_radius, polar_radius, mass=None, *, density=None, G=1.0)`.
#[pyclass(module = "surfgrav", extends = Body, frozen)]
pub struct Spheroid;

#[pymethods]
impl Spheroid {
    #[new]
    #[pyo3(signature = (equatorial_radius, polar_radius, mass = None, *, density = None, G = 1.0))]
    #[allow(non_snake_case)]
    fn new(
        equatorial_radius: f64,
        polar_radius: f64,
        mass: Option<f64>,
        density: Option<f64>,
        G: f64,
    ) -> PyResult<PyClassInitializer<Self>> {
        let amount = amount("spheroid", mass, density)?;
        let core = Core::new(
            BodyKind::Spheroid,
            vec![equatorial_radius, polar_radius],
            amount,
            G,
        )?;
        Ok(Body::init(core).add_subclass(Spheroid))
    }

    /// Equatorial radius (the x and y semi-axes).
    #[getter]
    fn equatorial_radius(slf: &Bound<'_, Self>) -> f64 {
        slf.as_super().get().core.dimension(0)
    }

    /// Polar radius (the z semi-axis).
    #[getter]
    fn polar_radius(slf: &Bound<'_, Self>) -> f64 {
        slf.as_super().get().core.dimension(1)
    }
}

/// A homogeneous triaxial ellipsoid with semi-axes a, b, c along its body x, y, z axes.
///
/// `Ellipsoid(semi_axes=None, mass=None, *, a=None, b=None, c=None, density=None, G=1.0)`:
/// give `semi_axes=(a, b, c)` or `a=`, `b=`, `c=`.
#[pyclass(module = "surfgrav", extends = Body, frozen)]
pub struct Ellipsoid;

#[pymethods]
impl Ellipsoid {
    #[new]
    #[pyo3(signature = (semi_axes = None, mass = None, *, a = None, b = None, c = None, density = None, G = 1.0))]
    #[allow(non_snake_case, clippy::too_many_arguments)]
    fn new(
        semi_axes: Option<&Bound<'_, PyAny>>,
        mass: Option<f64>,
        a: Option<f64>,
        b: Option<f64>,
        c: Option<f64>,
        density: Option<f64>,
        G: f64,
    ) -> PyResult<PyClassInitializer<Self>> {
        let axes =
            match (semi_axes, a, b, c) {
                (Some(s), None, None, None) => {
                    let v = arrays::vector(s, "semi_axes")?;
                    vec![v.x, v.y, v.z]
                }
                (None, Some(a), Some(b), Some(c)) => vec![a, b, c],
                (Some(_), _, _, _) => return Err(InputError::new_err(
                    "give the semi-axes either as semi_axes=(a, b, c) or as a=, b=, c=, not both",
                )),
                (None, a, b, _) => {
                    let missing = if a.is_none() {
                        "a"
                    } else if b.is_none() {
                        "b"
                    } else {
                        "c"
                    };
                    return Err(InputError::new_err(format!(
                        "an ellipsoid needs `{missing}` (or semi_axes=(a, b, c))"
                    )));
                }
            };
        let amount = amount("ellipsoid", mass, density)?;
        let core = Core::new(BodyKind::Ellipsoid, axes, amount, G)?;
        Ok(Body::init(core).add_subclass(Ellipsoid))
    }

    /// The semi-axes (a, b, c) along the body x, y, z axes.
    #[getter]
    fn semi_axes<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let core = &slf.as_super().get().core;
        let d = [core.dimension(0), core.dimension(1), core.dimension(2)];
        PyTuple::new(slf.py(), d)
    }
}

/// A uniform thin disk of radius R in its body x–y plane (surface density mass / πR²).
///
/// `Disk(radius, mass, *, G=1.0)`.
#[pyclass(module = "surfgrav", extends = Body, frozen)]
pub struct Disk;

#[pymethods]
impl Disk {
    #[new]
    #[pyo3(signature = (radius, mass, *, G = 1.0))]
    #[allow(non_snake_case)]
    fn new(radius: f64, mass: f64, G: f64) -> PyResult<PyClassInitializer<Self>> {
        let core = Core::new(BodyKind::Disk, vec![radius], Amount::Mass(mass), G)?;
        Ok(Body::init(core).add_subclass(Disk))
    }

    /// Radius.
    #[getter]
    fn radius(slf: &Bound<'_, Self>) -> f64 {
        slf.as_super().get().core.dimension(0)
    }
}

/// The length unit of mesh coordinates, with the CLI's message.
fn mesh_unit(units: &str) -> PyResult<LengthUnit> {
    units
        .parse::<LengthUnit>()
        .map_err(|e| InputError::new_err(e.to_string()))
}

/// Validates `mesh` (already in metres) and builds the polyhedron's core.
fn polyhedron_core(
    mesh: &Mesh,
    source: String,
    unit: LengthUnit,
    amount: Amount,
    g: f64,
) -> Result<Core, Failure> {
    let body = match amount {
        Amount::Mass(m) => PolyhedronBody::with_mass(mesh, m),
        Amount::Density(d) => PolyhedronBody::with_density(mesh, d),
    }
    .map_err(|e| input(e.to_string()))?
    .with_gravitational_constant(g)
    .map_err(|e| input(e.to_string()))?;
    let centroid = body.centroid();
    let engine = EngineBody::polyhedron(body).map_err(|e| input(e.to_string()))?;
    Ok(Core {
        described: Described::Mesh(MeshInfo {
            source,
            amount,
            unit,
            centroid,
        }),
        g,
        engine,
    })
}

/// A homogeneous polyhedron: a closed triangle mesh of uniform density, by the closed form of
/// Werner & Scheeres (1997) (and, far away, its certified exterior expansion).
///
/// `Polyhedron(vertices, faces, mass=None, *, density=None, units="m", G=1.0)`: `vertices` an
/// (N, 3) float64 array, `faces` an (M, 3) integer array of 0-based vertex indices,
/// counter-clockwise seen from outside. Or read a file: `Polyhedron.from_obj(path, ...)`
/// (Wavefront OBJ, triangles) or `Polyhedron.from_csv(vertex_file, facet_file, ...)` (the
/// Didymos radar model's pair: `filler,x,y,z` and 1-based `i,j,k,,`). Coordinates are in
/// `units` ("m" or "km") and converted to metres. The mesh is validated (closed, consistently
/// outward-oriented, no degenerate face, no self-intersection): a bad one raises `InputError`
/// naming the face, edge or vertex.
///
/// The body frame has its origin at the mesh's centroid (`centroid`, in the input mesh's frame,
/// metres, is subtracted from every vertex); its axes are the mesh's.
#[pyclass(module = "surfgrav", extends = Body, frozen)]
pub struct Polyhedron;

impl Polyhedron {
    fn core_of<'py>(slf: &'py Bound<'py, Self>) -> &'py Core {
        &slf.as_super().get().core
    }

    fn info<'py>(slf: &'py Bound<'py, Self>) -> Option<&'py MeshInfo> {
        match &Self::core_of(slf).described {
            Described::Mesh(m) => Some(m),
            Described::Spec(_) => None,
        }
    }

    /// A mesh read by `read` (with the GIL released) into a new Python `Polyhedron`.
    fn from_file(
        py: Python<'_>,
        source: String,
        read: impl FnOnce(LengthUnit) -> Result<Mesh, Failure> + Send,
        mass: Option<f64>,
        density: Option<f64>,
        units: &str,
        g: f64,
    ) -> PyResult<Py<Polyhedron>> {
        let amount = amount("polyhedron", mass, density)?;
        let unit = mesh_unit(units)?;
        let core = compute(py, move || {
            let mesh = read(unit)?;
            polyhedron_core(&mesh, source, unit, amount, g)
        })?;
        Py::new(py, Body::init(core).add_subclass(Polyhedron))
    }
}

#[pymethods]
impl Polyhedron {
    #[new]
    #[pyo3(signature = (vertices, faces, mass = None, *, density = None, units = "m", G = 1.0))]
    #[allow(non_snake_case)]
    fn new(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        faces: &Bound<'_, PyAny>,
        mass: Option<f64>,
        density: Option<f64>,
        units: &str,
        G: f64,
    ) -> PyResult<PyClassInitializer<Self>> {
        let amount = amount("polyhedron", mass, density)?;
        let unit = mesh_unit(units)?;
        let points = arrays::points(vertices, "vertices")?;
        let faces = arrays::index_triples(faces, "faces")?;
        let core = compute(py, move || {
            let scale = unit.metres();
            let mesh = Mesh {
                vertices: points
                    .iter()
                    .map(|p| Vec3::new(p[0], p[1], p[2]) * scale)
                    .collect(),
                faces,
            };
            polyhedron_core(&mesh, "arrays".into(), unit, amount, G)
        })?;
        Ok(Body::init(core).add_subclass(Polyhedron))
    }

    /// Reads a Wavefront OBJ file (`v` and `f` lines, every face a triangle).
    ///
    /// `Polyhedron.from_obj(path, mass=None, *, density=None, units="m", G=1.0)`.
    #[staticmethod]
    #[pyo3(signature = (path, mass = None, *, density = None, units = "m", G = 1.0))]
    #[allow(non_snake_case)]
    fn from_obj(
        py: Python<'_>,
        path: PathBuf,
        mass: Option<f64>,
        density: Option<f64>,
        units: &str,
        G: f64,
    ) -> PyResult<Py<Polyhedron>> {
        let source = path.display().to_string();
        let read = move |unit| Mesh::read_obj(&path, unit).map_err(|e| input(e.to_string()));
        Self::from_file(py, source, read, mass, density, units, G)
    }

    /// Reads a vertex/facet CSV pair (the Didymos radar model's format: vertex lines
    /// `filler,x,y,z`, facet lines `i,j,k,,` with 1-based indices).
    ///
    /// `Polyhedron.from_csv(vertex_file, facet_file, mass=None, *, density=None, units="m",
    /// G=1.0)`.
    #[staticmethod]
    #[pyo3(signature = (vertex_file, facet_file, mass = None, *, density = None, units = "m", G = 1.0))]
    #[allow(non_snake_case)]
    fn from_csv(
        py: Python<'_>,
        vertex_file: PathBuf,
        facet_file: PathBuf,
        mass: Option<f64>,
        density: Option<f64>,
        units: &str,
        G: f64,
    ) -> PyResult<Py<Polyhedron>> {
        let source = format!("{} + {}", vertex_file.display(), facet_file.display());
        let read = move |unit| {
            Mesh::read_vertex_facet_csv(&vertex_file, &facet_file, unit)
                .map_err(|e| input(e.to_string()))
        };
        Self::from_file(py, source, read, mass, density, units, G)
    }

    /// Vertices in the body frame (centroid at the origin), metres, an (N, 3) array.
    #[getter]
    fn vertices<'py>(slf: &Bound<'py, Self>) -> Bound<'py, PyArray2<f64>> {
        let flat: Vec<f64> = Self::core_of(slf)
            .engine
            .as_polyhedron()
            .map(|p| p.vertices().iter().flat_map(|v| [v.x, v.y, v.z]).collect())
            .unwrap_or_default();
        arrays::matrix(slf.py(), flat, 3)
    }

    /// Faces as 0-based vertex indices, counter-clockwise seen from outside, an (M, 3) int64
    /// array.
    #[getter]
    fn faces<'py>(slf: &Bound<'py, Self>) -> Bound<'py, PyArray2<i64>> {
        let flat: Vec<i64> = Self::core_of(slf)
            .engine
            .as_polyhedron()
            .map(|p| p.faces().iter().flat_map(|f| f.map(i64::from)).collect())
            .unwrap_or_default();
        let n = flat.len() / 3;
        numpy::ndarray::Array2::from_shape_vec((n, 3), flat)
            .map(|a| numpy::IntoPyArray::into_pyarray(a, slf.py()))
            .unwrap_or_else(|_| PyArray2::zeros(slf.py(), (0, 3), false))
    }

    /// The input mesh's centroid in its own frame (metres), a (3,) array: subtracted from every
    /// vertex to make the body frame.
    #[getter]
    fn centroid<'py>(slf: &Bound<'py, Self>) -> Bound<'py, PyArray1<f64>> {
        let c = Self::info(slf).map_or(Vec3::zeros(), |m| m.centroid);
        arrays::vec3_array(slf.py(), &c)
    }

    /// The input coordinates' unit: "m" or "km".
    #[getter]
    fn units(slf: &Bound<'_, Self>) -> &'static str {
        match Self::info(slf).map(|m| m.unit) {
            Some(LengthUnit::Kilometres) => "km",
            _ => "m",
        }
    }

    /// Where the mesh came from: "arrays", the OBJ file, or "VERTICES + FACETS".
    #[getter]
    fn source(slf: &Bound<'_, Self>) -> String {
        Self::info(slf)
            .map(|m| m.source.clone())
            .unwrap_or_default()
    }
}
