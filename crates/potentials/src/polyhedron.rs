//! The homogeneous polyhedron: a closed, outward-oriented triangle mesh of uniform density,
//! by the closed form of Werner & Scheeres (1997, *Celest. Mech. Dyn. Astron.* 65, 313),
//! rederived here in this crate's sign convention.
//!
//! # Formulas
//!
//! Let $\mathbf p$ be the field point, $\mathbf n_f$ the outward unit normal of face $f$,
//! $h_f = \mathbf n_f\cdot(\mathbf v - \mathbf p)$ for any vertex $\mathbf v$ of $f$ (positive
//! when $\mathbf p$ is on the inner side of $f$'s plane) and
//! $$I_f(\mathbf p) = \int_f \frac{\mathrm dA}{|\mathbf x - \mathbf p|}$$
//! the potential of face $f$ as a unit lamina. Since $\nabla\cdot\frac{\mathbf x - \mathbf p}
//! {|\mathbf x - \mathbf p|} = \frac{2}{|\mathbf x - \mathbf p|}$ and $\nabla_x
//! \frac{1}{|\mathbf x - \mathbf p|} = -\frac{\mathbf x - \mathbf p}{|\mathbf x - \mathbf p|^3}$,
//! the divergence theorem gives, inside and outside alike,
//! $$\Phi = -\frac{G\rho}{2}\sum_f h_f I_f, \qquad \mathbf a = -\nabla\Phi
//!   = -G\rho \sum_f \mathbf n_f I_f .$$
//! The face integral, by the divergence theorem in the face's plane with
//! $\nabla_2\cdot[(\mathbf x - \mathbf p')(R - |h|)/\rho^2] = 1/R$:
//! $$I_f = \sum\_{e\in f} d\_{fe} L_e - h_f\\,\omega_f,\qquad
//!   L_e = \ln\frac{r_i + r_j + e\_{ij}}{r_i + r_j - e\_{ij}},\qquad
//!   \omega_f = 2\\,\mathrm{atan2}\bigl(2A_f h_f,\\;
//!   r_1r_2r_3 + r_1\\,\mathbf r_2\cdot\mathbf r_3 + r_2\\,\mathbf r_3\cdot\mathbf r_1 +
//!   r_3\\,\mathbf r_1\cdot\mathbf r_2\bigr),$$
//! with $\mathbf r_i = \mathbf v_i - \mathbf p$, $d\_{fe} = \mathbf m\_{fe}\cdot(\mathbf v_i -
//! \mathbf p)$ the distance from $\mathbf p$'s projection to edge $e$ along the edge's outward
//! in-plane normal $\mathbf m\_{fe}$, and $\omega_f$ the signed solid angle of $f$ seen from
//! $\mathbf p$ (van Oosterom & Strackee 1983; the triple product $\mathbf r_1\cdot(\mathbf r_2
//! \times\mathbf r_3) = 2A_f h_f$ exactly). Werner & Scheeres write the same sums with the edge
//! dyads $\mathsf E_e$ and face dyads $\mathsf F_f$ and a positive potential $U = -\Phi$.
//!
//! # Numerics
//!
//! - **Singular limits.** On a face's plane $h_f = 0$ and $\omega_f$'s jump of $4\pi$ is
//!   multiplied by zero. $L_e$ diverges on edge $e$ itself, where its factor $d\_{fe}$ vanishes
//!   like $\rho\ln\rho$; there $r_i + r_j - e\_{ij}$ is computed without cancellation as
//!   $2|\mathbf r_i\times\mathbf r_j|^2 / ((r_ir_j - \mathbf r_i\cdot\mathbf r_j)(r_i + r_j +
//!   e\_{ij}))$ whenever $\mathbf r_i\cdot\mathbf r_j < 0$, and exactly on the edge (or at a
//!   vertex) the term is its limit 0. So Φ and **a** are continuous across and on faces, edges
//!   and vertices, and finite everywhere.
//! - **Far field.** Each $I_f \approx A_f/r$ comes from edge terms of size $e\\,$ that cancel, and
//!   the sum over faces cancels again to $V/r$: the rounding error grows like
//!   $\varepsilon (r/R)^2$. Beyond [`FAR_FIELD_RADII`] circumscribing radii $R$ (about the
//!   centroid) the field is the exterior multipole expansion instead, with moments exact to
//!   rounding and the degree chosen per point so that the rigorous truncation bound stays below
//!   half an ulp (module `multipole`).
//! - **Mass properties** by signed tetrahedra about a point near the body (the mean vertex),
//!   the second moments about the centroid itself (no parallel-axis cancellation).

