//! The command line: raw flags (clap) apart from the work they start.

use crate::output::format::Format;
use crate::output::sweep::{SweepInfo, SweepWriter};
use crate::output::trace::{self, TraceInfo};
use crate::reference::Outcome;
use crate::reference::{self, Model, Summary};
use crate::sampling;
use crate::scenario::Sample;
use crate::scenario::{DEFAULT_TOML, INPUT_FIELDS, Scenario};
use crate::sweep::Shard;
use clap::{Parser, Subcommand};
use kernels::isa::{Isa, KernelKind};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Monte Carlo touchdown simulation of legged landers on asteroids.
#[derive(Parser, Debug)]
#[command(name = "touchdown", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Print the default scenario as a commented TOML file to edit.
    Scenario,
    /// Run one sample with the reference model and write its time history.
    Trace(TraceArgs),
    /// Run a Monte Carlo sweep through the SIMD kernels and write one row per sample.
    Sweep(SweepArgs),
    /// Summarise a sweep file: outcomes with 95 % intervals, the allowable slope per
    /// azimuth sector, peak loads (Markdown on stdout).
    Report(ReportArgs),
    /// Compare two sweeps of the same seed sample by sample (paired: the same landers
    /// wherever the scenarios draw an input alike): outcome shares, their differences with
    /// 95 % intervals, and which samples changed outcome (Markdown on stdout).
    Compare(CompareArgs),
    /// Sobol sensitivity indices of every input drawn at random, for P(stable), P(tipped),
    /// peak CG acceleration and longest damper stroke, from a sweep run with
    /// `design = "sobol-indices"` (Markdown on stdout).
    Sensitivity(SensitivityArgs),
    /// Run the sweep at each of several values of one scenario key (footpad radius, CG
    /// height, crush strength...) and tabulate outcome shares and the allowable slope per
    /// sector against it (Arrow, Markdown, PNG with the static limit).
    Study(crate::study::StudyArgs),
    /// Join the shard files of one sweep (`sweep --shard K/N`) into the file the sweep
    /// writes when run in one process.
    Merge(MergeArgs),
    /// Draw PNG pictures of a sweep file (stability map, tipped share per slope, load
    /// distributions) or of a trace file (CG and leg time histories, 3D path, shock along
    /// Z_B).
    Plot(PlotArgs),
    /// Animate a trace file as a GIF: the lander in 3D on its slope, the CG's trail, the
    /// contact forces and thrust plumes, with time, tilt and outcome.
    Animate(AnimateArgs),
    /// Write a trace file as one self-contained HTML page: the lander in 3D (drag to orbit,
    /// wheel to zoom), a time slider with play and pause, and the histories as charts.
    View(ViewArgs),
    /// Find the allowable slope per azimuth sector directly, by adaptive sampling.
    Boundary(crate::boundary::BoundaryArgs),
}

/// Flags of `touchdown animate`.
#[derive(clap::Args, Debug)]
pub struct AnimateArgs {
    /// A trace file (`touchdown trace` writes one).
    pub trace: PathBuf,
    /// GIF file to write (default: the trace's name with .gif).
    #[arg(long, value_name = "PATH")]
    pub out: Option<PathBuf>,
    /// Frames per second of playback, 1 to 50.
    #[arg(
        long,
        value_name = "N",
        default_value = "15",
        allow_negative_numbers = true
    )]
    pub fps: f64,
    /// Trace seconds per second of playback (default: the trace plays in 15 s, and never
    /// slower than real time; the last frame then stays 2 s).
    #[arg(long, value_name = "X", allow_negative_numbers = true)]
    pub speed: Option<f64>,
    /// Picture size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "640x480", value_parser = parse_size)]
    pub size: (u32, u32),
}

/// Flags of `touchdown sensitivity`.
#[derive(clap::Args, Debug)]
pub struct SensitivityArgs {
    /// A sweep or shard file (Arrow or Parquet) run with `design = "sobol-indices"`.
    pub sweep: PathBuf,
    /// Bootstrap replicates behind the 95 % intervals.
    #[arg(long, value_name = "B", default_value = "1000", value_parser = parse_count, allow_negative_numbers = true)]
    pub bootstrap: u64,
    /// Also draw the indices as a bar chart, to this PNG file.
    #[arg(long, value_name = "PATH")]
    pub png: Option<PathBuf>,
}

