//! `Scene`: scene files and presets, run exactly as `surfgrav run` runs them.
//!
//! `Scene.load`, `Scene.preset` and `Scene.parse` use the command line's readers (same
//! validation, same `file:line: field: ...` messages); `run` calls the same
//! [`prepare`](surfgrav_scenarios::simulate::prepare) and
//! [`simulate`](surfgrav_scenarios::simulate::simulate) as `surfgrav run`, and its summary is
//! the CLI's `summary.json` ([`Summary::of`]) parsed by Python's `json`, so every figure is the
//! same double.

use std::path::PathBuf;

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use surfgrav_dynamics::IntegratorKind;
use surfgrav_scenarios::output::Summary;
use surfgrav_scenarios::presets;
use surfgrav_scenarios::scene::{Scene as RustScene, SceneFile};
use surfgrav_scenarios::simulate::{prepare, simulate, OutputRow, RunError as ScenarioRunError};
use surfgrav_scenarios::spec::compact;

use crate::errors::{compute, Failure, InputError};
use crate::simulation::state_arrays;

fn failure(e: ScenarioRunError) -> Failure {
    match e {
        ScenarioRunError::Input(m) => Failure::Input(m),
        ScenarioRunError::Failed(m) => Failure::Run(m),
    }
}

/// A validated scene: two bodies, their initial state, the integrator and the output cadence.
///
/// Build one with `Scene.load(path)`, `Scene.preset(name)` or `Scene.parse(text)`; `run()`
/// integrates it as `surfgrav run` does.
#[pyclass(module = "surfgrav", frozen)]
pub struct Scene {
    scene: RustScene,
}

#[pymethods]
impl Scene {
    /// Reads and validates a scene file (TOML). Raises `InputError` with the command line's
    /// message (`my.toml:11: body_a.polar_radius: must be a positive finite length, got -0.25`).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Scene> {
        let (file, source) =
            SceneFile::read(&path).map_err(|e| InputError::new_err(e.to_string()))?;
        let scene = file
            .build(&source, &path.display().to_string())
            .map_err(|e| InputError::new_err(e.to_string()))?;
        Ok(Scene { scene })
    }

    /// A built-in scene by name (see `Scene.presets()`).
    #[staticmethod]
    fn preset(name: &str) -> PyResult<Scene> {
        let preset = presets::find(name).ok_or_else(|| {
            InputError::new_err(format!(
                "unknown preset `{name}`: expected one of {}",
                presets::names()
            ))
        })?;
        let scene = preset
            .scene()
            .map_err(|e| InputError::new_err(e.to_string()))?;
        Ok(Scene { scene })
    }

    /// Parses a scene from TOML text; `name` stands for the file in messages.
    #[staticmethod]
    #[pyo3(signature = (text, name = "<string>"))]
    fn parse(text: &str, name: &str) -> PyResult<Scene> {
        let scene = SceneFile::parse(text, name)
            .and_then(|f| f.build(text, name))
            .map_err(|e| InputError::new_err(e.to_string()))?;
        Ok(Scene { scene })
    }

    /// The names of the built-in scenes.
    #[staticmethod]
    fn presets() -> Vec<&'static str> {
        presets::PRESETS.iter().map(|p| p.name).collect()
    }

    /// The preset's TOML text (what `surfgrav presets --show NAME` prints).
    #[staticmethod]
    fn preset_toml(name: &str) -> PyResult<&'static str> {
        presets::find(name)
            .map(|p| p.toml.trim_end())
            .ok_or_else(|| {
                InputError::new_err(format!(
                    "unknown preset `{name}`: expected one of {}",
                    presets::names()
                ))
            })
    }

    /// A copy with the command line's overrides applied (`--t-end`, `--dt`, `--integrator`,
    /// `--tolerance`), checked as the command line checks them.
    #[pyo3(signature = (t_end = None, dt = None, integrator = None, tolerance = None))]
    fn with_overrides(
        &self,
        t_end: Option<f64>,
        dt: Option<f64>,
        integrator: Option<&str>,
        tolerance: Option<f64>,
    ) -> PyResult<Scene> {
        let method = integrator
            .map(|name| {
                name.trim()
                    .to_ascii_lowercase()
                    .parse::<IntegratorKind>()
                    .map_err(|e| InputError::new_err(format!("integrator: {e}")))
            })
            .transpose()?;
        // The command line's checks, with the keyword names for its flags.
        let positive = |name: &str, v: Option<f64>| match v {
            Some(x) if !(x.is_finite() && x > 0.0) => Err(InputError::new_err(format!(
                "{name} must be a positive finite number, got `{}`",
                compact(x)
            ))),
            _ => Ok(()),
        };
        positive("dt", dt)?;
        positive("tolerance", tolerance)?;
        if let Some(t) = t_end.filter(|t| !t.is_finite()) {
            return Err(InputError::new_err(format!(
                "t_end must be a finite number, got `{}`",
                compact(t)
            )));
        }
        let mut scene = self.scene.clone();
        scene
            .override_with(t_end, dt, method, tolerance)
            .map_err(|e| InputError::new_err(e.to_string()))?;
        Ok(Scene { scene })
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> &str {
        &self.scene.name
    }

    /// Start time.
    #[getter]
    fn t_start(&self) -> f64 {
        self.scene.t_start
    }

    /// End time.
    #[getter]
    fn t_end(&self) -> f64 {
        self.scene.t_end
    }

    /// The integrator's name.
    #[getter]
    fn integrator(&self) -> &'static str {
        self.scene.integrator.method().name()
    }

    /// The gravitational constant.
    #[getter(G)]
    fn gravitational_constant(&self) -> f64 {
        self.scene.gravitational_constant
    }

    /// Bodies A and B as the command line's specs.
    #[getter]
    fn bodies(&self) -> (String, String) {
        (self.scene.spec_a.to_string(), self.scene.spec_b.to_string())
    }

    /// Runs the scene as `surfgrav run` does (nothing is written) and returns a `SceneRun`.
    /// The GIL is released during the run. Raises `InputError` where the CLI exits with code 2
    /// (bodies overlapping at the start, ...), `RunError` where it exits with code 1.
    fn run(&self, py: Python<'_>) -> PyResult<SceneRun> {
        let scene = self.scene.clone();
        let (rows, record_bits, summary) = compute(py, move || {
            let prepared = prepare(&scene).map_err(failure)?;
            let mut rows: Vec<OutputRow> = Vec::new();
            let record = simulate(&scene, &prepared, &mut |_| {}, &mut |row| {
                rows.push(*row);
                Ok(())
            })
            .map_err(failure)?;
            let summary = serde_json::to_string(&Summary::of(&record))
                .map_err(|e| Failure::Run(e.to_string()))?;
            let bits = (
                record.method,
                record.step_times,
                record.energies,
                record.angular_momenta,
            );
            Ok((rows, bits, summary))
        })?;
        let json = py.import("json")?;
        let summary = json
            .call_method1("loads", (summary,))?
            .cast_into::<PyDict>()?;
        let (method, step_times, step_energies, step_momenta) = record_bits;
        let times: Vec<f64> = rows.iter().map(|r| r.time).collect();
        let states: Vec<_> = rows.iter().map(|r| r.state).collect();
        let energy: Vec<f64> = rows.iter().map(|r| r.energy).collect();
        let momentum: Vec<f64> = rows.iter().map(|r| r.angular_momentum).collect();
        let len = rows.len();
        let s = state_arrays(py, times, &states);
        Ok(SceneRun {
            summary: summary.unbind(),
            method,
            t: s.t.unbind(),
            positions: s.positions.unbind(),
            velocities: s.velocities.unbind(),
            orientations: s.orientations.unbind(),
            angular_velocities: s.angular_velocities.unbind(),
            energy: PyArray1::from_vec(py, energy).unbind(),
            angular_momentum: PyArray1::from_vec(py, momentum).unbind(),
            step_times: PyArray1::from_vec(py, step_times).unbind(),
            step_energy: PyArray1::from_vec(py, step_energies).unbind(),
            step_angular_momentum: PyArray1::from_vec(py, step_momenta).unbind(),
            len,
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene(name='{}', a={}, b={}, t_end={}, integrator='{}')",
            self.scene.name,
            self.scene.spec_a,
            self.scene.spec_b,
            self.scene.t_end,
            self.scene.integrator.method().name()
        )
    }
}

