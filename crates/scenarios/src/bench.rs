//! `surfgrav bench`: work–precision of the interaction engine and of the integrators, and the
//! measured speed-up over the founding paper's method.
//!
//! [`run_bench`] writes into an output folder:
//!
//! | file | what |
//! |---|---|
//! | `interaction.md`, `interaction.csv` | (a) the paper's pair (oblate spheroids a = 1, c = 0.25, m = 1, G = 1, common equatorial plane, B on A's x axis) at separations 2.1, 2.55, 3, 7, 30: for every rule and parametrisation of the engine (single tables of the ladder and the certified ladder in the azimuth–height (AH, the paper's (φ, z)) and polar–azimuth (PA) forms, the nested doubling rule (AH), the adaptive G7K15 cubature (PA)), evaluations, time per interaction (force, torques, energy) and per force-only evaluation, relative errors of the force and of the energy |
//! | `interaction_force.png/.svg`, `interaction_energy.png/.svg` | the same, error against time per evaluation (force-only time for the force, whole interaction for the energy), log–log, one panel per separation, with the paper's method as one point |
//! | `dynamics.md`, `dynamics.csv` | (b) paper-2s and (c) paper-2d over t = 0 … 300, and (d) `kw4-ellipsoids` (1999 KW4 as two rotating triaxial ellipsoids) over the preset's 10 mutual orbits (a quarter orbit in quick mode): for every integrator over a range of steps or tolerances, steps, force evaluations, wall time, energy error, trajectory error and, for (d), attitude error |
//! | `paper_2s.png/.svg`, `paper_2d.png/.svg`, `kw4_ellipsoids.png/.svg` | energy error, trajectory error (and for (d) attitude error) against wall time, log–log |
//! | `speedup.md`, `speedup.csv` | time of the paper's method (scipy `dblquad` + RK4, `tools/paper_baseline/`) over surfgrav's for the same task |
//!
//! # Errors, and against what
//!
//! * Interaction (a): the relative error of the force is $\lVert F - F\_\mathrm{ref}\rVert /
//!   \lVert F\_\mathrm{ref}\rVert$ and of the energy $|U - U\_\mathrm{ref}| / |U\_\mathrm{ref}|$,
//!   against `tests/reference/interactions.json`: an independent volume integration (by
//!   `tests/reference/interactions.py`) with an estimated relative accuracy of about
//!   $2\times10^{-16}$. Not against the engine itself.
//! * Dynamics (b, c, d): the energy error is $\max_k |E_k - E_0| / |E_0|$ over every accepted
//!   step (the total energy with the same model the run used), the trajectory error is
//!   $\lVert \mathbf r(t\_\mathrm{end}) - \mathbf r\_\mathrm{ref}(t\_\mathrm{end}) \rVert$ for the
//!   relative position $\mathbf r = \mathbf R_B - \mathbf R_A$ (length units), against a DOP853
//!   run at relative and absolute tolerance $10^{-14}$ with the same model (so it measures the
//!   integrator; the model's own error is (a)'s). How far a run at $10^{-13}$ ends from it is
//!   reported (measured: $1.0\times10^{-9}$ on paper-2s, $1.2\times10^{-9}$ on paper-2d):
//!   trajectory errors near $10^{-10}$ are the reference's limit, not the run's. For (d) the
//!   energy includes the spins' kinetic energy, the trajectory error is in metres, and the
//!   attitude error is the larger of the two bodies' rotation angles from the reference's
//!   final attitudes (rad).
//! * Errors below [`ERROR_FLOOR`] = $10^{-17}$ are reported as $10^{-17}$: below the
//!   references' own accuracy they carry no information, and a log axis needs a positive value.
//!
//! # Models of the runs
//!
//! paper-2s runs with the tabulated central pair (`SceneModel`, the fast path: $V(r)$
//! tabulated once from the engine, forces from its exact derivative; the table's build time is
//! reported and counted in the speed-up) for every integrator, and with the direct surface
//! integral at every force evaluation (`EngineModel`, engine tolerance $10^{-12}$) for the
//! paper's own setting (RK4, Δt = 0.1) and a few adaptive runs. paper-2d runs with the direct
//! model, which for two coplanar disks is Conway's closed form. `kw4-ellipsoids` runs the
//! preset's own model (the direct surface integral at every force and torque evaluation, at
//! the preset's engine tolerance, translation and rotation); its fixed steps are swept around
//! 100 per mutual orbit as paper-2s's are around Δt = 0.1.
//!
//! # Times
//!
//! Wall-clock, one thread. A time per interaction is the best of several batches (each at
//! least [`BenchOptions::min_batch_seconds`]) of repeated calls with the body tables already
//! built (a run reuses them). A run shorter than 0.2 s is repeated and its best time kept. The
//! machine is shared: expect ±30 %. A debug build is detected (a 130-node interaction slower
//! than 60 µs with debug assertions on) and reported in [`BenchReport::warnings`].
//!
//! # The baseline
//!
//! `tools/paper_baseline/baseline.json` (compiled in) holds the paper's method timed on this
//! kind of machine: seconds per force evaluation at each separation, per RK4 step of a
//! shortened paper-2s run (t = 0 … 3), and a measured whole paper-2s run. With
//! [`BenchOptions::rerun_baseline`], and when `python3` with scipy is found, the script is run
//! again in the same sitting (`--quick --json` in quick mode, `--json --no-full-run` otherwise,
//! so the whole-run figure stays the committed one); otherwise the committed JSON is used and
//! the report says so.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use serde_json::Value;
use surfgrav_dynamics::{
    BodyState, ConservationMonitor, EngineModel, IntegratorKind, InteractionModel, Sample,
    SceneModel, SceneSettings, Termination, TwoBodyState,
};
use surfgrav_interaction::{
    Body, Interaction, InteractionEngine, InteractionError, InteractionOptions, MethodChoice,
    Parametrisation,
};
use surfgrav_potentials::{Pose, Spheroid, UniformDisk, Vec3};

use crate::plot::{write_figure, Figure, LinePanel, Panel, PlotError, Series, Style};

/// Errors below this are reported as this (see the module docs).
pub const ERROR_FLOOR: f64 = 1e-17;

/// The separations of (a), in units of the equatorial radius.
pub const SEPARATIONS: [f64; 5] = [2.1, 2.55, 3.0, 7.0, 30.0];

/// End time of the paper's runs.
pub const PAPER_T_END: f64 = 300.0;

/// Tolerance of the reference runs of (b), (c) and (d).
pub const REFERENCE_TOLERANCE: f64 = 1e-14;

/// The preset of part (d): 1999 KW4 as two triaxial ellipsoids, rotating.
pub const KW4_SCENE: &str = "kw4-ellipsoids";

/// Length of part (d)'s runs in quick mode, in mutual orbits (the full bench runs the preset's
/// 10 orbits).
pub const QUICK_KW4_ORBITS: f64 = 0.25;

/// Runs shorter than 0.2 s are timed this many more times (best kept).
const REPEATS_OF_SHORT_RUNS: usize = 3;

const REFERENCE_JSON: &str = include_str!("../../../tests/reference/interactions.json");
const BASELINE_JSON: &str = include_str!("../../../tools/paper_baseline/baseline.json");
const BASELINE_SCRIPT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../tools/paper_baseline/paper_method.py"
);

/// What to run.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchOptions {
    /// Output folder (created if missing).
    pub out: PathBuf,
    /// Small sweeps and short timing batches: every file is written, in seconds.
    pub quick: bool,
    /// Run the baseline script again (needs `python3` with scipy); otherwise, or when it
    /// cannot run, the committed `baseline.json` is used.
    pub rerun_baseline: bool,
    /// Python interpreter for the baseline (default `python3`).
    pub python: String,
    /// Least duration of one timing batch in seconds (default 0.02; quick 0.002).
    pub min_batch_seconds: f64,
}

impl BenchOptions {
    /// Defaults for an output folder: full sweeps, committed baseline.
    pub fn new(out: impl Into<PathBuf>) -> Self {
        Self {
            out: out.into(),
            quick: false,
            rerun_baseline: false,
            python: "python3".into(),
            min_batch_seconds: 0.02,
        }
    }

    /// Quick mode (small sweeps, 2 ms batches).
    pub fn quick(mut self) -> Self {
        self.quick = true;
        self.min_batch_seconds = 0.002;
        self
    }
}

