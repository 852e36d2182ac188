//! The `surfgrav` command line.
//!
//! `potential` and `interact` print their result as JSON on stdout; `presets` prints a list or
//! a scene as TOML; `run` and `report` write a folder and print what they wrote with the key
//! numbers. Bad input gives one line on stderr starting with `error:`, nothing on stdout, no
//! output folder, and exit code 2; a run that starts and then fails exits with code 1 (see
//! [`run`]).

use std::path::{Path, PathBuf};

use clap::{Parser, Subcommand};
use serde::Serialize;

use surfgrav_interaction::{InteractionEngine, InteractionOptions};
use surfgrav_potentials::{Pose, PoseExt, Vec3};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::figures;
use crate::output;
use crate::presets;
use crate::scene::{IntegratorName, Scene, SceneFile};
use crate::simulate::{self, RunError, RunRecord};
use crate::spec::{parse_positive, parse_vector, Spec};

/// Exact gravitational interaction of extended rigid bodies.
#[derive(Debug, Parser)]
#[command(name = "surfgrav", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Potential and acceleration of one body at a point of its own frame.
    ///
    /// Prints {"potential": Φ, "acceleration": [ax, ay, az]} with Φ = −G∫ρ dV/|r − r'| (negative)
    /// and a = −∇Φ (toward the body). The body's centroid is at the origin, its symmetry axis
    /// (c axis) along z; a disk lies in the x–y plane.
    Potential {
        /// The body: point:mass=M | sphere:radius=R,mass=M | spheroid:equatorial=A,polar=C,mass=M
        /// | ellipsoid:a=A,b=B,c=C,mass=M | disk:radius=R,mass=M (density=D may replace mass=M
        /// for solids).
        #[arg(long, value_name = "SPEC")]
        body: String,
        /// The field point X,Y,Z in the body frame.
        #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
        at: String,
        /// The gravitational constant.
        #[arg(
            long,
            value_name = "G",
            default_value = "1",
            allow_hyphen_values = true
        )]
        g: String,
    },
    /// Force, torque and mutual potential energy of two bodies (Conway's surface integrals).
    ///
    /// A's centroid is at the origin and B's at --position, in the world frame. An orientation
    /// is a rotation vector (axis times angle in radians) taking the body frame to the world
    /// frame. Torques are about each body's own centroid; the energy is negative. Prints
    /// force_on_a, force_on_b, torque_on_a, torque_on_b, potential_energy, method, evaluations
    /// and error_estimate (relative) as one JSON object.
    ///
    /// With --batch FILE: one configuration per line of FILE (JSON Lines, `-` for standard
    /// input) with the keys a, b, position, and optionally orientation_a, orientation_b,
    /// tolerance, g (vectors as [x, y, z]); prints one JSON object per line with the keys
    /// above and `seconds`, the best of three warm evaluations. One engine serves the batch; a
    /// bad line stops it before anything is printed, naming the line.
    Interact {
        /// Body A (same SPEC syntax as `potential --body`).
        #[arg(long = "a", value_name = "SPEC", required_unless_present = "batch")]
        body_a: Option<String>,
        /// Body B.
        #[arg(long = "b", value_name = "SPEC", required_unless_present = "batch")]
        body_b: Option<String>,
        /// B's centroid X,Y,Z in the world frame (A's centroid is at the origin).
        #[arg(
            long,
            value_name = "X,Y,Z",
            allow_hyphen_values = true,
            required_unless_present = "batch"
        )]
        position: Option<String>,
        /// A JSON Lines file of configurations (see above); `-` reads standard input.
        #[arg(long, value_name = "FILE", conflicts_with_all = ["body_a", "body_b", "position"])]
        batch: Option<String>,
        /// A's orientation as a rotation vector RX,RY,RZ (radians).
        #[arg(
            long,
            value_name = "RX,RY,RZ",
            default_value = "0,0,0",
            allow_hyphen_values = true
        )]
        orientation_a: String,
        /// B's orientation as a rotation vector RX,RY,RZ (radians).
        #[arg(
            long,
            value_name = "RX,RY,RZ",
            default_value = "0,0,0",
            allow_hyphen_values = true
        )]
        orientation_b: String,
        /// Requested relative accuracy of every output.
        #[arg(
            long,
            value_name = "T",
            default_value = "1e-12",
            allow_hyphen_values = true
        )]
        tolerance: String,
        /// The gravitational constant.
        #[arg(
            long,
            value_name = "G",
            default_value = "1",
            allow_hyphen_values = true
        )]
        g: String,
    },
    /// List the built-in scenes, or print one as TOML to start a scene file from.
    Presets {
        /// Print this preset's scene file (TOML) instead of the list.
        #[arg(long, value_name = "NAME")]
        show: Option<String>,
    },
    /// Integrate a scene and write trajectory.csv, summary.json and the paper's Figs. 2–4.
    ///
    /// SCENE is a preset name (see `surfgrav presets`) or a TOML scene file. The output folder
    /// appears whole at the end (written under a temporary name, then renamed); a failed or
    /// interrupted run leaves no folder with the final name. A progress bar is shown on a
    /// terminal only (not on a pipe, not with --quiet).
    Run {
        /// A preset name or the path of a scene file.
        #[arg(value_name = "PRESET|FILE")]
        scene: String,
        /// Output folder (must not exist, or be empty); default: a new folder named after the
        /// scene in the working directory.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// End time (overrides the scene's t_end).
        #[arg(long, value_name = "T", allow_hyphen_values = true)]
        t_end: Option<String>,
        /// Step of a fixed-step integrator (overrides integrator.step).
        #[arg(long, value_name = "DT", allow_hyphen_values = true)]
        dt: Option<String>,
        /// Integrator: rk4, leapfrog, yoshida4, yoshida6, yoshida8, dopri5, dop853.
        #[arg(long, value_name = "NAME")]
        integrator: Option<String>,
        /// Tolerance of an adaptive integrator (overrides integrator.tolerance).
        #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
        tolerance: Option<String>,
        /// No progress bar and no summary on stdout.
        #[arg(long)]
        quiet: bool,
    },
    /// Work–precision of the engine and the integrators, and the speed-up over the paper's
    /// method (module `bench`); writes Markdown tables, CSV and figures into a folder.
    Bench {
        /// Output folder (must not exist, or be empty); default: a new folder `bench`.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Small sweeps and short timing batches (seconds instead of about a minute).
        #[arg(long)]
        quick: bool,
        /// Time the paper's method again (needs python3 with scipy); otherwise the committed
        /// baseline is used.
        #[arg(long, alias = "baseline")]
        rerun_baseline: bool,
        /// Python interpreter for --rerun-baseline.
        #[arg(long, value_name = "PYTHON", default_value = "python3")]
        python: String,
        /// No progress output and no summary on stdout.
        #[arg(long)]
        quiet: bool,
    },
    /// Run a parameter sweep: one base scene, varied fields, one task folder per parameter set.
    ///
    /// SWEEP.toml names a base scene (preset or file) and the fields to vary by grids (values,
    /// linspace, logspace) or Monte Carlo draws (uniform, normal, loguniform with a seed).
    /// Writes tasks/NNNNN/ (scene.toml, summary.json, task.toml), manifest.json and
    /// results.csv; a re-run skips finished tasks. `surfgrav sweep merge DIR...` gathers the
    /// outputs of --shard runs.
    Sweep(crate::sweep::SweepArgs),
    /// Run the paper's presets and write REPORT.md with the tables and figures.
    ///
    /// The precession table and Table 2 beside the paper's values, the limiting-case
    /// comparison of the paper's Fig. 7 and the Maclaurin-disk remark, with every figure.
    Report {
        /// Output folder (must not exist, or be empty); default: a new folder `report`.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// No progress output.
        #[arg(long)]
        quiet: bool,
    },
}

