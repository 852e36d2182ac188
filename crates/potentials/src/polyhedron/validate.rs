//! Validation of a triangle mesh as the boundary of a solid.
//!
//! Checked in this order, each failure a [`MeshError`] naming the face, edge or vertex (all
//! indices 0-based):
//! 1. finite coordinates, indices in range, at least four faces;
//! 2. no degenerate face (a repeated vertex, or an area below [`DEGENERATE_AREA_REL`] of its
//!    longest edge squared);
//! 3. a closed, consistently oriented 2-manifold: every directed edge is used by exactly one
//!    face and its reverse by exactly one other (an edge used twice in the same direction is a
//!    flipped face or a non-manifold edge; an edge without its reverse is a hole), and the
//!    faces around each vertex form one fan;
//! 4. no self-intersection: triangles that share no vertex must not meet; triangles that share
//!    one vertex must meet only there; triangles that share an edge must not fold onto each
//!    other. Candidate pairs come from a uniform grid of about one cell per face. Own code
//!    rather than parry3d-f64: the adjacency rules have to be applied per pair anyway (a
//!    collision crate reports every pair of neighbours as touching), and parry3d-f64 0.31.1
//!    alone took 3 min 10 s to build here (41 crates, 2 min 20 s of CPU, dependencies at
//!    opt-level 3 as in this workspace) for one predicate. The orientation tests are plain `f64`
//!    determinants, exact in sign except within rounding of a degenerate configuration;
//! 5. positive volume for every connected piece, by signed tetrahedra. Orientation is thus
//!    judged from edge pairing plus the sign of the volume, never by ray parity.

use std::collections::HashMap;

use crate::{Real, Vec3};

use super::Mesh;

/// A face whose area is below this fraction of its longest edge squared is degenerate (a
/// sliver with its height 2e-12 of its longest edge: its normal would carry relative rounding
/// errors of 1e-4 and it bounds no volume).
pub const DEGENERATE_AREA_REL: Real = 1e-12;

/// Why a mesh cannot bound a solid, or could not be read. Indices are 0-based.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    /// A file could not be opened or read.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The system's or the parser's message.
        message: String,
    },
    /// A line of a mesh file is not in the expected format.
    #[error("{path}:{line}: {message}")]
    Parse {
        /// The file.
        path: String,
        /// 1-based line number.
        line: usize,
        /// What was wrong.
        message: String,
    },
    /// A face of an OBJ file is not a triangle.
    #[error("{path}: face {face} has {corners} corners; only triangles are supported (triangulate the mesh)")]
    NotTriangle {
        /// The file.
        path: String,
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// A length unit other than `m` or `km`.
    #[error("unknown length unit {unit:?}: use \"m\" or \"km\"")]
    UnknownUnit {
        /// The unit given.
        unit: String,
    },
    /// Fewer than four faces cannot bound a solid.
    #[error("a closed mesh needs at least 4 faces, got {faces}")]
    TooFewFaces {
        /// Faces given.
        faces: usize,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate: {position:?}")]
    NonFiniteVertex {
        /// The vertex.
        vertex: usize,
        /// Its coordinates.
        position: [Real; 3],
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index}, but there are only {vertices} vertices")]
    IndexOutOfRange {
        /// The face.
        face: usize,
        /// The bad index.
        index: usize,
        /// Number of vertices.
        vertices: usize,
    },
    /// A face with a repeated vertex or (nearly) zero area.
    #[error("face {face} {vertices:?} is degenerate: {reason}")]
    DegenerateFace {
        /// The face.
        face: usize,
        /// Its vertices.
        vertices: [usize; 3],
        /// Repeated vertex or zero area.
        reason: &'static str,
    },
    /// A directed edge has no face running along it the other way: the surface has a hole.
    #[error("edge {from} -> {to} of face {face} has no face running the other way: the mesh is open there")]
    OpenEdge {
        /// First vertex.
        from: usize,
        /// Second vertex.
        to: usize,
        /// The face that has it.
        face: usize,
    },
    /// Two faces run along the same edge in the same direction: one of them is flipped (or the
    /// edge has more than two faces).
    #[error("edge {from} -> {to} is used in the same direction by faces {first} and {second}: one of them is flipped, or the edge is not manifold")]
    InconsistentEdge {
        /// First vertex.
        from: usize,
        /// Second vertex.
        to: usize,
        /// The first face using it.
        first: usize,
        /// The second face using it in the same direction.
        second: usize,
    },
    /// The faces around a vertex form more than one fan (two sheets touching at a point).
    #[error("vertex {vertex} is not manifold: its {faces} faces form more than one fan")]
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
        /// Faces around it.
        faces: usize,
    },
    /// Two faces intersect where they should not.
    #[error("faces {first} and {second} intersect")]
    SelfIntersection {
        /// One face.
        first: usize,
        /// The other.
        second: usize,
    },
    /// A connected piece of the surface encloses a negative (or zero) volume: its faces are
    /// ordered clockwise seen from outside (reverse every face), or it is a cavity.
    #[error("the piece of the surface containing face {face} encloses volume {volume:e} <= 0: its faces are clockwise seen from outside (the mesh is inside out; reverse each face's vertex order)")]
    InsideOut {
        /// A face of the piece.
        face: usize,
        /// Its signed volume.
        volume: Real,
    },
}

