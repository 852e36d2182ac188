//! numpy arrays in and out: strict checks of shape and dtype, with messages that say what to
//! pass instead.

use nalgebra::{Quaternion, UnitQuaternion};
use numpy::ndarray::Array2;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PySequence;
use surfgrav_potentials::Vec3;

use crate::errors::InputError;

/// How far a quaternion's norm may be from 1 (rounding of a few operations in the caller's code).
pub const UNIT_TOLERANCE: f64 = 1e-9;

/// Python's name of an object's type.
fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "object".into())
}

/// A shape as Python writes it: `(3, 2)`, `(3,)`.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// `obj` as a float64 numpy array whose shape passes `shape_ok`; `expect` describes the shape
/// in messages (`(N, 3)`).
fn float64_array<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    expect: &str,
    shape_ok: impl Fn(&[usize]) -> bool,
) -> PyResult<Bound<'py, PyUntypedArray>> {
    let array = obj.cast::<PyUntypedArray>().map_err(|_| {
        InputError::new_err(format!(
            "{what} must be a numpy array of shape {expect} and dtype float64, got a {} object; \
             convert it with numpy.asarray({what}, dtype=numpy.float64)",
            type_name(obj)
        ))
    })?;
    let dtype = array.dtype();
    if !dtype.is_equiv_to(&numpy::dtype::<f64>(obj.py())) {
        return Err(InputError::new_err(format!(
            "{what} must have dtype float64, got {dtype}; convert it with \
             numpy.asarray({what}, dtype=numpy.float64)"
        )));
    }
    if !shape_ok(array.shape()) {
        return Err(InputError::new_err(format!(
            "{what} must have shape {expect}, got shape {}",
            shape_text(array.shape())
        )));
    }
    Ok(array.clone())
}

/// An (N, k) float64 array as N rows of k numbers (copied, so the GIL can be released).
pub fn rows(obj: &Bound<'_, PyAny>, what: &str, k: usize) -> PyResult<Vec<f64>> {
    let expect = format!("(N, {k})");
    let array = float64_array(obj, what, &expect, |s| s.len() == 2 && s[1] == k)?;
    let typed = array.cast::<PyArray2<f64>>()?;
    let view = typed.readonly();
    Ok(view.as_array().iter().copied().collect())
}

/// An (N, 3) float64 array of points with finite coordinates (copied once, row by row, so
/// the GIL can be released).
pub fn points(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; 3]>> {
    let array = float64_array(obj, what, "(N, 3)", |s| s.len() == 2 && s[1] == 3)?;
    let typed = array.cast::<PyArray2<f64>>()?;
    let readonly = typed.readonly();
    let view = readonly.as_array();
    let points: Vec<[f64; 3]> = match view.as_slice() {
        // C-contiguous: one pass over the buffer.
        Some(flat) => flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        None => view.outer_iter().map(|r| [r[0], r[1], r[2]]).collect(),
    };
    if let Some((i, p)) = points
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|x| x.is_finite()))
    {
        return Err(InputError::new_err(format!(
            "{what}[{i}] must be three finite numbers, got ({}, {}, {})",
            p[0], p[1], p[2]
        )));
    }
    Ok(points)
}

