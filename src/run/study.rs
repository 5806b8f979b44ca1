//! The runs of a study: the scenario at each value of the varied key, and each value's
//! sweep file kept, merged from its shards, finished or run, in the study's folder.
//!
//! Each value's sweep is an ordinary sweep file in the study's folder, run with the same
//! seed (every value meets the same landers: the curve is paired). A study is resumed and
//! sharded through those files: the same command run again keeps the complete ones,
//! finishes an interrupted one (`sweep --resume`'s way) and runs the rest; with `--shard
//! K/N` it runs the K-th slice of every value, and the command without `--shard` merges the
//! N shard files of each value (`touchdown merge`'s way) before it writes the table.

use super::execute::{RunOptions, warn_untouched};
use super::load::{KernelChoice, load_scenario, scenario_from_toml};
use super::signals::stop_on_signals;
use super::steps::{self, Done, Kept, Names, Running, Step, shard_file, step_of};
use super::workers::worker_pool;
use crate::output::format::Format;
use crate::reference::Outcome;
use crate::scenario::Scenario;
use crate::scenario::keys::parent_table;
use crate::study::Vary;
use crate::sweep::Shard;
use anyhow::{Context as _, anyhow, bail};
use std::fmt::Write as _;
use std::path::PathBuf;

/// The settings of a study (`touchdown study`'s flags).
#[derive(Debug, Clone)]
pub struct StudySettings {
    /// Scenario file; the default scenario without it.
    pub scenario: Option<PathBuf>,
    /// The key varied and its values.
    pub vary: Vary,
    /// Samples per value; default: the scenario's.
    pub samples: Option<u64>,
    /// Overrides the scenario's seed.
    pub seed: Option<u64>,
    /// The study's folder.
    pub out_dir: PathBuf,
    /// Format of the sweep files.
    pub format: Format,
    /// The slice of every value's samples to run.
    pub shard: Option<Shard>,
    /// Worker threads (default: one per core).
    pub threads: Option<usize>,
    /// No progress bar, no banner.
    pub quiet: bool,
    /// The kernel every value's sweep runs with (`--kernel`).
    pub kernel: KernelChoice,
}

