//! Interaction models: the force between two bodies and their mutual potential energy.
//!
//! # Conventions
//!
//! With $\mathbf r = \mathbf R_B - \mathbf R_A$, $r = |\mathbf r|$ and the mutual potential energy
//! $V$ (negative for gravity), the force on A is $\mathbf F_A = -\nabla\_{\mathbf R_A} V$ and the
//! force on B is $\mathbf F_B = -\mathbf F_A$ (Newton's third law; the models return $\mathbf F_A$
//! only). For a central pair $V = V(r)$,
//! $$\mathbf F_A = V'(r)\\,\hat{\mathbf r},$$
//! which points from A toward B when $V' > 0$ (attraction). For two point masses
//! $V = -G m_A m_B / r$ and $\mathbf F_A = G m_A m_B\\, \mathbf r / r^3$.
//!
//! The energy is a separate method because the integrators never need it: it is evaluated only
//! for diagnostics and output.

use crate::state::TwoBodyState;
use surfgrav_potentials::{InertiaTensor, Pose, PoseExt, Real, Vec3};
use thiserror::Error;

/// Force on A and the torques on both bodies about their own centroids, world frame, from one
/// evaluation (the force on B is $-\mathbf F_A$).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wrench {
    /// Force on A.
    pub force_on_a: Vec3,
    /// Torque on A about A's centroid.
    pub torque_on_a: Vec3,
    /// Torque on B about B's centroid.
    pub torque_on_b: Vec3,
}

/// Which equations a run integrates, and why.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionPath {
    /// Translation only: the torques vanish along the whole motion (by a symmetry the motion
    /// preserves), so each body keeps its angular velocity and its attitude turns uniformly
    /// about it, $\mathsf Q(t) = \exp\big((t - t_0)\\,\boldsymbol\omega\big)\mathsf Q_0$.
    Translation(&'static str),
    /// Translation and rotation ([`crate::rigid`]).
    Rotation(&'static str),
}

impl MotionPath {
    /// Whether attitudes and spins are integrated.
    pub fn is_rotation(&self) -> bool {
        matches!(self, MotionPath::Rotation(_))
    }

    /// Why this path.
    pub fn reason(&self) -> &'static str {
        match self {
            MotionPath::Translation(r) | MotionPath::Rotation(r) => r,
        }
    }
}

/// Why a model could not evaluate the interaction.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InteractionError {
    /// The bodies touch or overlap: the exterior formulas no longer hold.
    #[error("the bodies overlap: centroid separation {separation} is below the contact distance {contact_distance}")]
    Overlap {
        /// Centroid separation.
        separation: Real,
        /// Separation at which the bodies touch (in this configuration).
        contact_distance: Real,
    },
    /// The centroids coincide (point masses), where the force is undefined.
    #[error("the centroids coincide: the interaction is singular")]
    Coincident,
    /// The separation lies outside the range a tabulated model covers.
    #[error("separation {separation} is outside the tabulated range [{min_separation}, {max_separation}]; rebuild the table over a wider range")]
    OutsideRange {
        /// Centroid separation.
        separation: Real,
        /// Smallest tabulated separation.
        min_separation: Real,
        /// Largest tabulated separation.
        max_separation: Real,
    },
    /// The model produced a NaN or infinite value.
    #[error("the {quantity} is not finite ({value}) at separation {separation}")]
    NotFinite {
        /// `"force"` or `"energy"`.
        quantity: &'static str,
        /// The offending value (first non-finite component for a vector).
        value: Real,
        /// Centroid separation.
        separation: Real,
    },
    /// The surface-integral engine failed (the requested tolerance was not met within the
    /// evaluation budget, its result was not finite, ...): its typed error, with the separation.
    #[error("the interaction could not be computed at separation {separation}: {source}")]
    Engine {
        /// Centroid separation.
        separation: Real,
        /// The engine's error, saying what to change.
        source: surfgrav_interaction::InteractionError,
    },
}

/// The interaction of two rigid bodies A and B.
///
/// Object safe: a scene can hold `Box<dyn InteractionModel>`.
pub trait InteractionModel: Send + Sync {
    /// Mass of body A.
    fn mass_a(&self) -> Real;
    /// Mass of body B.
    fn mass_b(&self) -> Real;

