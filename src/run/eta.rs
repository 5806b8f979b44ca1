//! A run that will take more than a day says so on stderr, a terminal or not: a batch job's
//! log has no progress bar with its ETA, and `--samples 1e12` would otherwise start
//! silently on a year of work. It is told at once where even a rate no kernel reaches needs
//! more than a day, else from the rate measured over the run's first seconds; a run never
//! waits for the estimate.

use std::io::Write as _;
use std::time::Instant;

/// One day, s.
const DAY_S: f64 = 86_400.0;

/// Samples per second per thread that no run reaches: the default sweep runs about 31,000
/// per thread in f64 lanes and 56,000 in f32 (README "Performance"), and the shortest
/// flights a scenario allows a few times that; this bound is well above all of them, so
/// the warning at the start is never wrong.
const FASTEST_PER_THREAD: f64 = 1.0e6;

/// Seconds of running after which the rate measured so far estimates the rest: past the
/// workers' start-up, yet early in any run long enough to matter.
const MEASURE_S: f64 = 2.0;

/// The estimate of a run's time, told once if it exceeds a day.
pub(super) struct Eta {
    /// Samples the run computes.
    samples: u64,
    started: Instant,
    /// Whether the estimate is made (told or found short).
    decided: bool,
}

impl Eta {
    /// Starts the estimate of a run of `samples` samples on `threads` threads; tells at once
    /// where even `FASTEST_PER_THREAD` on every thread takes more than a day.
    pub(super) fn start(samples: u64, threads: usize) -> Eta {
        let mut eta = Eta {
            samples,
            started: Instant::now(),
            decided: false,
        };
        let fastest = FASTEST_PER_THREAD * threads.max(1) as f64;
        let least_s = samples as f64 / fastest;
        if least_s > DAY_S {
            eta.tell(&format!(
                "at least {}, even at {fastest:.0} samples/s (faster than any scenario runs \
                 on {threads} thread{})",
                duration(least_s),
                if threads == 1 { "" } else { "s" }
            ));
        }
        eta
    }

    /// Takes the count of samples `done` so far; once the run has measured its rate for
    /// `MEASURE_S`, tells if the samples left take more than a day at that rate.
    pub(super) fn done(&mut self, done: u64) {
        if self.decided || done == 0 {
            return;
        }
        let elapsed = self.started.elapsed().as_secs_f64();
        if elapsed < MEASURE_S {
            return;
        }
        let rate = done as f64 / elapsed;
        let left_s = self.samples.saturating_sub(done) as f64 / rate;
        self.decided = true;
        if left_s > DAY_S {
            self.tell(&format!(
                "about {} more, at the {rate:.0} samples/s of its first {elapsed:.0} s",
                duration(left_s)
            ));
        }
    }

    /// Tells that the run takes `how_long`.
    fn tell(&mut self, how_long: &str) {
        self.decided = true;
        // Not `eprintln!`, which panics where stderr is gone.
        let _ = writeln!(
            std::io::stderr(),
            "touchdown: warning: this run of {} samples takes more than a day: {how_long}; \
             fewer samples (--samples), or Ctrl-C to stop it with the rows done kept",
            self.samples
        );
    }
}

/// A duration for people: seconds, minutes, hours, days, weeks or years.
pub(super) fn duration(s: f64) -> String {
    let days = s / DAY_S;
    if s < 120.0 {
        format!("{s:.0} s")
    } else if s < 7200.0 {
        format!("{:.0} min", s / 60.0)
    } else if days < 1.0 {
        format!("{:.1} h", s / 3600.0)
    } else if days < 14.0 {
        format!("{days:.1} days")
    } else if days < 2.0 * 365.25 {
        format!("{:.0} weeks", days / 7.0)
    } else {
        format!("{:.0} years", days / 365.25)
    }
}

#[cfg(test)]
mod tests {
    use super::duration;

    #[test]
    fn durations_read_in_days_weeks_or_years() {
        assert_eq!(duration(40.0), "40 s");
        assert_eq!(duration(600.0), "10 min");
        assert_eq!(duration(3.5 * 3600.0), "3.5 h");
        assert_eq!(duration(1.5 * 86_400.0), "1.5 days");
        assert_eq!(duration(364.0 * 86_400.0), "52 weeks");
        assert_eq!(duration(3.0 * 365.25 * 86_400.0), "3 years");
    }
}