mod local;
mod mesh;
pub(crate) mod multipole;
mod reach;
mod validate;

use std::f64::consts::PI;
use std::sync::OnceLock;

use nalgebra::{Matrix3, Rotation3};
use rayon::prelude::*;

use crate::error::{positive, representable, BodyError};
use crate::{Field, Potential, Real, Region, Vec3};

pub use local::{LocalExpansion, LOCAL_MAX_DEGREE};
pub use mesh::{LengthUnit, Mesh};
pub use reach::{REACH_DEGREE, REACH_RADII};
pub use validate::MeshError;

use multipole::Multipole;

/// Beyond this many circumscribing radii (about the centroid) the field comes from the
/// certified multipole expansion. The direct sum's rounding grows like ε (r/R)²; measured
/// against the expansion on the cube and KW4 Beta it is ≤ 1.7e-14 at 6 radii (≤ 6.6e-14 at 8,
/// ≤ 1.1e-13 at 16), so 6 keeps it an order of magnitude inside
/// [`crate::tolerance::POLYHEDRON_REL`].
pub const FAR_FIELD_RADII: Real = 6.0;

/// Cost of one [`Potential::field`] evaluation per face, relative to one of a homogeneous
/// spheroid ([`Potential::field_cost`] is this times the face count). Measured with
/// `cargo run --release -p surfgrav-interaction --example polyhedron_pairs -- --field-cost`
/// (serial, best of five passes, 200 to 20,000 points spread over a sphere about the centroid,
/// the spheroid of the circumscribing radius and aspect 0.6 over the same sphere): at 1.05 to
/// 5 circumscribing radii, where the direct sum is used, the Didymos radar model (1,996 faces)
/// costs 1.55 to 1.93 spheroid evaluations per face, KW4 Beta (2,292) 1.10 to 2.18 and KW4
/// Alpha (9,168) 0.98 to 1.62; 1.6 is the median. Beyond [`FAR_FIELD_RADII`] the multipole
/// expansion costs 36 to 60 spheroid evaluations whatever the face count: the value here is
/// the near field's, the one that matters when a surface integral runs close to the body.
pub const FIELD_COST_PER_FACE: Real = 1.6;

/// Beyond this many circumscribing radii the gravity-gradient tensor comes from the
/// expansion: the smallest distance at which the stored degree meets the Hessian's (looser,
/// Cauchy-estimate) truncation bound.
pub const GRADIENT_FAR_FIELD_RADII: Real = 13.0;

/// The multipole degree the truncation bound needs at [`FAR_FIELD_RADII`] (22).
fn max_degree() -> usize {
    multipole::degree_for(1.0 / FAR_FIELD_RADII, 60).expect("the bound is met below degree 60")
}

/// Why a polyhedron could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PolyhedronError {
    /// The mesh is not a valid closed, outward-oriented surface.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// A mass, density or G was not a positive finite number.
    #[error(transparent)]
    Body(#[from] BodyError),
}

/// A homogeneous polyhedron: a closed triangle mesh (validated) with uniform density.
///
/// Lengths in the mesh's units after [`LengthUnit`] conversion (metres for SI work), mass in
/// the user's mass unit. The body frame is the mesh's own frame: call
/// [`Polyhedron::to_principal_axes`] to move it to the crate's convention (centroid at the
/// origin, principal axes along x, y, z with the largest moment about z).
#[derive(Debug, Clone)]
pub struct Polyhedron {
    vertices: Vec<Vec3>,
    faces: Vec<[u32; 3]>,
    edges: Vec<EdgeGeometry>,
    face_geometry: Vec<FaceGeometry>,
    mass: Real,
    density: Real,
    volume: Real,
    centroid: Vec3,
    /// Second moments ∫ (x − c)(x − c)ᵀ dV about the centroid (volume units × length²).
    covariance: Matrix3<Real>,
    gravitational_constant: Real,
    bounding_radius: Real,
    circumscribing_radius: Real,
    multipole: OnceLock<Multipole>,
    /// The higher-degree expansion of [`reach`], built on first use.
    reach: OnceLock<Multipole>,
}

