//! How commands speak: what they have to say on stdout (a closed pipe is no error), or on
//! stderr when their output itself goes to stdout.

use std::io::Write;
use std::path::Path;

pub use crate::run::shown;

/// Writes what a command has to say about its output `out`: to stdout, or to stderr when
/// the output itself goes to stdout (`-`).
pub fn say(text: &str, out: &Path) {
    if out.as_os_str() == "-" {
        eprint!("{text}");
    } else {
        print_out(text);
    }
}

/// Writes to stdout; a closed pipe (`| head`) is not an error.
pub fn print_out(text: &str) {
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
}
