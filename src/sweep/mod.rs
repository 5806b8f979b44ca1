//! Runs many samples through the SIMD kernels: blocks of lanes, lane refill, per-lane
//! clocks, rayon over the cores, rows handed on in sample order.
//!
//! Every worker thread streams samples through one block: a lane whose sample is decided
//! takes the next sample index at once, from a counter shared by the threads. A finished
//! sample's row goes into its stretch of consecutive indices; the worker that completes a
//! stretch builds it (for a sweep file, its record batch, encoded), and the calling thread
//! hands the built stretches on in order: the only serial part. Workers take samples at
//! most a stretch and a little past the first row not yet handed on, so memory holds about
//! two stretches whatever the sample count; no worker waits for another's slow sample.
//!
//! The folder: `shard` (a slice of the sample range), `row` (what a run hands on), `lanes`
//! (the kernels' parameters and a lane's state from the reference model, and back),
//! `worker` (one block and its step loop), `cohort` (a worker whose landers meet at their
//! control instants, for a law that gathers them: one call for hundreds), `run` (the
//! pipeline of workers and stretches).

mod cohort;
mod lanes;
mod row;
mod run;
mod shard;
mod worker;

pub use lanes::{kernel_params, lane_init, lane_thrust};
pub use row::{LaneStats, Row};
pub use run::{Ran, Stretches, pipeline, run, run_until};
pub use shard::Shard;
