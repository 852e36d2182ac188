//! Writing a run to a folder, whole or not at all.
//!
//! Everything is written into a hidden sibling folder `.NAME.partial-PID` and renamed to its
//! final name only after the last file is closed (a rename within one directory is atomic on
//! POSIX file systems). A run that fails removes its partial folder; one that is killed leaves
//! only the hidden `.partial` folder, never a folder with the final name, and the next run to
//! the same name removes it (when its process is gone).
//!
//! Files of a run folder:
//! - `trajectory.csv`: header row, then one row per written sample: `t`, `xa, ya, za`,
//!   `xb, yb, zb`, `vxa, vya, vza`, `vxb, vyb, vzb` (world frame), `separation`, `energy`
//!   ($E = T + V$, spins included), `angular_momentum` ($|\mathbf J|$ about the origin, orbital
//!   and spin), then `qwa, qxa, qya, qza, qwb, qxb, qyb, qzb` (attitude quaternions, scalar
//!   first, body → world), `wxa, wya, wza, wxb, wyb, wzb` (angular velocities, world frame),
//!   `jx, jy, jz` (total angular momentum $\mathbf J$); shortest round-trip decimal form. Streamed as the run goes ([`TrajectoryWriter`]); which samples are written
//!   follows [`OutputPlan::of`] (by default at most [`DEFAULT_MAX_ROWS`] rows, or
//!   [`DEFAULT_MAX_ADAPTIVE_ROWS`] for adaptive methods).
//! - `summary.json`: see [`Summary`].
//! - figures as PNG and SVG (see [`crate::figures`]).

use std::fmt::Write as _;
use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;
use surfgrav_dynamics::ConservationStatistics;
use surfgrav_potentials::Real;

use crate::scene::{IntegratorChoice, OutputCadence, Scene};
use crate::simulate::{OutputRow, RunRecord};

/// Statistics of one conserved quantity in `summary.json`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ConservationSummary {
    /// Value at the first sample.
    pub initial: Real,
    /// Mean per-step change.
    pub mean_step_change: Real,
    /// Sample standard deviation of the per-step changes.
    pub std_step_change: Real,
    /// Standard error σ/√N.
    pub std_error: Real,
    /// Least-squares slope of the per-step change against time.
    pub slope: Real,
    /// Largest |x − x₀|/|x₀|.
    pub max_relative_drift: Real,
}

impl From<&ConservationStatistics> for ConservationSummary {
    fn from(s: &ConservationStatistics) -> Self {
        Self {
            initial: s.initial,
            mean_step_change: s.step_changes.mean,
            std_step_change: s.step_changes.standard_deviation,
            std_error: s.step_changes.standard_error,
            slope: s.step_changes.slope,
            max_relative_drift: s.max_relative_drift,
        }
    }
}

/// How `trajectory.csv` was written, in `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputSummary {
    /// Rows written (header excluded).
    pub rows: usize,
    /// Every n-th step was written (`null` with an interval).
    pub every: Option<usize>,
    /// Rows at $t_0 + k\\,\Delta$ from the dense output (`null` with `every`).
    pub interval: Option<Real>,
    /// `scene` (the scene file's `[output]`) or `default` (chosen from the run's length).
    pub chosen_by: &'static str,
    /// The rule, in words.
    pub rule: String,
}

/// The contents of `summary.json` (keys in this order; absent quantities are `null`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Scene name.
    pub scene: String,
    /// Time reached (the scene's end time, or the contact time).
    pub t_end: Real,
    /// Accepted steps.
    pub steps: usize,
    /// Force evaluations.
    pub force_evaluations: usize,
    /// Seconds for model building and integration.
    pub wall_seconds: Real,
    /// Smallest centroid separation.
    pub min_separation: Option<Real>,
    /// $T_r$.
    pub radial_period: Option<Real>,
    /// $T\_\psi$.
    pub azimuthal_period: Option<Real>,
    /// $\psi_p$ in degrees.
    pub precession_angle_deg: Option<Real>,
    /// $\Omega_p$ in arcminutes per time unit.
    pub precession_rate_arcmin: Option<Real>,
    /// Energy statistics (every step, whatever the output cadence).
    pub energy: ConservationSummary,
    /// Angular-momentum statistics (every step).
    pub angular_momentum: ConservationSummary,
    /// How the trajectory was written.
    pub output: OutputSummary,
    /// Which equations ran: `translation` (attitudes turn uniformly with their spins: every
    /// torque vanishes along the motion by symmetry) or `rotation` (Euler's equations
    /// integrated with the orbit).
    pub motion: MotionSummary,
    /// Largest $|\mathbf J - \mathbf J_0|/|\mathbf J_0|$ of the total angular-momentum vector.
    pub angular_momentum_vector_max_relative_drift: Real,
    /// Largest change of the linear momentum relative to $m_A|\dot{\mathbf R}\_A| + m_B|\dot{\mathbf R}\_B|$ at the start.
    pub linear_momentum_max_relative_drift: Real,
    /// Per body (A, B): spin rate, obliquity, libration.
    pub spins: [SpinSummary; 2],
    /// The mutual orbit's osculating elements and precession rates.
    pub mutual_orbit: MutualOrbitSummary,
}

