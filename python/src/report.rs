//! `touchdown.report`: what `touchdown report` says of a sweep, of its file or of its table
//! held in memory, as Markdown or as the JSON document of `report --json`.

use crate::errors::OrPy;
use arrow_pyarrow::{FromPyArrow, Table};
use pyo3::prelude::*;
use std::path::PathBuf;
use touchdown::output::sweep::SweepSource;

/// The report of the sweep file `path`, or of `table` (a pyarrow table with a sweep's
/// schema metadata), weighed onto `slope_distribution` if given (as `report
/// --slope-distribution`); JSON text if `json`, else Markdown.
#[pyfunction]
#[pyo3(signature = (path=None, table=None, slope_distribution=None, json=true))]
pub fn report(
    py: Python<'_>,
    path: Option<PathBuf>,
    table: Option<&Bound<'_, PyAny>>,
    slope_distribution: Option<String>,
    json: bool,
) -> PyResult<String> {
    let source = match (path, table) {
        (Some(path), _) => SweepSource::Path(path),
        (None, Some(table)) => {
            let (batches, schema) = Table::from_pyarrow_bound(table)?.into_inner();
            SweepSource::Memory {
                name: "the sweep table".to_string(),
                schema,
                batches,
            }
        }
        (None, None) => {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "report: give a sweep's file or its table",
            ));
        }
    };
    py.detach(|| -> anyhow::Result<String> {
        let terrain = slope_distribution
            .as_deref()
            .map(|d| touchdown::weighting::SlopeDistribution::parse(d).map(|t| (t, d)))
            .transpose()?;
        let terrain = terrain.as_ref().map(|(t, d)| (t, *d));
        if json {
            touchdown::report::report_json(&source, terrain)
        } else {
            touchdown::report::report(&source, terrain)
        }
    })
    .or_py()
}
