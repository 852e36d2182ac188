//! Python exceptions, and running Rust work with the GIL released and panics caught.
//!
//! Every error a user can cause is an [`InputError`] (a `ValueError`) carrying the same one-line
//! message as the command line (where the CLI exits with code 2); a run that starts and then
//! fails is a [`RunError`] (a `RuntimeError`; the CLI's exit code 1). A panic inside Rust never
//! crosses into the interpreter: it becomes an [`InternalError`].

use std::panic::{catch_unwind, AssertUnwindSafe};

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    surfgrav,
    InputError,
    PyValueError,
    "Bad input: a body, pose, array, setting or scene that surfgrav refuses. The message is the \
     command line's one-line message and says what to change."
);
pyo3::create_exception!(
    surfgrav,
    RunError,
    PyRuntimeError,
    "A computation that started and then failed (an integrator or a model failure during a run)."
);
pyo3::create_exception!(
    surfgrav,
    InternalError,
    PyRuntimeError,
    "A bug in surfgrav: Rust code panicked. The interpreter is unharmed; please report the message."
);

/// Why a computation did not give a result.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    /// The user must change the input ([`InputError`]).
    Input(String),
    /// A run started and failed ([`RunError`]).
    Run(String),
}

/// Bad input with this message.
pub fn input(message: impl Into<String>) -> Failure {
    Failure::Input(message.into())
}

impl From<Failure> for PyErr {
    fn from(f: Failure) -> Self {
        match f {
            Failure::Input(m) => InputError::new_err(m),
            Failure::Run(m) => RunError::new_err(m),
        }
    }
}

/// The text of a panic payload.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".to_string()
    }
}

/// Runs `work` with the GIL released (other Python threads run meanwhile), turning a panic into
/// [`InternalError`] and a [`Failure`] into its exception.
pub fn compute<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce() -> Result<T, Failure> + Send,
{
    let outcome = py.detach(move || catch_unwind(AssertUnwindSafe(work)));
    match outcome {
        Ok(result) => result.map_err(PyErr::from),
        Err(payload) => Err(InternalError::new_err(format!(
            "internal error in surfgrav (please report it): {}",
            panic_message(payload.as_ref())
        ))),
    }
}

/// Panics inside [`compute`], to test that a panic reaches Python as [`InternalError`] and
/// leaves the interpreter running (`surfgrav._surfgrav._panic_for_tests`; not public API).
#[pyfunction]
pub fn _panic_for_tests(py: Python<'_>) -> PyResult<()> {
    compute(py, || -> Result<(), Failure> {
        panic!("a deliberate panic for the tests")
    })
}