/// A user error: printed as one line, exit code 2.
#[derive(Debug)]
pub struct UserError(pub String);

/// Why a command failed, with its exit code.
#[derive(Debug)]
pub enum CliError {
    /// Bad input (exit code 2): nothing was written.
    Input(String),
    /// A run started and failed (exit code 1): nothing was written.
    Failed(String),
}

impl CliError {
    /// The message (one line).
    pub fn message(&self) -> &str {
        match self {
            CliError::Input(m) | CliError::Failed(m) => m,
        }
    }

    /// The process exit code.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Input(_) => 2,
            CliError::Failed(_) => 1,
        }
    }
}

impl From<UserError> for CliError {
    fn from(e: UserError) -> Self {
        CliError::Input(e.0)
    }
}

impl From<RunError> for CliError {
    fn from(e: RunError) -> Self {
        match e {
            RunError::Input(m) => CliError::Input(m),
            RunError::Failed(m) => CliError::Failed(m),
        }
    }
}

impl<E: std::error::Error> From<E> for UserError {
    fn from(e: E) -> Self {
        UserError(e.to_string())
    }
}

#[derive(Serialize)]
struct PotentialOutput {
    potential: f64,
    acceleration: [f64; 3],
}

#[derive(Serialize)]
struct InteractOutput {
    force_on_a: [f64; 3],
    force_on_b: [f64; 3],
    torque_on_a: [f64; 3],
    torque_on_b: [f64; 3],
    potential_energy: f64,
    method: &'static str,
    evaluations: usize,
    error_estimate: f64,
    /// Batch only: the best of three warm evaluations, in seconds.
    #[serde(skip_serializing_if = "Option::is_none")]
    seconds: Option<f64>,
}