/// What `Scene.run` gives: the CLI's summary, the rows of its `trajectory.csv` as arrays, and
/// the energy and |J| at every step.
#[pyclass(module = "surfgrav", frozen)]
pub struct SceneRun {
    /// The contents of the CLI's `summary.json` (wall_seconds is this run's).
    #[pyo3(get)]
    summary: Py<PyDict>,
    /// How forces were computed: point masses (exact), tabulated V(r), direct surface integral.
    #[pyo3(get)]
    method: &'static str,
    /// Row times (the rows of trajectory.csv), (M,).
    #[pyo3(get)]
    t: Py<PyArray1<f64>>,
    /// Positions of A and B, (M, 2, 3).
    #[pyo3(get)]
    positions: Py<numpy::PyArray3<f64>>,
    /// Velocities, (M, 2, 3).
    #[pyo3(get)]
    velocities: Py<numpy::PyArray3<f64>>,
    /// Attitudes, unit quaternions scalar first, (M, 2, 4).
    #[pyo3(get)]
    orientations: Py<numpy::PyArray3<f64>>,
    /// Angular velocities, (M, 2, 3).
    #[pyo3(get)]
    angular_velocities: Py<numpy::PyArray3<f64>>,
    /// Total energy per row, (M,).
    #[pyo3(get)]
    energy: Py<PyArray1<f64>>,
    /// |J| about the origin per row, (M,).
    #[pyo3(get)]
    angular_momentum: Py<PyArray1<f64>>,
    /// Time of every step (the start, each accepted step, a stop event), (S,).
    #[pyo3(get)]
    step_times: Py<PyArray1<f64>>,
    /// Total energy at every step, (S,).
    #[pyo3(get)]
    step_energy: Py<PyArray1<f64>>,
    /// |J| at every step, (S,).
    #[pyo3(get)]
    step_angular_momentum: Py<PyArray1<f64>>,
    len: usize,
}

#[pymethods]
impl SceneRun {
    fn __len__(&self) -> usize {
        self.len
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let name = self
            .summary
            .bind(py)
            .get_item("scene")
            .ok()
            .flatten()
            .map(|n| n.to_string())
            .unwrap_or_default();
        format!(
            "SceneRun(scene='{name}', rows={}, method='{}')",
            self.len, self.method
        )
    }
}
