//! `Simulation`: two bodies with their states, an integrator chosen by name, `integrate` to a
//! time returning the trajectory as numpy arrays (shaped like REBOUND's `Simulation`).
//!
//! The model is chosen as `surfgrav run` chooses it: two point masses move under the exact
//! $V = -Gm_Am_B/r$; otherwise [`SceneModel::build`] tabulates $V(r)$ when the pair is central
//! (and `tabulate` is on) and uses the direct surface integral otherwise. The integrator then
//! takes the translation path where a symmetry keeps every torque at zero, and integrates
//! rotation otherwise (the summary says which and why).

use std::sync::Arc;
use std::time::Instant;

use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use surfgrav_dynamics::{
    angular_momentum, total_energy, BodyState, DynamicsError, EngineModelError, IntegratorKind,
    InteractionModel, PointMasses, SceneModel, SceneSettings, Termination, TwoBodyState,
};
use surfgrav_interaction::InteractionError as EngineError;
use surfgrav_potentials::Vec3;

use crate::arrays;
use crate::bodies::{Body, Core};
use crate::errors::{compute, input, Failure, InputError};
use crate::interaction::options;

/// One body of a simulation with its state.
struct Member {
    body: Py<Body>,
    core: Arc<Core>,
    state: BodyState,
}

/// Two bodies, their states and the integrator: `add` the bodies, then `integrate`.
///
/// `Simulation(integrator="rk4", step=None, tolerance=None, t=0.0, interaction_tolerance=1e-12,
/// tabulate=True, escape_distance=None)`. Fixed-step integrators (rk4, leapfrog, yoshida4, yoshida6, yoshida8) need
/// `step`; adaptive ones (dopri5, dop853) need `tolerance`.
#[pyclass(module = "surfgrav")]
pub struct Simulation {
    members: Vec<Member>,
    /// Current time.
    #[pyo3(get, set)]
    t: f64,
    kind: IntegratorKind,
    /// Fixed step of rk4, leapfrog and yoshida4/6/8 (None until set).
    #[pyo3(get, set)]
    step: Option<f64>,
    /// Tolerance of dopri5 and dop853 (None until set).
    #[pyo3(get, set)]
    tolerance: Option<f64>,
    /// Relative accuracy of the surface integrals (default 1e-12).
    #[pyo3(get, set)]
    interaction_tolerance: f64,
    /// Tabulate V(r) once when the pair is central (default True).
    #[pyo3(get, set)]
    tabulate: bool,
    /// Stop an unbound orbit when the separation passes this (None: never).
    #[pyo3(get, set)]
    escape_distance: Option<f64>,
}

/// The integrator kind of a name, with the CLI's message.
fn kind_of(name: &str) -> PyResult<IntegratorKind> {
    name.parse::<IntegratorKind>()
        .map_err(|e| InputError::new_err(e.to_string()))
}

/// What one integrate call records.
#[derive(Default)]
struct Record {
    times: Vec<f64>,
    states: Vec<TwoBodyState>,
    energies: Vec<f64>,
    momenta: Vec<Vec3>,
    energy_error: Option<String>,
}

impl Record {
    fn push(&mut self, model: &dyn InteractionModel, time: f64, state: &TwoBodyState) {
        let e = match total_energy(model, state) {
            Ok(e) => e,
            Err(err) => {
                if self.energy_error.is_none() {
                    self.energy_error = Some(format!("at t = {time}: energy: {err}"));
                }
                f64::NAN
            }
        };
        self.times.push(time);
        self.states.push(*state);
        self.energies.push(e);
        self.momenta.push(angular_momentum(model, state));
    }
}

/// The summary of one integrate call.
struct Outcome {
    record: Record,
    last: TwoBodyState,
    t_reached: f64,
    steps: usize,
    rejected_steps: usize,
    force_evaluations: usize,
    termination: &'static str,
    event_time: Option<f64>,
    model: &'static str,
    path: (&'static str, &'static str),
    wall_seconds: f64,
}

