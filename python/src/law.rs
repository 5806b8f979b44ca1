//! Control laws written in Python: an object whose `command(sensed, memory)` is called at
//! every control instant with the sensed state of the landers of a block as numpy arrays,
//! registered under a name for scenarios to name (`[control] law = "NAME"`), and run by the
//! sweep and the trace as a law of Rust is (`touchdown::control::Law`).

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use touchdown::control::{LAW_MEMORY, Law, LawCommand, Sensed as Read};

/// What the sensors of the landers at a control instant read (every lander a sweep's worker
/// holds there, up to 512), one row per
/// lander (`n` of them), as the control loop gives it to a law (noise, bias and latency
/// as the scenario sets them).
#[pyclass(module = "touchdown", frozen)]
pub struct Sensed {
    /// Time of the control instant, s, shape (n,).
    #[pyo3(get)]
    t_s: Py<PyArray1<f64>>,
    /// Attitude B to I as quaternions, scalar last (x, y, z, w), shape (n, 4): what
    /// `scipy.spatial.transform.Rotation.from_quat` takes.
    #[pyo3(get)]
    attitude: Py<PyArray2<f64>>,
    /// Body rates in B, rad/s, shape (n, 3).
    #[pyo3(get)]
    rate_rad_s: Py<PyArray2<f64>>,
    /// CG velocity in I, m/s, shape (n, 3).
    #[pyo3(get)]
    velocity_m_s: Py<PyArray2<f64>>,
    /// CG height above the surface plane along its normal, m, shape (n,).
    #[pyo3(get)]
    altitude_m: Py<PyArray1<f64>>,
    /// A touchdown switch closed since the last control instant (latched), shape (n,).
    #[pyo3(get)]
    contact: Py<PyArray1<bool>>,
    /// A footpad touches the surface now, shape (n,).
    #[pyo3(get)]
    touching: Py<PyArray1<bool>>,
}

#[pymethods]
impl Sensed {
    /// The number of landers.
    fn __len__(&self, py: Python<'_>) -> usize {
        self.t_s.bind(py).len()
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        format!("Sensed({} landers)", self.t_s.bind(py).len())
    }
}

/// A law of Python's, shared by the sweep's worker threads (each call takes the GIL).
struct PyLaw {
    law: Py<PyAny>,
    name: String,
}

/// The turn to call a law of Python's (see `Law::command`).
static TURN: Mutex<()> = Mutex::new(());

/// Set when a law of Python's raised: the run that called it stops, and raises it.
static FAILED: AtomicBool = AtomicBool::new(false);
/// The first exception a law of Python's raised since the last `clear`.
static ERROR: Mutex<Option<PyErr>> = Mutex::new(None);

/// Forgets an earlier law's exception (before a run starts).
pub fn clear() {
    FAILED.store(false, Ordering::SeqCst);
    *ERROR
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner) = None;
}

/// Whether a law raised since `clear`.
pub fn failed() -> bool {
    FAILED.load(Ordering::SeqCst)
}

/// The exception a law raised since `clear`, taken.
pub fn take_error() -> Option<PyErr> {
    ERROR
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .take()
}

impl Law for PyLaw {
    /// A call costs tens of microseconds whatever the landers in it (numpy's overhead):
    /// the sweep gathers them, hundreds a call.
    fn gathered(&self) -> bool {
        true
    }

    fn command(
        &self,
        sensed: &[Read],
        memory: &mut [[f64; LAW_MEMORY]],
        command: &mut [LawCommand],
    ) {
        // After a raise the run is stopping: what it computes is thrown away.
        if failed() {
            return;
        }
        // One worker at a time calls Python, waiting here rather than for the GIL: waiting
        // for the GIL, a worker would ask the one in Python to drop it every 5 ms
        // (CPython's switch interval), and the two would trade it back and forth in the
        // middle of calls (measured: 2 threads 2.5 times slower than 1 without this).
        let _turn = TURN
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        Python::attach(|py| {
            if let Err(e) = self.call(py, sensed, memory, command) {
                let mut first = ERROR
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner);
                if first.is_none() {
                    *first = Some(e);
                }
                FAILED.store(true, Ordering::SeqCst);
            }
        });
    }
}

