//! The uniform disk as a lamina: radius $R$, in the body x–y plane, centred at the origin, unit
//! normal $\hat{\mathbf n} = \hat{\mathbf z}$.
//!
//! A lamina has no volume and is not a closed [`Surface`](crate::Surface), so Gauss's theorem in
//! 3-D does not apply; the engine uses area
//! integrals over the disk and, for the in-plane force, the 2-D divergence theorem on its rim.
//!
//! # Nodes
//!
//! **Area nodes**, in polar coordinates $(s, \varphi)$ with area element $s\\,\mathrm ds\\,\mathrm d\varphi$:
//! with an angle rule $(\varphi_i, \omega^\varphi_i)$ mapped onto $[0, 2\pi]$ and a radial rule
//! $(s_j, \omega^s_j)$ mapped onto $[0, R]$,
//!
//! $$ \mathbf r_k = (s_j\cos\varphi_i,\ s_j\sin\varphi_i,\ 0), \qquad w_k = \omega^\varphi_i\\,\omega^s_j\\,s_j,
//!    \qquad \iint f\\,\mathrm dA \approx \sum_k w_k f(\mathbf r_k) . $$
//!
//! For $f$ analytic on the disk the radial integrand $s\\,f(s\cos\varphi, s\sin\varphi)$ is analytic in
//! $s$, so Gauss–Legendre in $s$ converges geometrically (and the trapezoid rule in $\varphi$ too).
//!
//! **Rim nodes**, with the outward in-plane normal $\hat{\boldsymbol\nu} = (\cos\varphi, \sin\varphi, 0)$
//! and $\mathrm dl = R\\,\mathrm d\varphi$:
//!
//! $$ \boldsymbol\rho_i = R(\cos\varphi_i, \sin\varphi_i, 0), \qquad
//!    \boldsymbol\nu_i = \omega^\varphi_i\\,R\\,\hat{\boldsymbol\nu}(\varphi_i), \qquad
//!    \oint f\\,\hat{\boldsymbol\nu}\\,\mathrm dl \approx \sum_i f(\boldsymbol\rho_i)\\,\boldsymbol\nu_i . $$
//!
//! The 2-D divergence theorem $\iint \nabla\_\parallel\\!\cdot\mathbf G\\,\mathrm dA = \oint \mathbf G\cdot\hat{\boldsymbol\nu}\\,\mathrm dl$
//! gives $\iint \nabla\_\parallel \Phi\\,\mathrm dA = \oint \Phi\\,\hat{\boldsymbol\nu}\\,\mathrm dl$ for the in-plane
//! gradient $\nabla\_\parallel = \nabla - \hat{\mathbf n}(\hat{\mathbf n}\cdot\nabla)$.
//!
//! # How the engine combines them (sign convention of the workspace)
//!
//! Lamina A of mass $m_A$ has surface density $\sigma = m_A / (\pi R^2)$. With $\Phi_B < 0$ and
//! $\mathbf a_B = -\nabla\Phi_B$ evaluated at the nodes (all vectors in one frame; $\mathbf c$ the
//! disk centre, $\hat{\mathbf n}$ its normal, both carried by [`LaminaNodes`]):
//!
//! $$ U = \sigma \iint \Phi_B\\,\mathrm dA \approx \sigma\sum_k w_k\\,\Phi_B(\mathbf r_k), $$
//!
//! $$ \mathbf F_A = \sigma\iint \mathbf a_B\\,\mathrm dA
//!    = \sigma\\,\hat{\mathbf n}\iint (\mathbf a_B\cdot\hat{\mathbf n})\\,\mathrm dA \\;-\\; \sigma\oint \Phi_B\\,\hat{\boldsymbol\nu}\\,\mathrm dl
//!    \approx \sigma\\,\hat{\mathbf n}\sum_k w_k\\,\mathbf a_B(\mathbf r_k)\cdot\hat{\mathbf n} \\;-\\; \sigma\sum_i \Phi_B(\boldsymbol\rho_i)\\,\boldsymbol\nu_i , $$
//!
//! $$ \mathbf M_A = \sigma\iint (\mathbf r - \mathbf c)\times\mathbf a_B\\,\mathrm dA
//!    = \sigma\iint (\mathbf a_B\cdot\hat{\mathbf n})\\,(\mathbf r - \mathbf c)\times\hat{\mathbf n}\\,\mathrm dA
//!    \approx \sigma\sum_k w_k\\,(\mathbf a_B(\mathbf r_k)\cdot\hat{\mathbf n})\\,(\mathbf r_k - \mathbf c)\times\hat{\mathbf n} . $$
//!
//! The torque needs no in-plane term: $\iint (\mathbf r - \mathbf c)\times\nabla\_\parallel\Phi\\,\mathrm dA
//! = \hat{\mathbf n}\oint \Phi\\,[(\mathbf r - \mathbf c)\times\hat{\boldsymbol\nu}]\cdot\hat{\mathbf n}\\,\mathrm dl = 0$
//! because $\hat{\boldsymbol\nu} \parallel \mathbf r - \mathbf c$ on a circle: no field turns a uniform
//! disk about its axis. For a coplanar B (its field has no normal component in its own plane)
//! the force comes from the rim alone and the torque vanishes.
//!
//! The plain area forms ($\mathbf F_A \approx \sigma\sum_k w_k \mathbf a_B$, likewise for
//! $\mathbf M_A$) are equal to quadrature accuracy and serve as checks.
//!
//! Validity: $\Phi_B$ continuously differentiable on the closed disk, i.e. B does not touch
//! A's lamina.