/// Why the bench stopped.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BenchError {
    /// Writing an output file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A figure could not be drawn.
    #[error(transparent)]
    Plot(#[from] PlotError),
    /// The engine failed where a result was required.
    #[error("interaction engine, {context}: {message}")]
    Engine {
        /// What was being computed.
        context: String,
        /// The engine's message.
        message: String,
    },
    /// A run or a model failed where a result was required.
    #[error("dynamics, {context}: {message}")]
    Dynamics {
        /// What was being computed.
        context: String,
        /// The message.
        message: String,
    },
    /// The compiled-in reference or baseline data lack something.
    #[error("data: {0}")]
    Data(String),
}

/// One rule at one setting at one separation (part a).
#[derive(Debug, Clone, PartialEq)]
pub struct InteractionRow {
    /// Centroid separation.
    pub separation: f64,
    /// Rule family, e.g. "AH single table" (AH: azimuth–height, the paper's (φ, z); PA:
    /// polar angle–azimuth).
    pub family: String,
    /// Its setting, e.g. "t = 8" or "tol 1e-9".
    pub setting: String,
    /// Potential evaluations per interaction.
    pub evaluations: usize,
    /// Seconds per interaction (force, torques and energy).
    pub seconds: f64,
    /// Seconds per force-only evaluation (`InteractionEngine::force`: the rules sum and
    /// certify the force alone), the task of the paper's method.
    pub force_only_seconds: f64,
    /// Relative force error of the force-only evaluation (floored).
    pub force_only_error: f64,
    /// Relative force error against the reference (floored at [`ERROR_FLOOR`]).
    pub force_error: f64,
    /// Relative energy error against the reference (floored).
    pub energy_error: f64,
    /// The engine's own relative error estimate (∞ for single tables).
    pub error_estimate: f64,
    /// False when the engine reported that the tolerance was not met (its best result is used).
    pub converged: bool,
}

/// One integrator at one setting on one scene (parts b, c).
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsRow {
    /// `paper-2s`, `paper-2d` or `kw4-ellipsoids`.
    pub scene: String,
    /// Model: "interpolant", "direct engine" or "closed form (disks)".
    pub model: String,
    /// Integrator name (`rk4`, …).
    pub integrator: String,
    /// "dt = 0.1" or "tol 1e-10".
    pub setting: String,
    /// End time of the run.
    pub t_end: f64,
    /// Accepted steps.
    pub steps: usize,
    /// Force evaluations.
    pub force_evaluations: usize,
    /// Wall time of the integration (seconds), without the diagnostics.
    pub wall_seconds: f64,
    /// max |E − E0| / |E0| (floored), `None` if the run did not complete.
    pub energy_error: Option<f64>,
    /// |r(t_end) − r_ref(t_end)| (floored), `None` without a reference or a complete run.
    pub trajectory_error: Option<f64>,
    /// For rotating bodies, the larger of the two bodies' rotation angles (rad) between the
    /// final attitudes and the reference's (floored); `None` for the paper's planar scenes,
    /// without a reference or a complete run.
    pub attitude_error: Option<f64>,
    /// "completed" or what stopped it.
    pub termination: String,
}

/// One measured speed-up.
#[derive(Debug, Clone, PartialEq)]
pub struct Speedup {
    /// The task.
    pub task: String,
    /// The paper's method's seconds.
    pub baseline_seconds: f64,
    /// surfgrav's seconds.
    pub surfgrav_seconds: f64,
    /// baseline / surfgrav.
    pub ratio: f64,
    /// Accuracy of each and where the numbers come from.
    pub note: String,
}

/// What the bench measured and wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchReport {
    /// Part (a).
    pub interaction: Vec<InteractionRow>,
    /// Parts (b) and (c).
    pub dynamics: Vec<DynamicsRow>,
    /// Speed-ups over the paper's method.
    pub speedups: Vec<Speedup>,
    /// Where the baseline figures come from (committed file and its date, or this sitting).
    pub baseline_source: String,
    /// What makes the figures less trustworthy (a debug build).
    pub warnings: Vec<String>,
    /// Every file written.
    pub files: Vec<PathBuf>,
}

/// Runs the bench and writes its files into `options.out`. `progress` receives one line per
/// step of the work (for a terminal or a log).
pub fn run_bench(
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<BenchReport, BenchError> {
    std::fs::create_dir_all(&options.out).map_err(|source| BenchError::Io {
        path: options.out.clone(),
        source,
    })?;
    let (baseline, baseline_source) = load_baseline(options, progress)?;
    progress(&format!("baseline: {baseline_source}"));

    let interaction = interaction_bench(options, progress)?;
    let warnings = build_warnings(&interaction);
    for w in &warnings {
        progress(&format!("warning: {w}"));
    }
    let mut dynamics = Vec::new();
    // The direct engine's short run covers the baseline's shortened run (same steps).
    let short_t_end = baseline.rk4_step.map_or(3.0, |(_, t)| t);
    let two_s = paper_2s(options, short_t_end, progress)?;
    dynamics.extend(two_s.rows);
    let two_d = paper_2d(options, progress)?;
    dynamics.extend(two_d.rows);
    let kw4 = kw4_ellipsoids(options, progress)?;
    dynamics.extend(kw4.rows.iter().cloned());

    let speedups = speedups(
        &baseline,
        &interaction,
        &dynamics,
        two_s.table_seconds,
        two_s.reference_final,
    );
    for s in &speedups {
        progress(&format!(
            "speed-up {}: {:.3e} s / {:.3e} s = {:.0}x ({})",
            s.task, s.baseline_seconds, s.surfgrav_seconds, s.ratio, s.note
        ));
    }

    let mut files = Vec::new();
    let out = &options.out;
    files.push(write_text(
        &out.join("interaction.md"),
        &interaction_markdown(&interaction, &baseline),
    )?);
    files.push(write_text(
        &out.join("interaction.csv"),
        &interaction_csv(&interaction),
    )?);
    files.push(write_text(
        &out.join("dynamics.md"),
        &dynamics_markdown(
            &dynamics,
            two_s.table_seconds,
            [
                two_s.reference_spread,
                two_d.reference_spread,
                kw4.reference_spread,
            ],
            &kw4,
        ),
    )?);
    files.push(write_text(
        &out.join("dynamics.csv"),
        &dynamics_csv(&dynamics),
    )?);
    files.push(write_text(
        &out.join("speedup.md"),
        &speedup_markdown(&speedups, &baseline_source, &warnings),
    )?);
    files.push(write_text(
        &out.join("speedup.csv"),
        &speedup_csv(&speedups),
    )?);
    for (stem, figure) in [
        (
            "interaction_force",
            interaction_figure(&interaction, &baseline, true),
        ),
        (
            "interaction_energy",
            interaction_figure(&interaction, &baseline, false),
        ),
        (
            "paper_2s",
            dynamics_figure(
                &dynamics,
                "paper-2s",
                PAPER_T_END,
                baseline_run_point(&baseline, two_s.reference_final),
            ),
        ),
        (
            "paper_2d",
            dynamics_figure(&dynamics, "paper-2d", PAPER_T_END, None),
        ),
        (
            "kw4_ellipsoids",
            dynamics_figure(&dynamics, KW4_SCENE, kw4.t_end, None),
        ),
    ] {
        files.extend(write_figure(&figure, &out.join(stem))?);
    }
    for f in &files {
        progress(&format!("wrote {}", f.display()));
    }
    Ok(BenchReport {
        interaction,
        dynamics,
        speedups,
        baseline_source,
        warnings,
        files,
    })
}

/// A short text for a terminal: where the baseline came from, the speed-ups, the files.
pub fn summary(report: &BenchReport) -> String {
    let mut s = String::new();
    for w in &report.warnings {
        let _ = writeln!(s, "Warning: {w}.");
    }
    let _ = writeln!(s, "Baseline: {}.", report.baseline_source);
    let _ = writeln!(
        s,
        "Speed-up over the paper's method (its seconds / surfgrav's):"
    );
    for r in &report.speedups {
        let _ = writeln!(
            s,
            "  {:>8.0}x  {} ({:.3e} s / {:.3e} s)",
            r.ratio, r.task, r.baseline_seconds, r.surfgrav_seconds
        );
    }
    let _ = writeln!(s, "Files:");
    for f in &report.files {
        let _ = writeln!(s, "  {}", f.display());
    }
    s
}

fn write_text(path: &Path, text: &str) -> Result<PathBuf, BenchError> {
    std::fs::write(path, text).map_err(|source| BenchError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(path.to_path_buf())
}

fn floored(e: f64) -> f64 {
    if e.is_finite() {
        e.max(ERROR_FLOOR)
    } else {
        e
    }
}

/// Best time per call in seconds: batches of at least `min_batch` seconds, best of `batches`.
fn time_per_call(min_batch: f64, batches: usize, mut f: impl FnMut()) -> f64 {
    let mut reps = 1usize;
    loop {
        let t = Instant::now();
        for _ in 0..reps {
            f();
        }
        let elapsed = t.elapsed().as_secs_f64();
        if elapsed >= min_batch || reps >= 1 << 24 {
            if batches <= 1 {
                return elapsed / reps as f64;
            }
            break;
        }
        reps *= 2;
    }
    (0..batches)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                f();
            }
            t.elapsed().as_secs_f64() / reps as f64
        })
        .fold(f64::INFINITY, f64::min)
}

