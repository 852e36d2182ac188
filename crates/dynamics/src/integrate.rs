//! Integrators of the translational two-body motion, behind one trait, [`Integrator`].
//!
//! The equations of motion are $m_A \ddot{\mathbf R}\_A = \mathbf F_A$,
//! $m_B \ddot{\mathbf R}\_B = -\mathbf F_A$, with $\mathbf F_A$ from an [`InteractionModel`];
//! on this translation path each attitude turns uniformly about its constant angular velocity
//! (valid where every torque vanishes along the motion, [`crate::MotionPath::Translation`]);
//! every other scene integrates rotation too ([`crate::rigid`]), chosen by the model's
//! [`InteractionModel::motion_path`] at the start of every run.
//!
//! - [`FixedStep`] with a [`FixedScheme`]:
//!   - [`FixedScheme::RungeKutta4`]: classical RK4 (the founding paper's), order 4, 4 force
//!     evaluations per step (the last stage's acceleration is reused as the next step's first).
//!   - [`FixedScheme::Leapfrog`]: kick–drift–kick (velocity Verlet), symplectic and time
//!     reversible, order 2, 1 evaluation per step.
//!   - [`FixedScheme::Yoshida4`]: symmetric triple-jump composition of leapfrog,
//!     $w_1 = 1/(2 - 2^{1/3})$, $w_0 = 1 - 2w_1$ (Yoshida 1990; Forest & Ruth 1990), order 4,
//!     3 evaluations per step.
//!   - [`FixedScheme::Yoshida6`]: Yoshida's 7-stage composition ("solution A" of Yoshida 1990),
//!     order 6, 7 evaluations per step.
//!   - [`FixedScheme::TripleJump8`]: triple jump of `Yoshida6`, $y_1 = 1/(2 - 2^{1/7})$,
//!     $y_0 = 1 - 2y_1$, order 8, 21 evaluations per step.
//!
//!   All compositions are symmetric, hence symplectic and time reversible. Every order is measured
//!   by a test (errors at two step sizes on a Kepler orbit of eccentricity 0.5).
//! - [`Adaptive`] with an [`EmbeddedPair`]: Dormand–Prince 5(4) (Dormand & Prince 1980) or
//!   DOP853 (Hairer, Nørsett & Wanner), both with local extrapolation and FSAL. The error of a
//!   step is measured component-wise against
//!   $\mathrm{sc}\_i = \mathrm{atol} + \mathrm{rtol}\max(|y\_{0,i}|,|y\_{1,i}|)$ over the 12
//!   components of both positions and velocities: DP5(4) uses the root mean square
//!   $\mathrm{err} = \big(\tfrac1{12}\sum_i (e_i/\mathrm{sc}\_i)^2\big)^{1/2}$, DOP853 combines its
//!   5th- and 3rd-order estimates as $\mathrm{err} = \\|e_5\\|^2/\sqrt{\\|e_5\\|^2 + 0.01\\|e_3\\|^2}$
//!   (both norms root-mean-square scaled). A step is accepted when err ≤ 1, and the next step is
//!   $h \leftarrow h\\,\min(f\_{\max}, \max(f\_{\min}, 0.9\\,\mathrm{err}^{-1/(q+1)}))$ with q = 4,
//!   $[f\_{\min}, f\_{\max}] = [0.2, 5]$ for DP5(4) and q = 7, [1/3, 6] for DOP853 (no growth
//!   after a rejection). A step below `min_step` is a typed error carrying the time; so is a
//!   non-finite error estimate or state. Round-off: the increment $h\sum_i b_i\mathbf k_i$ is
//!   added with compensated (Kahan) summation and each stage sum is formed before its product
//!   with h, so that with the coefficient correction of the tableaux the round-off energy error
//!   of long runs grows like $\sqrt t$ (Brouwer's law), not like t (tests/long_runs.rs).
//!
//! Dense output: every integrator reports [`Sample`]s carrying the accelerations, so the quintic
//! Hermite interpolant of [`crate::interpolate`] gives positions and velocities between samples
//! (local error $O(h^6)$). [`Integrator::integrate_with_output`] gives evenly spaced states;
//! DOP853 computes them from its own continuous extension of order 7 (local error $O(h^8)$,
//! three more force evaluations in each step that contains an output time).
//!
//! Contact: when the model has a contact distance and a step would end at or below it (or a stage
//! lands in overlap), the step length from the last accepted sample is bisected until the contact
//! time is found to round-off; the run stops with [`Termination::Contact`]. The adaptive
//! integrators test the error of the bisected step that reaches the contact like that of any
//! other step (one that fails is rejected and the contact approached in shorter steps), and the
//! evenly spaced output over it comes from the method's own dense output. Every step of the
//! fixed-step methods that ends clear, whole or subdivided, goes through the escape test.

use crate::interpolate::{
    emit_step, hermite_or_end, state_between, with_even_output, EvenOutput, EvenStates, OutputClock,
};
use crate::model::{InteractionError, InteractionModel};
use crate::rigid;
use crate::state::{Sample, TwoBodyState};
use crate::tableau::{Tableau, DOP853, DOP853_D, DOP853_DENSE_A, DORMAND_PRINCE_54, MAX_STAGES};
use surfgrav_potentials::{Pose, PoseExt, Real, Vec3};
use thiserror::Error;

/// Why a run failed.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// A parameter of the integrator or the run is out of its domain.
    #[error("{name} must be {requirement}, got {value}")]
    InvalidParameter {
        /// Parameter name (`step`, `relative_tolerance`, `t_end`, ...).
        name: &'static str,
        /// What it must be.
        requirement: &'static str,
        /// The rejected value.
        value: Real,
    },
    /// The adaptive step fell below its floor.
    #[error("at t = {time}: the step {step:e} fell below the minimum step {min_step:e}; loosen the tolerance or lower the floor")]
    StepSizeTooSmall {
        /// Time of the last accepted state.
        time: Real,
        /// The step that was proposed.
        step: Real,
        /// The floor.
        min_step: Real,
    },
    /// The state became NaN or infinite.
    #[error("at t = {time}: the state is not finite")]
    NonFinite {
        /// Time of the last accepted state.
        time: Real,
    },
    /// The model failed.
    #[error("at t = {time}: {source}")]
    Interaction {
        /// Time of the last accepted state.
        time: Real,
        /// The model's error.
        source: InteractionError,
    },
    /// Intermediate stages keep landing in overlap although the trajectory stays clear, even
    /// after subdividing the step to 2⁻⁴⁰ of its length.
    #[error("at t = {time}: could not decide whether the bodies touch (stages overlap, the orbit does not); reduce the step")]
    ContactUnresolved {
        /// Time of the last accepted state.
        time: Real,
    },
    /// The model reports torques on the translation path (its bodies have no inertia tensors,
    /// or its motion path claims a symmetry its torques contradict): integrating with frozen
    /// attitudes would be silently wrong.
    #[error("at t = {time}: the bodies exert torques (|τ_A| = {torque_a:e}, |τ_B| = {torque_b:e}, relative to |F| r: {relative:e}) but the model gives no inertia tensors, so rotational dynamics cannot be integrated; give both bodies their inertia tensors (InteractionModel::inertia_a/inertia_b, or Body::with_inertia)")]
    TorquesNotSupported {
        /// Start time.
        time: Real,
        /// Magnitude of the torque on A.
        torque_a: Real,
        /// Magnitude of the torque on B.
        torque_b: Real,
        /// Larger torque over |F_A| × separation.
        relative: Real,
    },
    /// The run needed more steps than allowed.
    #[error("at t = {time}: more than {max_steps} steps")]
    TooManySteps {
        /// Time of the last accepted state.
        time: Real,
        /// The limit.
        max_steps: usize,
    },
}

