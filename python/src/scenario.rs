//! `touchdown.Scenario`: a scenario's TOML text, read and checked as the command line reads
//! a scenario file, its keys read and set by their dotted names.

use crate::errors::ScenarioError;
use pyo3::exceptions::{PyKeyError, PyOSError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::path::PathBuf;
use std::sync::LazyLock;
use touchdown::scenario::{DEFAULT_TOML, LIMIT_NAMES, keys};

/// A scenario: what a sweep or a trace runs, as a scenario file gives it.
///
/// `Scenario.default()` is the default sweep (`touchdown scenario` prints it),
/// `Scenario.load(path)` reads a file and `Scenario.from_toml(text)` a text. Keys are read
/// and set by their dotted names, the file's tables joined by dots
/// (`s["surface.friction_coefficient"] = 0.4`, `s["thrusters.2.max_thrust_n"]`, a
/// distribution as a dict: `s["inputs.slope_deg"] = {"dist": "uniform", "min": 0, "max":
/// 30}`). Every change is checked at once: a key the scenario does not know or a value it
/// does not allow raises `ScenarioError` with the command line's message, and leaves the
/// scenario as it was.
#[pyclass(module = "touchdown")]
pub struct Scenario {
    /// The text as given (the default scenario's with its comments) until a key is set,
    /// then the table written out.
    pub text: String,
    table: toml::Table,
}

impl Scenario {
    /// Takes `table` for the scenario if it reads as one (else the command line's message,
    /// and the scenario as it was).
    fn replace(&mut self, table: toml::Table) -> PyResult<()> {
        let text = toml::to_string(&table)
            .map_err(|e| ScenarioError::new_err(format!("cannot write the scenario: {e}")))?;
        touchdown::run::scenario_from_toml(&text)
            .map_err(|e| ScenarioError::new_err(e.to_string()))?;
        self.table = table;
        self.text = text;
        Ok(())
    }

    /// What holds for `key`, which the scenario does not give: the default scenario's
    /// value, nothing (a limit left out), or the reader's message for a key it does not
    /// know.
    fn not_given(&self, key: &str) -> String {
        static DEFAULTS: LazyLock<toml::Table> =
            LazyLock::new(|| DEFAULT_TOML.parse().expect("the default scenario is TOML"));
        if let Some(value) = keys::get(&DEFAULTS, key) {
            return format!(
                "the scenario does not give `{key}`: its default holds, {key} = {value} \
                 (set it to change it)"
            );
        }
        // Whether the reader knows the key: set to a value no key takes, a known key is
        // refused for its value, an unknown one for its name.
        let mut probe = self.table.clone();
        let never = toml::Value::Datetime("1970-01-01".parse().expect("a TOML date"));
        if keys::set(&mut probe, key, never).is_err() {
            return format!("`{key}` is not a key of the scenario");
        }
        let text = toml::to_string(&probe).unwrap_or_default();
        if let Err(e @ touchdown::scenario::ScenarioError::UnknownKey { .. }) =
            touchdown::run::scenario_from_toml(&text)
        {
            return e.to_string();
        }
        if LIMIT_NAMES
            .iter()
            .any(|(_, name)| key.strip_prefix("limits.") == Some(name))
        {
            return format!(
                "the scenario does not give `{key}`, which has no default: no such limit \
                 applies (set it to apply one)"
            );
        }
        format!(
            "the scenario does not give `{key}`, and the default scenario has no value for \
             it: where its table is given, the reader's default holds (`touchdown scenario` \
             describes each key)"
        )
    }

    /// The scenario of `text`, checked.
    fn of(text: String) -> PyResult<Scenario> {
        touchdown::run::scenario_from_toml(&text)
            .map_err(|e| ScenarioError::new_err(e.to_string()))?;
        let table = text
            .parse::<toml::Table>()
            .map_err(|e| ScenarioError::new_err(format!("scenario is not valid TOML: {e}")))?;
        Ok(Scenario { text, table })
    }
}

#[pymethods]
impl Scenario {
    /// The default scenario: the four-leg lander on the default slope-and-attitude sweep.
    #[staticmethod]
    fn default() -> PyResult<Scenario> {
        Scenario::of(DEFAULT_TOML.to_string())
    }

    /// The scenario of the TOML file at `path`.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Scenario> {
        let text = std::fs::read_to_string(&path).map_err(|e| {
            PyOSError::new_err(format!("cannot read scenario file {}: {e}", path.display()))
        })?;
        Scenario::of(text)
    }

    /// The scenario of a TOML text.
    #[staticmethod]
    fn from_toml(text: String) -> PyResult<Scenario> {
        Scenario::of(text)
    }

    /// The scenario as TOML text: what `Scenario.from_toml` reads back, and what a sweep
    /// stores in its metadata (`touchdown.scenario`).
    fn to_toml(&self) -> String {
        self.text.clone()
    }

    /// The value of a key by its dotted name: a number, string or bool, a dict (a table
    /// or a distribution) or a list (`[[thrusters]]`). `KeyError` where the scenario does
    /// not give the key, saying what holds instead (the default, or nothing), or that the
    /// scenario has no such key.
    fn __getitem__<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        let value =
            keys::get(&self.table, key).ok_or_else(|| PyKeyError::new_err(self.not_given(key)))?;
        to_python(py, value)
    }

    /// Sets a key by its dotted name; the scenario is checked at once (`ScenarioError`
    /// with the command line's message, the scenario unchanged).
    fn __setitem__(&mut self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let value = to_toml(value, key)?;
        let mut table = self.table.clone();
        keys::set(&mut table, key, value).map_err(|e| ScenarioError::new_err(format!("{e:#}")))?;
        self.replace(table)
    }

    /// Removes a key by its dotted name: its default holds again (checked as a set is).
    fn __delitem__(&mut self, key: &str) -> PyResult<()> {
        let mut table = self.table.clone();
        let leaf = key.rsplit('.').next().unwrap_or(key);
        let removed = keys::get(&table, key).is_some()
            && keys::parent_table(&mut table, key)
                .map_err(|e| ScenarioError::new_err(format!("{e:#}")))?
                .remove(leaf)
                .is_some();
        if !removed {
            return Err(PyKeyError::new_err(self.not_given(key)));
        }
        self.replace(table)
    }

    /// Whether the scenario gives `key`.
    fn __contains__(&self, key: &str) -> bool {
        keys::get(&self.table, key).is_some()
    }

    /// The dotted names of the values the scenario gives (a distribution is one value).
    fn keys(&self) -> Vec<String> {
        let mut out = Vec::new();
        leaf_keys(&self.table, "", &mut out);
        out
    }

    /// A copy, to change without changing this one.
    fn copy(&self) -> Scenario {
        Scenario {
            text: self.text.clone(),
            table: self.table.clone(),
        }
    }

    fn __eq__(&self, other: &Scenario) -> bool {
        self.table == other.table
    }

    fn __repr__(&self) -> String {
        let get =
            |k: &str| keys::get(&self.table, k).map_or("default".to_string(), |v| v.to_string());
        format!(
            "Scenario(seed={}, samples={}, {} keys given)",
            get("seed"),
            get("samples"),
            self.keys().len()
        )
    }
}