impl InteractOutput {
    fn of(r: &surfgrav_interaction::Interaction, seconds: Option<f64>) -> Self {
        Self {
            force_on_a: r.force_on_a.into(),
            force_on_b: r.force_on_b.into(),
            torque_on_a: r.torque_on_a.into(),
            torque_on_b: r.torque_on_b.into(),
            potential_energy: r.potential_energy,
            method: r.method.name(),
            evaluations: r.evaluations,
            error_estimate: r.error_estimate,
            seconds,
        }
    }
}

/// One line of an `interact --batch` file.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct BatchLine {
    a: String,
    b: String,
    position: [f64; 3],
    #[serde(default)]
    orientation_a: Option<[f64; 3]>,
    #[serde(default)]
    orientation_b: Option<[f64; 3]>,
    #[serde(default)]
    tolerance: Option<f64>,
    #[serde(default)]
    g: Option<f64>,
}

/// `interact --batch`: every line evaluated (bodies built once per spec and G, one engine per
/// tolerance, so node tables are shared), each timed as the best of three warm repeats after a
/// first call; all lines are computed before any is printed.
fn interact_batch(path: &str) -> Result<String, UserError> {
    use std::collections::HashMap;
    use std::time::Instant;
    use surfgrav_interaction::Body;
    let text = if path == "-" {
        let mut t = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut t)
            .map_err(|e| UserError(format!("--batch -: cannot read standard input: {e}")))?;
        t
    } else {
        std::fs::read_to_string(path)
            .map_err(|e| UserError(format!("--batch {path}: cannot read: {e}")))?
    };
    let mut bodies: HashMap<(String, u64), Body> = HashMap::new();
    let mut engines: HashMap<u64, InteractionEngine> = HashMap::new();
    let mut out = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let number = index + 1;
        if line.trim().is_empty() {
            continue;
        }
        let at = |message: String| UserError(format!("{path}:{number}: {message}"));
        let config: BatchLine =
            serde_json::from_str(line).map_err(|e| at(format!("not a configuration: {e}")))?;
        let g = config.g.unwrap_or(1.0);
        let tolerance = config.tolerance.unwrap_or(1e-12);
        for (name, value) in [("g", g), ("tolerance", tolerance)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(at(format!(
                    "{name} must be a positive finite number, got {value}"
                )));
            }
        }
        let vector = |name: &str, v: [f64; 3]| {
            if v.iter().all(|x| x.is_finite()) {
                Ok(Vec3::from(v))
            } else {
                Err(at(format!("{name} must be three finite numbers")))
            }
        };
        let position = vector("position", config.position)?;
        if !(position.norm_squared()).is_finite() {
            return Err(at(
                "position: values out of range: the squared distance overflows double precision"
                    .into(),
            ));
        }
        let pose_a = Pose::new(
            Vec3::zeros(),
            vector("orientation_a", config.orientation_a.unwrap_or_default())?,
        );
        let pose_b = Pose::new(
            position,
            vector("orientation_b", config.orientation_b.unwrap_or_default())?,
        );
        for (key, spec) in [("a", &config.a), ("b", &config.b)] {
            if let std::collections::hash_map::Entry::Vacant(slot) =
                bodies.entry((spec.clone(), g.to_bits()))
            {
                let body = spec
                    .parse::<Spec>()
                    .and_then(|s| s.build(g))
                    .map_err(|e| at(format!("{key}: {e}")))?
                    .into_interaction_body()
                    .map_err(|e| at(format!("{key}: {e}")))?;
                slot.insert(body);
            }
        }
        let a = &bodies[&(config.a.clone(), g.to_bits())];
        let b = &bodies[&(config.b.clone(), g.to_bits())];
        let engine = match engines.entry(tolerance.to_bits()) {
            std::collections::hash_map::Entry::Occupied(e) => e.into_mut(),
            std::collections::hash_map::Entry::Vacant(v) => v.insert(
                InteractionEngine::new(InteractionOptions {
                    relative_tolerance: tolerance,
                    ..InteractionOptions::default()
                })
                .map_err(|e| at(e.to_string()))?,
            ),
        };
        let r = engine
            .interact(a, &pose_a, b, &pose_b)
            .map_err(|e| at(e.to_string()))?;
        let mut best = f64::INFINITY;
        for _ in 0..3 {
            let started = Instant::now();
            let again = engine
                .interact(a, &pose_a, b, &pose_b)
                .map_err(|e| at(e.to_string()))?;
            best = best.min(started.elapsed().as_secs_f64());
            std::hint::black_box(again);
        }
        out.push(
            serde_json::to_string(&InteractOutput::of(&r, Some(best)))
                .map_err(|e| UserError(e.to_string()))?,
        );
    }
    if out.is_empty() {
        return Err(UserError(format!(
            "--batch {path}: no configuration in the file"
        )));
    }
    Ok(out.join("\n"))
}

