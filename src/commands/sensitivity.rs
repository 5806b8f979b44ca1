//! `touchdown sensitivity`: the Sobol indices of a `sobol-indices` sweep, as Markdown and
//! optionally a bar chart.

use super::flags::parse_count;
use super::print::print_out;
use std::path::PathBuf;

/// Flags of `touchdown sensitivity`.
#[derive(clap::Args, Debug)]
pub struct SensitivityArgs {
    /// A sweep or shard file (Arrow or Parquet) run with `design = "sobol-indices"`.
    pub sweep: PathBuf,
    /// Bootstrap replicates behind the 95 % intervals.
    #[arg(long, value_name = "B", default_value = "1000", value_parser = parse_count, allow_negative_numbers = true)]
    pub bootstrap: u64,
    /// Also draw the indices as a bar chart, to this PNG file.
    #[arg(long, value_name = "PATH")]
    pub png: Option<PathBuf>,
}

/// Runs `touchdown sensitivity`.
pub fn run(args: &SensitivityArgs) -> anyhow::Result<()> {
    let bootstrap = usize::try_from(args.bootstrap).unwrap_or(usize::MAX);
    if let Some(png) = &args.png {
        crate::output::check_output_path(png)?;
    }
    let analysis = crate::sensitivity::analyse(&args.sweep, bootstrap)?;
    if let Some(png) = &args.png {
        let title = format!(
            "Sobol indices of {} ({} base points)",
            args.sweep.display(),
            analysis.base_points
        );
        crate::plot::sensitivity_chart(png, &analysis, &title)?;
    }
    print_out(
        "the indices",
        &crate::sensitivity::markdown(&args.sweep, &analysis),
    )
}
