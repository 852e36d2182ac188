//! Dense output between two trajectory samples: quintic Hermite interpolation.
//!
//! Between samples at $t_0$ and $t_1 = t_0 + h$ with positions, velocities and accelerations
//! $(\mathbf x_i, \mathbf v_i, \mathbf a_i)$ known at both ends, with $s = (t - t_0)/h$,
//! $$\mathbf x(t) = \mathbf x_0 H_0 + h\mathbf v_0 H_1 + h^2\mathbf a_0 H_2 + \mathbf x_1 H_3 + h\mathbf v_1 H_4 + h^2\mathbf a_1 H_5,$$
//! with the quintic Hermite basis
//! $H_0 = 1 - 10s^3 + 15s^4 - 6s^5$, $H_1 = s - 6s^3 + 8s^4 - 3s^5$,
//! $H_2 = (s^2 - 3s^3 + 3s^4 - s^5)/2$, $H_3 = 10s^3 - 15s^4 + 6s^5$,
//! $H_4 = -4s^3 + 7s^4 - 3s^5$, $H_5 = (s^3 - 2s^4 + s^5)/2$.
//!
//! The interpolant matches value, first and second derivative at both ends; its error for a smooth
//! trajectory is $O(h^6)$ in position and $O(h^5)$ in velocity, on top of the integrator's own
//! error at the samples. It needs nothing from the integrator but the samples, so every method of
//! this crate (fixed-step or adaptive) has the same dense output.

use crate::integrate::{positive_finite, DynamicsError};
use crate::state::{Sample, TwoBodyState};
use surfgrav_potentials::{Real, Vec3};

/// Position and velocity at fraction `s` ∈ [0, 1] of a step of length `h`.
#[allow(clippy::too_many_arguments)]
pub fn hermite_quintic(
    x0: &Vec3,
    v0: &Vec3,
    a0: &Vec3,
    x1: &Vec3,
    v1: &Vec3,
    a1: &Vec3,
    h: Real,
    s: Real,
) -> (Vec3, Vec3) {
    let s2 = s * s;
    let s3 = s2 * s;
    let s4 = s3 * s;
    let s5 = s4 * s;
    let h0 = 1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5;
    let h1 = s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5;
    let h2 = 0.5 * (s2 - 3.0 * s3 + 3.0 * s4 - s5);
    let h3 = 10.0 * s3 - 15.0 * s4 + 6.0 * s5;
    let h4 = -4.0 * s3 + 7.0 * s4 - 3.0 * s5;
    let h5 = 0.5 * (s3 - 2.0 * s4 + s5);
    // Derivatives with respect to s.
    let d0 = -30.0 * s2 + 60.0 * s3 - 30.0 * s4;
    let d1 = 1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4;
    let d2 = 0.5 * (2.0 * s - 9.0 * s2 + 12.0 * s3 - 5.0 * s4);
    let d3 = -d0;
    let d4 = -12.0 * s2 + 28.0 * s3 - 15.0 * s4;
    let d5 = 0.5 * (3.0 * s2 - 8.0 * s3 + 5.0 * s4);
    let hh = h * h;
    let position =
        x0 * h0 + v0 * (h * h1) + a0 * (hh * h2) + x1 * h3 + v1 * (h * h4) + a1 * (hh * h5);
    let velocity = (x0 * d0 + x1 * d3) / h + v0 * d1 + v1 * d4 + a0 * (h * d2) + a1 * (h * d5);
    (position, velocity)
}

/// The state at time `time` between two consecutive samples (`time` is clamped to their span).
/// Attitudes turn uniformly from `first`'s about its angular velocity: the translation path's
/// free spin ([`crate::model::MotionPath::Translation`]); the rotational path interpolates its
/// own states.
pub fn state_between(first: &Sample, second: &Sample, time: Real) -> TwoBodyState {
    let h = second.time - first.time;
    if h == 0.0 {
        return first.state;
    }
    let s = ((time - first.time) / h).clamp(0.0, 1.0);
    let (a0, a1) = (&first.state.body_a, &second.state.body_a);
    let (b0, b1) = (&first.state.body_b, &second.state.body_b);
    let (xa, va) = hermite_quintic(
        &a0.position,
        &a0.velocity,
        &first.acceleration_a,
        &a1.position,
        &a1.velocity,
        &second.acceleration_a,
        h,
        s,
    );
    let (xb, vb) = hermite_quintic(
        &b0.position,
        &b0.velocity,
        &first.acceleration_b,
        &b1.position,
        &b1.velocity,
        &second.acceleration_b,
        h,
        s,
    );
    let mut state = first.state;
    state.body_a = state
        .body_a
        .spun(time.clamp(first.time, second.time) - first.time);
    state.body_b = state
        .body_b
        .spun(time.clamp(first.time, second.time) - first.time);
    state.body_a.position = xa;
    state.body_a.velocity = va;
    state.body_b.position = xb;
    state.body_b.velocity = vb;
    state
}

