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
//! The model says which equations run ([`MotionPath`]): translation only where a symmetry kept
//! by the motion holds every torque at zero, translation and rotation otherwise.
//!
//! Per sample the run records the total energy $E = T + V$ (spins included) and
//! $J = |\mathbf J|$ (orbital and spin angular momentum; one energy
//! evaluation per sample, never per stage) and feeds the changes between consecutive samples,
//! $\Delta E_k = E_k - E\_{k-1}$ and $\Delta J_k = J_k - J\_{k-1}$, to the statistics of
//! [`surfgrav_dynamics::diagnostics`] (the paper's Table 2). The relative orbit goes to
//! [`OrbitAnalyser`] (apsides, periods, precession, minimum separation).

use std::time::Instant;

use surfgrav_dynamics::{
    angular_momentum, total_energy, ConservationStatistics, DynamicsError, EngineModelError,
    InteractionModel, MotionPath, OrbitAnalyser, OrbitReport, PointMasses, RunSummary, Sample,
    SceneModel, SceneSettings, SeriesAccumulator, SpinOrbitAnalyser, SpinOrbitReport, Termination,
    TwoBodyState,
};
use surfgrav_interaction::{InteractionError as EngineError, InteractionOptions};
use surfgrav_potentials::{Real, Vec3};

