//! touchdown: Monte Carlo touchdown simulation of legged landers on asteroids.
//!
//! Layers, from the bottom; each imports only the layers below it:
//!
//! - `kernels` (workspace member): the SIMD lanes and the hot code without I/O.
//! - Data model: `scenario` reads and validates the inputs.
//! - Physics: `reference` is the scalar physics of one lander, `control` its control loop,
//!   `stability` the static tipping limit.
//! - Monte Carlo engine: `sampling` turns a sample index into inputs (with `qmc` and
//!   `terrain`), `table` gives the user's own inputs, `sweep` runs samples through the
//!   kernels on worker threads.
//! - `output`: Arrow and Parquet files written and read back.
//! - Statistics: `report`, `weighting`, `sensitivity`, `compare`, `study` (its table) and
//!   `boundary` (its rules).
//! - `run`: the sweep run (plans, workers, signals, progress, resume), a trace's run, a
//!   study's values, the boundary search.
//! - Pictures: `plot`, `scene`, `animate`, `view`.
//! - `commands`: the command line, one module per command; `main` calls
//!   `commands::main`.

pub mod animate;
pub mod boundary;
pub mod commands;
pub mod compare;
pub mod control;
pub mod dist;
pub mod output;
pub mod plot;
pub mod qmc;
pub mod reference;
pub mod report;
pub mod rng;
pub mod run;
pub mod sampling;
pub mod scenario;
pub mod scene;
pub mod sensitivity;
pub mod slope;
pub mod stability;
pub mod stats;
pub mod study;
pub mod sweep;
pub mod table;
pub mod terrain;
pub mod view;
pub mod weighting;
