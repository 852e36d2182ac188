//! The compiled half of `surfgrav.sweep` (the Python half, which hands the tasks to an
//! executor, is in `python/surfgrav/__init__.py`).
//!
//! - `_sweep_plan(path)`: the sweep's tasks as `surfgrav sweep` expands them
//!   ([`Sweep::load`]: same validation, same one-line messages);
//! - `_sweep_open(path, out)`: the output folder opened as `surfgrav sweep --out` opens it
//!   ([`SweepFolder::open`]): checked, the finished tasks read back (so a re-run skips them);
//! - `_sweep_task(scene_text, index, ...)`: one task's scene run as `surfgrav sweep` runs it
//!   ([`run_scene`], or [`run_task`] into the folder), returning plain data (a dict) so any
//!   executor can ship it back;
//! - `_sweep_finish(path, out, outcomes)`: `manifest.json` and `results.csv` written as the
//!   command line writes them ([`SweepFolder::finish`]).

use std::collections::BTreeMap;
use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use surfgrav_scenarios::scene::SceneFile;
use surfgrav_scenarios::simulate::RunError;
use surfgrav_scenarios::sweep::{
    run_scene, run_task, Sweep, SweepError, SweepFolder, Task, TaskFiles, TaskResult,
};

use crate::errors::{compute, input, Failure, InputError};

/// The sweep file at `path`, read with the GIL released.
fn load(py: Python<'_>, path: PathBuf) -> PyResult<Sweep> {
    compute(py, move || {
        Sweep::load(&path).map_err(|e| input(e.to_string()))
    })
}

/// A sweep file's plan: `{"fields", "columns", "trajectory", "figures", "tasks": [(index,
/// parameters dict, scene TOML, parameters TOML)]}`.
#[pyfunction]
pub fn _sweep_plan(py: Python<'_>, path: PathBuf) -> PyResult<Py<PyDict>> {
    let sweep = load(py, path)?;
    let json = py.import("json")?;
    let tasks = PyList::empty(py);
    for task in &sweep.tasks {
        let parameters: serde_json::Map<String, serde_json::Value> = task
            .parameters
            .iter()
            .map(|(k, v)| {
                (
                    k.clone(),
                    serde_json::to_value(v).unwrap_or(serde_json::Value::Null),
                )
            })
            .collect();
        let text =
            serde_json::to_string(&parameters).map_err(|e| InputError::new_err(e.to_string()))?;
        let parameters = json.call_method1("loads", (text,))?;
        let table: toml::Table = task.parameters.iter().cloned().collect();
        let toml_text = toml::to_string(&table).map_err(|e| InputError::new_err(e.to_string()))?;
        tasks.append((task.index, parameters, task.scene_text.as_str(), toml_text))?;
    }
    let plan = PyDict::new(py);
    plan.set_item("fields", sweep.fields.clone())?;
    plan.set_item("columns", COLUMNS.to_vec())?;
    plan.set_item("trajectory", sweep.save_trajectory)?;
    plan.set_item("figures", sweep.save_figures)?;
    plan.set_item("tasks", tasks)?;
    Ok(plan.unbind())
}

/// The result columns of results.csv, in order, after task, status and the parameters (the
/// command line's own list).
use surfgrav_scenarios::sweep::RESULT_COLUMNS as COLUMNS;

/// An outcome as the dict `_sweep_task` returns: `{"task", "status", <result columns>}`.
fn outcome_dict<'py>(
    py: Python<'py>,
    index: usize,
    outcome: &Result<TaskResult, SweepError>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("task", index)?;
    match outcome {
        Ok(r) => {
            d.set_item("status", "done")?;
            d.set_item("mass_a", r.mass_a)?;
            d.set_item("mass_b", r.mass_b)?;
            d.set_item("t_reached", r.t_reached)?;
            d.set_item("steps", r.steps)?;
            d.set_item("min_separation", r.min_separation)?;
            d.set_item("energy_drift", r.energy_drift)?;
            d.set_item("angular_momentum_drift", r.angular_momentum_drift)?;
            d.set_item(
                "angular_momentum_vector_drift",
                r.angular_momentum_vector_drift,
            )?;
            d.set_item("precession_angle_deg", r.precession_angle_deg)?;
            d.set_item("final_spin_a", r.final_spin_a)?;
            d.set_item("final_spin_b", r.final_spin_b)?;
            d.set_item("termination", r.termination.as_str())?;
            d.set_item("contact_time", r.contact_time)?;
            d.set_item("escape_time", r.escape_time)?;
            d.set_item("wall_seconds", r.wall_seconds)?;
            d.set_item("message", py.None())?;
        }
        Err(m) => {
            d.set_item("status", "failed")?;
            for c in &COLUMNS[..COLUMNS.len() - 1] {
                d.set_item(*c, py.None())?;
            }
            d.set_item("message", m.to_string())?;
        }
    }
    Ok(d)
}

