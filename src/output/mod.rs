//! Arrow files: fields that carry their units, provenance in the schema metadata, and
//! files that appear under their name only when complete.

pub mod trace;

use arrow_schema::{DataType, Field};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The engine and version that write a file, as stored in its schema metadata.
pub const ENGINE: &str = concat!("touchdown ", env!("CARGO_PKG_VERSION"));

/// A field with its unit (`"1"` for dimensionless) and a description in its metadata.
#[must_use]
pub fn field(name: &str, data_type: DataType, unit: &str, description: &str) -> Field {
    Field::new(name, data_type, false).with_metadata(
        [("unit", unit), ("description", description)]
            .into_iter()
            .collect::<arrow_schema::Metadata>(),
    )
}

/// A file written under a temporary name beside its final path and renamed onto it only
/// by `commit`, so that no file under the final name is ever incomplete. Dropped without
/// `commit`, it removes the temporary file.
pub struct AtomicFile {
    path: PathBuf,
    partial: PathBuf,
    writer: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file for `path`. Fails with a message naming the path when its
    /// folder does not exist or cannot be written.
    pub fn create(path: &Path) -> anyhow::Result<AtomicFile> {
        check_output_path(path)?;
        let mut name = path.file_name().unwrap_or_default().to_os_string();
        name.push(".partial");
        let partial = path.with_file_name(name);
        let file = File::create(&partial)
            .map_err(|e| anyhow::anyhow!("cannot write output file {}: {e}", partial.display()))?;
        Ok(AtomicFile {
            path: path.to_path_buf(),
            partial,
            writer: Some(BufWriter::with_capacity(1 << 20, file)),
        })
    }

    /// The writer to write the content to.
    pub fn writer(&mut self) -> &mut BufWriter<File> {
        self.writer.as_mut().expect("writer present until commit")
    }

    /// Flushes, syncs and renames the file onto its final path.
    pub fn commit(mut self) -> anyhow::Result<()> {
        let mut w = self.writer.take().expect("writer present until commit");
        w.flush()?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&self.partial, &self.path).map_err(|e| {
            anyhow::anyhow!(
                "cannot move the finished file onto {}: {e}",
                self.path.display()
            )
        })?;
        Ok(())
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.writer.is_some() {
            let _ = std::fs::remove_file(&self.partial);
        }
    }
}

/// Refuses an output path whose folder is missing or that names a folder, before any work.
pub fn check_output_path(path: &Path) -> anyhow::Result<()> {
    if path.as_os_str().is_empty() || path.file_name().is_none() {
        anyhow::bail!("output path {:?} names no file", path.display().to_string());
    }
    if path.is_dir() {
        anyhow::bail!("output path {} is a folder, not a file", path.display());
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        anyhow::bail!(
            "cannot write output file {}: folder {} does not exist",
            path.display(),
            parent.display()
        );
    }
    Ok(())
}
