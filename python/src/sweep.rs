//! `touchdown.sweep`'s run: the command line's sweep plan run on a thread of its own with
//! its batches kept, while Python waits in short slices (a progress bar moves, Ctrl-C is
//! heard), then handed to pyarrow through the Arrow C stream interface.

use crate::counts::{self, whole};
use crate::errors::{OrPy, TouchdownError, to_py};
use arrow_array::{RecordBatch, RecordBatchIterator, RecordBatchReader};
use arrow_pyarrow::IntoPyArrow;
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use touchdown::output::format::Format;
use touchdown::run::{
    Executed, KernelChoice, RunOptions, SweepPlan, SweepSettings, execute, worker_pool,
};
use touchdown::scenario::Design;

/// SIGINT's number: the stop a Ctrl-C makes, as the command line's.
const SIGINT: usize = 2;

/// A sweep running on a thread of its own (`touchdown.sweep` drives it).
///
/// Started by the constructor, which checks everything first (a bad value raises before
/// any sample runs). `wait(seconds)` waits at most that long with the GIL released and
/// says whether it is over; `done` counts the samples computed; `stop()` asks it to stop as
/// Ctrl-C stops the command line's; `result()` gives the sweep as a
/// `pyarrow.RecordBatchReader`, or raises what ended it (`KeyboardInterrupt` for a stop).
#[pyclass(module = "touchdown._touchdown")]
pub struct SweepRun {
    stop: Arc<AtomicUsize>,
    counter: Arc<AtomicU64>,
    total: u64,
    out: Option<PathBuf>,
    ended: Mutex<Ended>,
}

/// What the sweep's thread gave back, once it has.
enum Ended {
    Running(Receiver<anyhow::Result<(Executed, Vec<RecordBatch>)>>),
    Over(Option<anyhow::Result<(Executed, Vec<RecordBatch>)>>),
}

