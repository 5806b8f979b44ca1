//! `touchdown study`: the sweep of a scenario run at each of several values of one of its
//! keys, and one table of what changes with it (outcome shares with 95 % intervals, the
//! allowable slope per azimuth sector, the static tipping limit), as Arrow, Markdown and a
//! PNG of allowable slope against the value.
//!
//! Each value's sweep is an ordinary sweep file in the study's folder, run with the same
//! seed (every value meets the same landers: the curve is paired). A study is resumed and
//! sharded through those files: the same command run again keeps the complete ones,
//! finishes an interrupted one (`sweep --resume`'s way) and runs the rest; with `--shard
//! K/N` it runs the K-th slice of every value, and the command without `--shard` merges the
//! N shard files of each value (`touchdown merge`'s way) before it writes the table.

use crate::cli::{KernelChoice, RunOptions, SweepPlan};
use crate::output::sweep::Format;
use crate::reference::Outcome;
use crate::report::{
    Allowable, SECTOR_DEG, SECTORS, allowable_slope, relative_azimuth_deg, sector_of,
    wilson_interval,
};
use crate::scenario::Scenario;
use crate::sweep::Shard;
use anyhow::{Context as _, anyhow, bail};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

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
    #[arg(long, value_name = "N", value_parser = crate::cli::parse_count, allow_negative_numbers = true)]
    pub samples: Option<u64>,
    /// Seed of every value's sweep (overrides the scenario's `seed`).
    #[arg(long, value_name = "S", value_parser = crate::cli::parse_seed, allow_negative_numbers = true)]
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
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "T", value_parser = crate::cli::parse_threads, allow_negative_numbers = true)]
    pub threads: Option<usize>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// SIMD kernel, as for `touchdown sweep`.
    #[arg(long, value_name = "KERNEL", default_value = "auto", value_parser = crate::cli::parse_kernel)]
    pub kernel: KernelChoice,
}

/// A key and the values it takes (`--vary KEY=MIN:MAX:COUNT`).
#[derive(Debug, Clone, PartialEq)]
pub struct Vary {
    pub key: String,
    pub min: f64,
    pub max: f64,
    pub count: usize,
}

/// Most values one study runs.
const MAX_VALUES: usize = 1000;

impl Vary {
    /// Parses `KEY=MIN:MAX:COUNT`.
    pub fn parse(text: &str) -> Result<Vary, String> {
        let form = "write it KEY=MIN:MAX:COUNT, e.g. lander.footpad_radius_m=0.45:0.9:4";
        let (key, range) = text
            .split_once('=')
            .ok_or_else(|| format!("{text:?} has no '=': {form}"))?;
        let key = key.trim();
        let ok_part = |p: &str| {
            !p.is_empty()
                && p.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        };
        if !key.split('.').all(ok_part) {
            return Err(format!(
                "{key:?} is not a scenario key (names of letters, digits and _ joined by \
                 dots): {form}"
            ));
        }
        if matches!(key, "seed" | "samples" | "design") {
            return Err(format!(
                "{key} is not a key to vary (--seed and --samples set the study's; every \
                 value runs the same design)"
            ));
        }
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let [min, max, count] = parts[..] else {
            return Err(format!("{range:?} is not MIN:MAX:COUNT: {form}"));
        };
        let number = |what: &str, s: &str| -> Result<f64, String> {
            s.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{what} {s:?} is not a number"))
        };
        let (min, max) = (number("MIN", min)?, number("MAX", max)?);
        let count = match count.parse::<usize>() {
            Ok(n) if (1..=MAX_VALUES).contains(&n) => n,
            _ => {
                return Err(format!(
                    "COUNT {count:?} is not a whole number from 1 to {MAX_VALUES}"
                ));
            }
        };
        if count == 1 && min != max {
            return Err(format!(
                "one value from {min} to {max}? COUNT 1 needs MIN = MAX; give COUNT >= 2"
            ));
        }
        if count > 1 && min == max {
            return Err(format!(
                "{count} values all equal to {min}: MIN and MAX must differ"
            ));
        }
        let v = Vary {
            key: key.to_string(),
            min,
            max,
            count,
        };
        let values = v.values();
        if values.windows(2).any(|w| w[0] == w[1]) {
            return Err(format!(
                "{count} values from {min} to {max} are too close to tell apart"
            ));
        }
        Ok(v)
    }

