//! Pairs with a polyhedron ([`Body::polyhedron`]): contact, the closed form with a sphere or a
//! point, and the surface integrals over a triangle mesh or over the partner's surface.
//!
//! # Over a mesh
//!
//! The formulas of the [module docs](super) with $\mathrm d\mathbf S$ exact on each flat face
//! ($\mathbf n_fA_f$ times a rule's weight fractions, [`surfgrav_surfaces::mesh`]). Face $f$, of longest
//! edge $h_f$, is at distance $D_f$ from the other body's singular set (its focal set for an
//! ellipsoid or spheroid, the disk itself, a polyhedron's circumscribing ball), less $h_f/2$;
//! at level $\ell$ of the ladder [`LEVELS`] with rule order $n\_\ell$ ($n^2$ points, degree
//! $2n-1$) and subdivision threshold $\theta\_\ell$ it is cut into $k_f^2$ triangles, $k_f =
//! \lceil h_f/(\theta\_\ell D_f)\rceil$. The ladder starts at the first level whose predicted
//! error $E\_\ell$, the smaller of $\max_f e_f$ and 10 times $\sum_f (A_f/A)\\,e_f$, is within
//! 50 tolerances (`START_FACTOR`), where $e_f$ is the worst and the mean over the face's
//! pieces $p$ of $(h_f/(8k_fD_p))^{2n}$, $D_p$ the piece's own distance. It stops when two
//! successive levels agree to the tolerance, returning the finer. The estimate is the change
//! between the levels, times $\min(1, 30\\,E\_{\ell+1}/E\_\ell)$ from level 1 on (the model's
//! convergence with a safety factor 30, `STEP_SAFETY`: far away one step of the rule order
//! gains 4-5 digits that the plain change would leave unused), plus the disagreement of the two torque forms and
//! of the two force forms ($-\rho\oint\Phi\\,\mathrm d\mathbf S$ and $\rho\oint\mathbf x\\,(\mathbf
//! a\cdot\mathrm d\mathbf S)$, equal since $\nabla\cdot\mathbf a = 0$ in the integrated body),
//! plus the rounding bound ($4\varepsilon\sum_k|t_k|$ per sum), plus the expansion's truncation
//! bound below.
//!
//! # A polyhedron's field, certified at the tolerance
//!
//! Over a partner whose ball (its bounding radius about its centroid) stays
//! [`REACH_RADII`](surfgrav_potentials::polyhedron::REACH_RADII)
//! circumscribing radii from the polyhedron's centroid, the field can be the polyhedron's
//! local expansion about the partner's centroid ([`Polyhedron::local_expansion`]: the degree-60
//! exterior moments translated once per interaction, a few hundred operations per node);
//! beyond 2 circumscribing radii of each node, its exterior expansion
//! ([`Polyhedron::field_expansion`]); otherwise its closed form. Each expansion is taken to the
//! degree whose bound relative to $|\Phi|$ and $|\mathbf a|$ is $b$ at every node it serves.
//! At node $k$ then $|\delta\Phi_k| \le b|\Phi_k|$ and $|\delta\mathbf a_k| \le b|\mathbf a_k|$,
//! so each sum's truncation error is at most $b$ times the sum of the magnitudes of its terms:
//! that is added to the estimate. $b$ is chosen so that this stays below 5 % of the tolerance.
//! Near contact neither expansion is offered and the closed form is used; its own relative
//! accuracy, [`POLYHEDRON_REL`] ($10^{-13}$: the direct sum cancels over the faces), enters
//! as $b$ does.
//!
//! # Which surface
//!
//! Over the mesh in the partner's field, or over the partner's surface in the polyhedron's
//! field (the engine's rules with the polyhedron as a field-only body; the truncation bound is
//! then added from the geometry: $\rho_X b\\,S_X\Phi\_{\max}$ for the force and the like, with
//! $\Phi\_{\max} = GM/d\_{\min}$). The predicted cost of each is its node count times the cost
//! of the field there (a polyhedron's: about $5$ ns per term of its local expansion of degree
//! $N$, $(N+1)(N+2)/2$ terms, plus $2$ ns per term pair of the translation shared by the
//! nodes; $6.8\\,(N+2)^2$ ns by its exterior expansion; directly, and for every other body,
//! its [`Potential::field_cost`] times a spheroid's 40 ns: 1.6 per face for a polyhedron, 3
//! for a triaxial ellipsoid); the cheapest field and then the cheaper surface are taken.
//!
//! # Evaluations and accuracy (certified $10^{-10}$; example `polyhedron_pairs`, which also
//! times them: the README's Benchmarks)
//!
//! | pair | surface (chosen) | Polyhedron field | evaluations | estimate | error vs $10^{-13}$ over the other surface |
//! |---|---|---|---:|---:|---:|
//! | Didymos (1,996 faces) + ellipsoid, 1180 m | ellipsoid (auto) | local, $N = 18$, $P = 41$ | 170 | 8.4e-12 | 1.2e-14 |
//! | same | mesh | (ellipsoid's closed form) | 49,902 | 7.7e-15 | 2.4e-15 |
//! | KW4 Alpha (9,168) + Beta (2,292), 2540 m | Beta (auto) | local, $N = 19$, $P = 34$ | 29,798 | 1.0e-12 | 6.5e-15 |
//! | same | Alpha | Beta's exterior expansion | 119,186 | 1.9e-12 | 7.0e-15 |
//!
//! Error against cost with the automatic choice (`--work-precision`):
//!
//! | tolerance | Didymos: evaluations, estimate, true | KW4: evaluations, estimate, true |
//! |---|---|---|
//! | 1e-4 | 82, 6.0e-6, 4.5e-10 | 11,462, 8.6e-6, 4.0e-11 |
//! | 1e-6 | 82, 1.4e-7, 4.5e-10 | 32,091, 5.8e-9, 6.5e-15 |
//! | 1e-8 | 122, 1.0e-9, 2.5e-12 | 29,798, 4.0e-11, 6.5e-15 |
//! | 1e-10 | 170, 8.4e-12, 1.2e-14 | 29,798, 1.0e-12, 6.5e-15 |
//! | 1e-12 | 226, 1.0e-13, 2.4e-15 | 57,302, 8.5e-15, 5.2e-15 |
//!
//! $V$ over either surface agrees to 1e-14 (Didymos) and 6e-15 (KW4). The node loop runs in
//! parallel over chunks of faces, the local expansion four nodes at a time. The first
//! evaluation with a polyhedron field also builds its degree-60 moments (Didymos ~0.1 s,
//! Alpha ~0.6 s).
//!
//! # Contact
//!
//! Exact for a mesh against a point (the polyhedron's region test), an ellipsoid (mapped to
//! the unit sphere, an affine map keeping triangles triangles: they meet iff some mapped face
//! comes within distance 1 of the origin, or the ellipsoid's centre lies inside the mesh), a
//! disk (each face's crossing of the disk's plane against the disk) and another mesh (every
//! pair of faces near each other: edge–face crossings and triangle distances, plus one vertex
//! of each inside the other); bodies of unknown shape are checked on the mesh's vertices and
//! face centres and the other's centroid.