/// Runs one parsed command, returning the text to print on stdout.
pub fn run(cli: Cli) -> Result<String, CliError> {
    match cli.command {
        Command::Presets { show } => presets_command(show.as_deref()),
        Command::Run {
            scene,
            out,
            t_end,
            dt,
            integrator,
            tolerance,
            quiet,
        } => {
            let overrides = Overrides::parse(t_end, dt, integrator, tolerance)?;
            run_command(&scene, out.as_deref(), &overrides, quiet)
        }
        Command::Report { out, quiet } => crate::report::report_command(out.as_deref(), quiet),
        Command::Sweep(args) => crate::sweep::sweep_command(args),
        Command::Bench {
            out,
            quick,
            rerun_baseline,
            python,
            quiet,
        } => bench_command(out.as_deref(), quick, rerun_baseline, python, quiet),
        other => Ok(field_commands(other)?),
    }
}

fn field_commands(command: Command) -> Result<String, UserError> {
    match command {
        Command::Potential { body, at, g } => {
            let g = parse_positive("--g", &g)?;
            let spec: Spec = body.parse()?;
            let is_disk = spec.kind.name == "disk";
            let body = spec.build(g)?.into_potential();
            let r = parse_vector("--at", &at)?;
            let field = body.field(&r);
            let out = PotentialOutput {
                potential: field.potential,
                acceleration: field.acceleration.into(),
            };
            if !out.potential.is_finite() || out.acceleration.iter().any(|a| !a.is_finite()) {
                return Err(UserError(if body.bounding_radius() == 0.0 {
                    "--at is the position of the point mass, where its potential is infinite"
                        .to_string()
                } else if is_disk && out.potential.is_finite() {
                    // The rim: a_ρ ≈ −2Gσ(ln(8R/d) − 2) at a distance d from it.
                    format!(
                        "--at {at} lies on the disk's rim, where the in-plane attraction is \
                         infinite (it grows like 2Gσ·ln(8R/d) at a distance d from the rim); \
                         the potential there is finite, Φ = {}: move the point off the rim",
                        significant(out.potential, 10)
                    )
                } else {
                    format!("the field at --at {at} is not finite for this body")
                }));
            }
            Ok(serde_json::to_string(&out).map_err(|e| UserError(e.to_string()))?)
        }
        Command::Interact {
            batch: Some(path), ..
        } => interact_batch(&path),
        Command::Interact {
            body_a,
            body_b,
            position,
            orientation_a,
            orientation_b,
            tolerance,
            g,
            batch: None,
        } => {
            let (body_a, body_b, position) = (
                body_a.unwrap_or_default(),
                body_b.unwrap_or_default(),
                position.unwrap_or_default(),
            );
            let g = parse_positive("--g", &g)?;
            let tolerance = parse_positive("--tolerance", &tolerance)?;
            let a = body_a
                .parse::<Spec>()
                .and_then(|s| s.build(g))
                .map_err(|e| UserError(format!("--a: {e}")))?
                .into_interaction_body()
                .map_err(|e| UserError(format!("--a: {e}")))?;
            let b = body_b
                .parse::<Spec>()
                .and_then(|s| s.build(g))
                .map_err(|e| UserError(format!("--b: {e}")))?
                .into_interaction_body()
                .map_err(|e| UserError(format!("--b: {e}")))?;
            let pose_a = Pose::new(
                Vec3::zeros(),
                parse_vector("--orientation-a", &orientation_a)?,
            );
            let pose_b = Pose::new(
                parse_vector("--position", &position)?,
                parse_vector("--orientation-b", &orientation_b)?,
            );
            // Distances whose square overflows leave every force and error estimate non-finite:
            // that is input out of range, not a tolerance to relax.
            let distance = pose_b.position().norm();
            if !(distance * distance).is_finite() {
                return Err(UserError(format!(
                    "--position {position}: values out of range: the squared distance {}² \
                     overflows double precision; rescale the units so that coordinates stay \
                     well inside 1e-150…1e150",
                    crate::spec::compact(distance)
                )));
            }
            let mut engine = InteractionEngine::new(InteractionOptions {
                relative_tolerance: tolerance,
                ..InteractionOptions::default()
            })?;
            let r = engine.interact(&a, &pose_a, &b, &pose_b)?;
            Ok(serde_json::to_string(&InteractOutput::of(&r, None))
                .map_err(|e| UserError(e.to_string()))?)
        }
        Command::Presets { .. }
        | Command::Run { .. }
        | Command::Report { .. }
        | Command::Sweep(_)
        | Command::Bench { .. } => Err(UserError("internal: not a field command".into())),
    }
}

