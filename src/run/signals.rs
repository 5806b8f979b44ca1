//! Signals: how a run ends when asked to. Every command ends on SIGINT, SIGTERM or SIGHUP
//! without leaving an unfinished file behind (`end_on_signals`, set up by the command line
//! for every command); a run that can stop cleanly (a sweep, a study, an animation) asks
//! for the signal instead (`stop_on_signals`) and stops at its next step.

use super::workers::tell;
use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

/// Seconds between two SIGINTs for the second to count as a person pressing Ctrl-C again,
/// not one stop sent twice: a program signals a process and then its group within
/// microseconds (GNU `timeout`), while a person's second keypress takes a good tenth of a
/// second.
const SECOND_CTRL_C_S: f64 = 0.25;

/// The first signal that came (0: none yet).
static SIGNALLED: OnceLock<Arc<AtomicUsize>> = OnceLock::new();

/// Whether the running command stops cleanly on a signal (`stop_on_signals`).
static STOPS_CLEANLY: AtomicBool = AtomicBool::new(false);

/// Ends the process on SIGINT, SIGTERM or SIGHUP with exit code 128 + the signal, its
/// unfinished output files removed (`output::remove_unfinished_then`), unless the command has
/// asked to stop cleanly on them (`stop_on_signals`).
pub fn end_on_signals() -> anyhow::Result<()> {
    watch().map(|_| ())
}

/// The signal that asked the run to stop (0: none yet). SIGINT, SIGTERM and SIGHUP all stop
/// it the same way: no new samples, the rows done written to a valid file that `--resume`
/// continues. Further SIGTERMs and SIGHUPs change nothing (a scheduler or `timeout` may
/// send several); a second SIGINT at least `SECOND_CTRL_C_S` after the first (a person
/// pressing Ctrl-C again) ends the process at once, its unfinished file left under its
/// temporary name, so that nothing looks complete that is not.
pub fn stop_on_signals() -> anyhow::Result<Arc<AtomicUsize>> {
    STOPS_CLEANLY.store(true, Ordering::SeqCst);
    watch()
}

/// The flag of the first signal, watched by a thread of its own (started once).
fn watch() -> anyhow::Result<Arc<AtomicUsize>> {
    if let Some(flag) = SIGNALLED.get() {
        return Ok(flag.clone());
    }
    let flag = Arc::new(AtomicUsize::new(0));
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    let seen = flag.clone();
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            let mut first: Option<std::time::Instant> = None;
            for signal in signals.forever() {
                let now = std::time::Instant::now();
                if !STOPS_CLEANLY.load(Ordering::SeqCst) {
                    crate::output::remove_unfinished_then(|removed| {
                        tell(&format!(
                            "touchdown: interrupted by {}{}\n",
                            signal_name(signal as usize),
                            if removed > 0 {
                                ": its unfinished output removed"
                            } else {
                                ""
                            }
                        ));
                        std::process::exit(128 + signal)
                    });
                }
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
    Ok(SIGNALLED.get_or_init(|| flag).clone())
}

/// Whether `signal`, arriving at `now` when a first stop signal came at `first`, ends the
/// process at once: only a second SIGINT, at least `SECOND_CTRL_C_S` after the first.
fn ends_at_once(signal: i32, first: Option<std::time::Instant>, now: std::time::Instant) -> bool {
    first.is_some_and(|at| {
        signal == SIGINT && now.duration_since(at).as_secs_f64() >= SECOND_CTRL_C_S
    })
}

/// The name of `signal`, one of those that stop a run.
#[must_use]
pub fn signal_name(signal: usize) -> &'static str {
    match i32::try_from(signal) {
        Ok(SIGTERM) => "SIGTERM",
        Ok(SIGHUP) => "SIGHUP",
        Ok(SIGINT) => "SIGINT",
        _ => "a signal",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
