//! All integration tests, in one binary (one link instead of many).

mod agreement;
mod cli;
mod common;
mod sweep_cli;
mod validation;