/// Where and when the bodies touched.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEvent {
    /// The sample at the contact time: the bisected step length, completed by a second-order
    /// Taylor step of length O(round-off or stage overshoot) to the contact distance.
    pub sample: Sample,
    /// Centroid separation at contact.
    pub separation: Real,
    /// The model's contact distance there.
    pub contact_distance: Real,
    /// Unit vector from A's centroid toward B's at contact.
    pub direction: Vec3,
}

/// Where and when the bodies escaped each other.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EscapeEvent {
    /// The first sample beyond the escape distance on a hyperbolic relative orbit.
    pub sample: Sample,
    /// Centroid separation there.
    pub separation: Real,
    /// The escape distance that was set.
    pub escape_distance: Real,
    /// Energy of the relative orbit, $\tfrac12\mu|\dot{\mathbf r}|^2 + V$ (positive).
    pub orbital_energy: Real,
}

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Termination {
    /// The end time was reached.
    Completed,
    /// The bodies touched before the end time.
    Contact(Box<ContactEvent>),
    /// The relative orbit is unbound and the separation passed the escape distance
    /// ([`Integrator::set_escape_distance`]).
    Escape(Box<EscapeEvent>),
}

impl Termination {
    /// The time of a stop event (contact or escape), `None` for a completed run.
    pub fn event_time(&self) -> Option<Real> {
        match self {
            Termination::Completed => None,
            Termination::Contact(event) => Some(event.sample.time),
            Termination::Escape(event) => Some(event.sample.time),
        }
    }
}

/// The escape test after an accepted step: beyond `distance` with a positive relative-orbit
/// energy $\tfrac12\mu|\dot{\mathbf r}|^2 + V(\text{poses})$, μ the reduced mass. The energy is
/// evaluated only beyond the distance (once per step there).
pub(crate) fn escaped(
    model: &dyn InteractionModel,
    distance: Option<Real>,
    sample: &Sample,
) -> Option<EscapeEvent> {
    let distance = distance?;
    let separation = sample.state.separation();
    if separation <= distance {
        return None;
    }
    let (ma, mb) = (model.mass_a(), model.mass_b());
    let reduced = ma * mb / (ma + mb);
    let v = model
        .potential_energy(&sample.state.body_a.pose(), &sample.state.body_b.pose())
        .ok()?;
    let energy = 0.5 * reduced * sample.state.relative_velocity().norm_squared() + v;
    (energy > 0.0).then_some(EscapeEvent {
        sample: *sample,
        separation,
        escape_distance: distance,
        orbital_energy: energy,
    })
}

/// `value` if it is positive and finite, else [`DynamicsError::InvalidParameter`] naming it.
pub(crate) fn positive_finite(name: &'static str, value: Real) -> Result<Real, DynamicsError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(DynamicsError::InvalidParameter {
            name,
            requirement: "positive and finite",
            value,
        })
    }
}

fn check_escape_distance(distance: Option<Real>) -> Result<Option<Real>, DynamicsError> {
    distance
        .map(|d| positive_finite("escape_distance", d))
        .transpose()
}

/// What a run did.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// The last sample (at the end time, or at contact).
    pub last: Sample,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (adaptive only).
    pub rejected_steps: usize,
    /// Force evaluations, including those of rejected steps and of contact location.
    pub force_evaluations: usize,
    /// How the run ended.
    pub termination: Termination,
}

/// An integrator of the two-body translational motion. Object safe.
pub trait Integrator {
    /// Short name (`rk4`, `leapfrog`, `yoshida4`, `yoshida6`, `yoshida8`, `dopri5`, `dop853`).
    fn name(&self) -> &'static str;

    /// Stops runs with [`Termination::Escape`] once the separation exceeds `distance` on an
    /// unbound relative orbit (`None`, the default, never stops for escape).
    ///
    /// # Errors
    /// A distance that is not positive and finite.
    fn set_escape_distance(&mut self, distance: Option<Real>) -> Result<(), DynamicsError>;

    /// Integrates from `initial` at `t_start` to `t_end` (> `t_start`). `observer` receives the
    /// initial sample, then the sample at the end of every accepted step (and the contact sample,
    /// if any), in order.
    fn integrate(
        &mut self,
        model: &dyn InteractionModel,
        initial: &TwoBodyState,
        t_start: Real,
        t_end: Real,
        observer: &mut dyn FnMut(&Sample),
    ) -> Result<RunSummary, DynamicsError>;

    /// As [`Integrator::integrate`], and also calls `emit(time, state)` at the evenly spaced
    /// times $t\_{\mathrm{start}} + k\\,\Delta$ (`interval` Δ positive and finite; times computed
    /// from k, no accumulated round-off) up to the last sample, in order, each before the sample
    /// that ends its step reaches `observer`. The states come from the method's dense output: the
    /// quintic Hermite interpolant of the samples ([`crate::interpolate::EvenOutput`]) by default;
    /// DOP853 uses its own continuous extension of order 7. After a contact, the last output
    /// time is at or before the contact time.
    #[allow(clippy::too_many_arguments)]
    fn integrate_with_output(
        &mut self,
        model: &dyn InteractionModel,
        initial: &TwoBodyState,
        t_start: Real,
        t_end: Real,
        interval: Real,
        observer: &mut dyn FnMut(&Sample),
        emit: &mut dyn FnMut(Real, &TwoBodyState),
    ) -> Result<RunSummary, DynamicsError> {
        let mut output = EvenOutput::new(interval).ok_or(DynamicsError::InvalidParameter {
            name: "interval",
            requirement: "positive and finite",
            value: interval,
        })?;
        self.integrate(model, initial, t_start, t_end, &mut |sample| {
            output.observe(sample, emit);
            observer(sample);
        })
    }
}

/// Positions and velocities of both bodies: $(\mathbf R_A, \mathbf R_B, \dot{\mathbf R}\_A, \dot{\mathbf R}\_B)$.
#[derive(Debug, Clone, Copy)]
struct Phase([Vec3; 4]);

impl Phase {
    fn of(state: &TwoBodyState) -> Self {
        Phase([
            state.body_a.position,
            state.body_b.position,
            state.body_a.velocity,
            state.body_b.velocity,
        ])
    }
    fn into_state(self, template: &TwoBodyState) -> TwoBodyState {
        let mut s = *template;
        s.body_a.position = self.0[0];
        s.body_b.position = self.0[1];
        s.body_a.velocity = self.0[2];
        s.body_b.velocity = self.0[3];
        s
    }
}

/// Evaluates accelerations and counts evaluations.
struct Dynamics<'m> {
    model: &'m dyn InteractionModel,
    mass_a: Real,
    mass_b: Real,
    template: TwoBodyState,
    start: Real,
    evaluations: usize,
}

impl<'m> Dynamics<'m> {
    /// The summary of a run ending at `last` after `(steps, rejected)` steps.
    fn summary(
        &self,
        last: Sample,
        (steps, rejected_steps): (usize, usize),
        termination: Termination,
    ) -> RunSummary {
        RunSummary {
            last,
            steps,
            rejected_steps,
            force_evaluations: self.evaluations,
            termination,
        }
    }

    /// The summary of a run ending at the contact `event`.
    fn contact_summary(&self, event: ContactEvent, counts: (usize, usize)) -> RunSummary {
        self.summary(event.sample, counts, Termination::Contact(Box::new(event)))
    }

