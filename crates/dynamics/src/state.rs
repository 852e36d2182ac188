//! The state of two rigid bodies in an inertial frame.
//!
//! Each body carries its centroid position $\mathbf R$ and velocity $\dot{\mathbf R}$, and also its
//! orientation (a unit quaternion, body frame → world frame) and angular velocity $\boldsymbol\omega$
//! (world frame). Where the torques vanish along the whole motion by symmetry, the attitude
//! turns uniformly about the constant angular velocity; otherwise [`crate::rigid`] integrates
//! it.

use nalgebra::UnitQuaternion;
use surfgrav_potentials::{Pose, PoseExt, Real, Vec3};

/// Position, velocity, orientation and spin of one rigid body (world frame, problem units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyState {
    /// Centroid position.
    pub position: Vec3,
    /// Centroid velocity.
    pub velocity: Vec3,
    /// Body frame → world frame.
    pub orientation: UnitQuaternion<Real>,
    /// Angular velocity in the world frame.
    pub angular_velocity: Vec3,
}

impl BodyState {
    /// A non-rotating body at `position` moving with `velocity`, body frame aligned with the world.
    pub fn new(position: Vec3, velocity: Vec3) -> Self {
        Self {
            position,
            velocity,
            orientation: UnitQuaternion::identity(),
            angular_velocity: Vec3::zeros(),
        }
    }

    /// Where the body is: centroid and orientation.
    pub fn pose(&self) -> Pose {
        Pose::from_position_rotation(self.position, self.orientation)
    }

    /// The same body with its attitude turned by its own angular velocity over `elapsed`:
    /// $\mathsf Q \leftarrow \exp(\text{elapsed}\\,\boldsymbol\omega)\\,\mathsf Q$ (uniform spin
    /// about a fixed axis: exact for a torque-free sphere, and for an axisymmetric body spinning
    /// about its symmetry axis).
    pub fn spun(&self, elapsed: Real) -> Self {
        if self.angular_velocity == Vec3::zeros() || elapsed == 0.0 {
            return *self;
        }
        Self {
            orientation: UnitQuaternion::from_scaled_axis(self.angular_velocity * elapsed)
                * self.orientation,
            ..*self
        }
    }

    /// True when every component is finite.
    pub fn is_finite(&self) -> bool {
        self.position.iter().all(|x| x.is_finite())
            && self.velocity.iter().all(|x| x.is_finite())
            && self.orientation.coords.iter().all(|x| x.is_finite())
            && self.angular_velocity.iter().all(|x| x.is_finite())
    }
}

/// Both bodies, A and B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoBodyState {
    /// Body A.
    pub body_a: BodyState,
    /// Body B.
    pub body_b: BodyState,
}

impl TwoBodyState {
    /// Both bodies.
    pub fn new(body_a: BodyState, body_b: BodyState) -> Self {
        Self { body_a, body_b }
    }

    /// Relative position $\mathbf r = \mathbf R_B - \mathbf R_A$.
    pub fn relative_position(&self) -> Vec3 {
        self.body_b.position - self.body_a.position
    }

    /// Relative velocity $\dot{\mathbf r} = \dot{\mathbf R}\_B - \dot{\mathbf R}\_A$.
    pub fn relative_velocity(&self) -> Vec3 {
        self.body_b.velocity - self.body_a.velocity
    }

    /// Centroid separation $|\mathbf r|$.
    pub fn separation(&self) -> Real {
        self.relative_position().norm()
    }

    /// True when every component of both bodies is finite.
    pub fn is_finite(&self) -> bool {
        self.body_a.is_finite() && self.body_b.is_finite()
    }
}

/// One point of a trajectory: the time, the state and the translational accelerations there.
///
/// The accelerations make a quintic Hermite interpolant between consecutive samples possible
/// (position, velocity and acceleration known at both ends), which is the dense output used by
/// every integrator of this crate (see [`crate::interpolate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time.
    pub time: Real,
    /// State at `time`.
    pub state: TwoBodyState,
    /// Acceleration of body A's centroid at `time`.
    pub acceleration_a: Vec3,
    /// Acceleration of body B's centroid at `time`.
    pub acceleration_b: Vec3,
}

impl Sample {
    /// Relative acceleration $\ddot{\mathbf r}$.
    pub fn relative_acceleration(&self) -> Vec3 {
        self.acceleration_b - self.acceleration_a
    }
}