#[derive(Debug, Clone, Copy)]
struct EdgeGeometry {
    vertices: [u32; 2],
    length: Real,
}

#[derive(Debug, Clone, Copy)]
struct FaceGeometry {
    normal: Vec3,
    /// n · v for the face's vertices.
    offset: Real,
    twice_area: Real,
    vertices: [u32; 3],
    /// Edge k joins vertex k and vertex k+1.
    edges: [u32; 3],
    /// Outward in-plane unit normals of the edges and m · v on them.
    edge_normals: [Vec3; 3],
    edge_offsets: [Real; 3],
}

/// The moving of a body to its centroid and principal axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrincipalFrame {
    /// The old body-frame position of the centroid (subtracted from every vertex).
    pub centroid: Vec3,
    /// The rotation applied after the translation: new = rotation · (old − centroid). Its rows
    /// are the principal axes in the old frame.
    pub rotation: Rotation3<Real>,
    /// Principal moments of inertia A ≤ B ≤ C about the new x, y, z axes (mass × length²).
    pub moments: Vec3,
}

impl Polyhedron {
    /// A polyhedron of total `mass` (G = 1) bounded by `mesh`, which is validated first.
    pub fn with_mass(mesh: &Mesh, mass: Real) -> Result<Self, PolyhedronError> {
        let mass = positive("mass", mass)?;
        let geometry = Geometry::new(mesh)?;
        let density = representable("density", mass / geometry.volume)?;
        Ok(geometry.into_body(mass, density))
    }

    /// A polyhedron of uniform `density` (G = 1) bounded by `mesh`, validated first.
    pub fn with_density(mesh: &Mesh, density: Real) -> Result<Self, PolyhedronError> {
        let density = positive("density", density)?;
        let geometry = Geometry::new(mesh)?;
        let mass = representable("mass", density * geometry.volume)?;
        Ok(geometry.into_body(mass, density))
    }

    /// The same body with gravitational constant `g` (positive, finite).
    pub fn with_gravitational_constant(mut self, g: Real) -> Result<Self, BodyError> {
        self.gravitational_constant = positive("gravitational_constant", g)?;
        Ok(self)
    }

    /// Uniform density (mass / volume).
    pub fn density(&self) -> Real {
        self.density
    }

    /// The centroid (centre of mass) in the body frame.
    pub fn centroid(&self) -> Vec3 {
        self.centroid
    }

    /// The inertia tensor about the centroid, body frame (mass × length²).
    pub fn inertia_tensor(&self) -> Matrix3<Real> {
        let c = &self.covariance;
        (Matrix3::identity() * c.trace() - c) * self.density
    }

    /// Vertices (body frame).
    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    /// Faces as vertex indices, counter-clockwise seen from outside.
    pub fn faces(&self) -> &[[u32; 3]] {
        &self.faces
    }

    /// Radius of the smallest sphere about the centroid containing the body.
    pub fn circumscribing_radius(&self) -> Real {
        self.circumscribing_radius
    }

