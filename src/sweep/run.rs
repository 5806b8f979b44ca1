//! The sweep over a range as a pipeline: one worker per thread steps its block and drops
//! each finished sample's row into the stretch of consecutive samples it belongs to; the
//! worker that finishes a stretch builds what the caller makes of its rows (a record batch,
//! encoded); the calling thread only hands the built stretches on in sample order. No
//! worker waits for the caller unless it has run a set distance ahead of it.

use super::cohort::Cohort;
use super::lanes::kernel_params;
use super::row::{LaneStats, Row};
use super::worker::{Feed, Padded, Worker};
use crate::reference::Model;
use crate::scenario::Scenario;
use kernels::isa::{Isa, Kernel, KernelKind, WithKernel};
use std::any::Any;
use std::collections::BTreeMap;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::sync::{Condvar, Mutex};

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ran {
    /// How busy the kernel's lanes were.
    pub stats: LaneStats,
    /// The first sample not handed to the sink: the end of the range, or where a stop left
    /// the rows (every sample before it was handed on, none after).
    pub end: u64,
    /// CPU time of the whole process during the run, s.
    pub cpu_s: f64,
    /// CPU time of the calling thread during the run, s: it hands the built stretches to
    /// the sink one after another (the run's serial part).
    pub serial_cpu_s: f64,
}

impl Ran {
    /// The serial part's share of the run's CPU time.
    #[must_use]
    pub fn serial_share(&self) -> f64 {
        if self.cpu_s > 0.0 {
            (self.serial_cpu_s / self.cpu_s).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
}

/// CPU time, s, of `clock` (`libc::CLOCK_PROCESS_CPUTIME_ID` or
/// `libc::CLOCK_THREAD_CPUTIME_ID`); 0 where the system does not tell it.
fn cpu_s(clock: libc::clockid_t) -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to write.
    if unsafe { libc::clock_gettime(clock, &raw mut t) } != 0 {
        return 0.0;
    }
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// How a range is cut into stretches of consecutive samples: the first `first` samples,
/// then `len` at a time (the last stretch ends with the range).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stretches {
    /// Samples of the first stretch (at least 1).
    pub first: u64,
    /// Samples of every later stretch (at least 1).
    pub len: u64,
}

impl Stretches {
    /// Stretches of `len` samples from the start.
    #[must_use]
    pub fn even(len: u64) -> Stretches {
        Stretches {
            first: len.max(1),
            len: len.max(1),
        }
    }

    /// The stretch of the sample `offset` samples into the range: its number and the
    /// offset of its first sample.
    fn of(&self, offset: u64) -> (u64, u64) {
        if offset < self.first {
            (0, 0)
        } else {
            let k = (offset - self.first) / self.len;
            (k + 1, self.first + k * self.len)
        }
    }

    /// The offset of the first sample of stretch `k`, and its length in a range of `n`
    /// samples.
    fn span(&self, k: u64, n: u64) -> (u64, u64) {
        let start = if k == 0 {
            0
        } else {
            self.first + (k - 1) * self.len
        };
        let len = if k == 0 { self.first } else { self.len };
        (start.min(n), len.min(n.saturating_sub(start)))
    }
}

/// Runs `range` on the current rayon pool's number of threads with the widest kernel this
/// CPU has, in the scenario's precision (`simulation.precision`), handing rows to `sink` in
/// sample order, `4 * chunk` samples per thread at a time. Stops early when `sink` returns
/// an error.
pub fn run(
    scenario: &Scenario,
    model: &Model,
    range: Range<u64>,
    chunk: u64,
    sink: impl FnMut(Vec<Row>) -> anyhow::Result<()>,
) -> anyhow::Result<LaneStats> {
    let never = AtomicUsize::new(0);
    Ok(run_until(scenario, model, Isa::detect(), range, chunk, &never, sink)?.stats)
}

/// `run` with the kernel of `isa` (which this CPU must have), until `stop` becomes nonzero:
/// then no lane takes another sample, the samples in the lanes finish, and the rows of the
/// unbroken run of samples from the start of the range go to `sink` (a later sample whose
/// predecessors did not all finish is dropped).
pub fn run_until(
    scenario: &Scenario,
    model: &Model,
    isa: Isa,
    range: Range<u64>,
    chunk: u64,
    stop: &AtomicUsize,
    sink: impl FnMut(Vec<Row>) -> anyhow::Result<()>,
) -> anyhow::Result<Ran> {
    let window = chunk.max(1) * 4 * rayon::current_num_threads() as u64;
    pipeline(
        scenario,
        model,
        isa,
        range,
        Stretches::even(window),
        stop,
        &Ok,
        sink,
    )
}

/// The sweep of `range` as a pipeline, on as many worker threads as the current rayon
/// pool has, with the kernel of `isa` (which this CPU must have), until `stop` becomes
/// nonzero. The rows of each stretch of `stretches` go, in sample order, to `build`, on
/// the worker that finished the stretch's last sample; what it builds goes to `sink`, on
/// the calling thread, stretch by stretch in sample order. The workers take samples at
/// most a stretch and 2048 samples a thread past the first sample not yet sunk, so memory
/// holds about two stretches whatever the sample count.
///
/// When stopped, the samples in the lanes finish and the unbroken run of rows from the
/// start goes on (the last stretch cut short); an error of `build` or `sink` stops the
/// workers at once and is returned.
///
/// Only this shim is generic: it boxes what `build` makes, and the pipeline with its
/// workers and kernels is compiled once, in this crate, whatever `T` and `sink` a caller
/// brings (a test, a bench or an example calling it compiles no kernel again).
#[allow(clippy::too_many_arguments)]
pub fn pipeline<T: Send + 'static>(
    scenario: &Scenario,
    model: &Model,
    isa: Isa,
    range: Range<u64>,
    stretches: Stretches,
    stop: &AtomicUsize,
    build: &(dyn Fn(Vec<Row>) -> anyhow::Result<T> + Sync),
    mut sink: impl FnMut(T) -> anyhow::Result<()>,
) -> anyhow::Result<Ran> {
    let build = |rows: Vec<Row>| -> anyhow::Result<Built> { Ok(Box::new(build(rows)?)) };
    let mut sink = |built: Built| match built.downcast::<T>() {
        Ok(t) => sink(*t),
        Err(_) => unreachable!("every stretch is built by `build`, as a T"),
    };
    pipeline_built(
        scenario, model, isa, range, stretches, stop, &build, &mut sink,
    )
}

