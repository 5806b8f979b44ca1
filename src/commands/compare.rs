//! `touchdown compare`: two sweeps of the same seed compared sample by sample.

use super::print::print_out;
use std::path::PathBuf;

/// Flags of `touchdown compare`.
#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// The first sweep file (A).
    #[arg(value_name = "A")]
    pub a: PathBuf,
    /// The second sweep file (B), of the same seed and samples.
    #[arg(value_name = "B")]
    pub b: PathBuf,
}

/// Runs `touchdown compare`.
pub fn run(args: &CompareArgs) -> anyhow::Result<()> {
    print_out(
        "the comparison",
        &crate::compare::compare(&args.a, &args.b)?,
    )
}
