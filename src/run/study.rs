//! The runs of a study: the scenario at each value of the varied key, and each value's
//! sweep file kept, merged from its shards, finished or run, in the study's folder.
//!
//! Each value's sweep is an ordinary sweep file in the study's folder, run with the same
//! seed (every value meets the same landers: the curve is paired). A study is resumed and
//! sharded through those files: the same command run again keeps the complete ones,
//! finishes an interrupted one (`sweep --resume`'s way) and runs the rest; with `--shard
//! K/N` it runs the K-th slice of every value, and the command without `--shard` merges the
//! N shard files of each value (`touchdown merge`'s way) before it writes the table.

use super::execute::{RunOptions, execute, warn_untouched};
use super::load::{KernelChoice, load_scenario, scenario_from_toml};
use super::plan::SweepPlan;
use super::signals::stop_on_signals;
use super::workers::worker_pool;
use crate::output::format::Format;
use crate::reference::Outcome;
use crate::scenario::Scenario;
use crate::scenario::keys::parent_table;
use crate::study::Vary;
use crate::sweep::Shard;
use anyhow::{Context as _, anyhow, bail};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

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
    /// The file of shard `shard` of this value's sweep.
    fn shard_file(&self, shard: Shard) -> PathBuf {
        let stem = self.file.file_stem().unwrap_or_default().to_string_lossy();
        let ext = self.file.extension().unwrap_or_default().to_string_lossy();
        self.file.with_file_name(format!(
            "{stem}.shard-{}-of-{}.{ext}",
            shard.index, shard.count
        ))
    }
}

/// What a study run does with one value's file.
enum Step {
    /// It is there, complete: kept.
    Kept,
    /// Its N shard files are there: merged.
    Merge(Vec<PathBuf>),
    /// An interrupted run of it is there: finished.
    Resume,
    /// Nothing of it yet: run.
    Run,
}

/// Why the sweep file `path` (complete or interrupted, with `meta` as its metadata) is not
/// the one this study wants at `point`, if it is not.
fn differs(
    meta: &std::collections::HashMap<String, String>,
    point: &Point,
    samples: u64,
    shard: Option<Shard>,
) -> Option<&'static str> {
    let get = |k: &str| meta.get(k).map(String::as_str);
    if get("touchdown.seed") != Some(point.scenario.seed.to_string().as_str()) {
        return Some("its seed");
    }
    if get("touchdown.samples") != Some(samples.to_string().as_str()) {
        return Some("its sample count");
    }
    let file_shard = get(crate::output::sweep::SHARD_KEYS[0]);
    if file_shard != shard.map(|s| s.to_string()).as_deref() {
        return Some("its shard");
    }
    if get("touchdown.scenario") != Some(point.text.as_str()) {
        return Some("its scenario");
    }
    None
}

/// The metadata of the sweep file `path`.
fn metadata_of(path: &Path) -> anyhow::Result<std::collections::HashMap<String, String>> {
    let file = crate::output::sweep::SweepFile::open(path)?;
    Ok(file
        .metadata()
        .iter()
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect())
}

