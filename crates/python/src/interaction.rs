//! `interact` and `interact_batch`: force, torques and mutual energy of two bodies.

use std::sync::Arc;

use nalgebra::UnitQuaternion;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use surfgrav_interaction::{
    Interaction as EngineInteraction, InteractionEngine, InteractionError, InteractionOptions,
};
use surfgrav_potentials::{Pose, PoseExt, Vec3};

use crate::arrays;
use crate::bodies::{Body, Core};
use crate::errors::{compute, input, Failure, InputError};

/// Checks the tolerance as the CLI's `--tolerance` does, and builds the options.
pub fn options(tolerance: f64) -> PyResult<InteractionOptions> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(InputError::new_err(format!(
            "tolerance must be a positive finite number, got {tolerance}"
        )));
    }
    Ok(InteractionOptions {
        relative_tolerance: tolerance,
        ..InteractionOptions::default()
    })
}

/// The result of [`interact`]: world frame, torques about each body's own centroid.
#[pyclass(module = "surfgrav", frozen)]
pub struct Interaction {
    result: EngineInteraction,
}

#[pymethods]
impl Interaction {
    /// Force on A, a (3,) array.
    #[getter]
    fn force_on_a<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec3_array(py, &self.result.force_on_a)
    }
    /// Force on B (= −force_on_a), a (3,) array.
    #[getter]
    fn force_on_b<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec3_array(py, &self.result.force_on_b)
    }
    /// Torque on A about A's centroid, a (3,) array.
    #[getter]
    fn torque_on_a<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec3_array(py, &self.result.torque_on_a)
    }
    /// Torque on B about B's centroid, a (3,) array.
    #[getter]
    fn torque_on_b<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::vec3_array(py, &self.result.torque_on_b)
    }
    /// Mutual potential energy V (negative).
    #[getter]
    fn potential_energy(&self) -> f64 {
        self.result.potential_energy
    }
    /// How it was computed: analytic-point, analytic-disk-pair, surface-over-A, surface-over-B
    /// or adaptive.
    #[getter]
    fn method(&self) -> &'static str {
        self.result.method.name()
    }
    /// Potential evaluations spent.
    #[getter]
    fn evaluations(&self) -> usize {
        self.result.evaluations
    }
    /// Estimated relative error.
    #[getter]
    fn error_estimate(&self) -> f64 {
        self.result.error_estimate
    }

    /// The result as a dict with the keys of `surfgrav interact`'s JSON (vectors as lists).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let r = &self.result;
        let list = |v: &Vec3| vec![v.x, v.y, v.z];
        d.set_item("force_on_a", list(&r.force_on_a))?;
        d.set_item("force_on_b", list(&r.force_on_b))?;
        d.set_item("torque_on_a", list(&r.torque_on_a))?;
        d.set_item("torque_on_b", list(&r.torque_on_b))?;
        d.set_item("potential_energy", r.potential_energy)?;
        d.set_item("method", r.method.name())?;
        d.set_item("evaluations", r.evaluations)?;
        d.set_item("error_estimate", r.error_estimate)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        let r = &self.result;
        format!(
            "Interaction(force_on_a=[{}, {}, {}], potential_energy={}, method='{}', \
             evaluations={}, error_estimate={:e})",
            r.force_on_a.x,
            r.force_on_a.y,
            r.force_on_a.z,
            r.potential_energy,
            r.method.name(),
            r.evaluations,
            r.error_estimate
        )
    }
}

/// One interaction; the engine's error says why not (its message is the CLI's: exit code 2).
fn one(
    engine: &mut InteractionEngine,
    a: &Core,
    b: &Core,
    pose_a: &Pose,
    pose_b: &Pose,
) -> Result<EngineInteraction, InteractionError> {
    engine.interact(&a.engine, pose_a, &b.engine, pose_b)
}

/// Force, torques and mutual potential energy of bodies `a` and `b`.
///
/// A's centroid is at the origin and B's at `position` (world frame); an orientation takes the
/// body frame to the world frame, as a rotation vector (3 numbers, axis × angle in radians) or
/// a unit quaternion (4 numbers, w, x, y, z). `tolerance` is the relative accuracy asked of the
/// surface integrals. Returns an `Interaction`. Raises `InputError` with the command line's
/// message for overlapping or touching bodies, different G, a bad tolerance or pose. The GIL is
/// released during the computation.
#[pyfunction]
#[pyo3(signature = (a, b, position, orientation_a = None, orientation_b = None, tolerance = 1e-12))]
pub fn interact(
    py: Python<'_>,
    a: &Bound<'_, Body>,
    b: &Bound<'_, Body>,
    position: &Bound<'_, PyAny>,
    orientation_a: Option<&Bound<'_, PyAny>>,
    orientation_b: Option<&Bound<'_, PyAny>>,
    tolerance: f64,
) -> PyResult<Interaction> {
    let options = options(tolerance)?;
    let position = arrays::vector(position, "position")?;
    let qa = arrays::orientation(orientation_a, "orientation_a")?;
    let qb = arrays::orientation(orientation_b, "orientation_b")?;
    let (ca, cb) = (Arc::clone(&a.get().core), Arc::clone(&b.get().core));
    let result = compute(py, move || {
        let mut engine = InteractionEngine::new(options).map_err(|e| input(e.to_string()))?;
        let pose_a = Pose::from_position_rotation(Vec3::zeros(), qa);
        let pose_b = Pose::from_position_rotation(position, qb);
        one(&mut engine, &ca, &cb, &pose_a, &pose_b).map_err(|e| input(e.to_string()))
    })?;
    Ok(Interaction { result })
}

