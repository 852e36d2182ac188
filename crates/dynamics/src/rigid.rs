//! The full two-body problem: translation and rotation of two rigid bodies under their mutual
//! gravity, in 3-D.
//!
//! # Equations
//!
//! Each body $k \in \\{A, B\\}$ has its centroid $\mathbf R_k$, velocity $\dot{\mathbf R}\_k$,
//! attitude $\mathsf Q_k$ (a unit quaternion, body frame → world frame) and body-frame angular
//! momentum $\boldsymbol\Pi_k = \mathsf I_k\boldsymbol\omega_k$ about its centroid, with
//! $\mathsf I_k$ its inertia tensor in the body frame ([`surfgrav_potentials::inertia`]). With the
//! force $\mathbf F_A = -\mathbf F_B$ and the torques $\mathbf M_A, \mathbf M_B$ (world frame,
//! each about its own centroid) from one evaluation of the model ([`InteractionModel::wrench`]),
//! $$m_k\ddot{\mathbf R}\_k = \mathbf F_k,\qquad
//! \dot{\mathsf Q}\_k = \tfrac12\\,\mathsf Q_k\otimes(0, \boldsymbol\omega_k),\qquad
//! \dot{\boldsymbol\Pi}\_k = \boldsymbol\Pi_k\times\boldsymbol\omega_k + \mathsf Q_k^{-1}\mathbf M_k,$$
//! the last being Euler's equations $\mathsf I\dot{\boldsymbol\omega} + \boldsymbol\omega\times\mathsf I\boldsymbol\omega = \mathbf M$
//! in the body frame. A body without an inertia tensor (a point mass) cannot rotate: its
//! angular velocity must be zero and its attitude stays as given.
//!
//! Conserved: the energy
//! $E = \sum_k \big(\tfrac12 m_k|\dot{\mathbf R}\_k|^2 + \tfrac12\boldsymbol\omega_k\cdot\boldsymbol\Pi_k\big) + V$ and the total angular momentum
//! about the origin $\mathbf J = \sum_k \big(m_k\mathbf R_k\times\dot{\mathbf R}\_k + \mathsf Q_k\boldsymbol\Pi_k\big)$,
//! because the model's torques obey $\mathbf M_B = -\mathbf M_A - (\mathbf R_A - \mathbf R_B)\times\mathbf F_A$.
//!
//! # Geometric integrators (`leapfrog`, `yoshida4`, `yoshida6`, `yoshida8`)
//!
//! The splitting of Dullweber, Leimkuhler & McLachlan (1997): $H = T\_{\mathrm{trans}} + T\_{\mathrm{rot}} + V$,
//! a step of length $h$ is kick($h/2$) – drift($h$) – kick($h/2$):
//! - kick: $\dot{\mathbf R}\_k \mathrel{+}= \tfrac h2\\,\mathbf F_k/m_k$ and
//!   $\boldsymbol\Pi_k \mathrel{+}= \tfrac h2\\,\mathsf Q_k^{-1}\mathbf M_k$ (the exact flow of $V$);
//! - drift: $\mathbf R_k \mathrel{+}= h\dot{\mathbf R}\_k$, and the free rigid body split into
//!   its principal terms $T\_{\mathrm{rot}} = \sum_i \Pi_i^2/2I_i$ as
//!   $R_1(h/2)\\,R_2(h/2)\\,R_3(h)\\,R_2(h/2)\\,R_1(h/2)$, where $R_i(t)$ is the exact flow of
//!   $\Pi_i^2/2I_i$: a rotation about the principal axis $i$ by $\theta = t\\,\Pi_i/I_i$,
//!   $\mathsf Q \leftarrow \mathsf Q\otimes\exp(\theta\mathbf e_i/2)$,
//!   $\boldsymbol\Pi \leftarrow \exp(-\theta\mathbf e_i/2)\\,\boldsymbol\Pi$.
//!
//! Every piece is the exact flow of a Hamiltonian term, so the step is symplectic; it is
//! symmetric, so time reversible and of order 2; the compositions of [`FixedScheme`] raise it to
//! orders 4, 6 and 8. Each piece conserves $\mathbf J$ exactly (the kick because of the torque
//! balance, the drift because free motions conserve it), so $\mathbf J$ is kept to round-off;
//! attitudes are products of unit quaternions, renormalised after each step, so they stay
//! orthonormal to round-off. One model evaluation per sub-step (first same as last).
//!
//! # Runge–Kutta integrators (`rk4`, `dopri5`, `dop853`)
//!
//! The same equations as one first-order system of 26 components (positions, velocities,
//! quaternions, body angular momenta), stepped by classical RK4 or the embedded pairs with the
//! step control of [`crate::integrate`]. The error of a component is scaled by
//! $\mathrm{atol} + \mathrm{rtol}\max(|\mathbf g_0|, |\mathbf g_1|)$ with $\mathbf g$ the
//! 3-vector (or quaternion) it belongs to, so that a component that happens to be near zero is
//! held to the accuracy of its vector. The quaternions are projected back onto the unit sphere
//! after each accepted step (and their stages are normalised before use), which keeps the
//! attitudes on the rotation group.
//!
//! # Dense output
//!
//! DOP853 uses its own continuous extension of order 7 (three more evaluations in a step holding
//! an output time); the other methods interpolate positions and velocities by the quintic
//! Hermite interpolant and quaternions and angular momenta by the cubic Hermite interpolant of
//! their values and derivatives at both ends (local error $O(h^4)$). Quaternions are normalised.