#[pymethods]
impl SweepRun {
    /// Plans the sweep as `touchdown sweep` would with these flags and starts it.
    #[new]
    #[pyo3(signature = (scenario_toml, samples=None, seed=None, threads=None, design=None, inputs=None, keep_columns=false, out=None, format=None, kernel=None, keep=true))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        scenario_toml: String,
        samples: Option<Bound<'_, PyAny>>,
        seed: Option<Bound<'_, PyAny>>,
        threads: Option<Bound<'_, PyAny>>,
        design: Option<&str>,
        inputs: Option<PathBuf>,
        keep_columns: bool,
        out: Option<PathBuf>,
        format: Option<&str>,
        kernel: Option<&str>,
        keep: bool,
    ) -> PyResult<SweepRun> {
        let samples = whole("samples", samples.as_ref(), counts::POSITIVE)?;
        let seed = whole("seed", seed.as_ref(), counts::INDEX)?;
        let threads = whole("threads", threads.as_ref(), counts::THREADS)?
            .map(|n| usize::try_from(n).expect("at most MAX_THREADS"));
        if !keep && out.is_none() {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "table=False keeps no rows: give out= the file to write them to",
            ));
        }
        let design = design
            .map(|d| match d {
                "independent" => Ok(Design::Independent),
                "sobol-sequence" => Ok(Design::SobolSequence),
                "sobol-indices" => Ok(Design::SobolIndices),
                other => Err(pyo3::exceptions::PyValueError::new_err(format!(
                    "design {other:?}: expected \"independent\", \"sobol-sequence\" or \"sobol-indices\""
                ))),
            })
            .transpose()?;
        let format = format
            .map(|f| match f {
                "arrow" => Ok(Format::Arrow),
                "parquet" => Ok(Format::Parquet),
                other => Err(pyo3::exceptions::PyValueError::new_err(format!(
                    "format {other:?}: expected \"arrow\" or \"parquet\""
                ))),
            })
            .transpose()?;
        let kernel = match kernel {
            None | Some("auto") => KernelChoice::Auto,
            Some(k) => KernelChoice::Isa(kernels::isa::Isa::from_key(k).ok_or_else(|| {
                let keys: Vec<&str> = kernels::isa::Isa::ALL.iter().map(|i| i.key()).collect();
                pyo3::exceptions::PyValueError::new_err(format!(
                    "{k:?} is not a kernel: auto, {}",
                    keys.join(", ")
                ))
            })?),
        };
        let settings = SweepSettings {
            scenario: None,
            scenario_toml: Some(scenario_toml),
            samples,
            seed,
            design,
            inputs,
            keep_columns,
            out: out.clone(),
            format,
            resume: None,
            shard: None,
            kernel,
        };
        let plan = SweepPlan::new(&settings).or_py()?;
        crate::law::clear();
        let pool = worker_pool(threads).or_py()?;
        let total = plan.samples;
        let stop = Arc::new(AtomicUsize::new(0));
        let counter = Arc::new(AtomicU64::new(0));
        let (tx, rx) = std::sync::mpsc::channel();
        let (thread_stop, thread_counter) = (stop.clone(), counter.clone());
        std::thread::Builder::new()
            .name("touchdown-sweep".to_string())
            .spawn(move || {
                let run = RunOptions {
                    pool: &pool,
                    stop: &thread_stop,
                    progress: false,
                    banner: false,
                    auto_kernel: matches!(kernel, KernelChoice::Auto),
                    keep,
                    counter: Some(&thread_counter),
                };
                let done = execute(&plan, &run).map(|mut e| {
                    let batches = std::mem::take(&mut e.batches);
                    (e, batches)
                });
                let _ = tx.send(done);
            })
            .map_err(|e| {
                TouchdownError::new_err(format!("cannot start the sweep's thread: {e}"))
            })?;
        Ok(SweepRun {
            stop,
            counter,
            total,
            out,
            ended: Mutex::new(Ended::Running(rx)),
        })
    }

    /// Waits at most `seconds` (GIL released); whether the sweep is over.
    fn wait(&self, py: Python<'_>, seconds: f64) -> bool {
        let mut ended = self
            .ended
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if crate::law::failed() {
            // A law of Python's raised: the rows from then on are not right; stop.
            self.stop();
        }
        let rx = match std::mem::replace(&mut *ended, Ended::Over(None)) {
            Ended::Running(rx) => rx,
            over => {
                *ended = over;
                return true;
            }
        };
        let wait = Duration::from_secs_f64(seconds.clamp(0.0, 3600.0));
        let (rx, got) = py.detach(move || {
            let got = rx.recv_timeout(wait);
            (rx, got)
        });
        match got {
            Ok(result) => *ended = Ended::Over(Some(result)),
            Err(RecvTimeoutError::Timeout) => {
                *ended = Ended::Running(rx);
                return false;
            }
            Err(RecvTimeoutError::Disconnected) => {
                *ended = Ended::Over(Some(Err(anyhow::anyhow!(
                    "the sweep's thread ended without a result"
                ))));
            }
        }
        true
    }

    /// Asks the sweep to stop (as Ctrl-C stops the command line's); `wait` until it has.
    fn stop(&self) {
        self.stop.store(SIGINT, Ordering::Relaxed);
    }

    /// Samples computed so far.
    #[getter]
    fn done(&self) -> u64 {
        self.counter.load(Ordering::Relaxed)
    }

    /// Samples the sweep runs.
    #[getter]
    fn total(&self) -> u64 {
        self.total
    }

    /// The file it writes, if any.
    #[getter]
    fn out(&self) -> Option<PathBuf> {
        self.out.clone()
    }

    /// The sweep as a `pyarrow.RecordBatchReader` (its schema with the file's metadata),
    /// once `wait` says it is over, or None for a sweep that kept no rows (`keep` false);
    /// raises what ended it otherwise.
    fn result<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let mut ended = self
            .ended
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let Ended::Over(result) = &mut *ended else {
            return Err(TouchdownError::new_err(
                "the sweep is still running: wait() first",
            ));
        };
        if let Some(e) = crate::law::take_error() {
            // The rows after the raise are not right: the file the stop left goes too.
            if let Some(out) = &self.out {
                let _ = std::fs::remove_file(touchdown::output::interrupted_path(out));
            }
            return Err(e);
        }
        let (_, batches) = result
            .take()
            .ok_or_else(|| TouchdownError::new_err("the sweep's result was taken already"))?
            .map_err(|e| to_py(&e))?;
        if batches.is_empty() {
            return Ok(None);
        }
        reader(batches)?.into_pyarrow(py).map(Some)
    }
}

/// `batches` as a reader for the C stream interface.
pub fn reader(batches: Vec<RecordBatch>) -> PyResult<Box<dyn RecordBatchReader + Send>> {
    let schema = batches
        .first()
        .map(RecordBatch::schema)
        .ok_or_else(|| TouchdownError::new_err("no rows"))?;
    Ok(Box::new(RecordBatchIterator::new(
        batches.into_iter().map(Ok),
        schema,
    )))
}
