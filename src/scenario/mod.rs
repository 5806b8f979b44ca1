//! The scenario: every parameter of MODEL.md and the distribution of every sampled input,
//! read from TOML and validated before any work starts; and the data a sample carries.
//!
//! Every key is optional; a missing key takes the default of MODEL.md. Each key is typed
//! once in Rust: the `table!` declaration of its table (`reader`) makes it a documented
//! field, reads it under the field's name and names its check. Its default is the commented
//! file `default.toml` beside this module, at the same path, which `touchdown scenario`
//! prints and `Scenario::default()` reads (as an empty file); the tables and keys it shows
//! only in comments (`[surface.rocks]`, `[surface.regolith]`, `[propulsion]`, `[control]`,
//! ...) give theirs in their declaration (`Reader::or`). `tests/scenario_keys.rs` checks
//! that the file shows every key the reader accepts, each commented-out one with the
//! default its declaration gives.
//!
//! From the ground up: `error`, the TOML walker `reader`, one module per table of the file
//! (`inputs`, `lander`, `surface`, ...), a `sample` and a `table` of inputs, the whole
//! `definition`, what it `draws` per sample, and `read`ing it. This file only names them.

mod control;
mod damper;
mod definition;
mod draws;
mod error;
mod initial;
mod inputs;
pub mod keys;
mod lander;
mod limits;
mod outcome;
mod read;
mod reader;
mod regolith;
mod rocks;
mod sample;
mod simulation;
mod surface;
mod table;
mod thrusters;

pub use control::{AttitudeHold, Control, Descent, HoldDown, Sensors, Target};
pub use damper::{Damper, PSI_PA, Stage, StrutAxes};
pub use definition::{Design, Scenario};
pub use draws::{
    design_inputs, design_position, grid_indices, grid_size, law_grid_size, value_dists,
};
pub use error::ScenarioError;
pub use initial::{AttitudeReference, Initial, Start};
pub use inputs::{
    Dist, FALL_INPUTS, FIRST_LAW_VALUE, FIRST_STATE_VALUE, INITIAL_FIELDS, INPUT_FIELDS, Inputs,
    LAW_PARAMETERS, PARAMETER_FIELDS, PARAMETERS, Parameter, STATE_VALUES, Sampled, VALUES,
    check_value, stream_name, value_key, value_name, value_unit,
};
pub use lander::{Geometry, Lander};
pub use limits::{Broken, LIMIT_NAMES, Limits, Loads};
pub use outcome::Outcome;
pub use read::{with_design, with_seed};
pub use reader::DEFAULT_TOML;
pub use regolith::Regolith;
pub use rocks::Rocks;
pub use sample::Sample;
pub use simulation::Simulation;
pub use surface::{Roughness, Surface, SurfaceKind};
pub use table::{InputTable, METADATA_KEYS, RowSource, TableRow};
pub use thrusters::{G0_M_S2, MAX_THRUSTERS, Propulsion, Thruster};
