//! Mass properties: the inertia tensor of a rigid body about its centroid, in its body frame.
//!
//! For a homogeneous body of mass $m$ the inertia tensor about the centroid is
//! $$\mathsf I = \int \rho\\,\big(|\mathbf x|^2\\,\mathsf 1 - \mathbf x\mathbf x^{\mathsf T}\big)\\,\mathrm dV .$$
//! The built-in bodies have it in closed form (body frame = principal axes):
//! - solid ellipsoid with semi-axes $a, b, c$ (sphere and spheroids included):
//!   $\mathsf I = \tfrac m5\\,\mathrm{diag}(b^2+c^2,\ a^2+c^2,\ a^2+b^2)$;
//! - uniform disk of radius $R$ in the x–y plane:
//!   $\mathsf I = \mathrm{diag}(mR^2/4,\ mR^2/4,\ mR^2/2)$;
//! - a point mass has none: it cannot rotate.
//!
//! A user's body supplies its own tensor through [`InertiaTensor::new`], which checks that it is
//! a physical inertia tensor: finite, symmetric (to $10^{-12}$ of its largest entry), positive
//! definite, and with principal moments that satisfy the triangle inequalities
//! $I_1 \le I_2 + I_3$ (and cyclic), which every real mass distribution obeys (equality for a
//! lamina). The tests check the closed forms against a brute-force volume integral.

use crate::{Real, Vec3};
use nalgebra::{Matrix3, SymmetricEigen, UnitQuaternion};
use thiserror::Error;

/// A 3×3 matrix in a body or world frame.
pub type Mat3 = Matrix3<Real>;

/// Relative asymmetry tolerated in a user's tensor: rounding of a computed tensor, nothing more.
const SYMMETRY_RELATIVE: Real = 1e-12;

/// Relative slack of the triangle inequalities: a lamina meets one with equality, which its
/// rounded principal moments may miss by a few ulps.
const TRIANGLE_RELATIVE: Real = 1e-12;

/// Why a tensor is not an inertia tensor.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InertiaError {
    /// An entry is NaN or infinite.
    #[error("the inertia tensor has a non-finite entry ({value}) at row {row}, column {column}")]
    NotFinite {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        column: usize,
        /// The entry.
        value: Real,
    },
    /// $I\_{ij} \ne I\_{ji}$.
    #[error("the inertia tensor is not symmetric: I[{row}][{column}] = {upper:e} but I[{column}][{row}] = {lower:e}")]
    NotSymmetric {
        /// Row of the upper entry.
        row: usize,
        /// Column of the upper entry.
        column: usize,
        /// $I\_{ij}$.
        upper: Real,
        /// $I\_{ji}$.
        lower: Real,
    },
    /// A principal moment is zero or negative.
    #[error("the inertia tensor is not positive definite: principal moment {moment:e}; every principal moment must be positive")]
    NotPositiveDefinite {
        /// The smallest principal moment.
        moment: Real,
    },
    /// A point mass has no extent: it cannot rotate and has no inertia tensor.
    #[error("a point mass has no inertia tensor: it cannot rotate")]
    PointMass,
    /// One principal moment exceeds the sum of the other two.
    #[error("the principal moments ({0:e}, {1:e}, {2:e}) violate the triangle inequality: no mass distribution has them", moments[0], moments[1], moments[2])]
    TriangleInequality {
        /// The principal moments.
        moments: [Real; 3],
    },
}

/// A validated inertia tensor about the centroid, in the body frame, with its principal axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InertiaTensor {
    tensor: Mat3,
    moments: Vec3,
    principal: UnitQuaternion<Real>,
}