use super::assembly::finite;
use super::body::{Body, BodyShape};
use super::error::{InteractionError, Side};
use super::overlap::CONTACT_MARGIN;
use super::surface_choice::{cancellation_radius, CANCELLATION_RATIO, FAR_FIELD_RATIO};
use super::{
    Interaction, InteractionEngine, InteractionOptions, Method, MethodChoice, Request,
    SurfaceChoice, ANALYTIC_RELATIVE_ERROR, ROUNDING_PER_TERM,
};
use nalgebra::Matrix3;
use rayon::prelude::*;
use std::sync::Arc;
use surfgrav_potentials::polyhedron::LocalExpansion;
use surfgrav_potentials::tolerance::POLYHEDRON_REL;
use surfgrav_potentials::{Field, InertiaTensor, Polyhedron, Pose, PoseExt, Potential, Region};
use surfgrav_surfaces::mesh::{
    point_triangle_distance, segment_distance, TriangleMesh, TriangleRule,
};
use surfgrav_surfaces::{CompensatedSum, CompensatedSum3, Real, Vec3};

/// The ladder over a mesh: (rule order $n$, subdivision threshold θ).
pub const LEVELS: [(usize, Real); 14] = [
    (1, 1.0),
    (2, 1.0),
    (3, 1.0),
    (4, 1.0),
    (5, 1.0),
    (6, 1.0),
    (7, 0.7),
    (8, 0.5),
    (8, 0.35),
    (8, 0.25),
    (8, 0.18),
    (8, 0.125),
    (8, 0.09),
    (8, 0.0625),
];

/// Factor on the area-weighted mean of the faces' model errors in the predicted error of a
/// level ([`Geometry::predicted_error`]). Measured (true error of a level taken as its change to
/// the next): the weighted mean over the true error is 0.4-0.95 for KW4 Alpha in Beta's field
/// at 1800 m (levels 0-2) and 1.4-45 for the Didymos primary with the secondary 0.05 sizes
/// away (levels 0-4), while the worst face's model is 1.2-7.5 and 25-5,600 times the true
/// error; 10 keeps every start level of KW4 where the worst face puts it.
const SHARE_FACTOR: Real = 10.0;

/// The ladder starts at the first level predicted within this many tolerances
/// ([`Geometry::start_level`]). Measured (true error against the same surface at
/// $10^{-13}$, `examples/polyhedron_pairs --near`): the prediction is 3.4-7 times the true
/// error for KW4 Alpha in Beta's field at 1800 m (levels 0-2) and 1.2-22 times for Didymos
/// with the secondary 0.05 sizes away (levels 0-5; with the per-piece model); a level within
/// 50 predicted tolerances is within the tolerance in every case but KW4's level 1 at
/// $10^{-10}$ (5.4e-10), which the extrapolated change then certifies from level 2.
const START_FACTOR: Real = 50.0;

/// Safety factor on the model's ratio of two levels' errors when the change between them
/// estimates the finer one's ([`Geometry::step_factor`]). Measured ratio of true errors over
/// the model's (same cases as [`START_FACTOR`], levels 0-5): 0.26-0.64 for Didymos near
/// contact (1.2 from level 4 to 5, where level 5's 2.4e-15 is rounding), 0.52 and 1.7 for
/// KW4 (the latter where level 2's 2.9e-14 is rounding); 30 leaves a factor 18 over the
/// worst.
const STEP_SAFETY: Real = 30.0;

/// Most pieces a face is cut into per edge.
const MAX_PIECES: usize = 64;

/// Share of the tolerance given to the expansion's truncation.
const TRUNCATION_SHARE: Real = 0.05;

/// Measured field costs (ns per evaluation, release build, this machine): a homogeneous
/// spheroid's field (33 to 57 ns at 1.05 to 12 sizes, `polyhedron_pairs -- --field-cost`),
/// the unit of [`Potential::field_cost`] by which every other closed form is scaled (a
/// polyhedron's direct sum 1.6 per face, a triaxial ellipsoid 3, a disk 3.5), a polyhedron's
/// expansion per $(N+2)^2$ (Didymos at 2.5 radii, degree 40: 12 µs), and the mesh rule's own
/// work per node (node, frame change, eight compensated sums).
const NS_PER_SPHEROID_FIELD: Real = 40.0;
const NS_PER_HARMONIC: Real = 6.8;
const NS_PER_MESH_NODE: Real = 250.0;
/// The local expansion ([`LocalExpansion`]): per term $(n, m)$, $m \le n \le N$, of an
/// evaluation, and per term pair of its construction ($(N+1)(N+2)/2$ times $(P+1)^2$).
const NS_PER_LOCAL_TERM: Real = 5.0;
const NS_PER_TRANSLATION_TERM: Real = 2.0;

/// Relative margin on the ball of a local expansion over the partner's bounding radius (the
/// nodes, mapped between frames, carry rounding).
const BALL_MARGIN: Real = 1e-9;

/// Whether the contact of two bodies could be decided.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Contact {
    Separated,
    Touching,
    Overlapping,
}

/// The interaction of two bodies of which at least one is a polyhedron (see the module docs),
/// certified for what `request` asks: over a mesh, [`Request::Force`] certifies the force alone
/// (ladder changes and own error terms of the force); [`Request::Wrench`] and
/// [`Request::Everything`] certify force, torques and energy.
pub(crate) fn interact(
    options: &InteractionOptions,
    request: Request,
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
) -> Result<Interaction, InteractionError> {
    let separation = (pose_b.position() - pose_a.position()).norm();
    match contact(a, pose_a, b, pose_b) {
        Contact::Overlapping => return Err(InteractionError::Overlap { separation }),
        Contact::Touching => return Err(InteractionError::Touching { separation }),
        Contact::Separated => {}
    }
    if options.method == MethodChoice::Automatic {
        if a.is_spherically_symmetric() {
            return point_formula(Side::A, a, pose_a, b, pose_b);
        }
        if b.is_spherically_symmetric() {
            return point_formula(Side::B, a, pose_a, b, pose_b);
        }
    }
    let tol = options.relative_tolerance;
    let plans = [Side::A, Side::B].map(|side| {
        let (x, px, y, py) = order(side, a, pose_a, b, pose_b);
        plan(x, px, y, py, tol)
    });
    let side = match options.surface {
        SurfaceChoice::A => Side::A,
        SurfaceChoice::B => Side::B,
        SurfaceChoice::Automatic => match (&plans[0], &plans[1]) {
            (Some(pa), Some(pb)) if pb.cost < pa.cost => Side::B,
            (Some(_), _) => Side::A,
            (None, Some(_)) => Side::B,
            (None, None) => {
                return Err(InteractionError::NoSurface {
                    reason: "neither body has a surface to integrate over",
                })
            }
        },
    };
    let (x, px, y, py) = order(side, a, pose_a, b, pose_b);
    match x.shape() {
        BodyShape::Mesh(mesh) => over_mesh(options, request, side, mesh, x, px, y, py),
        _ => over_partner(options, side, a, pose_a, b, pose_b),
    }
}

/// (integrated body, its pose, source body, its pose) for integration over `side`.
fn order<'b>(
    side: Side,
    a: &'b Body,
    pa: &'b Pose,
    b: &'b Body,
    pb: &'b Pose,
) -> (&'b Body, &'b Pose, &'b Body, &'b Pose) {
    match side {
        Side::A => (a, pa, b, pb),
        Side::B => (b, pb, a, pa),
    }
}

/// A predicted cost (ns) of integrating over X in Y's field.
struct Plan {
    cost: Real,
}