use crate::output::{Cadence, OutputError, OutputPlan};
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
    /// Which equations the run integrates (translation only, or with rotation), and why.
    pub path: MotionPath,
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
    if let (BuiltBody::Point(a), BuiltBody::Point(b)) = (&scene.body_a, &scene.body_b) {
        use surfgrav_potentials::Potential;
        let model = PointMasses::new(a.mass(), b.mass(), scene.gravitational_constant)
            .ok_or_else(|| RunError::Input("point masses must be positive and finite".into()))?;
        let path = model.motion_path(&scene.initial);
        return Ok(PreparedModel {
            model: Box::new(model),
            method: "point masses (exact)",
            build_seconds: start.elapsed().as_secs_f64(),
            path,
        });
    }
    let body = |b: &BuiltBody, name: &str| {
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
        body(&scene.body_a, "body_a")?,
        body(&scene.body_b, "body_b")?,
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
    let path = model.motion_path(&scene.initial);
    Ok(PreparedModel {
        model: Box::new(model),
        method,
        build_seconds: start.elapsed().as_secs_f64(),
        path,
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
    /// $\mathbf J$ about the origin, orbital and spin.
    pub angular_momentum_vector: Vec3,
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
    /// $|\mathbf J - \mathbf J_0|/|\mathbf J_0|$ at each sample (every step): the error of the
    /// angular-momentum vector.
    pub angular_momentum_errors: Vec<Real>,
    /// Largest $|\mathbf J - \mathbf J_0|/|\mathbf J_0|$.
    pub angular_momentum_vector_drift: Real,
    /// Largest $|\mathbf P - \mathbf P_0|/(m_A|\dot{\mathbf R}\_A| + m_B|\dot{\mathbf R}\_B|)\_0$ of the
    /// linear momentum $\mathbf P = m_A\dot{\mathbf R}\_A + m_B\dot{\mathbf R}\_B$.
    pub linear_momentum_drift: Real,
    /// Which equations were integrated, and why.
    pub path: MotionPath,
    /// Spin rates, obliquities, libration, osculating elements (every step).
    pub spin_orbit: SpinOrbitReport,
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
    momenta: Option<MomentumTracker>,
    spin_orbit: Option<SpinOrbitAnalyser>,
    mu: Real,
}

/// The vectors $\mathbf J$ and $\mathbf P$ against their initial values.
struct MomentumTracker {
    j0: Vec3,
    p0: Vec3,
    p_scale: Real,
    errors: Vec<Real>,
    j_drift: Real,
    p_drift: Real,
}

fn linear_momentum(model: &dyn InteractionModel, state: &TwoBodyState) -> Vec3 {
    state.body_a.velocity * model.mass_a() + state.body_b.velocity * model.mass_b()
}

impl StepRecorder {
    /// Records one sample; returns its energy and $|\mathbf J|$.
    fn observe(&mut self, model: &dyn InteractionModel, sample: &Sample) -> (Real, Real, Vec3) {
        let (e, j_vector) =
            energy_and_momentum(model, &sample.state, sample.time, &mut self.energy_error);
        let j = j_vector.norm();
        let p = linear_momentum(model, &sample.state);
        let momenta = self.momenta.get_or_insert_with(|| MomentumTracker {
            j0: j_vector,
            p0: p,
            p_scale: model.mass_a() * sample.state.body_a.velocity.norm()
                + model.mass_b() * sample.state.body_b.velocity.norm(),
            errors: Vec::new(),
            j_drift: 0.0,
            p_drift: 0.0,
        });
        let j_error = (j_vector - momenta.j0).norm() / momenta.j0.norm();
        let j_error = if j_error.is_finite() { j_error } else { 0.0 };
        momenta.errors.push(j_error);
        momenta.j_drift = momenta.j_drift.max(j_error);
        if momenta.p_scale > 0.0 {
            momenta.p_drift = momenta
                .p_drift
                .max((p - momenta.p0).norm() / momenta.p_scale);
        }
        let mu = self.mu;
        self.spin_orbit
            .get_or_insert_with(|| {
                SpinOrbitAnalyser::new([model.inertia_a(), model.inertia_b()], mu, j_vector)
            })
            .observe(sample);
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
        (e, j, j_vector)
    }
}

fn energy_and_momentum(
    model: &dyn InteractionModel,
    state: &TwoBodyState,
    time: Real,
    error: &mut Option<String>,
) -> (Real, Vec3) {
    let e = match total_energy(model, state) {
        Ok(e) => e,
        Err(err) => {
            if error.is_none() {
                *error = Some(format!("at t = {time}: energy: {err}"));
            }
            Real::NAN
        }
    };
    (e, angular_momentum(model, state))
}

/// The written rows: handed to the sink as they come, kept thinned for figures.
struct RowRecorder<'s> {
    sink: &'s mut dyn FnMut(&OutputRow) -> Result<(), OutputError>,
    written: usize,
    last_time: Option<Real>,
    kept: Vec<OutputRow>,
    stride: usize,
    last_kept: Option<OutputRow>,
    error: Option<OutputError>,
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
/// integrators refuse at the start; [`RunError::Failed`] for an integrator or model failure during the run
/// (with its time), and for the sink's first error.
pub fn simulate(
    scene: &Scene,
    prepared: &PreparedModel,
    progress: &mut dyn FnMut(Real),
    sink: &mut dyn FnMut(&OutputRow) -> Result<(), OutputError>,
) -> Result<RunRecord, RunError> {
    let start = Instant::now();
    let model = prepared.model();
    let plan = OutputPlan::of(scene);
    let mut integrator = scene
        .integrator
        .make()
        .map_err(|e| RunError::Input(e.to_string()))?;
    integrator
        .set_escape_distance(scene.escape_distance)
        .map_err(|e| RunError::Input(e.to_string()))?;
    let mut steps = StepRecorder {
        trackers: None,
        orbit: OrbitAnalyser::new(),
        times: Vec::new(),
        energies: Vec::new(),
        angular_momenta: Vec::new(),
        first: None,
        closest: None,
        energy_error: None,
        momenta: None,
        spin_orbit: None,
        mu: scene.gravitational_constant * (model.mass_a() + model.mass_b()),
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
                    let (energy, angular_momentum, angular_momentum_vector) =
                        steps.observe(model, sample);
                    if index.is_multiple_of(every) {
                        rows.push(OutputRow {
                            time: sample.time,
                            state: sample.state,
                            energy,
                            angular_momentum,
                            angular_momentum_vector,
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
                let (energy, angular_momentum_vector) =
                    energy_and_momentum(model, state, time, &mut row_energy_error);
                rows.push(OutputRow {
                    time,
                    state: *state,
                    energy,
                    angular_momentum: angular_momentum_vector.norm(),
                    angular_momentum_vector,
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
        let energy = steps.energies.last().copied().unwrap_or(Real::NAN);
        let angular_momentum_vector = angular_momentum(model, &summary.last.state);
        rows.push(OutputRow {
            time: summary.last.time,
            state: summary.last.state,
            energy,
            angular_momentum: angular_momentum_vector.norm(),
            angular_momentum_vector,
        });
    }
    if let Some(e) = rows.error.take() {
        return Err(RunError::Failed(e.to_string()));
    }
    let (te, tj) = steps
        .trackers
        .ok_or_else(|| RunError::Failed("the run produced no sample".into()))?;
    let (first, closest) = match (steps.first, steps.closest) {
        (Some(f), Some(c)) => (f, c),
        _ => return Err(RunError::Failed("the run produced no sample".into())),
    };
    let (kept, row_stride, rows_written) = rows.into_rows();
    let momenta = steps
        .momenta
        .ok_or_else(|| RunError::Failed("the run produced no sample".into()))?;
    let spin_orbit = steps
        .spin_orbit
        .map(|a| a.report())
        .ok_or_else(|| RunError::Failed("the run produced no sample".into()))?;
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
        angular_momentum_errors: momenta.errors,
        angular_momentum_vector_drift: momenta.j_drift,
        linear_momentum_drift: momenta.p_drift,
        path: prepared.path,
        spin_orbit,
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