/// What `build` made of a stretch, as the pipeline hands it on.
type Built = Box<dyn Any + Send>;

/// `pipeline` with what is built boxed (see there).
#[allow(clippy::too_many_arguments)]
fn pipeline_built(
    scenario: &Scenario,
    model: &Model,
    isa: Isa,
    range: Range<u64>,
    stretches: Stretches,
    stop: &AtomicUsize,
    build: &(dyn Fn(Vec<Row>) -> anyhow::Result<Built> + Sync),
    sink: &mut dyn FnMut(Built) -> anyhow::Result<()>,
) -> anyhow::Result<Ran> {
    KernelKind {
        isa,
        precision: scenario.simulation.precision,
    }
    .dispatch(Pipeline {
        scenario,
        model,
        range,
        stretches,
        stop,
        build,
        sink,
    })
}

/// The arguments of `pipeline_built`, to run with the kernel `dispatch` picks.
struct Pipeline<'a> {
    scenario: &'a Scenario,
    model: &'a Model,
    range: Range<u64>,
    stretches: Stretches,
    stop: &'a AtomicUsize,
    build: &'a (dyn Fn(Vec<Row>) -> anyhow::Result<Built> + Sync),
    sink: &'a mut dyn FnMut(Built) -> anyhow::Result<()>,
}

/// What the workers share besides the feed: where rows go.
struct Stretching<'a> {
    range: Range<u64>,
    stretches: Stretches,
    build: &'a (dyn Fn(Vec<Row>) -> anyhow::Result<Built> + Sync),
    /// The rows of the stretches not yet complete, by stretch number.
    open: Mutex<BTreeMap<u64, Vec<Row>>>,
    /// Set on an error: the workers drop their lanes and return.
    failed: &'a AtomicBool,
}

impl Stretching<'_> {
    /// Files `row` under its stretch; when that completes the stretch, builds it and sends
    /// it on.
    fn deliver(&self, row: Row, send: &mpsc::Sender<(u64, anyhow::Result<Built>)>) {
        let n = self.range.end - self.range.start;
        let (k, start) = self.stretches.of(row.sample.index - self.range.start);
        let len = self.stretches.span(k, n).1 as usize;
        let complete = {
            let mut open = self.open.lock().expect("no worker panics holding it");
            let rows = open.entry(k).or_insert_with(|| Vec::with_capacity(len));
            rows.push(row);
            if rows.len() == len {
                open.remove(&k)
            } else {
                None
            }
        };
        if let Some(mut rows) = complete {
            rows.sort_unstable_by_key(|r| r.sample.index);
            debug_assert_eq!(rows[0].sample.index, self.range.start + start);
            let built = (self.build)(rows);
            if built.is_err() {
                self.failed.store(true, Ordering::Relaxed);
            }
            // The receiver outlives every worker.
            let _ = send.send((k, built));
        }
    }
}

