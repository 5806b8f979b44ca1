//! What a sweep runs: the settings a command gives, checked into a plan (scenario, samples,
//! shard, format, kernel), or the plan that finishes an interrupted sweep.

use super::load::{KernelChoice, load_scenario, scenario_from_toml, scenario_of_text};
use crate::output::format::Format;
use crate::scenario::{Design, Scenario};
use crate::sweep::Shard;
use kernels::isa::KernelKind;
use std::path::{Path, PathBuf};

/// The settings of a sweep, as the command line gives them (`touchdown sweep`'s flags).
#[derive(Debug, Clone)]
pub struct SweepSettings {
    /// Scenario file; the default scenario without it (or `scenario_toml`).
    pub scenario: Option<PathBuf>,
    /// The scenario as TOML text, in place of a file (the Python package's `Scenario`).
    pub scenario_toml: Option<String>,
    /// Samples; default: the scenario's, or the table's rows.
    pub samples: Option<u64>,
    /// Overrides the scenario's seed.
    pub seed: Option<u64>,
    /// Overrides the scenario's design.
    pub design: Option<Design>,
    /// The user's table of inputs.
    pub inputs: Option<PathBuf>,
    /// Pass the table's other columns through.
    pub keep_columns: bool,
    /// The sweep file to write; none for a sweep kept in memory only (`RunOptions::keep`).
    pub out: Option<PathBuf>,
    /// The format asked for (default: from the extension of `out`).
    pub format: Option<Format>,
    /// The interrupted sweep to finish (its `out`); the settings above but `inputs` and
    /// `kernel` are then the interrupted sweep's.
    pub resume: Option<PathBuf>,
    /// The slice of the sweep to run (`--shard K/N`).
    pub shard: Option<Shard>,
    /// The kernel to run with (`--kernel`).
    pub kernel: KernelChoice,
}

/// What a sweep runs: its settings, and where it starts when it resumes.
pub struct SweepPlan {
    /// The scenario, with the command line's seed and design applied.
    pub scenario: Scenario,
    /// Its TOML text, as the file's metadata stores it.
    pub text: String,
    /// Samples of the whole sweep (of all its shards).
    pub samples: u64,
    /// The slice of the sweep it runs, if it is a shard.
    pub shard: Option<Shard>,
    /// The format of the file.
    pub format: crate::output::format::Format,
    /// The sweep file it writes (under `OUT.interrupted` if a signal stops it); none for a
    /// sweep kept in memory only.
    pub out: Option<PathBuf>,
    /// The kernel it runs with (the precision is the scenario's).
    pub kernel: KernelKind,
    /// The interrupted sweep whose first rows this one takes over.
    pub resume: Option<crate::output::resume::Interrupted>,
    /// What to run to continue where a signal stops this sweep.
    pub continue_with: String,
}

/// The word of `design` on the command line (`--design`).
fn design_word(design: Design) -> &'static str {
    match design {
        Design::SobolIndices => "sobol-indices",
        Design::SobolSequence => "sobol-sequence",
        Design::Independent => "independent",
    }
}

impl SweepPlan {
    /// The plan of a sweep with `settings`.
    pub fn new(args: &SweepSettings) -> anyhow::Result<SweepPlan> {
        if let Some(out) = &args.resume {
            return SweepPlan::resuming(out, args.inputs.as_deref(), args.kernel);
        }
        if let Some(out) = &args.out {
            crate::output::check_sweep_output_path(out)?;
        }
        let (scenario, text) = match &args.scenario_toml {
            Some(text) => scenario_of_text(text, args.seed)?,
            None => load_scenario(args.scenario.as_ref(), args.seed)?,
        };
        // The design as the command line asks, checked as a scenario that says so is, and
        // stored with the scenario's text (`sensitivity` reads it there).
        let (scenario, text) = match args.design {
            None => (scenario, text),
            Some(design) => {
                let text = crate::scenario::with_design(&text, design);
                let mut again = scenario_from_toml(&text)
                    .map_err(|e| anyhow::anyhow!("--design {}: {e}", design_word(design)))?;
                again.seed = scenario.seed;
                (again, text)
            }
        };
        let mut scenario = scenario;
        if let Some(path) = &args.inputs {
            crate::table::attach(&mut scenario, path, args.keep_columns)?;
        }
        let samples = match (&scenario.table, args.samples) {
            (Some(t), Some(n)) if n > t.rows => anyhow::bail!(
                "--samples {n}: the table of inputs {} has {} rows (one sample each)",
                t.path.display(),
                t.rows
            ),
            (Some(t), None) => t.rows,
            (_, n) => n.unwrap_or(scenario.samples),
        };
        if samples == 0 {
            anyhow::bail!("--samples must be at least 1");
        }
        let kernel = KernelKind {
            isa: args.kernel.isa()?,
            precision: scenario.simulation.precision,
        };
        Ok(SweepPlan {
            scenario,
            text,
            samples,
            shard: args.shard,
            format: match &args.out {
                Some(out) => output_format(out, args.format)?,
                None => args.format.unwrap_or(Format::Arrow),
            },
            out: args.out.clone(),
            kernel,
            resume: None,
            continue_with: args.out.as_ref().map_or_else(String::new, |out| {
                format!("touchdown sweep --resume {}", out.display())
            }),
        })
    }