fn plan(x: &Body, px: &Pose, y: &Body, py: &Pose, tol: Real) -> Option<Plan> {
    let d = (px.position() - py.position()).norm();
    let min_distance = (d - x.bounding_radius()).max(0.0);
    let bound = truncation_bound(x, y, d, tol);
    let field_cost = field_cost(y, min_distance, bound);
    let nodes = match x.shape() {
        BodyShape::Mesh(mesh) => {
            let geometry = Geometry::new(mesh, px, y, py);
            let start = geometry.start_level(tol);
            let next = (start + 1).min(LEVELS.len() - 1);
            (geometry.nodes(start) + geometry.nodes(next)) as Real
        }
        BodyShape::Solid(_) | BodyShape::Disk(_) | BodyShape::Surface(_) => {
            partner_nodes(x, y, d, tol)
        }
        BodyShape::Point | BodyShape::FieldOnly => return None,
    };
    let node_cost = match x.shape() {
        BodyShape::Mesh(_) => NS_PER_MESH_NODE,
        _ => 0.0,
    };
    let local = y
        .as_polyhedron()
        .and_then(|p| local_cost(p, d, x.bounding_radius(), bound, nodes));
    let field = local.map_or(field_cost, |l| l.min(field_cost));
    Some(Plan {
        cost: nodes * (field + node_cost),
    })
}

/// Predicted ns per node of a polyhedron's local expansion over a ball of `radius` at `d`
/// from its centroid, its construction shared by `nodes`; `None` where it is not offered.
fn local_cost(p: &Polyhedron, d: Real, radius: Real, bound: Real, nodes: Real) -> Option<Real> {
    let (n, s) = p.local_expansion_degrees(d, radius * (1.0 + BALL_MARGIN), bound)?;
    let terms = ((n + 1) * (n + 2) / 2) as Real;
    let build = NS_PER_TRANSLATION_TERM * terms * ((s + 1) * (s + 1)) as Real;
    Some(NS_PER_LOCAL_TERM * terms + build / nodes.max(1.0))
}

/// The engine's ladder over a solid, disk or surface X at a gap of g sizes: calibrated on the
/// Didymos pair (g = 6.2, 1e-10: 200 evaluations); more digits and smaller gaps cost more.
fn partner_nodes(x: &Body, y: &Body, d: Real, tol: Real) -> Real {
    let size = x.bounding_radius();
    let gap = ((d - size - singular_radius(y)) / size).max(1e-3);
    let digits = (-tol.log10()).max(1.0) / 10.0;
    150.0 * digits * digits * (1.0 + 3.0 / gap)
}

/// Predicted ns per evaluation of `y`'s field at `distance` from its centroid: a polyhedron's
/// exterior expansion where it meets `bound`, else the closed form's
/// [`Potential::field_cost`] (relative to a spheroid's) in spheroid evaluations.
fn field_cost(y: &Body, distance: Real, bound: Real) -> Real {
    if let Some(p) = y.as_polyhedron() {
        let radii = distance / p.circumscribing_radius();
        if let Some(n) = p.expansion_degree(radii, bound) {
            return NS_PER_HARMONIC * ((n + 2) * (n + 2)) as Real;
        }
    }
    NS_PER_SPHEROID_FIELD * y.potential().field_cost()
}

/// Radius of the set where `y`'s exterior field, continued inward, may be singular.
fn singular_radius(y: &Body) -> Real {
    match y.shape() {
        BodyShape::Point => 0.0,
        BodyShape::Solid(e) => {
            let mut s = [e.x_semi_axis(), e.y_semi_axis(), e.z_semi_axis()];
            s.sort_by(Real::total_cmp);
            ((s[2] - s[0]) * (s[2] + s[0])).sqrt()
        }
        BodyShape::Disk(l) => l.radius(),
        _ => y.bounding_radius(),
    }
}

/// The relative bound $b$ asked of a polyhedron Y's expansion when integrating over X: 5 % of
/// the tolerance over the worst amplification (module docs), estimated from point masses.
fn truncation_bound(x: &Body, y: &Body, d: Real, tol: Real) -> Real {
    let s = x.bounding_radius();
    let near = (d - s).max(s * 1e-3);
    let _ = y;
    let amplification = match x.shape() {
        // Over a mesh the bound is taken on the smaller of the two forms of each sum, and the
        // acceleration forms' magnitudes are about s·area/volume times the results (3 for a
        // ball; Σ|x||a·W| ≤ s|a| area against |F| ≈ volume |a|): twice that.
        BodyShape::Mesh(m) => 2.0 * s * m.area() / m.volume(),
        // Over the partner the engine's Φ forms: Σ|Φ||W| / |F| ≈ area · (GM/near) /
        // (volume · GM/d²) ≈ 3 d² / (s near), the torque and energy sums the same over d / s.
        _ => 3.0 * d * d / (s * near) + 3.0 * d / near,
    };
    (TRUNCATION_SHARE * tol / amplification).max(1e-15)
}

/// A sphere or a point S with any body O: the other's field at S's centre.
fn point_formula(
    sphere: Side,
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
) -> Result<Interaction, InteractionError> {
    let (s, ps, o, po) = order(sphere, a, pose_a, b, pose_b);
    let field = o.potential().field(&po.to_body(&ps.position()));
    let force_on_s = po.rotation * field.acceleration * s.mass();
    let potential_energy = s.mass() * field.potential;
    let ca_minus_cb = pose_a.position() - pose_b.position();
    let (force_on_a, torque_on_a, torque_on_b) = match sphere {
        Side::A => (force_on_s, Vec3::zeros(), -ca_minus_cb.cross(&force_on_s)),
        Side::B => (
            -force_on_s,
            -ca_minus_cb.cross(&(-force_on_s)),
            Vec3::zeros(),
        ),
    };
    finite(Interaction {
        force_on_a,
        force_on_b: -force_on_a,
        torque_on_a,
        torque_on_b,
        potential_energy,
        method: Method::AnalyticPoint,
        integrated_over: None,
        evaluations: 1,
        error_estimate: ANALYTIC_RELATIVE_ERROR,
        level: None,
    })
}

/// Per-face sizes and distances to the source's singular set, for the subdivision.
struct Geometry<'m> {
    mesh: &'m TriangleMesh,
    /// $h_f / D_f$.
    ratio: Vec<Real>,
    /// $A_f / \sum_g A_g$.
    share: Vec<Real>,
    /// X frame → Y frame: $\mathbf y = Q\mathbf x + \mathbf t$.
    q: Matrix3<Real>,
    t: Vec3,
    /// Radius of Y's singular set.
    singular: Real,
}

impl<'m> Geometry<'m> {
    fn new(mesh: &'m TriangleMesh, px: &Pose, y: &Body, py: &Pose) -> Self {
        let singular = singular_radius(y);
        let rot_x = px.rotation.to_rotation_matrix().into_inner();
        let rot_y = py.rotation.to_rotation_matrix().into_inner();
        let q = rot_y.transpose() * rot_x;
        let t = rot_y.transpose() * (px.position() - py.position());
        let to_y = |v: &Vec3| py.to_body(&px.to_world(v));
        let ratio = (0..mesh.len())
            .map(|f| {
                let h = mesh.diameter(f);
                let dist = to_y(&mesh.centre(f)).norm() - singular - 0.5 * h;
                h / dist.max(h / MAX_PIECES as Real)
            })
            .collect();
        let areas: Vec<Real> = (0..mesh.len())
            .map(|f| mesh.area_vector(f).norm())
            .collect();
        let total: Real = areas.iter().sum::<Real>().max(Real::MIN_POSITIVE);
        let share = areas.iter().map(|a| a / total).collect();
        Self {
            mesh,
            ratio,
            share,
            q,
            t,
            singular,
        }
    }

