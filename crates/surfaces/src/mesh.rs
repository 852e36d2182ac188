//! Triangle meshes as surfaces the interaction engine integrates over: Gauss rules on
//! triangles, uniform subdivision of a face, and the exact area vectors of flat faces.
//!
//! # Rules on a triangle (Stroud's conical product)
//!
//! On the reference triangle $T = \\{(x, y): x, y \ge 0,\ x + y \le 1\\}$ the collapse
//! $x = u$, $y = (1-u)\\,t$ with $(u, t) \in (0,1)^2$ has Jacobian $1-u$:
//! $$\int_T f\\,\mathrm dA = \int_0^1\\!\\!\int_0^1 f\bigl(u, (1-u)t\bigr)\\,(1-u)\\,\mathrm dt\\,\mathrm du .$$
//! For a polynomial $f$ of total degree $d$ the integrand is a polynomial of degree $\le d$ in
//! $u$ (against the weight $1-u$) and in $t$. The $n$-point Gauss–Jacobi rule for the weight
//! $1-u$ on $[0, 1]$ and the $n$-point Gauss–Legendre rule in $t$ are both exact to degree
//! $2n-1$, so their product ($n^2$ points, positive weights, all inside $T$) is exact for every
//! polynomial of total degree $2n-1$ ([`TriangleRule::conical_product`]; the test
//! `mesh_rules` integrates every monomial $x^iy^j$, $i + j \le 2n-1$, against
//! $i!\\,j!/(i+j+2)!$ for $n = 1..8$ and shows that degree $2n$ fails). The Gauss–Jacobi rule is
//! computed here, not tabulated: the recurrence coefficients of the monic orthogonal
//! polynomials by the discretised Stieltjes procedure on a Gauss–Legendre rule of $n + 4$
//! points (exact for every inner product it forms), then Golub–Welsch (the eigenvalues of the
//! Jacobi matrix are the nodes, the squared first eigenvector components times
//! $\int_0^1(1-u)\\,\mathrm du = \tfrac12$ the weights).
//!
//! # Faces, subdivision, area vectors
//!
//! A flat face $f$ has the constant outward area vector $\mathbf n_f A_f =
//! \tfrac12(\mathbf v_1 - \mathbf v_0)\times(\mathbf v_2 - \mathbf v_0)$, so a rule's weights
//! (fractions of the area, summing to 1) times it are the exact $\mathrm d\mathbf S$ weights:
//! only the integrated field varies over a face. Where the other body is close to a face
//! (relative to the face's size) the face is cut into $k^2$ congruent triangles (the uniform
//! $k$-subdivision: $k(k+1)/2$ upright and $k(k-1)/2$ inverted), each integrated by the same
//! rule with weight fractions $1/k^2$ ([`TriangleMesh::face_nodes`]).

use crate::{Real, Vec3};
use nalgebra::DMatrix;
use std::sync::OnceLock;
use surfgrav_quadrature::GaussLegendre;

/// A quadrature rule on the reference triangle $(0,0), (1,0), (0,1)$: points in those
/// coordinates (the point of a face is $\mathbf v_0 + x(\mathbf v_1 - \mathbf v_0) +
/// y(\mathbf v_2 - \mathbf v_0)$) and weights as fractions of the area (they sum to 1).
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleRule {
    points: Vec<[Real; 2]>,
    weights: Vec<Real>,
    degree: usize,
}

/// The largest `n` of [`TriangleRule::conical_product`] offered (64 points, degree 15).
pub const MAX_CONICAL_ORDER: usize = 8;

impl TriangleRule {
    /// Stroud's conical product rule of $n^2$ points, exact for total degree $2n-1$ (module
    /// docs); `None` unless $1 \le n \le$ [`MAX_CONICAL_ORDER`].
    pub fn conical_product(n: usize) -> Option<Self> {
        if !(1..=MAX_CONICAL_ORDER).contains(&n) {
            return None;
        }
        let (ju, jw) = gauss_jacobi_one_zero(n);
        let gl = GaussLegendre::new(n, 0.0, 1.0).ok()?;
        let (tn, tw) = unit_interval(&gl);
        let mut points = Vec::with_capacity(n * n);
        let mut weights = Vec::with_capacity(n * n);
        for (u, wu) in ju.iter().zip(&jw) {
            for (t, wt) in tn.iter().zip(&tw) {
                points.push([*u, (1.0 - u) * t]);
                // ∫_T dA = 1/2: fractions of the area are twice the product weights.
                weights.push(2.0 * wu * wt);
            }
        }
        Some(Self {
            points,
            weights,
            degree: 2 * n - 1,
        })
    }

