//! Whole-number arguments (`samples`, `seed`, `threads`, `sample`, `every`): a Python int,
//! a float that is a whole number (`1e5`), or a string read by the command line's own
//! parser (`"1e5"`, `"2.5e5"`, `"1_000"`, as `--samples 1e5`), each checked against its
//! range. What is refused names the argument, the value and the range.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyString};
use std::ops::RangeInclusive;
use touchdown::commands::flags::{MAX_COUNT, MAX_THREADS, parse_count};

/// A seed or a sample's index: 0 to 2^63 - 1 (what a scenario file holds).
pub const INDEX: RangeInclusive<u64> = 0..=MAX_COUNT;
/// A number of samples, or every how many steps a trace keeps a row.
pub const POSITIVE: RangeInclusive<u64> = 1..=MAX_COUNT;
/// Worker threads, as `--threads` takes them.
pub const THREADS: RangeInclusive<u64> = 1..=MAX_THREADS;

/// `value` of the argument `name` as a whole number in `range` (none stays none).
pub fn whole(
    name: &str,
    value: Option<&Bound<'_, PyAny>>,
    range: RangeInclusive<u64>,
) -> PyResult<Option<u64>> {
    let Some(value) = value else {
        return Ok(None);
    };
    let allowed = allowed(&range);
    let shown = value.repr()?;
    let n: i128 = if value.is_instance_of::<PyBool>() {
        return Err(PyTypeError::new_err(format!(
            "{name}={shown}: {allowed}, not a bool"
        )));
    } else if value.is_instance_of::<PyString>() {
        let text: String = value.extract()?;
        match (
            parse_count(&text),
            text.trim().replace('_', "").parse::<i128>(),
        ) {
            (Ok(n), _) => i128::from(n),
            // A whole number, but below or past what the parser takes: out of range.
            (Err(_), Ok(n)) => n,
            (Err(why), Err(_)) => {
                return Err(PyValueError::new_err(format!("{name}: {why}; {allowed}")));
            }
        }
    } else if value.is_instance_of::<PyFloat>() {
        let x: f64 = value.extract()?;
        if !x.is_finite() || x.fract() != 0.0 {
            return Err(PyValueError::new_err(format!(
                "{name}={shown} is not a whole number: {allowed}"
            )));
        }
        // Saturates past i128's range, which is out of range all the same.
        x as i128
    } else if value.hasattr("__index__")? {
        // numpy's integers too; one past i128 is out of range all the same.
        value
            .call_method0("__index__")?
            .extract::<i128>()
            .unwrap_or(i128::MAX)
    } else {
        return Err(PyTypeError::new_err(format!(
            "{name}={shown}: {allowed}, not a {}",
            value.get_type().name()?
        )));
    };
    u64::try_from(n)
        .ok()
        .filter(|n| range.contains(n))
        .map(Some)
        .ok_or_else(|| PyValueError::new_err(format!("{name}={shown} is out of range: {allowed}")))
}

/// What `range` allows, in words.
fn allowed(range: &RangeInclusive<u64>) -> String {
    let end = if *range.end() == MAX_COUNT {
        format!("{MAX_COUNT} (2^63 - 1)")
    } else {
        range.end().to_string()
    };
    format!("expected a whole number from {} to {end}", range.start())
}