impl InertiaTensor {
    /// Checks `tensor` (body frame, about the centroid; units mass · length²) and finds its
    /// principal axes.
    ///
    /// # Errors
    /// A non-finite entry, asymmetry beyond rounding, a principal moment that is not positive,
    /// principal moments violating the triangle inequalities.
    pub fn new(tensor: Mat3) -> Result<Self, InertiaError> {
        for row in 0..3 {
            for column in 0..3 {
                let value = tensor[(row, column)];
                if !value.is_finite() {
                    return Err(InertiaError::NotFinite { row, column, value });
                }
            }
        }
        let scale = tensor.amax();
        for (row, column) in [(0, 1), (0, 2), (1, 2)] {
            let (upper, lower) = (tensor[(row, column)], tensor[(column, row)]);
            if (upper - lower).abs() > SYMMETRY_RELATIVE * scale {
                return Err(InertiaError::NotSymmetric {
                    row,
                    column,
                    upper,
                    lower,
                });
            }
        }
        let symmetric = (tensor + tensor.transpose()) * 0.5;
        let eigen = SymmetricEigen::new(symmetric);
        let mut moments = eigen.eigenvalues;
        let mut axes = eigen.eigenvectors;
        let smallest = moments.min();
        if smallest.is_nan() || smallest <= 0.0 {
            return Err(InertiaError::NotPositiveDefinite { moment: smallest });
        }
        let sum = moments.sum();
        for i in 0..3 {
            if moments[i] > (sum - moments[i]) + TRIANGLE_RELATIVE * sum {
                return Err(InertiaError::TriangleInequality {
                    moments: [moments[0], moments[1], moments[2]],
                });
            }
        }
        // Principal axes as a proper rotation (principal frame → body frame), ordered as the
        // body axes they are closest to, so a diagonal tensor keeps the identity.
        let mut order = [0usize, 1, 2];
        for (target, slot) in order.iter_mut().enumerate() {
            *slot = (0..3)
                .max_by(|&i, &j| axes[(target, i)].abs().total_cmp(&axes[(target, j)].abs()))
                .unwrap_or(target);
        }
        let distinct = order[0] != order[1] && order[1] != order[2] && order[0] != order[2];
        if distinct {
            let (m, a) = (moments, axes);
            for (k, &i) in order.iter().enumerate() {
                moments[k] = m[i];
                axes.set_column(k, &a.column(i));
            }
        }
        for k in 0..3 {
            if axes[(k, k)] < 0.0 {
                axes.set_column(k, &(-axes.column(k)));
            }
        }
        if axes.determinant() < 0.0 {
            axes.set_column(2, &(-axes.column(2)));
        }
        let principal = UnitQuaternion::from_matrix(&axes);
        Ok(Self {
            tensor: symmetric,
            moments,
            principal,
        })
    }

    /// $\tfrac m5\\,\mathrm{diag}(b^2+c^2, a^2+c^2, a^2+b^2)$: a homogeneous solid ellipsoid of
    /// mass `mass` and semi-axes `a`, `b`, `c` along the body x, y, z axes.
    ///
    /// # Errors
    /// Non-positive or non-finite mass or semi-axes (as [`InertiaTensor::new`] reports them).
    pub fn solid_ellipsoid(mass: Real, a: Real, b: Real, c: Real) -> Result<Self, InertiaError> {
        let (a2, b2, c2) = (a * a, b * b, c * c);
        Self::new(Mat3::from_diagonal(&Vec3::new(b2 + c2, a2 + c2, a2 + b2)) * (mass / 5.0))
    }

    /// $\mathrm{diag}(mR^2/4, mR^2/4, mR^2/2)$: a uniform disk of mass `mass` and radius
    /// `radius` in the body x–y plane.
    ///
    /// # Errors
    /// Non-positive or non-finite mass or radius.
    pub fn uniform_disk(mass: Real, radius: Real) -> Result<Self, InertiaError> {
        let q = mass * radius * radius / 4.0;
        Self::new(Mat3::from_diagonal(&Vec3::new(q, q, 2.0 * q)))
    }

    /// The tensor (body frame, about the centroid).
    pub fn tensor(&self) -> &Mat3 {
        &self.tensor
    }

    /// Principal moments, in the order of the principal axes of [`Self::principal_axes`].
    pub fn principal_moments(&self) -> Vec3 {
        self.moments
    }

    /// The rotation taking principal-frame vectors to body-frame vectors: its columns are the
    /// principal axes. The identity for a diagonal tensor.
    pub fn principal_axes(&self) -> UnitQuaternion<Real> {
        self.principal
    }

    /// $\mathsf I^{-1}\mathbf L$: the angular velocity of body-frame angular momentum `l`.
    pub fn angular_velocity(&self, l: &Vec3) -> Vec3 {
        let p = self.principal.inverse_transform_vector(l);
        self.principal * p.component_div(&self.moments)
    }

