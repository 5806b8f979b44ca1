//! `touchdown envelope`: the touchdown envelope of a sweep file, as a picture, a CSV
//! table of cells and a Markdown summary of the boundary.

use super::print::print_out;
use crate::envelope::{DEFAULT_X, DEFAULT_Y, Settings};
use anyhow::anyhow;
use std::path::{Path, PathBuf};

/// Flags of `touchdown envelope`.
#[derive(clap::Args, Debug)]
pub struct EnvelopeArgs {
    /// The sweep file (Arrow IPC or Parquet).
    #[arg(value_name = "SWEEP")]
    pub sweep: PathBuf,
    /// The column along x (any numeric column of the sweep).
    #[arg(long, value_name = "COL", default_value = DEFAULT_X)]
    pub x: String,
    /// The column along y (any numeric column of the sweep).
    #[arg(long, value_name = "COL", default_value = DEFAULT_Y)]
    pub y: String,
    /// Cells along x and along y, over the data's range.
    #[arg(long, value_name = "NX,NY", default_value = "12,10", value_parser = parse_bins)]
    pub bins: (usize, usize),
    /// The edges of the slope bands, one panel per band, deg (default: three round bands
    /// over the sweep's slopes; one panel on a fixed slope).
    #[arg(long, value_name = "EDGES", value_parser = parse_bands, allow_negative_numbers = true)]
    pub slope_bands: Option<Bands>,
    /// Panels per facing too: a leg downhill (the downhill direction relative to the
    /// lander within half a leg sector of a leg) and a side downhill.
    #[arg(long)]
    pub azimuth: bool,
    /// Folder to write the picture and the table into (default: the sweep's folder; made
    /// if missing); named after the sweep, e.g. `sweep-envelope.png`, `sweep-envelope.csv`.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
}

/// The edges of `--slope-bands`, deg.
#[derive(Debug, Clone)]
pub struct Bands(pub Vec<f64>);

/// Parses `--bins NX,NY`.
fn parse_bins(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("{s:?} is not two whole numbers NX,NY of at least 1 (e.g. 12,10)");
    let (a, b) = s.split_once(',').ok_or_else(bad)?;
    let n = |t: &str| t.trim().parse::<usize>().ok().filter(|n| *n >= 1);
    let (nx, ny) = (n(a).ok_or_else(bad)?, n(b).ok_or_else(bad)?);
    if nx * ny > 1_000_000 {
        return Err(format!("{s:?}: at most 1,000,000 cells"));
    }
    Ok((nx, ny))
}

/// Parses `--slope-bands A,B,...` (its edges are checked against each other later).
fn parse_bands(s: &str) -> Result<Bands, String> {
    s.split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("{t:?} is not a slope in deg (e.g. 0,10,20,30)"))
        })
        .collect::<Result<Vec<f64>, String>>()
        .map(Bands)
}

/// Runs `touchdown envelope`.
pub fn run(args: &EnvelopeArgs) -> anyhow::Result<()> {
    let settings = Settings {
        x: args.x.clone(),
        y: args.y.clone(),
        bins: args.bins,
        slope_bands: args.slope_bands.as_ref().map(|b| b.0.clone()),
        azimuth: args.azimuth,
    };
    let e = crate::envelope::envelope(&args.sweep, &settings)?;
    let dir = out_dir(&args.sweep, args.out_dir.as_deref())?;
    let stem = args
        .sweep
        .file_stem()
        .ok_or_else(|| anyhow!("{} names no file", args.sweep.display()))?
        .to_string_lossy()
        .into_owned();
    let (png, csv) = (
        dir.join(format!("{stem}-envelope.png")),
        dir.join(format!("{stem}-envelope.csv")),
    );
    crate::output::write_text(&csv, &crate::envelope::csv(&e))?;
    crate::plot::envelope_chart(&png, &e)?;
    print_out(
        "the envelope",
        &format!(
            "{}\nwrote {} and {}\n",
            crate::envelope::markdown(&e),
            png.display(),
            csv.display()
        ),
    )
}

/// The output folder (default: the sweep's), made with its parents if missing.
fn out_dir(sweep: &Path, given: Option<&Path>) -> anyhow::Result<PathBuf> {
    let dir = match given {
        Some(d) => d.to_path_buf(),
        None => match sweep.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        },
    };
    if dir.exists() && !dir.is_dir() {
        anyhow::bail!("--out-dir {}: a file, not a folder", dir.display());
    }
    std::fs::create_dir_all(&dir)
        .map_err(|e| anyhow!("cannot make output folder {}: {e}", dir.display()))?;
    Ok(dir)
}
