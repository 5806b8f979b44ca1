//! `touchdown view`: a trace file as one self-contained HTML page.

use super::flags::beside;
use super::print::{say, shown, tell};
use std::path::PathBuf;

/// Flags of `touchdown view`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// A trace file (`touchdown trace` writes one).
    pub trace: PathBuf,
    /// HTML file to write (default: the trace's name with .html).
    #[arg(long, value_name = "PATH")]
    pub out: Option<PathBuf>,
}

/// Runs `touchdown view`.
pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    let out = beside(&args.trace, args.out.as_ref(), "html");
    let w = crate::view::view(&args.trace, &out)?;
    if let Some(note) = crate::scene::sparse_note(&args.trace, w.every) {
        tell(&format!("{note}\n"));
    }
    say(
        "the page's summary",
        &format!(
            "{} times of {} rows\nwrote {}: {:.2} MB\n",
            w.times,
            w.rows,
            shown(&out),
            w.bytes as f64 / 1e6
        ),
        &out,
    )
}