    /// Face `f`'s model error at rule order `n` cut into `k` pieces per edge: the worst piece's
    /// and the mean over its $k^2$ pieces, each piece of diameter $h_f/k$ at its own distance
    /// $D_p$ (centre distance less $h_f/2k$) from the singular set, $e_p =
    /// (h_f/(8kD_p))^{2n}$, at most the face's $(h_f/(8kD_f))^{2n}$. Near contact only the
    /// pieces next to the partner are at $D_f$; the far side of a cut face is up to $h_f$
    /// farther.
    fn face_error(&self, f: usize, n: i32, k: usize) -> (Real, Real) {
        let face = (self.ratio[f] / (8.0 * k as Real)).powi(2 * n);
        if k == 1 {
            return (face, face);
        }
        let [a, b, c] = self.mesh.faces()[f].map(|i| self.mesh.vertices()[i as usize]);
        let piece = self.mesh.diameter(f) / k as Real;
        let (e1, e2) = ((b - a) / k as Real, (c - a) / k as Real);
        let (mut worst, mut sum): (Real, Real) = (0.0, 0.0);
        let mut add = |centre: Vec3| {
            let dist = (self.q * centre + self.t).norm() - self.singular - 0.5 * piece;
            let e = if dist > 0.0 {
                (piece / (8.0 * dist)).powi(2 * n).min(face)
            } else {
                face
            };
            worst = worst.max(e);
            sum += e;
        };
        for i in 0..k {
            for j in 0..k - i {
                let o = a + e1 * i as Real + e2 * j as Real;
                add(o + (e1 + e2) / 3.0);
                if i + j + 1 < k {
                    add(o + (e1 + e2) * (2.0 / 3.0));
                }
            }
        }
        (worst, sum / (k * k) as Real)
    }

    fn pieces(&self, f: usize, level: usize) -> usize {
        let theta = LEVELS[level].1;
        ((self.ratio[f] / theta).ceil() as usize).clamp(1, MAX_PIECES)
    }

    fn nodes(&self, level: usize) -> usize {
        let n = LEVELS[level].0;
        (0..self.mesh.len())
            .map(|f| self.pieces(f, level).pow(2) * n * n)
            .sum()
    }

    /// The smaller of the worst face's model error and [`SHARE_FACTOR`] times the
    /// area-weighted mean of the faces' model errors (a face's error enters the integral in
    /// proportion to its share of the surface: near contact only the few cut faces are
    /// coarse).
    fn predicted_error(&self, level: usize) -> Real {
        let n = LEVELS[level].0 as i32;
        let (mut worst, mut mean): (Real, Real) = (0.0, 0.0);
        for f in 0..self.mesh.len() {
            let (w, m) = self.face_error(f, n, self.pieces(f, level));
            worst = worst.max(w);
            mean += self.share[f] * m;
        }
        worst.min(SHARE_FACTOR * mean)
    }

    /// The first level predicted within [`START_FACTOR`] tolerances: the next one is then
    /// expected to agree with it to the tolerance, or to be certified by the extrapolated
    /// change ([`Self::step_factor`]). The model $(h/(8kD))^{2n}$ is calibrated on KW4 Beta in
    /// Alpha's field (largest $h/D$ 0.027; true error 4.0e-11 at (2, 1.0), 7.6e-6 at (1, 1.0));
    /// it only sets the cost, the certificate is the two levels' agreement.
    fn start_level(&self, tol: Real) -> usize {
        (0..LEVELS.len() - 1)
            .find(|&l| self.predicted_error(l) <= START_FACTOR * tol)
            .unwrap_or(LEVELS.len() - 2)
    }

    /// The factor on the change between levels `coarse` and `fine` that estimates the finer
    /// level's error: [`STEP_SAFETY`] times the model's ratio of their predicted errors, at
    /// most 1 (the plain change, the coarser level's error), and 1 from level 0 (one node per
    /// piece, before the model's asymptotic regime) or where the model gives no ratio.
    fn step_factor(&self, coarse: usize, fine: usize) -> Real {
        if coarse == 0 || fine <= coarse {
            return 1.0;
        }
        let ratio = self.predicted_error(fine) / self.predicted_error(coarse);
        if ratio.is_finite() {
            (STEP_SAFETY * ratio).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }
}

/// One level's sums over the mesh (X's frame), with the magnitudes for the rounding and
/// truncation bounds.
#[derive(Debug, Clone, Copy)]
struct Level {
    force: Vec3,
    force_acc: Vec3,
    torque: Vec3,
    torque_acc: Vec3,
    energy: Real,
    /// Σ|terms| of the force, torque and energy sums (Φ forms), and of the acceleration forms.
    abs_force: Real,
    abs_torque: Real,
    abs_energy: Real,
    abs_force_acc: Real,
    abs_torque_acc: Real,
    /// The expansion's relative bound used at any node (0 where the closed form was used).
    bound: Real,
    evaluations: usize,
}

/// Integrates over mesh X in Y's field; see the module docs.
#[allow(clippy::too_many_arguments)]
fn over_mesh(
    options: &InteractionOptions,
    request: Request,
    side: Side,
    mesh: &TriangleMesh,
    x: &Body,
    px: &Pose,
    y: &Body,
    py: &Pose,
) -> Result<Interaction, InteractionError> {
    let tol = options.relative_tolerance;
    let force_only = request == Request::Force;
    let d = (px.position() - py.position()).norm();
    let bound = truncation_bound(x, y, d, tol);
    let geometry = Geometry::new(mesh, px, y, py);
    let rot_x = px.rotation.to_rotation_matrix().into_inner();
    let rot_y = py.rotation.to_rotation_matrix().into_inner();
    // X frame → Y frame: y = q x + t.
    let q = rot_y.transpose() * rot_x;
    let t = rot_y.transpose() * (px.position() - py.position());
    let source = Source::new(y, bound, &t, mesh.bounding_radius(), &geometry, tol);
    let density = x.density();
    let fixed = match options.method {
        MethodChoice::FixedLevel(l) => Some((l as usize).min(LEVELS.len() - 1)),
        _ => None,
    };
    let mut level = fixed.unwrap_or_else(|| geometry.start_level(tol));
    let mut evaluations = 0;
    let mut previous: Option<(Interaction, usize)> = None;
    loop {
        let sums = level_sums(&geometry, level, &q, &t, &source, density);
        evaluations += sums.evaluations;
        let current = assemble(side, &sums, px, py, density);
        let own = own_estimate(&current, &sums, force_only, d);
        if let Some(l) = fixed {
            let mut r = current;
            r.evaluations = evaluations;
            r.error_estimate = Real::INFINITY;
            r.level = Some(l as u16);
            return finite(r);
        }
        if let Some((prev, prev_level)) = previous {
            let change = relative_change(&current, &prev, force_only);
            let estimate = change * geometry.step_factor(prev_level, level) + own;
            let mut r = current;
            r.evaluations = evaluations;
            r.error_estimate = estimate;
            r.level = Some(level as u16);
            if estimate <= tol {
                return finite(r);
            }
            if level + 1 >= LEVELS.len() || evaluations >= options.max_evaluations {
                let r = finite(r)?;
                return Err(InteractionError::ToleranceNotMet {
                    tolerance: tol,
                    error_estimate: r.error_estimate,
                    evaluations,
                    best: Box::new(r),
                });
            }
        }
        previous = Some((current, level));
        level += 1;
        if level >= LEVELS.len() {
            level = LEVELS.len() - 1;
        }
    }
}

/// A source field: a polyhedron by its local expansion over the integrated body's ball or its
/// exterior expansion where either meets the bound (whichever is predicted cheaper), or any
/// potential.
struct Source<'y> {
    potential: &'y dyn Potential,
    polyhedron: Option<&'y Polyhedron>,
    local: Option<LocalExpansion>,
    bound: Real,
}