use crate::integrate::{
    check_span, escaped, ContactEvent, DynamicsError, FixedGrid, FixedScheme, RunSummary,
    StepControl, Termination,
};
use crate::interpolate::{hermite_quintic, EvenStates};
use crate::model::{InteractionError, InteractionModel, Wrench};
use crate::state::{BodyState, Sample, TwoBodyState};
use crate::tableau::{Tableau, DOP853, DOP853_D, DOP853_DENSE_A, MAX_STAGES};
use nalgebra::{Quaternion, UnitQuaternion};
use surfgrav_potentials::{InertiaTensor, Pose, PoseExt, Real, Vec3};

/// Components of the flat state: $\mathbf R_A, \mathbf R_B, \dot{\mathbf R}\_A, \dot{\mathbf R}\_B$
/// (12), $\mathsf Q_A, \mathsf Q_B$ (8, scalar first), $\boldsymbol\Pi_A, \boldsymbol\Pi_B$ (6).
const N: usize = 26;
type Flat = [Real; N];
/// Start of the quaternions and of the angular momenta in [`Flat`].
const Q0: usize = 12;
const L0: usize = 20;

/// The state of both bodies with body-frame angular momenta.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rigid {
    x: [Vec3; 2],
    v: [Vec3; 2],
    q: [UnitQuaternion<Real>; 2],
    l: [Vec3; 2],
}

impl Rigid {
    fn flat(&self) -> Flat {
        let mut y = [0.0; N];
        for k in 0..2 {
            for c in 0..3 {
                y[3 * k + c] = self.x[k][c];
                y[6 + 3 * k + c] = self.v[k][c];
                y[L0 + 3 * k + c] = self.l[k][c];
            }
            let q = self.q[k].quaternion();
            y[Q0 + 4 * k] = q.w;
            y[Q0 + 4 * k + 1] = q.i;
            y[Q0 + 4 * k + 2] = q.j;
            y[Q0 + 4 * k + 3] = q.k;
        }
        y
    }

    /// From a flat state, quaternions normalised (a zero quaternion gives the identity).
    fn from_flat(y: &Flat) -> Self {
        let v3 = |i: usize| Vec3::new(y[i], y[i + 1], y[i + 2]);
        let quat = |i: usize| {
            let q = Quaternion::new(y[i], y[i + 1], y[i + 2], y[i + 3]);
            UnitQuaternion::try_new(q, 0.0).unwrap_or_else(UnitQuaternion::identity)
        };
        Self {
            x: [v3(0), v3(3)],
            v: [v3(6), v3(9)],
            q: [quat(Q0), quat(Q0 + 4)],
            l: [v3(L0), v3(L0 + 3)],
        }
    }

    fn poses(&self) -> (Pose, Pose) {
        (
            Pose::from_position_rotation(self.x[0], self.q[0]),
            Pose::from_position_rotation(self.x[1], self.q[1]),
        )
    }
}

/// A state with the model's wrench there.
#[derive(Debug, Clone, Copy)]
struct Point {
    time: Real,
    state: Rigid,
    wrench: Wrench,
}

/// Where a step failed: at an intermediate stage, or at the step's end point (the trajectory
/// itself reached the model's error, e.g. contact).
enum StepError {
    Stage(InteractionError),
    End(InteractionError),
}

impl StepError {
    fn into_inner(self) -> InteractionError {
        match self {
            StepError::Stage(e) | StepError::End(e) => e,
        }
    }
    fn is_overlap(&self) -> bool {
        matches!(
            self,
            StepError::Stage(InteractionError::Overlap { .. })
                | StepError::End(InteractionError::Overlap { .. })
        )
    }
}

/// The two bodies' mass properties and the model, with an evaluation counter.
struct System<'m> {
    model: &'m dyn InteractionModel,
    mass: [Real; 2],
    inertia: [Option<InertiaTensor>; 2],
    evaluations: usize,
}

impl<'m> System<'m> {
    fn new(model: &'m dyn InteractionModel) -> Self {
        Self {
            model,
            mass: [model.mass_a(), model.mass_b()],
            inertia: [model.inertia_a(), model.inertia_b()],
            evaluations: 0,
        }
    }

    fn wrench(&mut self, state: &Rigid) -> Result<Wrench, InteractionError> {
        self.evaluations += 1;
        let (pa, pb) = state.poses();
        let w = self.model.wrench(&pa, &pb)?;
        let finite = w
            .force_on_a
            .iter()
            .chain(w.torque_on_a.iter())
            .chain(w.torque_on_b.iter())
            .find(|x| !x.is_finite());
        match finite {
            Some(&value) => Err(InteractionError::NotFinite {
                quantity: "force or torque",
                value,
                separation: (state.x[1] - state.x[0]).norm(),
            }),
            None => Ok(w),
        }
    }

