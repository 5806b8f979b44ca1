//! `touchdown scenario`: the default scenario, as a commented TOML file to edit.

use super::print::print_out;
use crate::scenario::DEFAULT_TOML;

/// Prints the default scenario.
pub fn run() -> anyhow::Result<()> {
    print_out("the scenario", DEFAULT_TOML)
}
