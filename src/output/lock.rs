//! One writer per output: a run holds an exclusive lock on the temporary file it writes
//! (and a study on its folder) for as long as it writes, so that a second run to the same
//! path is refused, naming the run that writes it, instead of the two mixing their files.
//! The operating system releases a lock when its process ends, however it ends, so a run
//! killed outright never blocks the next one.

use anyhow::anyhow;
use std::fs::{File, OpenOptions};
use std::os::unix::fs::{MetadataExt, OpenOptionsExt};
use std::path::Path;

/// Opens `partial` (the temporary file of the output `out`) for writing, empty, and locked
/// for this process alone. Refused, naming the other run, while another process writes to
/// `out`.
pub(super) fn create_locked(partial: &Path, out: &Path) -> anyhow::Result<File> {
    let cannot = |e: std::io::Error| anyhow!("cannot write output file {}: {e}", partial.display());
    // A run that finishes renames its temporary file onto the output, and a run that fails
    // removes it: the file locked here may no longer be the one named `partial` by the time
    // the lock is granted. Then the name belongs to a newer file: take that one.
    for _ in 0..100 {
        // Never through a symbolic link put at the temporary name (it would truncate the
        // file it names): the link itself is removed, as an unfinished file would be.
        let opened = OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(false)
            .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
            .open(partial);
        let file = match opened {
            Ok(file) => file,
            Err(e) if e.raw_os_error() == Some(libc::ELOOP) => {
                std::fs::remove_file(partial).map_err(cannot)?;
                continue;
            }
            // A FIFO put there (without a reader: opening it would otherwise wait).
            Err(e) if e.raw_os_error() == Some(libc::ENXIO) => {
                std::fs::remove_file(partial).map_err(cannot)?;
                continue;
            }
            Err(e) => return Err(cannot(e)),
        };
        // Not a regular file of one name (a hard link put at the temporary name): not ours
        // to empty; the name is removed and a file of our own made.
        let opened = file.metadata().map_err(cannot)?;
        if !opened.is_file() || opened.nlink() > 1 {
            std::fs::remove_file(partial).map_err(cannot)?;
            continue;
        }
        match file.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(busy(&file, out, "writing"));
            }
            // A file system without locks (some network and FUSE ones): written unlocked,
            // as before locks were taken.
            Err(std::fs::TryLockError::Error(_)) => {
                file.set_len(0).map_err(cannot)?;
                return Ok(file);
            }
        }
        let locked = file.metadata().map_err(cannot)?;
        match std::fs::symlink_metadata(partial) {
            Ok(named) if named.dev() == locked.dev() && named.ino() == locked.ino() => {
                file.set_len(0).map_err(cannot)?;
                return Ok(file);
            }
            _ => {}
        }
    }
    Err(anyhow!(
        "cannot write output file {}: other runs keep replacing it",
        partial.display()
    ))
}

/// The lock of a folder that one run writes several files into (a study's `--out-dir`),
/// held until it is dropped.
#[derive(Debug)]
pub struct FolderLock {
    _folder: File,
}

impl FolderLock {
    /// Locks the existing folder `dir` for this process: exclusively, or `shared` with
    /// other processes that lock it shared too. Refused, naming the other run, while
    /// another process holds a lock that this one cannot share.
    pub fn acquire(dir: &Path, shared: bool) -> anyhow::Result<FolderLock> {
        let folder = File::open(dir)
            .map_err(|e| anyhow!("cannot open the folder {}: {e}", dir.display()))?;
        let locked = if shared {
            folder.try_lock_shared()
        } else {
            folder.try_lock()
        };
        match locked {
            // A file system without locks: the folder goes unlocked.
            Ok(()) | Err(std::fs::TryLockError::Error(_)) => Ok(FolderLock { _folder: folder }),
            Err(std::fs::TryLockError::WouldBlock) => Err(busy(&folder, dir, "writing into")),
        }
    }
}

/// The refusal of a run to `out`, whose `file` another process has locked: names that
/// process and its command line where the system says (Linux: `/proc/locks`).
fn busy(file: &File, out: &Path, doing: &str) -> anyhow::Error {
    let holder = file
        .metadata()
        .ok()
        .and_then(|m| holder_of(m.dev(), m.ino()));
    let who = match holder {
        Some((pid, Some(command))) => format!("process {pid}, `{command}`"),
        Some((pid, None)) => format!("process {pid}"),
        None => "another process".to_string(),
    };
    anyhow!(
        "another run is {doing} {} now ({who}): wait for it to end, or choose another path",
        out.display()
    )
}

/// The process holding a lock on the file `(dev, ino)`, and its command line, from
/// `/proc/locks` (lines such as `1: FLOCK  ADVISORY  WRITE 31571 fe:00:5334563 0 EOF`).
fn holder_of(dev: u64, ino: u64) -> Option<(u32, Option<String>)> {
    let major = ((dev >> 8) & 0xfff) | ((dev >> 32) & !0xfff);
    let minor = (dev & 0xff) | ((dev >> 12) & !0xff);
    let id = format!("{major:02x}:{minor:02x}:{ino}");
    let locks = std::fs::read_to_string("/proc/locks").ok()?;
    let pid = locks.lines().find_map(|line| {
        let words: Vec<&str> = line.split_whitespace().collect();
        // A lock that blocks another is listed as `1: -> FLOCK ...`: not the holder.
        (words.get(1) != Some(&"->") && words.get(5) == Some(&id.as_str()))
            .then(|| words.get(4)?.parse::<u32>().ok())
            .flatten()
    })?;
    let command = std::fs::read(format!("/proc/{pid}/cmdline"))
        .ok()
        .map(|bytes| {
            let words: Vec<String> = bytes
                .split(|b| *b == 0)
                .filter(|w| !w.is_empty())
                .map(|w| String::from_utf8_lossy(w).into_owned())
                .collect();
            let line = words.join(" ");
            match line.char_indices().nth(200) {
                Some((cut, _)) => format!("{}...", &line[..cut]),
                None => line,
            }
        })
        .filter(|c| !c.is_empty());
    Some((pid, command))
}