/// Results of [`interact_batch`], one row per pose.
#[pyclass(module = "surfgrav", frozen)]
pub struct BatchInteraction {
    #[pyo3(get)]
    /// Forces on A, (N, 3).
    force_on_a: Py<PyArray2<f64>>,
    #[pyo3(get)]
    /// Forces on B, (N, 3).
    force_on_b: Py<PyArray2<f64>>,
    #[pyo3(get)]
    /// Torques on A about A's centroid, (N, 3).
    torque_on_a: Py<PyArray2<f64>>,
    #[pyo3(get)]
    /// Torques on B about B's centroid, (N, 3).
    torque_on_b: Py<PyArray2<f64>>,
    #[pyo3(get)]
    /// Mutual potential energies, (N,).
    potential_energy: Py<PyArray1<f64>>,
    #[pyo3(get)]
    /// Potential evaluations per row, (N,) int64.
    evaluations: Py<PyArray1<i64>>,
    #[pyo3(get)]
    /// Estimated relative errors, (N,).
    error_estimate: Py<PyArray1<f64>>,
    #[pyo3(get)]
    /// Method names per row (tuple of str).
    method: Py<PyAny>,
    len: usize,
}

#[pymethods]
impl BatchInteraction {
    fn __len__(&self) -> usize {
        self.len
    }

    fn __repr__(&self) -> String {
        format!("BatchInteraction(n={})", self.len)
    }
}

/// [`interact`] for many poses at once, in parallel (one engine per worker, the bodies' node
/// tables shared), with the GIL released.
///
/// `positions` is an (N, 3) float64 array of B's centroid (A at the origin);
/// `orientations_a` and `orientations_b` are None (identity), one orientation for every row
/// (3 or 4 numbers), or (N, 3) rotation vectors or (N, 4) unit quaternions (w, x, y, z).
/// Returns a `BatchInteraction` whose attributes are arrays with one row per pose. The first
/// failing row (overlap, touching, tolerance not met) raises `InputError`, naming the row.
#[pyfunction]
#[pyo3(signature = (a, b, positions, orientations_a = None, orientations_b = None, tolerance = 1e-12))]
pub fn interact_batch(
    py: Python<'_>,
    a: &Bound<'_, Body>,
    b: &Bound<'_, Body>,
    positions: &Bound<'_, PyAny>,
    orientations_a: Option<&Bound<'_, PyAny>>,
    orientations_b: Option<&Bound<'_, PyAny>>,
    tolerance: f64,
) -> PyResult<BatchInteraction> {
    let options = options(tolerance)?;
    let positions = arrays::points(positions, "positions")?;
    let n = positions.len();
    let qa = arrays::orientations(orientations_a, "orientations_a", n)?;
    let qb = arrays::orientations(orientations_b, "orientations_b", n)?;
    let (ca, cb) = (Arc::clone(&a.get().core), Arc::clone(&b.get().core));
    let results = compute(py, move || batch(options, &ca, &cb, &positions, &qa, &qb))?;
    let mut flat = [Vec::new(), Vec::new(), Vec::new(), Vec::new()];
    let (mut energy, mut evaluations, mut error, mut method) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for r in &results {
        for (out, v) in
            flat.iter_mut()
                .zip([&r.force_on_a, &r.force_on_b, &r.torque_on_a, &r.torque_on_b])
        {
            out.extend_from_slice(v.as_slice());
        }
        energy.push(r.potential_energy);
        evaluations.push(r.evaluations as i64);
        error.push(r.error_estimate);
        method.push(r.method.name());
    }
    let [fa, fb, ta, tb] = flat;
    Ok(BatchInteraction {
        force_on_a: arrays::matrix(py, fa, 3).unbind(),
        force_on_b: arrays::matrix(py, fb, 3).unbind(),
        torque_on_a: arrays::matrix(py, ta, 3).unbind(),
        torque_on_b: arrays::matrix(py, tb, 3).unbind(),
        potential_energy: PyArray1::from_vec(py, energy).unbind(),
        evaluations: PyArray1::from_vec(py, evaluations).unbind(),
        error_estimate: PyArray1::from_vec(py, error).unbind(),
        method: pyo3::types::PyTuple::new(py, method)?.into_any().unbind(),
        len: n,
    })
}

/// The batch, in parallel over chunks of rows with one engine per chunk.
fn batch(
    options: InteractionOptions,
    a: &Core,
    b: &Core,
    positions: &[[f64; 3]],
    qa: &[UnitQuaternion<f64>],
    qb: &[UnitQuaternion<f64>],
) -> Result<Vec<EngineInteraction>, Failure> {
    let n = positions.len();
    let threads = rayon::current_num_threads().max(1);
    let chunk = n.div_ceil(4 * threads).clamp(1, 64);
    let rows: Vec<usize> = (0..n).collect();
    let chunks: Vec<Result<Vec<EngineInteraction>, (usize, InteractionError)>> = rows
        .par_chunks(chunk)
        .map(|idx| {
            let mut engine = InteractionEngine::new(options).map_err(|e| (idx[0], e))?;
            idx.iter()
                .map(|&i| {
                    let p = positions[i];
                    let pose_a = Pose::from_position_rotation(Vec3::zeros(), qa[i]);
                    let pose_b = Pose::from_position_rotation(Vec3::new(p[0], p[1], p[2]), qb[i]);
                    one(&mut engine, a, b, &pose_a, &pose_b).map_err(|m| (i, m))
                })
                .collect()
        })
        .collect();
    let mut out = Vec::with_capacity(n);
    for c in chunks {
        match c {
            Ok(v) => out.extend(v),
            Err((i, m)) => return Err(input(format!("positions[{i}]: {m}"))),
        }
    }
    Ok(out)
}