    /// The values, evenly spaced from `min` to `max`, rounded to 12 significant digits (so
    /// that 0.45:0.9:4 gives 0.6, not 0.6000000000000001).
    #[must_use]
    pub fn values(&self) -> Vec<f64> {
        if self.count == 1 {
            return vec![self.min];
        }
        (0..self.count)
            .map(|i| {
                let x = self.min + (self.max - self.min) * i as f64 / (self.count - 1) as f64;
                format!("{x:.11e}").parse().unwrap_or(x)
            })
            .collect()
    }

    /// The key's last name (`footpad_radius_m` of `lander.footpad_radius_m`).
    #[must_use]
    pub fn leaf(&self) -> &str {
        self.key.rsplit('.').next().unwrap_or(&self.key)
    }
}

/// The scenario text `base` (parsed) with `key` set to `value`, and the scenario it reads
/// as; refused with the reader's message where the scenario refuses the value.
fn with_value(base: &toml::Table, key: &str, value: f64) -> anyhow::Result<(String, Scenario)> {
    let leaf = key.rsplit('.').next().unwrap_or(key);
    let mut probe = base.clone();
    let at = parent_table(&mut probe, key)?;
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
        Some(toml::Value::Table(_)) => bail!(
            "--vary {key}: {key} is a table of settings in the scenario (a distribution?), \
             not a number: vary one of its keys (e.g. {key}.max)"
        ),
        Some(other) => bail!(
            "--vary {key}: {key} is {} in the scenario, not a number",
            other.type_str()
        ),
    };
    let mut first_error = None;
    for v in given {
        let mut table = base.clone();
        parent_table(&mut table, key)?.insert(leaf.to_string(), v);
        let text = format!(
            "# touchdown study: {key} = {value}\n{}",
            toml::to_string(&table).context("cannot write the scenario of a study value")?
        );
        match Scenario::from_toml(&text) {
            Ok(s) => return Ok((text, s)),
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    let e = first_error.expect("at least one form was tried");
    bail!("--vary {key}: at {key} = {value}, {e}")
}

/// The table of `table` that holds `key`'s last name (made where missing).
fn parent_table<'t>(table: &'t mut toml::Table, key: &str) -> anyhow::Result<&'t mut toml::Table> {
    let names: Vec<&str> = key.split('.').collect();
    let mut at = table;
    for (i, name) in names[..names.len() - 1].iter().enumerate() {
        let entry = at
            .entry((*name).to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        at = match entry {
            toml::Value::Table(t) => t,
            _ => bail!(
                "--vary {key}: `{}` is a value in the scenario, not a table of keys",
                names[..=i].join(".")
            ),
        };
    }
    Ok(at)
}