    fn new(model: &'m dyn InteractionModel, template: TwoBodyState, start: Real) -> Self {
        Self {
            model,
            mass_a: model.mass_a(),
            mass_b: model.mass_b(),
            template,
            start,
            evaluations: 0,
        }
    }
    fn poses(&self, xa: &Vec3, xb: &Vec3) -> (Pose, Pose) {
        (
            Pose::from_position_rotation(*xa, self.template.body_a.orientation),
            Pose::from_position_rotation(*xb, self.template.body_b.orientation),
        )
    }
    fn accelerations(&mut self, xa: &Vec3, xb: &Vec3) -> Result<(Vec3, Vec3), InteractionError> {
        self.evaluations += 1;
        let (pa, pb) = self.poses(xa, xb);
        let f = self.model.force_on_a(&pa, &pb)?;
        Ok((f / self.mass_a, -f / self.mass_b))
    }
    fn contact_distance(&self, xa: &Vec3, xb: &Vec3) -> Option<Real> {
        let (pa, pb) = self.poses(xa, xb);
        self.model.contact_distance(&pa, &pb)
    }
    fn sample(&self, time: Real, phase: Phase, acc: (Vec3, Vec3)) -> Sample {
        let mut state = phase.into_state(&self.template);
        // Translation path: each body spins freely and uniformly (see `MotionPath`).
        let elapsed = time - self.start;
        for body in [&mut state.body_a, &mut state.body_b] {
            *body = body.spun(elapsed);
        }
        Sample {
            time,
            state,
            acceleration_a: acc.0,
            acceleration_b: acc.1,
        }
    }
}

pub(crate) fn check_span(t_start: Real, t_end: Real) -> Result<(), DynamicsError> {
    if !t_start.is_finite() {
        return Err(DynamicsError::InvalidParameter {
            name: "t_start",
            requirement: "finite",
            value: t_start,
        });
    }
    if !(t_end.is_finite() && t_end > t_start) {
        return Err(DynamicsError::InvalidParameter {
            name: "t_end",
            requirement: "finite and after t_start",
            value: t_end,
        });
    }
    Ok(())
}

fn initial_sample(
    dynamics: &mut Dynamics<'_>,
    initial: &TwoBodyState,
    t_start: Real,
) -> Result<Sample, DynamicsError> {
    if !initial.is_finite() {
        return Err(DynamicsError::NonFinite { time: t_start });
    }
    check_torque_free(dynamics.model, initial, t_start)?;
    let phase = Phase::of(initial);
    let acc = dynamics
        .accelerations(&phase.0[0], &phase.0[1])
        .map_err(|source| DynamicsError::Interaction {
            time: t_start,
            source,
        })?;
    if !acc.0.iter().chain(acc.1.iter()).all(|x| x.is_finite()) {
        return Err(DynamicsError::NonFinite { time: t_start });
    }
    Ok(dynamics.sample(t_start, phase, acc))
}

/// Refuses a start where the model reports torques above
/// [`crate::tolerance::TORQUE_FREE_RELATIVE`] × |F_A| × separation.
fn check_torque_free(
    model: &dyn InteractionModel,
    initial: &TwoBodyState,
    time: Real,
) -> Result<(), DynamicsError> {
    let (pa, pb) = (initial.body_a.pose(), initial.body_b.pose());
    let interaction = |source| DynamicsError::Interaction { time, source };
    let Some((torque_a, torque_b)) = model.torques(&pa, &pb).map_err(interaction)? else {
        return Ok(());
    };
    let force = model.force_on_a(&pa, &pb).map_err(interaction)?;
    let scale = force.norm() * initial.separation();
    let largest = torque_a.norm().max(torque_b.norm());
    let relative = if scale > 0.0 {
        largest / scale
    } else {
        largest
    };
    if relative.is_nan() || relative > crate::tolerance::TORQUE_FREE_RELATIVE {
        return Err(DynamicsError::TorquesNotSupported {
            time,
            torque_a: torque_a.norm(),
            torque_b: torque_b.norm(),
            relative,
        });
    }
    Ok(())
}

/// Outcome of trying one step from an accepted sample (short-lived, not worth boxing).
#[allow(clippy::large_enum_variant)]
enum Trial {
    /// The step ended clear of contact.
    Clear(Sample),
    /// The step ended in or past contact, or a stage overlapped.
    Touching,
}

fn classify(
    dynamics: &Dynamics<'_>,
    result: Result<Sample, InteractionError>,
    time: Real,
) -> Result<Trial, DynamicsError> {
    match result {
        Ok(sample) => {
            if !sample.state.is_finite()
                || !sample.acceleration_a.iter().all(|x| x.is_finite())
                || !sample.acceleration_b.iter().all(|x| x.is_finite())
            {
                return Err(DynamicsError::NonFinite { time });
            }
            let (xa, xb) = (&sample.state.body_a.position, &sample.state.body_b.position);
            match dynamics.contact_distance(xa, xb) {
                Some(d) if (xb - xa).norm() <= d => Ok(Trial::Touching),
                _ => Ok(Trial::Clear(sample)),
            }
        }
        Err(InteractionError::Overlap { .. }) => Ok(Trial::Touching),
        Err(source) => Err(DynamicsError::Interaction { time, source }),
    }
}

/// A step of a given length from a sample: the sample it reaches and its error norm (0 for the
/// fixed-step methods, which have no estimate).
type TrialStep<'s> =
    dyn FnMut(&mut Dynamics<'_>, &Sample, Real) -> Result<(Sample, Real), InteractionError> + 's;

/// A contact located within a step.
struct Located {
    event: ContactEvent,
    /// The last clear sample of the bisection (before the closing Taylor step), the length of
    /// the step from the start that reached it, and that step's error norm.
    reached: Sample,
    step: Real,
    error: Real,
}

/// Bisects the step length from `from` (a clear sample) over (0, `h`] where a step of `h` touches.
/// `None` when the bisection ends clear of contact (only a stage overlapped).
fn locate_contact(
    dynamics: &mut Dynamics<'_>,
    from: &Sample,
    h: Real,
    step: &mut TrialStep<'_>,
) -> Result<Option<Located>, DynamicsError> {
    let (mut lo, mut hi) = (0.0, h);
    let mut best = *from;
    let mut best_error = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let (result, error) = match step(dynamics, from, mid) {
            Ok((sample, error)) => (Ok(sample), error),
            Err(e) => (Err(e), 0.0),
        };
        match classify(dynamics, result, from.time)? {
            Trial::Clear(sample) => {
                lo = mid;
                best = sample;
                best_error = error;
            }
            Trial::Touching => hi = mid,
        }
    }
    let reached = best;
    // A stage of a step can overlap while the step's end would still be clear, so the bisection
    // may stop a little short of contact. Close the remaining gap δ with the local Taylor
    // expansion r + ṙδ + r̈δ²/2 (error O(δ³), δ is tiny) by Newton's method.
    if let Some(d) =
        dynamics.contact_distance(&best.state.body_a.position, &best.state.body_b.position)
    {
        let (r, v, a) = (
            best.state.relative_position(),
            best.state.relative_velocity(),
            best.relative_acceleration(),
        );
        let mut delta: Real = 0.0;
        for _ in 0..8 {
            let p = r + v * delta + a * (0.5 * delta * delta);
            let dp = v + a * delta;
            let n = p.norm();
            let slope = p.dot(&dp) / n;
            if slope.is_nan() || slope >= 0.0 {
                break;
            }
            delta -= (n - d) / slope;
        }
        let remaining = from.time + h - best.time;
        if delta > 0.0 && delta <= remaining {
            let advance = |x: &Vec3, v: &Vec3, a: &Vec3, delta: Real| {
                (x + v * delta + a * (0.5 * delta * delta), v + a * delta)
            };
            // Newton lands on the contact distance up to rounding, which may fall on either
            // side: shorten δ by a few ulps until the state is not inside contact (a contact
            // sample inside contact would make the model refuse its energy).
            for shrink in 0..8 {
                let delta = delta * (1.0 - 4.0 * Real::EPSILON * Real::from(shrink));
                let (xa, va) = advance(
                    &best.state.body_a.position,
                    &best.state.body_a.velocity,
                    &best.acceleration_a,
                    delta,
                );
                let (xb, vb) = advance(
                    &best.state.body_b.position,
                    &best.state.body_b.velocity,
                    &best.acceleration_b,
                    delta,
                );
                if (xb - xa).norm() < d {
                    continue;
                }
                let acc = dynamics
                    .accelerations(&xa, &xb)
                    .unwrap_or((best.acceleration_a, best.acceleration_b));
                best = dynamics.sample(best.time + delta, Phase([xa, xb, va, vb]), acc);
                break;
            }
        }
    }
    let (xa, xb) = (&best.state.body_a.position, &best.state.body_b.position);
    let r = xb - xa;
    let separation = r.norm();
    let contact_distance = dynamics.contact_distance(xa, xb).unwrap_or(separation);
    if separation > contact_distance * (1.0 + CONTACT_RELATIVE_GAP) {
        // A stage overshot into overlap while the trajectory itself stays clear.
        return Ok(None);
    }
    Ok(Some(Located {
        event: ContactEvent {
            sample: best,
            separation,
            contact_distance,
            direction: if separation > 0.0 {
                r / separation
            } else {
                Vec3::zeros()
            },
        },
        reached,
        step: lo,
        error: best_error,
    }))
}

