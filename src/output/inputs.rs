//! No output is an input of the same command: a command declares the files it reads
//! (`declare`), and every output it opens afterwards (`AtomicFile::create`,
//! `check_output_path`, `OutputSet::reserve`, standard output) is refused when it is one of
//! them, whether named the same way, through a symbolic link or as another hard link of
//! the same file; and so is an output whose temporary file (or an interrupted sweep's file)
//! would take an input's name.

use anyhow::bail;
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// A file a command reads: its path as given, and the file it is (device and inode).
struct Input {
    path: PathBuf,
    dev: u64,
    ino: u64,
}

/// The inputs declared by the running command.
static INPUTS: Mutex<Vec<Input>> = Mutex::new(Vec::new());

/// Declares the files the running command reads. A path that does not exist (yet) is left
/// to its reader's message.
pub fn declare(paths: &[&Path]) {
    let mut inputs = INPUTS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    for path in paths {
        if let Ok(m) = std::fs::metadata(path) {
            inputs.push(Input {
                path: path.to_path_buf(),
                dev: m.dev(),
                ino: m.ino(),
            });
        }
    }
}

/// The declared input that is the file `m` describes, if one is.
fn input_of(m: &std::fs::Metadata) -> Option<PathBuf> {
    let inputs = INPUTS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    inputs
        .iter()
        .find(|i| i.dev == m.dev() && i.ino == m.ino() && m.is_file())
        .map(|i| i.path.clone())
}

/// Refuses the output `out` when it is (or links to) a file the command reads.
pub fn refuse_input_as_output(out: &Path) -> anyhow::Result<()> {
    if out.as_os_str() == "-" {
        return refuse_stdout_as_output();
    }
    if let Ok(m) = std::fs::metadata(out)
        && let Some(input) = input_of(&m)
    {
        bail!(
            "cannot write {}: it is {} and would be overwritten; choose another output path",
            out.display(),
            same_as(out, &input)
        );
    }
    Ok(())
}

/// Refuses the output `out` when `beside`, a file it makes beside itself (`what`: its
/// unfinished file, an interrupted sweep's rows), is (or links to) a file the command reads:
/// that file would be emptied, replaced or removed.
pub fn refuse_input_beside(out: &Path, beside: &Path, what: &str) -> anyhow::Result<()> {
    if let Ok(m) = std::fs::metadata(beside)
        && let Some(input) = input_of(&m)
    {
        bail!(
            "cannot write {}: {}, the name of {what}, is {}; choose another output path",
            out.display(),
            beside.display(),
            same_as(beside, &input)
        );
    }
    Ok(())
}

/// Refuses standard output when it is redirected into a file the command reads
/// (`touchdown report s.arrow >> s.arrow`).
pub fn refuse_stdout_as_output() -> anyhow::Result<()> {
    use std::os::fd::AsFd;
    let Ok(fd) = std::io::stdout().as_fd().try_clone_to_owned() else {
        return Ok(());
    };
    if let Ok(m) = std::fs::File::from(fd).metadata()
        && let Some(input) = input_of(&m)
    {
        bail!(
            "standard output goes into {}, which this command reads: it would be overwritten; \
             send the output elsewhere",
            input.display()
        );
    }
    Ok(())
}

/// The folder that holds `path` (`.` for a bare name).
pub(super) fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(f) if !f.as_os_str().is_empty() => f,
        _ => Path::new("."),
    }
}

/// Whether paths `a` and `b` name the same entry of the same folder, however written
/// (`m/x` and `/abs/m/x`; a link at the last step is not followed).
fn same_name(a: &Path, b: &Path) -> bool {
    let entry = |p: &Path| {
        Some((
            std::fs::canonicalize(folder_of(p)).ok()?,
            p.file_name()?.to_owned(),
        ))
    };
    a == b || entry(a).is_some_and(|e| entry(b) == Some(e))
}

/// What `out` is of the input `input`: the same path (however written), or the same file
/// under another name.
fn same_as(out: &Path, input: &Path) -> String {
    if same_name(out, input) {
        "an input of this command".to_string()
    } else {
        format!("the input {} under another name (a link)", input.display())
    }
}