// ---------------------------------------------------------------------------------------------
// (a) The interaction engine.

struct Reference {
    force: Vec3,
    energy: f64,
}

fn number(v: &Value) -> Option<f64> {
    match v {
        Value::String(s) => s.parse().ok(),
        Value::Number(n) => n.as_f64(),
        _ => None,
    }
}

fn vector(v: &Value) -> Option<Vec3> {
    let a = v.as_array()?;
    if a.len() != 3 {
        return None;
    }
    Some(Vec3::new(number(&a[0])?, number(&a[1])?, number(&a[2])?))
}

/// The reference for the paper's pair at separation `d` (B on A's x axis, no rotations).
fn paper_pair_reference(root: &Value, d: f64) -> Option<Reference> {
    let is_paper = |body: &Value| {
        body["kind"] == "spheroid"
            && number(&body["equatorial_radius"]) == Some(1.0)
            && number(&body["polar_radius"]) == Some(0.25)
            && number(&body["mass"]) == Some(1.0)
    };
    root["cases"].as_array()?.iter().find_map(|case| {
        let unrotated = vector(&case["rotation_a"])? == Vec3::zeros()
            && vector(&case["rotation_b"])? == Vec3::zeros();
        (is_paper(&case["a"])
            && is_paper(&case["b"])
            && number(&case["g"]) == Some(1.0)
            && vector(&case["position_b"])? == Vec3::new(d, 0.0, 0.0)
            && unrotated)
            .then(|| {
                Some(Reference {
                    force: vector(&case["force_on_a"])?,
                    energy: number(&case["potential_energy"])?,
                })
            })
            .flatten()
    })
}

/// The paper's body: oblate spheroid a = 1, c = 0.25, m = 1.
fn paper_spheroid() -> Result<Body, BenchError> {
    let s = Spheroid::new(1.0, 0.25, 1.0).map_err(|e| BenchError::Data(e.to_string()))?;
    Body::spheroid(s).map_err(|e| engine_error("paper spheroid", e))
}

fn paper_disk() -> Result<Body, BenchError> {
    let d = UniformDisk::new(1.0, 1.0).map_err(|e| BenchError::Data(e.to_string()))?;
    Body::disk(d).map_err(|e| engine_error("paper disk", e))
}

fn engine_error(context: &str, e: impl std::fmt::Display) -> BenchError {
    BenchError::Engine {
        context: context.to_string(),
        message: e.to_string(),
    }
}

/// Every rule and parametrisation the engine offers, at a few settings each.
fn rule_variants(quick: bool) -> Vec<(String, String, InteractionOptions)> {
    let mut out = Vec::new();
    let levels: &[u16] = if quick {
        &[4, 10]
    } else {
        &[2, 4, 6, 8, 10, 13, 16, 20]
    };
    let tolerances: &[f64] = if quick { &[1e-9] } else { &[1e-6, 1e-9, 1e-12] };
    for (name, parametrisation) in [
        ("AH", Parametrisation::AzimuthHeight),
        ("PA", Parametrisation::PolarAzimuth),
    ] {
        for &t in levels {
            out.push((
                format!("{name} single table"),
                format!("t = {t}"),
                InteractionOptions {
                    method: MethodChoice::FixedLevel(t),
                    parametrisation,
                    ..Default::default()
                },
            ));
        }
        for &tol in tolerances {
            out.push((
                format!("{name} ladder"),
                format!("tol {tol:.0e}"),
                InteractionOptions {
                    method: MethodChoice::FixedRules,
                    relative_tolerance: tol,
                    parametrisation,
                    ..Default::default()
                },
            ));
        }
    }
    for &tol in tolerances {
        out.push((
            "nested doubling (AH)".into(),
            format!("tol {tol:.0e}"),
            InteractionOptions {
                method: MethodChoice::Nested,
                relative_tolerance: tol,
                ..Default::default()
            },
        ));
    }
    for &tol in tolerances {
        out.push((
            "adaptive G7K15 (PA form)".into(),
            format!("tol {tol:.0e}"),
            InteractionOptions {
                method: MethodChoice::Adaptive,
                relative_tolerance: tol,
                ..Default::default()
            },
        ));
    }
    out
}

fn interact_once(
    engine: &mut InteractionEngine,
    a: &Body,
    b: &Body,
    pose_b: &Pose,
) -> Result<(Interaction, bool), InteractionError> {
    match engine.interact(a, &Pose::identity(), b, pose_b) {
        Ok(r) => Ok((r, true)),
        Err(InteractionError::ToleranceNotMet { best, .. }) => Ok((*best, false)),
        Err(e) => Err(e),
    }
}

fn interaction_bench(
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<InteractionRow>, BenchError> {
    let root: Value = serde_json::from_str(REFERENCE_JSON)
        .map_err(|e| BenchError::Data(format!("tests/reference/interactions.json: {e}")))?;
    let a = paper_spheroid()?;
    let b = paper_spheroid()?;
    let batches = if options.quick { 1 } else { 5 };
    let mut rows = Vec::new();
    for d in SEPARATIONS {
        let reference = paper_pair_reference(&root, d).ok_or_else(|| {
            BenchError::Data(format!(
                "tests/reference/interactions.json has no paper-pair case at separation {d}"
            ))
        })?;
        let pose_b = Pose::new(Vec3::new(d, 0.0, 0.0), Vec3::zeros());
        for (family, setting, engine_options) in rule_variants(options.quick) {
            let context = format!("separation {d}, {family} {setting}");
            let mut engine =
                InteractionEngine::new(engine_options).map_err(|e| engine_error(&context, e))?;
            let (result, converged) = interact_once(&mut engine, &a, &b, &pose_b)
                .map_err(|e| engine_error(&context, e))?;
            let seconds = time_per_call(options.min_batch_seconds, batches, || {
                let _ = std::hint::black_box(interact_once(&mut engine, &a, &b, &pose_b));
            });
            let force_only = match engine.force(&a, &Pose::identity(), &b, &pose_b) {
                Ok(f) => f.force_on_a,
                Err(InteractionError::ToleranceNotMet { best, .. }) => best.force_on_a,
                Err(e) => return Err(engine_error(&context, e)),
            };
            let force_only_seconds = time_per_call(options.min_batch_seconds, batches, || {
                let _ = std::hint::black_box(engine.force(&a, &Pose::identity(), &b, &pose_b));
            });
            let relative_force = |f: Vec3| (f - reference.force).norm() / reference.force.norm();
            let force_error = relative_force(result.force_on_a);
            let force_only_error = relative_force(force_only);
            let energy_error =
                ((result.potential_energy - reference.energy) / reference.energy).abs();
            if !force_error.is_finite()
                || !energy_error.is_finite()
                || !force_only_error.is_finite()
            {
                return Err(engine_error(&context, "non-finite result"));
            }
            let row = InteractionRow {
                separation: d,
                family,
                setting,
                evaluations: result.evaluations,
                seconds,
                force_only_seconds,
                force_only_error: floored(force_only_error),
                force_error: floored(force_error),
                energy_error: floored(energy_error),
                error_estimate: result.error_estimate,
                converged,
            };
            progress(&format!(
                "(a) d = {d}: {} {}: {} evaluations, {:.1} µs ({:.1} µs force only), force error {:.1e}, energy error {:.1e}",
                row.family,
                row.setting,
                row.evaluations,
                row.seconds * 1e6,
                row.force_only_seconds * 1e6,
                row.force_error,
                row.energy_error
            ));
            rows.push(row);
        }
    }
    Ok(rows)
}

// ---------------------------------------------------------------------------------------------
// (b), (c) The integrators.

/// The paper's initial state: A at (−3.5, 0, 0) moving (0, 0.2, 0), B mirrored.
pub fn paper_initial_state() -> TwoBodyState {
    TwoBodyState::new(
        BodyState::new(Vec3::new(-3.5, 0.0, 0.0), Vec3::new(0.0, 0.2, 0.0)),
        BodyState::new(Vec3::new(3.5, 0.0, 0.0), Vec3::new(0.0, -0.2, 0.0)),
    )
}

/// The settings swept for one integrator (steps for fixed-step kinds, tolerances otherwise).
fn sweep(kind: IntegratorKind, paper_step: f64, quick: bool) -> Vec<f64> {
    if kind.is_adaptive() {
        return if quick {
            vec![1e-8, 1e-11]
        } else if kind == IntegratorKind::Dopri5 {
            vec![1e-6, 1e-8, 1e-10, 1e-12]
        } else {
            vec![1e-6, 1e-8, 1e-10, 1e-12, 1e-13]
        };
    }
    // Steps as multiples of the paper's step, larger for higher orders (same work range).
    let factors: &[f64] = match kind {
        IntegratorKind::Leapfrog => &[1.0, 0.5, 0.25, 0.125, 0.0625],
        IntegratorKind::Rk4 | IntegratorKind::Yoshida4 => &[2.0, 1.0, 0.5, 0.25, 0.125],
        IntegratorKind::Yoshida6 => &[4.0, 2.0, 1.0, 0.5, 0.25],
        _ => &[8.0, 4.0, 2.0, 1.0, 0.5],
    };
    let factors = if quick { &factors[1..3] } else { factors };
    factors.iter().map(|f| f * paper_step).collect()
}

struct RunOutcome {
    row: DynamicsRow,
    final_state: Option<TwoBodyState>,
}

/// A scene with the model it runs on.
#[derive(Clone, Copy)]
struct SceneRun<'m> {
    scene: &'m str,
    model_name: &'m str,
    model: &'m dyn InteractionModel,
    initial: &'m TwoBodyState,
    /// The bodies rotate: the attitude error is reported too.
    attitudes: bool,
    /// Fixed steps are named as fractions of this orbital period (s), if given.
    period: Option<f64>,
}