    /// The body moved to its centroid and principal axes (A ≤ B ≤ C about x, y, z; a
    /// right-handed frame), with the transformation applied.
    pub fn to_principal_axes(&self) -> (Self, PrincipalFrame) {
        let eigen = self.inertia_tensor().symmetric_eigen();
        let mut order = [0usize, 1, 2];
        order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
        let mut axes = order.map(|i| {
            let v: Vec3 = eigen.eigenvectors.column(i).into();
            // Deterministic sign: the largest component positive.
            let k = v.iamax();
            if v[k] < 0.0 {
                -v
            } else {
                v
            }
        });
        if axes[0].cross(&axes[1]).dot(&axes[2]) < 0.0 {
            axes[2] = -axes[2];
        }
        let matrix = Matrix3::from_rows(&[
            axes[0].transpose(),
            axes[1].transpose(),
            axes[2].transpose(),
        ]);
        let rotation = Rotation3::from_matrix_unchecked(matrix);
        let mesh = Mesh {
            vertices: self
                .vertices
                .iter()
                .map(|v| rotation * (v - self.centroid))
                .collect(),
            faces: self.faces.iter().map(|f| f.map(|i| i as usize)).collect(),
        };
        let geometry = Geometry::new(&mesh).expect("a rigid motion keeps a valid mesh valid");
        let mut body = geometry.into_body(self.mass, self.density);
        body.gravitational_constant = self.gravitational_constant;
        let moments = Vec3::new(
            eigen.eigenvalues[order[0]],
            eigen.eigenvalues[order[1]],
            eigen.eigenvalues[order[2]],
        );
        let frame = PrincipalFrame {
            centroid: self.centroid,
            rotation,
            moments,
        };
        (body, frame)
    }

    /// Fields at many body-frame points, in parallel over the points (rayon).
    pub fn fields(&self, points: &[Vec3]) -> Vec<Field> {
        points.par_iter().map(|p| self.field(p)).collect()
    }

    /// The field by the closed-form sum over faces and edges, at any distance (no multipole
    /// switch): for tests and for measuring the far-field rounding it would suffer.
    pub fn field_direct(&self, p: &Vec3) -> Field {
        let mut scratch = Scratch::default();
        self.direct(p, &mut scratch)
    }

    /// The field by the multipole expansion, if `p` is far enough for the stored degree to
    /// meet the truncation bound; `None` otherwise.
    pub fn field_multipole(&self, p: &Vec3) -> Option<Field> {
        let mp = self.multipole();
        let r = (p - mp.centre).norm() / mp.radius;
        let degree = mp.degree_needed(r)?;
        Some(self.multipole_field(mp, p, degree))
    }

    /// The gravity-gradient tensor ∇a = −∇∇Φ at body-frame `r` (symmetric; units G · mass /
    /// length³): outside, its trace is 0; inside, −4πGρ. By the closed form
    /// ∇a = Gρ Σ_f Σ_e L_e n_f m_feᵀ − Gρ Σ_f ω_f n_f n_fᵀ (each face's share: n_f times
    /// ∇I_f = −Σ_e m_fe L_e + n_f ω_f), and beyond [`GRADIENT_FAR_FIELD_RADII`] by the
    /// expansion's Hessian, certified below 1.1e-16 of the tidal scale GM/r³ (the bound is
    /// looser than the potential's, hence the larger switch radius). The direct sum agrees
    /// with the expansion at the switch to ≤ 3e-14 on KW4 Alpha, Beta and Didymos. The tensor jumps
    /// by −4πGρ n nᵀ across a face and diverges logarithmically at an edge; exactly on an edge
    /// or a vertex the divergent edge terms are dropped (the value there is not meaningful).
    pub fn gravity_gradient(&self, r: &Vec3) -> Matrix3<Real> {
        let mp = self.multipole();
        let distance = (r - mp.centre).norm() / mp.radius;
        if distance >= GRADIENT_FAR_FIELD_RADII || !distance.is_finite() {
            let q = 1.0 / distance;
            if let Some(degree) = (0..=mp.degree)
                .find(|&n| multipole::hessian_relative_bound(q, n) <= multipole::TRUNCATION_REL)
            {
                return mp.hessian(r, degree) * self.gravitational_constant;
            }
        }
        let mut rel = Vec::with_capacity(self.vertices.len());
        rel.extend(self.vertices.iter().map(|v| {
            let d = v - r;
            [d.x, d.y, d.z, d.norm()]
        }));
        let logs: Vec<Real> = self
            .edges
            .iter()
            .map(|e| {
                edge_log(
                    &rel[e.vertices[0] as usize],
                    &rel[e.vertices[1] as usize],
                    e.length,
                )
            })
            .collect();
        let mut t = Matrix3::zeros();
        for f in &self.face_geometry {
            let [r1, r2, r3] = f.vertices.map(|i| rel[i as usize]);
            let h = f.offset - f.normal.dot(r);
            let dot = |a: &[Real; 4], b: &[Real; 4]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let den = r1[3] * r2[3] * r3[3]
                + r1[3] * dot(&r2, &r3)
                + r2[3] * dot(&r3, &r1)
                + r3[3] * dot(&r1, &r2);
            let omega = 2.0 * half_solid_angle(f.twice_area * h, den);
            let mut m = Vec3::zeros();
            for k in 0..3 {
                m += f.edge_normals[k] * logs[f.edges[k] as usize];
            }
            t += f.normal * (m - f.normal * omega).transpose();
        }
        let g_rho = self.gravitational_constant * self.density;
        // Symmetric in exact arithmetic (the edge dyads pair up); symmetrise the rounding.
        (t + t.transpose()) * (0.5 * g_rho)
    }