fn presets_command(show: Option<&str>) -> Result<String, CliError> {
    match show {
        Some(name) => presets::find(name)
            .map(|p| p.toml.trim_end().to_string())
            .ok_or_else(|| {
                CliError::Input(format!(
                    "unknown preset `{name}`: expected one of {}",
                    presets::names()
                ))
            }),
        None => {
            let width = presets::PRESETS
                .iter()
                .map(|p| p.name.len())
                .max()
                .unwrap_or(0);
            let mut text: Vec<String> = presets::PRESETS
                .iter()
                .map(|p| format!("{:width$}  {}", p.name, p.summary))
                .collect();
            text.push(String::new());
            text.push(
                "Run one with `surfgrav run NAME`; print its scene file with `surfgrav presets --show NAME`."
                    .into(),
            );
            Ok(text.join("\n"))
        }
    }
}

/// Command-line overrides of a scene.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Overrides {
    /// --t-end.
    pub t_end: Option<f64>,
    /// --dt.
    pub dt: Option<f64>,
    /// --integrator.
    pub integrator: Option<IntegratorName>,
    /// --tolerance.
    pub tolerance: Option<f64>,
}

impl Overrides {
    fn parse(
        t_end: Option<String>,
        dt: Option<String>,
        integrator: Option<String>,
        tolerance: Option<String>,
    ) -> Result<Self, CliError> {
        let positive = |name: &'static str, v: Option<String>| {
            v.map(|text| parse_positive(name, &text).map_err(|e| CliError::Input(e.to_string())))
                .transpose()
        };
        let t_end = t_end
            .map(|text| match text.trim().parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(CliError::Input(format!(
                    "--t-end must be a finite number, got `{text}`"
                ))),
            })
            .transpose()?;
        Ok(Self {
            t_end,
            dt: positive("--dt", dt)?,
            integrator: integrator
                .map(|name| {
                    name.trim()
                        .to_ascii_lowercase()
                        .parse::<IntegratorName>()
                        .map_err(|e| CliError::Input(format!("--integrator: {e}")))
                })
                .transpose()?,
            tolerance: positive("--tolerance", tolerance)?,
        })
    }
}