impl PyLaw {
    /// One call of the law's `command` for the landers of `sensed`.
    fn call(
        &self,
        py: Python<'_>,
        sensed: &[Read],
        memory: &mut [[f64; LAW_MEMORY]],
        command: &mut [LawCommand],
    ) -> PyResult<()> {
        let n = sensed.len();
        let rows3 = |f: &dyn Fn(&Read) -> [f64; 3]| {
            PyArray2::from_vec2(
                py,
                &sensed.iter().map(|s| f(s).to_vec()).collect::<Vec<_>>(),
            )
        };
        let view = Sensed {
            t_s: PyArray1::from_iter(py, sensed.iter().map(|s| s.t_s)).unbind(),
            attitude: PyArray2::from_vec2(
                py,
                &sensed
                    .iter()
                    .map(|s| vec![s.attitude.x, s.attitude.y, s.attitude.z, s.attitude.w])
                    .collect::<Vec<_>>(),
            )?
            .unbind(),
            rate_rad_s: rows3(&|s| s.rate_rad_s.to_array())?.unbind(),
            velocity_m_s: rows3(&|s| s.velocity_m_s.to_array())?.unbind(),
            altitude_m: PyArray1::from_iter(py, sensed.iter().map(|s| s.altitude_m)).unbind(),
            contact: PyArray1::from_iter(py, sensed.iter().map(|s| s.contact)).unbind(),
            touching: PyArray1::from_iter(py, sensed.iter().map(|s| s.touching)).unbind(),
        };
        let kept = PyArray2::from_vec2(py, &memory.iter().map(|m| m.to_vec()).collect::<Vec<_>>())?;
        let out = self
            .law
            .bind(py)
            .call_method1("command", (view, kept.clone()))?;
        // What the law kept, back (it writes into `memory` in place).
        let kept = kept.readonly();
        let kept = kept.as_slice()?;
        for (m, row) in memory.iter_mut().zip(kept.chunks_exact(LAW_MEMORY)) {
            m.copy_from_slice(row);
        }
        if out.is_none() {
            // Most likely a `return` forgotten: refused rather than taken as nothing.
            return Err(PyTypeError::new_err(format!(
                "control law {:?}: command(sensed, memory) returned None; return a \
                 touchdown.Command (its fields left None command nothing)",
                self.name
            )));
        }
        let force = self.rows(py, &out, "force_b_n", n)?;
        let torque = self.rows(py, &out, "torque_b_n_m", n)?;
        let done = self.done(py, &out, n)?;
        for (i, c) in command.iter_mut().enumerate() {
            if let Some(f) = &force {
                c.wrench.force_b_n = glam::DVec3::from_slice(&f[3 * i..3 * i + 3]);
            }
            if let Some(t) = &torque {
                c.wrench.torque_b_n_m = glam::DVec3::from_slice(&t[3 * i..3 * i + 3]);
            }
            if let Some(d) = &done {
                c.done = d[i];
            }
        }
        Ok(())
    }

