//! Running a [`Scene`]: the interaction model, the integration and every diagnostic. The
//! trajectory's rows go to a sink as they are made (`surfgrav run` streams them into
//! `trajectory.csv`); the record keeps the per-step energy and angular momentum and a bounded,
//! evenly thinned copy of the rows for figures, so memory does not grow with the state history.
//!
//! The model is chosen once, before anything is written:
//! - two point masses: the exact $V = -G m_A m_B / r$ ([`PointMasses`]);
//! - otherwise [`SceneModel`]: the tabulated $V(r)$ when the pair is central and the scene asks
//!   for it (`interaction.tabulate`, default on), the direct surface integral at every force
//!   evaluation otherwise. Building it evaluates the interaction at the start, so bodies that
//!   overlap there are refused before any output exists.
//!
//! Per sample the run records the total energy $E = T + V$ and $J = |\mathbf J|$ (one energy
//! evaluation per sample, never per stage) and feeds the changes between consecutive samples,
//! $\Delta E_k = E_k - E_{k-1}$ and $\Delta J_k = J_k - J_{k-1}$, to the statistics of
//! [`surfgrav_dynamics::diagnostics`] (the paper's Table 2). The relative orbit goes to
//! [`OrbitAnalyser`] (apsides, periods, precession, minimum separation).

use std::time::Instant;

use surfgrav_dynamics::{
    angular_momentum, total_energy, ConservationStatistics, DynamicsError, EngineModelError,
    InteractionModel, OrbitAnalyser, OrbitReport, PointMasses, RunSummary, Sample, SceneModel,
    SceneSettings, SeriesAccumulator, Termination, TwoBodyState,
};
use surfgrav_potentials::Real;
use surfgrav_surfaces::interaction::{InteractionError as EngineError, InteractionOptions};

use crate::output::{Cadence, OutputPlan};
use crate::scene::Scene;
use crate::spec::BuiltBody;