use crate::nodes::check_transform;
use crate::sum::{CompensatedSum, CompensatedSum3};
use crate::{BorrowedRule, Interval, NodeTableError, Real, ShapeError, Vec3};
use nalgebra::Rotation3;
use std::f64::consts::PI;

/// A uniform disk's shape: a circle of `radius` (length) in the body x–y plane, centred at the
/// origin, normal $+\hat{\mathbf z}$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lamina {
    radius: Real,
}

impl Lamina {
    /// A lamina of the given radius; fails unless it is positive and finite and $\pi R^2$ is a
    /// normal double.
    pub fn new(radius: Real) -> Result<Self, ShapeError> {
        if !radius.is_finite() {
            return Err(ShapeError::NotFinite {
                field: "radius",
                value: radius,
            });
        }
        if radius <= 0.0 {
            return Err(ShapeError::NotPositive {
                field: "radius",
                value: radius,
            });
        }
        let area = PI * radius * radius;
        if !area.is_normal() {
            return Err(ShapeError::OutOfRange {
                what: "disk area",
                value: area,
            });
        }
        Ok(Self { radius })
    }

    /// The radius $R$.
    pub fn radius(&self) -> Real {
        self.radius
    }

    /// $\pi R^2$.
    pub fn area(&self) -> Real {
        PI * self.radius * self.radius
    }

    /// The node table in the body frame: `angle_rule` and `radial_rule` (mapped onto $[0, 2\pi]$
    /// and $[0, R]$) for the area nodes, `rim_rule` (mapped onto $[0, 2\pi]$) for the rim.
    pub fn nodes(
        &self,
        angle_rule: BorrowedRule<'_>,
        radial_rule: BorrowedRule<'_>,
        rim_rule: BorrowedRule<'_>,
    ) -> Result<LaminaNodes, NodeTableError> {
        let (n_angle, n_radial) = (angle_rule.len(), radial_rule.len());
        let count = n_angle
            .checked_mul(n_radial)
            .filter(|&n| n <= isize::MAX as usize / std::mem::size_of::<Vec3>())
            .ok_or(NodeTableError::TooManyNodes {
                first: n_angle,
                second: n_radial,
            })?;
        let radial = Interval::new(0.0, self.radius)?;
        let angles: Vec<(Real, Real, Real, Real)> = angle_rule
            .mapped_to(Interval::FULL_TURN)
            .map(|(phi, w)| {
                let (sin, cos) = phi.sin_cos();
                (cos, sin, phi, w)
            })
            .collect();
        let mut area_points = Vec::with_capacity(count);
        let mut area_weights = Vec::with_capacity(count);
        for (s, weight_s) in radial_rule.mapped_to(radial) {
            for &(cos, sin, _, weight_phi) in &angles {
                area_points.push(Vec3::new(s * cos, s * sin, 0.0));
                area_weights.push(weight_phi * weight_s * s);
            }
        }
        let mut rim_points = Vec::with_capacity(rim_rule.len());
        let mut rim_weighted_normals = Vec::with_capacity(rim_rule.len());
        for (phi, weight) in rim_rule.mapped_to(Interval::FULL_TURN) {
            let (sin, cos) = phi.sin_cos();
            let outward = Vec3::new(cos, sin, 0.0);
            rim_points.push(outward * self.radius);
            rim_weighted_normals.push(outward * (weight * self.radius));
        }
        Ok(LaminaNodes {
            area_points,
            area_weights,
            rim_points,
            rim_weighted_normals,
            centre: Vec3::zeros(),
            normal: Vec3::z(),
        })
    }
}