    /// Force on A for the bodies placed by `pose_a` and `pose_b`; the force on B is its negative.
    fn force_on_a(&self, pose_a: &Pose, pose_b: &Pose) -> Result<Vec3, InteractionError>;

    /// Mutual potential energy $V$ (negative for gravity).
    fn potential_energy(&self, pose_a: &Pose, pose_b: &Pose) -> Result<Real, InteractionError>;

    /// Torques on A and on B about their own centroids, for models that can compute them.
    ///
    /// `Ok(None)` (the default) declares that the torques vanish identically, as for point
    /// masses and central pairs. The integrators of this crate carry orientations unchanged, so
    /// they refuse a start where this returns torques that are not negligible (see
    /// [`crate::integrate::DynamicsError::TorquesNotSupported`]).
    fn torques(
        &self,
        pose_a: &Pose,
        pose_b: &Pose,
    ) -> Result<Option<(Vec3, Vec3)>, InteractionError> {
        let _ = (pose_a, pose_b);
        Ok(None)
    }

    /// Inertia tensor of A about its centroid, body frame; `None` (the default) when A cannot
    /// rotate (a point mass) or the model does not say.
    fn inertia_a(&self) -> Option<InertiaTensor> {
        None
    }

    /// Inertia tensor of B (as [`InteractionModel::inertia_a`]).
    fn inertia_b(&self) -> Option<InertiaTensor> {
        None
    }

    /// Force and torques from one evaluation. The default calls
    /// [`InteractionModel::force_on_a`] and [`InteractionModel::torques`] (zero torques where
    /// those vanish identically); models that compute both in one pass override it.
    fn wrench(&self, pose_a: &Pose, pose_b: &Pose) -> Result<Wrench, InteractionError> {
        let force_on_a = self.force_on_a(pose_a, pose_b)?;
        let (torque_on_a, torque_on_b) = self
            .torques(pose_a, pose_b)?
            .unwrap_or((Vec3::zeros(), Vec3::zeros()));
        Ok(Wrench {
            force_on_a,
            torque_on_a,
            torque_on_b,
        })
    }

    /// Which equations a run from `initial` needs. The default: rotation when either body has
    /// an inertia tensor, translation otherwise (the torques of a model without rotating bodies
    /// vanish identically).
    fn motion_path(&self, initial: &TwoBodyState) -> MotionPath {
        let _ = initial;
        if self.inertia_a().is_some() || self.inertia_b().is_some() {
            MotionPath::Rotation("the bodies have inertia tensors and may exert torques")
        } else {
            MotionPath::Translation("no body can rotate")
        }
    }

    /// Centroid separation at which the bodies touch, if they can touch (None for point masses).
    ///
    /// For bodies that are not spheres the value may depend on the orientations, hence the poses.
    fn contact_distance(&self, pose_a: &Pose, pose_b: &Pose) -> Option<Real> {
        let _ = (pose_a, pose_b);
        None
    }
}

fn check_force(force: Vec3, separation: Real) -> Result<Vec3, InteractionError> {
    match force.iter().find(|x| !x.is_finite()) {
        Some(&value) => Err(InteractionError::NotFinite {
            quantity: "force",
            value,
            separation,
        }),
        None => Ok(force),
    }
}

fn check_energy(energy: Real, separation: Real) -> Result<Real, InteractionError> {
    if energy.is_finite() {
        Ok(energy)
    } else {
        Err(InteractionError::NotFinite {
            quantity: "energy",
            value: energy,
            separation,
        })
    }
}

/// Two point masses: $V = -G m_A m_B / r$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMasses {
    mass_a: Real,
    mass_b: Real,
    gravitational_constant: Real,
}

impl PointMasses {
    /// Two point masses with gravitational constant `gravitational_constant`. Returns `None`
    /// unless all three are positive and finite.
    pub fn new(mass_a: Real, mass_b: Real, gravitational_constant: Real) -> Option<Self> {
        let ok = |x: Real| x.is_finite() && x > 0.0;
        (ok(mass_a) && ok(mass_b) && ok(gravitational_constant)).then_some(Self {
            mass_a,
            mass_b,
            gravitational_constant,
        })
    }

    /// $G (m_A + m_B)$, the gravitational parameter of the relative orbit.
    pub fn gravitational_parameter(&self) -> Real {
        self.gravitational_constant * (self.mass_a + self.mass_b)
    }
}