/// Runs one integrator, timing the integration alone; energies are evaluated afterwards from
/// the stored samples.
fn run_one(
    run: SceneRun<'_>,
    kind: IntegratorKind,
    setting: f64,
    t_end: f64,
    reference: Option<&TwoBodyState>,
) -> Result<RunOutcome, BenchError> {
    let SceneRun {
        scene,
        model_name,
        model,
        initial,
        attitudes,
        period,
    } = run;
    let (step, tolerance) = if kind.is_adaptive() {
        (1.0, setting)
    } else {
        (setting, 1.0)
    };
    let setting_text = if kind.is_adaptive() {
        format!("tol {setting:.0e}")
    } else if let Some(period) = period {
        format!("dt = T/{:.0} ({setting:.1} s)", period / setting)
    } else {
        format!("dt = {setting}")
    };
    let context = format!("{scene}, {model_name}, {} {setting_text}", kind.name());
    let mut integrator = kind
        .build(step, tolerance)
        .map_err(|e| BenchError::Dynamics {
            context: context.clone(),
            message: e.to_string(),
        })?;
    let mut samples: Vec<Sample> = Vec::new();
    let start = Instant::now();
    let result = integrator.integrate(model, initial, 0.0, t_end, &mut |s| samples.push(*s));
    let mut wall_seconds = start.elapsed().as_secs_f64();
    // Short runs are timed again (the same deterministic run), best of several: one run of a
    // few milliseconds is at the mercy of the shared machine.
    if result.is_ok() && wall_seconds < 0.2 {
        for _ in 0..REPEATS_OF_SHORT_RUNS {
            let mut again = kind
                .build(step, tolerance)
                .map_err(|e| BenchError::Dynamics {
                    context: context.clone(),
                    message: e.to_string(),
                })?;
            let start = Instant::now();
            let repeat = again.integrate(model, initial, 0.0, t_end, &mut |_| {});
            let t = start.elapsed().as_secs_f64();
            if repeat.is_ok() {
                wall_seconds = wall_seconds.min(t);
            }
        }
    }
    let summary = match result {
        Ok(s) => s,
        Err(e) => {
            // A failed run is a row, not the end of the bench (a large step may not survive
            // the close approach).
            return Ok(RunOutcome {
                row: DynamicsRow {
                    scene: scene.into(),
                    model: model_name.into(),
                    integrator: kind.name().into(),
                    setting: setting_text,
                    t_end,
                    steps: 0,
                    force_evaluations: 0,
                    wall_seconds,
                    energy_error: None,
                    trajectory_error: None,
                    attitude_error: None,
                    termination: format!("failed: {e}"),
                },
                final_state: None,
            });
        }
    };
    let completed = matches!(summary.termination, Termination::Completed);
    let termination = match &summary.termination {
        Termination::Completed => "completed".to_string(),
        Termination::Contact(c) => format!("contact at t = {:.3}", c.sample.time),
        Termination::Escape(e) => format!("escape at t = {:.3}", e.sample.time),
    };
    let (energy_error, trajectory_error, attitude_error, final_state) = if completed {
        let mut monitor = ConservationMonitor::new(model);
        for s in &samples {
            monitor.observe(s);
        }
        let energy = monitor.energy().map_err(|(t, e)| BenchError::Dynamics {
            context: format!("{context}: energy at t = {t}"),
            message: e.to_string(),
        })?;
        let fin = summary.last.state;
        let trajectory =
            reference.map(|r| floored((fin.relative_position() - r.relative_position()).norm()));
        let attitude = reference
            .filter(|_| attitudes)
            .map(|r| floored(attitude_difference(&fin, r)));
        (
            Some(floored(energy.max_relative_drift)),
            trajectory,
            attitude,
            Some(fin),
        )
    } else {
        (None, None, None, None)
    };
    Ok(RunOutcome {
        row: DynamicsRow {
            scene: scene.into(),
            model: model_name.into(),
            integrator: kind.name().into(),
            setting: setting_text,
            t_end,
            steps: summary.steps,
            force_evaluations: summary.force_evaluations,
            wall_seconds,
            energy_error,
            trajectory_error,
            attitude_error,
            termination,
        },
        final_state,
    })
}

/// The larger of the two bodies' rotation angles (rad) between the attitudes of `a` and `b`.
fn attitude_difference(a: &TwoBodyState, b: &TwoBodyState) -> f64 {
    a.body_a
        .orientation
        .angle_to(&b.body_a.orientation)
        .max(a.body_b.orientation.angle_to(&b.body_b.orientation))
}

/// The reference state at `t_end` (DOP853 at [`REFERENCE_TOLERANCE`]) and the distance of a
/// run at ten times that tolerance from its relative position (errors much below it are not
/// resolved).
fn reference_final(
    run: SceneRun<'_>,
    t_end: f64,
    progress: &mut dyn FnMut(&str),
) -> Result<(TwoBodyState, f64), BenchError> {
    let SceneRun {
        scene, model_name, ..
    } = run;
    let outcome = run_one(
        run,
        IntegratorKind::Dop853,
        REFERENCE_TOLERANCE,
        t_end,
        None,
    )?;
    progress(&format!(
        "{scene}: reference run (dop853, tol {REFERENCE_TOLERANCE:.0e}, {model_name}): {} steps, {:.2} s, {}",
        outcome.row.steps, outcome.row.wall_seconds, outcome.row.termination
    ));
    let reference = outcome.final_state.ok_or_else(|| BenchError::Dynamics {
        context: format!("{scene} reference run"),
        message: outcome.row.termination.clone(),
    })?;
    let check = run_one(
        run,
        IntegratorKind::Dop853,
        10.0 * REFERENCE_TOLERANCE,
        t_end,
        Some(&reference),
    )?;
    let spread = check
        .row
        .trajectory_error
        .ok_or_else(|| BenchError::Dynamics {
            context: format!("{scene} reference check run"),
            message: check.row.termination,
        })?;
    progress(&format!(
        "{scene}: dop853 at tolerance {:.0e} ends {spread:.1e} from the reference",
        10.0 * REFERENCE_TOLERANCE
    ));
    Ok((reference, spread))
}

fn sweep_all(
    run: SceneRun<'_>,
    paper_step: f64,
    t_end: f64,
    reference: &TwoBodyState,
    quick: bool,
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<DynamicsRow>, BenchError> {
    let mut rows = Vec::new();
    for kind in IntegratorKind::ALL {
        for setting in sweep(kind, paper_step, quick) {
            let outcome = run_one(run, kind, setting, t_end, Some(reference))?;
            progress(&dynamics_line(&outcome.row));
            rows.push(outcome.row);
        }
    }
    Ok(rows)
}

fn dynamics_line(r: &DynamicsRow) -> String {
    let e = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.1e}"));
    let attitude = r
        .attitude_error
        .map_or(String::new(), |a| format!(", attitude error {a:.1e} rad"));
    format!(
        "({}) {}, {}: {} {}: {} steps, {} force evaluations, {:.3} s, energy error {}, trajectory error {}{attitude}, {}",
        part_letter(&r.scene),
        r.scene,
        r.model,
        r.integrator,
        r.setting,
        r.steps,
        r.force_evaluations,
        r.wall_seconds,
        e(r.energy_error),
        e(r.trajectory_error),
        r.termination
    )
}

