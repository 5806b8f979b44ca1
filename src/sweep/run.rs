//! The sweep over a range: one worker per thread, a window of samples at a time, rows
//! handed to the sink in sample order, and the unbroken run kept when stopped.

use super::lanes::kernel_params;
use super::row::{LaneStats, Row};
use super::worker::{Feed, Padded, Worker};
use crate::reference::Model;
use crate::scenario::Scenario;
use kernels::isa::{Isa, Kernel, KernelKind, WithKernel};
use rayon::prelude::*;
use std::ops::Range;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ran {
    /// How busy the kernel's lanes were.
    pub stats: LaneStats,
    /// The first sample not handed to the sink: the end of the range, or where a stop left
    /// the rows (every sample before it was handed on, none after).
    pub end: u64,
}

/// Runs `range` on the current rayon pool with the widest kernel this CPU has, in the
/// scenario's precision (`simulation.precision`), one worker
/// (one block) per thread, handing rows to `sink` a window of `4 * chunk` samples per
/// thread at a time, in sample order. Stops early when `sink` returns an error.
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
///
/// The workers take samples one at a time from a shared counter. Once the samples of a
/// window run out, lanes go on to those of the next window while the last samples of this
/// one finish; their rows are kept for the next window. Memory holds two windows of rows
/// whatever the sample count.
pub fn run_until(
    scenario: &Scenario,
    model: &Model,
    isa: Isa,
    range: Range<u64>,
    chunk: u64,
    stop: &AtomicUsize,
    sink: impl FnMut(Vec<Row>) -> anyhow::Result<()>,
) -> anyhow::Result<Ran> {
    KernelKind {
        isa,
        precision: scenario.simulation.precision,
    }
    .dispatch(Sweep {
        scenario,
        model,
        range,
        chunk,
        stop,
        sink,
    })
}

/// The arguments of `run_until`, to run with the kernel `dispatch` picks.
struct Sweep<'a, F> {
    scenario: &'a Scenario,
    model: &'a Model,
    range: Range<u64>,
    chunk: u64,
    stop: &'a AtomicUsize,
    sink: F,
}

impl<F: FnMut(Vec<Row>) -> anyhow::Result<()>> WithKernel for Sweep<'_, F> {
    type Output = anyhow::Result<Ran>;

    fn run<K: Kernel>(self) -> anyhow::Result<Ran> {
        let Sweep {
            scenario,
            model,
            range,
            chunk,
            stop,
            mut sink,
        } = self;
        // Read by every thread at every step: never in a pair of cache lines with the
        // counters the threads write (see `Padded`).
        let params = Padded(kernel_params::<K>(model));
        let params = &params.0;
        let threads = rayon::current_num_threads();
        let window = chunk.max(1) * 4 * threads as u64;
        let per_sample = scenario.sampled.iter().any(Option::is_some);
        let mut workers: Vec<Worker<K>> = (0..threads)
            .map(|_| Worker::new(params, per_sample))
            .collect();
        let next = Padded(AtomicU64::new(range.start));
        let next = &next.0;
        let mut carried: Vec<Row> = Vec::new();
        let mut stats = LaneStats::default();
        let mut start = range.start;
        while start < range.end {
            let end = start.saturating_add(window).min(range.end);
            let done = carried.len() as u64;
            let outstanding = Padded(AtomicU64::new(end - start - done));
            let outstanding = &outstanding.0;
            let feed = Feed {
                stop,
                next,
                cap: end.saturating_add(window).min(range.end),
                window_end: end,
                outstanding,
            };
            let results: Vec<(Vec<Row>, LaneStats)> = if outstanding.load(Ordering::Relaxed) == 0 {
                Vec::new()
            } else {
                workers
                    .par_iter_mut()
                    .map(|w| w.run(scenario, model, params, &feed))
                    .collect()
            };
            let mut rows = std::mem::take(&mut carried);
            for (r, s) in results {
                stats = stats.add(s);
                for row in r {
                    if row.sample.index < end {
                        rows.push(row);
                    } else {
                        carried.push(row);
                    }
                }
            }
            rows.sort_unstable_by_key(|r| r.sample.index);
            if outstanding.load(Ordering::Relaxed) > 0 {
                // Stopped: keep the unbroken run from `start`, the rows of the next window too.
                rows.append(&mut carried);
                rows.sort_unstable_by_key(|r| r.sample.index);
                let unbroken = rows
                    .iter()
                    .zip(start..)
                    .take_while(|(r, i)| r.sample.index == *i)
                    .count();
                rows.truncate(unbroken);
                sink(rows)?;
                return Ok(Ran {
                    stats,
                    end: start + unbroken as u64,
                });
            }
            debug_assert_eq!(rows.len() as u64, end - start);
            sink(rows)?;
            start = end;
        }
        Ok(Ran {
            stats,
            end: range.end,
        })
    }
}
