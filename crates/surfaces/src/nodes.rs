//! Node tables: a surface's quadrature points and weighted outward area vectors, built once.
//!
//! For a [`Surface`] $\mathbf r(u, v)$ with area vector $\mathbf S(u, v)$ and 1-D rules
//! $(u_i, \omega^u_i)$, $(v_j, \omega^v_j)$ mapped onto its parameter rectangle, the table holds
//!
//! $$ \mathbf r_k = \mathbf r(u_i, v_j), \qquad
//!    \mathbf W_k = \omega^u_i\\,\omega^v_j\\,\mathbf S(u_i, v_j), \qquad k = j\\,n_u + i, $$
//!
//! so that $\oint f\\,\mathrm d\mathbf S \approx \sum_k f(\mathbf r_k)\\,\mathbf W_k$ for any integrand.
//! The table also records where the body-frame origin (the centroid) is, so that moments can be
//! taken about it after the table has been moved.
//!
//! # How the engine uses it (sign convention of the workspace)
//!
//! With $\Phi_B < 0$ and $\mathbf a_B = -\nabla\Phi_B$, a homogeneous solid A of density
//! $\rho_A$ outside B feels, by Gauss's theorem ($\int_V \nabla\Phi\\,\mathrm dV = \oint \Phi\\,\mathrm d\mathbf S$):
//!
//! $$ \mathbf F_A = \rho_A\\!\int_A \mathbf a_B\\,\mathrm dV = -\rho_A \oint_A \Phi_B\\,\mathrm d\mathbf S
//!    \approx -\rho_A \sum_k \Phi_B(\mathbf r_k)\\,\mathbf W_k ,$$
//!
//! $$ \mathbf M_A = \rho_A\\!\int_A (\mathbf r - \mathbf o)\times\mathbf a_B\\,\mathrm dV
//!    = -\rho_A \oint_A \Phi_B\\,(\mathbf r - \mathbf o)\times\mathrm d\mathbf S , $$
//!
//! (torque about the centroid $\mathbf o$; Conway's $\mathbf V_1 = -(\mathbf r - \mathbf o)\Phi$),
//! and, when $\nabla^2\Phi_B = 0$ inside A (the bodies do not overlap),
//!
//! $$ U = \rho_A\\!\int_A \Phi_B\\,\mathrm dV = \frac{\rho_A}{3}\oint_A
//!    \Big[\Phi_B\\,(\mathbf r - \mathbf o) + \tfrac12\\,|\mathbf r - \mathbf o|^2\\,\mathbf a_B\Big]\cdot\mathrm d\mathbf S ,$$
//!
//! since $\nabla\cdot[\Phi\\,\mathbf x - \tfrac12|\mathbf x|^2\nabla\Phi] = 3\Phi - \tfrac12|\mathbf x|^2\nabla^2\Phi$.
//! (The paper writes $\mathbf g = +\nabla\Phi$; with our $\mathbf a = -\nabla\Phi$ the sign of the
//! second term flips.) Each identity is checked by this crate's tests against independent volume
//! quadratures.
//!
//! # Frames
//!
//! [`SurfaceNodes::transformed`] maps the table by $\mathbf r' = R\\,\mathbf r + \mathbf t$,
//! $\mathbf W' = R\\,\mathbf W$ (a proper rotation keeps area vectors outward and of the same
//! length). To evaluate B's potential at A's nodes in B's frame, with poses
//! $(\mathbf p_A, R_A)$, $(\mathbf p_B, R_B)$ mapping body to world, use
//! $R = R_B^{\mathsf T} R_A$ and $\mathbf t = R_B^{\mathsf T}(\mathbf p_A - \mathbf p_B)$; the sums above are
//! then B-frame vectors. [`SurfaceNodes::transform_into`] reuses an existing table's storage so a
//! time step allocates nothing.

use crate::sum::{CompensatedSum, CompensatedSum3};
use crate::{BorrowedRule, NodeTableError, Periodicity, Real, Surface, Vec3};
use nalgebra::Rotation3;