    fn multipole(&self) -> &Multipole {
        self.multipole.get_or_init(|| {
            Multipole::new(
                &self.vertices,
                &self.faces,
                self.density,
                self.centroid,
                self.circumscribing_radius,
                max_degree(),
            )
        })
    }

    fn multipole_field(&self, mp: &Multipole, p: &Vec3, degree: usize) -> Field {
        let mut scratch = Vec::new();
        let (sum, grad) = mp.evaluate(p, degree, &mut scratch);
        let g = self.gravitational_constant;
        Field {
            potential: -g * sum,
            acceleration: grad * g,
        }
    }

    fn direct(&self, p: &Vec3, scratch: &mut Scratch) -> Field {
        let Scratch { rel, logs } = scratch;
        rel.clear();
        rel.extend(self.vertices.iter().map(|v| {
            let r = v - p;
            [r.x, r.y, r.z, r.norm()]
        }));
        logs.clear();
        logs.extend(self.edges.iter().map(|e| {
            let a = rel[e.vertices[0] as usize];
            let b = rel[e.vertices[1] as usize];
            edge_log(&a, &b, e.length)
        }));
        let mut sum_phi = 0.0;
        let mut sum_a = Vec3::zeros();
        for f in &self.face_geometry {
            let [r1, r2, r3] = f.vertices.map(|i| rel[i as usize]);
            let h = f.offset - f.normal.dot(p);
            let dot = |a: &[Real; 4], b: &[Real; 4]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let den = r1[3] * r2[3] * r3[3]
                + r1[3] * dot(&r2, &r3)
                + r2[3] * dot(&r3, &r1)
                + r3[3] * dot(&r1, &r2);
            let omega = 2.0 * half_solid_angle(f.twice_area * h, den);
            let mut face = -h * omega;
            for k in 0..3 {
                let d = f.edge_offsets[k] - f.edge_normals[k].dot(p);
                face += d * logs[f.edges[k] as usize];
            }
            sum_phi += h * face;
            sum_a += f.normal * face;
        }
        let g_rho = self.gravitational_constant * self.density;
        Field {
            potential: -0.5 * g_rho * sum_phi,
            acceleration: sum_a * (-g_rho),
        }
    }

    /// Σ_f ω_f / 4π: 1 inside, 0 outside (the winding number).
    fn winding_number(&self, p: &Vec3) -> Real {
        let mut total = 0.0;
        for f in &self.face_geometry {
            let [r1, r2, r3] = f.vertices.map(|i| self.vertices[i as usize] - p);
            let (n1, n2, n3) = (r1.norm(), r2.norm(), r3.norm());
            let h = f.offset - f.normal.dot(p);
            let den = n1 * n2 * n3 + n1 * r2.dot(&r3) + n2 * r3.dot(&r1) + n3 * r1.dot(&r2);
            total += 2.0 * (f.twice_area * h).atan2(den);
        }
        total / (4.0 * PI)
    }

    /// Distance from `p` to the nearest face.
    fn distance_to_surface(&self, p: &Vec3) -> Real {
        self.faces
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(|i| self.vertices[i as usize]);
                validate::point_triangle_distance(p, &a, &b, &c)
            })
            .fold(Real::INFINITY, Real::min)
    }
}

/// Per-call buffers: vertex offsets with their norms, and the edge logarithms.
#[derive(Default)]
struct Scratch {
    rel: Vec<[Real; 4]>,
    logs: Vec<Real>,
}

