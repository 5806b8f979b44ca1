//! What a run's workers share: the pool of threads, the size of their tasks, the signals
//! that stop them and how the stop is told.

use std::io::Write;
use std::path::Path;

/// Samples a thread of the rows `sweep::run_until` hands on at a time (four times this).
pub const CHUNK: u64 = 1024;

/// A sweep stopped by a signal; its rows so far are in a valid file beside the output.
#[derive(Debug)]
pub struct Interrupted {
    /// The exit code: 128 + the signal (130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP).
    pub code: u8,
    /// What stopped the sweep, where its rows are and how to continue it.
    pub message: String,
}

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Interrupted {}

/// The pool of `--threads` workers (default: one per core).
pub fn worker_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    let threads = threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, std::num::NonZero::get));
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
}

/// Writes `text` to stderr. A failure is not reported (there is nowhere left to report it)
/// and never panics, as `eprint!` does (where stderr is gone: a closed terminal after
/// SIGHUP).
pub fn tell(text: &str) {
    let _ = std::io::stderr().lock().write_all(text.as_bytes());
}

/// An output path as messages name it (`-` is standard output).
#[must_use]
pub fn shown(out: &Path) -> String {
    if out.as_os_str() == "-" {
        "standard output".to_string()
    } else {
        out.display().to_string()
    }
}