/// A located contact must lie this close (relative) to the contact distance; a larger gap means
/// only an intermediate stage overlapped (a false alarm: the step is subdivided instead).
const CONTACT_RELATIVE_GAP: Real = 1e-9;

/// Result of advancing a fixed step, subdivided if a stage overshot into overlap.
enum Advance {
    Reached(Sample),
    Contact(ContactEvent),
}

/// The fixed-step methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum FixedScheme {
    /// Classical fourth-order Runge–Kutta.
    RungeKutta4,
    /// Kick–drift–kick leapfrog, order 2.
    Leapfrog,
    /// Triple-jump composition of leapfrog, order 4.
    Yoshida4,
    /// Yoshida's 7-stage composition, order 6.
    Yoshida6,
    /// Triple jump of `Yoshida6`, order 8.
    TripleJump8,
}

/// Yoshida (1990) solution A: $w_1, w_2, w_3$; $w_0 = 1 - 2(w_1 + w_2 + w_3)$.
const YOSHIDA6_W: [Real; 3] = [
    -1.177_679_984_178_871,
    0.235_573_213_359_358_1,
    0.784_513_610_477_557_3,
];

impl FixedScheme {
    /// The leapfrog sub-step weights of a composition (empty for RK4).
    fn weights(self) -> Vec<Real> {
        match self {
            FixedScheme::RungeKutta4 => Vec::new(),
            FixedScheme::Leapfrog => vec![1.0],
            FixedScheme::Yoshida4 => {
                let w1 = 1.0 / (2.0 - 2f64.cbrt());
                vec![w1, 1.0 - 2.0 * w1, w1]
            }
            FixedScheme::Yoshida6 => {
                let [w1, w2, w3] = YOSHIDA6_W;
                let w0 = 1.0 - 2.0 * (w1 + w2 + w3);
                vec![w3, w2, w1, w0, w1, w2, w3]
            }
            FixedScheme::TripleJump8 => {
                let inner = FixedScheme::Yoshida6.weights();
                let y1 = 1.0 / (2.0 - 2f64.powf(1.0 / 7.0));
                let y0 = 1.0 - 2.0 * y1;
                [y1, y0, y1]
                    .iter()
                    .flat_map(|y| inner.iter().map(move |w| y * w))
                    .collect()
            }
        }
    }

    /// Order of accuracy.
    pub fn order(self) -> u32 {
        match self {
            FixedScheme::RungeKutta4 | FixedScheme::Yoshida4 => 4,
            FixedScheme::Leapfrog => 2,
            FixedScheme::Yoshida6 => 6,
            FixedScheme::TripleJump8 => 8,
        }
    }

    /// Short name (the same as [`crate::IntegratorKind`]'s: `TripleJump8` is `yoshida8`).
    pub fn name(self) -> &'static str {
        match self {
            FixedScheme::RungeKutta4 => "rk4",
            FixedScheme::Leapfrog => "leapfrog",
            FixedScheme::Yoshida4 => "yoshida4",
            FixedScheme::Yoshida6 => "yoshida6",
            FixedScheme::TripleJump8 => "yoshida8",
        }
    }
}

/// A fixed-step integrator: steps of `step` from the start, the last one shortened to land on the
/// end time exactly. Sample times are $t_0 + k\\,h$ (no accumulated round-off in time).
#[derive(Debug, Clone, PartialEq)]
pub struct FixedStep {
    scheme: FixedScheme,
    step: Real,
    weights: Vec<Real>,
    escape_distance: Option<Real>,
}

impl FixedStep {
    /// A fixed-step integrator; `step` must be positive and finite.
    pub fn new(scheme: FixedScheme, step: Real) -> Result<Self, DynamicsError> {
        Ok(Self {
            scheme,
            step: positive_finite("step", step)?,
            weights: scheme.weights(),
            escape_distance: None,
        })
    }

    /// The scheme.
    pub fn scheme(&self) -> FixedScheme {
        self.scheme
    }

    /// The step.
    pub fn step(&self) -> Real {
        self.step
    }
}

fn rk4_step(
    dynamics: &mut Dynamics<'_>,
    from: &Sample,
    h: Real,
) -> Result<Sample, InteractionError> {
    let y = Phase::of(&from.state).0;
    let k1v = [y[2], y[3]];
    let k1a = [from.acceleration_a, from.acceleration_b];
    let half = 0.5 * h;
    let x2 = [y[0] + k1v[0] * half, y[1] + k1v[1] * half];
    let k2v = [y[2] + k1a[0] * half, y[3] + k1a[1] * half];
    let k2a = dynamics.accelerations(&x2[0], &x2[1])?;
    let x3 = [y[0] + k2v[0] * half, y[1] + k2v[1] * half];
    let k3v = [y[2] + k2a.0 * half, y[3] + k2a.1 * half];
    let k3a = dynamics.accelerations(&x3[0], &x3[1])?;
    let x4 = [y[0] + k3v[0] * h, y[1] + k3v[1] * h];
    let k4v = [y[2] + k3a.0 * h, y[3] + k3a.1 * h];
    let k4a = dynamics.accelerations(&x4[0], &x4[1])?;
    let sixth = h / 6.0;
    let xa = y[0] + (k1v[0] + (k2v[0] + k3v[0]) * 2.0 + k4v[0]) * sixth;
    let xb = y[1] + (k1v[1] + (k2v[1] + k3v[1]) * 2.0 + k4v[1]) * sixth;
    let va = y[2] + (k1a[0] + (k2a.0 + k3a.0) * 2.0 + k4a.0) * sixth;
    let vb = y[3] + (k1a[1] + (k2a.1 + k3a.1) * 2.0 + k4a.1) * sixth;
    let acc = dynamics.accelerations(&xa, &xb)?;
    Ok(dynamics.sample(from.time + h, Phase([xa, xb, va, vb]), acc))
}

fn composition_step(
    dynamics: &mut Dynamics<'_>,
    weights: &[Real],
    from: &Sample,
    h: Real,
) -> Result<Sample, InteractionError> {
    let [mut xa, mut xb, mut va, mut vb] = Phase::of(&from.state).0;
    let (mut aa, mut ab) = (from.acceleration_a, from.acceleration_b);
    for w in weights {
        let hw = h * w;
        va += aa * (0.5 * hw);
        vb += ab * (0.5 * hw);
        xa += va * hw;
        xb += vb * hw;
        (aa, ab) = dynamics.accelerations(&xa, &xb)?;
        va += aa * (0.5 * hw);
        vb += ab * (0.5 * hw);
    }
    Ok(dynamics.sample(from.time + h, Phase([xa, xb, va, vb]), (aa, ab)))
}

impl FixedStep {
    fn one_step(
        &self,
        dynamics: &mut Dynamics<'_>,
        from: &Sample,
        h: Real,
    ) -> Result<Sample, InteractionError> {
        match self.scheme {
            FixedScheme::RungeKutta4 => rk4_step(dynamics, from, h),
            _ => composition_step(dynamics, &self.weights, from, h),
        }
    }
}

/// Largest number of fixed steps in one run.
const MAX_FIXED_STEPS: Real = 1e15;

