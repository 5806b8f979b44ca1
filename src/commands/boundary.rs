//! `touchdown boundary`: the allowable slope of each azimuth sector found directly, by
//! adaptive sampling (`run::boundary`), and told as Markdown.

use super::flags::{Threads, parse_count, parse_seed};
use super::print::print_out;
use crate::boundary::Stop;
use crate::run::boundary::{Search, Settings, search};
use crate::scenario::Design;
use crate::stats::SECTOR_DEG;
use anyhow::bail;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Flags of `touchdown boundary`.
#[derive(clap::Args, Debug)]
pub struct BoundaryArgs {
    /// Scenario file (TOML); without it, the default sweep of MODEL.md section 11. Its
    /// slope must be drawn from a distribution (uniform or normal).
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Seed (overrides the scenario's `seed`).
    #[arg(long, value_name = "S", value_parser = parse_seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// A sector is finished once its 95 % interval is at most this wide, deg.
    #[arg(
        long,
        value_name = "DEG",
        default_value = "0.5",
        allow_negative_numbers = true
    )]
    pub tolerance: f64,
    /// Samples per unfinished sector per round.
    #[arg(long, value_name = "N", default_value = "2000", value_parser = parse_count, allow_negative_numbers = true)]
    pub batch: u64,
    /// A sector is finished once it has run this many samples.
    #[arg(long, value_name = "N", default_value = "200000", value_parser = parse_count, allow_negative_numbers = true)]
    pub max_samples_per_sector: u64,
    /// Worker threads (`--threads`).
    #[command(flatten)]
    pub threads: Threads,
    /// No progress on stderr (there is none either when stderr is not a terminal).
    #[arg(long)]
    pub quiet: bool,
}

/// Runs `touchdown boundary`.
pub fn run(args: &BoundaryArgs) -> anyhow::Result<()> {
    use std::io::IsTerminal;
    let started = std::time::Instant::now();
    if !(args.tolerance > 0.0 && args.tolerance.is_finite()) {
        bail!(
            "--tolerance {}: must be a width in deg above 0",
            args.tolerance
        );
    }
    if args.batch == 0 {
        bail!("--batch 0: each round needs at least 1 sample per sector");
    }
    if args.max_samples_per_sector == 0 {
        bail!("--max-samples-per-sector 0: a sector needs at least 1 sample");
    }
    let (scenario, _) = crate::run::load_scenario(args.scenario.as_ref(), args.seed)?;
    let seed = scenario.seed;
    let settings = Settings {
        tolerance: args.tolerance,
        batch: args.batch,
        max_samples_per_sector: args.max_samples_per_sector,
    };
    let progress = !args.quiet && std::io::stderr().is_terminal();
    let found = search(scenario, &settings, args.threads.threads, progress)?;
    print_out(
        "the search's report",
        &markdown(args, seed, &found, started),
    )
}

/// The search's report: what ran, and the allowable slope of each sector.
fn markdown(args: &BoundaryArgs, seed: u64, found: &Search, started: std::time::Instant) -> String {
    let name = args.scenario.as_ref().map_or_else(
        || "the default scenario".to_string(),
        |p| p.display().to_string(),
    );
    let mut t = String::new();
    let _ = writeln!(t, "# touchdown boundary: {name}\n");
    let _ = writeln!(
        t,
        "Seed {}, slope_deg = {}, tolerance {} deg, batch {} per sector, at most {} samples \
         per sector{}. {} samples simulated ({} candidates drawn) in \
         {:.1} s.\n",
        seed,
        found.dist.toml(),
        args.tolerance,
        args.batch,
        args.max_samples_per_sector,
        if found.design == Design::Independent {
            ""
        } else {
            "; inputs drawn independently (the scenario's design is not)"
        },
        found.total,
        found.candidates,
        started.elapsed().as_secs_f64()
    );
    let _ = writeln!(
        t,
        "## Allowable slope\n\nAs `touchdown report` defines it, per sector of downhill \
         azimuth relative to the lander; each round drew a sector's slopes below the upper \
         end of its interval so far, and the interval pools all its rounds.\n"
    );
    let _ = writeln!(
        t,
        "| azimuth sector | samples | rounds | allowable slope | 95 % interval | stopped |\n\
         |---|---:|---:|---:|---:|---|"
    );
    for (k, s) in found.sectors.iter().enumerate() {
        let _ = writeln!(
            t,
            "| {:.0}–{:.0} deg | {} | {} | {} | {} | {} |",
            k as f64 * SECTOR_DEG,
            (k + 1) as f64 * SECTOR_DEG,
            s.used,
            s.rounds.len(),
            s.allowable.cell(),
            s.allowable.interval_cell(),
            s.stop.map_or("", Stop::cell)
        );
    }
    t
}