/// Reads a preset or a scene file and applies the overrides.
///
/// # Errors
/// Neither a preset nor a readable file; the scene's own errors; bad overrides.
pub fn load_scene(which: &str, overrides: &Overrides) -> Result<Scene, CliError> {
    let path = Path::new(which);
    // A preset name wins unless a file of that name exists; a name that looks like a path is
    // read as a file (so a typo there says "cannot read").
    let preset = presets::find(which);
    let looks_like_file = path.is_file()
        || (preset.is_none()
            && (which.ends_with(".toml")
                || which.contains(std::path::MAIN_SEPARATOR)
                || which.contains('/')
                || path.exists()));
    let mut scene = if looks_like_file {
        let (file, source) = SceneFile::read(path).map_err(|e| CliError::Input(e.to_string()))?;
        file.build(&source, &path.display().to_string())
            .map_err(|e| CliError::Input(e.to_string()))?
    } else {
        preset
            .ok_or_else(|| {
                CliError::Input(format!(
                    "`{which}` is neither a preset ({}) nor a scene file",
                    presets::names()
                ))
            })?
            .scene()
            .map_err(|e| CliError::Input(e.to_string()))?
    };
    scene
        .override_with(
            overrides.t_end,
            overrides.dt,
            overrides.integrator,
            overrides.tolerance,
        )
        .map_err(|e| CliError::Input(e.to_string()))?;
    Ok(scene)
}

/// `x` with `digits` significant digits: positional between 1e-3 and 1e6 (`18.9638`,
/// `0.00123457`), scientific outside (`1.23457e-9`), `0` for zero.
pub fn significant(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if x == 0.0 || !x.is_finite() {
        return x.to_string();
    }
    let magnitude = x.abs().log10().floor() as i32;
    if (-3..6).contains(&magnitude) {
        let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.prec$e}", prec = digits - 1)
    }
}

/// A progress bar on stderr when it is a terminal and not `quiet`; hidden otherwise.
pub fn progress_bar(quiet: bool, length: u64, message: &str) -> ProgressBar {
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::with_draw_target(Some(length), ProgressDrawTarget::stderr())
    };
    if let Ok(style) = ProgressStyle::with_template(
        "{msg} [{elapsed_precise}] {wide_bar} {percent:>3}% (eta {eta})",
    ) {
        bar.set_style(style);
    }
    bar.set_message(message.to_string());
    bar
}

fn run_command(
    which: &str,
    out: Option<&Path>,
    overrides: &Overrides,
    quiet: bool,
) -> Result<String, CliError> {
    let scene = load_scene(which, overrides)?;
    // What was done to read a mesh (its size, its frame): one line per body.
    if !quiet {
        for note in &scene.notes {
            eprintln!("{note}");
        }
    }
    scene
        .integrator
        .make()
        .map_err(|e| CliError::Input(e.to_string()))?;
    // The output folder is checked and created (hidden, under a temporary name) before the
    // computation, so a bad --out costs nothing and the trajectory can be streamed into it.
    let folder = output::choose_folder(out, &scene.name).map_err(|e| CliError::Input(e.into()))?;
    let staging = output::Staging::new(&folder).map_err(|e| CliError::Input(e.into()))?;
    let prepared = simulate::prepare(&scene)?;
    let mut csv = output::TrajectoryWriter::create(&staging.path().join("trajectory.csv"))
        .map_err(|e| CliError::Failed(e.into()))?;
    const TICKS: u64 = 1000;
    let bar = progress_bar(quiet, TICKS, &scene.name);
    let span = scene.t_end - scene.t_start;
    let mut last_tick = 0;
    let record = simulate::simulate(
        &scene,
        &prepared,
        &mut |t| {
            let tick = (((t - scene.t_start) / span).clamp(0.0, 1.0) * TICKS as f64) as u64;
            if tick != last_tick {
                last_tick = tick;
                bar.set_position(tick);
            }
        },
        &mut |row| csv.write(row),
    );
    bar.finish_and_clear();
    let record = record?;
    csv.finish().map_err(|e| CliError::Failed(e.into()))?;
    output::write_summary(&record, &staging.path().join("summary.json"))
        .map_err(|e| CliError::Failed(e.into()))?;
    let figures = figures::write_all(&record, staging.path())
        .map_err(|e| CliError::Failed(format!("figures: {e}")))?;
    let folder = staging.commit().map_err(|e| CliError::Failed(e.into()))?;
    if quiet {
        return Ok(String::new());
    }
    let mut files = vec!["trajectory.csv".to_string(), "summary.json".to_string()];
    files.extend(
        figures
            .iter()
            .filter_map(|f| f.file_name().map(|n| n.to_string_lossy().into_owned())),
    );
    Ok(run_digest(&record, &folder, &files))
}

