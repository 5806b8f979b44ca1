//! One sample run with the reference model and its time history written: the scenario
//! from a sweep file, a scenario file or the default, the sample at an index.

use super::load::{load_scenario, scenario_of_sweep, scenario_of_text};
use crate::output::trace::{self, TraceInfo};
use crate::reference::{self, Model, Summary};
use crate::sampling;
use crate::scenario::Sample;
use crate::scenario::Scenario;
use std::io::Write as _;
use std::path::PathBuf;

/// The settings of a trace (`touchdown trace`'s flags).
#[derive(Debug, Clone)]
pub struct TraceSettings {
    /// The sweep or shard file whose scenario and seed the trace runs.
    pub sweep: Option<PathBuf>,
    /// Scenario file (without it and without `sweep`: the default scenario, or
    /// `scenario_toml`).
    pub scenario: Option<PathBuf>,
    /// The scenario as TOML text, in place of a file (the Python package's `Scenario`).
    pub scenario_toml: Option<String>,
    /// Overrides the scenario's seed.
    pub seed: Option<u64>,
    /// The table of inputs the sweep ran, or the one to take row `sample` of.
    pub inputs: Option<PathBuf>,
    /// The sample's index.
    pub sample: u64,
    /// The trace file; none for a trace kept in memory (`Traced::batches`).
    pub out: Option<PathBuf>,
    /// One row every `every` steps.
    pub every: u64,
}

/// What a trace ran and wrote.
pub struct Traced {
    /// The scenario the sample was drawn from.
    pub scenario: Scenario,
    /// The sample run: its drawn inputs.
    pub sample: Sample,
    /// The sample's results from the reference model.
    pub summary: Summary,
    /// Rows written.
    pub rows: u64,
    /// The time history, where it was kept in memory (no `out`).
    pub batches: Vec<arrow_array::RecordBatch>,
}

/// Runs the sample `args` names and writes its time history to `args.out`.
pub fn trace(args: &TraceSettings) -> anyhow::Result<Traced> {
    if let Some(out) = &args.out {
        crate::output::check_output_path(out)?;
    }
    let (scenario, text) = match &args.sweep {
        Some(sweep) => scenario_of_sweep(sweep, args.sample, args.inputs.as_deref())?,
        None => scenario_of(args)?,
    };
    trace_scenario(scenario, &text, args)
}

/// Runs sample `args.sample` of `scenario` (its TOML `text`, as the trace stores it) and
/// writes its time history to `args.out`, or keeps it (no `out`); `args`' scenario, seed
/// and sweep are not read.
pub fn trace_scenario(
    scenario: Scenario,
    text: &str,
    args: &TraceSettings,
) -> anyhow::Result<Traced> {
    if let Some(t) = &scenario.table
        && args.sample >= t.rows
    {
        anyhow::bail!(
            "--sample {}: the table of inputs {} has rows 0 to {}",
            args.sample,
            t.path.display(),
            t.rows - 1
        );
    }
    if scenario.simulation.precision == kernels::isa::Precision::F32 {
        // Written without `eprintln!`, which panics where stderr is gone.
        let _ = writeln!(
            std::io::stderr(),
            "touchdown: note: the scenario's sweeps run in f32 lanes; a trace runs the f64 \
             reference, whose outcome may differ from a sweep row's near a decision threshold \
             (11 of 100,000 default samples end otherwise in f32 lanes than in f64 lanes)"
        );
    }
    let model = Model::new(&scenario);
    let sample = sampling::sample(&scenario, args.sample);
    let summary = reference::run(&model, &sample, |_| {});
    let info = TraceInfo {
        scenario_toml: text,
        sweep_seed: scenario.seed,
        sample: &sample,
        summary: &summary,
        table: scenario.table.as_deref(),
        control: &crate::output::sweep::control_columns(&scenario),
    };
    let (rows, batches) = match &args.out {
        Some(out) => (trace::write(out, &model, &info, args.every)?, Vec::new()),
        None => {
            let batches = trace::batches(&model, &info, args.every)?;
            let rows = batches.iter().map(|b| b.num_rows() as u64).sum();
            (rows, batches)
        }
    };
    Ok(Traced {
        scenario,
        sample,
        summary,
        rows,
        batches,
    })
}

/// The scenario of a trace not of a sweep file: `args`' scenario file or the default, with
/// its table of inputs if it names one, and its text.
fn scenario_of(args: &TraceSettings) -> anyhow::Result<(Scenario, String)> {
    let (mut scenario, text) = match &args.scenario_toml {
        Some(text) => scenario_of_text(text, args.seed)?,
        None => load_scenario(args.scenario.as_ref(), args.seed)?,
    };
    if let Some(path) = &args.inputs {
        // A trace writes no kept columns: the table's other columns are let be.
        crate::table::attach(&mut scenario, path, true)?;
    }
    Ok((scenario, text))
}