    /// $\mathsf I\boldsymbol\omega$: the angular momentum of body-frame angular velocity `w`.
    pub fn angular_momentum(&self, w: &Vec3) -> Vec3 {
        self.tensor * w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_forms_are_diagonal_with_identity_axes() {
        let i = InertiaTensor::solid_ellipsoid(2.0, 3.0, 2.0, 1.0).unwrap();
        assert_eq!(i.principal_moments(), Vec3::new(2.0, 4.0, 5.2));
        assert_eq!(i.principal_axes(), UnitQuaternion::identity());
        let d = InertiaTensor::uniform_disk(4.0, 1.0).unwrap();
        assert_eq!(d.principal_moments(), Vec3::new(1.0, 1.0, 2.0));
    }

    /// Brute force: $\int\rho(|x|^2\mathsf 1 - xx^T)\\,dV$ in scaled spherical coordinates
    /// $x = (a\\,r\sin\theta\cos\phi, b\\,r\sin\theta\sin\phi, c\\,r\cos\theta)$ with
    /// Gauss rules exact for the polynomial integrands (3 points in r, 3 in cos θ, 8 in φ), so
    /// the sum agrees with the closed form to rounding.
    #[test]
    fn closed_forms_match_a_volume_integral() {
        let gauss3 = [
            (-(0.6f64.sqrt()), 5.0 / 9.0),
            (0.0, 8.0 / 9.0),
            (0.6f64.sqrt(), 5.0 / 9.0),
        ];
        let (mass, a, b, c) = (3.0, 2.0, 1.5, 0.5);
        let density = mass / (4.0 / 3.0 * std::f64::consts::PI * a * b * c);
        let mut sum = Mat3::zeros();
        for &(xr, wr) in &gauss3 {
            let r = 0.5 * (xr + 1.0);
            for &(u, wu) in &gauss3 {
                let s = (1.0 - u * u).sqrt();
                for k in 0..8 {
                    let phi = k as Real * std::f64::consts::PI / 4.0;
                    let x = Vec3::new(a * r * s * phi.cos(), b * r * s * phi.sin(), c * r * u);
                    let w = 0.5 * wr * r * r * wu * (std::f64::consts::PI / 4.0) * a * b * c;
                    sum +=
                        (Mat3::identity() * x.norm_squared() - x * x.transpose()) * (w * density);
                }
            }
        }
        let closed = InertiaTensor::solid_ellipsoid(mass, a, b, c).unwrap();
        assert!(
            (sum - closed.tensor()).amax() < 1e-14 * closed.tensor().amax(),
            "{sum}"
        );
        // The disk: surface density m / πR², x = (ρ cos φ, ρ sin φ, 0), dA = ρ dρ dφ.
        let (mass, radius) = (2.0, 1.5);
        let sigma = mass / (std::f64::consts::PI * radius * radius);
        let mut sum = Mat3::zeros();
        for &(xr, wr) in &gauss3 {
            let rho = 0.5 * radius * (xr + 1.0);
            for k in 0..8 {
                let phi = k as Real * std::f64::consts::PI / 4.0;
                let x = Vec3::new(rho * phi.cos(), rho * phi.sin(), 0.0);
                let w = 0.5 * radius * wr * rho * (std::f64::consts::PI / 4.0);
                sum += (Mat3::identity() * x.norm_squared() - x * x.transpose()) * (w * sigma);
            }
        }
        let closed = InertiaTensor::uniform_disk(mass, radius).unwrap();
        assert!(
            (sum - closed.tensor()).amax() < 1e-14 * closed.tensor().amax(),
            "{sum}"
        );
    }

    #[test]
    fn bad_tensors_are_refused() {
        let bad = |m: Mat3| InertiaTensor::new(m).unwrap_err();
        assert!(matches!(
            bad(Mat3::from_diagonal(&Vec3::new(1.0, 1.0, 3.0))),
            InertiaError::TriangleInequality { .. }
        ));
        assert!(matches!(
            bad(Mat3::from_diagonal(&Vec3::new(1.0, -1.0, 1.0))),
            InertiaError::NotPositiveDefinite { .. }
        ));
        let mut m = Mat3::identity();
        m[(0, 1)] = 0.1;
        assert!(matches!(bad(m), InertiaError::NotSymmetric { .. }));
        m[(0, 1)] = Real::NAN;
        assert!(matches!(bad(m), InertiaError::NotFinite { .. }));
        assert!(InertiaTensor::solid_ellipsoid(-1.0, 1.0, 1.0, 1.0).is_err());
        assert!(InertiaTensor::uniform_disk(1.0, Real::NAN).is_err());
    }

    #[test]
    fn rotated_tensor_recovers_principal_frame() {
        let r = UnitQuaternion::from_scaled_axis(Vec3::new(0.3, -0.2, 0.7));
        let d = Mat3::from_diagonal(&Vec3::new(2.0, 3.0, 4.0));
        let m = r.to_rotation_matrix().matrix() * d * r.to_rotation_matrix().matrix().transpose();
        let i = InertiaTensor::new(m).unwrap();
        // I P = P D: the principal axes diagonalise the tensor.
        let p = *i.principal_axes().to_rotation_matrix().matrix();
        let back = p.transpose() * m * p;
        assert!((back - Mat3::from_diagonal(&i.principal_moments())).amax() < 1e-14);
        // ω = I⁻¹ L round-trips.
        let w = Vec3::new(0.1, -0.4, 0.25);
        let l = i.angular_momentum(&w);
        assert!((i.angular_velocity(&l) - w).amax() < 1e-15);
    }
}
