//! A study's folder: one study writes it at a time (a lock on the folder, shared by the
//! shards of one study that a cluster runs side by side), and a folder that holds another
//! study's files is refused before any work, never overwritten or mixed.

use crate::output::FolderLock;
use anyhow::{anyhow, bail};
use std::path::{Path, PathBuf};

/// What identifies a study: its key and values, seed, samples and base scenario.
pub struct StudyId<'a> {
    /// The varied key.
    pub key: &'a str,
    /// Its values as `MIN:MAX:COUNT`.
    pub values: String,
    /// The seed of every value's sweep.
    pub seed: u64,
    /// Samples per value.
    pub samples: u64,
    /// The base scenario's text, its seed applied.
    pub base_text: &'a str,
}

/// Makes the study's folder `dir` if missing and locks it: exclusively for a whole study
/// (which merges and writes the table), shared for a shard (the shards of one study run at
/// once). Refused, naming the other run, while another study writes it.
pub fn lock_folder(dir: &Path, shard: bool) -> anyhow::Result<FolderLock> {
    std::fs::create_dir_all(dir)
        .map_err(|e| anyhow!("cannot make the study's folder {}: {e}", dir.display()))?;
    FolderLock::acquire(dir, shard)
}

/// Refuses the folder `dir` when it holds another study: a table (`study.arrow`) of
/// another key, values, seed, sample count or scenario, or a value's sweep file (`NN-...`)
/// that is none of `files` (this study's, by name without folder, shard or suffix).
pub fn refuse_other_study(dir: &Path, id: &StudyId<'_>, files: &[PathBuf]) -> anyhow::Result<()> {
    let elsewhere = "give this study another --out-dir, or remove the other study's files";
    let [table, ..] = crate::study::table_files(dir);
    // A table there (not a device or FIFO the user put in its place) must be this study's.
    if std::fs::metadata(&table).is_ok_and(|m| m.is_file()) {
        let meta = crate::output::read::format_of(&table)
            .and_then(|f| crate::output::read::open(&table, f))
            .map(|(schema, _)| schema.metadata().clone())
            .map_err(|e| anyhow!("{e:#}; {elsewhere}"))?;
        let get = |k: &str| meta.get(k).map_or("", String::as_str);
        let differs = [
            ("its key", get("touchdown.study.key") != id.key),
            ("its values", get("touchdown.study.values") != id.values),
            ("its seed", get("touchdown.seed") != id.seed.to_string()),
            (
                "its samples per value",
                get("touchdown.samples") != id.samples.to_string(),
            ),
            ("its scenario", get("touchdown.scenario") != id.base_text),
        ];
        if let Some((what, _)) = differs.iter().find(|(_, d)| *d) {
            bail!(
                "{} holds another study ({} = {}, seed {}, {} samples per value; it differs \
                 in {what}): {elsewhere}",
                dir.display(),
                get("touchdown.study.key"),
                get("touchdown.study.values"),
                get("touchdown.seed"),
                get("touchdown.samples")
            );
        }
    }
    let ours: Vec<String> = files.iter().filter_map(|f| stem_of(f)).collect();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if let Some(stem) = stem_of(Path::new(&name))
            && !ours.contains(&stem)
        {
            bail!(
                "{} holds {name}, a sweep of another study (this one's files are {}, ...): \
                 {elsewhere}",
                dir.display(),
                files
                    .first()
                    .and_then(|f| f.file_name())
                    .map_or(String::new(), |f| f.to_string_lossy().into_owned())
            );
        }
    }
    Ok(())
}

/// The value part of a study's sweep file name (`03-footpad_radius_m-0.6` of
/// `03-footpad_radius_m-0.6.shard-1-of-4.arrow.interrupted`), if the name is one.
fn stem_of(file: &Path) -> Option<String> {
    let name = file.file_name()?.to_str()?;
    let bytes = name.as_bytes();
    if bytes.len() < 4
        || !bytes[0].is_ascii_digit()
        || !bytes[1].is_ascii_digit()
        || bytes[2] != b'-'
    {
        return None;
    }
    let mut rest = name;
    for suffix in [".partial", ".interrupted"] {
        rest = rest.strip_suffix(suffix).unwrap_or(rest);
    }
    let rest = rest
        .strip_suffix(".arrow")
        .or_else(|| rest.strip_suffix(".parquet"))?;
    let rest = match rest.rfind(".shard-") {
        Some(i) => &rest[..i],
        None => rest,
    };
    Some(rest.to_string())
}
