//! `touchdown plot`: the PNG pictures of a sweep or trace file.

use super::print::print_out;
use std::path::PathBuf;

/// Flags of `touchdown plot`.
#[derive(clap::Args, Debug)]
pub struct PlotArgs {
    /// A sweep file (Arrow IPC or Parquet) or a trace file (Arrow IPC).
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// Folder to write the PNG files into (default: the file's folder; made if missing);
    /// they are named after the file, e.g. `sweep-stability-map.png`.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
}

/// Runs `touchdown plot`.
pub fn run(args: &PlotArgs) -> anyhow::Result<()> {
    for p in crate::plot::plot(&args.file, args.out_dir.as_deref())? {
        print_out("the list of pictures", &format!("wrote {}\n", p.display()))?;
    }
    Ok(())
}