/// The motion path in `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionSummary {
    /// `translation` or `rotation`.
    pub path: &'static str,
    /// Why.
    pub reason: &'static str,
}

/// A range in `summary.json`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RangeSummary {
    /// Smallest value.
    pub min: Real,
    /// Largest value.
    pub max: Real,
}

fn range(r: Option<surfgrav_dynamics::Range>) -> Option<RangeSummary> {
    r.map(|r| RangeSummary {
        min: r.min,
        max: r.max,
    })
}

/// One body's spin in `summary.json` (angles in degrees).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpinSummary {
    /// $|\boldsymbol\omega|$ range (radians per time unit).
    pub spin_rate: Option<RangeSummary>,
    /// Angle between the spin axis and the mutual orbit's normal.
    pub obliquity_deg: Option<RangeSummary>,
    /// Angle from the line of centres to the long axis in the orbit plane (elongated bodies).
    pub libration_deg: Option<RangeSummary>,
    /// Mean period of the libration.
    pub libration_period: Option<Real>,
    /// The long axis turns through the line of centres (no libration range then).
    pub circulating: bool,
}

/// The mutual orbit in `summary.json`: osculating elements for $\mu = G(m_A + m_B)$ in the frame
/// of the initial total angular momentum (angles in degrees).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MutualOrbitSummary {
    /// a.
    pub semi_major_axis: Option<RangeSummary>,
    /// e.
    pub eccentricity: Option<RangeSummary>,
    /// i.
    pub inclination_deg: Option<RangeSummary>,
    /// Ω (unwrapped).
    pub node_deg: Option<RangeSummary>,
    /// ω (unwrapped).
    pub pericentre_deg: Option<RangeSummary>,
    /// dΩ/dt in degrees per time unit.
    pub nodal_precession_rate_deg: Option<Real>,
    /// dϖ/dt in degrees per time unit.
    pub apsidal_precession_rate_deg: Option<Real>,
}

impl Summary {
    /// The summary of a run.
    pub fn of(run: &RunRecord) -> Self {
        let o = &run.orbit;
        let (every, interval) = match run.output.cadence {
            Cadence::Every(n) => (Some(n), None),
            Cadence::Interval(d) => (None, Some(d)),
        };
        Self {
            scene: run.scene.name.clone(),
            t_end: run.t_reached(),
            steps: run.summary.steps,
            force_evaluations: run.summary.force_evaluations,
            wall_seconds: run.wall_seconds,
            min_separation: o.minimum_separation,
            radial_period: o.radial_period,
            azimuthal_period: o.azimuthal_period,
            precession_angle_deg: o.precession_angle_deg,
            precession_rate_arcmin: o.precession_rate_arcmin,
            energy: (&run.energy).into(),
            angular_momentum: (&run.angular_momentum).into(),
            output: OutputSummary {
                rows: run.rows_written,
                every,
                interval,
                chosen_by: if run.output.by_default {
                    "default"
                } else {
                    "scene"
                },
                rule: run.output.rule(),
            },
            motion: MotionSummary {
                path: if run.path.is_rotation() {
                    "rotation"
                } else {
                    "translation"
                },
                reason: run.path.reason(),
            },
            angular_momentum_vector_max_relative_drift: run.angular_momentum_vector_drift,
            linear_momentum_max_relative_drift: run.linear_momentum_drift,
            spins: run.spin_orbit.bodies.map(|b| SpinSummary {
                spin_rate: range(b.spin_rate),
                obliquity_deg: range(b.obliquity),
                libration_deg: range(b.libration),
                libration_period: b.libration_period,
                circulating: b.circulating,
            }),
            mutual_orbit: {
                let o = &run.spin_orbit.orbit;
                MutualOrbitSummary {
                    semi_major_axis: range(o.semi_major_axis),
                    eccentricity: range(o.eccentricity),
                    inclination_deg: range(o.inclination),
                    node_deg: range(o.node),
                    pericentre_deg: range(o.pericentre),
                    nodal_precession_rate_deg: o.nodal_precession_rate,
                    apsidal_precession_rate_deg: o.apsidal_precession_rate,
                }
            },
        }
    }
}