/// Builds the model as `surfgrav run` does; the messages are the CLI's.
fn build_model(
    a: &Core,
    b: &Core,
    initial: &TwoBodyState,
    interaction_tolerance: f64,
    tabulate: bool,
) -> Result<(Box<dyn InteractionModel>, &'static str), Failure> {
    if a.is_point() && b.is_point() {
        if a.g != b.g {
            return Err(input(
                EngineError::GravitationalConstantMismatch { a: a.g, b: b.g }.to_string(),
            ));
        }
        let (ma, mb) = (a.engine.mass(), b.engine.mass());
        let model = PointMasses::new(ma, mb, a.g)
            .ok_or_else(|| input("point masses must be positive and finite"))?;
        return Ok((Box::new(model), "point masses (exact)"));
    }
    let settings = SceneSettings {
        engine: surfgrav_interaction::InteractionOptions {
            relative_tolerance: interaction_tolerance,
            ..Default::default()
        },
        interpolate: tabulate,
        ..SceneSettings::default()
    };
    let model = SceneModel::build(a.engine.clone(), b.engine.clone(), initial, &settings)
        .map_err(|e| match e {
            EngineModelError::Engine(
                EngineError::Overlap { separation } | EngineError::Touching { separation },
            ) => input(format!(
                "the bodies overlap or touch at the start (centroid separation {separation}): move them apart"
            )),
            EngineModelError::Engine(e) => input(format!("the scene cannot start: {e}")),
            EngineModelError::InvalidMass { .. } | EngineModelError::InvalidSetting { .. } => {
                input(e.to_string())
            }
            other => Failure::Run(other.to_string()),
        })?;
    let name = if model.is_interpolated() {
        "tabulated V(r)"
    } else {
        "direct surface integral"
    };
    Ok((Box::new(model), name))
}

#[allow(clippy::too_many_arguments)]
fn run(
    a: &Core,
    b: &Core,
    initial: TwoBodyState,
    kind: IntegratorKind,
    step: f64,
    tolerance: f64,
    interaction_tolerance: f64,
    tabulate: bool,
    t_start: f64,
    t_end: f64,
    interval: Option<f64>,
    escape_distance: Option<f64>,
) -> Result<Outcome, Failure> {
    let started = Instant::now();
    let mut integrator = kind
        .build(step, tolerance)
        .map_err(|e| input(e.to_string()))?;
    integrator
        .set_escape_distance(escape_distance)
        .map_err(|e| input(e.to_string()))?;
    let (model, model_name) = build_model(a, b, &initial, interaction_tolerance, tabulate)?;
    let model = model.as_ref();
    let path = model.motion_path(&initial);
    let path = (
        if path.is_rotation() {
            "rotation"
        } else {
            "translation"
        },
        path.reason(),
    );
    let mut record = Record::default();
    let result = match interval {
        None => integrator.integrate(model, &initial, t_start, t_end, &mut |sample| {
            record.push(model, sample.time, &sample.state)
        }),
        Some(dt) => integrator.integrate_with_output(
            model,
            &initial,
            t_start,
            t_end,
            dt,
            &mut |_| {},
            &mut |time, state| record.push(model, time, state),
        ),
    };
    let summary = result.map_err(|e| match e {
        DynamicsError::TorquesNotSupported { .. } | DynamicsError::InvalidParameter { .. } => {
            input(e.to_string())
        }
        other => Failure::Run(other.to_string()),
    })?;
    // With an interval, the last state is always given too (the end time, or the contact).
    if record.times.last().is_none_or(|&t| t < summary.last.time) {
        record.push(model, summary.last.time, &summary.last.state);
    }
    if let Some(message) = record.energy_error.take() {
        return Err(Failure::Run(message));
    }
    let termination = match &summary.termination {
        Termination::Completed => "completed",
        Termination::Contact(_) => "contact",
        Termination::Escape(_) => "escape",
    };
    let event_time = summary.termination.event_time();
    Ok(Outcome {
        record,
        last: summary.last.state,
        t_reached: summary.last.time,
        steps: summary.steps,
        rejected_steps: summary.rejected_steps,
        force_evaluations: summary.force_evaluations,
        termination,
        event_time,
        model: model_name,
        path,
        wall_seconds: started.elapsed().as_secs_f64(),
    })
}

/// The per-row arrays of a trajectory: (M,) times, (M, 2, 3) positions and velocities, (M, 2, 4)
/// attitude quaternions scalar first, (M, 2, 3) angular velocities.
pub struct StateArrays<'py> {
    pub t: Bound<'py, PyArray1<f64>>,
    pub positions: Bound<'py, PyArray3<f64>>,
    pub velocities: Bound<'py, PyArray3<f64>>,
    pub orientations: Bound<'py, PyArray3<f64>>,
    pub angular_velocities: Bound<'py, PyArray3<f64>>,
}

/// The arrays of `times` and `states`.
pub fn state_arrays<'py>(
    py: Python<'py>,
    times: Vec<f64>,
    states: &[TwoBodyState],
) -> StateArrays<'py> {
    let (mut x, mut v, mut q, mut w) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for s in states {
        for body in [&s.body_a, &s.body_b] {
            x.extend_from_slice(body.position.as_slice());
            v.extend_from_slice(body.velocity.as_slice());
            q.extend_from_slice(&arrays::scalar_first(&body.orientation));
            w.extend_from_slice(body.angular_velocity.as_slice());
        }
    }
    StateArrays {
        t: PyArray1::from_vec(py, times),
        positions: arrays::pairs(py, x, 3),
        velocities: arrays::pairs(py, v, 3),
        orientations: arrays::pairs(py, q, 4),
        angular_velocities: arrays::pairs(py, w, 3),
    }
}