/// The sample times of a fixed-step run over $[t_0, t_1]$: whole steps of $h$, then a last short
/// one when the span is not a multiple of the step; $t_k = t_0 + k h$ (no accumulated round-off)
/// and the last is $t_1$ exactly.
pub(crate) struct FixedGrid {
    t_start: Real,
    t_end: Real,
    step: Real,
    /// The number of steps.
    pub(crate) count: usize,
}

impl FixedGrid {
    /// # Errors
    /// [`DynamicsError::InvalidParameter`] for more than [`MAX_FIXED_STEPS`] steps.
    pub(crate) fn new(t_start: Real, t_end: Real, step: Real) -> Result<Self, DynamicsError> {
        let span = t_end - t_start;
        let ratio = span / step;
        if ratio > MAX_FIXED_STEPS {
            return Err(DynamicsError::InvalidParameter {
                name: "step",
                requirement: "at least 1e-15 of the time span",
                value: step,
            });
        }
        let whole = (ratio * (1.0 + 8.0 * Real::EPSILON)).floor();
        let extra = (ratio - whole) * step > 1e-12 * span;
        Ok(Self {
            t_start,
            t_end,
            step,
            count: whole as usize + usize::from(extra),
        })
    }

    /// The time at the end of step `k` (1 ≤ k ≤ `count`).
    pub(crate) fn target(&self, k: usize) -> Real {
        if k == self.count {
            self.t_end
        } else {
            self.t_start + k as Real * self.step
        }
    }
}

/// Subdivisions allowed when stages overshoot into overlap without contact (2⁻⁴⁰ of a step).
const MAX_SUBDIVISION_DEPTH: u32 = 40;

impl FixedStep {
    /// Advances `h` from `from` after a step touched: locates the contact, or, when only a stage
    /// overshot, takes the step as two halves (recursively). Sub-step samples are not reported.
    fn advance(
        &self,
        dynamics: &mut Dynamics<'_>,
        from: &Sample,
        h: Real,
        depth: u32,
    ) -> Result<Advance, DynamicsError> {
        let result = self.one_step(dynamics, from, h);
        if let Trial::Clear(sample) = classify(dynamics, result, from.time)? {
            return Ok(Advance::Reached(sample));
        }
        let mut step = |d: &mut Dynamics<'_>, s: &Sample, h: Real| {
            self.one_step(d, s, h).map(|sample| (sample, 0.0))
        };
        if let Some(located) = locate_contact(dynamics, from, h, &mut step)? {
            return Ok(Advance::Contact(located.event));
        }
        if depth >= MAX_SUBDIVISION_DEPTH {
            return Err(DynamicsError::ContactUnresolved { time: from.time });
        }
        match self.advance(dynamics, from, 0.5 * h, depth + 1)? {
            Advance::Reached(middle) => self.advance(dynamics, &middle, 0.5 * h, depth + 1),
            contact => Ok(contact),
        }
    }
}

impl FixedStep {
    fn rigid_method(&self) -> rigid::Method<'_> {
        rigid::Method::Fixed {
            scheme: self.scheme,
            weights: &self.weights,
            step: self.step,
        }
    }
}

impl FixedStep {
    /// The fixed-step loop (translation here, rotation in [`rigid`]); `output` asks for evenly
    /// spaced states, from the quintic Hermite interpolant of the samples.
    fn run(
        &self,
        model: &dyn InteractionModel,
        initial: &TwoBodyState,
        t_start: Real,
        t_end: Real,
        observer: &mut dyn FnMut(&Sample),
        mut output: EvenStates<'_>,
    ) -> Result<RunSummary, DynamicsError> {
        check_span(t_start, t_end)?;
        if model.motion_path(initial).is_rotation() {
            return rigid::integrate(
                self.rigid_method(),
                model,
                initial,
                (t_start, t_end),
                self.escape_distance,
                observer,
                output,
            );
        }
        let mut dynamics = Dynamics::new(model, *initial, t_start);
        let mut current = initial_sample(&mut dynamics, initial, t_start)?;
        emit_step(&mut output, &current, &current);
        observer(&current);
        let grid = FixedGrid::new(t_start, t_end, self.step)?;
        for k in 1..=grid.count {
            let target = grid.target(k);
            let h = target - current.time;
            let result = self.one_step(&mut dynamics, &current, h);
            // Every step that ends clear goes through the same checks below, whether it was
            // taken whole or subdivided after a stage's overlap.
            let mut next = match classify(&dynamics, result, current.time)? {
                Trial::Clear(next) => next,
                Trial::Touching => match self.advance(&mut dynamics, &current, h, 0)? {
                    Advance::Reached(next) => next,
                    Advance::Contact(event) => {
                        emit_step(&mut output, &current, &event.sample);
                        observer(&event.sample);
                        return Ok(dynamics.contact_summary(event, (k - 1, 0)));
                    }
                },
            };
            next.time = target;
            emit_step(&mut output, &current, &next);
            current = next;
            observer(&current);
            if let Some(event) = escaped(model, self.escape_distance, &current) {
                return Ok(dynamics.summary(current, (k, 0), Termination::Escape(Box::new(event))));
            }
        }
        Ok(dynamics.summary(current, (grid.count, 0), Termination::Completed))
    }
}

impl Integrator for FixedStep {
    fn name(&self) -> &'static str {
        self.scheme.name()
    }

    fn set_escape_distance(&mut self, distance: Option<Real>) -> Result<(), DynamicsError> {
        self.escape_distance = check_escape_distance(distance)?;
        Ok(())
    }

    fn integrate(
        &mut self,
        model: &dyn InteractionModel,
        initial: &TwoBodyState,
        t_start: Real,
        t_end: Real,
        observer: &mut dyn FnMut(&Sample),
    ) -> Result<RunSummary, DynamicsError> {
        self.run(model, initial, t_start, t_end, observer, None)
    }

    fn integrate_with_output(
        &mut self,
        model: &dyn InteractionModel,
        initial: &TwoBodyState,
        t_start: Real,
        t_end: Real,
        interval: Real,
        observer: &mut dyn FnMut(&Sample),
        emit: &mut dyn FnMut(Real, &TwoBodyState),
    ) -> Result<RunSummary, DynamicsError> {
        with_even_output(t_start, interval, emit, |output| {
            self.run(model, initial, t_start, t_end, observer, output)
        })
    }
}

/// The embedded Runge–Kutta pairs of [`Adaptive`] (error norms and step control in this
/// module's documentation; the tableaux, their sources and the order-condition tests in
/// `src/tableau.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum EmbeddedPair {
    /// Dormand–Prince 5(4): order 5, 6 force evaluations per step; dense output by the quintic
    /// Hermite interpolant of the samples.
    DormandPrince54,
    /// DOP853 (Hairer, Nørsett & Wanner): order 8, 12 force evaluations per step, error from
    /// combined 5th- and 3rd-order estimators; its own dense output of order 7 costs 3 more
    /// evaluations in each step that contains an output time.
    Dop853,
}

impl EmbeddedPair {
    /// Short name (`dopri5`, `dop853`).
    pub fn name(self) -> &'static str {
        match self {
            EmbeddedPair::DormandPrince54 => "dopri5",
            EmbeddedPair::Dop853 => "dop853",
        }
    }

    /// Order of the propagated solution.
    pub fn order(self) -> u32 {
        match self {
            EmbeddedPair::DormandPrince54 => 5,
            EmbeddedPair::Dop853 => 8,
        }
    }

    fn tableau(self) -> &'static Tableau {
        match self {
            EmbeddedPair::DormandPrince54 => &DORMAND_PRINCE_54,
            EmbeddedPair::Dop853 => &DOP853,
        }
    }
}

