//! Arrow files: fields that carry their units, provenance in the schema metadata, and
//! files that appear under their name only when complete.

pub mod columns;
pub mod format;
pub mod inputs;
mod lock;
pub mod merge;
pub mod read;
pub mod resume;
pub mod set;
pub mod sweep;
mod target;
pub mod trace;

use arrow_schema::{DataType, Field};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

pub use lock::FolderLock;
pub use set::OutputSet;
use target::{Target, create_unfinished, remove_unfinished_file, settle_unfinished, target_of};
pub use target::{check_output_path, remove_unfinished_then};

/// The engine and version that write a file, as stored in its schema metadata.
pub const ENGINE: &str = concat!("touchdown ", env!("CARGO_PKG_VERSION"));

/// Where an interrupted sweep to `out` keeps its rows.
#[must_use]
pub fn interrupted_path(out: &Path) -> PathBuf {
    let mut name = out.file_name().unwrap_or_default().to_os_string();
    name.push(".interrupted");
    out.with_file_name(name)
}

/// Refuses a sweep's output `out` as `check_output_path` does, and where the file an
/// interrupted run leaves beside it (`interrupted_path`) would take an input's name.
pub fn check_sweep_output_path(out: &Path) -> anyhow::Result<()> {
    check_output_path(out)?;
    if out.as_os_str() == "-" {
        return Ok(());
    }
    inputs::refuse_input_beside(out, &interrupted_path(out), "an interrupted sweep's file")
}

/// A field with its unit (`"1"` for dimensionless) and a description in its metadata.
#[must_use]
pub fn field(name: &str, data_type: DataType, unit: &str, description: &str) -> Field {
    Field::new(name, data_type, false).with_metadata(
        [("unit", unit), ("description", description)]
            .into_iter()
            .collect::<arrow_schema::Metadata>(),
    )
}

/// The stream an output is written to.
pub enum Sink {
    /// A file (regular, or a device or FIFO).
    File(File),
    /// Standard output.
    Stdout(std::io::Stdout),
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            Sink::File(f) => f.write(buf),
            Sink::Stdout(s) => s.write(buf),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            Sink::File(f) => f.flush(),
            Sink::Stdout(s) => s.flush(),
        }
    }
}

/// The buffered writer of an output.
pub type Out = BufWriter<Sink>;

/// An output file that appears under its name only when it is complete: a regular file is
/// written under a temporary name beside its final path and renamed onto it by `commit`
/// (dropped without `commit`, the temporary file is removed). An output that is not a
/// regular file (a device, a FIFO, a symbolic link to one) is written into directly and
/// never replaced, and `-` is standard output: such streams cannot be renamed, so they are
/// complete when the writer says so.
///
/// One run writes a regular file at a time: the temporary file stays locked until it is
/// renamed or removed, and a second run to the same path is refused, naming the first.
/// A file of an `OutputSet` is written into the temporary file the set reserved, and
/// `commit` leaves it there for the set to move into place with the others.
pub struct AtomicFile {
    target: Target,
    /// The lock on the temporary file of a regular output, released after it is renamed
    /// or removed (never before: the name could then be another run's file).
    lock: Option<File>,
    /// Whether it is a file of an `OutputSet`, which renames or removes it.
    in_set: bool,
}

impl AtomicFile {
    /// Opens the output `path` (`-` for standard output). Fails with a message naming the
    /// path when its folder does not exist or it cannot be written.
    pub fn create(path: &Path) -> anyhow::Result<(AtomicFile, Out)> {
        check_output_path(path)?;
        if let Some((path, partial, file)) = set::claim(path)? {
            let handle = AtomicFile {
                target: Target::Regular { path, partial },
                lock: None,
                in_set: true,
            };
            return Ok((handle, BufWriter::with_capacity(1 << 20, Sink::File(file))));
        }
        let target = target_of(path)?;
        let mut lock = None;
        let sink = match &target {
            Target::Regular { partial, .. } => {
                let file = create_unfinished(partial, path)?;
                lock = Some(file.try_clone().map_err(|e| {
                    remove_unfinished_file(partial);
                    anyhow::anyhow!("cannot write output file {}: {e}", partial.display())
                })?);
                Sink::File(file)
            }
            Target::Direct { path } => Sink::File(
                std::fs::OpenOptions::new()
                    .write(true)
                    .open(path)
                    .map_err(|e| anyhow::anyhow!("cannot write to {}: {e}", path.display()))?,
            ),
            Target::Stdout => Sink::Stdout(std::io::stdout()),
        };
        let handle = AtomicFile {
            target,
            lock,
            in_set: false,
        };
        Ok((handle, BufWriter::with_capacity(1 << 20, sink)))
    }

    /// Where the bytes go while they are written (the temporary file of a regular output).
    #[must_use]
    pub fn partial_path(&self) -> &Path {
        match &self.target {
            Target::Regular { partial, .. } => partial,
            Target::Direct { path } => path,
            Target::Stdout => Path::new("-"),
        }
    }

    /// Whether the output is a stream that is read as it is written (standard output), so
    /// that Arrow goes as an IPC stream rather than an IPC file.
    #[must_use]
    pub fn is_stdout(&self) -> bool {
        matches!(self.target, Target::Stdout)
    }

    /// Whether the output is renamed into place when complete (a regular file), so that a
    /// file of another name (an interrupted sweep's) can be made beside it.
    #[must_use]
    pub fn is_regular(&self) -> bool {
        matches!(self.target, Target::Regular { .. })
    }