/// Most rows the default output cadence writes for a fixed-step method (about 3 MB of CSV),
/// plus the last state. Its rows are the integrator's own samples, whose energies the
/// diagnostics compute anyway.
pub const DEFAULT_MAX_ROWS: usize = 10_000;

/// Most rows the default output cadence writes for an adaptive method, plus the last state:
/// each row is a dense-output state whose energy costs one more interaction, so the rows'
/// cost grows with their number while the integration's does not.
pub const DEFAULT_MAX_ADAPTIVE_ROWS: usize = 2_000;

/// Which samples become rows of `trajectory.csv`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cadence {
    /// Every n-th step (the integrator's own samples, exact), and the last.
    Every(usize),
    /// The states at $t_0 + k\\,\Delta$ from the integrator's dense output, and the last.
    Interval(Real),
}

/// The output cadence of a run and whether the scene chose it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputPlan {
    /// The cadence.
    pub cadence: Cadence,
    /// Chosen by [`OutputPlan::of`] from the run's length (no `every` or `interval` given).
    pub by_default: bool,
}

impl OutputPlan {
    /// The scene's `[output] every` or `interval`; by default, for a fixed step h over a span
    /// T, every $\lceil (T/h) / 10^4 \rceil$-th step (every step when there are at most
    /// [`DEFAULT_MAX_ROWS`]), and for an adaptive method the dense output at the smallest
    /// interval of the form 1, 2 or 5 × 10^k that gives at most [`DEFAULT_MAX_ADAPTIVE_ROWS`]
    /// rows.
    pub fn of(scene: &Scene) -> Self {
        let span = scene.t_end - scene.t_start;
        let max_rows = DEFAULT_MAX_ROWS as Real;
        match scene.output {
            OutputCadence::Every(n) => Self {
                cadence: Cadence::Every(n.max(1)),
                by_default: false,
            },
            OutputCadence::Interval(d) => Self {
                cadence: Cadence::Interval(d),
                by_default: false,
            },
            OutputCadence::Default => Self {
                cadence: match scene.integrator {
                    IntegratorChoice::Fixed { step, .. } => {
                        let steps = (span / step).ceil();
                        // Saturates for absurd step counts; at least every step.
                        Cadence::Every(((steps / max_rows).ceil() as usize).max(1))
                    }
                    IntegratorChoice::Adaptive { .. } => Cadence::Interval(round_up_to_1_2_5(
                        span / DEFAULT_MAX_ADAPTIVE_ROWS as Real,
                    )),
                },
                by_default: true,
            },
        }
    }

    /// The rule in words, for `summary.json`.
    pub fn rule(&self) -> String {
        let what = match self.cadence {
            Cadence::Every(1) => "every step".to_string(),
            Cadence::Every(n) => format!("one step in {n}"),
            Cadence::Interval(d) => format!(
                "the dense output at t_start + k·{}",
                crate::spec::compact(d)
            ),
        };
        if self.by_default {
            let most = match self.cadence {
                Cadence::Every(_) => DEFAULT_MAX_ROWS,
                Cadence::Interval(_) => DEFAULT_MAX_ADAPTIVE_ROWS,
            };
            format!(
                "{what} and the last state (default: at most {most} rows; set [output] every or interval to change it); diagnostics use every step"
            )
        } else {
            format!("{what} and the last state ([output] of the scene); diagnostics use every step")
        }
    }
}

/// The smallest number of the form 1, 2 or 5 × 10^k (as its nearest double) at or above `x`.
fn round_up_to_1_2_5(x: Real) -> Real {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let k = x.log10().floor() as i32;
    for exponent in [k - 1, k, k + 1] {
        for mantissa in [1, 2, 5] {
            let candidate: Real = format!("{mantissa}e{exponent}")
                .parse()
                .unwrap_or(Real::NAN);
            if candidate >= x {
                return candidate;
            }
        }
    }
    x
}

/// The CSV header of `trajectory.csv`.
pub const TRAJECTORY_HEADER: &str =
    "t,xa,ya,za,xb,yb,zb,vxa,vya,vza,vxb,vyb,vzb,separation,energy,angular_momentum,qwa,qxa,qya,qza,qwb,qxb,qyb,qzb,wxa,wya,wza,wxb,wyb,wzb,jx,jy,jz";