/// Adaptive embedded Runge–Kutta integrator with step-size control: Dormand–Prince 5(4)
/// ([`Adaptive::new`]) or DOP853 ([`Adaptive::dop853`]); both share the step control, the step
/// floor, the contact handling and the evenly spaced output.
#[derive(Debug, Clone, PartialEq)]
pub struct Adaptive {
    pair: EmbeddedPair,
    relative_tolerance: Real,
    absolute_tolerance: Real,
    min_step: Real,
    max_step: Real,
    initial_step: Option<Real>,
    max_steps: usize,
    escape_distance: Option<Real>,
}

/// The stage derivatives $\mathbf k_i$ of one step: (velocity of A, velocity of B, acceleration
/// of A, acceleration of B) per stage.
type Stages = [[Vec3; 4]; MAX_STAGES];

/// The step-size control shared by the adaptive loops (translation and rotation): the step
/// factor $0.9\\,\mathrm{err}^{-1/(q+1)}$ within the tableau's range, no growth right after a
/// rejection, the step floor and the step budget (module documentation).
#[derive(Debug, Clone)]
pub(crate) struct StepControl {
    exponent: Real,
    shrink_limit: Real,
    grow_limit: Real,
    min_step: Real,
    max_step: Real,
    max_steps: usize,
    last_rejected: bool,
    /// Accepted steps so far.
    pub steps: usize,
    /// Rejected steps so far.
    pub rejected: usize,
}

impl StepControl {
    /// The control of `tableau` over a run of length `span`; a `min_step` of 0 means
    /// $10^{-12}$ × `span`.
    pub(crate) fn new(
        tableau: &Tableau,
        min_step: Real,
        max_step: Real,
        max_steps: usize,
        span: Real,
    ) -> Self {
        let (shrink_limit, grow_limit) = tableau.factor_range;
        Self {
            exponent: -1.0 / Real::from(tableau.error_order + 1),
            shrink_limit,
            grow_limit,
            min_step: if min_step > 0.0 {
                min_step
            } else {
                1e-12 * span
            },
            max_step,
            max_steps,
            last_rejected: false,
            steps: 0,
            rejected: 0,
        }
    }

    /// The step to try from `time` toward `t_end` with the proposed `h`, and whether it is the
    /// last (shortened to land on `t_end`).
    ///
    /// # Errors
    /// The step budget is spent; the step fell below its floor.
    pub(crate) fn next(
        &self,
        h: Real,
        time: Real,
        t_end: Real,
    ) -> Result<(Real, bool), DynamicsError> {
        if self.steps + self.rejected >= self.max_steps {
            return Err(DynamicsError::TooManySteps {
                time,
                max_steps: self.max_steps,
            });
        }
        let remaining = t_end - time;
        let last = h >= remaining;
        let h_try = if last { remaining } else { h };
        if h_try < self.min_step && !last {
            return Err(DynamicsError::StepSizeTooSmall {
                time,
                step: h_try,
                min_step: self.min_step,
            });
        }
        Ok((h_try, last))
    }

    /// A step of `h_try` was rejected with error norm `error` (> 1): the next step to try.
    pub(crate) fn reject(&mut self, h_try: Real, error: Real) -> Real {
        self.rejected += 1;
        self.last_rejected = true;
        h_try * (0.9 * error.powf(self.exponent)).max(self.shrink_limit)
    }

    /// A step of `h_try` was refused for a stage's overlap: try a quarter of it.
    pub(crate) fn retry_shorter(&mut self, h_try: Real) -> Real {
        self.rejected += 1;
        self.last_rejected = true;
        0.25 * h_try
    }

    /// A step of `h_try` with error norm `error` (≤ 1) was accepted: the next step.
    pub(crate) fn accept(&mut self, h_try: Real, error: Real) -> Real {
        self.steps += 1;
        let grow = if error > 0.0 {
            (0.9 * error.powf(self.exponent)).clamp(self.shrink_limit, self.grow_limit)
        } else {
            self.grow_limit
        };
        let grow = if self.last_rejected {
            grow.min(1.0)
        } else {
            grow
        };
        self.last_rejected = false;
        (h_try * grow).min(self.max_step)
    }
}

/// $\mathbf y + h\sum_j a_j\mathbf k_j$, the sum formed before the multiplication by h: a
/// product $a_j h$ rounded once would repeat the same relative error at every step of equal
/// length (a systematic error), while the rounding of $h\sum_j a_j\mathbf k_j$ depends on the
/// data.
fn combine(y: &[Vec3; 4], row: &[Real], k: &Stages, h: Real) -> [Vec3; 4] {
    let mut sum = [Vec3::zeros(); 4];
    for (kj, &a) in k.iter().zip(row) {
        if a != 0.0 {
            for n in 0..4 {
                sum[n] += kj[n] * a;
            }
        }
    }
    let mut out = *y;
    for n in 0..4 {
        out[n] += sum[n] * h;
    }
    out
}

impl Adaptive {
    /// Dormand–Prince 5(4) with relative and absolute tolerances (positive, finite). Defaults:
    /// minimum step 1e-12 × the span of the run, maximum step the span, initial step chosen
    /// automatically, at most 10⁸ steps. [`Adaptive::with_pair`] switches the pair.
    pub fn new(relative_tolerance: Real, absolute_tolerance: Real) -> Result<Self, DynamicsError> {
        Ok(Self {
            pair: EmbeddedPair::DormandPrince54,
            relative_tolerance: positive_finite("relative_tolerance", relative_tolerance)?,
            absolute_tolerance: positive_finite("absolute_tolerance", absolute_tolerance)?,
            min_step: 0.0,
            max_step: Real::INFINITY,
            initial_step: None,
            max_steps: 100_000_000,
            escape_distance: None,
        })
    }

    /// DOP853 with relative and absolute tolerances (positive, finite); other defaults as
    /// [`Adaptive::new`].
    pub fn dop853(
        relative_tolerance: Real,
        absolute_tolerance: Real,
    ) -> Result<Self, DynamicsError> {
        Ok(Self::new(relative_tolerance, absolute_tolerance)?.with_pair(EmbeddedPair::Dop853))
    }

    /// Uses `pair`.
    pub fn with_pair(mut self, pair: EmbeddedPair) -> Self {
        self.pair = pair;
        self
    }

    /// The embedded pair.
    pub fn pair(&self) -> EmbeddedPair {
        self.pair
    }

    /// Sets the step floor (non-negative, finite; 0 means 1e-12 × the span).
    pub fn with_min_step(mut self, min_step: Real) -> Result<Self, DynamicsError> {
        if !(min_step.is_finite() && min_step >= 0.0) {
            return Err(DynamicsError::InvalidParameter {
                name: "min_step",
                requirement: "non-negative and finite",
                value: min_step,
            });
        }
        self.min_step = min_step;
        Ok(self)
    }

    /// Sets the largest step (positive).
    pub fn with_max_step(mut self, max_step: Real) -> Result<Self, DynamicsError> {
        if max_step.is_nan() || max_step <= 0.0 {
            return Err(DynamicsError::InvalidParameter {
                name: "max_step",
                requirement: "positive",
                value: max_step,
            });
        }
        self.max_step = max_step;
        Ok(self)
    }

    /// Sets the first step (positive, finite).
    pub fn with_initial_step(mut self, step: Real) -> Result<Self, DynamicsError> {
        self.initial_step = Some(positive_finite("initial_step", step)?);
        Ok(self)
    }