/// The bench's letter for a scene: (b) paper-2s, (c) paper-2d, (d) kw4-ellipsoids.
fn part_letter(scene: &str) -> &'static str {
    match scene {
        "paper-2s" => "b",
        "paper-2d" => "c",
        _ => "d",
    }
}

struct SceneOutcome {
    rows: Vec<DynamicsRow>,
    /// Seconds spent building the model (the table for the fast path).
    table_seconds: f64,
    /// Reference relative position at t_end.
    reference_final: Option<Vec3>,
    /// Distance of a run at ten times the reference's tolerance from the reference.
    reference_spread: f64,
}

fn dynamics_error(context: &str, e: impl std::fmt::Display) -> BenchError {
    BenchError::Dynamics {
        context: context.into(),
        message: e.to_string(),
    }
}

fn paper_2s(
    options: &BenchOptions,
    short_t_end: f64,
    progress: &mut dyn FnMut(&str),
) -> Result<SceneOutcome, BenchError> {
    let scene = "paper-2s";
    let initial = paper_initial_state();
    let start = Instant::now();
    let fast = SceneModel::build(
        paper_spheroid()?,
        paper_spheroid()?,
        &initial,
        &SceneSettings::default(),
    )
    .map_err(|e| dynamics_error("paper-2s interpolant", e))?;
    let table_seconds = start.elapsed().as_secs_f64();
    let fast_name = if fast.is_interpolated() {
        "interpolant"
    } else {
        "direct engine"
    };
    progress(&format!(
        "(b) paper-2s: model built in {table_seconds:.2} s ({fast_name})"
    ));
    let fast_run = SceneRun {
        scene,
        model_name: fast_name,
        model: &fast,
        initial: &initial,
        attitudes: false,
        period: None,
    };
    let (reference, reference_spread) = reference_final(fast_run, PAPER_T_END, progress)?;
    let mut rows = sweep_all(
        fast_run,
        0.1,
        PAPER_T_END,
        &reference,
        options.quick,
        progress,
    )?;

    // The direct surface integral at every force evaluation: the paper's own setting (RK4,
    // dt = 0.1) over the baseline's shortened run (t = 0 … 3, or 1 in its quick mode), and in
    // full mode the whole run and adaptive runs (against the interpolant's reference: this
    // also shows the table's error).
    let direct = EngineModel::new(
        paper_spheroid()?,
        paper_spheroid()?,
        InteractionOptions::default(),
    )
    .map_err(|e| dynamics_error("paper-2s direct engine", e))?;
    let mut direct_runs = vec![(IntegratorKind::Rk4, 0.1, short_t_end)];
    if !options.quick {
        direct_runs.push((IntegratorKind::Rk4, 0.1, PAPER_T_END));
        direct_runs.push((IntegratorKind::Dop853, 1e-10, PAPER_T_END));
        direct_runs.push((IntegratorKind::Dop853, 1e-12, PAPER_T_END));
    }
    for (kind, setting, t_end) in direct_runs {
        let reference = (t_end == PAPER_T_END).then_some(&reference);
        let direct_run = SceneRun {
            scene,
            model_name: "direct engine",
            model: &direct,
            initial: &initial,
            attitudes: false,
            period: None,
        };
        let outcome = run_one(direct_run, kind, setting, t_end, reference)?;
        progress(&dynamics_line(&outcome.row));
        rows.push(outcome.row);
    }
    Ok(SceneOutcome {
        rows,
        table_seconds,
        reference_final: Some(reference.relative_position()),
        reference_spread,
    })
}