impl Lamina {
    /// Rebuilds `out` as the node table of this lamina (body frame) from explicit nodes:
    /// `angles` as $(\cos\varphi_i, \sin\varphi_i, \omega^\varphi_i)$, `radial` as $(s_j, \omega^s_j)$
    /// with $s_j \in [0, R]$, `rim` as $(\cos\varphi_i, \sin\varphi_i, \omega_i)$ for the rim. Reuses
    /// `out`'s storage (no allocation once it is large enough): the aimed lamina rule builds a
    /// new table for every pose.
    pub fn fill_nodes(
        &self,
        angles: &[(Real, Real, Real)],
        radial: &[(Real, Real)],
        rim: &[(Real, Real, Real)],
        out: &mut LaminaNodes,
    ) {
        out.area_points.clear();
        out.area_weights.clear();
        for &(s, weight_s) in radial {
            push_row(out, s, weight_s, angles);
        }
        self.fill_rim(rim, out);
    }

    /// The rim nodes, centre and normal of a table being rebuilt.
    fn fill_rim(&self, rim: &[(Real, Real, Real)], out: &mut LaminaNodes) {
        out.rim_points.clear();
        out.rim_weighted_normals.clear();
        for &(cos, sin, weight) in rim {
            let outward = Vec3::new(cos, sin, 0.0);
            out.rim_points.push(outward * self.radius);
            out.rim_weighted_normals
                .push(outward * (weight * self.radius));
        }
        out.centre = Vec3::zeros();
        out.normal = Vec3::z();
    }
}

/// The area nodes of radius `s` (radial weight `weight_s`) at `angles`, appended to `out`.
fn push_row(out: &mut LaminaNodes, s: Real, weight_s: Real, angles: &[(Real, Real, Real)]) {
    for &(cos, sin, weight_phi) in angles {
        out.area_points.push(Vec3::new(s * cos, s * sin, 0.0));
        out.area_weights.push(weight_phi * weight_s * s);
    }
}

/// A row of [`Lamina::fill_turned_rows`]: the area nodes of radius $s_j$ (`radius`) with the
/// radial weight $\omega^s_j$ (`weight`) at the angles $\delta_j + \varphi$ for $\varphi$ in
/// `angles[a_j..b_j]` (`angles`), `turn` $= (\cos\delta_j, \sin\delta_j)$.
#[derive(Debug, Clone, PartialEq)]
pub struct TurnedRow {
    pub radius: Real,
    pub weight: Real,
    pub turn: (Real, Real),
    pub angles: std::ops::Range<usize>,
}

/// As [`push_row`], with the row's angles turned by $\delta$ (`turn` $= (\cos\delta, \sin\delta)$).
fn push_turned_row(
    out: &mut LaminaNodes,
    s: Real,
    weight_s: Real,
    (cos_d, sin_d): (Real, Real),
    angles: &[(Real, Real, Real)],
) {
    let (a, b) = (s * cos_d, s * sin_d);
    for &(cos, sin, weight_phi) in angles {
        out.area_points
            .push(Vec3::new(a * cos - b * sin, b * cos + a * sin, 0.0));
        out.area_weights.push(weight_phi * weight_s * s);
    }
}