fn bench_command(
    out: Option<&Path>,
    quick: bool,
    rerun_baseline: bool,
    python: String,
    quiet: bool,
) -> Result<String, CliError> {
    let folder = output::choose_folder(out, "bench").map_err(|e| CliError::Input(e.into()))?;
    let staging = output::Staging::new(&folder).map_err(|e| CliError::Failed(e.into()))?;
    let mut options = crate::bench::BenchOptions::new(staging.path());
    if quick {
        options = options.quick();
    }
    options.rerun_baseline = rerun_baseline;
    options.python = python;
    // A spinner with the current step on a terminal; nothing on a pipe or with --quiet.
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr())
    };
    let report = crate::bench::run_bench(&options, &mut |line| {
        bar.set_message(line.to_string());
        bar.tick();
    });
    bar.finish_and_clear();
    let report = report.map_err(|e| CliError::Failed(format!("bench: {e}")))?;
    let folder = staging.commit().map_err(|e| CliError::Failed(e.into()))?;
    if quiet {
        return Ok(String::new());
    }
    let mut lines = vec![format!(
        "wrote {}/: {} files ({}; baseline: {})",
        folder.display(),
        report.files.len(),
        if quick { "quick sweeps" } else { "full sweeps" },
        report.baseline_source
    )];
    // A debug build times surfgrav ~30x too slow: say so beside the ratios, not only in files.
    for warning in &report.warnings {
        lines.push(format!("warning: {warning}"));
    }
    for s in &report.speedups {
        lines.push(format!(
            "{}: {:.3e} s (paper's method) / {:.3e} s (surfgrav) = {:.0}×",
            s.task, s.baseline_seconds, s.surfgrav_seconds, s.ratio
        ));
    }
    Ok(lines.join("\n"))
}

/// What `surfgrav run` prints: the folder, its files and the key numbers.
pub fn run_digest(record: &RunRecord, folder: &Path, files: &[String]) -> String {
    let units = figures::Units::of(&record.scene);
    // Significant digits, not fixed decimals: an SI run's Ω_p of 1e-9 ′/s must not print 0.000.
    let show = |x: Option<f64>, unit: &str| {
        x.map_or("n/a".to_string(), |v| {
            format!("{}{unit}", significant(v, 6))
        })
    };
    let time = units.time_suffix();
    let length = units.length_suffix();
    let o = &record.orbit;
    let mut lines = vec![
        format!("wrote {}/: {}", folder.display(), files.join(", ")),
        format!(
            "{}: {} steps, {} force evaluations, {:.3} s wall ({}, {}); {} rows written ({})",
            record.scene.name,
            record.summary.steps,
            record.summary.force_evaluations,
            record.wall_seconds,
            figures::integrator_label(record),
            record.method,
            record.rows_written,
            record.output.rule()
        ),
        format!(
            "precession ψ_p = {}, Ω_p = {}; T_r = {}, T_ψ = {}; minimum separation {}",
            show(o.precession_angle_deg, "°"),
            show(o.precession_rate_arcmin, &format!("′ per {}", units.time_singular)),
            show(o.radial_period, &time),
            show(o.azimuthal_period, &time),
            show(o.minimum_separation, &length)
        ),
        format!(
            "energy: σ(ΔE) = {:.2e} per step, max |E − E0|/|E0| = {:.2e}; angular momentum: σ(ΔJ) = {:.2e}, max drift {:.2e}",
            record.energy.step_changes.standard_deviation,
            record.energy.max_relative_drift,
            record.angular_momentum.step_changes.standard_deviation,
            record.angular_momentum.max_relative_drift
        ),
    ];
    if let Some(t) = record.contact() {
        lines.push(format!(
            "the bodies touched at t = {}{time}: the run stopped there",
            crate::spec::compact(t)
        ));
    }
    if let Some(t) = record.escape() {
        lines.push(format!(
            "the bodies escaped each other at t = {}{time}: the run stopped there",
            crate::spec::compact(t)
        ));
    }
    lines.join("\n")
}