    /// Body-frame angular velocity of body `k` ($\mathsf I^{-1}\boldsymbol\Pi$; zero without an
    /// inertia tensor).
    fn omega(&self, k: usize, l: &Vec3) -> Vec3 {
        self.inertia[k]
            .as_ref()
            .map_or_else(Vec3::zeros, |i| i.angular_velocity(l))
    }

    fn forces(&self, w: &Wrench) -> [Vec3; 2] {
        [w.force_on_a, -w.force_on_a]
    }

    fn torques(&self, w: &Wrench) -> [Vec3; 2] {
        let mut t = [w.torque_on_a, w.torque_on_b];
        for (k, t) in t.iter_mut().enumerate() {
            if self.inertia[k].is_none() {
                *t = Vec3::zeros();
            }
        }
        t
    }

    /// The rigid state of a two-body state: body angular momenta $\mathsf I\\,\mathsf Q^{-1}\boldsymbol\omega$.
    fn rigid(&self, state: &TwoBodyState) -> Result<Rigid, DynamicsError> {
        let bodies = [&state.body_a, &state.body_b];
        let mut l = [Vec3::zeros(); 2];
        for (k, body) in bodies.iter().enumerate() {
            match &self.inertia[k] {
                Some(i) => {
                    l[k] = i.angular_momentum(
                        &body
                            .orientation
                            .inverse_transform_vector(&body.angular_velocity),
                    )
                }
                None if body.angular_velocity != Vec3::zeros() => {
                    return Err(DynamicsError::InvalidParameter {
                        name: if k == 0 {
                            "angular_velocity of body A (a point mass cannot rotate)"
                        } else {
                            "angular_velocity of body B (a point mass cannot rotate)"
                        },
                        requirement: "zero",
                        value: body.angular_velocity.norm(),
                    });
                }
                None => {}
            }
        }
        Ok(Rigid {
            x: [state.body_a.position, state.body_b.position],
            v: [state.body_a.velocity, state.body_b.velocity],
            q: [state.body_a.orientation, state.body_b.orientation],
            l,
        })
    }

    fn two_body(&self, s: &Rigid) -> TwoBodyState {
        let body = |k: usize| BodyState {
            position: s.x[k],
            velocity: s.v[k],
            orientation: s.q[k],
            angular_velocity: s.q[k] * self.omega(k, &s.l[k]),
        };
        TwoBodyState::new(body(0), body(1))
    }

    fn sample(&self, p: &Point) -> Sample {
        let f = self.forces(&p.wrench);
        Sample {
            time: p.time,
            state: self.two_body(&p.state),
            acceleration_a: f[0] / self.mass[0],
            acceleration_b: f[1] / self.mass[1],
        }
    }

    /// The time derivative of a flat state whose quaternions have been normalised into `s`,
    /// with the wrench `w` at `s`.
    fn derivative(&self, y: &Flat, s: &Rigid, w: &Wrench) -> Flat {
        let mut d = [0.0; N];
        let f = self.forces(w);
        let t = self.torques(w);
        for k in 0..2 {
            let omega = self.omega(k, &s.l[k]);
            let a = f[k] / self.mass[k];
            let ldot = s.l[k].cross(&omega) + s.q[k].inverse_transform_vector(&t[k]);
            for c in 0..3 {
                d[3 * k + c] = y[6 + 3 * k + c];
                d[6 + 3 * k + c] = a[c];
                d[L0 + 3 * k + c] = ldot[c];
            }
            // q̇ = ½ q ⊗ (0, ω), with q as integrated (not normalised).
            let i = Q0 + 4 * k;
            let q = Quaternion::new(y[i], y[i + 1], y[i + 2], y[i + 3]);
            let qdot = (q * Quaternion::from_parts(0.0, omega)) * 0.5;
            d[i] = qdot.w;
            d[i + 1] = qdot.i;
            d[i + 2] = qdot.j;
            d[i + 3] = qdot.k;
        }
        d
    }

    /// Wrench and derivative at a flat state (normalising its quaternions for the pose).
    fn evaluate(&mut self, y: &Flat) -> Result<(Flat, Wrench), InteractionError> {
        let s = Rigid::from_flat(y);
        let w = self.wrench(&s)?;
        Ok((self.derivative(y, &s, &w), w))
    }

    fn initial(&mut self, state: &TwoBodyState, time: Real) -> Result<Point, DynamicsError> {
        if !state.is_finite() {
            return Err(DynamicsError::NonFinite { time });
        }
        let rigid = self.rigid(state)?;
        let wrench = self
            .wrench(&rigid)
            .map_err(|source| DynamicsError::Interaction { time, source })?;
        Ok(Point {
            time,
            state: rigid,
            wrench,
        })
    }

    /// Total energy and angular momentum are the diagnostics' business; here only the contact
    /// test: the model's contact distance where it has one (orientation dependent otherwise:
    /// the model's overlap error is the event).
    fn touching(&self, s: &Rigid) -> bool {
        let (pa, pb) = s.poses();
        self.model
            .contact_distance(&pa, &pb)
            .is_some_and(|d| (s.x[1] - s.x[0]).norm() <= d)
    }
}

/// Rotation about principal axis `axis` by `angle`.
fn axis_rotation(axis: usize, angle: Real) -> UnitQuaternion<Real> {
    let mut v = Vec3::zeros();
    v[axis] = angle;
    UnitQuaternion::from_scaled_axis(v)
}