impl Lamina {
    /// As [`Lamina::fill_rows`], but each row's angles turned by its own angle
    /// ([`TurnedRow`]; rows whose angles are clustered toward their own point share one list
    /// of angles).
    pub fn fill_turned_rows(
        &self,
        angles: &[(Real, Real, Real)],
        rows: &[TurnedRow],
        rim: &[(Real, Real, Real)],
        out: &mut LaminaNodes,
    ) {
        out.area_points.clear();
        out.area_weights.clear();
        for row in rows {
            push_turned_row(
                out,
                row.radius,
                row.weight,
                row.turn,
                angles.get(row.angles.clone()).unwrap_or(&[]),
            );
        }
        self.fill_rim(rim, out);
    }

    /// As [`Lamina::fill_nodes`], but each radius with its own angles: `rows` as
    /// $(s_j, \omega^s_j, a_j..b_j)$, the area nodes of radius $s_j$ at the angles
    /// `angles[a_j..b_j]` (same form as in [`Lamina::fill_nodes`]); rows whose range is out of
    /// `angles` contribute nothing.
    pub fn fill_rows(
        &self,
        angles: &[(Real, Real, Real)],
        rows: &[(Real, Real, std::ops::Range<usize>)],
        rim: &[(Real, Real, Real)],
        out: &mut LaminaNodes,
    ) {
        out.area_points.clear();
        out.area_weights.clear();
        for (s, weight_s, range) in rows {
            push_row(out, *s, *weight_s, angles.get(range.clone()).unwrap_or(&[]));
        }
        self.fill_rim(rim, out);
    }
}

impl Default for LaminaNodes {
    /// An empty table (no nodes; centre at the origin, normal $+\hat{\mathbf z}$), to be filled.
    fn default() -> Self {
        Self {
            area_points: Vec::new(),
            area_weights: Vec::new(),
            rim_points: Vec::new(),
            rim_weighted_normals: Vec::new(),
            centre: Vec3::zeros(),
            normal: Vec3::z(),
        }
    }
}

/// A lamina's node table (see the module docs): area points $\mathbf r_k$ with weights $w_k$
/// (length²), rim points $\boldsymbol\rho_i$ with weighted outward in-plane normals
/// $\boldsymbol\nu_i$ (length), the centre $\mathbf c$ and the unit normal $\hat{\mathbf n}$, all in
/// the table's current frame.
#[derive(Debug, Clone, PartialEq)]
pub struct LaminaNodes {
    area_points: Vec<Vec3>,
    area_weights: Vec<Real>,
    rim_points: Vec<Vec3>,
    rim_weighted_normals: Vec<Vec3>,
    centre: Vec3,
    normal: Vec3,
}

impl LaminaNodes {
    /// Area nodes $\mathbf r_k$.
    pub fn area_points(&self) -> &[Vec3] {
        &self.area_points
    }

    /// Area weights $w_k$ ($\mathrm dA$ including the factor $s$).
    pub fn area_weights(&self) -> &[Real] {
        &self.area_weights
    }

    /// Rim nodes $\boldsymbol\rho_i$.
    pub fn rim_points(&self) -> &[Vec3] {
        &self.rim_points
    }

    /// Weighted outward in-plane normals $\boldsymbol\nu_i = \hat{\boldsymbol\nu}\\,\mathrm dl$.
    pub fn rim_weighted_normals(&self) -> &[Vec3] {
        &self.rim_weighted_normals
    }

