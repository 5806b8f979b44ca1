//! Arrow files: fields that carry their units, provenance in the schema metadata, and
//! files that appear under their name only when complete.

pub mod merge;
pub mod read;
pub mod resume;
pub mod sweep;
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
    committed: bool,
}

impl AtomicFile {
    /// Creates the temporary file for `path` and a buffered writer to it. Fails with a
    /// message naming the path when its folder does not exist or cannot be written.
    pub fn create(path: &Path) -> anyhow::Result<(AtomicFile, BufWriter<File>)> {
        check_output_path(path)?;
        let mut name = path.file_name().unwrap_or_default().to_os_string();
        name.push(".partial");
        let partial = path.with_file_name(name);
        let file = File::create(&partial)
            .map_err(|e| anyhow::anyhow!("cannot write output file {}: {e}", partial.display()))?;
        let handle = AtomicFile {
            path: path.to_path_buf(),
            partial,
            committed: false,
        };
        Ok((handle, BufWriter::with_capacity(1 << 20, file)))
    }

    /// The temporary path the file is written under.
    #[must_use]
    pub fn partial_path(&self) -> &Path {
        &self.partial
    }

    /// The final path.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Flushes and syncs `writer`, then renames the file onto its final path.
    pub fn commit(self, writer: BufWriter<File>) -> anyhow::Result<()> {
        let path = self.path.clone();
        self.commit_as(writer, &path)
    }

    /// Flushes and syncs `writer`, then renames the file onto `path` (for a file that is
    /// valid but not what the final path promises, such as an interrupted sweep's).
    pub fn commit_as(mut self, mut writer: BufWriter<File>, path: &Path) -> anyhow::Result<()> {
        let context = |e: std::io::Error| {
            anyhow::anyhow!("cannot finish output file {}: {e}", self.partial.display())
        };
        writer.flush().map_err(context)?;
        let file = writer.into_inner().map_err(|e| context(e.into_error()))?;
        file.sync_all().map_err(context)?;
        std::fs::rename(&self.partial, path).map_err(|e| {
            anyhow::anyhow!("cannot move the finished file onto {}: {e}", path.display())
        })?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if !self.committed {
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
    if parent.exists() && !parent.is_dir() {
        anyhow::bail!(
            "cannot write output file {}: {} is a file, not a folder",
            path.display(),
            parent.display()
        );
    }
    if !parent.is_dir() {
        anyhow::bail!(
            "cannot write output file {}: folder {} does not exist",
            path.display(),
            parent.display()
        );
    }
    Ok(())
}