    /// The command's `name` (force or torque) as n rows of 3 (one row of 3 for all), or
    /// none where the command does not give it.
    fn rows(
        &self,
        py: Python<'_>,
        out: &Bound<'_, PyAny>,
        name: &str,
        n: usize,
    ) -> PyResult<Option<Vec<f64>>> {
        let Some(value) = attribute(out, name)? else {
            return Ok(None);
        };
        let values = match value.cast::<PyArray2<f64>>() {
            // What a numpy law returns: taken as it is.
            Ok(a) if a.shape() == [n, 3] && a.is_c_contiguous() => {
                a.readonly().as_slice()?.to_vec()
            }
            _ => {
                let np = numpy_module(py)?;
                let a = np.call_method1("asarray", (&value, np.getattr("float64")?))?;
                let a = np.call_method1("broadcast_to", (a, (n, 3))).map_err(|_| {
                    self.shape_error(py, name, &value, &format!("({n}, 3) or (3,)"))
                })?;
                let a = np.call_method1("ascontiguousarray", (a,))?;
                a.cast_into::<PyArray2<f64>>()?
                    .readonly()
                    .as_slice()?
                    .to_vec()
            }
        };
        if let Some(bad) = values.iter().position(|v| !v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "control law {:?}: {name} of lander {} is {}, not a finite number",
                self.name,
                bad / 3,
                values[bad]
            )));
        }
        Ok(Some(values))
    }

    /// The command's `done`, n flags (one for all), or none where it does not give it.
    fn done(
        &self,
        py: Python<'_>,
        out: &Bound<'_, PyAny>,
        n: usize,
    ) -> PyResult<Option<Vec<bool>>> {
        let Some(value) = attribute(out, "done")? else {
            return Ok(None);
        };
        let flags = match value.cast::<PyArray1<bool>>() {
            Ok(a) if a.shape() == [n] && a.is_c_contiguous() => a.readonly().as_slice()?.to_vec(),
            _ => {
                let np = numpy_module(py)?;
                let a = np.call_method1("asarray", (&value, np.getattr("bool_")?))?;
                let a = np.call_method1("broadcast_to", (a, (n,))).map_err(|_| {
                    self.shape_error(py, "done", &value, &format!("({n},) or one bool"))
                })?;
                let a = np.call_method1("ascontiguousarray", (a,))?;
                a.cast_into::<PyArray1<bool>>()?
                    .readonly()
                    .as_slice()?
                    .to_vec()
            }
        };
        Ok(Some(flags))
    }

    /// The error of a command field of the wrong shape.
    fn shape_error(
        &self,
        py: Python<'_>,
        name: &str,
        value: &Bound<'_, PyAny>,
        wanted: &str,
    ) -> PyErr {
        let shape = numpy_module(py)
            .and_then(|np| np.call_method1("shape", (value,)))
            .map_or("?".to_string(), |s| s.to_string());
        PyValueError::new_err(format!(
            "control law {:?}: {name} has shape {shape}; expected {wanted}",
            self.name
        ))
    }
}

/// `out.name` (a dict's item or an attribute), none where missing or None.
fn attribute<'py>(out: &Bound<'py, PyAny>, name: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
    let value = match out.cast::<pyo3::types::PyDict>() {
        Ok(d) => d.get_item(name)?,
        Err(_) if out.hasattr(name)? => Some(out.getattr(name)?),
        Err(_) => None,
    };
    Ok(value.filter(|v| !v.is_none()))
}

/// numpy, imported once.
fn numpy_module(py: Python<'_>) -> PyResult<&Bound<'_, PyModule>> {
    static NUMPY: PyOnceLock<Py<PyModule>> = PyOnceLock::new();
    NUMPY
        .get_or_try_init(py, || Ok::<_, PyErr>(py.import("numpy")?.unbind()))
        .map(|m| m.bind(py))
}

/// Registers `law` under `name` for scenarios to name (`[control] law = "NAME"`); a later
/// registration under the same name replaces it.
#[pyfunction]
pub fn register_law(name: &str, law: Py<PyAny>, py: Python<'_>) -> PyResult<()> {
    let method = law
        .bind(py)
        .getattr("command")
        .ok()
        .filter(|m| m.is_callable());
    if method.is_none() {
        return Err(PyTypeError::new_err(format!(
            "control law {name:?}: {} has no method command(sensed, memory)",
            law.bind(py).repr()?
        )));
    }
    if name.is_empty() {
        return Err(PyValueError::new_err("a control law needs a name"));
    }
    touchdown::control::register_law(
        name,
        PyLaw {
            law,
            name: name.to_string(),
        },
    );
    Ok(())
}

/// The names of the laws registered, in the order they were.
#[pyfunction]
pub fn registered_laws() -> Vec<String> {
    touchdown::control::registered_names()
}