/// Flags of `touchdown view`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// A trace file (`touchdown trace` writes one).
    pub trace: PathBuf,
    /// HTML file to write (default: the trace's name with .html).
    #[arg(long, value_name = "PATH")]
    pub out: Option<PathBuf>,
}

/// Parses a picture size written `640x480`.
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("{s:?} is not a size WIDTHxHEIGHT in pixels (example: 640x480)");
    let (w, h) = s.trim().split_once(['x', 'X']).ok_or_else(bad)?;
    Ok((w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?))
}

/// The output beside `trace` with `extension`, unless `out` names one.
fn beside(trace: &Path, out: Option<&PathBuf>, extension: &str) -> PathBuf {
    out.cloned()
        .unwrap_or_else(|| trace.with_extension(extension))
}

/// Flags of `touchdown sweep`.
#[derive(clap::Args, Debug)]
pub struct SweepArgs {
    /// Scenario file (TOML); without it, the default sweep of MODEL.md section 11.
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Number of samples (accepts 1e6, 250000, 2.5e5); default: the scenario's `samples`.
    #[arg(long, value_name = "N", value_parser = parse_count, allow_negative_numbers = true)]
    pub samples: Option<u64>,
    /// Seed of the sweep (overrides the scenario's `seed`).
    #[arg(long, value_name = "S", value_parser = parse_seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// How samples draw their inputs (overrides the scenario's `design`): independent,
    /// sobol-sequence (quasi-random), or sobol-indices (Saltelli's design, for
    /// `touchdown sensitivity`).
    #[arg(long, value_name = "DESIGN", value_parser = ["independent", "sobol-sequence", "sobol-indices"])]
    pub design: Option<String>,
    /// The user's own inputs: a table (CSV, Arrow or Parquet), one sample per row, in
    /// order, its columns named as the sweep's input columns; what it does not give is
    /// drawn from the scenario. The sweep runs its rows (--samples N: the first N).
    #[arg(long, value_name = "TABLE")]
    pub inputs: Option<PathBuf>,
    /// Pass the table's other columns through to the output (without it, a column the
    /// sweep does not know is refused).
    #[arg(long, requires = "inputs", conflicts_with = "resume")]
    pub keep_columns: bool,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "T", value_parser = parse_threads, allow_negative_numbers = true)]
    pub threads: Option<usize>,
    /// Output file; `-` writes to standard output (Arrow as an IPC stream). A device or
    /// FIFO at PATH (or a symbolic link to one) is written into, never replaced.
    #[arg(long, value_name = "PATH", default_value = "sweep.arrow")]
    pub out: PathBuf,
    /// Output format (default: from the extension of --out, `.parquet` for Parquet, else
    /// Arrow); refused when it contradicts the extension.
    #[arg(long, value_enum)]
    pub format: Option<Format>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Continue the sweep that was interrupted while writing PATH (its `--out`), with the
    /// scenario, seed, samples, shard and format it was started with; the finished file is
    /// the one an uninterrupted sweep writes.
    #[arg(
        long,
        value_name = "PATH",
        conflicts_with_all = ["scenario", "samples", "seed", "design", "out", "format", "shard"]
    )]
    pub resume: Option<PathBuf>,
    /// Run only the K-th of N contiguous slices of the samples (K from 0 to N-1, as a Slurm
    /// array numbers its tasks); `touchdown merge` joins the N files.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<Shard>,
    /// SIMD kernel: `auto` picks the widest this CPU runs (avx512, then avx2, then
    /// portable). avx512 and avx2 give the same bits; portable on x86-64 rounds its
    /// multiply-adds apart (no FMA there) and differs from them in the last bits.
    #[arg(long, value_name = "KERNEL", default_value = "auto", value_parser = parse_kernel)]
    pub kernel: KernelChoice,
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

pub(crate) fn parse_kernel(s: &str) -> Result<KernelChoice, String> {
    if s == "auto" {
        return Ok(KernelChoice::Auto);
    }
    Isa::from_key(s).map(KernelChoice::Isa).ok_or_else(|| {
        let keys: Vec<&str> = Isa::ALL.iter().map(|i| i.key()).collect();
        format!("{s:?} is not a kernel: auto, {}", keys.join(", "))
    })
}

