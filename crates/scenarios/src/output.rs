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
//!   ($E = T + V$), `angular_momentum` ($|\mathbf J|$ about the origin); shortest round-trip
//!   decimal form.
//! - `summary.json`: see [`Summary`].
//! - figures as PNG and SVG (see [`crate::figures`]).

use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;
use surfgrav_dynamics::ConservationStatistics;
use surfgrav_potentials::Real;

use crate::simulate::RunRecord;

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
    /// $T_\psi$.
    pub azimuthal_period: Option<Real>,
    /// $\psi_p$ in degrees.
    pub precession_angle_deg: Option<Real>,
    /// $\Omega_p$ in arcminutes per time unit.
    pub precession_rate_arcmin: Option<Real>,
    /// Energy statistics.
    pub energy: ConservationSummary,
    /// Angular-momentum statistics.
    pub angular_momentum: ConservationSummary,
}

impl Summary {
    /// The summary of a run.
    pub fn of(run: &RunRecord) -> Self {
        let o = &run.orbit;
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
        }
    }
}

/// The CSV header of `trajectory.csv`.
pub const TRAJECTORY_HEADER: &str =
    "t,xa,ya,za,xb,yb,zb,vxa,vya,vza,vxb,vyb,vzb,separation,energy,angular_momentum";

/// Writes `trajectory.csv` (every `scene.output_every`-th sample and the last one).
///
/// # Errors
/// I/O errors, with the path.
pub fn write_trajectory(run: &RunRecord, path: &Path) -> Result<(), String> {
    let fail = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
    let mut w = BufWriter::new(fs::File::create(path).map_err(fail)?);
    writeln!(w, "{TRAJECTORY_HEADER}").map_err(fail)?;
    let every = run.scene.output_every.max(1);
    let last = run.samples.len().saturating_sub(1);
    for (k, s) in run.samples.iter().enumerate() {
        if k % every != 0 && k != last {
            continue;
        }
        let (a, b) = (&s.state.body_a, &s.state.body_b);
        let mut row = vec![s.time];
        row.extend(a.position.iter());
        row.extend(b.position.iter());
        row.extend(a.velocity.iter());
        row.extend(b.velocity.iter());
        row.push(s.state.separation());
        row.push(run.energies[k]);
        row.push(run.angular_momenta[k]);
        let text: Vec<String> = row.iter().map(|x| x.to_string()).collect();
        writeln!(w, "{}", text.join(",")).map_err(fail)?;
    }
    w.flush().map_err(fail)
}

/// Writes `summary.json`.
///
/// # Errors
/// I/O errors, with the path.
pub fn write_summary(run: &RunRecord, path: &Path) -> Result<(), String> {
    let text = serde_json::to_string_pretty(&Summary::of(run)).map_err(|e| e.to_string())?;
    fs::write(path, text + "\n").map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Where a run or report goes: `out` if given (it must not exist, or be an empty folder),
/// otherwise `NAME` in the working directory, or `NAME-2`, `NAME-3`, … if that exists.
///
/// # Errors
/// An explicit `out` that exists and is not an empty folder.
pub fn choose_folder(out: Option<&Path>, name: &str) -> Result<PathBuf, String> {
    if let Some(out) = out {
        if out.exists() {
            let empty = out.is_dir() && fs::read_dir(out).is_ok_and(|mut d| d.next().is_none());
            if !empty {
                return Err(format!(
                    "--out {} already exists and is not an empty folder: choose a new folder or remove it",
                    out.display()
                ));
            }
        }
        if out.as_os_str().is_empty() {
            return Err("--out must not be empty".into());
        }
        return Ok(out.to_path_buf());
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
    pub fn new(target: &Path) -> Result<Self, String> {
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .ok_or_else(|| format!("{} is not a folder name", target.display()))?;
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !parent.is_dir() {
            return Err(format!(
                "the parent folder {} does not exist: create it first",
                parent.display()
            ));
        }
        remove_stale_partials(&parent, &name);
        let temporary = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if temporary.exists() {
            fs::remove_dir_all(&temporary)
                .map_err(|e| format!("cannot clear {}: {e}", temporary.display()))?;
        }
        fs::create_dir(&temporary)
            .map_err(|e| format!("cannot create {}: {e}", temporary.display()))?;
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
    pub fn commit(mut self) -> Result<PathBuf, String> {
        if self.target.is_dir() {
            // An empty folder given as --out (checked before the run): replace it.
            fs::remove_dir(&self.target).map_err(|e| {
                format!(
                    "cannot replace {} (it must be empty): {e}",
                    self.target.display()
                )
            })?;
        }
        fs::rename(&self.temporary, &self.target).map_err(|e| {
            format!(
                "cannot rename {} to {}: {e}",
                self.temporary.display(),
                self.target.display()
            )
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