/// Why a scene could not be run.
#[derive(Debug, Clone, PartialEq)]
pub enum RunError {
    /// The scene cannot start (bodies overlap, an invalid combination): the user must change it.
    Input(String),
    /// The run started and failed (an integrator or model failure).
    Failed(String),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::Input(m) | RunError::Failed(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for RunError {}

/// The interaction model of a scene, built and checked at the start.
pub struct PreparedModel {
    model: Box<dyn InteractionModel>,
    /// How forces are computed: `point masses (exact)`, `tabulated V(r)` or
    /// `direct surface integral`.
    pub method: &'static str,
    /// Seconds spent building the model (tables included).
    pub build_seconds: Real,
}

impl PreparedModel {
    /// The model.
    pub fn model(&self) -> &dyn InteractionModel {
        self.model.as_ref()
    }
}

/// Builds the model of `scene`; fails when the bodies overlap or touch at the start.
///
/// # Errors
/// [`RunError::Input`] for overlap and for scenes the engine refuses; [`RunError::Failed`] when
/// a table cannot be built.
pub fn prepare(scene: &Scene) -> Result<PreparedModel, RunError> {
    let start = Instant::now();
    if let (BuiltBody::Point(a), BuiltBody::Point(b)) = (scene.body_a, scene.body_b) {
        use surfgrav_potentials::Potential;
        let model = PointMasses::new(a.mass(), b.mass(), scene.gravitational_constant)
            .ok_or_else(|| RunError::Input("point masses must be positive and finite".into()))?;
        return Ok(PreparedModel {
            model: Box::new(model),
            method: "point masses (exact)",
            build_seconds: start.elapsed().as_secs_f64(),
        });
    }
    let body = |b: BuiltBody, name: &str| {
        b.into_interaction_body()
            .map_err(|e| RunError::Input(format!("{name}: {e}")))
    };
    let settings = SceneSettings {
        engine: InteractionOptions {
            relative_tolerance: scene.interaction_tolerance,
            ..InteractionOptions::default()
        },
        interpolate: scene.tabulate,
        ..SceneSettings::default()
    };
    let model = SceneModel::build(
        body(scene.body_a, "body_a")?,
        body(scene.body_b, "body_b")?,
        &scene.initial,
        &settings,
    )
    .map_err(|e| match e {
        EngineModelError::Engine(
            EngineError::Overlap { separation } | EngineError::Touching { separation },
        ) => RunError::Input(format!(
            "the bodies overlap or touch at the start (centroid separation {separation}): move them apart"
        )),
        EngineModelError::Engine(e) => RunError::Input(format!("the scene cannot start: {e}")),
        EngineModelError::InvalidMass { .. } | EngineModelError::InvalidSetting { .. } => {
            RunError::Input(e.to_string())
        }
        other => RunError::Failed(other.to_string()),
    })?;
    let method = if model.is_interpolated() {
        "tabulated V(r)"
    } else {
        "direct surface integral"
    };
    Ok(PreparedModel {
        model: Box::new(model),
        method,
        build_seconds: start.elapsed().as_secs_f64(),
    })
}

/// One row of `trajectory.csv`: a state at a written time with its energy and $|\mathbf J|$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputRow {
    /// Time.
    pub time: Real,
    /// Both bodies' state.
    pub state: TwoBodyState,
    /// Total energy $E = T + V$.
    pub energy: Real,
    /// $|\mathbf J|$ about the origin.
    pub angular_momentum: Real,
}

/// Most written rows a [`RunRecord`] keeps for figures: beyond it every other kept row is
/// dropped (the kept rows stay evenly spaced among the written ones), so a run's memory does
/// not grow with its length.
pub const KEPT_ROWS: usize = 16_384;

/// A finished run: the diagnostics of every step, the written rows (thinned for figures) and
/// the per-step energy and angular momentum.
#[derive(Debug, Clone)]
pub struct RunRecord {
    /// The scene that ran (after overrides).
    pub scene: Scene,
    /// How forces were computed.
    pub method: &'static str,
    /// The output cadence used and how it was chosen.
    pub output: OutputPlan,
    /// Rows written (or handed to the sink).
    pub rows_written: usize,
    /// The written rows, every `row_stride`-th of them (at most [`KEPT_ROWS`]), and the last.
    pub rows: Vec<OutputRow>,
    /// Which written rows `rows` holds: every `row_stride`-th.
    pub row_stride: usize,
    /// Time of every sample: the start, then the end of every accepted step (and the contact).
    pub step_times: Vec<Real>,
    /// Total energy $E$ at each sample (every step).
    pub energies: Vec<Real>,
    /// $|\mathbf J|$ at each sample (every step).
    pub angular_momenta: Vec<Real>,
    /// The first sample.
    pub first: Sample,
    /// The sample of smallest separation among the steps.
    pub closest: Sample,
    /// Steps, evaluations, termination.
    pub summary: RunSummary,
    /// Energy statistics.
    pub energy: ConservationStatistics,
    /// Angular-momentum statistics.
    pub angular_momentum: ConservationStatistics,
    /// Apsides, periods, precession, minimum separation.
    pub orbit: OrbitReport,
    /// Seconds from the start of model building to the end of the integration.
    pub wall_seconds: Real,
}

impl RunRecord {
    /// The end time reached (the scene's, or the contact time).
    pub fn t_reached(&self) -> Real {
        self.summary.last.time
    }

    /// Whether the bodies touched before the end.
    pub fn contact(&self) -> Option<Real> {
        match &self.summary.termination {
            Termination::Contact(event) => Some(event.sample.time),
            Termination::Completed | Termination::Escape(_) => None,
        }
    }

