//! `touchdown._touchdown`: the extension module under the Python package `touchdown`
//! (python/touchdown/__init__.py). Each function calls the library the command line calls:
//! a scenario is read and checked by `run::scenario_from_toml`, a sweep is `run::execute`'s
//! plan run on worker threads with its batches kept, a trace is `run::trace::trace_scenario`
//! kept in memory, a report is `report::report`'s. Errors keep the command line's messages.

mod counts;
mod errors;
mod law;
mod report;
mod scenario;
mod sweep;
mod trace;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _touchdown(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("TouchdownError", py.get_type::<errors::TouchdownError>())?;
    m.add("ScenarioError", py.get_type::<errors::ScenarioError>())?;
    m.add_class::<scenario::Scenario>()?;
    m.add_class::<sweep::SweepRun>()?;
    m.add_class::<law::Sensed>()?;
    m.add_function(wrap_pyfunction!(law::register_law, m)?)?;
    m.add_function(wrap_pyfunction!(law::registered_laws, m)?)?;
    m.add_function(wrap_pyfunction!(trace::trace, m)?)?;
    m.add_function(wrap_pyfunction!(report::report, m)?)?;
    m.add("ENGINE", touchdown::output::ENGINE)?;
    m.add("DEFAULT_TOML", touchdown::scenario::DEFAULT_TOML)?;
    Ok(())
}