/// The dotted names of the values under `table`, prefixed by `at`.
fn leaf_keys(table: &toml::Table, at: &str, out: &mut Vec<String>) {
    for (name, value) in table {
        let key = if at.is_empty() {
            name.clone()
        } else {
            format!("{at}.{name}")
        };
        match value {
            toml::Value::Table(t) if !t.contains_key("dist") => leaf_keys(t, &key, out),
            toml::Value::Array(items)
                if items.iter().all(toml::Value::is_table) && !items.is_empty() =>
            {
                for (j, item) in items.iter().enumerate() {
                    if let toml::Value::Table(t) = item {
                        leaf_keys(t, &format!("{key}.{j}"), out);
                    }
                }
            }
            _ => out.push(key),
        }
    }
}

/// A TOML value as Python's.
fn to_python<'py>(py: Python<'py>, value: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        toml::Value::String(s) => PyString::new(py, s).into_any(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        toml::Value::Float(f) => PyFloat::new(py, *f).into_any(),
        toml::Value::Boolean(b) => PyBool::new(py, *b).to_owned().into_any(),
        toml::Value::Datetime(d) => PyString::new(py, &d.to_string()).into_any(),
        toml::Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(to_python(py, item)?)?;
            }
            list.into_any()
        }
        toml::Value::Table(t) => {
            let dict = PyDict::new(py);
            for (k, v) in t {
                dict.set_item(k, to_python(py, v)?)?;
            }
            dict.into_any()
        }
    })
}

/// A Python value as TOML's (bool, int, float, str, a dict of them, a list of them).
fn to_toml(value: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(value.extract().map_err(|_| {
            ScenarioError::new_err(format!(
                "scenario key `{key}`: {value} does not fit in 64 bits"
            ))
        })?));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if let Ok(d) = value.cast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, v) in d.iter() {
            let k: String = k.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "scenario key `{key}`: a dict's keys are names (str)"
                ))
            })?;
            let sub = to_toml(&v, &format!("{key}.{k}"))?;
            t.insert(k, sub);
        }
        return Ok(toml::Value::Table(t));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items = value
            .try_iter()?
            .map(|v| to_toml(&v?, key))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // numpy's scalars and other numbers: an integer where it is one, else a float.
    if value.hasattr("__index__")? {
        return Ok(toml::Value::Integer(value.extract()?));
    }
    if let Ok(f) = value.extract::<f64>() {
        return Ok(toml::Value::Float(f));
    }
    Err(PyTypeError::new_err(format!(
        "scenario key `{key}`: a {} is not a value of a scenario (a number, str, bool, dict or list)",
        value.get_type().name()?
    )))
}
