//! The SHA-256 a sweep records of its table of inputs, to hold a resumed, merged or
//! traced sweep to the same bytes; computed as the file streams, and with it, for a CSV
//! file, the checks of its text as a whole (UTF-8, no blank line between rows).

use anyhow::{anyhow, bail};
use sha2::Digest;
use std::io::Read;
use std::path::Path;

/// SHA-256 of `bytes`, in lower-case hexadecimal.
#[must_use]
pub fn sha256_hex(bytes: &[u8]) -> String {
    hex(&sha2::Sha256::digest(bytes))
}

fn hex(digest: &[u8]) -> String {
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

/// SHA-256 of the file at `path`, read as it streams; a CSV file's text (`csv`) checked on
/// the way (`TextScan`).
pub(super) fn file_sha256(path: &Path, csv: bool) -> anyhow::Result<String> {
    let mut file = std::fs::File::open(path)
        .map_err(|e| anyhow!("cannot read the input table {}: {e}", path.display()))?;
    let mut hasher = sha2::Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    let mut scan = TextScan::default();
    loop {
        let n = match file.read(&mut buf) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => bail!("cannot read the input table {}: {e}", path.display()),
        };
        hasher.update(&buf[..n]);
        if csv {
            scan.take(&buf[..n], path)?;
        }
    }
    if csv && !scan.carry.is_empty() {
        bail!(
            "{} is neither Parquet, Arrow nor CSV text (not UTF-8 at byte {})",
            path.display(),
            scan.offset
        );
    }
    Ok(hex(&hasher.finalize()))
}

/// The text of a CSV file as it streams: refused where it is not UTF-8, or where a blank
/// line stands before the last row. The CSV reader skips blank lines, which in a
/// one-column table are empty values, so one would shift every later row's sample. A
/// blank line inside a quoted field (after an odd number of quotes) is the field's.
#[derive(Default)]
struct TextScan {
    /// Bytes before `carry`.
    offset: u64,
    /// The start of a character the last piece cut.
    carry: Vec<u8>,
    /// The line being read, from 0.
    line: usize,
    /// Whether the line has only white space so far.
    nonblank: bool,
    /// Quotes so far.
    quotes: u64,
    /// The first blank line (from 0) outside a quoted field, once one is seen.
    blank: Option<usize>,
}

impl TextScan {
    fn take(&mut self, bytes: &[u8], path: &Path) -> anyhow::Result<()> {
        let mut piece = std::mem::take(&mut self.carry);
        piece.extend_from_slice(bytes);
        let valid = match std::str::from_utf8(&piece) {
            Ok(_) => piece.len(),
            Err(e) if e.error_len().is_none() => e.valid_up_to(),
            Err(e) => bail!(
                "{} is neither Parquet, Arrow nor CSV text (not UTF-8 at byte {})",
                path.display(),
                self.offset + e.valid_up_to() as u64
            ),
        };
        let text = std::str::from_utf8(&piece[..valid]).expect("checked");
        self.lines(text, path)?;
        self.offset += valid as u64;
        self.carry = piece[valid..].to_vec();
        Ok(())
    }

    fn lines(&mut self, text: &str, path: &Path) -> anyhow::Result<()> {
        let bytes = text.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            if self.nonblank {
                // Only line ends and quotes matter now (neither is part of another
                // character in UTF-8).
                match bytes[i..].iter().position(|&b| b == b'\n' || b == b'"') {
                    Some(k) => i += k,
                    None => return Ok(()),
                }
            }
            let c = text[i..].chars().next().expect("in the text");
            i += c.len_utf8();
            if c == '\n' {
                if !self.nonblank && self.line > 0 && self.quotes.is_multiple_of(2) {
                    self.blank = self.blank.or(Some(self.line));
                }
                self.line += 1;
                self.nonblank = false;
                continue;
            }
            if c == '"' {
                self.quotes += 1;
            }
            if !self.nonblank && !c.is_whitespace() {
                self.nonblank = true;
                if let Some(blank) = self.blank {
                    bail!(
                        "{}: line {} is blank: every row needs its values (a blank line \
                         would shift every later row's sample)",
                        path.display(),
                        blank + 1
                    );
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::sha256_hex;

    #[test]
    fn sha256_of_known_texts() {
        // FIPS 180-2 test vectors.
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
    }
}
