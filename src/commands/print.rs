//! How commands speak: what they have to say on stdout, or on stderr when their output
//! itself goes to stdout. A failed write to stdout is an error that names what was being
//! written (a closed pipe among them: `main` ends quietly on it); a message on stderr never
//! panics, even where stderr is gone (a closed terminal after SIGHUP).

use std::io::Write;
use std::path::Path;

pub use crate::run::{shown, tell};

/// Writes what a command has to say about its output `out` (`what`: "the sweep's summary"
/// ...): to stdout, or to stderr when the output itself goes to stdout (`-`).
pub fn say(what: &str, text: &str, out: &Path) -> anyhow::Result<()> {
    if out.as_os_str() == "-" {
        tell(text);
        Ok(())
    } else {
        print_out(what, text)
    }
}

/// Writes `text`, which is `what` ("the report", ...), to stdout. Fails naming `what`
/// and the reason (a full disk, a closed pipe...); the reason stays the error's source.
pub fn print_out(what: &str, text: &str) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| {
            anyhow::Error::new(e).context(format!("cannot write {what} to standard output"))
        })
}

/// Whether `e` comes from a closed pipe (`touchdown report s.arrow | head -1`, a reader of
/// `--out -` that stopped reading): the reader has what it wanted, so it is no error.
#[must_use]
pub fn closed_pipe(e: &anyhow::Error) -> bool {
    use std::io::ErrorKind::BrokenPipe;
    e.chain().any(|cause| {
        let io = cause
            .downcast_ref::<std::io::Error>()
            .or_else(|| match cause.downcast_ref::<arrow_schema::ArrowError>() {
                Some(arrow_schema::ArrowError::IoError(_, io)) => Some(io),
                _ => None,
            });
        io.is_some_and(|io| io.kind() == BrokenPipe)
    })
}