    /// Whether the bodies escaped each other (an unbound orbit past the escape distance).
    pub fn escape(&self) -> Option<Real> {
        match &self.summary.termination {
            Termination::Escape(event) => Some(event.sample.time),
            Termination::Completed | Termination::Contact(_) => None,
        }
    }
}

/// Per-series tracker: the accumulator of changes, the first value and the largest drift.
struct Tracker {
    changes: SeriesAccumulator,
    initial: Real,
    previous: Real,
    drift: Real,
}

impl Tracker {
    fn new(x: Real) -> Self {
        Self {
            changes: SeriesAccumulator::default(),
            initial: x,
            previous: x,
            drift: 0.0,
        }
    }
    fn push(&mut self, t: Real, x: Real) {
        self.changes.push(t, x - self.previous);
        let d = if self.initial != 0.0 {
            ((x - self.initial) / self.initial).abs()
        } else {
            (x - self.initial).abs()
        };
        self.drift = self.drift.max(d);
        self.previous = x;
    }
    fn statistics(&self) -> ConservationStatistics {
        ConservationStatistics {
            initial: self.initial,
            last: self.previous,
            step_changes: self.changes.statistics(),
            max_relative_drift: self.drift,
        }
    }
}

/// Everything measured at every step.
struct StepRecorder {
    trackers: Option<(Tracker, Tracker)>,
    orbit: OrbitAnalyser,
    times: Vec<Real>,
    energies: Vec<Real>,
    angular_momenta: Vec<Real>,
    first: Option<Sample>,
    closest: Option<Sample>,
    energy_error: Option<String>,
}

impl StepRecorder {
    /// Records one sample; returns its energy and $|\mathbf J|$.
    fn observe(&mut self, model: &dyn InteractionModel, sample: &Sample) -> (Real, Real) {
        let (e, j) = energy_and_momentum(model, &sample.state, sample.time, &mut self.energy_error);
        match &mut self.trackers {
            None => self.trackers = Some((Tracker::new(e), Tracker::new(j))),
            Some((te, tj)) => {
                te.push(sample.time, e);
                tj.push(sample.time, j);
            }
        }
        self.orbit.observe(sample);
        self.first.get_or_insert(*sample);
        if self
            .closest
            .is_none_or(|c| sample.state.separation() < c.state.separation())
        {
            self.closest = Some(*sample);
        }
        self.times.push(sample.time);
        self.energies.push(e);
        self.angular_momenta.push(j);
        (e, j)
    }
}

fn energy_and_momentum(
    model: &dyn InteractionModel,
    state: &TwoBodyState,
    time: Real,
    error: &mut Option<String>,
) -> (Real, Real) {
    let e = match total_energy(model, state) {
        Ok(e) => e,
        Err(err) => {
            if error.is_none() {
                *error = Some(format!("at t = {time}: energy: {err}"));
            }
            Real::NAN
        }
    };
    (e, angular_momentum(model, state).norm())
}

/// The written rows: handed to the sink as they come, kept thinned for figures.
struct RowRecorder<'s> {
    sink: &'s mut dyn FnMut(&OutputRow) -> Result<(), String>,
    written: usize,
    last_time: Option<Real>,
    kept: Vec<OutputRow>,
    stride: usize,
    last_kept: Option<OutputRow>,
    error: Option<String>,
}

impl RowRecorder<'_> {
    fn push(&mut self, row: OutputRow) {
        if self.error.is_some() {
            return;
        }
        if let Err(e) = (self.sink)(&row) {
            self.error = Some(e);
            return;
        }
        if self.written.is_multiple_of(self.stride) {
            if self.kept.len() == KEPT_ROWS {
                let mut k = 0;
                self.kept.retain(|_| {
                    k += 1;
                    k % 2 == 1
                });
                self.stride *= 2;
            }
            if self.written.is_multiple_of(self.stride) {
                self.kept.push(row);
            }
        }
        self.last_kept = Some(row);
        self.written += 1;
        self.last_time = Some(row.time);
    }

    /// The kept rows with the last written row at the end.
    fn into_rows(mut self) -> (Vec<OutputRow>, usize, usize) {
        if let Some(last) = self.last_kept {
            if self.kept.last() != Some(&last) {
                self.kept.push(last);
            }
        }
        (self.kept, self.stride, self.written)
    }
}