/// Flags of `touchdown report`.
#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// The sweep file (Arrow IPC or Parquet).
    #[arg(value_name = "SWEEP")]
    pub sweep: PathBuf,
    /// The outcome shares on a terrain with this distribution of slopes, each sample
    /// weighed by its density over the sweep's: uniform:MIN:MAX, normal:MEAN:SD,
    /// rayleigh:SIGMA, exponential:MEAN (deg), or a CSV file of bins with the columns
    /// slope_min_deg, slope_max_deg, probability.
    #[arg(long, value_name = "D")]
    pub slope_distribution: Option<String>,
}

/// Flags of `touchdown compare`.
#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// The first sweep file (A).
    #[arg(value_name = "A")]
    pub a: PathBuf,
    /// The second sweep file (B), of the same seed and samples.
    #[arg(value_name = "B")]
    pub b: PathBuf,
}

/// Flags of `touchdown plot`.
#[derive(clap::Args, Debug)]
pub struct PlotArgs {
    /// A sweep file (Arrow IPC or Parquet) or a trace file (Arrow IPC).
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// Folder to write the PNG files into (default: the file's folder; made if missing);
    /// they are named after the file, e.g. `sweep-stability-map.png`.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
}

/// Flags of `touchdown merge`.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The shard files, in any order (Arrow IPC or Parquet).
    #[arg(value_name = "SHARD", required = true)]
    pub shards: Vec<PathBuf>,
    /// Output file; `-` writes to standard output (Arrow as an IPC stream). A device or
    /// FIFO at PATH (or a symbolic link to one) is written into, never replaced.
    #[arg(long, value_name = "PATH", default_value = "sweep.arrow")]
    pub out: PathBuf,
    /// Output format (default: from the extension of --out, `.parquet` for Parquet, else
    /// Arrow); refused when it contradicts the extension.
    #[arg(long, value_enum)]
    pub format: Option<Format>,
}

/// Flags of `touchdown trace`.
#[derive(clap::Args, Debug)]
pub struct TraceArgs {
    /// A sweep or shard file (Arrow or Parquet): trace its sample I, with the scenario and
    /// seed it ran with (stored in the file), exactly as its row was computed.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["scenario", "seed"])]
    pub sweep: Option<PathBuf>,
    /// Scenario file (TOML); without it (and without --sweep), the default sweep of
    /// MODEL.md section 11.
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Seed of the sweep (overrides the scenario's `seed`).
    #[arg(long, value_name = "S", value_parser = parse_seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// The table of inputs the sweep ran (`sweep --inputs`), where it is no longer where
    /// the sweep file says; with --scenario, row I of this table is the sample.
    #[arg(long, value_name = "TABLE")]
    pub inputs: Option<PathBuf>,
    /// Index of the sample to run, as in the sweep's `sample` column (accepts 1e6, 250000,
    /// 2.5e5).
    #[arg(long, value_name = "I", default_value = "0", value_parser = parse_count, allow_negative_numbers = true)]
    pub sample: u64,
    /// Arrow IPC file to write the time history to; `-` writes an IPC stream to standard
    /// output, and a device or FIFO is written into, never replaced.
    #[arg(long, value_name = "PATH", default_value = "trace.arrow")]
    pub out: PathBuf,
    /// Write one row every N steps.
    #[arg(long, value_name = "N", default_value = "1", value_parser = parse_every, allow_negative_numbers = true)]
    pub every: u64,
}

/// Parses a whole number written as `250000`, `1e6` or `2.5e5`.
pub fn parse_count(s: &str) -> Result<u64, String> {
    let t = s.trim().replace('_', "");
    if let Ok(n) = t.parse::<u64>() {
        return Ok(n);
    }
    let bad = || format!("{s:?} is not a whole number (examples: 250000, 1e6, 2.5e5)");
    let x: f64 = t.parse().map_err(|_| bad())?;
    if !x.is_finite() || x < 0.0 || x.fract() != 0.0 {
        return Err(bad());
    }
    if x > 2f64.powi(63) {
        return Err(format!("{s:?} is too large (at most 2^63)"));
    }
    Ok(x as u64)
}

/// A seed: a whole number a scenario file can hold too (at most 2^63 - 1).
pub(crate) fn parse_seed(s: &str) -> Result<u64, String> {
    match parse_count(s)? {
        n if n > i64::MAX as u64 => Err(format!("must be at most {}", i64::MAX)),
        n => Ok(n),
    }
}

pub(crate) fn parse_threads(s: &str) -> Result<usize, String> {
    match parse_count(s)? {
        0 => Err("must be at least 1".to_string()),
        n if n > 1024 => Err("must be at most 1024".to_string()),
        n => Ok(n as usize),
    }
}

fn parse_every(s: &str) -> Result<u64, String> {
    match parse_count(s)? {
        0 => Err("must be at least 1".to_string()),
        n => Ok(n),
    }
}

/// Runs a parsed command line.
/// The `touchdown` program: parses the command line, runs it, prints an error and returns
/// exit code 2 (or the code of an interruption) where it fails. A program that embeds
/// touchdown, to register laws of its own (`control::register_law`), calls this from its
/// `main`.
#[must_use]
pub fn main() -> std::process::ExitCode {
    use clap::Parser;
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            if let Some(i) = e.downcast_ref::<Interrupted>() {
                eprintln!("touchdown: {i}");
                return std::process::ExitCode::from(i.code);
            }
            eprintln!("touchdown: error: {e:#}");
            std::process::ExitCode::from(2)
        }
    }
}

pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Scenario => {
            print_out(DEFAULT_TOML);
            Ok(())
        }
        Command::Trace(args) => run_trace(&args),
        Command::Sweep(args) => run_sweep(&args),
        Command::Study(args) => crate::study::run(&args),
        Command::Boundary(args) => crate::boundary::run(&args),
        Command::Report(args) => {
            let terrain = args
                .slope_distribution
                .as_deref()
                .map(|d| crate::weighting::SlopeDistribution::parse(d).map(|t| (t, d)))
                .transpose()?;
            let terrain = terrain.as_ref().map(|(t, d)| (t, *d));
            print_out(&crate::report::report(&args.sweep, terrain)?);
            Ok(())
        }
        Command::Sensitivity(args) => {
            let bootstrap = usize::try_from(args.bootstrap).unwrap_or(usize::MAX);
            if let Some(png) = &args.png {
                crate::output::check_output_path(png)?;
                if let (Ok(a), Ok(b)) = (
                    std::fs::canonicalize(png),
                    std::fs::canonicalize(&args.sweep),
                ) && a == b
                {
                    anyhow::bail!("--png {}: that is the sweep file being read", png.display());
                }
            }
            let analysis = crate::sensitivity::analyse(&args.sweep, bootstrap)?;
            if let Some(png) = &args.png {
                let title = format!(
                    "Sobol indices of {} ({} base points)",
                    args.sweep.display(),
                    analysis.base_points
                );
                crate::plot::sensitivity_chart(png, &analysis, &title)?;
            }
            print_out(&crate::sensitivity::markdown(&args.sweep, &analysis));
            Ok(())
        }
        Command::Compare(args) => {
            print_out(&crate::compare::compare(&args.a, &args.b)?);
            Ok(())
        }
        Command::Plot(args) => {
            for p in crate::plot::plot(&args.file, args.out_dir.as_deref())? {
                print_out(&format!("wrote {}\n", p.display()));
            }
            Ok(())
        }
        Command::Animate(args) => {
            let out = beside(&args.trace, args.out.as_ref(), "gif");
            let options = crate::animate::Options {
                fps: args.fps,
                speed: args.speed,
                width: args.size.0,
                height: args.size.1,
            };
            let started = std::time::Instant::now();
            let r = crate::animate::animate(&args.trace, &out, &options)?;
            if let Some(note) = crate::scene::sparse_note(&args.trace, r.every) {
                eprintln!("{note}");
            }
            say(
                &format!(
                    "{} frames at {} fps, {}x speed: plays in {:.1} s\nwrote {}: {:.2} MB in {:.1} s\n",
                    r.frames,
                    args.fps,
                    if r.speed >= 10.0 {
                        format!("{:.0}", r.speed)
                    } else {
                        format!("{:.2}", r.speed)
                    },
                    r.playback_s,
                    shown(&out),
                    r.bytes as f64 / 1e6,
                    started.elapsed().as_secs_f64()
                ),
                &out,
            );
            Ok(())
        }
        Command::View(args) => {
            let out = beside(&args.trace, args.out.as_ref(), "html");
            let w = crate::view::view(&args.trace, &out)?;
            if let Some(note) = crate::scene::sparse_note(&args.trace, w.every) {
                eprintln!("{note}");
            }
            say(
                &format!(
                    "{} times of {} rows\nwrote {}: {:.2} MB\n",
                    w.times,
                    w.rows,
                    shown(&out),
                    w.bytes as f64 / 1e6
                ),
                &out,
            );
            Ok(())
        }
        Command::Merge(args) => {
            let format = output_format(&args.out, args.format)?;
            let m = crate::output::merge::merge(&args.shards, &args.out, format)?;
            say(
                &format!(
                    "merged {} shards, {} samples\nwrote {}\n",
                    m.shards,
                    m.rows,
                    shown(&args.out)
                ),
                &args.out,
            );
            Ok(())
        }
    }
}

