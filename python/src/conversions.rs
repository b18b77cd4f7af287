//! Values between Python and the library: numpy arrays and fields (checked as the `.npy`
//! reader checks a file, borrowed without a copy on the way in, taken over without a copy
//! on the way out), names, integers, and records that the library serialises (a summary,
//! an outcome, a plan) as the dicts and lists of `json.loads` of the same JSON the
//! command line writes.

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyInt;
use serde::Serialize;

use persson_check::error::Error;
use persson_check::io::npy;
use persson_check::tasks::surface::{MAX_N, MIN_N};

use crate::errors::to_py;

/// A square float64 field handed over from numpy, checked as the `.npy` reader checks a
/// file; borrowed, not copied.
pub fn field<'a>(heights: &'a PyReadonlyArrayDyn<'_, f64>) -> PyResult<(usize, &'a [f64])> {
    let shape: Vec<u64> = heights.shape().iter().map(|&d| d as u64).collect();
    let n = npy::check_shape(&shape, MIN_N..=MAX_N).map_err(PyValueError::new_err)?;
    let values = heights
        .as_slice()
        .map_err(|_| PyValueError::new_err("heights must be a C-contiguous array"))?;
    npy::check_finite(values, n).map_err(PyValueError::new_err)?;
    Ok((n, values))
}

/// An `n x n` numpy array that takes over `values` (no copy).
pub fn array2(py: Python<'_>, n: usize, values: Vec<f64>) -> PyResult<Py<PyArray2<f64>>> {
    Ok(PyArray1::from_vec(py, values).reshape([n, n])?.unbind())
}

/// Points per side given as a Python integer (its range is checked with the surface's).
pub fn grid_size(n: i64) -> PyResult<usize> {
    usize::try_from(n).map_err(|_| {
        to_py(Error::invalid(
            "n",
            n,
            format!("an integer in [{MIN_N}, {MAX_N}]"),
        ))
    })
}

/// A seed given as a Python integer: any in `[0, 2^64)`; not an integer is a `TypeError`.
pub fn seed(seed: &Bound<'_, PyAny>) -> PyResult<u64> {
    match seed.extract::<u64>() {
        Ok(s) => Ok(s),
        Err(_) if seed.is_instance_of::<PyInt>() => Err(to_py(Error::invalid(
            "seed",
            seed,
            format!("an integer in [0, {}]", u64::MAX),
        ))),
        Err(e) => Err(e),
    }
}

/// Names as a list: one string or a list of strings (None: all).
pub fn name_list(names: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<String>> {
    match names {
        None => Ok(Vec::new()),
        Some(obj) => match obj.extract::<String>() {
            Ok(one) => Ok(vec![one]),
            Err(_) => obj.extract::<Vec<String>>(),
        },
    }
}

/// JSON text as Python objects (dicts, lists), through the json module.
pub fn json_to_py<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// A record as the Python objects of its JSON: the keys and values the command line
/// writes (a non-finite number is `None`, as JSON's `null`).
pub fn record<'py>(py: Python<'py>, value: &impl Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).expect("records serialise");
    json_to_py(py, &text)
}