/// What validation learns on the way: the undirected edges, each face's edges, the vertices
/// in use.
pub(crate) struct Checked {
    /// Undirected edges [i, j] (i → j as used by the first face found with it).
    pub edges: Vec<[usize; 2]>,
    /// For each face, its edges k = (v_k, v_{k+1}).
    pub face_edges: Vec<[usize; 3]>,
    /// Vertices referenced by some face.
    pub used_vertices: Vec<usize>,
}

pub(crate) fn validate(mesh: &Mesh) -> Result<Checked, MeshError> {
    let (vertices, faces) = (&mesh.vertices, &mesh.faces);
    if faces.len() < 4 {
        return Err(MeshError::TooFewFaces { faces: faces.len() });
    }
    let mut used = vec![false; vertices.len()];
    for (face, f) in faces.iter().enumerate() {
        for &index in f {
            if index >= vertices.len() {
                return Err(MeshError::IndexOutOfRange {
                    face,
                    index,
                    vertices: vertices.len(),
                });
            }
            used[index] = true;
        }
    }
    let used_vertices: Vec<usize> = (0..vertices.len()).filter(|&i| used[i]).collect();
    for &vertex in &used_vertices {
        let v = vertices[vertex];
        if v.iter().any(|x| !x.is_finite()) {
            return Err(MeshError::NonFiniteVertex {
                vertex,
                position: [v.x, v.y, v.z],
            });
        }
    }

    // Degenerate faces.
    for (face, f) in faces.iter().enumerate() {
        let [a, b, c] = *f;
        if a == b || b == c || c == a {
            return Err(MeshError::DegenerateFace {
                face,
                vertices: *f,
                reason: "a vertex is repeated",
            });
        }
        let [pa, pb, pc] = f.map(|i| vertices[i]);
        let longest = (pb - pa)
            .norm_squared()
            .max((pc - pb).norm_squared())
            .max((pa - pc).norm_squared());
        let twice_area = (pb - pa).cross(&(pc - pa)).norm();
        // (Also catches a NaN area.)
        if twice_area.is_nan() || twice_area <= 2.0 * DEGENERATE_AREA_REL * longest {
            return Err(MeshError::DegenerateFace {
                face,
                vertices: *f,
                reason: "its area is zero (collinear or coincident vertices)",
            });
        }
    }

    // Edge pairing: each directed edge once, with its reverse once.
    let mut directed: HashMap<(usize, usize), usize> = HashMap::with_capacity(3 * faces.len());
    for (face, f) in faces.iter().enumerate() {
        for k in 0..3 {
            let (from, to) = (f[k], f[(k + 1) % 3]);
            if let Some(&first) = directed.get(&(from, to)) {
                return Err(MeshError::InconsistentEdge {
                    from,
                    to,
                    first,
                    second: face,
                });
            }
            directed.insert((from, to), face);
        }
    }
    let mut edge_index: HashMap<(usize, usize), usize> = HashMap::with_capacity(directed.len());
    let mut edges = Vec::with_capacity(directed.len() / 2);
    let mut face_edges = vec![[0usize; 3]; faces.len()];
    for (face, f) in faces.iter().enumerate() {
        for k in 0..3 {
            let (from, to) = (f[k], f[(k + 1) % 3]);
            if !directed.contains_key(&(to, from)) {
                return Err(MeshError::OpenEdge { from, to, face });
            }
            let key = (from.min(to), from.max(to));
            let e = *edge_index.entry(key).or_insert_with(|| {
                edges.push([from, to]);
                edges.len() - 1
            });
            face_edges[face][k] = e;
        }
    }

    // One fan per vertex: walk around each vertex from one of its faces.
    let mut incident = vec![0usize; vertices.len()];
    let mut start = vec![usize::MAX; vertices.len()];
    for (face, f) in faces.iter().enumerate() {
        for &v in f {
            incident[v] += 1;
            start[v] = start[v].min(face);
        }
    }
    for &v in &used_vertices {
        let mut face = start[v];
        let mut steps = 0;
        loop {
            let f = faces[face];
            let k = f.iter().position(|&x| x == v).expect("v is on its face");
            let prev = f[(k + 2) % 3];
            // The face across the edge prev -> v runs v -> prev.
            face = directed[&(v, prev)];
            steps += 1;
            if face == start[v] || steps > incident[v] {
                break;
            }
        }
        if steps != incident[v] {
            return Err(MeshError::NonManifoldVertex {
                vertex: v,
                faces: incident[v],
            });
        }
    }

    self_intersections(vertices, faces)?;

    // Positive volume per connected piece.
    let pieces = components(faces, &face_edges, edges.len());
    let origin =
        used_vertices.iter().map(|&i| vertices[i]).sum::<Vec3>() / used_vertices.len() as Real;
    let mut volumes: HashMap<usize, (Real, usize)> = HashMap::new();
    for (face, f) in faces.iter().enumerate() {
        let [a, b, c] = f.map(|i| vertices[i] - origin);
        let entry = volumes.entry(pieces[face]).or_insert((0.0, face));
        entry.0 += a.dot(&b.cross(&c)) / 6.0;
    }
    let mut list: Vec<_> = volumes.into_values().collect();
    list.sort_by_key(|&(_, face)| face);
    if let Some(&(volume, face)) = list.iter().find(|(v, _)| v.is_nan() || *v <= 0.0) {
        return Err(MeshError::InsideOut { face, volume });
    }

    Ok(Checked {
        edges,
        face_edges,
        used_vertices,
    })
}