/// A scenario to run, from its TOML text: read and checked (`Scenario::from_toml`), and
/// its control loop checked against its thrusters and the laws this program registers
/// (`control::check`).
pub(crate) fn scenario_from_toml(text: &str) -> Result<Scenario, crate::scenario::ScenarioError> {
    let s = Scenario::from_toml(text)?;
    crate::control::check(&s)?;
    Ok(s)
}

/// A scenario from its file (or the default) with the command line's seed applied, and the
/// text to store as its provenance.
pub(crate) fn load_scenario(
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
fn scenario_of_sweep(
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

fn run_trace(args: &TraceArgs) -> anyhow::Result<()> {
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
        eprintln!(
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
    };
    let rows = trace::write(&args.out, &model, &info, args.every)?;
    let mut text = describe(&scenario, &sample, &summary);
    text.push_str(&format!(
        "\nwrote {}: {rows} rows (every {} of {} steps, and the state at the decision)\n",
        shown(&args.out),
        args.every,
        summary.steps
    ));
    say(&text, &args.out);
    Ok(())
}

/// Samples per task of the sweep's workers.
pub(crate) const CHUNK: u64 = 1024;

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

/// What a sweep runs: its settings, and where it starts when it resumes.
pub(crate) struct SweepPlan {
    pub scenario: Scenario,
    pub text: String,
    pub samples: u64,
    pub shard: Option<Shard>,
    pub format: crate::output::format::Format,
    pub out: PathBuf,
    /// The kernel it runs with (the precision is the scenario's).
    pub kernel: KernelKind,
    /// The interrupted sweep whose first rows this one takes over.
    pub resume: Option<crate::output::resume::Interrupted>,
    /// What to run to continue where a signal stops this sweep.
    pub continue_with: String,
}

impl SweepPlan {
    fn new(args: &SweepArgs) -> anyhow::Result<SweepPlan> {
        if let Some(out) = &args.resume {
            return SweepPlan::resuming(out, args.inputs.as_deref(), args.kernel);
        }
        crate::output::check_output_path(&args.out)?;
        let (scenario, text) = load_scenario(args.scenario.as_ref(), args.seed)?;
        // The design as the command line asks, checked as a scenario that says so is, and
        // stored with the scenario's text (`sensitivity` reads it there).
        let (scenario, text) = match args.design.as_deref() {
            None => (scenario, text),
            Some(word) => {
                let design = match word {
                    "sobol-indices" => crate::scenario::Design::SobolIndices,
                    "sobol-sequence" => crate::scenario::Design::SobolSequence,
                    _ => crate::scenario::Design::Independent,
                };
                let text = crate::scenario::with_design(&text, design);
                let mut again = scenario_from_toml(&text)
                    .map_err(|e| anyhow::anyhow!("--design {word}: {e}"))?;
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
            format: output_format(&args.out, args.format)?,
            out: args.out.clone(),
            kernel,
            resume: None,
            continue_with: format!("touchdown sweep --resume {}", args.out.display()),
        })
    }

    /// The plan that finishes the interrupted sweep to `out` (`sweep --resume`), its table
    /// of inputs reread where the sweep read it (or at `inputs`).
    pub(crate) fn resuming(
        out: &Path,
        inputs: Option<&Path>,
        kernel: KernelChoice,
    ) -> anyhow::Result<SweepPlan> {
        let from = crate::output::resume::Interrupted::read(out)?;
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
        crate::output::check_output_path(out)?;
        Ok(SweepPlan {
            scenario,
            text: from.scenario_toml.clone(),
            samples: from.samples,
            shard: from.shard,
            format: from.format,
            out: out.to_path_buf(),
            kernel,
            resume: Some(from),
            continue_with: format!("touchdown sweep --resume {}", out.display()),
        })
    }
}

/// The signal that asked the sweep to stop (0: none yet). A first SIGINT or SIGTERM sets
/// it; a second one ends the process at once (the unfinished file keeps its temporary
/// name, so nothing looks complete that is not).
pub(crate) fn stop_on_signals() -> anyhow::Result<std::sync::Arc<std::sync::atomic::AtomicUsize>> {
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
pub(crate) fn worker_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    let threads = threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, std::num::NonZero::get));
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
}

