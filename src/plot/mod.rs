//! `touchdown plot`: PNG pictures of a sweep file (stability map, tipped share per slope,
//! load distributions) or of a trace file (CG and leg time histories, 3D path, the
//! instruments' shock). Pure Rust: `plotters` on a bitmap, with DejaVu Sans compiled in, so
//! no system fonts, no Python.

pub(crate) mod canvas;
mod envelope;
mod exceedance;
mod sensitivity;
pub mod site;
mod study;
mod sweep;
mod trace;

use crate::output::OutputSet;
use crate::output::read::{format_of, open};
use anyhow::{anyhow, bail};
use std::path::{Path, PathBuf};

pub(crate) use envelope::{envelope_chart, envelope_picture_size};
pub use sensitivity::sensitivity_chart;
pub(crate) use study::study_chart;

/// What draws the pictures of one kind of file, named by the function given.
type Draw = fn(&Path, &dyn Fn(&str) -> PathBuf) -> anyhow::Result<Vec<PathBuf>>;

/// Writes the pictures of the sweep or trace file at `path` into `out_dir` (default: the
/// file's folder), named after the file, as one set (`OutputSet`); returns their paths.
pub fn plot(path: &Path, out_dir: Option<&Path>) -> anyhow::Result<Vec<PathBuf>> {
    let stem = path
        .file_stem()
        .ok_or_else(|| anyhow!("{} names no file", path.display()))?
        .to_string_lossy()
        .into_owned();
    let dir = match out_dir {
        Some(d) => d.to_path_buf(),
        None => match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        },
    };
    let name = |what: &str| dir.join(format!("{stem}-{what}.png"));
    let format = format_of(path)?;
    let (schema, _) = open(path, format)?;
    let kind = schema.metadata().get("touchdown.kind").map(String::as_str);
    if !matches!(kind, Some("sweep" | "trace")) {
        bail!(
            "{} is neither a sweep nor a trace file of touchdown",
            path.display()
        );
    }
    // The folder is made (with its parents) once the file is known to be drawable.
    if dir.exists() && !dir.is_dir() {
        bail!("output folder {} is a file", dir.display());
    }
    std::fs::create_dir_all(&dir)
        .map_err(|e| anyhow!("cannot make output folder {}: {e}", dir.display()))?;
    // The pictures of one file are one set: reserved before they are drawn, moved into
    // place together once all are.
    let (pictures, draw): (&[&str], Draw) = match kind {
        Some("sweep") => (&sweep::PICTURES, sweep::plot),
        _ => (&trace::PICTURES, trace::plot),
    };
    let set = OutputSet::reserve(&pictures.iter().map(|p| name(p)).collect::<Vec<_>>())?;
    let written = draw(path, &name)?;
    set.commit()?;
    Ok(written)
}