    /// The rule of order `n` from a table built once per process.
    pub fn cached(n: usize) -> Option<&'static TriangleRule> {
        static RULES: OnceLock<Vec<TriangleRule>> = OnceLock::new();
        let rules = RULES.get_or_init(|| {
            (1..=MAX_CONICAL_ORDER)
                .map(|k| Self::conical_product(k).expect("orders 1..=8 exist"))
                .collect()
        });
        rules.get(n.checked_sub(1)?)
    }

    /// Points in reference-triangle coordinates.
    pub fn points(&self) -> &[[Real; 2]] {
        &self.points
    }

    /// Weights as fractions of the triangle's area (sum 1).
    pub fn weights(&self) -> &[Real] {
        &self.weights
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the rule has no points (never, for a built rule).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The total degree up to which every polynomial is integrated exactly.
    pub fn degree(&self) -> usize {
        self.degree
    }
}

/// Nodes and weights of a Gauss–Legendre rule mapped to [0, 1] (weights summing to 1).
fn unit_interval(gl: &GaussLegendre) -> (Vec<Real>, Vec<Real>) {
    let nodes = gl
        .standard_nodes()
        .iter()
        .map(|x| 0.5 * (x + 1.0))
        .collect();
    let weights = gl.standard_weights().iter().map(|w| 0.5 * w).collect();
    (nodes, weights)
}

/// The n-point Gauss rule for the weight 1 − u on [0, 1] (weights summing to 1/2), by the
/// discretised Stieltjes procedure and Golub–Welsch (module docs).
fn gauss_jacobi_one_zero(n: usize) -> (Vec<Real>, Vec<Real>) {
    let m = n + 4;
    let gl = GaussLegendre::new(m, 0.0, 1.0).expect("small Gauss-Legendre orders exist");
    let (x, w0) = unit_interval(&gl);
    // The discrete measure: exact for polynomials of degree 2m - 2 against the weight 1 - u.
    let w: Vec<Real> = x.iter().zip(&w0).map(|(x, w)| w * (1.0 - x)).collect();
    let mut alpha = vec![0.0; n];
    let mut beta = vec![0.0; n];
    let mut p_prev = vec![0.0; m];
    let mut p = vec![1.0; m];
    let mut norm_prev = 1.0;
    for k in 0..n {
        let norm: Real = p.iter().zip(&w).map(|(p, w)| w * p * p).sum();
        let moment: Real = p
            .iter()
            .zip(&w)
            .zip(&x)
            .map(|((p, w), x)| w * x * p * p)
            .sum();
        alpha[k] = moment / norm;
        beta[k] = if k == 0 { norm } else { norm / norm_prev };
        let next: Vec<Real> = (0..m)
            .map(|i| (x[i] - alpha[k]) * p[i] - if k == 0 { 0.0 } else { beta[k] * p_prev[i] })
            .collect();
        p_prev = std::mem::replace(&mut p, next);
        norm_prev = norm;
    }
    let jacobi = DMatrix::from_fn(n, n, |i, j| {
        if i == j {
            alpha[i]
        } else if i + 1 == j {
            beta[j].sqrt()
        } else if j + 1 == i {
            beta[i].sqrt()
        } else {
            0.0
        }
    });
    let eigen = jacobi.symmetric_eigen();
    let mut pairs: Vec<(Real, Real)> = (0..n)
        .map(|i| {
            let v0 = eigen.eigenvectors[(0, i)];
            (eigen.eigenvalues[i], beta[0] * v0 * v0)
        })
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    pairs.into_iter().unzip()
}

/// A closed triangle mesh in its body frame (centroid at the origin), with each face's
/// outward area vector $\mathbf n_f A_f$, centre and diameter (its longest edge).
#[derive(Debug, Clone)]
pub struct TriangleMesh {
    vertices: Vec<Vec3>,
    faces: Vec<[u32; 3]>,
    area_vectors: Vec<Vec3>,
    centres: Vec<Vec3>,
    diameters: Vec<Real>,
    bounding_radius: Real,
    area: Real,
    volume: Real,
}

impl TriangleMesh {
    /// The mesh with these vertices and faces (counter-clockwise seen from outside, indices
    /// valid). The engine builds it from a validated `Polyhedron`; nothing is checked here
    /// beyond the indices, so a caller with its own mesh must validate it first.
    ///
    /// # Panics
    /// An index out of range.
    pub fn new(vertices: Vec<Vec3>, faces: Vec<[u32; 3]>) -> Self {
        let mut area_vectors = Vec::with_capacity(faces.len());
        let mut centres = Vec::with_capacity(faces.len());
        let mut diameters = Vec::with_capacity(faces.len());
        let mut area = 0.0;
        let mut volume = 0.0;
        for f in &faces {
            let [a, b, c] = f.map(|i| vertices[i as usize]);
            let s = (b - a).cross(&(c - a)) * 0.5;
            let centre = (a + b + c) / 3.0;
            area += s.norm();
            volume += centre.dot(&s) / 3.0;
            area_vectors.push(s);
            centres.push(centre);
            diameters.push((b - a).norm().max((c - b).norm()).max((a - c).norm()));
        }
        let bounding_radius = faces
            .iter()
            .flat_map(|f| f.iter())
            .map(|&i| vertices[i as usize].norm())
            .fold(0.0, Real::max);
        Self {
            vertices,
            faces,
            area_vectors,
            centres,
            diameters,
            bounding_radius,
            area,
            volume,
        }
    }

