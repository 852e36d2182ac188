//! Running a [`Scene`] in memory: the interaction model, the integration and every diagnostic,
//! with all samples kept for output and figures.
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
    SceneSettings, SeriesAccumulator, Termination,
};
use surfgrav_potentials::Real;
use surfgrav_surfaces::interaction::{InteractionError as EngineError, InteractionOptions};

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

/// A finished run: every sample, the per-sample energy and angular momentum, and the
/// diagnostics.
#[derive(Debug, Clone)]
pub struct RunRecord {
    /// The scene that ran (after overrides).
    pub scene: Scene,
    /// How forces were computed.
    pub method: &'static str,
    /// Every sample: the start, then the end of every accepted step (and the contact sample).
    pub samples: Vec<Sample>,
    /// Total energy $E$ at each sample.
    pub energies: Vec<Real>,
    /// $|\mathbf J|$ at each sample.
    pub angular_momenta: Vec<Real>,
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
            Termination::Completed => None,
            Termination::Contact(event) => Some(event.sample.time),
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

/// Integrates `scene` with `prepared`, calling `progress(time)` after every sample.
///
/// # Errors
/// [`RunError::Input`] for an integrator the build cannot provide and for scenes the
/// integrators refuse at the start (torques that do not vanish: rotational dynamics is not
/// integrated yet); [`RunError::Failed`] for an integrator or model failure during the run
/// (with its time).
pub fn simulate(
    scene: &Scene,
    prepared: &PreparedModel,
    progress: &mut dyn FnMut(Real),
) -> Result<RunRecord, RunError> {
    let start = Instant::now();
    let model = prepared.model();
    let mut integrator = scene.integrator.make().map_err(RunError::Input)?;
    let mut samples = Vec::new();
    let mut energies = Vec::new();
    let mut angular_momenta = Vec::new();
    let mut trackers: Option<(Tracker, Tracker)> = None;
    let mut orbit = OrbitAnalyser::new();
    let mut energy_error: Option<String> = None;
    let summary = integrator
        .integrate(
            model,
            &scene.initial,
            scene.t_start,
            scene.t_end,
            &mut |sample| {
                let e = match total_energy(model, &sample.state) {
                    Ok(e) => e,
                    Err(err) => {
                        if energy_error.is_none() {
                            energy_error = Some(format!("at t = {}: energy: {err}", sample.time));
                        }
                        Real::NAN
                    }
                };
                let j = angular_momentum(model, &sample.state).norm();
                match &mut trackers {
                    None => trackers = Some((Tracker::new(e), Tracker::new(j))),
                    Some((te, tj)) => {
                        te.push(sample.time, e);
                        tj.push(sample.time, j);
                    }
                }
                orbit.observe(sample);
                samples.push(*sample);
                energies.push(e);
                angular_momenta.push(j);
                progress(sample.time);
            },
        )
        .map_err(|e| match e {
            // Refused at the start: the scene, not the run, must change.
            DynamicsError::TorquesNotSupported { .. } | DynamicsError::InvalidParameter { .. } => {
                RunError::Input(e.to_string())
            }
            other => RunError::Failed(other.to_string()),
        })?;
    if let Some(message) = energy_error {
        return Err(RunError::Failed(message));
    }
    let (te, tj) = trackers.ok_or_else(|| RunError::Failed("the run produced no sample".into()))?;
    Ok(RunRecord {
        scene: scene.clone(),
        method: prepared.method,
        samples,
        energies,
        angular_momenta,
        summary,
        energy: te.statistics(),
        angular_momentum: tj.statistics(),
        orbit: orbit.report(),
        wall_seconds: prepared.build_seconds + start.elapsed().as_secs_f64(),
    })
}

/// [`prepare`] then [`simulate`], without progress.
///
/// # Errors
/// As [`prepare`] and [`simulate`].
pub fn run_scene(scene: &Scene) -> Result<RunRecord, RunError> {
    let prepared = prepare(scene)?;
    simulate(scene, &prepared, &mut |_| {})
}
