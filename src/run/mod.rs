//! The sweep run: a scenario from its file, a sweep file or the command line's values
//! turned into a plan, and the plan run on a pool of workers (signals, progress, resume,
//! the writer). Every command that runs the lander (sweep, study, boundary, trace) comes
//! through here; nothing here knows the command line's flags.

pub mod boundary;
mod execute;
mod plan;
pub mod study;
pub mod trace;

pub use execute::{Executed, RunOptions, execute, warn_untouched};
pub use plan::{SweepPlan, SweepSettings, output_format};

use crate::scenario::{DEFAULT_TOML, Scenario, ScenarioError};
use kernels::isa::Isa;
use std::path::{Path, PathBuf};

/// The scenario to run from its TOML text: every command that runs a scenario read from
/// text (a file, a sweep file's metadata, a study's value) gets it here.
pub fn scenario_from_toml(text: &str) -> Result<Scenario, ScenarioError> {
    Scenario::from_toml(text)
}

/// The kernel a sweep runs with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelChoice {
    /// The widest this CPU runs.
    Auto,
    /// This one.
    Isa(Isa),
}

impl KernelChoice {
    /// The instruction set to run: refused, naming what the CPU lacks, if it cannot.
    pub fn isa(self) -> anyhow::Result<Isa> {
        match self {
            KernelChoice::Auto => Ok(Isa::detect()),
            KernelChoice::Isa(isa) if isa.available() => Ok(isa),
            KernelChoice::Isa(isa) => anyhow::bail!(
                "--kernel {}: this CPU cannot run it (it lacks {}); --kernel auto picks {}",
                isa.key(),
                isa.missing_features().join(", "),
                Isa::detect().key()
            ),
        }
    }
}

/// A scenario from its file (or the default) with the command line's seed applied, and the
/// text to store as its provenance.
pub fn load_scenario(
    path: Option<&PathBuf>,
    seed: Option<u64>,
) -> anyhow::Result<(Scenario, String)> {
    let (mut scenario, text) = match path {
        None => (Scenario::default(), DEFAULT_TOML.to_string()),
        Some(p) => {
            let text = std::fs::read_to_string(p)
                .map_err(|e| anyhow::anyhow!("cannot read scenario file {}: {e}", p.display()))?;
            (scenario_from_toml(&text)?, text)
        }
    };
    if let Some(s) = seed {
        scenario.seed = s;
    }
    // The text stored as provenance is the scenario that runs, seed included.
    let text = crate::scenario::with_seed(&text, scenario.seed);
    Ok((scenario, text))
}

/// The scenario (with its seed) that a sweep or shard file `path` ran, and its text; checks
/// that sample `index` is one of its samples.
pub fn scenario_of_sweep(
    path: &Path,
    index: u64,
    inputs: Option<&Path>,
) -> anyhow::Result<(Scenario, String)> {
    let (schema, _) = crate::output::read::open_sweep(path)?;
    let meta = schema.metadata();
    let get = |key: &str| {
        meta.get(key)
            .ok_or_else(|| anyhow::anyhow!("{}: no {key} in its metadata", path.display()))
    };
    let text = get("touchdown.scenario")?.clone();
    let number = |key: &str| -> anyhow::Result<u64> {
        get(key)?
            .parse()
            .map_err(|_| anyhow::anyhow!("{}: {key} is not a whole number", path.display()))
    };
    let (seed, samples) = (number("touchdown.seed")?, number("touchdown.samples")?);
    let mut scenario = scenario_from_toml(&text)
        .map_err(|e| anyhow::anyhow!("the scenario stored in {}: {e}", path.display()))?;
    scenario.seed = seed;
    crate::table::reattach(&mut scenario, meta, inputs, path)?;
    if index >= samples {
        anyhow::bail!(
            "--sample {index}: {} has samples 0 to {} (its sweep ran {samples})",
            path.display(),
            samples.saturating_sub(1)
        );
    }
    let engine = get("touchdown.engine")?;
    if engine != crate::output::ENGINE {
        eprintln!(
            "touchdown: warning: {} was written by {engine}, this is {}: the trace may differ \
             from its row",
            path.display(),
            crate::output::ENGINE
        );
    }
    Ok((scenario, crate::scenario::with_seed(&text, seed)))
}

/// Samples per task of the sweep's workers.
pub const CHUNK: u64 = 1024;

/// A sweep stopped by a signal; its rows so far are in a valid file beside the output.
#[derive(Debug)]
pub struct Interrupted {
    /// The exit code: 128 + the signal (130 for SIGINT, 143 for SIGTERM).
    pub code: u8,
    pub message: String,
}

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Interrupted {}

/// The signal that asked the sweep to stop (0: none yet). A first SIGINT or SIGTERM sets
/// it; a second one ends the process at once (the unfinished file keeps its temporary
/// name, so nothing looks complete that is not).
pub fn stop_on_signals() -> anyhow::Result<std::sync::Arc<std::sync::atomic::AtomicUsize>> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, AtomicUsize};
    let asked = Arc::new(AtomicBool::new(false));
    let which = Arc::new(AtomicUsize::new(0));
    for signal in [SIGINT, SIGTERM] {
        signal_hook::flag::register_conditional_shutdown(signal, 128 + signal, asked.clone())?;
        signal_hook::flag::register(signal, asked.clone())?;
        signal_hook::flag::register_usize(signal, which.clone(), signal as usize)?;
    }
    Ok(which)
}

/// The pool of `--threads` workers (default: one per core).
pub fn worker_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    let threads = threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, std::num::NonZero::get));
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
}

/// An output path as messages name it (`-` is standard output).
#[must_use]
pub fn shown(out: &Path) -> String {
    if out.as_os_str() == "-" {
        "standard output".to_string()
    } else {
        out.display().to_string()
    }
}
