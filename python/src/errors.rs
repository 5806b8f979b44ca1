//! The exceptions of the package, and the library's errors turned into them with the
//! command line's messages.

use pyo3::exceptions::{PyException, PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    touchdown,
    TouchdownError,
    PyException,
    "An error of touchdown: the message is the one the command line prints."
);
pyo3::create_exception!(
    touchdown,
    ScenarioError,
    PyValueError,
    "A scenario that touchdown refuses: a key it does not know or a value it does not \
     allow, named as the command line names it."
);

/// The Python exception for an error of the library: `ScenarioError` for a scenario
/// refused, `KeyboardInterrupt` for a run stopped, else `TouchdownError`; the message is
/// the command line's (`touchdown: error: MESSAGE`).
pub fn to_py(e: &anyhow::Error) -> PyErr {
    if let Some(s) = e.downcast_ref::<touchdown::scenario::ScenarioError>() {
        return ScenarioError::new_err(s.to_string());
    }
    if let Some(i) = e.downcast_ref::<touchdown::run::Interrupted>() {
        return PyKeyboardInterrupt::new_err(i.message.clone());
    }
    TouchdownError::new_err(format!("{e:#}"))
}

/// `r` with its error as a Python exception (`to_py`).
pub trait OrPy<T> {
    /// The value, or the Python exception of the error.
    fn or_py(self) -> PyResult<T>;
}

impl<T> OrPy<T> for anyhow::Result<T> {
    fn or_py(self) -> PyResult<T> {
        self.map_err(|e| to_py(&e))
    }
}