fn run_sweep(args: &SweepArgs) -> anyhow::Result<()> {
    let plan = SweepPlan::new(args)?;
    let pool = worker_pool(args.threads)?;
    let threads = pool.current_num_threads();
    let stop = stop_on_signals()?;
    let run = RunOptions {
        pool: &pool,
        stop: &stop,
        progress: !args.quiet,
        banner: true,
        auto_kernel: matches!(args.kernel, KernelChoice::Auto),
    };
    let done = execute(&plan, &run)?;
    let wall = done.wall_s;
    let rows = done.rows;
    let mut t = format!(
        "samples                 {rows}\nwall time               {wall:.2} s\nsamples/s               {:.0}\nlander-steps/s          {:.3e} ({:.3e} per thread)\nmean steps per sample   {:.0}\nlane occupancy          {:.3}\noutcomes\n",
        done.computed as f64 / wall,
        done.stats.busy_lane_steps as f64 / wall,
        done.stats.busy_lane_steps as f64 / wall / threads as f64,
        done.steps as f64 / rows as f64,
        done.stats.occupancy(),
    );
    for (o, c) in Outcome::ALL.iter().zip(done.counts) {
        t.push_str(&format!(
            "  {:<10} {c:>10}  {:>6.2} %\n",
            o.name(),
            100.0 * c as f64 / rows as f64
        ));
    }
    t.push_str(&format!("wrote {}\n", shown(&plan.out)));
    say(&t, &plan.out);
    warn_untouched(&done, &plan.scenario, "");
    Ok(())
}

/// How `execute` runs a plan: on which pool, stopped by which signal flag
/// (`stop_on_signals`), and what it shows on stderr.
pub(crate) struct RunOptions<'a> {
    pub pool: &'a rayon::ThreadPool,
    pub stop: &'a std::sync::Arc<std::sync::atomic::AtomicUsize>,
    /// A progress bar (when stderr is a terminal).
    pub progress: bool,
    /// The line naming the samples, seed, kernel and threads.
    pub banner: bool,
    /// Whether the kernel is the widest the CPU runs (`--kernel auto`), for the banner.
    pub auto_kernel: bool,
}

/// What `execute` did.
pub(crate) struct Executed {
    /// Rows in the file (kept from an interrupted run and computed now).
    pub rows: u64,
    /// Samples computed by this run.
    pub computed: u64,
    pub wall_s: f64,
    pub stats: crate::sweep::LaneStats,
    /// Rows per outcome, in the order of `Outcome::ALL`.
    pub counts: [u64; Outcome::ALL.len()],
    pub steps: u64,
    /// Samples of this run that never touched the surface.
    pub untouched: u64,
}