/// One value of the study: its scenario and its sweep file.
struct Point {
    value: f64,
    text: String,
    scenario: Scenario,
    /// The complete sweep of this value.
    file: PathBuf,
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
    let (schema, _) = crate::output::read::open_sweep(path)?;
    Ok(schema
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
    let interrupted = crate::output::resume::interrupted_path(&file);
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

/// Runs `touchdown study`.
pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    let (base, base_text) = crate::cli::load_scenario(args.scenario.as_ref(), args.seed)?;
    let parsed: toml::Table = base_text
        .parse()
        .map_err(|e| anyhow!("cannot read the scenario as TOML: {e}"))?;
    let samples = args.samples.unwrap_or(base.samples);
    if samples == 0 {
        bail!("--samples must be at least 1");
    }
    let dir = &args.out_dir;
    if dir.exists() && !dir.is_dir() {
        bail!("--out-dir {}: that is a file, not a folder", dir.display());
    }
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
            let (text, scenario) = with_value(&parsed, &args.vary.key, value)?;
            let file = dir.join(format!("{i:02}-{}-{value}.{ext}", args.vary.leaf()));
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
    let steps = points
        .iter()
        .map(|p| step_of(p, samples, args.shard))
        .collect::<anyhow::Result<Vec<Step>>>()?;
    std::fs::create_dir_all(dir)
        .map_err(|e| anyhow!("cannot make the study's folder {}: {e}", dir.display()))?;

    let pool = crate::cli::worker_pool(args.threads)?;
    let stop = crate::cli::stop_on_signals()?;
    let options = RunOptions {
        pool: &pool,
        stop: &stop,
        progress: !args.quiet,
        banner: false,
        auto_kernel: matches!(args.kernel, KernelChoice::Auto),
    };
    let shard_note = args
        .shard
        .map_or(String::new(), |s| format!(", shard {s} of each"));
    if !args.quiet {
        eprintln!(
            "touchdown study: {} = {} ({} value{}), {samples} samples each{shard_note}, seed {}, \
         into {}",
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
        );
    }
    let started = std::time::Instant::now();
    let mut log = String::new();
    for (p, step) in points.iter().zip(steps) {
        let file = args
            .shard
            .map_or_else(|| p.file.clone(), |s| p.shard_file(s));
        let continue_with = "the same touchdown study command again".to_string();
        let at = format!("at {} = {}, ", args.vary.key, p.value);
        let line = match step {
            Step::Kept => "kept (done before)".to_string(),
            Step::Merge(files) => {
                let m = crate::output::merge::merge(&files, &file, args.format)?;
                format!("merged from {} shards ({} samples)", m.shards, m.rows)
            }
            Step::Resume => {
                let mut plan = SweepPlan::resuming(&file, None, args.kernel)?;
                plan.continue_with = continue_with;
                let done = crate::cli::execute(&plan, &options)?;
                crate::cli::warn_untouched(&done, &plan.scenario, &at);
                format!(
                    "resumed: {} samples in {:.1} s, {} kept",
                    done.computed,
                    done.wall_s,
                    done.rows - done.computed
                )
            }
            Step::Run => {
                crate::output::check_output_path(&file)?;
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
                    out: file.clone(),
                    kernel,
                    resume: None,
                    continue_with,
                };
                let done = crate::cli::execute(&plan, &options)?;
                crate::cli::warn_untouched(&done, &plan.scenario, &at);
                format!(
                    "{} samples in {:.1} s, {:.1} % stable",
                    done.computed,
                    done.wall_s,
                    100.0 * done.counts[Outcome::Stable as usize] as f64 / done.rows as f64
                )
            }
        };
        let _ = writeln!(
            log,
            "{} = {}: {line} -> {}",
            args.vary.key,
            p.value,
            file.display()
        );
    }
    crate::cli::print_out(&log);
    if let Some(s) = args.shard {
        crate::cli::print_out(&format!(
            "shard {s} of every value done in {:.1} s; once all {} shards are done, the same \
             command without --shard merges them and writes the study's table\n",
            started.elapsed().as_secs_f64(),
            s.count
        ));
        return Ok(());
    }
    let rows = points
        .iter()
        .map(|p| Row::read(p, samples))
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
        seed: base.seed,
        samples,
        base_text: &base_text,
    };
    let table = dir.join("study.arrow");
    let md = dir.join("study.md");
    let png = dir.join("study.png");
    write_table(&table, &rows, &about)?;
    let text = markdown(&rows, &about);
    write_text(&md, &text)?;
    crate::plot::study_chart(&png, &rows, &about)?;
    crate::cli::print_out(&format!(
        "\n{text}\nwrote {}, {} and {}\n",
        table.display(),
        md.display(),
        png.display()
    ));
    Ok(())
}

/// What the table, its Markdown and its picture say about the study.
pub(crate) struct About<'a> {
    pub key: &'a str,
    pub vary: &'a Vary,
    /// The scenario file, as the command line named it.
    pub scenario: String,
    pub seed: u64,
    pub samples: u64,
    pub base_text: &'a str,
}

/// One value's line of the table.
pub(crate) struct Row {
    pub value: f64,
    pub file: PathBuf,
    pub samples: u64,
    /// Samples per outcome, in the order of `Outcome::ALL`.
    pub counts: [u64; Outcome::ALL.len()],
    /// The allowable slope per sector (as `touchdown report` finds it).
    pub allowable: [Allowable; SECTORS],
    /// The least static tipping limit over each sector's azimuths (none where the gear
    /// stands on no slope).
    pub static_limit: [Option<f64>; SECTORS],
    /// The least and the greatest static tipping limit over all azimuths.
    pub static_range: Option<(f64, f64)>,
}