/// The scenario text `base` (parsed) with `key` set to `value`, and the scenario it reads
/// as; refused with the reader's message where the scenario refuses the value. A key the
/// scenario draws from a distribution takes the value in its place.
fn with_value(base: &toml::Table, key: &str, value: f64) -> anyhow::Result<(String, Scenario)> {
    let leaf = key.rsplit('.').next().unwrap_or(key);
    let mut probe = base.clone();
    let at = parent_table(&mut probe, key).map_err(|e| anyhow!("--vary {key}: {e}"))?;
    let integral = value.fract() == 0.0 && value.abs() < 2f64.powi(53);
    let given = match at.get(leaf) {
        Some(toml::Value::Integer(_)) if !integral => {
            bail!("--vary {key}: the scenario gives {key} as a whole number; {value} is not one")
        }
        Some(toml::Value::Integer(_)) => vec![toml::Value::Integer(value as i64)],
        Some(toml::Value::Float(_)) | None if integral => vec![
            toml::Value::Float(value),
            toml::Value::Integer(value as i64),
        ],
        Some(toml::Value::Float(_)) | None => vec![toml::Value::Float(value)],
        // A distribution: the value replaces it.
        Some(toml::Value::Table(t)) if t.contains_key("dist") => vec![toml::Value::Float(value)],
        Some(toml::Value::Table(_)) => bail!(
            "--vary {key}: {key} is a table of settings in the scenario, not a number: vary \
             one of its keys"
        ),
        Some(other) => bail!(
            "--vary {key}: {key} is {} in the scenario, not a number",
            other.type_str()
        ),
    };
    let mut first_error = None;
    for v in given {
        let mut table = base.clone();
        parent_table(&mut table, key)
            .map_err(|e| anyhow!("--vary {key}: {e}"))?
            .insert(leaf.to_string(), v);
        let text = format!(
            "# touchdown study: {key} = {value}\n{}",
            toml::to_string(&table).context("cannot write the scenario of a study value")?
        );
        match scenario_from_toml(&text) {
            Ok(s) => return Ok((text, s)),
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    let e = first_error.expect("at least one form was tried");
    bail!("--vary {key}: at {key} = {value}, {e}")
}

/// One value of the study: its scenario and its sweep file.
pub struct Point {
    /// The varied key's value.
    pub value: f64,
    /// The base scenario's TOML text with the key set to `value`.
    pub text: String,
    /// The scenario that text reads as.
    pub scenario: Scenario,
    /// The complete sweep of this value.
    pub file: PathBuf,
}

impl Point {
    /// This value's sweep as its folder keeps it.
    fn kept(&self, samples: u64) -> Kept<'_> {
        Kept {
            text: &self.text,
            scenario: &self.scenario,
            file: &self.file,
            samples,
            names: Names {
                whose: format!("this study's sweep at {}", self.value),
                owner: "study",
                set_by_flags: &[],
                sweep: format!("the sweep at {}", self.value),
                // "the sweep at lander.cg_height_m = 0.4": the key is the text's header's.
                sweep_long: format!(
                    "the sweep at {}",
                    self.text
                        .lines()
                        .next()
                        .and_then(|l| l.strip_prefix("# touchdown study: "))
                        .map_or_else(|| self.value.to_string(), str::to_string)
                ),
            },
        }
    }
}

/// What a study's runs leave: its values and their files, and a line per value.
pub struct Study {
    /// The values, in the order of `Vary::values`, with their sweep files.
    pub points: Vec<Point>,
    /// Samples per value.
    pub samples: u64,
    /// The seed of every value's sweep.
    pub seed: u64,
    /// The base scenario's text, its seed applied.
    pub base_text: String,
    /// A line per value: what was done with its file, and where it is.
    pub log: String,
    /// When the values' runs began.
    pub started: std::time::Instant,
    /// The study's folder, locked until the study has written its table.
    pub lock: crate::output::FolderLock,
}

/// Runs the study `args` asks for: each value's sweep (or its shard) kept, merged,
/// finished or run.
pub fn run(args: &StudySettings) -> anyhow::Result<Study> {
    let (base, base_text) = load_scenario(args.scenario.as_ref(), args.seed)?;
    let parsed: toml::Table = base_text
        .parse()
        .map_err(|e| anyhow!("cannot read the scenario as TOML: {e}"))?;
    let samples = args.samples.unwrap_or(base.samples);
    if samples == 0 {
        bail!("--samples must be at least 1");
    }
    // Each value's samples are read back for its allowable slopes (`study::Row::read`):
    // slope and outcome, 16 bytes each, with room for their vectors to grow.
    super::memory::check_fits(samples.saturating_mul(32), || {
        format!(
            "--samples {samples}: a study reads each value's samples back (32 bytes each) \
             for the allowable slope of each sector; it"
        )
    })?;
    let dir = &args.out_dir;
    if dir.exists() && !dir.is_dir() {
        bail!("--out-dir {}: that is a file, not a folder", dir.display());
    }
    let points = points(args, &parsed)?;
    // Every file the study writes is refused before the first sample if one may not be
    // written (an input of this command under its name, say).
    let mut outputs: Vec<PathBuf> = points
        .iter()
        .map(|p| {
            args.shard
                .map_or_else(|| p.file.clone(), |s| shard_file(&p.file, s))
        })
        .collect();
    if args.shard.is_none() {
        outputs.extend(crate::study::table_files(dir));
    }
    crate::output::set::check(&outputs)?;
    let lock = super::folder::lock_folder(dir, args.shard.is_some())?;
    let id = super::folder::StudyId {
        key: &args.vary.key,
        values: format!("{}:{}:{}", args.vary.min, args.vary.max, args.vary.count),
        seed: base.seed,
        samples,
        base_text: &base_text,
    };
    let files: Vec<PathBuf> = points.iter().map(|p| p.file.clone()).collect();
    super::folder::refuse_other_study(dir, &id, &files)?;
    let steps = points
        .iter()
        .map(|p| step_of(&p.kept(samples), args.shard))
        .collect::<anyhow::Result<Vec<Step>>>()?;

    let pool = worker_pool(args.threads)?;
    let stop = stop_on_signals()?;
    let options = RunOptions {
        pool: &pool,
        stop: &stop,
        progress: !args.quiet,
        banner: false,
        auto_kernel: matches!(args.kernel, KernelChoice::Auto),
        keep: false,
        counter: None,
    };
    let shard_note = args
        .shard
        .map_or(String::new(), |s| format!(", shard {s} of each"));
    if !args.quiet {
        super::workers::tell(&format!(
            "touchdown study: {} = {} ({} value{}), {samples} samples each{shard_note}, seed {}, \
         into {}\n",
            args.vary.key,
            points
                .iter()
                .map(|p| p.value.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            points.len(),
            if points.len() == 1 { "" } else { "s" },
            base.seed,
            dir.display()
        ));
    }
    let started = std::time::Instant::now();
    let mut log = String::new();
    for (p, step) in points.iter().zip(steps) {
        let file = args
            .shard
            .map_or_else(|| p.file.clone(), |s| shard_file(&p.file, s));
        let line = run_step(args, p, step, samples, &options)?;
        let _ = writeln!(
            log,
            "{} = {}: {line} -> {}",
            args.vary.key,
            p.value,
            file.display()
        );
    }
    Ok(Study {
        points,
        samples,
        seed: base.seed,
        base_text,
        log,
        started,
        lock,
    })
}

/// The study's values: each one's scenario (the base `parsed` with the key set) and file.
fn points(args: &StudySettings, parsed: &toml::Table) -> anyhow::Result<Vec<Point>> {
    let ext = match args.format {
        Format::Arrow => "arrow",
        Format::Parquet => "parquet",
    };
    let points = args
        .vary
        .values()
        .into_iter()
        .enumerate()
        .map(|(i, value)| {
            let (text, scenario) = with_value(parsed, &args.vary.key, value)?;
            let file = args
                .out_dir
                .join(format!("{i:02}-{}-{value}.{ext}", args.vary.leaf()));
            Ok(Point {
                value,
                text,
                scenario,
                file,
            })
        })
        .collect::<anyhow::Result<Vec<Point>>>()?;
    if points.iter().all(|p| p.text == points[0].text) && points.len() > 1 {
        bail!(
            "--vary {}: every value gives the same scenario",
            args.vary.key
        );
    }
    Ok(points)
}

/// Does `step` for value `p` (its file, or its shard's); returns what it did.
fn run_step(
    args: &StudySettings,
    p: &Point,
    step: Step,
    samples: u64,
    options: &RunOptions<'_>,
) -> anyhow::Result<String> {
    let at = format!("at {} = {}, ", args.vary.key, p.value);
    let running = Running {
        shard: args.shard,
        format: args.format,
        kernel: args.kernel,
        continue_with: "the same touchdown study command again",
        options,
    };
    Ok(match steps::run_step(&p.kept(samples), step, &running)? {
        Done::Kept => "kept (done before)".to_string(),
        Done::Merged { shards, rows } => format!("merged from {shards} shards ({rows} samples)"),
        Done::Resumed(done) => {
            warn_untouched(&done, &p.scenario, &at);
            format!(
                "resumed: {} samples in {:.1} s, {} kept",
                done.computed,
                done.wall_s,
                done.rows - done.computed
            )
        }
        Done::Ran(done) => {
            warn_untouched(&done, &p.scenario, &at);
            format!(
                "{} samples in {:.1} s, {:.1} % stable",
                done.computed,
                done.wall_s,
                100.0 * done.counts[Outcome::Stable as usize] as f64 / done.rows as f64
            )
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_goes_where_its_key_says_and_the_scenario_checks_it() {
        let base: toml::Table = "seed = 3\n[lander]\nlegs = 4\n".parse().unwrap();
        let (text, s) = with_value(&base, "lander.footpad_radius_m", 0.75).unwrap();
        let tip = s.lander.tips_m()[0];
        assert!((tip[0].hypot(tip[1]) - 0.75).abs() < 1e-12, "{tip:?}");
        assert_eq!(s.seed, 3);
        assert!(text.starts_with("# touchdown study: lander.footpad_radius_m = 0.75\n"));
        // A whole number where the scenario wants one.
        let (_, s) = with_value(&base, "lander.legs", 3.0).unwrap();
        assert_eq!(s.lander.tips_m().len(), 3);
        // A key the scenario does not have, and a value it refuses: its reader's message.
        let e = with_value(&base, "lander.footpad_radius_mm", 0.5).unwrap_err();
        assert!(format!("{e:#}").contains("footpad_radius_mm"), "{e:#}");
        let e = with_value(&base, "lander.footpad_radius_m", -1.0).unwrap_err();
        assert!(
            format!("{e:#}").contains("at lander.footpad_radius_m = -1"),
            "{e:#}"
        );
        let e = with_value(&base, "lander.legs", 3.5).unwrap_err();
        assert!(format!("{e:#}").contains("whole number"), "{e:#}");
        let e = with_value(&base, "lander", 1.0).unwrap_err();
        assert!(format!("{e:#}").contains("table of settings"), "{e:#}");
        let e = with_value(&base, "seed.x", 1.0).unwrap_err();
        assert!(format!("{e:#}").contains("not a table of keys"), "{e:#}");
    }
}
