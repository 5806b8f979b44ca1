//! What a run's workers share: the pool of threads, the size of their tasks, the signals
//! that stop them and how the stop is told.

use std::path::Path;

/// Samples per task of the sweep's workers.
pub const CHUNK: u64 = 1024;

/// A sweep stopped by a signal; its rows so far are in a valid file beside the output.
#[derive(Debug)]
pub struct Interrupted {
    /// The exit code: 128 + the signal (130 for SIGINT, 143 for SIGTERM).
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

/// The signal that asked the sweep to stop (0: none yet). A first SIGINT or SIGTERM sets
/// it; a second one ends the process at once (the unfinished file keeps its temporary
/// name, so nothing looks complete that is not).
pub fn stop_on_signals() -> anyhow::Result<std::sync::Arc<std::sync::atomic::AtomicUsize>> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, AtomicUsize};
    let asked = Arc::new(AtomicBool::new(false));
    let which = Arc::new(AtomicUsize::new(0));
    for signal in [SIGINT, SIGTERM] {
        signal_hook::flag::register_conditional_shutdown(signal, 128 + signal, asked.clone())?;
        signal_hook::flag::register(signal, asked.clone())?;
        signal_hook::flag::register_usize(signal, which.clone(), signal as usize)?;
    }
    Ok(which)
}

/// The pool of `--threads` workers (default: one per core).
pub fn worker_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    let threads = threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, std::num::NonZero::get));
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
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