impl<'y> Source<'y> {
    /// `centre` and `radius`: the integrated body's ball in Y's frame (every node within).
    fn new(
        y: &'y Body,
        bound: Real,
        centre: &Vec3,
        radius: Real,
        geometry: &Geometry,
        tol: Real,
    ) -> Self {
        let polyhedron = y.as_polyhedron();
        let local = polyhedron.and_then(|p| {
            let d = (centre - p.centroid()).norm();
            let start = geometry.start_level(tol);
            let next = (start + 1).min(LEVELS.len() - 1);
            let nodes = (geometry.nodes(start) + geometry.nodes(next)) as Real;
            local_cost(p, d, radius, bound, nodes)
                .filter(|&cost| cost < field_cost(y, (d - radius).max(0.0), bound))
                .and_then(|_| p.local_expansion(centre, radius * (1.0 + BALL_MARGIN), bound))
        });
        Self {
            potential: y.potential(),
            polyhedron,
            local,
            bound,
        }
    }

    /// The fields at source-frame points into `out` (replaced), with their bounds: four at a
    /// time by the local expansion when it holds them all (bit for bit its single-point
    /// values), else point by point.
    fn fields(&self, points: &[Vec3], out: &mut Vec<(Field, Real)>) {
        out.clear();
        if let Some(local) = self
            .local
            .as_ref()
            .filter(|l| points.iter().all(|p| l.contains(p)))
        {
            let zero = Field {
                potential: 0.0,
                acceleration: Vec3::zeros(),
            };
            let mut fields = [zero; NODES_PER_BATCH];
            for p in points.chunks(NODES_PER_BATCH) {
                let f = &mut fields[..p.len()];
                local.fields_into(p, f);
                out.extend(f.iter().map(|&f| (f, local.relative_bound())));
            }
            return;
        }
        out.extend(points.iter().map(|p| self.field(p)));
    }

    /// The field at a source-frame point and the relative truncation bound it carries.
    #[inline]
    fn field(&self, p: &Vec3) -> (Field, Real) {
        if let Some(local) = &self.local {
            if local.contains(p) {
                return (local.field(p), local.relative_bound());
            }
        }
        if let Some(poly) = self.polyhedron {
            if let Some((f, _)) = poly.field_expansion(p, self.bound) {
                return (f, self.bound);
            }
            // The direct sum's own relative accuracy (its terms cancel over the faces).
            return (poly.field(p), POLYHEDRON_REL);
        }
        (self.potential.field(p), 0.0)
    }
}

/// Faces per chunk of the node loop; chunks run in parallel (rayon) and are combined in
/// their fixed order, so the result does not depend on the number of threads.
const FACES_PER_CHUNK: usize = 256;

/// One chunk's partial sums (X frame, without the density).
#[derive(Debug, Clone, Copy, Default)]
struct Partial {
    force: Vec3,
    force_acc: Vec3,
    torque: Vec3,
    torque_acc: Vec3,
    energy: Real,
    abs: [Real; 5],
    bound: Real,
    evaluations: usize,
}

/// Nodes gathered before their fields are evaluated together.
const NODES_PER_BATCH: usize = 64;

/// A chunk's running sums (X frame, without the density).
struct Sums {
    force: CompensatedSum3,
    force_acc: CompensatedSum3,
    torque: CompensatedSum3,
    torque_acc: CompensatedSum3,
    energy: CompensatedSum,
    abs: [Real; 5],
    bound: Real,
    evaluations: usize,
}

impl Sums {
    /// Adds node `x` with weighted area vector `w`, where the source field (Y frame) and the
    /// relative bound it carries are `field`, `b`; `qt` maps Y to X.
    #[inline]
    fn add(&mut self, x: &Vec3, w: &Vec3, field: &Field, b: Real, qt: &Matrix3<Real>, phi0: Real) {
        self.bound = self.bound.max(b);
        self.evaluations += 1;
        let a = qt * field.acceleration;
        let dphi = field.potential - phi0;
        let r2 = x.norm_squared();
        let fw = w * dphi;
        self.force.add(&fw);
        self.abs[0] += fw.norm();
        let tw = x.cross(w) * dphi;
        self.torque.add(&tw);
        self.abs[1] += tw.norm();
        let aw = a.dot(w);
        let fa = x * aw;
        self.force_acc.add(&fa);
        self.abs[3] += fa.norm();
        let ta = w.cross(&a) * r2;
        self.torque_acc.add(&ta);
        self.abs[4] += ta.norm();
        let (e1, e2) = (field.potential * x.dot(w), 0.5 * r2 * aw);
        self.energy.add(e1 + e2);
        self.abs[2] += e1.abs() + e2.abs();
    }
}

/// A batch of nodes (X frame), their images in Y's frame and the fields there.
struct Batch {
    nodes: Vec<(Vec3, Vec3)>,
    points: Vec<Vec3>,
    fields: Vec<(Field, Real)>,
}

impl Batch {
    fn flush(&mut self, sums: &mut Sums, source: &Source, qt: &Matrix3<Real>, phi0: Real) {
        source.fields(&self.points, &mut self.fields);
        for ((x, w), (field, b)) in self.nodes.iter().zip(&self.fields) {
            sums.add(x, w, field, *b, qt, phi0);
        }
        self.nodes.clear();
        self.points.clear();
    }
}

#[allow(clippy::too_many_arguments)]
fn chunk_sums(
    geometry: &Geometry,
    faces: std::ops::Range<usize>,
    rule: &TriangleRule,
    level: usize,
    q: &Matrix3<Real>,
    t: &Vec3,
    source: &Source,
    phi0: Real,
) -> Partial {
    let mesh = geometry.mesh;
    let qt = q.transpose();
    let mut sums = Sums {
        force: CompensatedSum3::new(),
        force_acc: CompensatedSum3::new(),
        torque: CompensatedSum3::new(),
        torque_acc: CompensatedSum3::new(),
        energy: CompensatedSum::new(),
        abs: [0.0; 5],
        bound: 0.0,
        evaluations: 0,
    };
    let mut batch = Batch {
        nodes: Vec::with_capacity(NODES_PER_BATCH),
        points: Vec::with_capacity(NODES_PER_BATCH),
        fields: Vec::with_capacity(NODES_PER_BATCH),
    };
    for f in faces {
        let k = geometry.pieces(f, level);
        mesh.face_nodes(f, k, rule, |x, w| {
            batch.nodes.push((*x, *w));
            batch.points.push(q * x + t);
            if batch.nodes.len() == NODES_PER_BATCH {
                batch.flush(&mut sums, source, &qt, phi0);
            }
        });
    }
    batch.flush(&mut sums, source, &qt, phi0);
    Partial {
        force: sums.force.value(),
        force_acc: sums.force_acc.value(),
        torque: sums.torque.value(),
        torque_acc: sums.torque_acc.value(),
        energy: sums.energy.value(),
        abs: sums.abs,
        bound: sums.bound,
        evaluations: sums.evaluations,
    }
}