    /// Sets the maximum number of accepted plus rejected steps.
    pub fn with_max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }

    /// One step of length `h` of the pair from `from`, whose state carries the low-order part
    /// `carry` (compensated summation, see [`Adaptive::run`]); returns the propagated sample,
    /// its carry and the error norm, and leaves the stage derivatives in `k` (for the dense
    /// output).
    fn rk_step(
        &self,
        dynamics: &mut Dynamics<'_>,
        from: &Sample,
        carry: &[Vec3; 4],
        h: Real,
        k: &mut Stages,
    ) -> Result<(Sample, [Vec3; 4], Real), InteractionError> {
        let tableau = self.pair.tableau();
        let y = Phase::of(&from.state).0;
        k[0] = [y[2], y[3], from.acceleration_a, from.acceleration_b];
        let inner = &tableau.a[..tableau.a.len() - 1];
        for (i, row) in inner.iter().enumerate() {
            let stage = combine(&y, row, k, h);
            let acc = dynamics.accelerations(&stage[0], &stage[1])?;
            k[i + 1] = [stage[2], stage[3], acc.0, acc.1];
        }
        // The increment h Σ b_i k_i is formed on its own and added with compensated summation
        // (Kahan): the rounding of y + Δ is kept in the carry and added back at the next step,
        // so round-off does not accumulate systematically over long runs (Brouwer's law).
        let increment = combine(&[Vec3::zeros(); 4], tableau.b(), k, h);
        let mut end = y;
        let mut next_carry = [Vec3::zeros(); 4];
        for n in 0..4 {
            let delta = increment[n] + carry[n];
            end[n] = y[n] + delta;
            next_carry[n] = delta - (end[n] - y[n]);
        }
        // The last stage (FSAL) is the derivative at the propagated solution.
        let acc = dynamics.accelerations(&end[0], &end[1])?;
        let last = tableau.stages() - 1;
        k[last] = [end[2], end[3], acc.0, acc.1];
        let error = self.error_norm(tableau, &y, &end, k, h);
        let sample = dynamics.sample(from.time + h, Phase(end), acc);
        Ok((sample, next_carry, error))
    }

    /// The scaled error norm of a step (see the module documentation).
    fn error_norm(
        &self,
        tableau: &Tableau,
        y0: &[Vec3; 4],
        y1: &[Vec3; 4],
        k: &Stages,
        h: Real,
    ) -> Real {
        let stages = tableau.stages();
        // Σ over the 12 components of (h Σ_i w_i k_i / scale)².
        let squares = |w: &dyn Fn(usize) -> Real| -> Real {
            let mut sum = 0.0;
            for n in 0..4 {
                let mut e = Vec3::zeros();
                for (i, ki) in k.iter().enumerate().take(stages) {
                    let c = w(i);
                    if c != 0.0 {
                        e += ki[n] * c;
                    }
                }
                for c in 0..3 {
                    let scale = self.absolute_tolerance
                        + self.relative_tolerance * y0[n][c].abs().max(y1[n][c].abs());
                    sum += (e[c] * h / scale).powi(2);
                }
            }
            sum
        };
        tableau.error_norm(12, squares)
    }

    /// DOP853's continuous extension over the accepted step `from` → `to` of length `h` whose
    /// stages are in `k` (three more force evaluations, stored in `k[13..16]`).
    fn dense_step(
        &self,
        dynamics: &mut Dynamics<'_>,
        from: &Sample,
        to: &Sample,
        h: Real,
        k: &mut Stages,
    ) -> Result<DenseStep, InteractionError> {
        let y0 = Phase::of(&from.state).0;
        let y1 = Phase::of(&to.state).0;
        let first = DOP853.stages();
        for (m, row) in DOP853_DENSE_A.iter().enumerate() {
            let stage = combine(&y0, row, k, h);
            let acc = dynamics.accelerations(&stage[0], &stage[1])?;
            k[first + m] = [stage[2], stage[3], acc.0, acc.1];
        }
        let mut coefficients = [[Vec3::zeros(); 4]; 7];
        let zero = [Vec3::zeros(); 4];
        for n in 0..4 {
            let delta = y1[n] - y0[n];
            let beta = k[0][n] * h - delta;
            coefficients[0][n] = delta;
            coefficients[1][n] = beta;
            coefficients[2][n] = delta - k[first - 1][n] * h - beta;
        }
        for (r, row) in DOP853_D.iter().enumerate() {
            coefficients[3 + r] = combine(&zero, row, k, h);
        }
        Ok(DenseStep {
            start: from.time,
            step: h,
            y0,
            coefficients,
        })
    }

    fn first_step(&self, from: &Sample, span: Real) -> Real {
        if let Some(h) = self.initial_step {
            return h.min(span);
        }
        let y = Phase::of(&from.state).0;
        let f = [y[2], y[3], from.acceleration_a, from.acceleration_b];
        let (mut d0, mut d1) = (0.0, 0.0);
        for n in 0..4 {
            for c in 0..3 {
                let scale = self.absolute_tolerance + self.relative_tolerance * y[n][c].abs();
                d0 += (y[n][c] / scale).powi(2);
                d1 += (f[n][c] / scale).powi(2);
            }
        }
        let h = if d0 > 1e-10 && d1 > 1e-10 {
            0.01 * (d0 / d1).sqrt()
        } else {
            1e-6 * span
        };
        h.min(span).min(self.max_step)
    }

    /// Emits every output time in (`from.time`, `to.time`] of an accepted step: DOP853 by its
    /// own dense output (computed once per step, only when an output time falls inside), the
    /// other pair, or DOP853 if a dense stage fails, by the quintic Hermite interpolant.
    #[allow(clippy::too_many_arguments)]
    fn emit_step(
        &self,
        dynamics: &mut Dynamics<'_>,
        from: &Sample,
        to: &Sample,
        h: Real,
        k: &mut Stages,
        clock: &mut OutputClock,
        emit: &mut dyn FnMut(Real, &TwoBodyState),
    ) {
        if self.pair != EmbeddedPair::Dop853 {
            return clock.emit_between(from, to, emit);
        }
        let mut dense: Option<Option<DenseStep>> = None;
        let state_at = |t| {
            if t == to.time || t <= from.time {
                return hermite_or_end(from, to, t);
            }
            let step = dense
                .get_or_insert_with(|| self.dense_step(dynamics, from, to, h, k).ok())
                .as_ref();
            match step {
                Some(step) => step.state(t, &from.state),
                None => state_between(from, to, t),
            }
        };
        clock.emit_until(to.time, state_at, emit);
    }

    /// Emits the output times of the step that ends at the contact `located` from `from`: up
    /// to the bisection's last clear sample by DOP853's own dense output of that step (its
    /// stages recomputed, the same step bit for bit, and three dense stages), or for the other
    /// pair, or DOP853 if a stage fails, by the quintic Hermite interpolant; beyond it, over the
    /// closing Taylor step, by the Hermite interpolant of that step. No output time after the
    /// contact is emitted.
    #[allow(clippy::too_many_arguments)]
    fn emit_contact_step(
        &self,
        dynamics: &mut Dynamics<'_>,
        from: &Sample,
        carry: &[Vec3; 4],
        located: &Located,
        k: &mut Stages,
        clock: &mut OutputClock,
        emit: &mut dyn FnMut(Real, &TwoBodyState),
    ) {
        let (reached, contact) = (&located.reached, &located.event.sample);
        let dense = if self.pair == EmbeddedPair::Dop853 && located.step > 0.0 {
            self.rk_step(dynamics, from, carry, located.step, k)
                .and_then(|_| self.dense_step(dynamics, from, reached, located.step, k))
                .ok()
        } else {
            None
        };
        let state_at = |t: Real| {
            if t > reached.time {
                state_between(reached, contact, t)
            } else if let Some(step) = &dense {
                if t <= from.time {
                    from.state
                } else {
                    step.state(t, &from.state)
                }
            } else {
                state_between(from, reached, t)
            }
        };
        clock.emit_until(contact.time, state_at, emit);
    }

    /// The adaptive loop shared by both pairs; `output` asks for evenly spaced states.
    fn run(
        &self,
        model: &dyn InteractionModel,
        initial: &TwoBodyState,
        t_start: Real,
        t_end: Real,
        observer: &mut dyn FnMut(&Sample),
        mut output: EvenStates<'_>,
    ) -> Result<RunSummary, DynamicsError> {
        check_span(t_start, t_end)?;
        if model.motion_path(initial).is_rotation() {
            let settings = rigid::AdaptiveSettings {
                tableau: self.pair.tableau(),
                dense: self.pair == EmbeddedPair::Dop853,
                relative_tolerance: self.relative_tolerance,
                absolute_tolerance: self.absolute_tolerance,
                min_step: self.min_step,
                max_step: self.max_step,
                initial_step: self.initial_step,
                max_steps: self.max_steps,
            };
            return rigid::integrate(
                rigid::Method::Adaptive(settings),
                model,
                initial,
                (t_start, t_end),
                self.escape_distance,
                observer,
                output,
            );
        }
        let span = t_end - t_start;
        let mut control = StepControl::new(
            self.pair.tableau(),
            self.min_step,
            self.max_step,
            self.max_steps,
            span,
        );
        let mut dynamics = Dynamics::new(model, *initial, t_start);
        let mut current = initial_sample(&mut dynamics, initial, t_start)?;
        emit_step(&mut output, &current, &current);
        observer(&current);
        let mut k: Stages = [[Vec3::zeros(); 4]; MAX_STAGES];
        // Low-order part of the propagated state (compensated summation).
        let mut carry = [Vec3::zeros(); 4];
        let mut h = self.first_step(&current, span);
        loop {
            let (h_try, last) = control.next(h, current.time, t_end)?;
            let result = self.rk_step(&mut dynamics, &current, &carry, h_try, &mut k);
            let (sample, next_carry, error) = match result {
                Ok((s, c, e)) => (Ok(s), c, e),
                Err(err) => (Err(err), carry, 0.0),
            };
            if !error.is_finite() {
                return Err(DynamicsError::NonFinite { time: current.time });
            }
            if error > 1.0 {
                h = control.reject(h_try, error);
                continue;
            }
            match classify(&dynamics, sample, current.time)? {
                Trial::Clear(mut next) => {
                    if last {
                        next.time = t_end;
                    }
                    if let Some((clock, emit)) = output.as_mut() {
                        self.emit_step(&mut dynamics, &current, &next, h_try, &mut k, clock, *emit);
                    }
                    current = next;
                    carry = next_carry;
                    let next_h = control.accept(h_try, error);
                    observer(&current);
                    if let Some(event) = escaped(model, self.escape_distance, &current) {
                        return Ok(dynamics.summary(
                            current,
                            (control.steps, control.rejected),
                            Termination::Escape(Box::new(event)),
                        ));
                    }
                    if last {
                        break;
                    }
                    h = next_h;
                }
                Trial::Touching => {
                    let mut scratch: Stages = [[Vec3::zeros(); 4]; MAX_STAGES];
                    let mut step = |d: &mut Dynamics<'_>, s: &Sample, h: Real| {
                        self.rk_step(d, s, &carry, h, &mut scratch)
                            .map(|(sample, _, error)| (sample, error))
                    };
                    let Some(located) = locate_contact(&mut dynamics, &current, h_try, &mut step)?
                    else {
                        // Only a stage overlapped: reject and retry with a shorter step.
                        h = control.retry_shorter(h_try);
                        continue;
                    };
                    if !located.error.is_finite() {
                        return Err(DynamicsError::NonFinite { time: current.time });
                    }
                    if located.error > 1.0 {
                        // The step that reaches contact fails the error test (a step touching
                        // at its end or a stage has no estimate of its own, so its bisected
                        // lengths are tested here): reject it like any other step and approach
                        // the contact in steps the tolerance accepts.
                        h = control.reject(located.step, located.error);
                        continue;
                    }
                    let event = located.event;
                    if let Some((clock, emit)) = output.as_mut() {
                        self.emit_contact_step(
                            &mut dynamics,
                            &current,
                            &carry,
                            &located,
                            &mut k,
                            clock,
                            *emit,
                        );
                    }
                    observer(&event.sample);
                    return Ok(dynamics.contact_summary(event, (control.steps, control.rejected)));
                }
            }
        }
        Ok(dynamics.summary(
            current,
            (control.steps, control.rejected),
            Termination::Completed,
        ))
    }
}

