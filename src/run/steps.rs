//! A sweep a command keeps in its folder (a study's value, a landing-site map's sweep):
//! kept when it is there complete, merged from its shards, finished when interrupted, run
//! otherwise; and with `--shard K/N`, the K-th slice of it alone.
//!
//! The sweep is an ordinary sweep file (its shards `NAME.shard-K-of-N.EXT` beside it), so
//! the same command run again, `sweep --resume` and `touchdown merge` all work on it. A
//! file there that is another sweep (another scenario, seed, sample count or shard) is
//! refused, never overwritten.

use super::execute::{Executed, RunOptions, execute};
use super::load::KernelChoice;
use super::plan::SweepPlan;
use crate::output::format::Format;
use crate::scenario::Scenario;
use crate::sweep::Shard;
use anyhow::{Context as _, anyhow, bail};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A sweep a command makes in its folder.
pub struct Kept<'a> {
    /// Its scenario text (as stored in the file's metadata, seed applied).
    pub text: &'a str,
    /// The scenario that text reads as.
    pub scenario: &'a Scenario,
    /// The complete sweep's file.
    pub file: &'a Path,
    /// Its samples.
    pub samples: u64,
    /// How messages name it.
    pub names: Names,
}

/// How a command's messages name its sweep.
pub struct Names {
    /// "this study's sweep at 0.3": "PATH is not {whose}".
    pub whose: String,
    /// "study": "give the {owner} another --out-dir".
    pub owner: &'static str,
    /// "the sweep at 0.3": "{sweep} is sharded N ways and lacks ...".
    pub sweep: String,
    /// The name in "DIR holds shards of {sweep_long} cut N and M ways".
    pub sweep_long: String,
    /// The scenario keys the command's flags set, each with what sets it: a file whose
    /// scenario differs in one is said to differ in it, and why.
    pub set_by_flags: &'static [(&'static str, &'static str)],
}

/// What to do with a kept sweep (or its shard) given what the folder holds.
pub enum Step {
    /// It is there, complete: kept.
    Kept,
    /// Its N shard files are there: merged.
    Merge(Vec<PathBuf>),
    /// An interrupted run of it is there: finished.
    Resume,
    /// Nothing of it yet: run.
    Run,
}

/// What a step did.
pub enum Done {
    /// The file was there, complete.
    Kept,
    /// Merged from `shards` shard files, `rows` samples.
    Merged {
        /// Shard files joined.
        shards: usize,
        /// Samples in all.
        rows: u64,
    },
    /// Finished where it was interrupted.
    Resumed(Executed),
    /// Run from the start.
    Ran(Executed),
}

/// The file of shard `shard` of the sweep `file`: `NAME.shard-K-of-N.EXT` beside it.
#[must_use]
pub fn shard_file(file: &Path, shard: Shard) -> PathBuf {
    let stem = file.file_stem().unwrap_or_default().to_string_lossy();
    let ext = file.extension().unwrap_or_default().to_string_lossy();
    file.with_file_name(format!(
        "{stem}.shard-{}-of-{}.{ext}",
        shard.index, shard.count
    ))
}

/// Why the sweep file with `meta` as its metadata is not `kept` (or its shard `shard`),
/// if it is not.
fn differs(
    meta: &HashMap<String, String>,
    kept: &Kept<'_>,
    shard: Option<Shard>,
) -> Option<String> {
    let get = |k: &str| meta.get(k).map(String::as_str);
    if get("touchdown.seed") != Some(kept.scenario.seed.to_string().as_str()) {
        return Some("its seed".into());
    }
    if get("touchdown.samples") != Some(kept.samples.to_string().as_str()) {
        return Some("its sample count".into());
    }
    let file_shard = get(crate::output::sweep::SHARD_KEYS[0]);
    if file_shard != shard.map(|s| s.to_string()).as_deref() {
        return Some("its shard".into());
    }
    let text = get("touchdown.scenario");
    if text != Some(kept.text) {
        let keys = text.map_or_else(Vec::new, |t| changed_keys(t, kept.text));
        if keys.is_empty() {
            return Some("its scenario".into());
        }
        let named: Vec<String> = keys
            .iter()
            .map(
                |k| match kept.names.set_by_flags.iter().find(|(key, _)| key == k) {
                    Some((_, by)) => format!("{k} ({by})"),
                    None => k.clone(),
                },
            )
            .collect();
        return Some(format!("its scenario's {}", named.join(", ")));
    }
    None
}

/// The keys whose values differ between the scenario texts `a` and `b`, dotted, in order
/// (a distribution is one value); none where either is not TOML.
fn changed_keys(a: &str, b: &str) -> Vec<String> {
    fn walk(a: &toml::Table, b: &toml::Table, path: &str, out: &mut Vec<String>) {
        let mut keys: Vec<&String> = a.keys().chain(b.keys()).collect();
        keys.sort_unstable();
        keys.dedup();
        for k in keys {
            let key = if path.is_empty() {
                k.clone()
            } else {
                format!("{path}.{k}")
            };
            match (a.get(k), b.get(k)) {
                (Some(toml::Value::Table(x)), Some(toml::Value::Table(y)))
                    if !x.contains_key("dist") && !y.contains_key("dist") =>
                {
                    walk(x, y, &key, out);
                }
                (x, y) if x != y => out.push(key),
                _ => {}
            }
        }
    }
    let (Ok(a), Ok(b)) = (a.parse::<toml::Table>(), b.parse::<toml::Table>()) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    walk(&a, &b, "", &mut out);
    out
}

