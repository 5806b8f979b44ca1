//! Runs many samples through the SIMD kernels: blocks of lanes, lane refill, per-lane
//! clocks, rayon over the cores, rows handed on in sample order.
//!
//! Every thread streams samples through one block: a lane whose sample is decided takes
//! the next sample index at once, from a counter shared by the threads. Rows are passed on
//! a window of consecutive indices at a time, in order, so memory holds about two windows
//! of rows whatever the sample count; blocks keep their lanes from one window to the next,
//! so the last (longest) samples of a window do not leave the block half empty.
//!
//! The folder: `shard` (a slice of the sample range), `row` (what a run hands on), `lanes`
//! (the kernels' parameters and a lane's state from the reference model, and back),
//! `worker` (one block and its step loop), `run` (the workers over the windows).

mod lanes;
mod row;
mod run;
mod shard;
mod worker;

pub use lanes::{kernel_params, lane_init, lane_thrust};
pub use row::{LaneStats, Row};
pub use run::{Ran, Stretches, pipeline, run, run_until};
pub use shard::Shard;