    /// Vertices (body frame).
    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    /// Faces as vertex indices, counter-clockwise seen from outside.
    pub fn faces(&self) -> &[[u32; 3]] {
        &self.faces
    }

    /// Number of faces.
    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// Whether the mesh has no faces.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// Outward area vector $\mathbf n_f A_f$ of face `f`.
    pub fn area_vector(&self, f: usize) -> Vec3 {
        self.area_vectors[f]
    }

    /// Centre (vertex mean) of face `f`.
    pub fn centre(&self, f: usize) -> Vec3 {
        self.centres[f]
    }

    /// Longest edge of face `f`.
    pub fn diameter(&self, f: usize) -> Real {
        self.diameters[f]
    }

    /// Largest distance of a vertex from the body-frame origin.
    pub fn bounding_radius(&self) -> Real {
        self.bounding_radius
    }

    /// Total area.
    pub fn area(&self) -> Real {
        self.area
    }

    /// Enclosed volume $\tfrac13\sum_f \mathbf c_f\cdot\mathbf n_fA_f$ (exact for flat faces).
    pub fn volume(&self) -> Real {
        self.volume
    }

    /// Calls `visit(point, weighted_area_vector)` for every node of face `f` cut into `k`²
    /// triangles, each integrated by `rule`: the weighted area vectors sum to the face's
    /// $\mathbf n_fA_f$.
    pub fn face_nodes(
        &self,
        f: usize,
        k: usize,
        rule: &TriangleRule,
        mut visit: impl FnMut(&Vec3, &Vec3),
    ) {
        let [a, b, c] = self.faces[f].map(|i| self.vertices[i as usize]);
        let k = k.max(1);
        let (e1, e2) = ((b - a) / k as Real, (c - a) / k as Real);
        let share = self.area_vectors[f] / (k * k) as Real;
        let mut sub = |origin: Vec3, d1: Vec3, d2: Vec3| {
            for (p, w) in rule.points.iter().zip(&rule.weights) {
                let x = origin + d1 * p[0] + d2 * p[1];
                visit(&x, &(share * *w));
            }
        };
        for i in 0..k {
            for j in 0..k - i {
                let o = a + e1 * i as Real + e2 * j as Real;
                sub(o, e1, e2);
                if i + j + 1 < k {
                    // The inverted triangle (i+1, j), (i, j+1), (i+1, j+1).
                    sub(o + e1 + e2, -e2, -e1);
                }
            }
        }
    }
}

/// Distance from `p` to the triangle `a, b, c` (Euclidean, exact to rounding): the projection
/// onto the plane if it falls inside, otherwise the nearest of the three edges.
pub fn point_triangle_distance(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> Real {
    let n = (b - a).cross(&(c - a));
    let n2 = n.norm_squared();
    if n2 > 0.0 {
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|(u, v)| (*v - *u).cross(&(p - *u)).dot(&n) >= 0.0);
        if inside {
            return (p - a).dot(&n).abs() / n2.sqrt();
        }
    }
    segment_distance(p, a, b)
        .min(segment_distance(p, b, c))
        .min(segment_distance(p, c, a))
}

/// Distance from `p` to the segment `a b`.
pub fn segment_distance(p: &Vec3, a: &Vec3, b: &Vec3) -> Real {
    let d = b - a;
    let len2 = d.norm_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(&d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + d * t - p).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_and_points_inside() {
        for n in 1..=MAX_CONICAL_ORDER {
            let r = TriangleRule::conical_product(n).unwrap();
            let s: Real = r.weights().iter().sum();
            assert!((s - 1.0).abs() < 4e-16, "n = {n}: {s}");
            for p in r.points() {
                assert!(p[0] > 0.0 && p[1] > 0.0 && p[0] + p[1] < 1.0);
            }
        }
    }

    #[test]
    fn subdivision_keeps_the_area_vector() {
        let mesh = TriangleMesh::new(
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(0.0, 3.0, 1.0),
            ],
            vec![[0, 1, 2]],
        );
        let rule = TriangleRule::conical_product(2).unwrap();
        for k in 1..6 {
            let mut total = Vec3::zeros();
            let mut first = Vec3::zeros();
            mesh.face_nodes(0, k, &rule, |x, w| {
                total += w;
                first += x * w.norm();
            });
            // Up to 100 weights summed: 64 ε relative is the sum's worst rounding with margin.
            let gap = (total - mesh.area_vector(0)).norm();
            assert!(
                gap < 64.0 * Real::EPSILON * total.norm(),
                "k = {k}: {gap:e}"
            );
            // The centroid of the face from the nodes (degree 1 exact on every piece).
            let c = first / mesh.area_vector(0).norm();
            assert!((c - mesh.centre(0)).norm() < 1e-14, "k = {k}");
        }
    }
}
