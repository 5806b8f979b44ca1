//! The scenario a run runs: from its file or the default, from a sweep file's metadata, or
//! from TOML text, always checked the same way; and the kernel it runs with.

use crate::scenario::{DEFAULT_TOML, Scenario, ScenarioError};
use kernels::isa::Isa;
use std::path::{Path, PathBuf};

/// The scenario to run from its TOML text: every command that runs a scenario read from
/// text (a file, a sweep file's metadata, a study's value) gets it here. Read and checked
/// (`Scenario::from_toml`), then its control loop checked against its thrusters and the laws
/// this program registers (`control::check`), which the data model cannot do itself.
pub fn scenario_from_toml(text: &str) -> Result<Scenario, ScenarioError> {
    let s = Scenario::from_toml(text)?;
    crate::control::check(&s)?;
    Ok(s)
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
    let (scenario, text) = match path {
        None => (Scenario::default(), DEFAULT_TOML.to_string()),
        Some(p) => {
            let text = std::fs::read_to_string(p)
                .map_err(|e| anyhow::anyhow!("cannot read scenario file {}: {e}", p.display()))?;
            (scenario_from_toml(&text)?, text)
        }
    };
    Ok(seeded(scenario, &text, seed))
}

/// The scenario of TOML `text` with `seed` applied, and the text to store as its
/// provenance (`load_scenario` of text rather than a file).
pub fn scenario_of_text(text: &str, seed: Option<u64>) -> anyhow::Result<(Scenario, String)> {
    Ok(seeded(scenario_from_toml(text)?, text, seed))
}

/// `scenario` with `seed` applied if given, and its `text` with the seed that runs.
fn seeded(mut scenario: Scenario, text: &str, seed: Option<u64>) -> (Scenario, String) {
    if let Some(s) = seed {
        scenario.seed = s;
    }
    // The text stored as provenance is the scenario that runs, seed included.
    let text = crate::scenario::with_seed(text, scenario.seed);
    (scenario, text)
}

/// The scenario (with its seed) that a sweep or shard file `path` ran, and its text; checks
/// that sample `index` is one of its samples.
pub fn scenario_of_sweep(
    path: &Path,
    index: u64,
    inputs: Option<&Path>,
) -> anyhow::Result<(Scenario, String)> {
    let file = crate::output::sweep::SweepFile::open(path)?;
    scenario_of_metadata(file.metadata(), path, index, inputs)
}

/// The scenario (with its seed) that the sweep whose schema metadata is `meta` ran, and its
/// text; checks that sample `index` is one of its samples. `path` names the sweep in
/// messages (its file, or what holds it in memory).
pub fn scenario_of_metadata(
    meta: &arrow_schema::Metadata,
    path: &Path,
    index: u64,
    inputs: Option<&Path>,
) -> anyhow::Result<(Scenario, String)> {
    if meta.get("touchdown.kind").map(String::as_str) != Some("sweep") {
        anyhow::bail!("{} is not a sweep of touchdown", path.display());
    }
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
        super::workers::tell(&format!(
            "touchdown: warning: {} was written by {engine}, this is {}: the trace may differ \
             from its row\n",
            path.display(),
            crate::output::ENGINE
        ));
    }
    Ok((scenario, crate::scenario::with_seed(&text, seed)))
}