/// The exact free rotation of one body over `h` by the symmetric splitting of the module docs.
fn free_rotation(inertia: &InertiaTensor, q: &mut UnitQuaternion<Real>, l: &mut Vec3, h: Real) {
    let p = inertia.principal_axes();
    let moments = inertia.principal_moments();
    // Principal frame: Q = q p, Π = p⁻¹ l.
    let mut big_q = *q * p;
    let mut pi = p.inverse_transform_vector(l);
    for (axis, fraction) in [(0, 0.5), (1, 0.5), (2, 1.0), (1, 0.5), (0, 0.5)] {
        let theta = fraction * h * pi[axis] / moments[axis];
        if theta != 0.0 {
            let r = axis_rotation(axis, theta);
            big_q *= r;
            pi = r.inverse_transform_vector(&pi);
        }
    }
    *q = big_q * p.inverse();
    *l = p * pi;
}

impl System<'_> {
    fn kick(&self, s: &mut Rigid, w: &Wrench, h: Real) {
        let f = self.forces(w);
        let t = self.torques(w);
        for k in 0..2 {
            s.v[k] += f[k] * (h / self.mass[k]);
            if self.inertia[k].is_some() {
                s.l[k] += s.q[k].inverse_transform_vector(&t[k]) * h;
            }
        }
    }

    fn drift(&self, s: &mut Rigid, h: Real) {
        for k in 0..2 {
            s.x[k] += s.v[k] * h;
            if let Some(i) = &self.inertia[k] {
                free_rotation(i, &mut s.q[k], &mut s.l[k], h);
            }
        }
    }

    /// One composed kick–drift–kick step.
    fn splitting_step(
        &mut self,
        weights: &[Real],
        from: &Point,
        h: Real,
    ) -> Result<Point, StepError> {
        let mut s = from.state;
        let mut w = from.wrench;
        let last = weights.len() - 1;
        for (n, c) in weights.iter().enumerate() {
            let hc = h * c;
            self.kick(&mut s, &w, 0.5 * hc);
            self.drift(&mut s, hc);
            w = self.wrench(&s).map_err(|e| {
                if n == last {
                    StepError::End(e)
                } else {
                    StepError::Stage(e)
                }
            })?;
            self.kick(&mut s, &w, 0.5 * hc);
        }
        for q in &mut s.q {
            q.renormalize();
        }
        Ok(Point {
            time: from.time + h,
            state: s,
            wrench: w,
        })
    }

    /// One classical RK4 step on the flat state.
    fn rk4_step(&mut self, from: &Point, h: Real) -> Result<Point, StepError> {
        let y = from.state.flat();
        let k1 = self.derivative(&y, &from.state, &from.wrench);
        let at = |k: &Flat, c: Real| -> Flat { std::array::from_fn(|i| y[i] + k[i] * c) };
        let k2 = self
            .evaluate(&at(&k1, 0.5 * h))
            .map_err(StepError::Stage)?
            .0;
        let k3 = self
            .evaluate(&at(&k2, 0.5 * h))
            .map_err(StepError::Stage)?
            .0;
        let k4 = self.evaluate(&at(&k3, h)).map_err(StepError::Stage)?.0;
        let end: Flat =
            std::array::from_fn(|i| y[i] + (k1[i] + (k2[i] + k3[i]) * 2.0 + k4[i]) * (h / 6.0));
        let state = Rigid::from_flat(&end);
        let wrench = self.wrench(&state).map_err(StepError::End)?;
        Ok(Point {
            time: from.time + h,
            state,
            wrench,
        })
    }
}

/// $\mathbf y + h\sum_j a_j\mathbf k_j$ (the sum formed before the product with h).
fn combine(y: &Flat, row: &[Real], k: &[Flat], h: Real) -> Flat {
    let mut sum = [0.0; N];
    for (kj, &a) in k.iter().zip(row) {
        if a != 0.0 {
            for i in 0..N {
                sum[i] += kj[i] * a;
            }
        }
    }
    std::array::from_fn(|i| y[i] + sum[i] * h)
}

/// The norm of the vector group (3-vector or quaternion) that component `i` belongs to.
fn group_norm(y: &Flat, i: usize) -> Real {
    let (start, len) = if i >= L0 {
        (L0 + 3 * ((i - L0) / 3), 3)
    } else if i >= Q0 {
        (Q0 + 4 * ((i - Q0) / 4), 4)
    } else {
        (3 * (i / 3), 3)
    };
    y[start..start + len]
        .iter()
        .map(|x| x * x)
        .sum::<Real>()
        .sqrt()
}

/// The adaptive settings the rotational path needs from [`crate::Adaptive`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct AdaptiveSettings {
    pub tableau: &'static Tableau,
    pub dense: bool,
    pub relative_tolerance: Real,
    pub absolute_tolerance: Real,
    pub min_step: Real,
    pub max_step: Real,
    pub initial_step: Option<Real>,
    pub max_steps: usize,
}

/// How to advance: a fixed scheme or an adaptive pair.
pub(crate) enum Method<'a> {
    Fixed {
        scheme: FixedScheme,
        weights: &'a [Real],
        step: Real,
    },
    Adaptive(AdaptiveSettings),
}

