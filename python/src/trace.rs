//! `touchdown.trace`: one sample run with the reference model, its time history kept in
//! memory and handed to pyarrow, with what the command line prints of it.

use crate::errors::OrPy;
use arrow_pyarrow::IntoPyArrow;
use pyo3::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use touchdown::run::trace::{TraceSettings, trace_scenario};

/// Runs sample `sample` of a scenario (its TOML text, `seed` overriding its own), of the
/// sweep file `sweep`, or of the sweep whose schema metadata is `metadata` (a table held in
/// memory), one row every `every` steps. Returns what `touchdown trace` prints and the
/// time history as a `pyarrow.RecordBatchReader`.
#[pyfunction]
#[pyo3(signature = (sample, every=1, scenario_toml=None, seed=None, sweep=None, metadata=None, inputs=None))]
#[allow(clippy::too_many_arguments)]
pub fn trace<'py>(
    py: Python<'py>,
    sample: u64,
    every: u64,
    scenario_toml: Option<String>,
    seed: Option<u64>,
    sweep: Option<PathBuf>,
    metadata: Option<HashMap<String, String>>,
    inputs: Option<PathBuf>,
) -> PyResult<(String, Bound<'py, PyAny>)> {
    if every == 0 {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "every must be at least 1",
        ));
    }
    crate::law::clear();
    let settings = TraceSettings {
        sweep: None,
        scenario: None,
        seed,
        inputs: inputs.clone(),
        sample,
        out: None,
        every,
    };
    let done = py.detach(|| -> anyhow::Result<_> {
        let (scenario, text) = match (&sweep, &metadata, &scenario_toml) {
            (Some(path), ..) => touchdown::run::scenario_of_sweep(path, sample, inputs.as_deref())?,
            (None, Some(meta), _) => touchdown::run::scenario_of_metadata(
                &arrow_schema::Metadata::from(meta.clone()),
                Path::new("the sweep table"),
                sample,
                inputs.as_deref(),
            )?,
            (None, None, text) => {
                let text = text.as_deref().unwrap_or(touchdown::scenario::DEFAULT_TOML);
                let (mut scenario, text) = touchdown::run::scenario_of_text(text, seed)?;
                if let Some(path) = &inputs {
                    // A trace writes no kept columns: the table's other columns are let be.
                    touchdown::table::attach(&mut scenario, path, true)?;
                }
                (scenario, text)
            }
        };
        trace_scenario(scenario, &text, &settings)
    });
    if let Some(e) = crate::law::take_error() {
        return Err(e);
    }
    let done = done.or_py()?;
    let text = touchdown::commands::trace::describe(&done.scenario, &done.sample, &done.summary);
    let reader = crate::sweep::reader(done.batches)?;
    Ok((text, reader.into_pyarrow(py)?))
}