/// Connected pieces of the surface (faces joined across edges): a piece label per face.
fn components(faces: &[[usize; 3]], face_edges: &[[usize; 3]], n_edges: usize) -> Vec<usize> {
    let mut edge_faces = vec![Vec::with_capacity(2); n_edges];
    for (face, fe) in face_edges.iter().enumerate() {
        for &e in fe {
            edge_faces[e].push(face);
        }
    }
    let mut label = vec![usize::MAX; faces.len()];
    for seed in 0..faces.len() {
        if label[seed] != usize::MAX {
            continue;
        }
        label[seed] = seed;
        let mut stack = vec![seed];
        while let Some(face) = stack.pop() {
            for &e in &face_edges[face] {
                for &other in &edge_faces[e] {
                    if label[other] == usize::MAX {
                        label[other] = seed;
                        stack.push(other);
                    }
                }
            }
        }
    }
    label
}

/// Six times the signed volume of (a, b, c, d): positive when d is below the counter-clockwise
/// triangle a, b, c.
#[inline]
fn orient(a: &Vec3, b: &Vec3, c: &Vec3, d: &Vec3) -> Real {
    (a - d).dot(&(b - d).cross(&(c - d)))
}

/// Twice the signed area of (a, b, c) in the plane dropping axis `drop`.
#[inline]
fn orient2(a: &Vec3, b: &Vec3, c: &Vec3, drop: usize) -> Real {
    let (i, j) = ((drop + 1) % 3, (drop + 2) % 3);
    (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i])
}

