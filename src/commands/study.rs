//! `touchdown study`: the sweep of a scenario run at each of several values of one of its
//! keys, and one table of what changes with it (outcome shares with 95 % intervals, the
//! allowable slope per azimuth sector, the static tipping limit), as Arrow, Markdown and a
//! PNG of allowable slope against the value.

use super::flags::{Threads, parse_count, parse_kernel, parse_seed};
use super::print::print_out;
use crate::output::OutputSet;
use crate::output::format::Format;
use crate::run::KernelChoice;
use crate::run::study::StudySettings;
use crate::study::{About, Row, Vary, markdown, table_files, write_table};
use crate::sweep::Shard;
use std::path::PathBuf;

/// Flags of `touchdown study`.
#[derive(clap::Args, Debug)]
pub struct StudyArgs {
    /// Scenario file (TOML); without it, the default sweep of MODEL.md section 11.
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// The scenario key to vary and its values: COUNT values evenly spaced from MIN to MAX.
    /// KEY is written as in the scenario file with its tables joined by dots
    /// (lander.footpad_radius_m, damper.crush_strength_psi, inputs.slope_deg.max).
    #[arg(long, value_name = "KEY=MIN:MAX:COUNT", value_parser = Vary::parse)]
    pub vary: Vary,
    /// Samples per value (accepts 1e6, 2.5e5); default: the scenario's `samples`.
    #[arg(long, value_name = "N", value_parser = parse_count, allow_negative_numbers = true)]
    pub samples: Option<u64>,
    /// Seed of every value's sweep (overrides the scenario's `seed`).
    #[arg(long, value_name = "S", value_parser = parse_seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// Folder of the study (made if missing): one sweep file per value, and
    /// study.arrow, study.md and study.png. Running the same command again continues a
    /// study that was interrupted.
    #[arg(long, value_name = "DIR", default_value = "study")]
    pub out_dir: PathBuf,
    /// Format of the sweep files (the table is Arrow).
    #[arg(long, value_enum, default_value = "arrow")]
    pub format: Format,
    /// Run only the K-th of N contiguous slices of every value's samples; the command
    /// without --shard then merges the shards and writes the table.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<Shard>,
    /// Worker threads (`--threads`).
    #[command(flatten)]
    pub threads: Threads,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// SIMD kernel, as for `touchdown sweep`.
    #[arg(long, value_name = "KERNEL", default_value = "auto", value_parser = parse_kernel)]
    pub kernel: KernelChoice,
}

/// Runs `touchdown study`.
pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    let settings = StudySettings {
        scenario: args.scenario.clone(),
        vary: args.vary.clone(),
        samples: args.samples,
        seed: args.seed,
        out_dir: args.out_dir.clone(),
        format: args.format,
        shard: args.shard,
        threads: args.threads.threads,
        quiet: args.quiet,
        kernel: args.kernel,
    };
    let study = crate::run::study::run(&settings)?;
    let samples = study.samples;
    print_out("the study's log", &study.log)?;
    if let Some(s) = args.shard {
        print_out(
            "the study's log",
            &format!(
                "shard {s} of every value done in {:.1} s; once all {} shards are done, the same \
             command without --shard merges them and writes the study's table\n",
                study.started.elapsed().as_secs_f64(),
                s.count
            ),
        )?;
        return Ok(());
    }
    let rows = study
        .points
        .iter()
        .map(|p| Row::read(p.value, &p.file, &p.scenario, samples))
        .collect::<anyhow::Result<Vec<Row>>>()?;
    let about = About {
        key: &args.vary.key,
        vary: &args.vary,
        scenario: args
            .scenario
            .as_ref()
            .map_or("the default scenario".to_string(), |p| {
                p.display().to_string()
            }),
        seed: study.seed,
        samples,
        base_text: &study.base_text,
    };
    let files = table_files(&args.out_dir);
    let set = OutputSet::reserve(&files)?;
    let [table, md, png] = files;
    write_table(&table, &rows, &about)?;
    let text = markdown(&rows, &about);
    crate::output::write_text(&md, &text)?;
    crate::plot::study_chart(&png, &rows, &about)?;
    set.commit()?;
    print_out(
        "the study's table",
        &format!(
            "\n{text}\nwrote {}, {} and {}\n",
            table.display(),
            md.display(),
            png.display()
        ),
    )
}