    /// Pairs $(\mathbf r_k, w_k)$.
    pub fn area_iter(&self) -> impl ExactSizeIterator<Item = (&Vec3, &Real)> + '_ {
        self.area_points.iter().zip(&self.area_weights)
    }

    /// Pairs $(\boldsymbol\rho_i, \boldsymbol\nu_i)$.
    pub fn rim_iter(&self) -> impl ExactSizeIterator<Item = (&Vec3, &Vec3)> + '_ {
        self.rim_points.iter().zip(&self.rim_weighted_normals)
    }

    /// The disk centre in the current frame.
    pub fn centre(&self) -> Vec3 {
        self.centre
    }

    /// The unit normal (body $+\hat{\mathbf z}$) in the current frame.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// $\iint f\\,\mathrm dA \approx \sum_k w_k f(\mathbf r_k)$ (compensated sum).
    #[inline]
    pub fn integrate_area<F: FnMut(&Vec3) -> Real>(&self, mut f: F) -> Real {
        self.area_iter()
            .map(|(r, w)| w * f(r))
            .collect::<CompensatedSum>()
            .value()
    }

    /// $\iint \mathbf g\\,\mathrm dA \approx \sum_k w_k \mathbf g(\mathbf r_k)$.
    #[inline]
    pub fn integrate_area_vector<F: FnMut(&Vec3) -> Vec3>(&self, mut g: F) -> Vec3 {
        self.area_iter()
            .map(|(r, w)| g(r) * *w)
            .collect::<CompensatedSum3>()
            .value()
    }

    /// $\oint f\\,\hat{\boldsymbol\nu}\\,\mathrm dl \approx \sum_i f(\boldsymbol\rho_i)\\,\boldsymbol\nu_i$.
    #[inline]
    pub fn integrate_rim<F: FnMut(&Vec3) -> Real>(&self, mut f: F) -> Vec3 {
        self.rim_iter()
            .map(|(r, nu)| nu * f(r))
            .collect::<CompensatedSum3>()
            .value()
    }

    /// $\oint \mathbf G\cdot\hat{\boldsymbol\nu}\\,\mathrm dl \approx \sum_i \mathbf G(\boldsymbol\rho_i)\cdot\boldsymbol\nu_i$.
    #[inline]
    pub fn integrate_rim_flux<F: FnMut(&Vec3) -> Vec3>(&self, mut field: F) -> Real {
        self.rim_iter()
            .map(|(r, nu)| field(r).dot(nu))
            .collect::<CompensatedSum>()
            .value()
    }

    /// The table in another frame: points $R\mathbf r + \mathbf t$, normals $R\boldsymbol\nu$,
    /// $R\hat{\mathbf n}$, centre $R\mathbf c + \mathbf t$; weights unchanged. Fails on a non-finite
    /// rotation or offset.
    pub fn transformed(
        &self,
        rotation: &Rotation3<Real>,
        offset: &Vec3,
    ) -> Result<Self, NodeTableError> {
        let mut out = Self {
            area_points: Vec::new(),
            area_weights: Vec::new(),
            rim_points: Vec::new(),
            rim_weighted_normals: Vec::new(),
            centre: Vec3::zeros(),
            normal: Vec3::z(),
        };
        self.transform_into(rotation, offset, &mut out)?;
        Ok(out)
    }

    /// [`LaminaNodes::transformed`] into `out`, reusing its storage. On error `out` is unchanged.
    pub fn transform_into(
        &self,
        rotation: &Rotation3<Real>,
        offset: &Vec3,
        out: &mut LaminaNodes,
    ) -> Result<(), NodeTableError> {
        check_transform(rotation, offset)?;
        let m = rotation.matrix();
        out.area_points.clear();
        out.area_points
            .extend(self.area_points.iter().map(|p| m * p + offset));
        out.area_weights.clear();
        out.area_weights.extend_from_slice(&self.area_weights);
        out.rim_points.clear();
        out.rim_points
            .extend(self.rim_points.iter().map(|p| m * p + offset));
        out.rim_weighted_normals.clear();
        out.rim_weighted_normals
            .extend(self.rim_weighted_normals.iter().map(|n| m * n));
        out.centre = m * self.centre + offset;
        out.normal = m * self.normal;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row turned by $\delta$ has the nodes of the unturned row at the angles $\varphi + \delta$
    /// (to rounding, 1e-15 of the radius) and the same weights.
    #[test]
    fn turned_rows_are_rows_at_shifted_angles() {
        let lamina = Lamina::new(1.3).unwrap();
        let base: Vec<(Real, Real, Real)> = (0..7)
            .map(|k| {
                let phi = 0.9 * Real::from(k) - 2.0;
                (phi.cos(), phi.sin(), 0.1 + 0.01 * Real::from(k))
            })
            .collect();
        let rim = [(1.0, 0.0, 0.5)];
        let mut turned_nodes = LaminaNodes::default();
        let mut shifted_nodes = LaminaNodes::default();
        let mut turned_rows = vec![];
        let mut shifted = vec![];
        let mut shifted_rows = vec![];
        for (j, delta) in [0.0, 0.7, -2.9, 3.1].into_iter().enumerate() {
            let s = 0.2 + 0.3 * j as Real;
            turned_rows.push(TurnedRow {
                radius: s,
                weight: 0.25,
                turn: (Real::cos(delta), Real::sin(delta)),
                angles: 0..base.len(),
            });
            let first = shifted.len();
            for &(cos, sin, w) in &base {
                let phi = sin.atan2(cos) + delta;
                shifted.push((phi.cos(), phi.sin(), w));
            }
            shifted_rows.push((s, 0.25, first..shifted.len()));
        }
        lamina.fill_turned_rows(&base, &turned_rows, &rim, &mut turned_nodes);
        lamina.fill_rows(&shifted, &shifted_rows, &rim, &mut shifted_nodes);
        assert_eq!(turned_nodes.area_weights(), shifted_nodes.area_weights());
        assert_eq!(turned_nodes.area_points().len(), 28);
        for (a, b) in turned_nodes
            .area_points()
            .iter()
            .zip(shifted_nodes.area_points())
        {
            assert!((a - b).norm() <= 1e-15 * 1.3, "{a} {b}");
        }
        assert_eq!(turned_nodes.rim_points(), shifted_nodes.rim_points());
    }

    /// Rows that all take the same angles give the tensor table of [`Lamina::fill_nodes`],
    /// node for node and bit for bit; rows with their own angles give each radius its angles.
    #[test]
    fn rows_with_common_angles_are_the_tensor_table() {
        let lamina = Lamina::new(1.5).unwrap();
        let angles = [(0.6, 0.8, 0.3), (-0.8, 0.6, 0.7), (0.0, -1.0, 1.1)];
        let radial = [(0.2, 0.5), (1.1, 0.25)];
        let rim = [(1.0, 0.0, 2.0), (0.0, 1.0, 4.0)];
        let mut tensor = LaminaNodes::default();
        lamina.fill_nodes(&angles, &radial, &rim, &mut tensor);
        let rows: Vec<_> = radial.iter().map(|&(s, w)| (s, w, 0..3)).collect();
        let mut by_rows = LaminaNodes::default();
        lamina.fill_rows(&angles, &rows, &rim, &mut by_rows);
        assert_eq!(tensor.area_points(), by_rows.area_points());
        assert_eq!(tensor.area_weights(), by_rows.area_weights());
        assert_eq!(tensor.rim_points(), by_rows.rim_points());
        assert_eq!(
            tensor.rim_weighted_normals(),
            by_rows.rim_weighted_normals()
        );
        // Own angles per row: one angle at s = 0.2, two at s = 1.1; a range out of bounds
        // contributes nothing.
        let rows = [(0.2, 0.5, 0..1), (1.1, 0.25, 1..3), (0.7, 1.0, 2..9)];
        lamina.fill_rows(&angles, &rows, &rim, &mut by_rows);
        assert_eq!(by_rows.area_points().len(), 3);
        assert_eq!(by_rows.area_weights()[0], 0.3 * 0.5 * 0.2);
        assert_eq!(by_rows.area_points()[2], Vec3::new(0.0, -1.1, 0.0));
    }

    #[test]
    fn constructor_rejects_bad_radius() {
        assert!(matches!(
            Lamina::new(0.0),
            Err(ShapeError::NotPositive {
                field: "radius",
                ..
            })
        ));
        assert!(matches!(
            Lamina::new(f64::NAN),
            Err(ShapeError::NotFinite { .. })
        ));
        assert!(matches!(
            Lamina::new(1e300),
            Err(ShapeError::OutOfRange { .. })
        ));
    }
}