fn paper_2d(
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<SceneOutcome, BenchError> {
    let scene = "paper-2d";
    let model = EngineModel::new(paper_disk()?, paper_disk()?, InteractionOptions::default())
        .map_err(|e| dynamics_error("paper-2d model", e))?;
    let initial = paper_initial_state();
    let run = SceneRun {
        scene,
        model_name: "closed form (disks)",
        model: &model,
        initial: &initial,
        attitudes: false,
        period: None,
    };
    let (reference, reference_spread) = reference_final(run, PAPER_T_END, progress)?;
    let rows = sweep_all(run, 0.01, PAPER_T_END, &reference, options.quick, progress)?;
    Ok(SceneOutcome {
        rows,
        table_seconds: 0.0,
        reference_final: Some(reference.relative_position()),
        reference_spread,
    })
}

/// The `kw4-ellipsoids` preset's scene and model, and its Keplerian period (from the initial
/// relative state).
fn kw4_scene() -> Result<(crate::scene::Scene, crate::simulate::PreparedModel, f64), BenchError> {
    let preset = crate::presets::find(KW4_SCENE)
        .ok_or_else(|| BenchError::Data(format!("no preset {KW4_SCENE}")))?;
    let scene = preset
        .scene()
        .map_err(|e| dynamics_error("kw4-ellipsoids preset", e))?;
    let prepared =
        crate::simulate::prepare(&scene).map_err(|e| dynamics_error("kw4-ellipsoids model", e))?;
    let model = prepared.model();
    let mu = scene.gravitational_constant * (model.mass_a() + model.mass_b());
    let r = scene.initial.relative_position().norm();
    let v = (scene.initial.body_b.velocity - scene.initial.body_a.velocity).norm();
    let semi_major_axis = 1.0 / (2.0 / r - v * v / mu);
    let period = 2.0 * std::f64::consts::PI * (semi_major_axis.powi(3) / mu).sqrt();
    if !(period.is_finite() && period > 0.0) {
        return Err(BenchError::Data(format!(
            "{KW4_SCENE}: the initial orbit is not bound (a = {semi_major_axis} m)"
        )));
    }
    Ok((scene, prepared, period))
}

/// (d) Every integrator on `kw4-ellipsoids` (full 3-D motion with rotation, direct surface
/// integral): over the preset's whole run (10 mutual orbits), or [`QUICK_KW4_ORBITS`] of an
/// orbit in quick mode, against DOP853 at [`REFERENCE_TOLERANCE`]. Fixed steps are swept
/// around 100 per orbit as paper-2s's are around its dt = 0.1.
/// Part (d)'s rows and what its table needs to say.
struct Kw4Outcome {
    rows: Vec<DynamicsRow>,
    /// End time of the runs (s).
    t_end: f64,
    /// Keplerian period of the initial relative orbit (s).
    period: f64,
    /// Seconds spent building the model.
    build_seconds: f64,
    /// Distance of a run at ten times the reference's tolerance from the reference (m).
    reference_spread: f64,
}

fn kw4_ellipsoids(
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<Kw4Outcome, BenchError> {
    let start = Instant::now();
    let (scene, prepared, period) = kw4_scene()?;
    let build_seconds = start.elapsed().as_secs_f64();
    let t_end = if options.quick {
        QUICK_KW4_ORBITS * period
    } else {
        scene.t_end - scene.t_start
    };
    progress(&format!(
        "(d) {KW4_SCENE}: {} ({}), period {period:.1} s, t = 0 … {t_end:.1} s ({:.2} orbits)",
        prepared.method,
        if prepared.path.is_rotation() {
            "translation and rotation"
        } else {
            "translation only"
        },
        t_end / period
    ));
    let run = SceneRun {
        scene: KW4_SCENE,
        model_name: prepared.method,
        model: prepared.model(),
        initial: &scene.initial,
        attitudes: prepared.path.is_rotation(),
        period: Some(period),
    };
    let (reference, reference_spread) = reference_final(run, t_end, progress)?;
    let rows = sweep_all(
        run,
        period / 100.0,
        t_end,
        &reference,
        options.quick,
        progress,
    )?;
    Ok(Kw4Outcome {
        rows,
        t_end,
        period,
        build_seconds,
        reference_spread,
    })
}

// ---------------------------------------------------------------------------------------------
// The baseline and the speed-ups.

/// The paper's method at one separation.
#[derive(Debug, Clone, Copy, PartialEq)]
struct BaselineForce {
    separation: f64,
    /// Seconds per force evaluation (median).
    seconds: f64,
    /// Relative force error against the reference.
    force_error: f64,
    /// Relative energy error, if measured.
    energy_error: Option<f64>,
    /// Seconds per energy evaluation, if measured.
    energy_seconds: Option<f64>,
}

/// The baseline figures used here.
#[derive(Debug, Clone, PartialEq, Default)]
struct Baseline {
    /// Force evaluations with B on A's x axis, one per separation.
    force: Vec<BaselineForce>,
    /// Seconds per RK4 step of the shortened run (t = 0 … t_end_short), and that t_end.
    rk4_step: Option<(f64, f64)>,
    /// Whole paper-2s run, forces only: seconds, final R_B − R_A, max |ΔE/E0|.
    full_run: Option<(f64, Vec3, f64)>,
}

fn parse_baseline(root: &Value) -> Result<Baseline, BenchError> {
    let mut b = Baseline::default();
    let evaluations = root["force_evaluations"]
        .as_array()
        .ok_or_else(|| BenchError::Data("baseline: no force_evaluations".into()))?;
    for e in evaluations {
        if number(&e["direction_angle_rad"]) != Some(0.0) {
            continue;
        }
        let (Some(d), Some(s), Some(err)) = (
            number(&e["separation"]),
            number(&e["seconds_per_force_evaluation_median"]),
            number(&e["force_relative_error"]),
        ) else {
            continue;
        };
        b.force.push(BaselineForce {
            separation: d,
            seconds: s,
            force_error: err,
            energy_error: number(&e["energy_relative_error"]),
            energy_seconds: number(&e["seconds_per_energy_evaluation"]),
        });
    }
    let short = &root["rk4_run"];
    if let (Some(s), Some(t)) = (number(&short["seconds_per_step"]), number(&short["t_end"])) {
        b.rk4_step = Some((s, t));
    }
    let full = &root["rk4_full_run"];
    if let (Some(s), Some(ra), Some(rb)) = (
        number(&full["wall_seconds_forces"]),
        vector(&full["final_positions"]["R_A"]),
        vector(&full["final_positions"]["R_B"]),
    ) {
        let de = number(&full["energy_every_step"]["max_abs_relative_energy_change"])
            .unwrap_or(f64::NAN);
        b.full_run = Some((s, rb - ra, de));
    }
    Ok(b)
}

fn load_baseline(
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<(Baseline, String), BenchError> {
    let committed: Value = serde_json::from_str(BASELINE_JSON)
        .map_err(|e| BenchError::Data(format!("tools/paper_baseline/baseline.json: {e}")))?;
    let mut baseline = parse_baseline(&committed)?;
    let date = committed["date_utc"].as_str().unwrap_or("unknown date");
    let committed_source = format!(
        "committed tools/paper_baseline/baseline.json (run of {date}, {} mode)",
        committed["mode"].as_str().unwrap_or("?")
    );
    if !options.rerun_baseline {
        return Ok((
            baseline,
            format!("{committed_source}; not re-run (`surfgrav bench --rerun-baseline` re-runs it in the same sitting)"),
        ));
    }
    match rerun_baseline(options, progress) {
        Ok(fresh) => {
            let parsed = parse_baseline(&fresh)?;
            baseline.force = parsed.force;
            baseline.rk4_step = parsed.rk4_step.or(baseline.rk4_step);
            let full_note = if parsed.full_run.is_some() {
                baseline.full_run = parsed.full_run;
                "whole run also re-measured"
            } else {
                "whole paper-2s run from the committed file"
            };
            Ok((
                baseline,
                format!(
                    "re-run in this sitting ({} mode; {full_note}: {committed_source})",
                    fresh["mode"].as_str().unwrap_or("?")
                ),
            ))
        }
        Err(why) => Ok((
            baseline,
            format!("{committed_source}; re-run not possible: {why}"),
        )),
    }
}

/// Why the baseline script could not be re-run (the committed figures are used instead, and
/// the report says why).
#[derive(Debug, thiserror::Error)]
enum RerunError {
    #[error("{0} not found")]
    ScriptMissing(&'static str),
    #[error("{python} cannot be started: {source}")]
    CannotStart {
        python: String,
        source: std::io::Error,
    },
    #[error("{0} has no scipy/numpy")]
    NoScipy(String),
    #[error("the script failed ({status}): {last_line}")]
    ScriptFailed {
        status: std::process::ExitStatus,
        last_line: String,
    },
    #[error("its output is not JSON: {0}")]
    NotJson(serde_json::Error),
}

fn rerun_baseline(
    options: &BenchOptions,
    progress: &mut dyn FnMut(&str),
) -> Result<Value, RerunError> {
    if !Path::new(BASELINE_SCRIPT).exists() {
        return Err(RerunError::ScriptMissing(BASELINE_SCRIPT));
    }
    let cannot_start = |source| RerunError::CannotStart {
        python: options.python.clone(),
        source,
    };
    let check = Command::new(&options.python)
        .args(["-c", "import scipy, numpy"])
        .output()
        .map_err(cannot_start)?;
    if !check.status.success() {
        return Err(RerunError::NoScipy(options.python.clone()));
    }
    let mut args = vec![BASELINE_SCRIPT, "--json"];
    if options.quick {
        args.push("--quick");
    } else {
        args.push("--no-full-run");
    }
    progress(&format!(
        "baseline: running {} {} (the paper's method, scipy)",
        options.python,
        args.join(" ")
    ));
    let output = Command::new(&options.python)
        .args(&args)
        .output()
        .map_err(cannot_start)?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        return Err(RerunError::ScriptFailed {
            status: output.status,
            last_line: stderr.lines().last().unwrap_or("").to_string(),
        });
    }
    serde_json::from_slice(&output.stdout).map_err(RerunError::NotJson)
}

/// The engine's default: azimuth–height ladder at 10⁻¹².
const DEFAULT_FAMILY: (&str, &str) = ("AH ladder", "tol 1e-12");

fn speedups(
    baseline: &Baseline,
    interaction: &[InteractionRow],
    dynamics: &[DynamicsRow],
    table_seconds: f64,
    reference: Option<Vec3>,
) -> Vec<Speedup> {
    let mut out = Vec::new();
    for &BaselineForce {
        separation: d,
        seconds,
        force_error: error,
        ..
    } in &baseline.force
    {
        let at_d: Vec<&InteractionRow> = interaction
            .iter()
            .filter(|r| r.separation == d && r.converged)
            .collect();
        // The engine's default if it was run, else the fastest row at least as accurate.
        let default = at_d
            .iter()
            .find(|r| r.family == DEFAULT_FAMILY.0 && r.setting == DEFAULT_FAMILY.1);
        let as_accurate = at_d
            .iter()
            .filter(|r| r.force_only_error <= error.max(ERROR_FLOOR))
            .min_by(|a, b| a.force_only_seconds.total_cmp(&b.force_only_seconds));
        for (label, row) in [
            ("engine default", default),
            ("fastest as accurate", as_accurate),
        ] {
            if let Some(r) = row {
                out.push(Speedup {
                    task: format!("force evaluation at separation {d} ({label})"),
                    baseline_seconds: seconds,
                    surfgrav_seconds: r.force_only_seconds,
                    ratio: seconds / r.force_only_seconds,
                    note: format!(
                        "force only; force error: paper's method {error:.1e}, surfgrav {:.1e} ({} {}); force, torques and energy together take {:.1} µs",
                        r.force_only_error, r.family, r.setting, r.seconds * 1e6
                    ),
                });
            }
        }
    }
    let find = |model: &str, integrator: &str, setting: &str, t_end: f64| {
        dynamics.iter().find(|r| {
            r.scene == "paper-2s"
                && r.model == model
                && r.integrator == integrator
                && r.setting == setting
                && r.t_end == t_end
                && r.termination == "completed"
        })
    };
    if let (Some((seconds, t_short)), Some(r)) = (
        baseline.rk4_step,
        find(
            "direct engine",
            "rk4",
            "dt = 0.1",
            baseline.rk4_step.map_or(3.0, |(_, t)| t),
        ),
    ) {
        let ours = r.wall_seconds / r.steps.max(1) as f64;
        out.push(Speedup {
            task: format!("RK4 step of paper-2s, t = 0 … {t_short}, direct surface integral"),
            baseline_seconds: seconds,
            surfgrav_seconds: ours,
            ratio: seconds / ours,
            note: "mean over the shortened run's steps; surfgrav's engine at tolerance 1e-12"
                .into(),
        });
    }
    if let Some((seconds, final_rel, energy)) = baseline.full_run {
        let baseline_trajectory = reference.map(|r| (final_rel - r).norm());
        let accuracy = |r: &DynamicsRow| {
            format!(
                "max |ΔE/E0|: paper's method {energy:.1e}, surfgrav {}; trajectory error at t = 300: paper's method {}, surfgrav {}",
                r.energy_error.map_or("—".into(), |e| format!("{e:.1e}")),
                baseline_trajectory.map_or("—".into(), |e| format!("{e:.1e}")),
                r.trajectory_error.map_or("—".into(), |e| format!("{e:.1e}")),
            )
        };
        if let Some(r) = find("direct engine", "rk4", "dt = 0.1", PAPER_T_END) {
            out.push(Speedup {
                task: "whole paper-2s (RK4, dt = 0.1, t = 300), direct surface integral".into(),
                baseline_seconds: seconds,
                surfgrav_seconds: r.wall_seconds,
                ratio: seconds / r.wall_seconds,
                note: accuracy(r),
            });
        }
        if let Some(r) = find("interpolant", "rk4", "dt = 0.1", PAPER_T_END) {
            let ours = r.wall_seconds + table_seconds;
            out.push(Speedup {
                task: "whole paper-2s (RK4, dt = 0.1, t = 300), tabulated central pair".into(),
                baseline_seconds: seconds,
                surfgrav_seconds: ours,
                ratio: seconds / ours,
                note: format!(
                    "including the table's build, {table_seconds:.3} s; {}",
                    accuracy(r)
                ),
            });
        }
        // The fastest run of each model at least as accurate in both measures.
        for (model, label, build) in [
            ("direct engine", "direct surface integral", 0.0),
            ("interpolant", "tabulated central pair", table_seconds),
        ] {
            let Some(bt) = baseline_trajectory else {
                break;
            };
            let best = dynamics
                .iter()
                .filter(|r| {
                    r.scene == "paper-2s"
                        && r.model == model
                        && r.t_end == PAPER_T_END
                        && r.energy_error.is_some_and(|e| e <= energy)
                        && r.trajectory_error.is_some_and(|e| e <= bt)
                })
                .min_by(|a, b| a.wall_seconds.total_cmp(&b.wall_seconds));
            if let Some(r) = best {
                let ours = r.wall_seconds + build;
                out.push(Speedup {
                    task: format!(
                        "whole paper-2s at equal or better accuracy, {label} ({} {})",
                        r.integrator, r.setting
                    ),
                    baseline_seconds: seconds,
                    surfgrav_seconds: ours,
                    ratio: seconds / ours,
                    note: if build > 0.0 {
                        format!("including the table's build; {}", accuracy(r))
                    } else {
                        accuracy(r)
                    },
                });
            }
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Tables.

/// Text for a Markdown table cell: a `|` would end the cell.
fn md_cell(s: &str) -> String {
    s.replace('|', "\\|")
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| format!("{x:e}"))
}

fn opt_md(v: Option<f64>) -> String {
    v.map_or("—".into(), |x| format!("{x:.1e}"))
}

fn interaction_markdown(rows: &[InteractionRow], baseline: &Baseline) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Interaction of the paper's pair: error against time\n\nTwo oblate spheroids a = 1, c = 0.25, m = 1, G = 1, common equatorial plane, B on A's x axis. Errors relative, against `tests/reference/interactions.json` (independent volume integration, about 2e-16), floored at {ERROR_FLOOR:.0e}. AH: azimuth–height (the paper's (φ, z)); PA: polar angle–azimuth. Times: one interaction (force, torques, energy), best of several batches, tables already built.\n"
    );
    for d in SEPARATIONS {
        let _ = writeln!(s, "\n## Separation {d}\n");
        let _ = writeln!(
            s,
            "| rule | setting | evaluations | µs / interaction | force error | energy error | engine's estimate | converged | µs / force only | its force error |"
        );
        let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---|---:|---:|");
        for r in rows.iter().filter(|r| r.separation == d) {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {:.2} | {:.1e} | {:.1e} | {:.1e} | {} | {:.2} | {:.1e} |",
                r.family,
                r.setting,
                r.evaluations,
                r.seconds * 1e6,
                r.force_error,
                r.energy_error,
                r.error_estimate,
                if r.converged { "yes" } else { "no" },
                r.force_only_seconds * 1e6,
                r.force_only_error
            );
        }
        if let Some(&BaselineForce {
            seconds: secs,
            force_error: ferr,
            energy_error: eerr,
            energy_seconds: esecs,
            ..
        }) = baseline.force.iter().find(|b| b.separation == d)
        {
            let _ = writeln!(
                s,
                "| paper's method (scipy dblquad ×3, force only) | default tolerances | — | — | — | {} | — | — | {:.0} | {ferr:.1e} |",
                opt_md(eerr),
                secs * 1e6
            );
            if let Some(es) = esecs {
                let _ = writeln!(
                    s,
                    "\n(The paper's method's energy is one more dblquad: {:.0} µs.)",
                    es * 1e6
                );
            }
        }
    }
    s
}

fn interaction_csv(rows: &[InteractionRow]) -> String {
    let mut s = String::from(
        "separation,rule,setting,evaluations,seconds_per_interaction,force_relative_error,energy_relative_error,engine_error_estimate,converged,seconds_per_force_only,force_only_relative_error\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{:e},{:e},{:e},{:e},{},{:e},{:e}",
            r.separation,
            csv_field(&r.family),
            csv_field(&r.setting),
            r.evaluations,
            r.seconds,
            r.force_error,
            r.energy_error,
            r.error_estimate,
            r.converged,
            r.force_only_seconds,
            r.force_only_error
        );
    }
    s
}

/// `spreads`: paper-2s, paper-2d, kw4-ellipsoids.
fn dynamics_markdown(
    rows: &[DynamicsRow],
    table_seconds: f64,
    spreads: [f64; 3],
    kw4: &Kw4Outcome,
) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Integrators on the paper's scenes and on 1999 KW4: error against wall time\n\nPaper's scenes: initial state R_A = (−3.5, 0, 0), V_A = (0, 0.2, 0), B mirrored; t = 0 … {PAPER_T_END} unless stated. Energy error: max |E − E0| / |E0| over the accepted steps (E includes the spins' kinetic energy). Trajectory error: |r(t_end) − r_ref(t_end)| (length units) for r = R_B − R_A, against DOP853 at tolerance {REFERENCE_TOLERANCE:.0e} with the same model ('interpolant' rows and 'direct engine' rows share the interpolant's reference, so the latter include the table's error). Errors floored at {ERROR_FLOOR:.0e}. Wall time of the integration alone; paper-2s's table took {table_seconds:.3} s to build.\n"
    );
    let Kw4Outcome {
        t_end: kw4_t_end,
        period: kw4_period,
        build_seconds: kw4_build,
        ..
    } = *kw4;
    for (scene, spread) in ["paper-2s", "paper-2d", KW4_SCENE].into_iter().zip(spreads) {
        let _ = writeln!(s, "\n## {scene}\n");
        let rotating = scene == KW4_SCENE;
        if rotating {
            let _ = writeln!(
                s,
                "The `{KW4_SCENE}` preset (1999 KW4 as two triaxial ellipsoids, SI units, full 3-D motion with rotation; every force and torque by the direct surface integral at the preset's tolerance; model built in {kw4_build:.3} s), t = 0 … {kw4_t_end:.1} s: {:.2} mutual orbits of period T = {kw4_period:.1} s (the preset's whole run; {QUICK_KW4_ORBITS} of an orbit in quick mode). Trajectory error in metres; attitude error: the larger of the two bodies' rotation angles (rad) from the reference's final attitudes. Fixed steps are given as fractions of T.\n",
                kw4_t_end / kw4_period
            );
        }
        let _ = writeln!(
            s,
            "DOP853 at tolerance {:.0e} ends {spread:.1e} from the reference: trajectory errors near or below that are the reference's, not the run's.\n",
            10.0 * REFERENCE_TOLERANCE
        );
        let _ = writeln!(
            s,
            "| model | integrator | setting | t_end | steps | force evaluations | wall s | energy error | trajectory error |{} end |",
            if rotating { " attitude error (rad) |" } else { "" }
        );
        let _ = writeln!(
            s,
            "|---|---|---|---:|---:|---:|---:|---:|---:|{}---|",
            if rotating { "---:|" } else { "" }
        );
        for r in rows.iter().filter(|r| r.scene == scene) {
            let attitude = if rotating {
                format!(" {} |", opt_md(r.attitude_error))
            } else {
                String::new()
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {:.4} | {} | {} |{attitude} {} |",
                r.model,
                r.integrator,
                r.setting,
                r.t_end,
                r.steps,
                r.force_evaluations,
                r.wall_seconds,
                opt_md(r.energy_error),
                opt_md(r.trajectory_error),
                md_cell(&r.termination)
            );
        }
    }
    s
}

fn dynamics_csv(rows: &[DynamicsRow]) -> String {
    let mut s = String::from(
        "scene,model,integrator,setting,t_end,steps,force_evaluations,wall_seconds,energy_relative_error,trajectory_error,attitude_error_rad,termination\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{:e},{},{},{},{}",
            r.scene,
            csv_field(&r.model),
            r.integrator,
            csv_field(&r.setting),
            r.t_end,
            r.steps,
            r.force_evaluations,
            r.wall_seconds,
            opt(r.energy_error),
            opt(r.trajectory_error),
            opt(r.attitude_error),
            csv_field(&r.termination)
        );
    }
    s
}