fn level_sums(
    geometry: &Geometry,
    level: usize,
    q: &Matrix3<Real>,
    t: &Vec3,
    source: &Source,
    density: Real,
) -> Level {
    let faces = geometry.mesh.len();
    let rule = TriangleRule::cached(LEVELS[level].0).expect("orders of LEVELS exist");
    let (phi0, _) = source.field(t);
    let phi0 = phi0.potential;
    let chunks: Vec<std::ops::Range<usize>> = (0..faces)
        .step_by(FACES_PER_CHUNK)
        .map(|s| s..(s + FACES_PER_CHUNK).min(faces))
        .collect();
    let partials: Vec<Partial> = chunks
        .into_par_iter()
        .map(|range| chunk_sums(geometry, range, rule, level, q, t, source, phi0))
        .collect();
    let mut force = CompensatedSum3::new();
    let mut force_acc = CompensatedSum3::new();
    let mut torque = CompensatedSum3::new();
    let mut torque_acc = CompensatedSum3::new();
    let mut energy = CompensatedSum::new();
    let mut abs = [0.0; 5];
    let mut bound: Real = 0.0;
    let mut evaluations = 1;
    for p in &partials {
        force.add(&p.force);
        force_acc.add(&p.force_acc);
        torque.add(&p.torque);
        torque_acc.add(&p.torque_acc);
        energy.add(p.energy);
        for (a, b) in abs.iter_mut().zip(&p.abs) {
            *a += b;
        }
        bound = bound.max(p.bound);
        evaluations += p.evaluations;
    }
    Level {
        force: force.value() * (-density),
        force_acc: force_acc.value() * density,
        torque: torque.value() * (-density),
        torque_acc: torque_acc.value() * (0.5 * density),
        energy: energy.value() * (density / 3.0),
        abs_force: abs[0] * density,
        abs_torque: abs[1] * density,
        abs_energy: abs[2] * density / 3.0,
        abs_force_acc: abs[3] * density,
        abs_torque_acc: abs[4] * 0.5 * density,
        bound,
        evaluations,
    }
}

/// World-frame result from X's sums.
fn assemble(side: Side, s: &Level, px: &Pose, py: &Pose, _density: Real) -> Interaction {
    let force_x = px.rotation * s.force;
    let torque_x = px.rotation * s.torque;
    let (force_on_a, torque_on_a, torque_on_b) = match side {
        Side::A => {
            let cab = px.position() - py.position();
            (force_x, torque_x, -torque_x - cab.cross(&force_x))
        }
        Side::B => {
            // M_A = −M_B − (c_B − c_A) × F_B.
            let cba = px.position() - py.position();
            (-force_x, -torque_x - cba.cross(&force_x), torque_x)
        }
    };
    Interaction {
        force_on_a,
        force_on_b: -force_on_a,
        torque_on_a,
        torque_on_b,
        potential_energy: s.energy,
        method: match side {
            Side::A => Method::SurfaceOverA,
            Side::B => Method::SurfaceOverB,
        },
        integrated_over: Some(side),
        evaluations: s.evaluations,
        error_estimate: 0.0,
        level: None,
    }
}

/// The level's own error terms: form discrepancies, rounding and truncation (relative, in the
/// norms of [`Interaction::error_estimate`]).
fn own_estimate(r: &Interaction, s: &Level, force_only: bool, lever: Real) -> Real {
    let f = s.force.norm().max(Real::MIN_POSITIVE);
    let v = s.energy.abs().max(Real::MIN_POSITIVE);
    let m = s.torque.norm().max(v);
    let forms_f = (s.force - s.force_acc).norm() / f;
    let rounding_f = ROUNDING_PER_TERM * s.abs_force.min(s.abs_force_acc) / f;
    let trunc_f = s.bound * s.abs_force.min(s.abs_force_acc) / f;
    let force = forms_f + rounding_f + trunc_f;
    if force_only {
        return force;
    }
    let forms_m = (s.torque - s.torque_acc).norm() / m;
    let rounding = ROUNDING_PER_TERM * (s.abs_torque / m + s.abs_energy / v);
    let trunc = s.bound * (s.abs_torque.min(s.abs_torque_acc) / m + s.abs_energy / v);
    // The other body's torque comes from the balance: its error is that of M_X plus the lever
    // arm (the centroid distance) times that of F_X, measured against its own scale.
    let other_scale = r.torque_on_a.norm().min(r.torque_on_b.norm()).max(v);
    let other = force * f * lever / other_scale;
    force.max(forms_m + rounding + trunc + other)
}

/// The engine's relative change between two results.
fn relative_change(a: &Interaction, b: &Interaction, force_only: bool) -> Real {
    let v = a.potential_energy.abs().max(Real::MIN_POSITIVE);
    let df = (a.force_on_a - b.force_on_a).norm() / a.force_on_a.norm().max(Real::MIN_POSITIVE);
    if force_only {
        return df;
    }
    let dv = (a.potential_energy - b.potential_energy).abs() / v;
    let dma = (a.torque_on_a - b.torque_on_a).norm() / a.torque_on_a.norm().max(v);
    let dmb = (a.torque_on_b - b.torque_on_b).norm() / a.torque_on_b.norm().max(v);
    df.max(dv).max(dma).max(dmb)
}

/// A polyhedron as a field-only body for the engine: its expansion at bound `bound` where that
/// reaches, its closed form elsewhere; the region test is skipped outside the circumscribing
/// ball.
#[derive(Debug)]
struct ExpansionField {
    polyhedron: Arc<Polyhedron>,
    bound: Real,
    /// The local expansion over the partner's ball, where predicted cheaper.
    local: Option<LocalExpansion>,
}

impl Potential for ExpansionField {
    fn mass(&self) -> Real {
        self.polyhedron.mass()
    }
    fn gravitational_constant(&self) -> Real {
        self.polyhedron.gravitational_constant()
    }
    fn volume(&self) -> Real {
        self.polyhedron.volume()
    }
    fn bounding_radius(&self) -> Real {
        self.polyhedron.bounding_radius()
    }
    fn region(&self, r: &Vec3) -> Region {
        let p = &self.polyhedron;
        if (r - p.centroid()).norm() > p.circumscribing_radius() * (1.0 + 1e-12) {
            Region::Outside
        } else {
            p.region(r)
        }
    }
    fn field(&self, r: &Vec3) -> Field {
        if let Some(local) = &self.local {
            if local.contains(r) {
                return local.field(r);
            }
        }
        match self.polyhedron.field_expansion(r, self.bound) {
            Some((f, _)) => f,
            None => self.polyhedron.field(r),
        }
    }
    fn inertia(&self) -> Option<InertiaTensor> {
        self.polyhedron.inertia()
    }
}