/// Runs `plan` and writes its file. A signal (`run.stop`) ends it with an `Interrupted`
/// error whose message says how to continue (`plan.continue_with`).
pub(crate) fn execute(plan: &SweepPlan, run: &RunOptions<'_>) -> anyhow::Result<Executed> {
    use std::io::IsTerminal;
    let (scenario, samples) = (&plan.scenario, plan.samples);
    let threads = run.pool.current_num_threads();
    let model = Model::new(scenario);
    let range = plan.shard.map_or(0..samples, |s| s.range(samples));
    let kept = plan.resume.as_ref().map_or(0, |r| r.kept_rows());
    let shard_note = plan.shard.map_or(String::new(), |s| {
        format!(
            ", shard {s} (samples {}..{} of {samples})",
            range.start, range.end
        )
    });
    let resume_note = plan.resume.as_ref().map_or(String::new(), |r| {
        format!(
            ", resuming {} at sample {} ({} rows kept of {})",
            plan.out.display(),
            range.start + kept,
            kept,
            r.rows
        )
    });
    let control = crate::output::sweep::control_columns(scenario);
    let parameters = crate::output::sweep::parameter_columns(scenario);
    let table = scenario
        .table
        .as_ref()
        .map_or_else(Vec::new, |t| t.metadata());
    let kept_columns = scenario
        .table
        .as_ref()
        .map_or_else(Vec::new, |t| t.kept_fields());
    let info = SweepInfo {
        scenario_toml: &plan.text,
        seed: scenario.seed,
        samples,
        lane_type: plan.kernel.arithmetic(),
        shard: plan.shard,
        control: &control,
        parameters: &parameters,
        table: &table,
        kept: &kept_columns,
    };
    let mut writer = SweepWriter::create(&plan.out, plan.format, model.legs.len(), &info)?
        .with_table(scenario.table.clone());
    let table_note = scenario.table.as_ref().map_or(String::new(), |t| {
        format!(
            ", inputs from {} ({} rows, {} columns)",
            t.path.display(),
            t.rows,
            t.columns.len()
        )
    });
    if run.banner {
        eprintln!(
            "touchdown sweep: {} samples, seed {}{table_note}, kernel {} ({} landers per block{}), {threads} thread{}{shard_note}{resume_note}",
            range.end - range.start,
            scenario.seed,
            plan.kernel.name(),
            plan.kernel.precision.lanes(),
            if run.auto_kernel {
                "; the widest this CPU runs"
            } else {
                ""
            },
            if threads == 1 { "" } else { "s" },
        );
    }
    let mut counts = [0u64; Outcome::ALL.len()];
    let mut steps = 0u64;
    if let Some(from) = &plan.resume {
        let (kept_counts, kept_steps) = from.copy_kept_rows(range.start, &mut writer)?;
        for (o, c) in Outcome::ALL.iter().zip(&mut counts) {
            *c += kept_counts.get(o.name()).copied().unwrap_or(0);
        }
        steps += kept_steps;
    }
    let todo = (range.start + kept)..range.end;
    let bar = if !run.progress || !std::io::stderr().is_terminal() {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::new(todo.end - todo.start).with_style(
            indicatif::ProgressStyle::with_template(
                "{bar:40} {pos}/{len} samples  {rate}  ETA {eta}",
            )
            .expect("valid template")
            // Whole samples per second (indicatif's own `per_sec` has four decimals).
            .with_key(
                "rate",
                |state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = write!(w, "{:.0} samples/s", state.per_sec());
                },
            ),
        )
    };
    let start = std::time::Instant::now();
    let mut computed = 0u64;
    let mut untouched = 0u64;
    let ran = run.pool.install(|| {
        crate::sweep::run_until(
            scenario,
            &model,
            plan.kernel.isa,
            todo.clone(),
            CHUNK,
            run.stop,
            |rows| {
                for r in &rows {
                    counts[r.summary.outcome as usize] += 1;
                    steps += r.summary.steps;
                    untouched += u64::from(r.summary.first_contact_s.is_none());
                }
                computed += rows.len() as u64;
                bar.inc(rows.len() as u64);
                writer.push(rows)
            },
        )
    })?;
    bar.finish_and_clear();
    if ran.end < todo.end {
        let signal = run.stop.load(std::sync::atomic::Ordering::Relaxed);
        let (rows, path) = writer.finish_interrupted()?;
        let name = if signal == signal_hook::consts::SIGTERM as usize {
            "SIGTERM"
        } else {
            "SIGINT"
        };
        let message = match path {
            Some(path) => format!(
                "interrupted by {name}: {rows} of {} samples done, in {} (a valid file); \
                 continue with: {}",
                range.end - range.start,
                path.display(),
                plan.continue_with
            ),
            None => format!(
                "interrupted by {name}: {rows} of {} samples done, written to {} as a valid \
                 file; it is not a regular file, so the sweep cannot be resumed from it",
                range.end - range.start,
                shown(&plan.out)
            ),
        };
        return Err(Interrupted {
            code: (128 + signal).min(255) as u8,
            message,
        }
        .into());
    }
    let rows = writer.finish()?;
    if let Some(from) = &plan.resume {
        std::fs::remove_file(&from.path).map_err(|e| {
            anyhow::anyhow!(
                "finished {}, but cannot remove {}: {e}",
                plan.out.display(),
                from.path.display()
            )
        })?;
    }
    Ok(Executed {
        rows,
        computed,
        wall_s: start.elapsed().as_secs_f64(),
        stats: ran.stats,
        counts,
        steps,
        untouched,
    })
}

/// Warns of samples that never touched the surface.
/// `at` names the sweep among several (a study's value), or is empty.
pub(crate) fn warn_untouched(done: &Executed, scenario: &Scenario, at: &str) {
    if done.untouched > 0 {
        eprintln!(
            "touchdown: warning: {at}{} of the {} samples run never touched the \
             surface before simulation.t_max_s = {} s (their first_contact_s is empty: they \
             end bouncing, or tipped if they turned past 90 deg in flight). A release too \
             high or an upward velocity error for the run's length? See \
             initial.clearance_m, inputs.release_height_m and inputs.velocity_error_z_m_s",
            done.untouched, done.computed, scenario.simulation.t_max_s
        );
    }
}

