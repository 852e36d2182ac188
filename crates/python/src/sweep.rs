//! The compiled half of `surfgrav.sweep` (the Python half, which hands the tasks to an
//! executor, is in `python/surfgrav/__init__.py`).
//!
//! - `_sweep_plan(path)`: the sweep's tasks as `surfgrav sweep` expands them
//!   ([`Sweep::load`]: same validation, same one-line messages);
//! - `_sweep_task(scene_text, index)`: one task's scene run as `surfgrav sweep` runs it
//!   ([`run_scene`]), returning plain data (a dict) so any executor can ship it back;
//! - `_sweep_csv(path, outcomes)`: `results.csv`'s text for those outcomes
//!   ([`results_csv_text`]), byte for byte the command line's format.

use std::collections::BTreeMap;
use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use surfgrav_scenarios::scene::SceneFile;
use surfgrav_scenarios::sweep::{results_csv_text, run_scene, Sweep, TaskResult};

use crate::errors::{compute, input, Failure, InputError};

/// `(fields, [(index, parameters JSON, scene TOML)])` of a sweep file.
#[pyfunction]
pub fn _sweep_plan(py: Python<'_>, path: PathBuf) -> PyResult<(Vec<String>, Py<PyList>)> {
    let sweep = compute(py, move || Sweep::load(&path).map_err(Failure::Input))?;
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
        tasks.append((task.index, parameters, task.scene_text.as_str()))?;
    }
    Ok((sweep.fields.clone(), tasks.unbind()))
}

/// The result columns of results.csv, in order, after task, status and the parameters (the
/// command line's own list).
use surfgrav_scenarios::sweep::RESULT_COLUMNS as COLUMNS;

/// Runs one task's scene (TOML text) as `surfgrav sweep` runs it; the GIL is released.
/// Returns `{"task", "status", <result columns>}`: status `done`, or `failed` with `message`.
#[pyfunction]
pub fn _sweep_task(py: Python<'_>, scene_text: String, index: usize) -> PyResult<Py<PyDict>> {
    let outcome = compute(py, move || {
        let label = format!("task {index:05}");
        let scene = SceneFile::parse(&scene_text, &label)
            .and_then(|f| f.build(&scene_text, &label))
            .map_err(|e| input(e.to_string()))?;
        Ok(run_scene(&scene))
    })?;
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
            d.set_item("termination", r.termination)?;
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
            d.set_item("message", m)?;
        }
    }
    Ok(d.unbind())
}

fn result_of(d: &Bound<'_, PyDict>) -> PyResult<Result<TaskResult, String>> {
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
        return Ok(Err(get::<Option<String>>(d, "message")?.unwrap_or_default()));
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

/// `results.csv`'s text for these outcomes (`_sweep_task`'s dicts) of the sweep at `path`.
#[pyfunction]
pub fn _sweep_csv(
    py: Python<'_>,
    path: PathBuf,
    outcomes: Vec<Bound<'_, PyDict>>,
) -> PyResult<String> {
    let mut by_index = BTreeMap::new();
    for d in &outcomes {
        let index: usize = match d.get_item("task")? {
            Some(v) => v.extract()?,
            None => return Err(InputError::new_err("sweep outcome: missing `task`")),
        };
        by_index.insert(index, result_of(d)?);
    }
    let file = path.clone();
    let sweep = compute(py, move || Sweep::load(&file).map_err(Failure::Input))?;
    let rows: Vec<_> = sweep
        .tasks
        .iter()
        .filter_map(|t| {
            by_index
                .remove(&t.index)
                .map(|r| (t.index, t.parameters.clone(), r))
        })
        .collect();
    if let Some(index) = by_index.keys().next() {
        return Err(InputError::new_err(format!(
            "{}: no task {index} in this sweep",
            path.display()
        )));
    }
    Ok(results_csv_text(&sweep.fields, &rows))
}
