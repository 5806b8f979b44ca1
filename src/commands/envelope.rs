//! `touchdown envelope`: the touchdown envelope of a sweep file, as a picture, a CSV
//! table of cells and a Markdown summary of the boundary.

use super::print::print_out;
use crate::envelope::{DEFAULT_X, DEFAULT_Y, Settings};
use crate::output::OutputSet;
use anyhow::{anyhow, bail};
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
    if nx.saturating_mul(ny) > MAX_CELLS {
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

/// The most cells an envelope holds, all its panels together.
const MAX_CELLS: usize = 1_000_000;

/// The largest picture, pixels (three bytes each): about 250 panels.
const MAX_PIXELS: u64 = 50_000_000;

/// Bytes held per sample read (x, y and slope, outcome, facing, a limit broken: 27) and
/// per sample in its row of cells for the boundary (16).
const SAMPLE_BYTES: u64 = 27 + 16;

/// Bytes held per cell: its counts.
const CELL_BYTES: u64 = std::mem::size_of::<crate::envelope::Cell>() as u64;

/// Bytes held per row of cells: its samples' list and its boundary.
const ROW_BYTES: u64 = 24 + std::mem::size_of::<crate::envelope::Row>() as u64;

/// Refuses an envelope whose `panels` (with `args.bins` cells each) hold more cells than
/// `MAX_CELLS` all together, draw a picture larger than `MAX_PIXELS`, or would hold, with
/// the `samples` read, more memory than the machine has: before any of it is allocated,
/// naming the flags and the size.
fn fits(args: &EnvelopeArgs, panels: usize, samples: Option<u64>) -> anyhow::Result<()> {
    let (nx, ny) = args.bins;
    let asked = || {
        let bands = args
            .slope_bands
            .as_ref()
            .map_or("the default slope bands".to_string(), |b| {
                format!("--slope-bands of {} bands", b.0.len() - 1)
            });
        let azimuth = if args.azimuth { " and --azimuth" } else { "" };
        format!("--bins {nx},{ny} with {bands}{azimuth}: {panels} panels of {nx} x {ny} cells")
    };
    let cells = (nx as u64)
        .saturating_mul(ny as u64)
        .saturating_mul(panels as u64);
    let facings = if args.azimuth { 2 } else { 1 };
    let (width, height) = crate::plot::envelope_picture_size(panels / facings, facings);
    let pixels = width.saturating_mul(height);
    let bytes = cells
        .saturating_mul(CELL_BYTES)
        .saturating_add(
            (ny as u64)
                .saturating_mul(panels as u64)
                .saturating_mul(ROW_BYTES),
        )
        .saturating_add(samples.unwrap_or(0).saturating_mul(SAMPLE_BYTES))
        .saturating_add(pixels.saturating_mul(3));
    if cells > MAX_CELLS as u64 {
        bail!(
            "{}, {cells} cells in all (about {} of memory): at most 1,000,000 cells in all \
             panels together; ask for fewer bins or bands",
            asked(),
            crate::run::memory::shown_bytes(bytes)
        );
    }
    if pixels > MAX_PIXELS {
        bail!(
            "{}: a picture of {width} x {height} pixels ({} of memory), more than the \
             {MAX_PIXELS} pixels a picture may have; ask for fewer bands",
            asked(),
            crate::run::memory::shown_bytes(pixels.saturating_mul(3))
        );
    }
    crate::run::memory::check_fits(bytes, || {
        format!(
            "{}, with the {} samples of {}, read and drawn,",
            asked(),
            samples.map_or("?".to_string(), |n| n.to_string()),
            args.sweep.display()
        )
    })
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
    let checked = crate::envelope::check(&args.sweep, &settings)?;
    let samples = checked.samples_asked();
    // The default bands are the data's (one to three): their panels are checked once it
    // is read, the fewest meanwhile.
    fits(args, checked.panels().unwrap_or(checked.facings()), samples)?;
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
    // The picture and the table are one set, reserved before the samples are read.
    let set = OutputSet::reserve(&[csv.clone(), png.clone()])?;
    let e = checked.build(|panels| fits(args, panels, samples))?;
    crate::output::write_with(&csv, |out| crate::envelope::write_csv(&e, out))?;
    crate::plot::envelope_chart(&png, &e)?;
    set.commit()?;
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