    /// Flushes `writer`; a regular file is synced and renamed onto its final path.
    pub fn commit(self, writer: Out) -> anyhow::Result<()> {
        self.commit_replacing(writer, None)
    }

    /// As `commit`, and removes `stale` (a file the finished one makes obsolete, such as an
    /// interrupted run's) while no other run can write the output.
    pub fn commit_replacing(mut self, writer: Out, stale: Option<&Path>) -> anyhow::Result<()> {
        let path = match &self.target {
            Target::Regular { path, .. } => Some(path.clone()),
            _ => None,
        };
        let lock = self.lock.take();
        self.finish(writer, path.as_deref())?;
        if let (Some(stale), Some(path)) = (stale, &path)
            && std::fs::symlink_metadata(stale).is_ok()
        {
            std::fs::remove_file(stale).map_err(|e| {
                anyhow::anyhow!(
                    "finished {}, but cannot remove {}: {e}",
                    path.display(),
                    stale.display()
                )
            })?;
        }
        drop(lock);
        Ok(())
    }

    /// Flushes `writer`; a regular file is synced and renamed onto `path` instead of its
    /// final path (for a file that is valid but not what the final path promises, such as
    /// an interrupted sweep's). Returns whether it made `path`.
    pub fn commit_as(self, writer: Out, path: &Path) -> anyhow::Result<bool> {
        let regular = self.is_regular();
        self.finish(writer, regular.then_some(path))?;
        Ok(regular)
    }

    fn finish(self, mut writer: Out, rename_to: Option<&Path>) -> anyhow::Result<()> {
        let partial = self.partial_path().to_path_buf();
        let context = |e: std::io::Error| cannot_write(&partial, e);
        writer.flush().map_err(context)?;
        let sink = writer.into_inner().map_err(|e| context(e.into_error()))?;
        if let (Sink::File(file), Some(path), Target::Regular { partial, .. }) =
            (sink, rename_to, &self.target)
        {
            file.sync_all().map_err(context)?;
            if self.in_set {
                set::written(partial);
            } else {
                settle_unfinished(partial, || std::fs::rename(partial, path)).map_err(|e| {
                    anyhow::anyhow!("cannot move the finished file onto {}: {e}", path.display())
                })?;
            }
        }
        Ok(())
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // A file of a set is the set's to remove.
        if self.in_set {
            return;
        }
        if let Target::Regular { partial, .. } = &self.target {
            // Listed still unless it was renamed into place.
            remove_unfinished_file(partial);
        }
        // Only now may another run take the name.
        self.lock.take();
    }
}

/// Writes `text` to `path`, complete or not at all (a temporary file renamed once whole).
pub fn write_text(path: &Path, text: &str) -> anyhow::Result<()> {
    write_with(path, |out| out.write_all(text.as_bytes()))
}

/// Writes to `path` what `write` writes as it goes (a table too large to hold as one
/// string), complete or not at all.
pub fn write_with(
    path: &Path,
    write: impl FnOnce(&mut Out) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    let (file, mut out) = AtomicFile::create(path)?;
    write(&mut out)
        .and_then(|()| out.flush())
        .map_err(|e| cannot_write(path, e))?;
    file.commit(out)
}

/// The error of a failed write to the output `path` (`-`: standard output), such as a full
/// disk: the output named once and the reason once (Arrow's and Parquet's errors wrap the
/// system's and repeat it). An I/O error's kind stays in the error's source, so that a
/// closed pipe is still told apart (the commands end quietly on one). The sweep's writer and
/// the study's table report their write errors with it too.
#[must_use]
pub fn cannot_write(path: &Path, e: impl Into<anyhow::Error>) -> anyhow::Error {
    let context = if path.as_os_str() == "-" {
        "cannot write to standard output".to_string()
    } else {
        format!("cannot write output file {}", path.display())
    };
    let e = e.into();
    let io = e.chain().find_map(|c| c.downcast_ref::<std::io::Error>());
    match io {
        Some(io) => anyhow::Error::new(std::io::Error::new(io.kind(), io.to_string())),
        None => e,
    }
    .context(context)
}

/// An Arrow IPC writer: the IPC file format (Feather v2), or the IPC stream format for
/// standard output, where a reader reads as it comes.
pub enum IpcWriter {
    /// IPC file.
    File(arrow_ipc::writer::FileWriter<Out>),
    /// IPC stream.
    Stream(arrow_ipc::writer::StreamWriter<Out>),
}

impl IpcWriter {
    /// The writer `output` wants for `schema`.
    pub fn new(
        output: &AtomicFile,
        out: Out,
        schema: &arrow_schema::Schema,
    ) -> anyhow::Result<IpcWriter> {
        Ok(if output.is_stdout() {
            IpcWriter::Stream(arrow_ipc::writer::StreamWriter::try_new(out, schema)?)
        } else {
            IpcWriter::File(arrow_ipc::writer::FileWriter::try_new(out, schema)?)
        })
    }

    /// Writes a batch.
    pub fn write(&mut self, b: &arrow_array::RecordBatch) -> Result<(), arrow_schema::ArrowError> {
        match self {
            IpcWriter::File(w) => w.write(b),
            IpcWriter::Stream(w) => w.write(b),
        }
    }

    /// Writes the end of the file or stream and gives the output back.
    pub fn finish(self) -> Result<Out, arrow_schema::ArrowError> {
        match self {
            IpcWriter::File(mut w) => {
                w.finish()?;
                w.into_inner()
            }
            IpcWriter::Stream(mut w) => {
                w.finish()?;
                w.into_inner()
            }
        }
    }
}