impl InteractionModel for PointMasses {
    fn mass_a(&self) -> Real {
        self.mass_a
    }
    fn mass_b(&self) -> Real {
        self.mass_b
    }
    fn force_on_a(&self, pose_a: &Pose, pose_b: &Pose) -> Result<Vec3, InteractionError> {
        let r = pose_b.position() - pose_a.position();
        let d = r.norm();
        if d == 0.0 {
            return Err(InteractionError::Coincident);
        }
        let k = self.gravitational_constant * self.mass_a * self.mass_b;
        check_force(r * (k / (d * d * d)), d)
    }
    fn potential_energy(&self, pose_a: &Pose, pose_b: &Pose) -> Result<Real, InteractionError> {
        let d = (pose_b.position() - pose_a.position()).norm();
        if d == 0.0 {
            return Err(InteractionError::Coincident);
        }
        check_energy(
            -self.gravitational_constant * self.mass_a * self.mass_b / d,
            d,
        )
    }
}

/// A central pair: the energy depends on the separation only, $V = V(r)$, given as two functions
/// (the energy and its derivative $\mathrm dV/\mathrm dr$), with an optional contact distance
/// below which the functions are not evaluated (an [`InteractionError::Overlap`] is returned).
pub struct CentralPair<E, D> {
    mass_a: Real,
    mass_b: Real,
    energy: E,
    derivative: D,
    contact_distance: Option<Real>,
}

impl<E, D> std::fmt::Debug for CentralPair<E, D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CentralPair")
            .field("mass_a", &self.mass_a)
            .field("mass_b", &self.mass_b)
            .field("contact_distance", &self.contact_distance)
            .finish_non_exhaustive()
    }
}

impl<E, D> CentralPair<E, D>
where
    E: Fn(Real) -> Real + Send + Sync,
    D: Fn(Real) -> Real + Send + Sync,
{
    /// A central pair of masses `mass_a`, `mass_b` with energy $V(r)$ = `energy(r)` and
    /// $V'(r)$ = `derivative(r)`. Returns `None` unless both masses are positive and finite.
    pub fn new(mass_a: Real, mass_b: Real, energy: E, derivative: D) -> Option<Self> {
        let ok = |x: Real| x.is_finite() && x > 0.0;
        (ok(mass_a) && ok(mass_b)).then_some(Self {
            mass_a,
            mass_b,
            energy,
            derivative,
            contact_distance: None,
        })
    }

    /// The same pair, touching at centroid separation `distance` (for spheres: the sum of the
    /// radii). Returns `None` unless `distance` is positive and finite.
    pub fn with_contact_distance(self, distance: Real) -> Option<Self> {
        (distance.is_finite() && distance > 0.0).then_some(Self {
            contact_distance: Some(distance),
            ..self
        })
    }

    fn separation(&self, pose_a: &Pose, pose_b: &Pose) -> Result<(Vec3, Real), InteractionError> {
        let r = pose_b.position() - pose_a.position();
        let d = r.norm();
        if let Some(contact_distance) = self.contact_distance {
            if d < contact_distance {
                return Err(InteractionError::Overlap {
                    separation: d,
                    contact_distance,
                });
            }
        }
        if d == 0.0 {
            return Err(InteractionError::Coincident);
        }
        Ok((r, d))
    }
}

impl<E, D> InteractionModel for CentralPair<E, D>
where
    E: Fn(Real) -> Real + Send + Sync,
    D: Fn(Real) -> Real + Send + Sync,
{
    fn mass_a(&self) -> Real {
        self.mass_a
    }
    fn mass_b(&self) -> Real {
        self.mass_b
    }
    fn force_on_a(&self, pose_a: &Pose, pose_b: &Pose) -> Result<Vec3, InteractionError> {
        let (r, d) = self.separation(pose_a, pose_b)?;
        check_force(r * ((self.derivative)(d) / d), d)
    }
    fn potential_energy(&self, pose_a: &Pose, pose_b: &Pose) -> Result<Real, InteractionError> {
        let (_, d) = self.separation(pose_a, pose_b)?;
        check_energy((self.energy)(d), d)
    }
    fn contact_distance(&self, _pose_a: &Pose, _pose_b: &Pose) -> Option<Real> {
        self.contact_distance
    }
}
