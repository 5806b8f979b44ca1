//! `touchdown boundary`: the allowable slope of each azimuth sector found directly, by
//! adaptive sampling (`run::boundary`), and told as Markdown; or the allowable value of
//! another drawn input (`--input`).

use super::boundary_data::{About, searched};
use super::flags::{Threads, parse_count, parse_seed};
use super::print::print_out;
use crate::boundary::with_unit;
use crate::run::boundary::{Search, Settings, search};
use crate::scenario::{Design, Dist, Scenario, VALUES, value_dists, value_name, value_unit};
use crate::stats::{Allowable, SECTOR_DEG};
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
    /// The drawn input to search along (a column of the sweep: an input, a parameter, a
    /// control-law parameter or `initial_*`), uniform or normal: its largest value with at
    /// least 99 % of the samples at or below it stable, per sector.
    #[arg(long, value_name = "NAME", default_value = "slope_deg")]
    pub input: String,
    /// A sector is finished once its 95 % interval is at most this wide, in the input's
    /// unit: by default 0.5 deg for the slope, and for another input 1/90 of its range (as
    /// 0.5 deg is of slopes from 0 to 45 deg).
    #[arg(long, value_name = "WIDTH", allow_negative_numbers = true)]
    pub tolerance: Option<f64>,
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
    /// The search as one JSON document on stdout (the same numbers, unrounded) instead of
    /// Markdown.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// The sectors as CSV on stdout, one row each (the same numbers, unrounded), instead of
    /// Markdown.
    #[arg(long)]
    pub csv: bool,
}