/// The metadata of the sweep file `path`.
fn metadata_of(path: &Path) -> anyhow::Result<HashMap<String, String>> {
    let file = crate::output::sweep::SweepFile::open(path)?;
    Ok(file
        .metadata()
        .iter()
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect())
}

/// What to do with `kept` (or its shard `shard`) given what its folder holds.
pub fn step_of(kept: &Kept<'_>, shard: Option<Shard>) -> anyhow::Result<Step> {
    let file = shard.map_or_else(|| kept.file.to_path_buf(), |s| shard_file(kept.file, s));
    let other = |path: &Path, what: &str| {
        anyhow!(
            "{} is not {}: it differs in {what}; remove it, or give the {} another --out-dir",
            path.display(),
            kept.names.whose,
            kept.names.owner
        )
    };
    if file.exists() {
        let meta = metadata_of(&file)?;
        return match differs(&meta, kept, shard) {
            None => Ok(Step::Kept),
            Some(what) => Err(other(&file, &what)),
        };
    }
    let interrupted = crate::output::interrupted_path(&file);
    if interrupted.exists() {
        let meta = metadata_of(&interrupted)?;
        return match differs(&meta, kept, shard) {
            None => Ok(Step::Resume),
            Some(what) => Err(other(&interrupted, &what)),
        };
    }
    if shard.is_some() {
        return Ok(Step::Run);
    }
    let Some(files) = shards_there(kept.file, &kept.names)? else {
        return Ok(Step::Run);
    };
    let n = files.len() as u64;
    for f in &files {
        let mut meta = metadata_of(f)?;
        let shard = Shard { index: 0, count: n };
        // Shards share all but their index: compare with shard 0's key, index aside.
        meta.insert(
            crate::output::sweep::SHARD_KEYS[0].to_string(),
            shard.to_string(),
        );
        if let Some(what) = differs(&meta, kept, Some(shard)) {
            return Err(other(f, &what));
        }
    }
    Ok(Step::Merge(files))
}

/// The complete shard files of the sweep `file` in its folder, all N of one count
/// (`NAME.shard-K-of-N.EXT`), by their names alone; `None` where there is none. Refused
/// where shards of two counts lie there, or some of the N are missing: a check cheap enough
/// to make before a command's costly set-up.
pub fn shards_there(file: &Path, names: &Names) -> anyhow::Result<Option<Vec<PathBuf>>> {
    let dir = file.parent().unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Ok(None);
    }
    // Shard files of this sweep, complete ones, by shard count.
    let mut counts = std::collections::BTreeMap::<u64, Vec<u64>>::new();
    let stem = file.file_stem().unwrap_or_default().to_string_lossy();
    let ext = file.extension().unwrap_or_default().to_string_lossy();
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
        return Ok(None);
    };
    if counts.len() > 1 {
        bail!(
            "{} holds shards of {} cut {} ways: keep those of one --shard count",
            dir.display(),
            names.sweep_long,
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
            "{} is sharded {n} ways and lacks shard{} {}: run {} with --shard, then this \
             command again",
            names.sweep,
            if missing.len() == 1 { "" } else { "s" },
            missing.join(", "),
            if missing.len() == 1 { "it" } else { "them" }
        );
    }
    let files: Vec<PathBuf> = (0..n)
        .map(|k| shard_file(file, Shard { index: k, count: n }))
        .collect();
    Ok(Some(files))
}

/// How a step runs a sweep.
pub struct Running<'a> {
    /// The slice to run, if one.
    pub shard: Option<Shard>,
    /// Format of a new file.
    pub format: Format,
    /// The kernel a new run takes.
    pub kernel: KernelChoice,
    /// The command that finishes an interrupted run ("the same touchdown study command
    /// again").
    pub continue_with: &'a str,
    /// Pool, stop, progress.
    pub options: &'a RunOptions<'a>,
}

/// Does `step` for `kept` (its file, or its shard's when `running.shard` is given).
pub fn run_step(kept: &Kept<'_>, step: Step, running: &Running<'_>) -> anyhow::Result<Done> {
    let file = running
        .shard
        .map_or_else(|| kept.file.to_path_buf(), |s| shard_file(kept.file, s));
    Ok(match step {
        Step::Kept => Done::Kept,
        Step::Merge(files) => {
            let m = crate::output::merge::merge(&files, &file, running.format)?;
            Done::Merged {
                shards: m.shards,
                rows: m.rows,
            }
        }
        Step::Resume => {
            let mut plan = SweepPlan::resuming(&file, None, running.kernel)?;
            plan.continue_with = running.continue_with.to_string();
            Done::Resumed(execute(&plan, running.options)?)
        }
        Step::Run => {
            crate::output::check_sweep_output_path(&file)?;
            let kernel = kernels::isa::KernelKind {
                isa: running.kernel.isa()?,
                precision: kept.scenario.simulation.precision,
            };
            let plan = SweepPlan {
                scenario: kept.scenario.clone(),
                text: kept.text.to_string(),
                samples: kept.samples,
                shard: running.shard,
                format: running.format,
                out: Some(file),
                kernel,
                resume: None,
                continue_with: running.continue_with.to_string(),
            };
            Done::Ran(execute(&plan, running.options)?)
        }
    })
}