impl Row {
    /// The line of `point` from its sweep file.
    fn read(point: &Point, samples: u64) -> anyhow::Result<Row> {
        let path = &point.file;
        let t = crate::output::columns::Table::read(path, |n| {
            matches!(n, "slope_deg" | "downhill_azimuth_deg" | "yaw_deg")
        })?;
        if t.rows as u64 != samples {
            bail!(
                "{} holds {} samples, not the {samples} of the study",
                path.display(),
                t.rows
            );
        }
        let (slope, azimuth, yaw) = (
            t.column("slope_deg", path)?,
            t.column("downhill_azimuth_deg", path)?,
            t.column("yaw_deg", path)?,
        );
        let mut counts = [0u64; Outcome::ALL.len()];
        let mut sectors: Vec<Vec<(f64, bool)>> = vec![Vec::new(); SECTORS];
        for i in 0..t.rows {
            let o = t.outcome[i];
            counts[usize::from(o)] += 1;
            let relative = relative_azimuth_deg(azimuth[i], yaw[i]);
            sectors[sector_of(relative)].push((slope[i], o == Outcome::Stable as u8));
        }
        let allowable: [Allowable; SECTORS] =
            std::array::from_fn(|k| allowable_slope(&mut sectors[k]));
        let tips = point.scenario.lander.tips_m();
        // Every 0.5 deg of azimuth.
        let limit = |deg: f64| crate::stability::static_limit_deg(&tips, deg);
        let static_limit = std::array::from_fn(|k| {
            (0..=(2.0 * SECTOR_DEG) as usize)
                .filter_map(|j| limit(k as f64 * SECTOR_DEG + 0.5 * j as f64))
                .reduce(f64::min)
        });
        let all: Vec<f64> = (0..720).filter_map(|j| limit(0.5 * f64::from(j))).collect();
        let static_range = (!all.is_empty()).then(|| {
            (
                all.iter().copied().fold(f64::INFINITY, f64::min),
                all.iter().copied().fold(0.0, f64::max),
            )
        });
        Ok(Row {
            value: point.value,
            file: path.clone(),
            samples,
            counts,
            allowable,
            static_limit,
            static_range,
        })
    }

    /// The share of outcome `o` and its 95 % interval.
    pub(crate) fn share(&self, o: usize) -> (f64, f64, f64) {
        let (lo, hi) = wilson_interval(self.counts[o], self.samples);
        (self.counts[o] as f64 / self.samples as f64, lo, hi)
    }
}

/// The name of sector `k`, as columns use it: `0_45`.
fn sector_name(k: usize) -> String {
    format!(
        "{:.0}_{:.0}",
        k as f64 * SECTOR_DEG,
        (k + 1) as f64 * SECTOR_DEG
    )
}

/// The allowable slope of a sector and its interval as three nullable numbers: slope, low,
/// high (no slope: none, 0, the bound below which it would lie; too few samples: none).
fn allowable_columns(a: Allowable) -> [Option<f64>; 3] {
    match a {
        Allowable::TooFewSamples(_) => [None; 3],
        Allowable::NoSlope { below_deg } => [None, Some(0.0), Some(below_deg)],
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => [Some(slope_deg), Some(low_deg), Some(high_deg)],
    }
}