/// Relative position and velocity $(\mathbf r, \dot{\mathbf r})$ at `time` between two samples.
pub fn relative_between(first: &Sample, second: &Sample, time: Real) -> (Vec3, Vec3) {
    let h = second.time - first.time;
    if h == 0.0 {
        return (
            first.state.relative_position(),
            first.state.relative_velocity(),
        );
    }
    let s = ((time - first.time) / h).clamp(0.0, 1.0);
    hermite_quintic(
        &first.state.relative_position(),
        &first.state.relative_velocity(),
        &first.relative_acceleration(),
        &second.state.relative_position(),
        &second.state.relative_velocity(),
        &second.relative_acceleration(),
        h,
        s,
    )
}

/// Evenly spaced output from the samples of any integrator: feed it every sample in order and it
/// calls `emit(time, state)` at $t_0, t_0 + \Delta, t_0 + 2\Delta, \dots$ (times computed as
/// $t_0 + k\Delta$, no accumulated round-off), interpolating with [`state_between`].
#[derive(Debug, Clone)]
pub struct EvenOutput {
    interval: Real,
    clock: Option<OutputClock>,
    previous: Option<Sample>,
}

impl EvenOutput {
    /// Output every `interval` (positive, finite) from the first sample's time; `None` otherwise.
    pub fn new(interval: Real) -> Option<Self> {
        (interval.is_finite() && interval > 0.0).then_some(Self {
            interval,
            clock: None,
            previous: None,
        })
    }

    /// Takes the next sample and emits every output time up to and including its time.
    pub fn observe(&mut self, sample: &Sample, emit: &mut dyn FnMut(Real, &TwoBodyState)) {
        let clock = self.clock.get_or_insert(OutputClock {
            start: sample.time,
            interval: self.interval,
            emitted: 0,
        });
        let first = self.previous.unwrap_or(*sample);
        clock.emit_between(&first, sample, emit);
        self.previous = Some(*sample);
    }
}

/// Where a run sends evenly spaced states, if anywhere: the output times and the receiver.
pub(crate) type EvenStates<'a> =
    Option<(&'a mut OutputClock, &'a mut dyn FnMut(Real, &TwoBodyState))>;

/// Output times $t_0 + k\Delta$ (computed from $k$, no accumulated round-off): the one output
/// loop of every integrator ([`EvenOutput`], the fixed-step and adaptive runs, the rotational
/// path).
#[derive(Debug, Clone)]
pub(crate) struct OutputClock {
    start: Real,
    interval: Real,
    emitted: u64,
}

impl OutputClock {
    /// Output every `interval` from `start`.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidParameter`] unless `interval` is positive and finite.
    pub(crate) fn new(start: Real, interval: Real) -> Result<Self, DynamicsError> {
        Ok(Self {
            start,
            interval: positive_finite("interval", interval)?,
            emitted: 0,
        })
    }

    /// The next output time if it is at most `until` (and counts it as emitted).
    fn next_until(&mut self, until: Real) -> Option<Real> {
        let t = self.start + self.emitted as Real * self.interval;
        (t <= until).then(|| {
            self.emitted += 1;
            t
        })
    }

    /// Emits every output time up to and including `until`, in order, with the state
    /// `state_at(t)`.
    pub(crate) fn emit_until(
        &mut self,
        until: Real,
        mut state_at: impl FnMut(Real) -> TwoBodyState,
        emit: &mut dyn FnMut(Real, &TwoBodyState),
    ) {
        while let Some(t) = self.next_until(until) {
            emit(t, &state_at(t));
        }
    }

    /// Emits the output times of the step between consecutive samples `from` → `to`: a sample's
    /// own state at its time, the quintic Hermite interpolant ([`state_between`]) inside.
    pub(crate) fn emit_between(
        &mut self,
        from: &Sample,
        to: &Sample,
        emit: &mut dyn FnMut(Real, &TwoBodyState),
    ) {
        self.emit_until(to.time, |t| hermite_or_end(from, to, t), emit);
    }
}

/// The state at `t` in the step `from` → `to`: the end samples' own states at (or beyond) the
/// ends, [`state_between`] inside.
pub(crate) fn hermite_or_end(from: &Sample, to: &Sample, t: Real) -> TwoBodyState {
    if t == to.time {
        to.state
    } else if t <= from.time {
        from.state
    } else {
        state_between(from, to, t)
    }
}

/// Runs `run` with evenly spaced output every `interval` from `t_start` sent to `emit`.
///
/// # Errors
/// [`DynamicsError::InvalidParameter`] for an interval that is not positive and finite, before
/// `run` starts; then whatever `run` returns.
pub(crate) fn with_even_output<R>(
    t_start: Real,
    interval: Real,
    emit: &mut dyn FnMut(Real, &TwoBodyState),
    run: impl FnOnce(EvenStates<'_>) -> Result<R, DynamicsError>,
) -> Result<R, DynamicsError> {
    let mut clock = OutputClock::new(t_start, interval)?;
    run(Some((&mut clock, emit)))
}

/// Emits, if output is asked for, the output times of the step `from` → `to` (see
/// [`OutputClock::emit_between`]).
pub(crate) fn emit_step(output: &mut EvenStates<'_>, from: &Sample, to: &Sample) {
    if let Some((clock, emit)) = output.as_mut() {
        clock.emit_between(from, to, *emit);
    }
}
