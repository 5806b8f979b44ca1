//! `touchdown sweep`: a Monte Carlo sweep run through the SIMD kernels, one row per sample,
//! and its summary (throughput, outcome shares).

use super::flags::{SweepOut, Threads, parse_count, parse_kernel, parse_seed};
use super::print::{say, shown};
use crate::reference::Outcome;
use crate::run::{
    KernelChoice, RunOptions, SweepPlan, SweepSettings, execute, stop_on_signals, warn_untouched,
    worker_pool,
};
use crate::scenario::Design;
use crate::sweep::Shard;
use std::path::PathBuf;

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
    /// Worker threads (`--threads`).
    #[command(flatten)]
    pub threads: Threads,
    /// Where the sweep file goes and its format (`--out`, `--format`).
    #[command(flatten)]
    pub output: SweepOut,
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

impl SweepArgs {
    /// The sweep's settings.
    fn settings(&self) -> SweepSettings {
        let design = self.design.as_deref().map(|word| match word {
            "sobol-indices" => Design::SobolIndices,
            "sobol-sequence" => Design::SobolSequence,
            _ => Design::Independent,
        });
        SweepSettings {
            scenario: self.scenario.clone(),
            scenario_toml: None,
            samples: self.samples,
            seed: self.seed,
            design,
            inputs: self.inputs.clone(),
            keep_columns: self.keep_columns,
            out: Some(self.output.out.clone()),
            format: self.output.format,
            resume: self.resume.clone(),
            shard: self.shard,
            kernel: self.kernel,
        }
    }
}

/// Runs `touchdown sweep`.
pub fn run(args: &SweepArgs) -> anyhow::Result<()> {
    let plan = SweepPlan::new(&args.settings())?;
    let pool = worker_pool(args.threads.threads)?;
    let threads = pool.current_num_threads();
    let stop = stop_on_signals()?;
    let run = RunOptions {
        pool: &pool,
        stop: &stop,
        progress: !args.quiet,
        banner: true,
        auto_kernel: matches!(args.kernel, KernelChoice::Auto),
        keep: false,
        counter: None,
    };
    let done = execute(&plan, &run)?;
    let wall = done.wall_s;
    let rows = done.rows;
    let mut t = format!(
        "samples                 {rows}\nwall time               {wall:.2} s\nsamples/s               {:.0}\nlander-steps/s          {:.3e} ({:.3e} per thread)\nmean steps per sample   {:.0}\nlane occupancy          {:.3}\nserial share            {:.4} of the CPU time (so at most {:.1}x on 16 threads)\noutcomes\n",
        done.computed as f64 / wall,
        done.stats.busy_lane_steps as f64 / wall,
        done.stats.busy_lane_steps as f64 / wall / threads as f64,
        done.steps as f64 / rows as f64,
        done.stats.occupancy(),
        done.serial_share,
        1.0 / (done.serial_share + (1.0 - done.serial_share) / 16.0),
    );
    t.push_str(&outcome_rows(&plan.scenario, &done));
    // The command line always names an output (`--out`'s default, or `--resume PATH`).
    let out = plan.out.clone().unwrap_or_else(|| args.output.out.clone());
    t.push_str(&format!("wrote {}\n", shown(&out)));
    say("the sweep's summary", &t, &out)?;
    warn_untouched(&done, &plan.scenario, "");
    Ok(())
}

/// The closing summary's outcome rows: each outcome listed and its share, with `[limits]`
/// "stable within limits" after "stable" and then the samples that broke each limit, as
/// `report` words them.
fn outcome_rows(scenario: &crate::scenario::Scenario, done: &crate::run::Executed) -> String {
    let rows = done.rows;
    let row = |name: &str, c: u64, width: usize| {
        format!(
            "  {name:<width$} {c:>10}  {:>6.2} %\n",
            100.0 * c as f64 / rows as f64
        )
    };
    let limits = scenario.limits.zip(done.limits.as_deref());
    let (within, broken) = limits.map_or((0, Vec::new()), |(l, counts)| {
        crate::report::limit_rows(&l, counts)
    });
    let within_name = "stable within limits";
    let width = if limits.is_some() {
        within_name.len()
    } else {
        10
    };
    let mut t = String::new();
    // `held` is listed where a lander can be held: with a control loop.
    let controlled = scenario.control.is_some();
    for o in Outcome::listed(controlled) {
        t.push_str(&row(o.name(), done.counts[o as usize], width));
        if o == Outcome::Stable && limits.is_some() {
            t.push_str(&row(within_name, within, width));
        }
    }
    if limits.is_some() {
        t.push_str("limits\n");
        let width = broken.iter().map(|(name, _)| name.len()).max().unwrap_or(0);
        for (name, c) in &broken {
            t.push_str(&row(name, *c, width));
        }
    }
    t
}