/// atan2(num, den) by one `atan` (half the cost of libm's `atan2` here); on the face's plane
/// inside the face (num = ±0, den < 0) either ±π, multiplied by h = 0 by the caller.
#[inline]
fn half_solid_angle(num: Real, den: Real) -> Real {
    if den > 0.0 {
        (num / den).atan()
    } else if den < 0.0 {
        (num / den).atan() + PI.copysign(num)
    } else {
        (PI / 2.0).copysign(num)
    }
}

/// $L_e$ for an edge of `length` seen from the point with offsets `a`, `b` (x, y, z, norm) to
/// its ends; its limit 0 on the edge itself (where its factor $d\_{fe}$ vanishes).
#[inline]
fn edge_log(a: &[Real; 4], b: &[Real; 4], length: Real) -> Real {
    let s = a[3] + b[3];
    let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let den = if dot < 0.0 {
        // Opposite sides of the point along the edge: s − e without cancellation.
        let cx = a[1] * b[2] - a[2] * b[1];
        let cy = a[2] * b[0] - a[0] * b[2];
        let cz = a[0] * b[1] - a[1] * b[0];
        2.0 * (cx * cx + cy * cy + cz * cz) / ((a[3] * b[3] - dot) * (s + length))
    } else {
        s - length
    };
    if den > 0.0 {
        // ln((s + e)/(s − e)) = ln(1 + 2e/(s − e)): far away the ratio is 1 + O(e/r), whose
        // rounding ln() would amplify by r/e.
        (2.0 * length / den).ln_1p()
    } else {
        0.0
    }
}

impl Potential for Polyhedron {
    fn as_typed(&self) -> crate::TypedPotential<'_> {
        crate::TypedPotential::Polyhedron(self)
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
        self.bounding_radius
    }

    /// [`Polyhedron::inertia_tensor`], validated (about the centroid, body frame).
    fn inertia(&self) -> Option<crate::InertiaTensor> {
        crate::InertiaTensor::new(self.inertia_tensor()).ok()
    }

    fn region(&self, r: &Vec3) -> Region {
        let scale = self.bounding_radius.max(r.norm());
        if self.distance_to_surface(r) <= 8.0 * Real::EPSILON * scale {
            Region::OnSurface
        } else if self.winding_number(r) > 0.5 {
            Region::Inside
        } else {
            Region::Outside
        }
    }

    /// [`FIELD_COST_PER_FACE`] times the face count: the direct sum's cost, which is what a
    /// surface integral near the body pays (see that constant for the measurement).
    fn field_cost(&self) -> Real {
        FIELD_COST_PER_FACE * self.faces.len() as Real
    }

    fn field(&self, r: &Vec3) -> Field {
        let offset = r - self.centroid;
        // Beyond 1e20 radii the quadrupole is below 1e-40 of the monopole: a point mass at the
        // centroid (which also keeps r² from overflowing in the expansion).
        if offset.norm() > 1e20 * self.circumscribing_radius {
            return crate::point_mass::kepler_field(self.gravitational_parameter(), &offset);
        }
        let far = offset.norm() >= FAR_FIELD_RADII * self.circumscribing_radius;
        if far || r.iter().any(|x| !x.is_finite()) {
            let mp = self.multipole();
            let distance = (r - mp.centre).norm() / mp.radius;
            if let Some(degree) = mp.degree_needed(distance) {
                return self.multipole_field(mp, r, degree);
            }
            if !distance.is_finite() {
                let nan = Real::NAN;
                return Field {
                    potential: nan,
                    acceleration: Vec3::repeat(nan),
                };
            }
        }
        self.field_direct(r)
    }
}

/// Validated mesh with its derived geometry and mass properties (density-free).
struct Geometry {
    vertices: Vec<Vec3>,
    faces: Vec<[u32; 3]>,
    edges: Vec<EdgeGeometry>,
    face_geometry: Vec<FaceGeometry>,
    volume: Real,
    centroid: Vec3,
    covariance: Matrix3<Real>,
    bounding_radius: Real,
    circumscribing_radius: Real,
}

