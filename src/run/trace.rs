//! One sample run with the reference model and its time history written: the scenario
//! from a sweep file, a scenario file or the default, the sample at an index.

use super::load::{load_scenario, scenario_of_sweep};
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
    /// Scenario file (without it and without `sweep`: the default scenario).
    pub scenario: Option<PathBuf>,
    /// Overrides the scenario's seed.
    pub seed: Option<u64>,
    /// The table of inputs the sweep ran, or the one to take row `sample` of.
    pub inputs: Option<PathBuf>,
    /// The sample's index.
    pub sample: u64,
    /// The trace file.
    pub out: PathBuf,
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
}

/// Runs the sample `args` names and writes its time history to `args.out`.
pub fn trace(args: &TraceSettings) -> anyhow::Result<Traced> {
    crate::output::check_output_path(&args.out)?;
    let (scenario, text) = match &args.sweep {
        Some(sweep) => scenario_of_sweep(sweep, args.sample, args.inputs.as_deref())?,
        None => {
            let (mut scenario, text) = load_scenario(args.scenario.as_ref(), args.seed)?;
            if let Some(path) = &args.inputs {
                // A trace writes no kept columns: the table's other columns are let be.
                crate::table::attach(&mut scenario, path, true)?;
                let rows = scenario.table.as_ref().map_or(0, |t| t.rows);
                if args.sample >= rows {
                    anyhow::bail!(
                        "--sample {}: the table of inputs {} has rows 0 to {}",
                        args.sample,
                        path.display(),
                        rows - 1
                    );
                }
            }
            (scenario, text)
        }
    };
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
        scenario_toml: &text,
        sweep_seed: scenario.seed,
        sample: &sample,
        summary: &summary,
        table: scenario.table.as_deref(),
        control: &crate::output::sweep::control_columns(&scenario),
    };
    let rows = trace::write(&args.out, &model, &info, args.every)?;
    Ok(Traced {
        scenario,
        sample,
        summary,
        rows,
    })
}