    /// The plan that finishes the interrupted sweep to `out` (`sweep --resume`), its table
    /// of inputs reread where the sweep read it (or at `inputs`).
    pub fn resuming(
        out: &Path,
        inputs: Option<&Path>,
        kernel: KernelChoice,
    ) -> anyhow::Result<SweepPlan> {
        let from = crate::output::resume::Interrupted::read(out)?;
        refuse_older_than_finished(out, &from)?;
        let mut scenario = scenario_from_toml(&from.scenario_toml)
            .map_err(|e| anyhow::anyhow!("the scenario of {}: {e}", from.path.display()))?;
        scenario.seed = from.seed;
        crate::table::reattach(&mut scenario, &from.meta, inputs, &from.path)?;
        let kernel = KernelKind {
            isa: kernel.isa()?,
            precision: scenario.simulation.precision,
        };
        if from.lane_type != kernel.arithmetic() {
            anyhow::bail!(
                "{} was computed with {} kernels, the {} kernel here is {}, whose rows \
                 differ in the last bits: resume it on a machine like the first, or run \
                 the sweep again",
                from.path.display(),
                from.lane_type,
                kernel.name(),
                kernel.arithmetic()
            );
        }
        crate::output::check_sweep_output_path(out)?;
        Ok(SweepPlan {
            scenario,
            text: from.scenario_toml.clone(),
            samples: from.samples,
            shard: from.shard,
            format: from.format,
            out: Some(out.to_path_buf()),
            kernel,
            resume: Some(from),
            continue_with: format!("touchdown sweep --resume {}", out.display()),
        })
    }
}

/// The format of output `out`: `--format` if given, else from the extension (`.parquet`
/// or `.pq`: Parquet; anything else: Arrow). A `--format` that contradicts the extension
/// (`--format arrow --out x.parquet`) is refused.
pub fn output_format(out: &Path, flag: Option<Format>) -> anyhow::Result<Format> {
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let from_ext = match ext.as_deref() {
        Some("parquet" | "pq") => Some(Format::Parquet),
        Some("arrow" | "feather" | "ipc" | "arrows") => Some(Format::Arrow),
        _ => None,
    };
    match (flag, from_ext) {
        (Some(f), Some(e)) if f != e => anyhow::bail!(
            "--format {} contradicts the extension of --out {} ({} file): drop --format or \
             rename the file",
            f.key(),
            out.display(),
            match e {
                Format::Arrow => "an arrow",
                Format::Parquet => "a parquet",
            }
        ),
        (Some(f), _) => Ok(f),
        (None, e) => Ok(e.unwrap_or(Format::Arrow)),
    }
}

/// Refuses to resume the interrupted sweep `from` onto `out` where `out` is a finished file
/// written after the interruption (a later run to the same path): resuming would replace
/// the newer file with the older run's.
fn refuse_older_than_finished(
    out: &Path,
    from: &crate::output::resume::Interrupted,
) -> anyhow::Result<()> {
    let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    let (Some(finished), Some(interrupted)) = (modified(out), modified(&from.path)) else {
        return Ok(());
    };
    let Ok(later) = finished.duration_since(interrupted) else {
        return Ok(());
    };
    if later.is_zero() {
        return Ok(());
    }
    let run = crate::output::read::format_of(out)
        .and_then(|f| crate::output::read::open(out, f))
        .ok()
        .map(|(schema, _)| {
            let m = schema.metadata();
            let key = |k: &str| m.get(k).map_or("?", String::as_str).to_string();
            format!(
                "a sweep of seed {}, {} samples",
                key("touchdown.seed"),
                key("touchdown.samples")
            )
        })
        .unwrap_or_else(|| "not a sweep file of touchdown".to_string());
    anyhow::bail!(
        "--resume {}: {} ({run}) was written {} after {} (seed {}, {} samples, {} rows done) \
         was interrupted; resuming would replace the newer file with the older run's. To \
         keep {}, remove {}; to resume, move {} away first",
        out.display(),
        out.display(),
        super::eta::duration(later.as_secs_f64()),
        from.path.display(),
        from.seed,
        from.samples,
        from.rows,
        out.display(),
        from.path.display(),
        out.display()
    )
}
