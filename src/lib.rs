//! touchdown: Monte Carlo touchdown simulation of legged landers on asteroids.
//!
//! The `touchdown` program is this library's `commands::main`. The library is public for
//! those who build on it: a program that embeds touchdown to run a control law of its own
//! (`control::register_law`, then `commands::main`, as `examples/user_law` does), and
//! the integration tests and benches, which drive the reference model, the kernels' set-up,
//! the scenario and the files directly. Every public item is documented (`missing_docs`);
//! what nothing outside its module needs is private.
//!
//! Layers, from the bottom; a module imports only from its layer and those below, never in
//! a circle (README "Layout"; `tests/layers.rs` checks it):
//!
//! - `kernels` (workspace member): the SIMD lanes and the hot code without I/O.
//! - Data model: `scenario` (the scenario file, a sample's values, a table of inputs as
//!   data), `dist` (distributions), `rng` (random streams), `qmc` (the Sobol sequence),
//!   `stability` (the static tipping limit).
//! - Physics: `reference` (the scalar physics of one lander), `control` (its control loop),
//!   `slope` (the slope a sample lands on), `terrain` (rough-terrain tiles).
//! - Monte Carlo engine: `sampling` (a sample index to inputs), `sweep` (samples through the
//!   kernels on worker threads, rows in order).
//! - Files: `output` (Arrow and Parquet written and read back), `table` (the user's tables
//!   of inputs read and checked).
//! - Statistics: `stats` (intervals and the allowable-slope rule), `report`, `weighting`,
//!   `sensitivity`, `compare`, `study` (its table), `boundary` (its rules), `envelope`
//!   (outcome shares over the plane of two columns).
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
pub mod envelope;
pub mod exceedance;
pub mod output;
pub mod plot;
pub mod qmc;
pub mod reference;
pub mod report;
pub mod rng;
pub mod rocks;
pub mod run;
pub mod sampling;
pub mod scenario;
pub mod scene;
pub mod sensitivity;
pub mod shape;
pub mod site;
pub mod slope;
pub mod stability;
pub mod stats;
pub mod study;
pub mod sweep;
pub mod table;
pub mod terrain;
pub mod view;
pub mod weighting;