/// What to do with `point`'s sweep (or its shard `shard`) given what the folder holds.
fn step_of(point: &Point, samples: u64, shard: Option<Shard>) -> anyhow::Result<Step> {
    let file = shard.map_or_else(|| point.file.clone(), |s| point.shard_file(s));
    let other = |path: &Path, what: &str| {
        anyhow!(
            "{} is not this study's sweep at {} (it differs in {what}): remove it, or give \
             the study another --out-dir",
            path.display(),
            point.value
        )
    };
    if file.exists() {
        let meta = metadata_of(&file)?;
        return match differs(&meta, point, samples, shard) {
            None => Ok(Step::Kept),
            Some(what) => Err(other(&file, what)),
        };
    }
    let interrupted = crate::output::interrupted_path(&file);
    if interrupted.exists() {
        let meta = metadata_of(&interrupted)?;
        return match differs(&meta, point, samples, shard) {
            None => Ok(Step::Resume),
            Some(what) => Err(other(&interrupted, what)),
        };
    }
    let dir = point.file.parent().unwrap_or(Path::new("."));
    if shard.is_some() || !dir.is_dir() {
        return Ok(Step::Run);
    }
    // Shard files of this value, complete ones, by shard count.
    let mut counts = std::collections::BTreeMap::<u64, Vec<u64>>::new();
    let stem = point.file.file_stem().unwrap_or_default().to_string_lossy();
    let ext = point.file.extension().unwrap_or_default().to_string_lossy();
    for entry in std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))? {
        let name = entry?.file_name().to_string_lossy().into_owned();
        let shard = name
            .strip_prefix(&format!("{stem}.shard-"))
            .and_then(|r| r.strip_suffix(&format!(".{ext}")))
            .and_then(|r| r.split_once("-of-"))
            .and_then(|(k, n)| Some((k.parse::<u64>().ok()?, n.parse::<u64>().ok()?)));
        if let Some((k, n)) = shard {
            counts.entry(n).or_default().push(k);
        }
    }
    let Some((&n, have)) = counts.iter().next_back() else {
        return Ok(Step::Run);
    };
    if counts.len() > 1 {
        bail!(
            "{} holds shards of the sweep at {} = {} cut {} ways: keep those of one --shard \
             count",
            dir.display(),
            point.text.lines().next().unwrap_or_default(),
            point.value,
            counts
                .keys()
                .map(u64::to_string)
                .collect::<Vec<_>>()
                .join(" and ")
        );
    }
    let missing: Vec<String> = (0..n)
        .filter(|k| !have.contains(k))
        .map(|k| format!("{k}/{n}"))
        .collect();
    if !missing.is_empty() {
        bail!(
            "the sweep at {} is sharded {n} ways and lacks shard{} {}: run {} with --shard, \
             then this command again",
            point.value,
            if missing.len() == 1 { "" } else { "s" },
            missing.join(", "),
            if missing.len() == 1 { "it" } else { "them" }
        );
    }
    let files: Vec<PathBuf> = (0..n)
        .map(|k| point.shard_file(Shard { index: k, count: n }))
        .collect();
    for f in &files {
        let meta = metadata_of(f)?;
        let shard = Shard { index: 0, count: n };
        // Shards share all but their index: compare with shard 0's key, index aside.
        let mut meta = meta;
        meta.insert(
            crate::output::sweep::SHARD_KEYS[0].to_string(),
            shard.to_string(),
        );
        if let Some(what) = differs(&meta, point, samples, Some(shard)) {
            return Err(other(f, what));
        }
    }
    Ok(Step::Merge(files))
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
        .map(|p| step_of(p, samples, args.shard))
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
            .map_or_else(|| p.file.clone(), |s| p.shard_file(s));
        let line = run_step(args, p, step, &file, samples, &options)?;
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

/// Does `step` for value `p` (its file, or its shard's, `file`); returns what it did.
fn run_step(
    args: &StudySettings,
    p: &Point,
    step: Step,
    file: &Path,
    samples: u64,
    options: &RunOptions<'_>,
) -> anyhow::Result<String> {
    let continue_with = "the same touchdown study command again".to_string();
    let at = format!("at {} = {}, ", args.vary.key, p.value);
    Ok(match step {
        Step::Kept => "kept (done before)".to_string(),
        Step::Merge(files) => {
            let m = crate::output::merge::merge(&files, file, args.format)?;
            format!("merged from {} shards ({} samples)", m.shards, m.rows)
        }
        Step::Resume => {
            let mut plan = SweepPlan::resuming(file, None, args.kernel)?;
            plan.continue_with = continue_with;
            let done = execute(&plan, options)?;
            warn_untouched(&done, &plan.scenario, &at);
            format!(
                "resumed: {} samples in {:.1} s, {} kept",
                done.computed,
                done.wall_s,
                done.rows - done.computed
            )
        }
        Step::Run => {
            crate::output::check_output_path(file)?;
            let kernel = kernels::isa::KernelKind {
                isa: args.kernel.isa()?,
                precision: p.scenario.simulation.precision,
            };
            let plan = SweepPlan {
                scenario: p.scenario.clone(),
                text: p.text.clone(),
                samples,
                shard: args.shard,
                format: args.format,
                out: Some(file.to_path_buf()),
                kernel,
                resume: None,
                continue_with,
            };
            let done = execute(&plan, options)?;
            warn_untouched(&done, &plan.scenario, &at);
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