/// An (M, 3) array of any integer dtype as M triples of 0-based indices (vertex indices of
/// triangles), copied so the GIL can be released.
pub fn index_triples(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[usize; 3]>> {
    let array = obj.cast::<PyUntypedArray>().map_err(|_| {
        InputError::new_err(format!(
            "{what} must be a numpy array of shape (M, 3) and an integer dtype, got a {} \
             object; convert it with numpy.asarray({what}, dtype=numpy.int64)",
            type_name(obj)
        ))
    })?;
    let dtype = array.dtype();
    if !matches!(dtype.kind(), b'i' | b'u') {
        return Err(InputError::new_err(format!(
            "{what} must have an integer dtype (0-based vertex indices), got {dtype}; convert \
             it with numpy.asarray({what}, dtype=numpy.int64)"
        )));
    }
    let shape = array.shape();
    if !(shape.len() == 2 && shape[1] == 3) {
        return Err(InputError::new_err(format!(
            "{what} must have shape (M, 3), got shape {}",
            shape_text(shape)
        )));
    }
    // Every integer dtype as int64 (an unsigned index beyond i64's range turns negative and is
    // refused below).
    let wide = obj.call_method1("astype", ("int64",))?;
    let typed = wide.cast::<PyArray2<i64>>()?;
    let readonly = typed.readonly();
    let view = readonly.as_array();
    let mut out = Vec::with_capacity(view.nrows());
    for (i, row) in view.outer_iter().enumerate() {
        let mut triple = [0usize; 3];
        for (k, &x) in row.iter().enumerate() {
            triple[k] = usize::try_from(x).map_err(|_| {
                InputError::new_err(format!(
                    "{what}[{i}] = ({}, {}, {}) has a negative index; indices are 0-based",
                    row[0], row[1], row[2]
                ))
            })?;
        }
        out.push(triple);
    }
    Ok(out)
}

/// A short list of numbers: a 1-D float64 array, or a tuple or list of numbers.
fn numbers(obj: &Bound<'_, PyAny>, what: &str, expect: &str) -> PyResult<Vec<f64>> {
    if obj.cast::<PyUntypedArray>().is_ok() {
        let array = float64_array(obj, what, expect, |s| s.len() == 1)?;
        let typed = array.cast::<numpy::PyArray1<f64>>()?;
        return Ok(typed.readonly().as_array().to_vec());
    }
    let bad = || {
        InputError::new_err(format!(
            "{what} must be {expect} numbers (a tuple, list or 1-D float64 array), got {}",
            obj.repr()
                .map(|r| r.to_string())
                .unwrap_or_else(|_| type_name(obj))
        ))
    };
    if obj.is_instance_of::<pyo3::types::PyString>() {
        return Err(bad());
    }
    let seq = obj.cast::<PySequence>().map_err(|_| bad())?;
    let mut out = Vec::new();
    for item in seq.try_iter()? {
        out.push(item?.extract::<f64>().map_err(|_| bad())?);
    }
    Ok(out)
}

/// Three finite numbers.
pub fn vector(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec3> {
    let v = numbers(obj, what, "3")?;
    if v.len() != 3 || !v.iter().all(|x| x.is_finite()) {
        return Err(InputError::new_err(format!(
            "{what} must be three finite numbers, got {v:?}"
        )));
    }
    Ok(Vec3::new(v[0], v[1], v[2]))
}

/// Why numbers are not an orientation (messages name the argument, `what`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OrientationError {
    /// A NaN or infinite number.
    #[error("{what} must be finite numbers, got {values:?}")]
    NotFinite {
        /// The argument's name.
        what: String,
        /// The numbers given.
        values: Vec<f64>,
    },
    /// A quaternion whose norm is not 1 within [`UNIT_TOLERANCE`].
    #[error(
        "{what} as a quaternion (w, x, y, z) must have unit norm, got norm {norm}; normalise \
         it, or give a rotation vector (3 numbers)"
    )]
    NotUnit {
        /// The argument's name.
        what: String,
        /// Its norm.
        norm: f64,
    },
    /// Neither 3 nor 4 numbers.
    #[error(
        "{what} must be a rotation vector (3 numbers, axis × angle in radians) or a unit \
         quaternion (4 numbers, w, x, y, z), got {count} numbers"
    )]
    WrongCount {
        /// The argument's name.
        what: String,
        /// How many numbers were given.
        count: usize,
    },
}