/// Integrates over the partner (side `side`, not a mesh) in the polyhedron's field by the
/// engine's own rules, then adds the truncation bound.
fn over_partner(
    options: &InteractionOptions,
    side: Side,
    a: &Body,
    pose_a: &Pose,
    b: &Body,
    pose_b: &Pose,
) -> Result<Interaction, InteractionError> {
    let tol = options.relative_tolerance;
    let (x, px, y, py) = order(side, a, pose_a, b, pose_b);
    let shared = y.polyhedron.clone().ok_or(InteractionError::NoSurface {
        reason: "neither body has a surface to integrate over",
    })?;
    let poly: &Polyhedron = &shared;
    let d = (px.position() - py.position()).norm();
    let bound = truncation_bound(x, y, d, tol);
    let radius = x.bounding_radius();
    let centre = py.to_body(&px.position());
    let nodes = partner_nodes(x, y, d, tol);
    let local = local_cost(
        poly,
        (centre - poly.centroid()).norm(),
        radius,
        bound,
        nodes,
    )
    .filter(|&cost| cost < field_cost(y, (d - radius).max(0.0), bound))
    .and_then(|_| poly.local_expansion(&centre, radius * (1.0 + BALL_MARGIN), bound));
    let field = Body::custom(
        Arc::new(ExpansionField {
            polyhedron: shared.clone(),
            bound,
            local,
        }),
        BodyShape::FieldOnly,
    )?;
    let mut engine = InteractionEngine::new(InteractionOptions {
        relative_tolerance: tol * (1.0 - 2.0 * TRUNCATION_SHARE),
        surface: match side {
            Side::A => SurfaceChoice::A,
            Side::B => SurfaceChoice::B,
        },
        ..*options
    })?;
    let result = match side {
        Side::A => engine.interact(x, px, &field, py),
        Side::B => engine.interact(&field, py, x, px),
    };
    let add = |mut r: Interaction| {
        r.error_estimate += partner_truncation(x, poly, d, bound, &r);
        r
    };
    match result {
        Ok(r) => {
            let r = add(r);
            if r.error_estimate <= tol || matches!(options.method, MethodChoice::FixedLevel(_)) {
                Ok(r)
            } else {
                Err(InteractionError::ToleranceNotMet {
                    tolerance: tol,
                    error_estimate: r.error_estimate,
                    evaluations: r.evaluations,
                    best: Box::new(r),
                })
            }
        }
        Err(InteractionError::ToleranceNotMet { best, .. }) => {
            let r = add(*best);
            Err(InteractionError::ToleranceNotMet {
                tolerance: tol,
                error_estimate: r.error_estimate,
                evaluations: r.evaluations,
                best: Box::new(r),
            })
        }
        Err(e) => Err(e),
    }
}

/// The truncation bound of the integrals over X's surface (module docs), from the geometry.
fn partner_truncation(x: &Body, poly: &Polyhedron, d: Real, bound: Real, r: &Interaction) -> Real {
    let s = x.bounding_radius();
    let near = (d - s).max(Real::MIN_POSITIVE);
    let gm = poly.gravitational_parameter();
    let (phi_max, a_max) = (gm / near, gm / (near * near));
    let rho = x.density();
    let (force, torque, energy) = match x.shape() {
        BodyShape::Disk(l) => {
            let (radius, area) = (l.radius(), std::f64::consts::PI * l.radius() * l.radius());
            (
                rho * (a_max * area + phi_max * 2.0 * std::f64::consts::PI * radius),
                rho * a_max * radius * area,
                rho * phi_max * area,
            )
        }
        BodyShape::Solid(e) => {
            let area = e.surface_area();
            // Far away the engine also sums the acceleration form of the force,
            // ρ∮x (a·dS), and keeps it where its terms are smaller (FAR_FIELD_RATIO): its
            // truncation error is then b·ρ|a| s·area, not the Φ form's b·ρ|Φ|·area, which
            // grows as d/s past the force itself.
            let far = d > FAR_FIELD_RATIO * s || d > CANCELLATION_RATIO * cancellation_radius(x);
            let potential_form = rho * phi_max * area;
            let force = if far {
                potential_form.min(rho * a_max * s * area)
            } else {
                potential_form
            };
            (
                force,
                rho * phi_max * s * area,
                rho / 3.0 * area * s * (phi_max + 0.5 * s * a_max),
            )
        }
        _ => return Real::INFINITY,
    };
    let v = r.potential_energy.abs().max(Real::MIN_POSITIVE);
    let m = r.torque_on_a.norm().max(r.torque_on_b.norm()).max(v);
    bound
        * (force / r.force_on_a.norm().max(Real::MIN_POSITIVE))
            .max(torque / m)
            .max(energy / v)
}

// ---------------------------------------------------------------------------------------------
// Contact
// ---------------------------------------------------------------------------------------------

fn contact(a: &Body, pa: &Pose, b: &Body, pb: &Pose) -> Contact {
    let d = (pb.position() - pa.position()).norm();
    if d > a.bounding_radius() + b.bounding_radius() {
        return Contact::Separated;
    }
    let (m, pm, o, po) = if a.as_polyhedron().is_some() {
        (a, pa, b, pb)
    } else {
        (b, pb, a, pa)
    };
    let (BodyShape::Mesh(mesh), Some(poly)) = (m.shape(), m.as_polyhedron()) else {
        return Contact::Overlapping;
    };
    let scale = m.bounding_radius().max(o.bounding_radius());
    let margin = CONTACT_MARGIN * scale;
    let o_centre_in_m = poly.region(&pm.to_body(&po.position()));
    let found = match o.shape() {
        BodyShape::Point => match o_centre_in_m {
            Region::Outside => Contact::Separated,
            Region::OnSurface => Contact::Touching,
            Region::Inside => Contact::Overlapping,
        },
        BodyShape::Solid(e) => {
            // Mesh vertices into the ellipsoid's frame, scaled to the unit sphere.
            let axes = e.semi_axes();
            let map = |v: &Vec3| po.to_body(&pm.to_world(v)).component_div(&axes);
            let verts: Vec<Vec3> = mesh.vertices().iter().map(map).collect();
            let small = axes.min();
            let mut best = Real::INFINITY;
            for f in mesh.faces() {
                let [p, q, r] = f.map(|i| verts[i as usize]);
                let near = p.norm().min(q.norm()).min(r.norm());
                let span = (q - p).norm().max((r - q).norm()).max((p - r).norm());
                if near - span > best.min(1.0 + 1e-6) {
                    continue;
                }
                best = best.min(point_triangle_distance(&Vec3::zeros(), &p, &q, &r));
            }
            let tol = CONTACT_MARGIN * scale / small;
            if best < 1.0 - tol {
                Contact::Overlapping
            } else if best <= 1.0 + tol {
                Contact::Touching
            } else if o_centre_in_m == Region::Outside {
                Contact::Separated
            } else {
                Contact::Overlapping
            }
        }
        BodyShape::Disk(l) => {
            let radius = l.radius();
            let verts: Vec<Vec3> = mesh
                .vertices()
                .iter()
                .map(|v| po.to_body(&pm.to_world(v)))
                .collect();
            let mut touching = false;
            for f in mesh.faces() {
                let tri = f.map(|i| verts[i as usize]);
                match disk_triangle(&tri, radius, margin) {
                    Contact::Overlapping => return Contact::Overlapping,
                    Contact::Touching => touching = true,
                    Contact::Separated => {}
                }
            }
            if touching {
                Contact::Touching
            } else if o_centre_in_m == Region::Outside {
                Contact::Separated
            } else {
                Contact::Overlapping
            }
        }
        BodyShape::Mesh(other) => {
            let Some(other_poly) = o.as_polyhedron() else {
                return Contact::Overlapping;
            };
            mesh_mesh(mesh, poly, pm, other, other_poly, po, margin)
        }
        BodyShape::Surface(_) | BodyShape::FieldOnly => {
            // Unknown shape: the mesh's vertices and face centres against the other's region,
            // and the other's centroid against the mesh.
            if o_centre_in_m != Region::Outside {
                return Contact::Overlapping;
            }
            let probe = mesh
                .vertices()
                .iter()
                .copied()
                .chain((0..mesh.len()).map(|f| mesh.centre(f)));
            for v in probe {
                match o.potential().region(&po.to_body(&pm.to_world(&v))) {
                    Region::Inside => return Contact::Overlapping,
                    Region::OnSurface => return Contact::Touching,
                    Region::Outside => {}
                }
            }
            Contact::Separated
        }
    };
    // Touching from inside (a disk tangent to the walls it sits within) is an overlap.
    if found == Contact::Touching && o_centre_in_m == Region::Inside {
        Contact::Overlapping
    } else {
        found
    }
}