impl Geometry {
    fn new(mesh: &Mesh) -> Result<Self, MeshError> {
        let checked = validate::validate(mesh)?;
        let vertices = mesh.vertices.clone();
        let faces: Vec<[u32; 3]> = mesh.faces.iter().map(|f| f.map(|i| i as u32)).collect();
        let edges: Vec<EdgeGeometry> = checked
            .edges
            .iter()
            .map(|&[i, j]| EdgeGeometry {
                vertices: [i as u32, j as u32],
                length: (vertices[j] - vertices[i]).norm(),
            })
            .collect();
        let face_geometry = faces
            .iter()
            .zip(&checked.face_edges)
            .map(|(f, fe)| {
                let [a, b, c] = f.map(|i| vertices[i as usize]);
                let cross = (b - a).cross(&(c - a));
                let twice_area = cross.norm();
                let normal = cross / twice_area;
                let offset = normal.dot(&((a + b + c) / 3.0));
                let corners = [a, b, c];
                let mut edge_normals = [Vec3::zeros(); 3];
                let mut edge_offsets = [0.0; 3];
                for k in 0..3 {
                    let (p, q) = (corners[k], corners[(k + 1) % 3]);
                    let m = (q - p).cross(&normal).normalize();
                    edge_normals[k] = m;
                    edge_offsets[k] = m.dot(&((p + q) * 0.5));
                }
                FaceGeometry {
                    normal,
                    offset,
                    twice_area,
                    vertices: *f,
                    edges: fe.map(|e| e as u32),
                    edge_normals,
                    edge_offsets,
                }
            })
            .collect();
        let (volume, centroid, covariance) = mass_properties(&vertices, &faces);
        let used = checked.used_vertices.iter().map(|&i| vertices[i]);
        let bounding_radius = used.clone().map(|v| v.norm()).fold(0.0, Real::max);
        let circumscribing_radius = used.map(|v| (v - centroid).norm()).fold(0.0, Real::max);
        Ok(Self {
            vertices,
            faces,
            edges,
            face_geometry,
            volume,
            centroid,
            covariance,
            bounding_radius,
            circumscribing_radius,
        })
    }

    fn into_body(self, mass: Real, density: Real) -> Polyhedron {
        Polyhedron {
            vertices: self.vertices,
            faces: self.faces,
            edges: self.edges,
            face_geometry: self.face_geometry,
            mass,
            density,
            volume: self.volume,
            centroid: self.centroid,
            covariance: self.covariance,
            gravitational_constant: 1.0,
            bounding_radius: self.bounding_radius,
            circumscribing_radius: self.circumscribing_radius,
            multipole: OnceLock::new(),
            reach: OnceLock::new(),
        }
    }
}

