//! `touchdown report`: a sweep file summarised as Markdown (or JSON), optionally weighed
//! to a terrain's slope distribution.

use super::print::print_out;
use crate::output::sweep::SweepSource;
use std::path::PathBuf;

/// Flags of `touchdown report`.
#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// The sweep file (Arrow IPC or Parquet).
    #[arg(value_name = "SWEEP")]
    pub sweep: PathBuf,
    /// The outcome shares on a terrain with this distribution of slopes, each sample
    /// weighed by its density over the sweep's: uniform:MIN:MAX, normal:MEAN:SD,
    /// rayleigh:SIGMA, exponential:MEAN (deg), or a CSV file of bins with the columns
    /// slope_min_deg, slope_max_deg, probability.
    #[arg(long, value_name = "D")]
    pub slope_distribution: Option<String>,
    /// The report as one JSON document (the same numbers, unrounded) instead of Markdown.
    #[arg(long)]
    pub json: bool,
}

/// Runs `touchdown report`.
pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    let terrain = args
        .slope_distribution
        .as_deref()
        .map(|d| crate::weighting::SlopeDistribution::parse(d).map(|t| (t, d)))
        .transpose()?;
    let terrain = terrain.as_ref().map(|(t, d)| (t, *d));
    let source = SweepSource::Path(args.sweep.clone());
    let report = if args.json {
        crate::report::report_json(&source, terrain)?
    } else {
        crate::report::report(&source, terrain)?
    };
    print_out("the report", &report)
}
