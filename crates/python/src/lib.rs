//! Python bindings of surfgrav: the extension module `surfgrav._surfgrav`, re-exported by the
//! `surfgrav` package (`python/surfgrav/__init__.py`; stubs in `__init__.pyi`).
//!
//! - bodies (module `bodies`): `Sphere`, `Spheroid`, `Ellipsoid`, `Disk`, `PointMass`, `Polyhedron`, with
//!   `field(points)` over an (N, 3) array, in parallel;
//! - interactions (module `interaction`): `interact` and `interact_batch`;
//! - simulations (module `simulation`): `Simulation` (two bodies, an integrator by name,
//!   `integrate(t_end, interval=None)` returning a `Trajectory` of arrays);
//! - scenes (module `scene`): `Scene.load`, `Scene.preset`, `Scene.parse`, run as `surfgrav run`
//!   runs them (`SceneRun`: the CLI's summary and the trajectory's rows);
//! - sweeps (module `sweep`): the compiled half of `surfgrav.sweep` (plan, one task, results.csv).
//!
//! Conventions are the workspace's (README): Φ < 0, a = −∇Φ, V < 0, orientations body → world.
//! Computation runs with the GIL released; errors are Python exceptions (module `errors`), never a
//! panic across the FFI boundary.

use pyo3::prelude::*;

mod arrays;
mod bodies;
mod errors;
mod interaction;
mod scene;
mod simulation;
mod sweep;

/// The compiled part of the `surfgrav` package.
#[pymodule]
fn _surfgrav(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("InputError", py.get_type::<errors::InputError>())?;
    m.add("RunError", py.get_type::<errors::RunError>())?;
    m.add("InternalError", py.get_type::<errors::InternalError>())?;
    m.add_class::<bodies::Body>()?;
    m.add_class::<bodies::PointMass>()?;
    m.add_class::<bodies::Sphere>()?;
    m.add_class::<bodies::Spheroid>()?;
    m.add_class::<bodies::Ellipsoid>()?;
    m.add_class::<bodies::Disk>()?;
    m.add_class::<bodies::Polyhedron>()?;
    m.add_class::<interaction::Interaction>()?;
    m.add_class::<interaction::BatchInteraction>()?;
    m.add_class::<simulation::Simulation>()?;
    m.add_class::<simulation::Trajectory>()?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::SceneRun>()?;
    m.add_function(wrap_pyfunction!(interaction::interact, m)?)?;
    m.add_function(wrap_pyfunction!(interaction::interact_batch, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::_sweep_plan, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::_sweep_task, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::_sweep_open, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::_sweep_finish, m)?)?;
    m.add_function(wrap_pyfunction!(errors::_panic_for_tests, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