/// DOP853's continuous extension over one step (module documentation): $\mathbf y_0$, then
/// $\Delta$, $\beta$, $\Delta - h\mathbf k\_{13} - \beta$, $\mathbf d_4, \dots, \mathbf d_7$.
struct DenseStep {
    start: Real,
    step: Real,
    y0: [Vec3; 4],
    coefficients: [[Vec3; 4]; 7],
}

impl DenseStep {
    fn at(&self, time: Real) -> Phase {
        let s = ((time - self.start) / self.step).clamp(0.0, 1.0);
        let s1 = 1.0 - s;
        let [delta, beta, third, d4, d5, d6, d7] = &self.coefficients;
        let mut out = self.y0;
        for n in 0..4 {
            let inner = d4[n] + (d5[n] + (d6[n] + d7[n] * s) * s1) * s;
            out[n] += (delta[n] + (beta[n] + (third[n] + inner * s1) * s) * s1) * s;
        }
        Phase(out)
    }

    /// The state at `time`: positions and velocities from [`DenseStep::at`], attitudes turned
    /// uniformly from the step's first state `first` (the translation path's free spin, as
    /// [`state_between`] turns them).
    fn state(&self, time: Real, first: &TwoBodyState) -> TwoBodyState {
        let mut state = self.at(time).into_state(first);
        let elapsed = time.clamp(self.start, self.start + self.step) - self.start;
        for body in [&mut state.body_a, &mut state.body_b] {
            *body = body.spun(elapsed);
        }
        state
    }
}

impl Integrator for Adaptive {
    fn name(&self) -> &'static str {
        self.pair.name()
    }

    fn set_escape_distance(&mut self, distance: Option<Real>) -> Result<(), DynamicsError> {
        self.escape_distance = check_escape_distance(distance)?;
        Ok(())
    }

    fn integrate(
        &mut self,
        model: &dyn InteractionModel,
        initial: &TwoBodyState,
        t_start: Real,
        t_end: Real,
        observer: &mut dyn FnMut(&Sample),
    ) -> Result<RunSummary, DynamicsError> {
        self.run(model, initial, t_start, t_end, observer, None)
    }

    fn integrate_with_output(
        &mut self,
        model: &dyn InteractionModel,
        initial: &TwoBodyState,
        t_start: Real,
        t_end: Real,
        interval: Real,
        observer: &mut dyn FnMut(&Sample),
        emit: &mut dyn FnMut(Real, &TwoBodyState),
    ) -> Result<RunSummary, DynamicsError> {
        with_even_output(t_start, interval, emit, |output| {
            self.run(model, initial, t_start, t_end, observer, output)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Necessary order conditions of a symmetric composition of order p: the odd power sums
    /// $\sum_i w_i^k$ vanish for k = 3, 5, ..., p − 1 (the error terms of the leapfrog
    /// sub-steps that are not nested commutators). The full order is measured in the tests.
    #[test]
    fn composition_odd_power_sums_vanish() {
        for scheme in [
            FixedScheme::Yoshida4,
            FixedScheme::Yoshida6,
            FixedScheme::TripleJump8,
        ] {
            let w = scheme.weights();
            for k in (3..scheme.order() as i32).step_by(2) {
                let sum: Real = w.iter().map(|x| x.powi(k)).sum();
                let scale: Real = w.iter().map(|x| x.abs().powi(k)).sum();
                assert!(
                    sum.abs() < 1e-14 * scale,
                    "{scheme:?}: sum of w^{k} = {sum:e} (scale {scale:e})"
                );
            }
        }
    }

    #[test]
    fn composition_weights_sum_to_one_and_are_symmetric() {
        for scheme in [
            FixedScheme::Leapfrog,
            FixedScheme::Yoshida4,
            FixedScheme::Yoshida6,
            FixedScheme::TripleJump8,
        ] {
            let w = scheme.weights();
            assert!((w.iter().sum::<Real>() - 1.0).abs() < 1e-14, "{scheme:?}");
            for (x, y) in w.iter().zip(w.iter().rev()) {
                assert_eq!(x, y);
            }
        }
    }
}