/// The stage derivatives of one adaptive step.
type Stages = [Flat; MAX_STAGES];

impl AdaptiveSettings {
    fn error_norm(&self, y0: &Flat, y1: &Flat, k: &Stages, h: Real) -> Real {
        let tableau = self.tableau;
        let stages = tableau.stages();
        let scale: Flat = std::array::from_fn(|i| {
            self.absolute_tolerance
                + self.relative_tolerance * group_norm(y0, i).max(group_norm(y1, i))
        });
        let squares = |w: &dyn Fn(usize) -> Real| -> Real {
            let mut e = [0.0; N];
            for (j, kj) in k.iter().enumerate().take(stages) {
                let c = w(j);
                if c != 0.0 {
                    for i in 0..N {
                        e[i] += kj[i] * c;
                    }
                }
            }
            (0..N).map(|i| (e[i] * h / scale[i]).powi(2)).sum()
        };
        tableau.error_norm(N, squares)
    }

    fn first_step(&self, y: &Flat, f: &Flat, span: Real) -> Real {
        if let Some(h) = self.initial_step {
            return h.min(span);
        }
        let (mut d0, mut d1) = (0.0, 0.0);
        for i in 0..N {
            let scale = self.absolute_tolerance + self.relative_tolerance * group_norm(y, i);
            d0 += (y[i] / scale).powi(2);
            d1 += (f[i] / scale).powi(2);
        }
        let h = if d0 > 1e-10 && d1 > 1e-10 {
            0.01 * (d0 / d1).sqrt()
        } else {
            1e-6 * span
        };
        h.min(span).min(self.max_step)
    }
}

impl System<'_> {
    /// One step of an embedded pair from `from` (its flat state `y`, derivative `f0`); the
    /// stages are left in `k`. Returns the end point and the error norm.
    fn pair_step(
        &mut self,
        settings: &AdaptiveSettings,
        from: &Point,
        h: Real,
        k: &mut Stages,
    ) -> Result<(Point, Real), StepError> {
        let tableau = settings.tableau;
        let y = from.state.flat();
        k[0] = self.derivative(&y, &from.state, &from.wrench);
        let inner = &tableau.a[..tableau.a.len() - 1];
        for (i, row) in inner.iter().enumerate() {
            let stage = combine(&y, row, &k[..], h);
            k[i + 1] = self.evaluate(&stage).map_err(StepError::Stage)?.0;
        }
        let mut end = combine(&y, tableau.b(), &k[..], h);
        // Projection onto the unit quaternions before the last (FSAL) stage.
        let state = Rigid::from_flat(&end);
        end = state.flat();
        let wrench = self.wrench(&state).map_err(StepError::End)?;
        let last = tableau.stages() - 1;
        k[last] = self.derivative(&end, &state, &wrench);
        let error = settings.error_norm(&y, &end, k, h);
        Ok((
            Point {
                time: from.time + h,
                state,
                wrench,
            },
            error,
        ))
    }

    /// The state at `time` in the step `from` → `to`: DOP853's continuous extension when
    /// `dense` holds its coefficients, else the Hermite interpolants (module docs).
    fn between(&self, from: &Point, to: &Point, time: Real, dense: Option<&Dense>) -> Rigid {
        let h = to.time - from.time;
        if h == 0.0 || time >= to.time {
            return to.state;
        }
        if time <= from.time {
            return from.state;
        }
        let s = (time - from.time) / h;
        if let Some(d) = dense {
            return Rigid::from_flat(&d.at(s));
        }
        let (y0, y1) = (from.state.flat(), to.state.flat());
        let f0 = self.derivative(&y0, &from.state, &from.wrench);
        let f1 = self.derivative(&y1, &to.state, &to.wrench);
        // Cubic Hermite basis.
        let (s2, s3) = (s * s, s * s * s);
        let (h00, h10, h01, h11) = (
            2.0 * s3 - 3.0 * s2 + 1.0,
            s3 - 2.0 * s2 + s,
            -2.0 * s3 + 3.0 * s2,
            s3 - s2,
        );
        let mut out: Flat =
            std::array::from_fn(|i| h00 * y0[i] + h * h10 * f0[i] + h01 * y1[i] + h * h11 * f1[i]);
        for k in 0..2 {
            let v3 = |y: &Flat, i: usize| Vec3::new(y[i], y[i + 1], y[i + 2]);
            let (x, v) = hermite_quintic(
                &v3(&y0, 3 * k),
                &v3(&y0, 6 + 3 * k),
                &v3(&f0, 6 + 3 * k),
                &v3(&y1, 3 * k),
                &v3(&y1, 6 + 3 * k),
                &v3(&f1, 6 + 3 * k),
                h,
                s,
            );
            for c in 0..3 {
                out[3 * k + c] = x[c];
                out[6 + 3 * k + c] = v[c];
            }
        }
        Rigid::from_flat(&out)
    }

    /// DOP853's continuous extension over an accepted step (three more evaluations).
    fn dense(
        &mut self,
        from: &Point,
        to: &Point,
        h: Real,
        k: &mut Stages,
    ) -> Result<Dense, InteractionError> {
        let y0 = from.state.flat();
        let y1 = to.state.flat();
        let first = DOP853.stages();
        for (m, row) in DOP853_DENSE_A.iter().enumerate() {
            let stage = combine(&y0, row, &k[..], h);
            k[first + m] = self.evaluate(&stage)?.0;
        }
        let mut c = [[0.0; N]; 7];
        for i in 0..N {
            let delta = y1[i] - y0[i];
            let beta = k[0][i] * h - delta;
            c[0][i] = delta;
            c[1][i] = beta;
            c[2][i] = delta - k[first - 1][i] * h - beta;
        }
        for (r, row) in DOP853_D.iter().enumerate() {
            c[3 + r] = combine(&[0.0; N], row, &k[..], h);
        }
        Ok(Dense { y0, c })
    }
}

