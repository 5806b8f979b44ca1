//! `touchdown.trace`: one sample run with the reference model, its time history kept in
//! memory and handed to pyarrow, with what the command line prints of it.

use crate::counts::{self, whole};
use crate::errors::OrPy;
use arrow_pyarrow::IntoPyArrow;
use pyo3::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use touchdown::run::trace::{self as run_trace, TraceSettings, trace_scenario};
use touchdown::scenario::DEFAULT_TOML;

/// Runs sample `sample` of a scenario (its TOML text, `seed` overriding its own), of the
/// sweep file `sweep`, or of the sweep whose schema metadata is `metadata` (a table held in
/// memory), one row every `every` steps. Returns what `touchdown trace` prints and the
/// time history as a `pyarrow.RecordBatchReader`.
#[pyfunction]
#[pyo3(signature = (sample, every=None, scenario_toml=None, seed=None, sweep=None, metadata=None, inputs=None))]
#[allow(clippy::too_many_arguments)]
pub fn trace<'py>(
    py: Python<'py>,
    sample: Bound<'py, PyAny>,
    every: Option<Bound<'py, PyAny>>,
    scenario_toml: Option<String>,
    seed: Option<Bound<'py, PyAny>>,
    sweep: Option<PathBuf>,
    metadata: Option<HashMap<String, String>>,
    inputs: Option<PathBuf>,
) -> PyResult<(String, Bound<'py, PyAny>)> {
    let sample = whole("sample", Some(&sample), counts::INDEX)?.unwrap_or_default();
    let every = whole("every", every.as_ref(), counts::POSITIVE)?.unwrap_or(1);
    let seed = whole("seed", seed.as_ref(), counts::INDEX)?;
    crate::law::clear();
    let settings = TraceSettings {
        sweep,
        scenario: None,
        // The default scenario where neither a text nor a sweep is given.
        scenario_toml: Some(scenario_toml.unwrap_or_else(|| DEFAULT_TOML.to_string())),
        seed,
        inputs,
        sample,
        out: None,
        every,
    };
    let done = py.detach(|| match &metadata {
        // A sweep held in memory: its scenario from its schema's metadata.
        Some(meta) if settings.sweep.is_none() => touchdown::run::scenario_of_metadata(
            &arrow_schema::Metadata::from(meta.clone()),
            Path::new("the sweep table"),
            sample,
            settings.inputs.as_deref(),
        )
        .and_then(|(scenario, text)| trace_scenario(scenario, &text, &settings)),
        _ => run_trace::trace(&settings),
    });
    if let Some(e) = crate::law::take_error() {
        return Err(e);
    }
    let done = done.or_py()?;
    let text = touchdown::commands::trace::describe(&done.scenario, &done.sample, &done.summary);
    let reader = crate::sweep::reader(done.batches)?;
    Ok((text, reader.into_pyarrow(py)?))
}