/// The inputs and summary of a sample, for people.
#[must_use]
pub fn describe(scenario: &Scenario, sample: &Sample, s: &Summary) -> String {
    let mut t = format!(
        "sample {} of seed {} (sample seed {:#018x})\n\ninputs\n",
        sample.index, scenario.seed, sample.seed
    );
    if let Some(table) = &scenario.table {
        t.insert_str(
            t.find('\n').unwrap_or(t.len()),
            &format!(
                ", row {} of the table of inputs {} (columns: {})",
                sample.index,
                table.path.display(),
                table.columns.join(", ")
            ),
        );
    }
    for ((name, unit), value) in INPUT_FIELDS.iter().zip(sample.inputs.to_array()) {
        t.push_str(&format!("  {name:<24} {value:>12.6} {unit}\n"));
    }
    for ((name, unit), p) in crate::scenario::PARAMETER_FIELDS
        .iter()
        .zip(crate::scenario::Parameter::ALL)
    {
        if scenario.sampled[p as usize].is_some() {
            let value = sample.parameters[p as usize];
            t.push_str(&format!("  {name:<24} {value:>12.6} {unit} (drawn)\n"));
        }
    }
    if scenario.rms_height_max_m() > 0.0 {
        t.push_str(&format!(
            "  {:<24} {:>12} (offset {:.3} m, {:.3} m)\n",
            "terrain_tile",
            sample.terrain_tile,
            sample.terrain_offset_m[0],
            sample.terrain_offset_m[1]
        ));
    }
    let first = s
        .first_contact_s
        .map_or("never".to_string(), |t| format!("{t:.3} s"));
    t.push_str(&format!(
        "\nsummary\n  {:<24} {} at {:.3} s ({} steps)\n  {:<24} {first}\n  {:<24} {}\n  {:<24} {:.2} deg (final {:.2} deg)\n  {:<24} {:.4} m\n  {:<24} {:.3} m/s^2 (along Z_B {:.3} m/s^2)\n  {:<24} {:.2} mm\n",
        "outcome", s.outcome.name(), s.decided_s, s.steps,
        "first contact",
        "bounces", s.bounces,
        "max tilt from normal", s.max_tilt_deg, s.final_tilt_deg,
        "displacement on surface", s.displacement_m,
        "peak acceleration", s.peak_acceleration_m_s2, s.peak_acceleration_z_body_m_s2,
        "max penetration", s.max_penetration_m * 1e3,
    ));
    t.push_str("\n  leg  peak normal force N   stroke mm   absorbed J\n");
    for (k, l) in s.legs.iter().enumerate() {
        t.push_str(&format!(
            "  {k:>3}  {:>19.2}   {:>9.3}   {:>10.4}\n",
            l.peak_normal_force_n,
            l.stroke_m * 1e3,
            l.absorbed_j
        ));
    }
    t
}

/// The format of output `out`: `--format` if given, else from the extension (`.parquet`
/// or `.pq`: Parquet; anything else: Arrow). A `--format` that contradicts the extension
/// (`--format arrow --out x.parquet`) is refused.
fn output_format(out: &Path, flag: Option<Format>) -> anyhow::Result<Format> {
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

/// An output path as messages name it (`-` is standard output).
fn shown(out: &Path) -> String {
    if out.as_os_str() == "-" {
        "standard output".to_string()
    } else {
        out.display().to_string()
    }
}

/// Writes what a command has to say about its output `out`: to stdout, or to stderr when
/// the output itself goes to stdout (`-`).
fn say(text: &str, out: &Path) {
    if out.as_os_str() == "-" {
        eprint!("{text}");
    } else {
        print_out(text);
    }
}

/// Writes to stdout; a closed pipe (`| head`) is not an error.
pub(crate) fn print_out(text: &str) {
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_parse_in_plain_and_scientific_notation() {
        assert_eq!(parse_count("250000"), Ok(250_000));
        assert_eq!(parse_count("1e6"), Ok(1_000_000));
        assert_eq!(parse_count("2.5e5"), Ok(250_000));
        assert_eq!(parse_count("1_000"), Ok(1000));
        for bad in ["-1", "1.5", "abc", "1e30", "nan", ""] {
            assert!(parse_count(bad).is_err(), "{bad}");
        }
    }
}