/// Time of one interaction with the 130-node table (AH single table, t = 10) at separation 3
/// above which the build is taken to be unoptimised: 10 µs in a release build on the build
/// machine, 300 µs in a debug build; the threshold leaves a factor 6 for a slower or busier
/// machine.
const UNOPTIMISED_SECONDS: f64 = 60e-6;

/// Warnings about how this binary was built: a debug build (`cfg(debug_assertions)`) whose
/// calibration interaction is slow is unoptimised (this workspace's test profile keeps debug
/// assertions but optimises, so the assertion flag alone does not tell).
fn build_warnings(interaction: &[InteractionRow]) -> Vec<String> {
    let calibration = interaction
        .iter()
        .find(|r| r.separation == 3.0 && r.family == "AH single table" && r.setting == "t = 10")
        .map(|r| r.seconds);
    match calibration {
        Some(t) if cfg!(debug_assertions) && t > UNOPTIMISED_SECONDS => vec![format!(
            "surfgrav's code is unoptimised (a debug build, e.g. `cargo run` without \
             `--release`): one 130-node interaction took {:.0} µs against about 10 µs in a \
             release build, so every surfgrav time here is too long and every speed-up too small",
            t * 1e6
        )],
        _ => Vec::new(),
    }
}

fn speedup_markdown(rows: &[Speedup], source: &str, warnings: &[String]) -> String {
    let mut s = String::new();
    for w in warnings {
        let _ = writeln!(s, "**Warning: {w}.**\n");
    }
    let _ = writeln!(
        s,
        "# Speed-up over the paper's method\n\nBaseline: {source}. Ratio = the paper's method's seconds / surfgrav's seconds for the same task, both on this kind of machine (surfgrav measured now).\n"
    );
    let _ = writeln!(
        s,
        "| task | paper's method, s | surfgrav, s | ratio | accuracy |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---|");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {:.3e} | {:.3e} | {:.0} | {} |",
            md_cell(&r.task),
            r.baseline_seconds,
            r.surfgrav_seconds,
            r.ratio,
            md_cell(&r.note)
        );
    }
    s
}