/// Why a run's folder or files could not be written. The messages name the path and say what
/// to change.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// Writing a file failed.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The summary could not be serialised.
    #[error(transparent)]
    Summary(#[from] serde_json::Error),
    /// `--out` was given as an empty path.
    #[error("--out must not be empty")]
    EmptyOut,
    /// `--out` exists and is not an empty folder.
    #[error(
        "--out {} already exists and is not an empty folder: choose a new folder or remove it",
        out.display()
    )]
    OutExists {
        /// The path given.
        out: PathBuf,
    },
    /// An ancestor of `--out` is a file.
    #[error(
        "--out {}: {} is a file, not a folder: choose an output path inside a folder",
        out.display(),
        ancestor.display()
    )]
    AncestorIsFile {
        /// The path given.
        out: PathBuf,
        /// The ancestor that is a file.
        ancestor: PathBuf,
    },
    /// The folder that would hold `--out` does not exist.
    #[error(
        "--out {}: the folder {} does not exist: create it first (mkdir -p {}) or choose another path",
        out.display(),
        parent.display(),
        parent.display()
    )]
    OutParentMissing {
        /// The path given.
        out: PathBuf,
        /// Its missing parent.
        parent: PathBuf,
    },
    /// Without `--out`, the scene's name cannot name the default folder.
    #[error(
        "the scene name `{name}` cannot name the default output folder (letters, digits, \
         -, _, . only, not starting with .): give --out DIR"
    )]
    UnsafeName {
        /// The scene's name.
        name: String,
    },
    /// The target path has no final component.
    #[error("{} is not a folder name", target.display())]
    NotAFolderName {
        /// The target.
        target: PathBuf,
    },
    /// The folder that would hold the target does not exist.
    #[error("the parent folder {} does not exist: create it first", parent.display())]
    ParentMissing {
        /// The missing folder.
        parent: PathBuf,
    },
    /// A stale temporary folder of this process could not be removed.
    #[error("cannot clear {}: {source}", path.display())]
    Clear {
        /// The folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The temporary folder could not be created.
    #[error("cannot create {}: {source}", path.display())]
    Create {
        /// The folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// An empty folder given as `--out` could not be replaced.
    #[error("cannot replace {} (it must be empty): {source}", path.display())]
    Replace {
        /// The folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The finished folder could not be renamed to its final name.
    #[error("cannot rename {} to {}: {source}", from.display(), to.display())]
    Rename {
        /// The temporary folder.
        from: PathBuf,
        /// The final name.
        to: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// For callers whose own errors are still text (the sweep's tasks, the run's row sink).
impl From<OutputError> for String {
    fn from(e: OutputError) -> Self {
        e.to_string()
    }
}

/// `trajectory.csv`, written row by row as the run goes (nothing is held in memory).
pub struct TrajectoryWriter {
    writer: BufWriter<fs::File>,
    path: PathBuf,
}

impl TrajectoryWriter {
    /// Creates the file and writes the header.
    ///
    /// # Errors
    /// I/O errors, with the path.
    pub fn create(path: &Path) -> Result<Self, OutputError> {
        let fail = |source| OutputError::Write {
            path: path.to_path_buf(),
            source,
        };
        let mut writer = BufWriter::new(fs::File::create(path).map_err(fail)?);
        writeln!(writer, "{TRAJECTORY_HEADER}").map_err(fail)?;
        Ok(Self {
            writer,
            path: path.to_path_buf(),
        })
    }

    /// Appends one row (shortest round-trip decimals).
    ///
    /// # Errors
    /// I/O errors, with the path.
    pub fn write(&mut self, row: &OutputRow) -> Result<(), OutputError> {
        let (a, b) = (&row.state.body_a, &row.state.body_b);
        let mut line = String::with_capacity(320);
        let values = std::iter::once(row.time)
            .chain(a.position.iter().copied())
            .chain(b.position.iter().copied())
            .chain(a.velocity.iter().copied())
            .chain(b.velocity.iter().copied())
            .chain([row.state.separation(), row.energy, row.angular_momentum])
            .chain([a, b].into_iter().flat_map(|body| {
                let q = body.orientation.quaternion();
                [q.w, q.i, q.j, q.k]
            }))
            .chain(a.angular_velocity.iter().copied())
            .chain(b.angular_velocity.iter().copied())
            .chain(row.angular_momentum_vector.iter().copied());
        for (k, x) in values.enumerate() {
            if k > 0 {
                line.push(',');
            }
            let _ = write!(line, "{x}");
        }
        writeln!(self.writer, "{line}").map_err(|source| OutputError::Write {
            path: self.path.clone(),
            source,
        })
    }

    /// Flushes and closes the file.
    ///
    /// # Errors
    /// I/O errors, with the path.
    pub fn finish(mut self) -> Result<(), OutputError> {
        self.writer.flush().map_err(|source| OutputError::Write {
            path: self.path.clone(),
            source,
        })
    }
}

/// Writes `summary.json`.
///
/// # Errors
/// I/O errors, with the path.
pub fn write_summary(run: &RunRecord, path: &Path) -> Result<(), OutputError> {
    let text = serde_json::to_string_pretty(&Summary::of(run))?;
    fs::write(path, text + "\n").map_err(|source| OutputError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// Whether `name` can name a folder as it is: letters, digits, `-`, `_`, `.` (ASCII), not
/// starting with `.`.
pub fn folder_safe(name: &str) -> bool {
    !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
        && !name.starts_with('.')
}

/// The folder that must hold `out`: it must exist and be a folder. Says which ancestor is a
/// file, or which folder is missing.
fn check_parent(out: &Path) -> Result<(), OutputError> {
    let Some(parent) = out.parent().filter(|p| !p.as_os_str().is_empty()) else {
        return Ok(());
    };
    for ancestor in parent.ancestors() {
        if ancestor.as_os_str().is_empty() {
            break;
        }
        match fs::metadata(ancestor) {
            Ok(meta) if meta.is_dir() => {
                if ancestor == parent {
                    return Ok(());
                }
                break;
            }
            Ok(_) => {
                return Err(OutputError::AncestorIsFile {
                    out: out.to_path_buf(),
                    ancestor: ancestor.to_path_buf(),
                })
            }
            Err(_) => continue,
        }
    }
    Err(OutputError::OutParentMissing {
        out: out.to_path_buf(),
        parent: parent.to_path_buf(),
    })
}

/// Where a run or report goes: `out` if given (it must not exist, or be an empty folder, and
/// its parent must be an existing folder), otherwise `NAME` in the working directory, or
/// `NAME-2`, `NAME-3`, … if that exists (`NAME` must then be folder-safe, see
/// [`folder_safe`]). Checked before anything is computed.
///
/// # Errors
/// An explicit `out` that exists and is not an empty folder, or whose parent is missing or a
/// file; a name that cannot name a folder without `--out`.
pub fn choose_folder(out: Option<&Path>, name: &str) -> Result<PathBuf, OutputError> {
    if let Some(out) = out {
        if out.as_os_str().is_empty() {
            return Err(OutputError::EmptyOut);
        }
        if out.exists() {
            let empty = out.is_dir() && fs::read_dir(out).is_ok_and(|mut d| d.next().is_none());
            if !empty {
                return Err(OutputError::OutExists {
                    out: out.to_path_buf(),
                });
            }
        }
        check_parent(out)?;
        return Ok(out.to_path_buf());
    }
    if !folder_safe(name) {
        return Err(OutputError::UnsafeName { name: name.into() });
    }
    let base = PathBuf::from(name);
    if !base.exists() {
        return Ok(base);
    }
    for k in 2.. {
        let candidate = PathBuf::from(format!("{name}-{k}"));
        if !candidate.exists() {
            return Ok(candidate);
        }
    }
    unreachable!("some numbered folder name is free")
}

/// A folder being written under a temporary name; renamed by [`Staging::commit`], removed on
/// drop otherwise.
#[derive(Debug)]
pub struct Staging {
    temporary: PathBuf,
    target: PathBuf,
    committed: bool,
}

/// Removes the partial folders `.NAME.partial-PID` in `parent` left by runs that were killed
/// (Ctrl-C, a crash): those whose process no longer exists. Where processes cannot be looked up
/// (no `/proc`), or a folder cannot be removed, nothing is done: a run in progress is never
/// touched, and a leftover is only clutter.
fn remove_stale_partials(parent: &Path, name: &str) {
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return;
    }
    let prefix = format!(".{name}.partial-");
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = file_name
            .to_str()
            .and_then(|n| n.strip_prefix(&prefix))
            .and_then(|pid| pid.parse::<u32>().ok())
        else {
            continue;
        };
        if pid != std::process::id() && !proc.join(pid.to_string()).exists() {
            let _ = fs::remove_dir_all(entry.path());
        }
    }
}

impl Staging {
    /// Creates the temporary sibling of `target`, after removing the partial folders of the
    /// same name left by killed runs.
    ///
    /// # Errors
    /// I/O errors, with the path.
    pub fn new(target: &Path) -> Result<Self, OutputError> {
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .ok_or_else(|| OutputError::NotAFolderName {
                target: target.to_path_buf(),
            })?;
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !parent.is_dir() {
            return Err(OutputError::ParentMissing { parent });
        }
        remove_stale_partials(&parent, &name);
        let temporary = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if temporary.exists() {
            fs::remove_dir_all(&temporary).map_err(|source| OutputError::Clear {
                path: temporary.clone(),
                source,
            })?;
        }
        fs::create_dir(&temporary).map_err(|source| OutputError::Create {
            path: temporary.clone(),
            source,
        })?;
        Ok(Self {
            temporary,
            target: target.to_path_buf(),
            committed: false,
        })
    }

    /// The folder to write into.
    pub fn path(&self) -> &Path {
        &self.temporary
    }

    /// The final folder.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Renames the temporary folder to its final name.
    ///
    /// # Errors
    /// I/O errors (the final name taken meanwhile by a non-empty folder), with both paths.
    pub fn commit(mut self) -> Result<PathBuf, OutputError> {
        if self.target.is_dir() {
            // An empty folder given as --out (checked before the run): replace it.
            fs::remove_dir(&self.target).map_err(|source| OutputError::Replace {
                path: self.target.clone(),
                source,
            })?;
        }
        fs::rename(&self.temporary, &self.target).map_err(|source| OutputError::Rename {
            from: self.temporary.clone(),
            to: self.target.clone(),
            source,
        })?;
        self.committed = true;
        Ok(self.target.clone())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.temporary);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;
    use crate::scene::IntegratorName;

    #[test]
    fn default_cadence_is_proportionate_and_round() {
        for (x, rounded) in [
            (0.03, 0.05),
            (0.05, 0.05),
            (0.011, 0.02),
            (7.0, 10.0),
            (1e-7, 1e-7),
        ] {
            assert_eq!(round_up_to_1_2_5(x), rounded, "{x}");
        }
        let mut scene = presets::find("paper-2s").unwrap().scene().unwrap();
        // 3,000 steps: every step.
        assert_eq!(OutputPlan::of(&scene).cadence, Cadence::Every(1));
        // 10⁶ steps: one in 100, 10,000 rows.
        scene.override_with(Some(1e5), None, None, None).unwrap();
        assert_eq!(OutputPlan::of(&scene).cadence, Cadence::Every(100));
        // Adaptive over 300: 300/2,000 = 0.15, rounded up to 0.2 (1,501 rows).
        scene
            .override_with(Some(300.0), None, Some(IntegratorName::Dop853), Some(1e-10))
            .unwrap();
        let plan = OutputPlan::of(&scene);
        assert_eq!(plan.cadence, Cadence::Interval(0.2));
        assert!(plan.by_default && plan.rule().contains("at most 2000 rows"));
        // The scene's own choice is kept.
        scene.output = OutputCadence::Every(7);
        assert_eq!(OutputPlan::of(&scene).cadence, Cadence::Every(7));
        assert!(!OutputPlan::of(&scene).by_default);
    }

    /// A killed run's partial folder (its process gone) is removed by the next run to the same
    /// name; a live process's (PID 1) and other names' are kept.
    #[test]
    fn stale_partial_folders_are_removed_live_ones_kept() {
        if !Path::new("/proc/self").exists() {
            return;
        }
        let root = std::env::temp_dir().join(format!("surfgrav-staging-{}", std::process::id()));
        let _ = fs::remove_dir_all(&root);
        fs::create_dir_all(&root).unwrap();
        // PIDs stay below 2^22 on Linux: this one belongs to no process.
        let stale = root.join(".run.partial-4999999");
        let live = root.join(".run.partial-1");
        let other = root.join(".other.partial-4999999");
        for d in [&stale, &live, &other] {
            fs::create_dir(d).unwrap();
            fs::write(d.join("trajectory.csv"), "t\n").unwrap();
        }
        let staging = Staging::new(&root.join("run")).unwrap();
        assert!(!stale.exists());
        assert!(live.exists() && other.exists());
        assert!(staging.path().exists());
        staging.commit().unwrap();
        assert!(root.join("run").is_dir());
        fs::remove_dir_all(&root).unwrap();
    }
}