/// DOP853's continuous extension over one step.
struct Dense {
    y0: Flat,
    c: [Flat; 7],
}

impl Dense {
    fn at(&self, s: Real) -> Flat {
        let s1 = 1.0 - s;
        let [delta, beta, third, d4, d5, d6, d7] = &self.c;
        std::array::from_fn(|i| {
            let inner = d4[i] + (d5[i] + (d6[i] + d7[i] * s) * s1) * s;
            self.y0[i] + (delta[i] + (beta[i] + (third[i] + inner * s1) * s) * s1) * s
        })
    }
}

/// Subdivisions allowed when stages overshoot into overlap without contact.
const MAX_SUBDIVISION_DEPTH: u32 = 40;

/// A contact is located to this fraction of the step that reached it.
const CONTACT_RESOLUTION: Real = 1e-12;

/// Outcome of a step that may end in contact.
enum Advance {
    Reached(Point),
    Contact(Point),
}

impl System<'_> {
    /// Classifies a step's result: `Ok(Some)` clear, `Ok(None)` touching (contact or a stage's
    /// overlap), `Err` for any other failure.
    fn clear(
        &self,
        result: Result<Point, StepError>,
        time: Real,
    ) -> Result<Option<Point>, DynamicsError> {
        match result {
            Ok(p) => {
                let finite = p.state.flat().iter().all(|x| x.is_finite());
                if !finite {
                    return Err(DynamicsError::NonFinite { time });
                }
                Ok((!self.touching(&p.state)).then_some(p))
            }
            Err(e) if e.is_overlap() => Ok(None),
            Err(e) => Err(DynamicsError::Interaction {
                time,
                source: e.into_inner(),
            }),
        }
    }

    /// A step of `h` from `from` touched: bisect its length for the contact; when only a stage
    /// overlapped (the end point of the shortest touching step is clear of the model's error),
    /// take the step as two halves instead.
    fn advance(
        &mut self,
        from: &Point,
        h: Real,
        depth: u32,
        step: &mut dyn FnMut(&mut Self, &Point, Real) -> Result<Point, StepError>,
    ) -> Result<Advance, DynamicsError> {
        let result = step(self, from, h);
        let end_overlap = matches!(
            result,
            Err(StepError::End(InteractionError::Overlap { .. }))
        ) || matches!(&result, Ok(p) if self.touching(&p.state));
        if let Some(p) = self.clear(result, from.time)? {
            return Ok(Advance::Reached(p));
        }
        let (mut lo, mut hi) = (0.0, h);
        let mut best = *from;
        let mut hi_at_end = end_overlap;
        // Bisect to CONTACT_RESOLUTION of the step (the located contact's accuracy in time).
        while hi - lo > CONTACT_RESOLUTION * h {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let result = step(self, from, mid);
            let at_end = matches!(
                result,
                Err(StepError::End(InteractionError::Overlap { .. }))
            ) || matches!(&result, Ok(p) if self.touching(&p.state));
            match self.clear(result, from.time)? {
                Some(p) => {
                    lo = mid;
                    best = p;
                }
                None => {
                    hi = mid;
                    hi_at_end = at_end;
                }
            }
        }
        if !hi_at_end {
            // Only a stage overlapped at the boundary (RK4's last stage runs ahead of the step's
            // end): drift the last clear state over a few resolutions; if that touches, the
            // trajectory itself is at contact within them.
            let mut probe = best.state;
            self.drift(&mut probe, 4.0 * CONTACT_RESOLUTION * h);
            let (pa, pb) = probe.poses();
            self.evaluations += 1;
            hi_at_end = self.touching(&probe)
                || matches!(
                    self.model.wrench(&pa, &pb),
                    Err(InteractionError::Overlap { .. })
                );
        }
        if hi_at_end {
            return Ok(Advance::Contact(best));
        }
        // Stages that run ahead of the step's end (a composition's sub-steps of weight above 1,
        // RK4's last stage) overlap at a grazing contact however short the step: locate it
        // with the kick-drift-kick step, whose only evaluation is at its end (local error
        // O(h^3) over this last step only).
        if let Some(contact) = self.contact_by_leapfrog(from, h)? {
            return Ok(Advance::Contact(contact));
        }
        if depth >= MAX_SUBDIVISION_DEPTH {
            return Err(DynamicsError::ContactUnresolved { time: from.time });
        }
        match self.advance(from, 0.5 * h, depth + 1, step)? {
            Advance::Reached(middle) => self.advance(&middle, 0.5 * h, depth + 1, step),
            contact => Ok(contact),
        }
    }

    /// The contact within a step of `h` from `from` by bisection over kick–drift–kick steps,
    /// if such a step reaches it (`None`: the orbit stays clear over `h` by that step).
    fn contact_by_leapfrog(
        &mut self,
        from: &Point,
        h: Real,
    ) -> Result<Option<Point>, DynamicsError> {
        let touches = |system: &Self, result: &Result<Point, StepError>| match result {
            Err(StepError::End(InteractionError::Overlap { .. })) => true,
            Ok(p) => system.touching(&p.state),
            Err(_) => false,
        };
        let whole = self.splitting_step(&[1.0], from, h);
        if !touches(self, &whole) {
            return match whole {
                Err(e) if !e.is_overlap() => Err(DynamicsError::Interaction {
                    time: from.time,
                    source: e.into_inner(),
                }),
                _ => Ok(None),
            };
        }
        let (mut lo, mut hi) = (0.0, h);
        let mut best = *from;
        while hi - lo > CONTACT_RESOLUTION * h {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let result = self.splitting_step(&[1.0], from, mid);
            if touches(self, &result) {
                hi = mid;
            } else {
                match result {
                    Ok(p) => {
                        lo = mid;
                        best = p;
                    }
                    Err(e) => {
                        return Err(DynamicsError::Interaction {
                            time: from.time,
                            source: e.into_inner(),
                        })
                    }
                }
            }
        }
        Ok(Some(best))
    }

    fn contact_event(&self, p: &Point) -> ContactEvent {
        let sample = self.sample(p);
        let r = p.state.x[1] - p.state.x[0];
        let separation = r.norm();
        let (pa, pb) = p.state.poses();
        ContactEvent {
            sample,
            separation,
            contact_distance: self.model.contact_distance(&pa, &pb).unwrap_or(separation),
            direction: if separation > 0.0 {
                r / separation
            } else {
                Vec3::zeros()
            },
        }
    }

    /// The end of a run at the contact `p`, reached from `from`: emits the output times up to it
    /// (from `dense`, the step's continuous extension, when given), reports its sample to
    /// `observer` and returns the termination.
    fn stop_at_contact(
        &self,
        from: &Point,
        p: &Point,
        dense: Option<&Dense>,
        output: &mut EvenStates<'_>,
        observer: &mut dyn FnMut(&Sample),
    ) -> Termination {
        self.emit_between(from, p, dense, output);
        let event = self.contact_event(p);
        observer(&event.sample);
        Termination::Contact(Box::new(event))
    }

    fn emit_between(
        &self,
        from: &Point,
        to: &Point,
        dense: Option<&Dense>,
        output: &mut EvenStates<'_>,
    ) {
        if let Some((clock, emit)) = output.as_mut() {
            let state_at = |t| self.two_body(&self.between(from, to, t, dense));
            clock.emit_until(to.time, state_at, *emit);
        }
    }
}