fn speedup_csv(rows: &[Speedup]) -> String {
    let mut s = String::from("task,baseline_seconds,surfgrav_seconds,ratio,note\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{:e},{:e},{:e},{}",
            csv_field(&r.task),
            r.baseline_seconds,
            r.surfgrav_seconds,
            r.ratio,
            csv_field(&r.note)
        );
    }
    s
}

// ---------------------------------------------------------------------------------------------
// Figures.

fn interaction_figure(rows: &[InteractionRow], baseline: &Baseline, force: bool) -> Figure {
    let what = if force { "force" } else { "energy" };
    let mut panels = Vec::new();
    for d in SEPARATIONS {
        let mut families: Vec<String> = Vec::new();
        for r in rows.iter().filter(|r| r.separation == d) {
            if !families.contains(&r.family) {
                families.push(r.family.clone());
            }
        }
        let mut series: Vec<Series> = families
            .iter()
            .map(|f| {
                let points: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.separation == d && &r.family == f)
                    .map(|r| {
                        if force {
                            (r.force_only_seconds * 1e6, r.force_only_error)
                        } else {
                            (r.seconds * 1e6, r.energy_error)
                        }
                    })
                    .collect();
                // In the order of the settings (coarse to fine), not of the times: timing
                // noise must not fold the curve.
                Series {
                    label: f.clone(),
                    points,
                    style: Style::LinePoints,
                }
            })
            .collect();
        if let Some(&BaselineForce {
            seconds: secs,
            force_error: ferr,
            energy_error: eerr,
            energy_seconds: esecs,
            ..
        }) = baseline.force.iter().find(|b| b.separation == d)
        {
            let point = if force {
                Some((secs * 1e6, floored(ferr)))
            } else {
                eerr.zip(esecs).map(|(e, s)| (s * 1e6, floored(e)))
            };
            if let Some(p) = point {
                series.push(Series {
                    label: "paper's method (scipy)".into(),
                    points: vec![p],
                    style: Style::Points,
                });
            }
        }
        panels.push(Panel::Log {
            lines: LinePanel {
                title: format!("separation {d}"),
                x_label: if force {
                    "time per force evaluation (µs)".into()
                } else {
                    "time per force + torque + energy evaluation (µs)".into()
                },
                y_label: format!("relative {what} error"),
                series,
                circles: vec![],
                equal_aspect: false,
            },
            log_x: true,
            log_y: true,
        });
    }
    Figure {
        title: format!("Paper's spheroid pair: {what} error against time"),
        panels,
        columns: 2,
    }
}

/// The baseline's whole run as a point (wall s, energy error, trajectory error).
fn baseline_run_point(baseline: &Baseline, reference: Option<Vec3>) -> Option<(f64, f64, f64)> {
    let (seconds, final_rel, energy) = baseline.full_run?;
    let trajectory = (final_rel - reference?).norm();
    (energy.is_finite() && trajectory.is_finite())
        .then(|| (seconds, floored(energy), floored(trajectory)))
}

/// The error measure drawn in one panel of a dynamics figure.
#[derive(Clone, Copy, PartialEq)]
enum Measure {
    Energy,
    Trajectory,
    Attitude,
}

fn dynamics_figure(
    rows: &[DynamicsRow],
    scene: &str,
    t_end: f64,
    baseline: Option<(f64, f64, f64)>,
) -> Figure {
    let mut panels = Vec::new();
    let rotating = rows
        .iter()
        .any(|r| r.scene == scene && r.attitude_error.is_some());
    let measures: &[Measure] = if rotating {
        &[Measure::Energy, Measure::Trajectory, Measure::Attitude]
    } else {
        &[Measure::Energy, Measure::Trajectory]
    };
    let si = scene == KW4_SCENE;
    for &measure in measures {
        let mut keys: Vec<(String, String)> = Vec::new();
        for r in rows.iter().filter(|r| r.scene == scene && r.t_end == t_end) {
            let key = (r.model.clone(), r.integrator.clone());
            if !keys.contains(&key) {
                keys.push(key);
            }
        }
        let several_models = keys.iter().any(|k| k.0 != keys[0].0);
        let mut series: Vec<Series> = keys
            .iter()
            .filter_map(|(model, integrator)| {
                let points: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| {
                        r.scene == scene
                            && &r.model == model
                            && &r.integrator == integrator
                            && r.t_end == t_end
                            && r.wall_seconds > 0.0
                    })
                    .filter_map(|r| {
                        let e = match measure {
                            Measure::Energy => r.energy_error,
                            Measure::Trajectory => r.trajectory_error,
                            Measure::Attitude => r.attitude_error,
                        }?;
                        Some((r.wall_seconds, e))
                    })
                    .collect();
                if points.is_empty() {
                    return None;
                }
                let label = if several_models {
                    format!("{integrator} ({model})")
                } else {
                    integrator.clone()
                };
                let style = if model == "direct engine" {
                    Style::Points
                } else {
                    Style::LinePoints
                };
                Some(Series {
                    label,
                    points,
                    style,
                })
            })
            .collect();
        if let (Some((s, e, t)), Measure::Energy | Measure::Trajectory) = (baseline, measure) {
            series.push(Series {
                label: "paper's method (RK4, dt = 0.1)".into(),
                points: vec![(s, if measure == Measure::Energy { e } else { t })],
                style: Style::Points,
            });
        }
        let end = if si {
            format!("{t_end:.0} s")
        } else {
            format!("{t_end}")
        };
        panels.push(Panel::Log {
            lines: LinePanel {
                title: match measure {
                    Measure::Energy => "energy error".into(),
                    Measure::Trajectory => format!("trajectory error at t = {end}"),
                    Measure::Attitude => format!("attitude error at t = {end}"),
                },
                x_label: "wall time (s)".into(),
                y_label: match measure {
                    Measure::Energy => "max |E − E0| / |E0|".into(),
                    Measure::Trajectory if si => "|r − r_ref| (m)".into(),
                    Measure::Trajectory => "|r − r_ref| (length units)".into(),
                    Measure::Attitude => "rotation angle from reference (rad)".into(),
                },
                series,
                circles: vec![],
                equal_aspect: false,
            },
            log_x: true,
            log_y: true,
        });
    }
    let span = if si {
        format!("t = 0 … {t_end:.0} s")
    } else {
        format!("t = 0 … {t_end}")
    };
    Figure {
        title: format!("{scene}: error against wall time, {span}"),
        panels,
        columns: 1,
    }
}