/// Writes the study's table to `path` (Arrow IPC file).
fn write_table(path: &Path, rows: &[Row], about: &About<'_>) -> anyhow::Result<()> {
    use crate::output::field;
    use arrow_array::{ArrayRef, Float64Array, RecordBatch, StringArray, UInt64Array};
    use arrow_schema::{DataType, Schema};
    use std::sync::Arc;
    let mut fields = vec![
        field(
            about.key,
            DataType::Float64,
            "",
            "the value of the varied scenario key",
        ),
        field(
            "samples",
            DataType::UInt64,
            "",
            "samples of the value's sweep",
        ),
    ];
    let mut columns: Vec<ArrayRef> = vec![
        Arc::new(Float64Array::from_iter_values(rows.iter().map(|r| r.value))),
        Arc::new(UInt64Array::from_iter_values(
            rows.iter().map(|r| r.samples),
        )),
    ];
    for (k, o) in Outcome::ALL.iter().enumerate() {
        let name = o.name();
        fields.push(field(
            name,
            DataType::UInt64,
            "",
            &format!("samples {name}"),
        ));
        columns.push(Arc::new(UInt64Array::from_iter_values(
            rows.iter().map(|r| r.counts[k]),
        )));
        for (j, (suffix, what)) in [
            ("share", "share of the samples"),
            ("low", "95 % Wilson interval of the share, low end"),
            ("high", "95 % Wilson interval of the share, high end"),
        ]
        .iter()
        .enumerate()
        {
            fields.push(field(
                &format!("{name}_{suffix}"),
                DataType::Float64,
                "",
                &format!("{name}: {what}"),
            ));
            columns.push(Arc::new(Float64Array::from_iter_values(rows.iter().map(
                |r| {
                    let (p, lo, hi) = r.share(k);
                    [p, lo, hi][j]
                },
            ))));
        }
    }
    for k in 0..SECTORS {
        let s = sector_name(k);
        for (j, (suffix, what)) in [
            (
                "",
                "allowable slope (touchdown report's; empty: none, or too few samples)",
            ),
            ("_low", "95 % interval of the allowable slope, low end"),
            ("_high", "95 % interval of the allowable slope, high end"),
        ]
        .iter()
        .enumerate()
        {
            fields.push(
                field(
                    &format!("allowable_slope_{s}{suffix}_deg"),
                    DataType::Float64,
                    "deg",
                    &format!("sector {s} deg of downhill azimuth relative to the lander: {what}"),
                )
                .with_nullable(true),
            );
            columns.push(Arc::new(Float64Array::from_iter(
                rows.iter().map(|r| allowable_columns(r.allowable[k])[j]),
            )));
        }
        fields.push(
            field(
                &format!("static_limit_{s}_deg"),
                DataType::Float64,
                "deg",
                &format!(
                    "the least static tipping limit over sector {s} deg (empty: the gear stands \
                 on no slope)"
                ),
            )
            .with_nullable(true),
        );
        columns.push(Arc::new(Float64Array::from_iter(
            rows.iter().map(|r| r.static_limit[k]),
        )));
    }
    for (j, which) in ["least", "greatest"].iter().enumerate() {
        fields.push(
            field(
                &format!("static_limit_{which}_deg"),
                DataType::Float64,
                "deg",
                &format!("the {which} static tipping limit over azimuth"),
            )
            .with_nullable(true),
        );
        columns.push(Arc::new(Float64Array::from_iter(
            rows.iter()
                .map(|r| r.static_range.map(|(lo, hi)| [lo, hi][j])),
        )));
    }
    fields.push(field(
        "sweep_file",
        DataType::Utf8,
        "",
        "the value's sweep file, in the study's folder",
    ));
    columns.push(Arc::new(StringArray::from_iter_values(rows.iter().map(
        |r| {
            r.file
                .file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned()
        },
    ))));
    let meta = [
        ("touchdown.kind", "study".to_string()),
        ("touchdown.engine", crate::output::ENGINE.to_string()),
        ("touchdown.study.key", about.key.to_string()),
        (
            "touchdown.study.values",
            format!("{}:{}:{}", about.vary.min, about.vary.max, about.vary.count),
        ),
        ("touchdown.seed", about.seed.to_string()),
        ("touchdown.samples", about.samples.to_string()),
        ("touchdown.scenario", about.base_text.to_string()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect::<std::collections::HashMap<String, String>>();
    let schema = Arc::new(Schema::new(fields).with_metadata(meta));
    let batch = RecordBatch::try_new(schema.clone(), columns)?;
    let (file, out) = crate::output::AtomicFile::create(path)?;
    let mut w = crate::output::IpcWriter::new(&file, out, &schema)?;
    w.write(&batch)?;
    file.commit(w.finish()?)
}

/// Writes `text` to `path`, complete or not at all.
fn write_text(path: &Path, text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    let (file, mut out) = crate::output::AtomicFile::create(path)?;
    out.write_all(text.as_bytes())
        .map_err(|e| anyhow!("cannot write {}: {e}", path.display()))?;
    file.commit(out)
}

/// A Markdown cell of an allowable slope and its interval.
fn allowable_cell(a: Allowable) -> String {
    match a {
        Allowable::TooFewSamples(n) => format!("too few ({n})"),
        Allowable::NoSlope { below_deg } => format!("none (< {below_deg:.1})"),
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => format!("{slope_deg:.1} ({low_deg:.1}–{high_deg:.1})"),
    }
}

/// The study as Markdown.
fn markdown(rows: &[Row], about: &About<'_>) -> String {
    let mut t = String::new();
    let v = about.vary;
    let _ = writeln!(
        t,
        "# touchdown study: {} from {} to {} ({} values)\n",
        about.key, v.min, v.max, v.count
    );
    let _ = writeln!(
        t,
        "{}, seed {}, {} samples per value: every value meets the same landers (each sample \
         draws its inputs from its own seed), so differences between values are paired.\n",
        about.scenario, about.seed, about.samples
    );
    let _ = writeln!(t, "## Outcomes (share, 95 % interval)\n");
    let leaf = about.vary.leaf();
    let _ = write!(t, "| {leaf} | samples |");
    for o in Outcome::ALL {
        let _ = write!(t, " {} |", o.name());
    }
    let _ = write!(t, "\n|---:|---:|");
    t.push_str(&"---:|".repeat(Outcome::ALL.len()));
    t.push('\n');
    for r in rows {
        let _ = write!(t, "| {} | {} |", r.value, r.samples);
        for k in 0..Outcome::ALL.len() {
            let (p, lo, hi) = r.share(k);
            let _ = write!(
                t,
                " {:.2} % ({:.2}–{:.2}) |",
                100.0 * p,
                100.0 * lo,
                100.0 * hi
            );
        }
        t.push('\n');
    }
    let _ = writeln!(
        t,
        "\n## Allowable slope per sector (deg, 95 % interval)\n\nSectors of downhill azimuth \
         relative to the lander, as in `touchdown report`; \"none (< x)\": no slope has 99 % \
         of the samples at or below it stable, and the true allowable slope (if any) lies \
         below x. Static limit: the least and the greatest static tipping limit over azimuth.\n"
    );
    let _ = write!(t, "| {leaf} |");
    for k in 0..SECTORS {
        let _ = write!(
            t,
            " {:.0}–{:.0} |",
            k as f64 * SECTOR_DEG,
            (k + 1) as f64 * SECTOR_DEG
        );
    }
    let _ = write!(t, " static limit |\n|---:|");
    t.push_str(&"---:|".repeat(SECTORS + 1));
    t.push('\n');
    for r in rows {
        let _ = write!(t, "| {} |", r.value);
        for a in r.allowable {
            let _ = write!(t, " {} |", allowable_cell(a));
        }
        let _ = writeln!(
            t,
            " {} |",
            r.static_range
                .map_or("none".to_string(), |(lo, hi)| format!("{lo:.1}–{hi:.1}"))
        );
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_evenly_spaced_and_rounded() {
        let v = Vary::parse("lander.footpad_radius_m=0.45:0.9:4").unwrap();
        assert_eq!(v.key, "lander.footpad_radius_m");
        assert_eq!(v.leaf(), "footpad_radius_m");
        assert_eq!(v.values(), vec![0.45, 0.6, 0.75, 0.9]);
        let down = Vary::parse("x=1:0:3").unwrap();
        assert_eq!(down.values(), vec![1.0, 0.5, 0.0]);
        assert_eq!(Vary::parse("x=2:2:1").unwrap().values(), vec![2.0]);
    }

    #[test]
    fn bad_vary_is_refused_with_the_reason() {
        for (bad, says) in [
            ("lander.footpad_radius_m", "no '='"),
            ("=1:2:3", "not a scenario key"),
            ("a..b=1:2:3", "not a scenario key"),
            ("seed=1:2:3", "not a key to vary"),
            ("x=1:2", "not MIN:MAX:COUNT"),
            ("x=a:2:3", "MIN \"a\" is not a number"),
            ("x=1:inf:3", "MAX \"inf\" is not a number"),
            ("x=1:2:0", "COUNT"),
            ("x=1:2:1.5", "COUNT"),
            ("x=1:2:1", "COUNT 1 needs MIN = MAX"),
            ("x=1:1:3", "must differ"),
            ("x=1:1.0000000000001:3", "too close"),
        ] {
            let e = Vary::parse(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

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