/// A surface's node table: points $\mathbf r_k$ and weighted outward area vectors $\mathbf W_k$
/// (see the module docs). Units: length and length².
///
/// Stored as two parallel arrays of 3-vectors, iterated together.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceNodes {
    points: Vec<Vec3>,
    weighted_area_vectors: Vec<Vec3>,
    origin: Vec3,
    u_count: usize,
    v_count: usize,
}

impl SurfaceNodes {
    /// The tensor-product table of `surface` with `u_rule` in $u$ and `v_rule` in $v$, each mapped
    /// affinely from its own interval onto the surface's parameter interval. In the body frame
    /// (origin at the centroid).
    pub fn new<S: Surface + ?Sized>(
        surface: &S,
        u_rule: BorrowedRule<'_>,
        v_rule: BorrowedRule<'_>,
    ) -> Result<Self, NodeTableError> {
        let (n_u, n_v) = (u_rule.len(), v_rule.len());
        let count = n_u
            .checked_mul(n_v)
            .filter(|&n| n <= isize::MAX as usize / std::mem::size_of::<Vec3>())
            .ok_or(NodeTableError::TooManyNodes {
                first: n_u,
                second: n_v,
            })?;
        let domain = surface.parameter_domain();
        let u_mapped: Vec<(Real, Real)> = u_rule.mapped_to(domain.u).collect();
        let mut points = Vec::with_capacity(count);
        let mut weighted_area_vectors = Vec::with_capacity(count);
        for (v, weight_v) in v_rule.mapped_to(domain.v) {
            for &(u, weight_u) in &u_mapped {
                let (point, area_vector) = surface.point_and_area_vector(u, v);
                points.push(point);
                weighted_area_vectors.push(area_vector * (weight_u * weight_v));
            }
        }
        Ok(Self {
            points,
            weighted_area_vectors,
            origin: Vec3::zeros(),
            u_count: n_u,
            v_count: n_v,
        })
    }

    /// Like [`SurfaceNodes::new`], naming the rules by role: `periodic_rule` (a trapezoid rule,
    /// say) for the surface's periodic direction and `transverse_rule` (Gauss–Legendre) for the
    /// other. Fails unless exactly one direction is periodic.
    pub fn with_periodic_rule<S: Surface + ?Sized>(
        surface: &S,
        periodic_rule: BorrowedRule<'_>,
        transverse_rule: BorrowedRule<'_>,
    ) -> Result<Self, NodeTableError> {
        match surface.parameter_domain().periodicity {
            Periodicity::U => Self::new(surface, periodic_rule, transverse_rule),
            Periodicity::V => Self::new(surface, transverse_rule, periodic_rule),
            periodicity => Err(NodeTableError::NotSinglyPeriodic { periodicity }),
        }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the table has no nodes (never, for a table built from validated rules).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Numbers of nodes in $u$ and in $v$; node $k = j\\,n_u + i$ belongs to $(u_i, v_j)$.
    pub fn rule_sizes(&self) -> (usize, usize) {
        (self.u_count, self.v_count)
    }

    /// The points $\mathbf r_k$.
    pub fn points(&self) -> &[Vec3] {
        &self.points
    }

    /// The weighted outward area vectors $\mathbf W_k$.
    pub fn weighted_area_vectors(&self) -> &[Vec3] {
        &self.weighted_area_vectors
    }

    /// Pairs $(\mathbf r_k, \mathbf W_k)$.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (&Vec3, &Vec3)> + '_ {
        self.points.iter().zip(&self.weighted_area_vectors)
    }

    /// The body-frame origin (centroid) expressed in the table's current frame.
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// The table in another frame: $\mathbf r' = R\mathbf r + \mathbf t$, $\mathbf W' = R\mathbf W$.
    /// Fails on a non-finite rotation entry or offset.
    pub fn transformed(
        &self,
        rotation: &Rotation3<Real>,
        offset: &Vec3,
    ) -> Result<Self, NodeTableError> {
        let mut out = Self {
            points: Vec::new(),
            weighted_area_vectors: Vec::new(),
            origin: Vec3::zeros(),
            u_count: 0,
            v_count: 0,
        };
        self.transform_into(rotation, offset, &mut out)?;
        Ok(out)
    }