/// Runs `touchdown boundary`.
pub fn run(args: &BoundaryArgs) -> anyhow::Result<()> {
    use std::io::IsTerminal;
    let started = std::time::Instant::now();
    if let Some(tolerance) = args.tolerance
        && !(tolerance > 0.0 && tolerance.is_finite())
    {
        let unit = (0..VALUES)
            .find(|&k| value_name(k) == args.input)
            .map(value_unit);
        bail!(
            "--tolerance {tolerance}: must be a width above 0{}",
            match unit {
                Some("1") | None => String::new(),
                Some(unit) => format!(", in {unit}"),
            }
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
    let input = input_of(&scenario, &args.input)?;
    let settings = Settings {
        input,
        tolerance: args.tolerance,
        batch: args.batch,
        max_samples_per_sector: args.max_samples_per_sector,
    };
    let progress = !args.quiet && std::io::stderr().is_terminal();
    let found = search(scenario, &settings, args.threads.threads, progress)?;
    let about = About {
        scenario: args.scenario.as_ref().map_or_else(
            || "the default scenario".to_string(),
            |p| p.display().to_string(),
        ),
        seed,
        settings,
        seconds: started.elapsed().as_secs_f64(),
    };
    if args.json {
        print_out(
            "the search's JSON",
            &super::boundary_data::json(&about, &found),
        )
    } else if args.csv {
        print_out("the search's CSV", &super::boundary_data::csv(&found))
    } else {
        print_out("the search's report", &markdown(&about, &found))
    }
}

/// The position in `Sample::values` of the input named `name`, refused (naming those the
/// scenario draws uniform or normal) where no value has that name.
fn input_of(scenario: &Scenario, name: &str) -> anyhow::Result<usize> {
    if let Some(k) = (0..VALUES).find(|&k| value_name(k) == name) {
        return Ok(k);
    }
    let dists = value_dists(scenario);
    let drawn: Vec<&str> = (0..VALUES)
        .filter(|&k| matches!(dists[k], Dist::Uniform { .. } | Dist::Normal { .. }))
        .map(value_name)
        .collect();
    bail!(
        "--input {name}: no such input; the scenario draws {} uniform or normal",
        if drawn.is_empty() {
            "none".to_string()
        } else {
            drawn.join(", ")
        }
    )
}

/// The search's report: what ran, and the allowable slope of each sector.
fn markdown(about: &About, found: &Search) -> String {
    let name = &about.scenario;
    let slope = found.input == 0;
    let (input, unit) = (value_name(found.input), value_unit(found.input));
    let mut t = String::new();
    let _ = writeln!(t, "# touchdown boundary: {name}\n");
    let _ = writeln!(
        t,
        "Seed {}, {input} = {}, tolerance {}, batch {} per sector, at most {} samples \
         per sector{}. {} samples simulated ({} candidates drawn) in \
         {:.1} s.\n",
        about.seed,
        found.dist.toml(),
        with_unit(found.tolerance, unit),
        about.settings.batch,
        about.settings.max_samples_per_sector,
        if found.design == Design::Independent {
            ""
        } else {
            "; inputs drawn independently (the scenario's design is not)"
        },
        found.total,
        found.candidates,
        about.seconds
    );
    let reached = searched(found).count();
    if reached < found.sectors.len() {
        let _ = writeln!(
            t,
            "The scenario's downhill azimuth and yaw put every sample in {} of the {} \
             sectors, those below; the other {} get none and are not shown.\n",
            if reached == 1 {
                "one".to_string()
            } else {
                reached.to_string()
            },
            found.sectors.len(),
            found.sectors.len() - reached
        );
    }
    if slope {
        let _ = writeln!(
            t,
            "## Allowable slope\n\nAs `touchdown report` defines it, per sector of downhill \
             azimuth relative to the lander; each round drew a sector's slopes below the upper \
             end of its interval so far, and the interval pools all its rounds.\n"
        );
    } else {
        let in_unit = if unit == "1" {
            String::new()
        } else {
            format!(", in {unit}")
        };
        let _ = writeln!(
            t,
            "## Allowable {input}\n\nThe largest {input} with at least 99 % of the samples at \
             or below it stable (the rule of `touchdown report`'s allowable slope), per sector \
             of downhill azimuth relative to the lander{in_unit}; each round drew a sector's \
             {input} below the upper end of its interval so far, and the interval pools all its \
             rounds.\n"
        );
    }
    let what = if slope { "slope" } else { "value" };
    let _ = writeln!(
        t,
        "| azimuth sector | samples | rounds | allowable {what} | 95 % interval | stopped |\n\
         |---|---:|---:|---:|---:|---|"
    );
    let min = found.dist.support().0;
    for (k, s) in searched(found) {
        let (cell, interval) = if slope {
            (s.allowable.cell(), s.allowable.interval_cell())
        } else {
            value_cells(s.allowable, min, unit)
        };
        let _ = writeln!(
            t,
            "| {:.0}–{:.0} deg | {} | {} | {cell} | {interval} | {} |",
            k as f64 * SECTOR_DEG,
            (k + 1) as f64 * SECTOR_DEG,
            s.used,
            s.rounds.len(),
            s.stop.map_or(String::new(), |stop| stop.cell(what))
        );
    }
    t
}

/// The cells of a sector's allowable value of an input other than the slope, and its
/// interval, in `unit` (its range starting at `min`), as `Allowable::cell` and
/// `interval_cell` give the slope's.
fn value_cells(allowable: Allowable, min: f64, unit: &str) -> (String, String) {
    match allowable {
        Allowable::TooFewSamples(_) | Allowable::NoSlope { .. } => {
            let cell = allowable.cell().replace("no slope", "no value");
            let interval = match allowable {
                Allowable::NoSlope { below_deg } => {
                    format!("{min:.3}–{}", with_unit(format!("{below_deg:.3}"), unit))
                }
                _ => allowable.interval_cell(),
            };
            (cell, interval)
        }
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => (
            with_unit(format!("{slope_deg:.3}"), unit),
            format!(
                "{:.3}–{}",
                low_deg.max(min),
                with_unit(format!("{high_deg:.3}"), unit)
            ),
        ),
    }
}