/// Integrates the full two-body problem (module docs) with `method` from `initial` at `t_start`
/// to `t_end`; `observer` gets every accepted step's sample, `output` the evenly spaced states.
pub(crate) fn integrate(
    method: Method<'_>,
    model: &dyn InteractionModel,
    initial: &TwoBodyState,
    (t_start, t_end): (Real, Real),
    escape_distance: Option<Real>,
    observer: &mut dyn FnMut(&Sample),
    mut output: EvenStates<'_>,
) -> Result<RunSummary, DynamicsError> {
    check_span(t_start, t_end)?;
    let mut system = System::new(model);
    let mut current = system.initial(initial, t_start)?;
    system.emit_between(&current, &current, None, &mut output);
    observer(&system.sample(&current));
    let span = t_end - t_start;
    let finish = |system: &System<'_>, last: &Point, steps, rejected, termination| RunSummary {
        last: system.sample(last),
        steps,
        rejected_steps: rejected,
        force_evaluations: system.evaluations,
        termination,
    };
    match method {
        Method::Fixed {
            scheme,
            weights,
            step,
        } => {
            let grid = FixedGrid::new(t_start, t_end, step)?;
            let mut one = |s: &mut System<'_>, from: &Point, h: Real| match scheme {
                FixedScheme::RungeKutta4 => s.rk4_step(from, h),
                _ => s.splitting_step(weights, from, h),
            };
            for k in 1..=grid.count {
                let target = grid.target(k);
                let h = target - current.time;
                match system.advance(&current, h, 0, &mut one)? {
                    Advance::Reached(mut next) => {
                        next.time = target;
                        system.emit_between(&current, &next, None, &mut output);
                        current = next;
                        let sample = system.sample(&current);
                        observer(&sample);
                        if let Some(event) = escaped(model, escape_distance, &sample) {
                            let termination = Termination::Escape(Box::new(event));
                            return Ok(finish(&system, &current, k, 0, termination));
                        }
                    }
                    Advance::Contact(p) => {
                        let termination =
                            system.stop_at_contact(&current, &p, None, &mut output, observer);
                        return Ok(finish(&system, &p, k - 1, 0, termination));
                    }
                }
            }
            Ok(finish(
                &system,
                &current,
                grid.count,
                0,
                Termination::Completed,
            ))
        }
        Method::Adaptive(settings) => {
            let mut control = StepControl::new(
                settings.tableau,
                settings.min_step,
                settings.max_step,
                settings.max_steps,
                span,
            );
            let mut k: Stages = [[0.0; N]; MAX_STAGES];
            let y0 = current.state.flat();
            let f0 = system.derivative(&y0, &current.state, &current.wrench);
            let mut h = settings.first_step(&y0, &f0, span);
            loop {
                let (h_try, last) = control.next(h, current.time, t_end)?;
                let result = system.pair_step(&settings, &current, h_try, &mut k);
                let (result, error) = match result {
                    Ok((p, e)) => (Ok(p), e),
                    Err(e) => (Err(e), 0.0),
                };
                if !error.is_finite() {
                    return Err(DynamicsError::NonFinite { time: current.time });
                }
                if error > 1.0 {
                    h = control.reject(h_try, error);
                    continue;
                }
                match system.clear(result, current.time)? {
                    Some(mut next) => {
                        if last {
                            next.time = t_end;
                        }
                        if output.is_some() {
                            let dense = if settings.dense {
                                system.dense(&current, &next, h_try, &mut k).ok()
                            } else {
                                None
                            };
                            system.emit_between(&current, &next, dense.as_ref(), &mut output);
                        }
                        current = next;
                        let next_h = control.accept(h_try, error);
                        let sample = system.sample(&current);
                        observer(&sample);
                        if let Some(event) = escaped(model, escape_distance, &sample) {
                            let termination = Termination::Escape(Box::new(event));
                            let (steps, rejected) = (control.steps, control.rejected);
                            return Ok(finish(&system, &current, steps, rejected, termination));
                        }
                        if last {
                            break;
                        }
                        h = next_h;
                    }
                    None => {
                        let mut scratch: Stages = [[0.0; N]; MAX_STAGES];
                        // (end, length, error norm) of the trial steps, so that the step
                        // reaching the contact is error-tested like any other.
                        let mut trials: Vec<(Point, Real, Real)> = Vec::new();
                        let mut one = |s: &mut System<'_>, from: &Point, h: Real| {
                            s.pair_step(&settings, from, h, &mut scratch).map(|(p, e)| {
                                trials.push((p, h, e));
                                p
                            })
                        };
                        let advanced =
                            system.advance(&current, h_try, MAX_SUBDIVISION_DEPTH, &mut one);
                        // A contact reached by a pair step (not by the kick-drift-kick location,
                        // which has no estimate): its length and error norm.
                        let reaching = |p: &Point| {
                            trials
                                .iter()
                                .rev()
                                .find(|(end, _, _)| {
                                    end.time == p.time && end.state.flat() == p.state.flat()
                                })
                                .map(|&(_, h, e)| (h, e))
                        };
                        match advanced {
                            Ok(Advance::Contact(p)) => {
                                let step = reaching(&p);
                                if step.is_none() && p.time > current.time {
                                    // Located by the kick-drift-kick fallback over a step the
                                    // tolerance does not bound (a stage overshoots at the
                                    // bisection's boundary): not trusted. Take the longest clear
                                    // pair step that passed the error test as an ordinary step
                                    // (retried, the same step bit for bit) and approach the
                                    // contact from there.
                                    let clear = trials
                                        .iter()
                                        .filter(|(end, _, e)| {
                                            end.time > current.time
                                                && *e <= 1.0
                                                && !system.touching(&end.state)
                                        })
                                        .max_by(|a, b| a.0.time.total_cmp(&b.0.time));
                                    if let Some(&(_, h_clear, _)) = clear {
                                        control.retry_shorter(h_try);
                                        h = h_clear;
                                        continue;
                                    }
                                }
                                if let Some((h_reach, error)) = step {
                                    if !error.is_finite() {
                                        return Err(DynamicsError::NonFinite {
                                            time: current.time,
                                        });
                                    }
                                    if error > 1.0 {
                                        h = control.reject(h_reach, error);
                                        continue;
                                    }
                                }
                                // DOP853's output over the contact step from its own dense
                                // output of that step (stages recomputed, bit for bit).
                                let dense = match step {
                                    Some((h_reach, _)) if settings.dense && output.is_some() => {
                                        system
                                            .pair_step(&settings, &current, h_reach, &mut k)
                                            .ok()
                                            .and_then(|_| {
                                                system.dense(&current, &p, h_reach, &mut k).ok()
                                            })
                                    }
                                    _ => None,
                                };
                                let termination = system.stop_at_contact(
                                    &current,
                                    &p,
                                    dense.as_ref(),
                                    &mut output,
                                    observer,
                                );
                                let (steps, rejected) = (control.steps, control.rejected);
                                return Ok(finish(&system, &p, steps, rejected, termination));
                            }
                            Ok(Advance::Reached(_))
                            | Err(DynamicsError::ContactUnresolved { .. }) => {
                                // Only a stage overlapped: reject, retry shorter.
                                h = control.retry_shorter(h_try);
                            }
                            Err(e) => return Err(e),
                        }
                    }
                }
            }
            let (steps, rejected) = (control.steps, control.rejected);
            Ok(finish(
                &system,
                &current,
                steps,
                rejected,
                Termination::Completed,
            ))
        }
    }
}