/// Integrates `scene` with `prepared`, calling `progress(time)` after every step and `sink(row)`
/// for every row of `trajectory.csv`, in order, as the run goes (the rows follow
/// [`OutputPlan::of`]: every n-th step, or the dense output at $t_0 + k\Delta$; the last state
/// always). Diagnostics use every step whatever the output cadence.
///
/// # Errors
/// [`RunError::Input`] for an integrator the build cannot provide and for scenes the
/// integrators refuse at the start (torques that do not vanish: rotational dynamics is not
/// integrated yet); [`RunError::Failed`] for an integrator or model failure during the run
/// (with its time), and for the sink's first error.
pub fn simulate(
    scene: &Scene,
    prepared: &PreparedModel,
    progress: &mut dyn FnMut(Real),
    sink: &mut dyn FnMut(&OutputRow) -> Result<(), String>,
) -> Result<RunRecord, RunError> {
    let start = Instant::now();
    let model = prepared.model();
    let plan = OutputPlan::of(scene);
    let mut integrator = scene.integrator.make().map_err(RunError::Input)?;
    let mut steps = StepRecorder {
        trackers: None,
        orbit: OrbitAnalyser::new(),
        times: Vec::new(),
        energies: Vec::new(),
        angular_momenta: Vec::new(),
        first: None,
        closest: None,
        energy_error: None,
    };
    let mut rows = RowRecorder {
        sink,
        written: 0,
        last_time: None,
        kept: Vec::new(),
        stride: 1,
        last_kept: None,
        error: None,
    };
    let mut row_energy_error = None;
    let result = match plan.cadence {
        Cadence::Every(every) => {
            let mut index = 0usize;
            integrator.integrate(
                model,
                &scene.initial,
                scene.t_start,
                scene.t_end,
                &mut |sample| {
                    let (energy, angular_momentum) = steps.observe(model, sample);
                    if index.is_multiple_of(every) {
                        rows.push(OutputRow {
                            time: sample.time,
                            state: sample.state,
                            energy,
                            angular_momentum,
                        });
                    }
                    index += 1;
                    progress(sample.time);
                },
            )
        }
        Cadence::Interval(interval) => integrator.integrate_with_output(
            model,
            &scene.initial,
            scene.t_start,
            scene.t_end,
            interval,
            &mut |sample| {
                steps.observe(model, sample);
                progress(sample.time);
            },
            &mut |time, state| {
                let (energy, angular_momentum) =
                    energy_and_momentum(model, state, time, &mut row_energy_error);
                rows.push(OutputRow {
                    time,
                    state: *state,
                    energy,
                    angular_momentum,
                });
            },
        ),
    };
    let summary = result.map_err(|e| match e {
        // Refused at the start: the scene, not the run, must change.
        DynamicsError::TorquesNotSupported { .. } | DynamicsError::InvalidParameter { .. } => {
            RunError::Input(e.to_string())
        }
        other => RunError::Failed(other.to_string()),
    })?;
    if let Some(message) = steps.energy_error.or(row_energy_error) {
        return Err(RunError::Failed(message));
    }
    // The last state is always written (the end time, or the contact).
    if rows.last_time.is_none_or(|t| t < summary.last.time) {
        let (energy, angular_momentum) = match (steps.energies.last(), steps.angular_momenta.last())
        {
            (Some(&e), Some(&j)) => (e, j),
            _ => (Real::NAN, Real::NAN),
        };
        rows.push(OutputRow {
            time: summary.last.time,
            state: summary.last.state,
            energy,
            angular_momentum,
        });
    }
    if let Some(message) = rows.error.take() {
        return Err(RunError::Failed(message));
    }
    let (te, tj) = steps
        .trackers
        .ok_or_else(|| RunError::Failed("the run produced no sample".into()))?;
    let (first, closest) = match (steps.first, steps.closest) {
        (Some(f), Some(c)) => (f, c),
        _ => return Err(RunError::Failed("the run produced no sample".into())),
    };
    let (kept, row_stride, rows_written) = rows.into_rows();
    Ok(RunRecord {
        scene: scene.clone(),
        method: prepared.method,
        output: plan,
        rows_written,
        rows: kept,
        row_stride,
        step_times: steps.times,
        energies: steps.energies,
        angular_momenta: steps.angular_momenta,
        first,
        closest,
        summary,
        energy: te.statistics(),
        angular_momentum: tj.statistics(),
        orbit: steps.orbit.report(),
        wall_seconds: prepared.build_seconds + start.elapsed().as_secs_f64(),
    })
}

/// [`prepare`] then [`simulate`], without progress.
///
/// # Errors
/// As [`prepare`] and [`simulate`].
pub fn run_scene(scene: &Scene) -> Result<RunRecord, RunError> {
    let prepared = prepare(scene)?;
    simulate(scene, &prepared, &mut |_| {}, &mut |_| Ok(()))
}