/// A triangle (disk frame: disk in z = 0, radius `radius`) against the disk.
fn disk_triangle(tri: &[Vec3; 3], radius: Real, margin: Real) -> Contact {
    let zs = tri.map(|p| p.z);
    let planar = |p: &Vec3| (p.x * p.x + p.y * p.y).sqrt();
    let mut touching = false;
    // Vertices on the plane within the margin.
    for p in tri {
        if p.z.abs() <= margin && planar(p) <= radius + margin {
            touching = true;
        }
    }
    let above = zs.iter().any(|&z| z > margin);
    let below = zs.iter().any(|&z| z < -margin);
    if above && below {
        // The crossing segment: points where the edges cross z = 0.
        let mut pts = Vec::with_capacity(3);
        for k in 0..3 {
            let (p, q) = (tri[k], tri[(k + 1) % 3]);
            if (p.z > 0.0) != (q.z > 0.0) {
                let s = p.z / (p.z - q.z);
                let x = p + (q - p) * s;
                pts.push(Vec3::new(x.x, x.y, 0.0));
            }
        }
        if pts.len() >= 2 {
            let dist = segment_distance(&Vec3::zeros(), &pts[0], &pts[1]);
            if dist < radius - margin {
                return Contact::Overlapping;
            }
            if dist <= radius + margin {
                touching = true;
            }
        }
    } else if !above && !below {
        // The face lies in the disk's plane.
        let [p, q, r] = tri.map(|p| Vec3::new(p.x, p.y, 0.0));
        if point_triangle_distance(&Vec3::zeros(), &p, &q, &r) <= radius + margin {
            touching = true;
        }
    }
    if touching {
        Contact::Touching
    } else {
        Contact::Separated
    }
}

fn mesh_mesh(
    m: &TriangleMesh,
    mp: &Polyhedron,
    pm: &Pose,
    n: &TriangleMesh,
    np: &Polyhedron,
    pn: &Pose,
    margin: Real,
) -> Contact {
    // World-frame faces of each mesh within the other's bounding ball (plus a margin).
    let near_faces = |mesh: &TriangleMesh, pose: &Pose, centre: &Vec3, radius: Real| {
        let verts: Vec<Vec3> = mesh.vertices().iter().map(|v| pose.to_world(v)).collect();
        mesh.faces()
            .iter()
            .enumerate()
            .filter_map(|(f, idx)| {
                let tri = idx.map(|i| verts[i as usize]);
                let c = pose.to_world(&mesh.centre(f));
                ((c - centre).norm() <= radius + mesh.diameter(f) + margin).then_some((
                    tri,
                    c,
                    mesh.diameter(f),
                ))
            })
            .collect::<Vec<_>>()
    };
    let fm = near_faces(m, pm, &pn.position(), n.bounding_radius());
    let fn_ = near_faces(n, pn, &pm.position(), m.bounding_radius());
    let mut touching = false;
    for (t1, c1, h1) in &fm {
        for (t2, c2, h2) in &fn_ {
            if (c1 - c2).norm() > h1 + h2 + margin {
                continue;
            }
            if triangles_cross(t1, t2) || triangles_cross(t2, t1) {
                return Contact::Overlapping;
            }
            if triangle_distance(t1, t2) <= margin {
                touching = true;
            }
        }
    }
    if touching {
        return Contact::Touching;
    }
    // Containment: a vertex of each inside the other.
    let vm = pm.to_world(&m.vertices()[m.faces()[0][0] as usize]);
    let vn = pn.to_world(&n.vertices()[n.faces()[0][0] as usize]);
    if np.region(&pn.to_body(&vm)) != Region::Outside
        || mp.region(&pm.to_body(&vn)) != Region::Outside
    {
        return Contact::Overlapping;
    }
    Contact::Separated
}

/// Whether an edge of `t1` crosses the interior of `t2` (strictly through its plane).
fn triangles_cross(t1: &[Vec3; 3], t2: &[Vec3; 3]) -> bool {
    let [a, b, c] = t2;
    let n = (b - a).cross(&(c - a));
    (0..3).any(|k| {
        let (p, q) = (t1[k], t1[(k + 1) % 3]);
        let (sp, sq) = ((p - a).dot(&n), (q - a).dot(&n));
        if !((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0)) {
            return false;
        }
        let x = p + (q - p) * (sp / (sp - sq));
        [(a, b), (b, c), (c, a)]
            .iter()
            .all(|(u, v)| (*v - *u).cross(&(x - *u)).dot(&n) > 0.0)
    })
}

/// Distance between two triangles that do not cross: the least of the vertex–triangle and
/// edge–edge distances.
fn triangle_distance(t1: &[Vec3; 3], t2: &[Vec3; 3]) -> Real {
    let mut best = Real::INFINITY;
    for p in t1 {
        best = best.min(point_triangle_distance(p, &t2[0], &t2[1], &t2[2]));
    }
    for p in t2 {
        best = best.min(point_triangle_distance(p, &t1[0], &t1[1], &t1[2]));
    }
    for i in 0..3 {
        for j in 0..3 {
            best = best.min(segment_segment(
                &t1[i],
                &t1[(i + 1) % 3],
                &t2[j],
                &t2[(j + 1) % 3],
            ));
        }
    }
    best
}

/// Distance between segments `p0 p1` and `q0 q1` (clamped closest points).
fn segment_segment(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3) -> Real {
    let (u, v, w) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, b, c, d, e) = (u.dot(&u), u.dot(&v), v.dot(&v), u.dot(&w), v.dot(&w));
    let den = a * c - b * b;
    let mut s = if den > 1e-300 {
        ((b * e - c * d) / den).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = if c > 0.0 {
        ((b * s + e) / c).clamp(0.0, 1.0)
    } else {
        0.0
    };
    if a > 0.0 {
        s = ((b * t - d) / a).clamp(0.0, 1.0);
    }
    if c > 0.0 {
        t = ((b * s + e) / c).clamp(0.0, 1.0);
    }
    ((p0 + u * s) - (q0 + v * t)).norm()
}
