//! All integration tests, in one binary (one link instead of many).

mod agreement;
mod cli;
mod common;
mod interrupt;
mod report;
mod scenario_fuzz;
mod shards;
mod sweep_cli;
mod validation;