fn sign(x: Real) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// Does the closed segment p–q meet the closed triangle a, b, c?
fn segment_meets_triangle(p: &Vec3, q: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> bool {
    let (sp, sq) = (sign(orient(a, b, c, p)), sign(orient(a, b, c, q)));
    if sp != 0 && sp == sq {
        return false;
    }
    if sp == 0 && sq == 0 {
        return coplanar_segment_meets_triangle(p, q, a, b, c);
    }
    let s1 = sign(orient(p, q, a, b));
    let s2 = sign(orient(p, q, b, c));
    let s3 = sign(orient(p, q, c, a));
    let pos = s1 >= 0 && s2 >= 0 && s3 >= 0;
    let neg = s1 <= 0 && s2 <= 0 && s3 <= 0;
    pos || neg
}

/// The dominant axis of the triangle's normal: dropping it projects without degeneracy.
fn dominant_axis(a: &Vec3, b: &Vec3, c: &Vec3) -> usize {
    (b - a).cross(&(c - a)).iamax()
}

fn point_in_triangle_2d(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3, drop: usize) -> bool {
    let s1 = sign(orient2(a, b, p, drop));
    let s2 = sign(orient2(b, c, p, drop));
    let s3 = sign(orient2(c, a, p, drop));
    (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)
}

fn segments_meet_2d(p: &Vec3, q: &Vec3, a: &Vec3, b: &Vec3, drop: usize) -> bool {
    let d1 = sign(orient2(p, q, a, drop));
    let d2 = sign(orient2(p, q, b, drop));
    let d3 = sign(orient2(a, b, p, drop));
    let d4 = sign(orient2(a, b, q, drop));
    if d1 * d2 < 0 && d3 * d4 < 0 {
        return true;
    }
    let on = |x: &Vec3, y: &Vec3, z: &Vec3| {
        (0..3).all(|k| z[k] >= x[k].min(y[k]) && z[k] <= x[k].max(y[k]))
    };
    (d1 == 0 && on(p, q, a))
        || (d2 == 0 && on(p, q, b))
        || (d3 == 0 && on(a, b, p))
        || (d4 == 0 && on(a, b, q))
}

fn coplanar_segment_meets_triangle(p: &Vec3, q: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> bool {
    let drop = dominant_axis(a, b, c);
    point_in_triangle_2d(p, a, b, c, drop)
        || point_in_triangle_2d(q, a, b, c, drop)
        || segments_meet_2d(p, q, a, b, drop)
        || segments_meet_2d(p, q, b, c, drop)
        || segments_meet_2d(p, q, c, a, drop)
}

/// Do the faces `f`, `g` meet anywhere they should not?
fn faces_intersect(vertices: &[Vec3], f: &[usize; 3], g: &[usize; 3]) -> bool {
    let shared: Vec<usize> = f.iter().copied().filter(|v| g.contains(v)).collect();
    let pf = f.map(|i| vertices[i]);
    let pg = g.map(|i| vertices[i]);
    match shared.len() {
        0 => (0..3).any(|k| {
            segment_meets_triangle(&pf[k], &pf[(k + 1) % 3], &pg[0], &pg[1], &pg[2])
                || segment_meets_triangle(&pg[k], &pg[(k + 1) % 3], &pf[0], &pf[1], &pf[2])
        }),
        1 => {
            // Beyond the shared vertex s: the edge opposite s in one face meets the other face.
            let s = shared[0];
            let opposite = |t: &[usize; 3]| {
                let k = t.iter().position(|&v| v == s).expect("shared");
                (vertices[t[(k + 1) % 3]], vertices[t[(k + 2) % 3]])
            };
            let (p, q) = opposite(f);
            let (u, w) = opposite(g);
            segment_meets_triangle(&p, &q, &pg[0], &pg[1], &pg[2])
                || segment_meets_triangle(&u, &w, &pf[0], &pf[1], &pf[2])
        }
        2 => {
            // Sharing an edge: they overlap only if coplanar with the third vertices on the
            // same side of the edge.
            let third = |t: &[usize; 3]| {
                vertices[*t
                    .iter()
                    .find(|v| !shared.contains(v))
                    .expect("a third vertex")]
            };
            let (a, b) = (vertices[shared[0]], vertices[shared[1]]);
            let (c, d) = (third(f), third(g));
            if orient(&a, &b, &c, &d) != 0.0 {
                return false;
            }
            let drop = dominant_axis(&a, &b, &c);
            sign(orient2(&a, &b, &c, drop)) == sign(orient2(&a, &b, &d, drop))
        }
        _ => true,
    }
}

fn self_intersections(vertices: &[Vec3], faces: &[[usize; 3]]) -> Result<(), MeshError> {
    let boxes: Vec<(Vec3, Vec3)> = faces
        .iter()
        .map(|f| {
            let p = f.map(|i| vertices[i]);
            (p[0].inf(&p[1]).inf(&p[2]), p[0].sup(&p[1]).sup(&p[2]))
        })
        .collect();
    let (lo, hi) = boxes.iter().fold(
        (
            Vec3::repeat(Real::INFINITY),
            Vec3::repeat(Real::NEG_INFINITY),
        ),
        |(lo, hi), (a, b)| (lo.inf(a), hi.sup(b)),
    );
    let extent = (hi - lo).map(|x| x.max(Real::MIN_POSITIVE));
    // About one cell per face.
    let cell = (extent.x * extent.y * extent.z / faces.len() as Real)
        .cbrt()
        .max(extent.max() / 256.0);
    let dims = extent.map(|x| ((x / cell).floor() as usize).clamp(1, 256));
    let cell_of = |p: &Vec3| -> [usize; 3] {
        let mut c = [0; 3];
        for k in 0..3 {
            c[k] = (((p[k] - lo[k]) / extent[k] * dims[k] as Real) as usize).min(dims[k] - 1);
        }
        c
    };
    let flat = |c: [usize; 3]| (c[2] * dims.y + c[1]) * dims.x + c[0];
    let mut grid: Vec<Vec<u32>> = vec![Vec::new(); dims.x * dims.y * dims.z];
    for (face, (a, b)) in boxes.iter().enumerate() {
        let (ca, cb) = (cell_of(a), cell_of(b));
        for z in ca[2]..=cb[2] {
            for y in ca[1]..=cb[1] {
                for x in ca[0]..=cb[0] {
                    grid[flat([x, y, z])].push(face as u32);
                }
            }
        }
    }
    for (index, members) in grid.iter().enumerate() {
        for (k, &i) in members.iter().enumerate() {
            for &j in &members[k + 1..] {
                let (i, j) = (i as usize, j as usize);
                let (a, b) = (&boxes[i], &boxes[j]);
                let overlap_lo = a.0.sup(&b.0);
                let overlap_hi = a.1.inf(&b.1);
                if (0..3).any(|d| overlap_lo[d] > overlap_hi[d]) {
                    continue;
                }
                // Test each pair once: in the cell holding the low corner of the overlap.
                if flat(cell_of(&overlap_lo)) != index {
                    continue;
                }
                if faces_intersect(vertices, &faces[i], &faces[j]) {
                    return Err(MeshError::SelfIntersection {
                        first: i.min(j),
                        second: i.max(j),
                    });
                }
            }
        }
    }
    Ok(())
}

/// Distance from `p` to the closed triangle a, b, c.
pub(crate) fn point_triangle_distance(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> Real {
    let n = (b - a).cross(&(c - a));
    let n2 = n.norm_squared();
    // Inside the prism over the triangle: the distance to the plane.
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|(u, v)| (*v - *u).cross(&(p - *u)).dot(&n) >= 0.0);
    if inside && n2 > 0.0 {
        return (p - a).dot(&n).abs() / n2.sqrt();
    }
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|(u, v)| {
            let e = *v - *u;
            let t = ((p - *u).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
            (p - (*u + e * t)).norm()
        })
        .fold(Real::INFINITY, Real::min)
}
