//! All integration tests, in one binary (one link instead of many).

mod agreement;
mod animate;
mod boundary;
mod cli;
mod common;
mod cpus;
mod inputs;
mod interrupt;
mod lander;
mod outcome_rules;
mod outputs;
mod paired_sweeps;
mod parameters;
mod plot;
mod python_example;
mod report;
mod scenario_fuzz;
mod scenarios;
mod sensitivity;
mod shards;
mod study;
mod sweep_cli;
mod thrust;
mod user_law;
mod validation;
mod weighting;