/// Opens the sweep's output folder as `surfgrav sweep --out` does (checked: absent or this
/// sweep's; `tasks/` created; the manifest written) and returns the finished tasks' outcomes.
#[pyfunction]
pub fn _sweep_open(py: Python<'_>, path: PathBuf, out: PathBuf) -> PyResult<Py<PyList>> {
    let sweep = load(py, path)?;
    let folder = compute(py, move || {
        SweepFolder::open(&sweep, &out, None).map_err(|e| input(e.to_string()))
    })?;
    let done = PyList::empty(py);
    for (index, result) in &folder.results {
        done.append(outcome_dict(py, *index, &Ok(result.clone()))?)?;
    }
    Ok(done.unbind())
}

/// Runs one task's scene (TOML text) as `surfgrav sweep` runs it; the GIL is released. With
/// `out`, the task writes its folder `out/tasks/NNNNN` as the command line does (the folder
/// must be reachable from where the task runs), so a re-run skips it.
/// Returns `{"task", "status", <result columns>}`: status `done`, or `failed` with `message`.
#[pyfunction]
#[pyo3(signature = (scene_text, index, out = None, parameters = None, trajectory = false, figures = false))]
pub fn _sweep_task(
    py: Python<'_>,
    scene_text: String,
    index: usize,
    out: Option<PathBuf>,
    parameters: Option<String>,
    trajectory: bool,
    figures: bool,
) -> PyResult<Py<PyDict>> {
    let outcome = compute(py, move || {
        let label = format!("task {index:05}");
        let scene = SceneFile::parse(&scene_text, &label)
            .and_then(|f| f.build(&scene_text, &label))
            .map_err(|e| input(e.to_string()))?;
        let Some(root) = out else {
            return Ok(run_scene(&scene));
        };
        let parameters: toml::Table = toml::from_str(parameters.as_deref().unwrap_or(""))
            .map_err(|e| input(format!("task {index:05}: parameters: {e}")))?;
        let task = Task {
            index,
            parameters: parameters.into_iter().collect(),
            scene_text,
            scene,
        };
        let files = TaskFiles {
            trajectory,
            figures,
        };
        Ok(run_task(&root, &task, files))
    })?;
    Ok(outcome_dict(py, index, &outcome)?.unbind())
}

/// A task's outcome from its dict; a failure's message comes back as the run's error.
fn result_of(d: &Bound<'_, PyDict>) -> PyResult<Result<TaskResult, SweepError>> {
    fn get<'py, T: FromPyObjectOwned<'py>>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<T> {
        match d.get_item(key)? {
            Some(v) => v.extract::<T>().map_err(Into::into),
            None => Err(InputError::new_err(format!(
                "sweep outcome: missing `{key}`"
            ))),
        }
    }
    let status: String = get(d, "status")?;
    if status != "done" {
        let message = get::<Option<String>>(d, "message")?.unwrap_or_default();
        return Ok(Err(SweepError::Run(RunError::Failed(message))));
    }
    Ok(Ok(TaskResult {
        mass_a: get(d, "mass_a")?,
        mass_b: get(d, "mass_b")?,
        t_reached: get(d, "t_reached")?,
        steps: get(d, "steps")?,
        min_separation: get(d, "min_separation")?,
        energy_drift: get(d, "energy_drift")?,
        angular_momentum_drift: get(d, "angular_momentum_drift")?,
        angular_momentum_vector_drift: get(d, "angular_momentum_vector_drift")?,
        precession_angle_deg: get(d, "precession_angle_deg")?,
        final_spin_a: get(d, "final_spin_a")?,
        final_spin_b: get(d, "final_spin_b")?,
        termination: get(d, "termination")?,
        contact_time: get(d, "contact_time")?,
        escape_time: get(d, "escape_time")?,
        wall_seconds: get(d, "wall_seconds")?,
    }))
}

/// Writes `manifest.json` and `results.csv` of the sweep at `path` into `out` as the command
/// line does: the folder is read again (every finished task, this run's included), then the
/// outcomes of tasks that failed, or finished where their folder is not visible here, are
/// recorded.
#[pyfunction]
pub fn _sweep_finish(
    py: Python<'_>,
    path: PathBuf,
    out: PathBuf,
    outcomes: Vec<Bound<'_, PyDict>>,
) -> PyResult<()> {
    let mut by_index = BTreeMap::new();
    for d in &outcomes {
        let index: usize = match d.get_item("task")? {
            Some(v) => v.extract()?,
            None => return Err(InputError::new_err("sweep outcome: missing `task`")),
        };
        by_index.insert(index, result_of(d)?);
    }
    let sweep = load(py, path)?;
    compute(py, move || {
        let mut folder = SweepFolder::open(&sweep, &out, None).map_err(|e| input(e.to_string()))?;
        for (index, outcome) in by_index {
            if folder.results.contains_key(&index) {
                continue;
            }
            folder.record(index, outcome);
        }
        folder
            .finish(&sweep)
            .map_err(|e| Failure::Run(e.to_string()))
    })
}