/// A trajectory: one row per accepted step (or per output time with an interval).
#[pyclass(module = "surfgrav", frozen)]
pub struct Trajectory {
    /// Times, (M,).
    #[pyo3(get)]
    t: Py<PyArray1<f64>>,
    /// Centroid positions of A and B, (M, 2, 3).
    #[pyo3(get)]
    positions: Py<PyArray3<f64>>,
    /// Centroid velocities, (M, 2, 3).
    #[pyo3(get)]
    velocities: Py<PyArray3<f64>>,
    /// Attitudes (body → world) as unit quaternions scalar first (w, x, y, z), (M, 2, 4).
    #[pyo3(get)]
    orientations: Py<PyArray3<f64>>,
    /// Angular velocities (world frame), (M, 2, 3).
    #[pyo3(get)]
    angular_velocities: Py<PyArray3<f64>>,
    /// Total energy E = T + V (spins included), (M,).
    #[pyo3(get)]
    energy: Py<PyArray1<f64>>,
    /// Total angular momentum about the origin (orbital and spin), (M, 3).
    #[pyo3(get)]
    angular_momentum: Py<PyArray2<f64>>,
    /// steps, rejected_steps, force_evaluations, motion_path, motion_reason, model,
    /// integrator, termination (completed, contact or escape), event_time (of the contact or
    /// escape, else None), t_start, t_end (reached), wall_seconds.
    #[pyo3(get)]
    summary: Py<PyDict>,
    len: usize,
}

#[pymethods]
impl Trajectory {
    fn __len__(&self) -> usize {
        self.len
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let summary = self
            .summary
            .bind(py)
            .repr()
            .map(|r| r.to_string())
            .unwrap_or_default();
        format!("Trajectory(rows={}, summary={summary})", self.len)
    }
}

#[pymethods]
impl Simulation {
    #[new]
    #[pyo3(signature = (integrator = "rk4", step = None, tolerance = None, t = 0.0, interaction_tolerance = 1e-12, tabulate = true, escape_distance = None))]
    fn new(
        integrator: &str,
        step: Option<f64>,
        tolerance: Option<f64>,
        t: f64,
        interaction_tolerance: f64,
        tabulate: bool,
        escape_distance: Option<f64>,
    ) -> PyResult<Self> {
        if !t.is_finite() {
            return Err(InputError::new_err(format!("t must be finite, got {t}")));
        }
        Ok(Self {
            members: Vec::new(),
            t,
            kind: kind_of(integrator)?,
            step,
            tolerance,
            interaction_tolerance,
            tabulate,
            escape_distance,
        })
    }