/// Volume, centroid and second moments about the centroid, by signed tetrahedra: about the
/// mean vertex `o` for the first two, about the centroid for the third. For the tetrahedron
/// (0, a, b, c) of signed volume V = a·(b×c)/6: ∫x dV = V(a+b+c)/4 and
/// ∫x xᵀ dV = V/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ), s = a + b + c.
pub(crate) fn mass_properties(
    vertices: &[Vec3],
    faces: &[[u32; 3]],
) -> (Real, Vec3, Matrix3<Real>) {
    let o = vertices.iter().sum::<Vec3>() / vertices.len() as Real;
    let tets = |origin: Vec3| {
        faces.iter().map(move |f| {
            let [a, b, c] = f.map(|i| vertices[i as usize] - origin);
            (a.dot(&b.cross(&c)) / 6.0, a, b, c)
        })
    };
    let mut volume = 0.0;
    let mut first = Vec3::zeros();
    for (v, a, b, c) in tets(o) {
        volume += v;
        first += (a + b + c) * (v / 4.0);
    }
    let centroid = o + first / volume;
    let mut covariance = Matrix3::zeros();
    for (v, a, b, c) in tets(centroid) {
        let s = a + b + c;
        covariance +=
            (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose())
                * (v / 20.0);
    }
    (volume, centroid, covariance)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(h: Real) -> Mesh {
        Mesh::cube(h)
    }

    /// I_f (recovered from one face's share) against a tensor Gauss rule on the triangle.
    #[test]
    fn face_integral_matches_quadrature() {
        use surfgrav_quadrature::{GaussLegendre, Rule1D};
        let a = Vec3::new(0.1, -0.2, 0.3);
        let b = Vec3::new(1.2, 0.1, 0.2);
        let c = Vec3::new(0.3, 0.9, 0.5);
        let rule = GaussLegendre::new(40, 0.0, 1.0).unwrap();
        for p in [
            Vec3::new(0.5, 0.3, 1.5),
            Vec3::new(0.4, 0.2, -1.0),
            Vec3::new(3.0, -2.0, 0.4),
        ] {
            let twice = (b - a).cross(&(c - a));
            let mut quad = 0.0;
            for (&s, &ws) in rule.nodes().iter().zip(rule.weights()) {
                for (&t, &wt) in rule.nodes().iter().zip(rule.weights()) {
                    let x = a + (b - a) * s + (c - b) * (s * t);
                    quad += ws * wt * s * twice.norm() / (x - p).norm();
                }
            }
            let closed = face_integral(&[a, b, c], &p);
            assert!(
                ((closed - quad) / quad).abs() < 1e-13,
                "I_f at {p:?}: closed {closed}, quadrature {quad}"
            );
        }
    }

    /// The face integral by this module's formula, for one isolated triangle.
    fn face_integral(t: &[Vec3; 3], p: &Vec3) -> Real {
        let cross = (t[1] - t[0]).cross(&(t[2] - t[0]));
        let normal = cross.normalize();
        let h = normal.dot(&(t[0] - p));
        let rel = t.map(|v| {
            let r = v - p;
            [r.x, r.y, r.z, r.norm()]
        });
        let r = t.map(|v| v - p);
        let n = rel.map(|x| x[3]);
        let den = n[0] * n[1] * n[2]
            + n[0] * r[1].dot(&r[2])
            + n[1] * r[2].dot(&r[0])
            + n[2] * r[0].dot(&r[1]);
        let mut total = -h * 2.0 * (cross.norm() * h).atan2(den);
        for k in 0..3 {
            let (i, j) = (k, (k + 1) % 3);
            let m = (t[j] - t[i]).cross(&normal).normalize();
            let d = m.dot(&(t[i] - p));
            total += d * edge_log(&rel[i], &rel[j], (t[j] - t[i]).norm());
        }
        total
    }

    /// The stored degree meets the Hessian's bound at [`GRADIENT_FAR_FIELD_RADII`].
    #[test]
    fn gradient_switch_is_covered_by_the_stored_degree() {
        let q = 1.0 / GRADIENT_FAR_FIELD_RADII;
        assert!(multipole::hessian_relative_bound(q, max_degree()) <= multipole::TRUNCATION_REL);
    }

    #[test]
    fn cube_mass_properties() {
        let body = Polyhedron::with_mass(&cube(2.0), 3.0).unwrap();
        assert!((body.volume() - 8.0).abs() < 1e-14);
        assert!(body.centroid().norm() < 1e-15);
        let i = body.inertia_tensor();
        // A cube of side s: I = m s²/6 on each axis.
        for k in 0..3 {
            assert!((i[(k, k)] - 2.0).abs() < 1e-14);
        }
    }

    #[test]
    fn edge_log_on_and_near_the_edge() {
        let a = [-1.0, 0.0, 0.0, 1.0];
        let b = [1.0, 0.0, 0.0, 1.0];
        assert_eq!(edge_log(&a, &b, 2.0), 0.0);
        // 1e-9 off the middle of the edge: ln((s+e)/(s−e)) with s − e = ρ²/… exactly.
        let rho: Real = 1e-9;
        let n = (1.0 + rho * rho).sqrt();
        let a = [-1.0, rho, 0.0, n];
        let b = [1.0, rho, 0.0, n];
        // s − e = 2n − 2 = 2ρ²/(n + 1): ln((2n + 2)(n + 1)/(2ρ²)).
        let exact = ((n + 1.0) * (n + 1.0) / (rho * rho)).ln();
        let got = edge_log(&a, &b, 2.0);
        assert!(((got - exact) / exact).abs() < 1e-15, "{got} vs {exact}");
    }
}