impl WithKernel for Pipeline<'_> {
    type Output = anyhow::Result<Ran>;

    fn run<K: Kernel>(self) -> anyhow::Result<Ran> {
        let Pipeline {
            scenario,
            model,
            range,
            stretches,
            stop,
            build,
            sink,
        } = self;
        // Read by every thread at every step: never in a pair of cache lines with the
        // counters the threads write (see `Padded`).
        let params = Padded(kernel_params::<K>(model));
        let params = &params.0;
        let threads = rayon::current_num_threads().max(1);
        let per_sample = scenario.sampled.iter().any(Option::is_some);
        let n = range.end - range.start;
        // How far past the first sample not yet sunk the workers may take samples: the
        // stretch being sunk and the next, and 2048 samples a thread besides, so that the
        // workers go on while a stretch waits for its slowest sample or is being sunk.
        let ahead = stretches.first.max(stretches.len) + 2048 * threads as u64;
        let failed = AtomicBool::new(false);
        let stretching = Stretching {
            range: range.clone(),
            stretches,
            build,
            open: Mutex::new(BTreeMap::new()),
            failed: &failed,
        };
        let next = Padded(AtomicU64::new(range.start));
        let cap = Padded(AtomicU64::new(
            range.start.saturating_add(ahead).min(range.end),
        ));
        let sunk_at = Mutex::new(0u64);
        let moved = Condvar::new();
        let feed = Feed {
            stop,
            failed: &failed,
            next: &next.0,
            cap: &cap.0,
            end: range.end,
            sunk: &sunk_at,
            moved: &moved,
        };
        let (cpu_0, serial_0) = (
            cpu_s(libc::CLOCK_PROCESS_CPUTIME_ID),
            cpu_s(libc::CLOCK_THREAD_CPUTIME_ID),
        );
        let mut stats = LaneStats::default();
        let mut sunk = 0u64; // offset of the first sample not yet sunk
        let mut expected = 0u64; // the stretch to sink next
        let mut failure: Option<anyhow::Error> = None;
        std::thread::scope(|scope| {
            let (send, receive) = mpsc::channel();
            let workers: Vec<_> = (0..threads)
                .map(|_| {
                    let (stretching, feed, send) = (&stretching, &feed, send.clone());
                    scope.spawn(move || {
                        let deliver = |row| stretching.deliver(row, &send);
                        // A law that gathers the landers: they meet at its instants.
                        let gathered = model
                            .control
                            .as_ref()
                            .and_then(|m| m.law.as_ref())
                            .is_some_and(|l| l.law.gathered());
                        if gathered {
                            Cohort::<K>::new(params, per_sample)
                                .run(scenario, model, params, feed, deliver)
                        } else {
                            Worker::<K>::new(params, per_sample)
                                .run(scenario, model, params, feed, deliver)
                        }
                    })
                })
                .collect();
            drop(send);
            // Built stretches in sample order, until every worker has returned.
            let mut waiting = BTreeMap::new();
            for (k, built) in receive {
                if failure.is_some() {
                    continue;
                }
                match built {
                    Ok(t) => {
                        waiting.insert(k, t);
                    }
                    Err(e) => failure = Some(e),
                }
                while failure.is_none()
                    && let Some(t) = waiting.remove(&expected)
                {
                    match sink(t) {
                        Ok(()) => {
                            let (start, len) = stretches.span(expected, n);
                            expected += 1;
                            sunk = start + len;
                            let mut at = sunk_at.lock().expect("no worker panics holding it");
                            *at = sunk;
                            let until = range.start.saturating_add(sunk + ahead);
                            cap.0.store(until.min(range.end), Ordering::Relaxed);
                            drop(at);
                            moved.notify_all();
                        }
                        Err(e) => failure = Some(e),
                    }
                }
                if failure.is_some() {
                    failed.store(true, Ordering::Relaxed);
                    moved.notify_all();
                }
            }
            for w in workers {
                stats = stats.add(w.join().expect("a sweep worker panicked"));
            }
        });
        if let Some(e) = failure {
            return Err(e);
        }
        if sunk < n {
            // Stopped: the unbroken run of the stretch the sink waits for, cut short.
            let mut open = stretching
                .open
                .into_inner()
                .expect("the workers have returned");
            let mut rows = open.remove(&expected).unwrap_or_default();
            rows.sort_unstable_by_key(|r| r.sample.index);
            let from = range.start + sunk;
            let unbroken = rows
                .iter()
                .zip(from..)
                .take_while(|(r, i)| r.sample.index == *i)
                .count();
            rows.truncate(unbroken);
            if unbroken > 0 {
                sink(build(rows)?)?;
            }
            return Ok(Ran {
                stats,
                end: from + unbroken as u64,
                cpu_s: cpu_s(libc::CLOCK_PROCESS_CPUTIME_ID) - cpu_0,
                serial_cpu_s: cpu_s(libc::CLOCK_THREAD_CPUTIME_ID) - serial_0,
            });
        }
        Ok(Ran {
            stats,
            end: range.end,
            cpu_s: cpu_s(libc::CLOCK_PROCESS_CPUTIME_ID) - cpu_0,
            serial_cpu_s: cpu_s(libc::CLOCK_THREAD_CPUTIME_ID) - serial_0,
        })
    }
}