/// An orientation (body frame → world frame) from 3 numbers (a rotation vector: axis × angle,
/// radians) or 4 (a unit quaternion, scalar first: w, x, y, z).
pub fn orientation_from(v: &[f64], what: &str) -> Result<UnitQuaternion<f64>, OrientationError> {
    if !v.iter().all(|x| x.is_finite()) {
        return Err(OrientationError::NotFinite {
            what: what.into(),
            values: v.to_vec(),
        });
    }
    match v.len() {
        3 => Ok(UnitQuaternion::from_scaled_axis(Vec3::new(
            v[0], v[1], v[2],
        ))),
        4 => {
            let q = Quaternion::new(v[0], v[1], v[2], v[3]);
            let norm = q.norm();
            if (norm - 1.0).abs() > UNIT_TOLERANCE {
                return Err(OrientationError::NotUnit {
                    what: what.into(),
                    norm,
                });
            }
            Ok(UnitQuaternion::new_normalize(q))
        }
        count => Err(OrientationError::WrongCount {
            what: what.into(),
            count,
        }),
    }
}

/// An optional orientation; `None` is the identity.
pub fn orientation(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<UnitQuaternion<f64>> {
    match obj {
        None => Ok(UnitQuaternion::identity()),
        Some(o) if o.is_none() => Ok(UnitQuaternion::identity()),
        Some(o) => {
            let v = numbers(o, what, "3 or 4")?;
            orientation_from(&v, what).map_err(|e| InputError::new_err(e.to_string()))
        }
    }
}

/// Orientations for a batch of `n`: `None` (identity), one orientation for all (3 or 4
/// numbers), or an (N, 3) or (N, 4) float64 array.
pub fn orientations(
    obj: Option<&Bound<'_, PyAny>>,
    what: &str,
    n: usize,
) -> PyResult<Vec<UnitQuaternion<f64>>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(vec![UnitQuaternion::identity(); n]);
    };
    let two_d = obj
        .cast::<PyUntypedArray>()
        .map(|a| a.ndim() == 2)
        .unwrap_or(false);
    if !two_d {
        let single = orientation(Some(obj), what)?;
        return Ok(vec![single; n]);
    }
    let array = float64_array(obj, what, "(N, 3) or (N, 4)", |s| {
        s.len() == 2 && (s[1] == 3 || s[1] == 4)
    })?;
    let shape = array.shape().to_vec();
    if shape[0] != n {
        return Err(InputError::new_err(format!(
            "{what} has {} rows but positions has {n}; give one orientation per position",
            shape[0]
        )));
    }
    let flat = rows(obj, what, shape[1])?;
    flat.chunks_exact(shape[1])
        .enumerate()
        .map(|(i, row)| {
            orientation_from(row, &format!("{what}[{i}]"))
                .map_err(|e| InputError::new_err(e.to_string()))
        })
        .collect()
}

/// A (3,) float64 array.
pub fn vec3_array<'py>(py: Python<'py>, v: &Vec3) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v.as_slice())
}

/// An (N, k) float64 array from N·k numbers in row order.
pub fn matrix<'py>(py: Python<'py>, flat: Vec<f64>, k: usize) -> Bound<'py, PyArray2<f64>> {
    let n = flat.len() / k;
    Array2::from_shape_vec((n, k), flat)
        .expect("n·k numbers make an (n, k) array")
        .into_pyarray(py)
}

/// An (N, 2, k) float64 array (both bodies per row) from N·2·k numbers in row order.
pub fn pairs<'py>(py: Python<'py>, flat: Vec<f64>, k: usize) -> Bound<'py, numpy::PyArray3<f64>> {
    let n = flat.len() / (2 * k);
    numpy::ndarray::Array3::from_shape_vec((n, 2, k), flat)
        .expect("n·2·k numbers make an (n, 2, k) array")
        .into_pyarray(py)
}

/// A quaternion scalar first: (w, x, y, z).
pub fn scalar_first(q: &UnitQuaternion<f64>) -> [f64; 4] {
    [q.w, q.i, q.j, q.k]
}
