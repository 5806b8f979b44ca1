//! What a run's workers share: the pool of threads, the size of their tasks, the signals
//! that stop them and how the stop is told.

use std::io::Write;
use std::path::Path;

/// Samples per task of the sweep's workers.
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

/// Seconds between two SIGINTs for the second to count as a person pressing Ctrl-C again,
/// not one stop sent twice: a program signals a process and then its group within
/// microseconds (GNU `timeout`), while a person's second keypress takes a good tenth of a
/// second.
const SECOND_CTRL_C_S: f64 = 0.25;

/// The signal that asked the run to stop (0: none yet). SIGINT, SIGTERM and SIGHUP all stop
/// it the same way: no new samples, the rows done written to a valid file that `--resume`
/// continues. Further SIGTERMs and SIGHUPs change nothing (a scheduler or `timeout` may
/// send several); a second SIGINT at least `SECOND_CTRL_C_S` after the first (a person
/// pressing Ctrl-C again) ends the process at once, its unfinished file left under its
/// temporary name, so that nothing looks complete that is not.
pub fn stop_on_signals() -> anyhow::Result<std::sync::Arc<std::sync::atomic::AtomicUsize>> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    use std::sync::Arc;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let which = Arc::new(AtomicUsize::new(0));
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    let seen = which.clone();
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            let mut first: Option<std::time::Instant> = None;
            for signal in signals.forever() {
                let now = std::time::Instant::now();
                if first.is_none() {
                    first = Some(now);
                    seen.store(signal as usize, Ordering::SeqCst);
                } else if ends_at_once(signal, first, now) {
                    tell(
                        "touchdown: stopped at once by a second Ctrl-C; the unfinished output \
                         keeps its temporary name\n",
                    );
                    std::process::exit(128 + SIGINT);
                }
            }
        })?;
    Ok(which)
}

/// Whether `signal`, arriving at `now` when a first stop signal came at `first`, ends the
/// process at once: only a second SIGINT, at least `SECOND_CTRL_C_S` after the first.
fn ends_at_once(signal: i32, first: Option<std::time::Instant>, now: std::time::Instant) -> bool {
    first.is_some_and(|at| {
        signal == signal_hook::consts::SIGINT
            && now.duration_since(at).as_secs_f64() >= SECOND_CTRL_C_S
    })
}

/// The name of `signal`, one of those that stop a run.
#[must_use]
pub fn signal_name(signal: usize) -> &'static str {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    match i32::try_from(signal) {
        Ok(SIGTERM) => "SIGTERM",
        Ok(SIGHUP) => "SIGHUP",
        Ok(SIGINT) => "SIGINT",
        _ => "a signal",
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    use std::time::{Duration, Instant};

    #[test]
    fn only_a_second_ctrl_c_by_hand_ends_at_once() {
        let t0 = Instant::now();
        let after = |ms: u64| t0 + Duration::from_millis(ms);
        // A first signal of any kind stops the run gracefully.
        for s in [SIGINT, SIGTERM, SIGHUP] {
            assert!(!ends_at_once(s, None, after(1000)));
        }
        // `timeout` signals the process, then its group, within microseconds.
        assert!(!ends_at_once(SIGINT, Some(t0), after(0)));
        assert!(!ends_at_once(SIGINT, Some(t0), after(200)));
        // A scheduler's or a closing terminal's repeated signals never end it at once.
        for ms in [0, 300, 60_000] {
            assert!(!ends_at_once(SIGTERM, Some(t0), after(ms)));
            assert!(!ends_at_once(SIGHUP, Some(t0), after(ms)));
        }
        // A person pressing Ctrl-C again.
        assert!(ends_at_once(SIGINT, Some(t0), after(250)));
        assert!(ends_at_once(SIGINT, Some(t0), after(3000)));
    }
}
