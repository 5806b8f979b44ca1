//! Where an output goes and whether it may go there: standard output, a device written
//! into, or a regular file written under a temporary name beside it (`PATH.partial`); the
//! checks of an output path made before any work (a folder that exists, not a folder
//! itself, none of the command's inputs, nor its temporary name one); and the temporary
//! files being written, removed when a signal ends the process.

use super::{inputs, lock};
use std::fs::File;
use std::path::{Path, PathBuf};

/// Where an output goes.
#[derive(Debug, Clone)]
pub(super) enum Target {
    /// A regular file (or none yet): written as `PATH.partial` beside it and renamed onto
    /// it when complete. A symbolic link is followed: the file it names is replaced, the
    /// link stays.
    Regular {
        /// The file replaced (a symbolic link's target).
        path: PathBuf,
        /// Its temporary name.
        partial: PathBuf,
    },
    /// Something that is not a regular file (a device such as `/dev/null`, a FIFO, or a
    /// symbolic link to one): written into directly, never replaced or removed.
    Direct {
        /// The path as given.
        path: PathBuf,
    },
    /// Standard output (`-`).
    Stdout,
}

/// The temporary files of the outputs being written, to remove when a signal ends the
/// process (`remove_unfinished_then`).
static UNFINISHED: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Creates the temporary file `partial` of the output `out` (`lock::create_locked`) and
/// lists it among those being written, both while holding the list: a signal that comes
/// between the file's creation and its listing would otherwise end the process with the
/// file left behind, and one that removed it first would remove another run's file.
pub(super) fn create_unfinished(partial: &Path, out: &Path) -> anyhow::Result<File> {
    let mut files = UNFINISHED
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let file = lock::create_locked(partial, out)?;
    files.push(partial.to_path_buf());
    Ok(file)
}

/// Runs `settle` (the temporary file `partial` renamed onto its output, or removed) and,
/// where it succeeds, takes the file off the list of those being written, both while
/// holding the list: a signal's removal then never meets the name after the file has gone,
/// when it may already be another run's.
pub(super) fn settle_unfinished(
    partial: &Path,
    settle: impl FnOnce() -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut files = UNFINISHED
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    settle()?;
    if let Some(i) = files.iter().position(|f| f == partial) {
        files.swap_remove(i);
    }
    Ok(())
}

/// Removes the temporary file `partial` if it is still listed as being written (neither
/// renamed onto its output nor removed), and takes it off the list, holding the list.
pub(super) fn remove_unfinished_file(partial: &Path) {
    let mut files = UNFINISHED
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(i) = files.iter().position(|f| f == partial) {
        let _ = std::fs::remove_file(partial);
        files.swap_remove(i);
    }
}

/// Removes the temporary files of every output being written and hands their count to
/// `end`, which ends the process (a signal came), still holding the list: no thread lists a
/// new file, nor renames or removes one by its name, before the process has ended, so
/// nothing unfinished is left behind and no other run's file under the same name is touched.
pub fn remove_unfinished_then(end: impl FnOnce(usize) -> std::convert::Infallible) -> ! {
    let files = UNFINISHED
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    for f in files.iter() {
        let _ = std::fs::remove_file(f);
    }
    match end(files.len()) {}
}

/// Where output `path` goes: standard output, a device or FIFO (followed through symbolic
/// links) written into, or a regular file (the one a symbolic link names) renamed into place.
pub(super) fn target_of(path: &Path) -> anyhow::Result<Target> {
    if path.as_os_str() == "-" {
        return Ok(Target::Stdout);
    }
    if let Ok(m) = std::fs::metadata(path)
        && !m.is_file()
    {
        return Ok(Target::Direct {
            path: path.to_path_buf(),
        });
    }
    // A symbolic link (to a regular file, or to nothing yet): replace what it names.
    let mut real = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&real) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&real)
                    .map_err(|e| anyhow::anyhow!("cannot follow {}: {e}", real.display()))?;
                real = match real.parent() {
                    Some(dir) => dir.join(to),
                    None => to,
                };
            }
            _ => break,
        }
    }
    let mut name = real.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    let partial = real.with_file_name(name);
    Ok(Target::Regular {
        path: real,
        partial,
    })
}

/// Refuses an output path whose folder is missing, that names a folder or that is one of
/// the command's inputs (`inputs::declare`), or whose temporary name is one, before any
/// work. `-` (standard output) and existing files of any kind other than folders are
/// accepted.
pub fn check_output_path(path: &Path) -> anyhow::Result<()> {
    if path.as_os_str() == "-" {
        return inputs::refuse_stdout_as_output();
    }
    if path.as_os_str().is_empty() || path.file_name().is_none() {
        anyhow::bail!("output path {:?} names no file", path.display().to_string());
    }
    if path.is_dir() {
        anyhow::bail!("output path {} is a folder, not a file", path.display());
    }
    if std::fs::metadata(path).is_ok() {
        inputs::refuse_input_as_output(path)?;
    } else {
        let parent = inputs::folder_of(path);
        if parent.exists() && !parent.is_dir() {
            anyhow::bail!(
                "cannot write output file {}: {} is a file, not a folder",
                path.display(),
                parent.display()
            );
        }
        if !parent.is_dir() {
            anyhow::bail!(
                "cannot write output file {}: folder {} does not exist",
                path.display(),
                parent.display()
            );
        }
    }
    // The temporary name it is written under is emptied first: not an input either.
    if let Target::Regular { partial, .. } = target_of(path)? {
        inputs::refuse_input_beside(path, &partial, "its unfinished file")?;
    }
    Ok(())
}
