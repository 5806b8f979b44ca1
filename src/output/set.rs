//! A command's outputs as one unit. A command that writes several files (the pictures of
//! `plot`, `envelope`'s picture and table, a landing-site map's or a study's files)
//! reserves them all before it writes any (`OutputSet::reserve`), before its work where it
//! can: each is checked as any output is (`check_output_path`: its folder, not a folder
//! itself, none of the command's inputs) and its temporary file made and locked, so that a
//! bad output is refused before the first file and a run to a file another run is writing
//! is refused before it writes anything. The command's writers then write as they write
//! any output (`AtomicFile::create` finds the reservation and writes into its temporary
//! file), and `commit` moves every file into place once all are written: two runs never
//! leave files of both, and a run that fails leaves the earlier set as it was. A command
//! that reserves its files after its work (a map, a study: their folders are locked from
//! the start) makes the same checks before it (`check`).

use super::target::{
    Target, check_output_path, create_unfinished, remove_unfinished_file, settle_unfinished,
    target_of,
};
use std::fs::File;
use std::io::Seek;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

/// A reserved output.
struct Reserved {
    /// The path as the command names it.
    path: PathBuf,
    /// The file it replaces when the set is committed (a symbolic link's target).
    target: PathBuf,
    /// Its temporary file's name.
    partial: PathBuf,
    /// The temporary file, locked for as long as the set is reserved.
    file: File,
    /// Whether its writer has finished it.
    written: bool,
}

/// The outputs reserved by the running command.
static RESERVED: Mutex<Vec<Reserved>> = Mutex::new(Vec::new());

/// Takes the reservations of `paths` out of `RESERVED`.
fn take(paths: &[PathBuf]) -> Vec<Reserved> {
    let mut reserved = RESERVED.lock().unwrap_or_else(PoisonError::into_inner);
    let (mine, others) = std::mem::take(&mut *reserved)
        .into_iter()
        .partition(|r| paths.contains(&r.path));
    *reserved = others;
    mine
}

/// The files of one command, reserved (checked, their temporary files locked) until
/// `commit` moves them into place; dropped without `commit`, their temporary files are
/// removed and nothing of the set is written.
#[must_use = "an output set writes nothing until it is committed"]
#[derive(Debug)]
pub struct OutputSet {
    paths: Vec<PathBuf>,
}

impl OutputSet {
    /// Reserves `paths` for this command: every one is checked first, then their temporary
    /// files are locked in the order of their names (so that of two runs to the same set
    /// one gets it all). Refused, naming the path and the other run, while another process
    /// writes one of them. An output that is not a regular file (a device, a FIFO, a link
    /// to one) is written into directly, as ever, and needs no reservation.
    pub fn reserve(paths: &[PathBuf]) -> anyhow::Result<OutputSet> {
        for path in paths {
            check_output_path(path)?;
        }
        let mut regular = Vec::new();
        for path in paths {
            if let Target::Regular {
                path: target,
                partial,
            } = target_of(path)?
            {
                regular.push((partial, target, path.clone()));
            }
        }
        regular.sort();
        regular.dedup_by(|a, b| a.0 == b.0);
        let mut set = OutputSet { paths: Vec::new() };
        for (partial, target, path) in regular {
            // On a refusal, `set` drops the reservations made so far.
            let file = create_unfinished(&partial, &path)?;
            RESERVED
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .push(Reserved {
                    path: path.clone(),
                    target,
                    partial,
                    file,
                    written: false,
                });
            set.paths.push(path);
        }
        Ok(set)
    }

    /// Moves every file of the set that was written onto its name; where a file of the set
    /// was not written this time (a trace's thrust picture, of a trace without thrusters),
    /// a regular file under its name, an earlier run's, is removed, so that the set never
    /// mixes two runs. The locks are released once all are in place.
    pub fn commit(mut self) -> anyhow::Result<()> {
        let members = take(&std::mem::take(&mut self.paths));
        let mut failed = None;
        for r in &members {
            let done = if failed.is_some() {
                Ok(())
            } else if r.written {
                settle_unfinished(&r.partial, || std::fs::rename(&r.partial, &r.target)).map_err(
                    |e| {
                        anyhow::anyhow!(
                            "cannot move the finished file onto {}: {e}",
                            r.target.display()
                        )
                    },
                )
            } else {
                remove_stale(&r.path)
            };
            if let Err(e) = done {
                failed = Some(e);
            }
        }
        // Those not moved (a move failed, or a member not written); a moved one is off the
        // list, and its name may already be another run's file.
        remove_listed(&members);
        drop(members);
        failed.map_or(Ok(()), Err)
    }
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        remove_listed(&take(&self.paths));
    }
}

/// Removes the temporary files of `members` still listed as being written.
fn remove_listed(members: &[Reserved]) {
    for r in members {
        remove_unfinished_file(&r.partial);
    }
}

/// Removes the file at `path` that a committed set did not write, if it is a regular file
/// (a link or a device is left as it is).
fn remove_stale(path: &Path) -> anyhow::Result<()> {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_file() => std::fs::remove_file(path).map_err(|e| {
            anyhow::anyhow!(
                "cannot remove {}, an earlier run's file of this set: {e}",
                path.display()
            )
        }),
        _ => Ok(()),
    }
}

/// The temporary file reserved for `path`, emptied, with the file it replaces and its
/// temporary name; `None` where `path` is not reserved.
pub(super) fn claim(path: &Path) -> anyhow::Result<Option<(PathBuf, PathBuf, File)>> {
    let reserved = RESERVED.lock().unwrap_or_else(PoisonError::into_inner);
    let Some(r) = reserved.iter().find(|r| r.path == path) else {
        return Ok(None);
    };
    let cannot = |e: std::io::Error| {
        anyhow::anyhow!("cannot write output file {}: {e}", r.partial.display())
    };
    let mut file = r.file.try_clone().map_err(cannot)?;
    file.set_len(0).map_err(cannot)?;
    file.rewind().map_err(cannot)?;
    Ok(Some((r.target.clone(), r.partial.clone(), file)))
}

/// Marks the reserved file whose temporary name is `partial` as written, to be moved into
/// place when its set is committed.
pub(super) fn written(partial: &Path) {
    let mut reserved = RESERVED.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some(r) = reserved.iter_mut().find(|r| r.partial == partial) {
        r.written = true;
    }
}

/// Checks `paths`, the outputs a command will reserve once its folder is made (a study's,
/// a map's), before its work: each one whose folder exists already is checked as
/// `reserve` checks it (in a folder not made yet, no input can lie).
pub fn check(paths: &[PathBuf]) -> anyhow::Result<()> {
    for path in paths {
        if super::inputs::folder_of(path).is_dir() {
            check_output_path(path)?;
        }
    }
    Ok(())
}