    /// The integrator's name: rk4, leapfrog, yoshida4, yoshida6, yoshida8, dopri5 or dop853.
    #[getter]
    fn get_integrator(&self) -> &'static str {
        self.kind.name()
    }

    #[setter]
    fn set_integrator(&mut self, name: &str) -> PyResult<()> {
        self.kind = kind_of(name)?;
        Ok(())
    }

    /// Number of bodies added (0, 1 or 2).
    #[getter(N)]
    fn count(&self) -> usize {
        self.members.len()
    }

    /// The bodies, A then B.
    #[getter]
    fn bodies<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, self.members.iter().map(|m| m.body.clone_ref(py)))
    }

    /// Adds a body (the first is A, the second B) with its world-frame state: centroid
    /// `position` and `velocity`, `orientation` (body → world; a rotation vector, 3 numbers, or
    /// a unit quaternion w, x, y, z; default none) and `angular_velocity` (world frame).
    #[pyo3(signature = (body, position = None, velocity = None, orientation = None, angular_velocity = None))]
    fn add(
        &mut self,
        body: &Bound<'_, Body>,
        position: Option<&Bound<'_, PyAny>>,
        velocity: Option<&Bound<'_, PyAny>>,
        orientation: Option<&Bound<'_, PyAny>>,
        angular_velocity: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        if self.members.len() == 2 {
            return Err(InputError::new_err(
                "a Simulation holds two bodies (A and B) and both are added",
            ));
        }
        let vector = |v: Option<&Bound<'_, PyAny>>, what: &str| match v {
            Some(v) if !v.is_none() => arrays::vector(v, what),
            _ => Ok(Vec3::zeros()),
        };
        let mut state =
            BodyState::new(vector(position, "position")?, vector(velocity, "velocity")?);
        state.orientation = arrays::orientation(orientation, "orientation")?;
        state.angular_velocity = vector(angular_velocity, "angular_velocity")?;
        self.members.push(Member {
            body: body.clone().unbind(),
            core: Arc::clone(&body.get().core),
            state,
        });
        Ok(())
    }

    /// Centroid positions now, (N, 3).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let flat = self
            .members
            .iter()
            .flat_map(|m| m.state.position.iter().copied().collect::<Vec<_>>())
            .collect();
        arrays::matrix(py, flat, 3)
    }

    /// Centroid velocities now, (N, 3).
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let flat = self
            .members
            .iter()
            .flat_map(|m| m.state.velocity.iter().copied().collect::<Vec<_>>())
            .collect();
        arrays::matrix(py, flat, 3)
    }

    /// Attitudes now as unit quaternions scalar first (w, x, y, z), (N, 4).
    #[getter]
    fn orientations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let flat = self
            .members
            .iter()
            .flat_map(|m| arrays::scalar_first(&m.state.orientation))
            .collect();
        arrays::matrix(py, flat, 4)
    }

    /// Angular velocities now (world frame), (N, 3).
    #[getter]
    fn angular_velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let flat = self
            .members
            .iter()
            .flat_map(|m| m.state.angular_velocity.iter().copied().collect::<Vec<_>>())
            .collect();
        arrays::matrix(py, flat, 3)
    }

    /// Integrates from `t` to `t_end` and moves the simulation there (or to the contact time,
    /// if the bodies touch first). Without `interval` the trajectory has a row per accepted
    /// step (the start included); with it, rows at t + k·interval from the integrator's dense
    /// output, and the last state. Returns a `Trajectory`. The GIL is released during the run.
    #[pyo3(signature = (t_end, interval = None))]
    fn integrate(
        &mut self,
        py: Python<'_>,
        t_end: f64,
        interval: Option<f64>,
    ) -> PyResult<Trajectory> {
        if self.members.len() != 2 {
            return Err(InputError::new_err(format!(
                "a Simulation needs two bodies to integrate, it has {}; add them with \
                 sim.add(body, position=..., velocity=...)",
                self.members.len()
            )));
        }
        options(self.interaction_tolerance).map_err(|_| {
            InputError::new_err(format!(
                "interaction_tolerance must be a positive finite number, got {}",
                self.interaction_tolerance
            ))
        })?;
        let (a, b) = (
            Arc::clone(&self.members[0].core),
            Arc::clone(&self.members[1].core),
        );
        let initial = TwoBodyState::new(self.members[0].state, self.members[1].state);
        let (kind, step, tolerance) = (
            self.kind,
            self.step.unwrap_or(f64::NAN),
            self.tolerance.unwrap_or(f64::NAN),
        );
        let (itol, tabulate, t0) = (self.interaction_tolerance, self.tabulate, self.t);
        let escape = self.escape_distance;
        let outcome = compute(py, move || {
            run(
                &a, &b, initial, kind, step, tolerance, itol, tabulate, t0, t_end, interval, escape,
            )
        })?;
        self.t = outcome.t_reached;
        self.members[0].state = outcome.last.body_a;
        self.members[1].state = outcome.last.body_b;

        let summary = PyDict::new(py);
        summary.set_item("steps", outcome.steps)?;
        summary.set_item("rejected_steps", outcome.rejected_steps)?;
        summary.set_item("force_evaluations", outcome.force_evaluations)?;
        summary.set_item("motion_path", outcome.path.0)?;
        summary.set_item("motion_reason", outcome.path.1)?;
        summary.set_item("model", outcome.model)?;
        summary.set_item("integrator", kind.name())?;
        summary.set_item("termination", outcome.termination)?;
        summary.set_item("event_time", outcome.event_time)?;
        summary.set_item("t_start", t0)?;
        summary.set_item("t_end", outcome.t_reached)?;
        summary.set_item("wall_seconds", outcome.wall_seconds)?;

        let record = outcome.record;
        let len = record.times.len();
        let momenta: Vec<f64> = record
            .momenta
            .iter()
            .flat_map(|j| [j.x, j.y, j.z])
            .collect();
        let s = state_arrays(py, record.times, &record.states);
        Ok(Trajectory {
            t: s.t.unbind(),
            positions: s.positions.unbind(),
            velocities: s.velocities.unbind(),
            orientations: s.orientations.unbind(),
            angular_velocities: s.angular_velocities.unbind(),
            energy: PyArray1::from_vec(py, record.energies).unbind(),
            angular_momentum: arrays::matrix(py, momenta, 3).unbind(),
            summary: summary.unbind(),
            len,
        })
    }

    fn __repr__(&self) -> String {
        let bodies: Vec<String> = self.members.iter().map(|m| m.core.describe()).collect();
        format!(
            "Simulation(t={}, integrator='{}', step={}, tolerance={}, bodies=[{}])",
            self.t,
            self.kind.name(),
            self.step.map_or("None".into(), |x| x.to_string()),
            self.tolerance.map_or("None".into(), |x| x.to_string()),
            bodies.join(", ")
        )
    }
}
