//! `touchdown merge`: the shard files of one sweep joined into the file the sweep writes
//! in one process.

use super::flags::SweepOut;
use super::print::{say, shown};
use std::path::PathBuf;

/// Flags of `touchdown merge`.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The shard files, in any order (Arrow IPC or Parquet).
    #[arg(value_name = "SHARD", required = true)]
    pub shards: Vec<PathBuf>,
    /// Where the merged sweep file goes and its format (`--out`, `--format`).
    #[command(flatten)]
    pub output: SweepOut,
}

/// Runs `touchdown merge`.
pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    let out = &args.output.out;
    let format = crate::run::output_format(out, args.output.format)?;
    let m = crate::output::merge::merge(&args.shards, out, format)?;
    say(
        "the merge's summary",
        &format!(
            "merged {} shards, {} samples\nwrote {}\n",
            m.shards,
            m.rows,
            shown(out)
        ),
        out,
    )
}