    /// [`SurfaceNodes::transformed`] written into `out`, reusing its storage (no allocation once
    /// `out` has held a table of this size). On error `out` is left unchanged.
    pub fn transform_into(
        &self,
        rotation: &Rotation3<Real>,
        offset: &Vec3,
        out: &mut SurfaceNodes,
    ) -> Result<(), NodeTableError> {
        check_transform(rotation, offset)?;
        let m = rotation.matrix();
        out.points.clear();
        out.points
            .extend(self.points.iter().map(|p| m * p + offset));
        out.weighted_area_vectors.clear();
        out.weighted_area_vectors
            .extend(self.weighted_area_vectors.iter().map(|w| m * w));
        out.origin = m * self.origin + offset;
        out.u_count = self.u_count;
        out.v_count = self.v_count;
        Ok(())
    }

    /// $\oint f\\,\mathrm d\mathbf S \approx \sum_k f(\mathbf r_k)\\,\mathbf W_k$ (compensated sum,
    /// see [`crate::sum`]).
    #[inline]
    pub fn integrate<F: FnMut(&Vec3) -> Real>(&self, mut f: F) -> Vec3 {
        self.iter()
            .map(|(r, w)| w * f(r))
            .collect::<CompensatedSum3>()
            .value()
    }

    /// Flux $\oint \mathbf G\cdot\mathrm d\mathbf S \approx \sum_k \mathbf G(\mathbf r_k)\cdot\mathbf W_k$.
    #[inline]
    pub fn integrate_flux<F: FnMut(&Vec3) -> Vec3>(&self, mut field: F) -> Real {
        self.iter()
            .map(|(r, w)| field(r).dot(w))
            .collect::<CompensatedSum>()
            .value()
    }

    /// Moment about the centroid,
    /// $\oint f\\,(\mathbf r - \mathbf o)\times\mathrm d\mathbf S \approx \sum_k f(\mathbf r_k)\\,(\mathbf r_k - \mathbf o)\times\mathbf W_k$.
    #[inline]
    pub fn integrate_moment<F: FnMut(&Vec3) -> Real>(&self, mut f: F) -> Vec3 {
        let o = self.origin;
        self.iter()
            .map(|(r, w)| (r - o).cross(w) * f(r))
            .collect::<CompensatedSum3>()
            .value()
    }

    /// The enclosed volume by the divergence theorem,
    /// $\tfrac13\oint (\mathbf r - \mathbf o)\cdot\mathrm d\mathbf S$ (length³).
    pub fn enclosed_volume(&self) -> Real {
        let o = self.origin;
        self.integrate_flux(|r| r - o) / 3.0
    }

    /// The surface area $\sum_k |\mathbf W_k|$ (length²); exact in the limit for rules with
    /// positive weights.
    pub fn area(&self) -> Real {
        self.weighted_area_vectors
            .iter()
            .map(|w| w.norm())
            .collect::<CompensatedSum>()
            .value()
    }

    /// $\sum_k \mathbf W_k$, which is $\oint \mathrm d\mathbf S = 0$ up to rounding for a closed
    /// surface.
    pub fn total_area_vector(&self) -> Vec3 {
        self.weighted_area_vectors
            .iter()
            .copied()
            .collect::<CompensatedSum3>()
            .value()
    }
}

/// Checks that a rotation and an offset are finite.
pub(crate) fn check_transform(
    rotation: &Rotation3<Real>,
    offset: &Vec3,
) -> Result<(), NodeTableError> {
    if rotation
        .matrix()
        .iter()
        .chain(offset.iter())
        .all(|x| x.is_finite())
    {
        Ok(())
    } else {
        Err(NodeTableError::NonFiniteTransform)
    }
}
