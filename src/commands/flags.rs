//! The command line's value parsers (counts, seeds, threads, sizes, kernels), the flag
//! groups several commands share, and the defaults that follow from other flags.

use crate::output::format::Format;
use crate::run::KernelChoice;
use kernels::isa::Isa;
use std::path::{Path, PathBuf};

/// `--threads`, as `sweep`, `study` and `boundary` take it.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct Threads {
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "T", value_parser = parse_threads, allow_negative_numbers = true)]
    pub threads: Option<usize>,
}

/// `--out` and `--format` of a sweep file, as `sweep` and `merge` take them.
#[derive(clap::Args, Debug, Clone)]
pub struct SweepOut {
    /// Output file; `-` writes to standard output (Arrow as an IPC stream). A device or
    /// FIFO at PATH (or a symbolic link to one) is written into, never replaced.
    #[arg(long, value_name = "PATH", default_value = "sweep.arrow")]
    pub out: PathBuf,
    /// Output format (default: from the extension of --out, `.parquet` for Parquet, else
    /// Arrow); refused when it contradicts the extension.
    #[arg(long, value_enum)]
    pub format: Option<Format>,
}

/// The largest count or seed: the largest whole number a scenario file holds (TOML's
/// integers are 64-bit signed), 2^63 - 1, so that every value of a flag can be written
/// into the scenario a file stores.
pub const MAX_COUNT: u64 = i64::MAX as u64;

/// The most worker threads (`--threads`).
pub const MAX_THREADS: u64 = 1024;

/// Parses a whole number from 0 to `MAX_COUNT` written as `250000`, `1e6` or `2.5e5`.
pub fn parse_count(s: &str) -> Result<u64, String> {
    let t = s.trim().replace('_', "");
    let too_large = || format!("{s:?} is too large: at most {MAX_COUNT} (2^63 - 1)");
    if let Ok(n) = t.parse::<u128>() {
        return u64::try_from(n)
            .ok()
            .filter(|&n| n <= MAX_COUNT)
            .ok_or_else(too_large);
    }
    let bad = || format!("{s:?} is not a whole number (examples: 250000, 1e6, 2.5e5)");
    let x: f64 = t.parse().map_err(|_| bad())?;
    if !x.is_finite() || x < 0.0 || x.fract() != 0.0 {
        return Err(bad());
    }
    // 2^63 is the first float past MAX_COUNT (which is not a float).
    if x >= 2f64.powi(63) {
        return Err(too_large());
    }
    Ok(x as u64)
}

/// A seed: a whole number a scenario file can hold too (`parse_count`'s range).
pub fn parse_seed(s: &str) -> Result<u64, String> {
    parse_count(s)
}

/// A worker thread count, 1 to `MAX_THREADS` (`--threads`).
fn parse_threads(s: &str) -> Result<usize, String> {
    match parse_count(s)? {
        0 => Err("must be at least 1".to_string()),
        n if n > MAX_THREADS => Err(format!("must be at most {MAX_THREADS}")),
        n => Ok(n as usize),
    }
}

/// A positive whole number (every N-th step of a trace).
pub(super) fn parse_every(s: &str) -> Result<u64, String> {
    match parse_count(s)? {
        0 => Err("must be at least 1".to_string()),
        n => Ok(n),
    }
}

/// Parses a picture size written `640x480`.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("{s:?} is not a size WIDTHxHEIGHT in pixels (example: 640x480)");
    let (w, h) = s.trim().split_once(['x', 'X']).ok_or_else(bad)?;
    Ok((w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?))
}

/// A SIMD kernel: `auto` (the best this CPU runs) or an instruction set's key.
pub(super) fn parse_kernel(s: &str) -> Result<KernelChoice, String> {
    if s == "auto" {
        return Ok(KernelChoice::Auto);
    }
    Isa::from_key(s).map(KernelChoice::Isa).ok_or_else(|| {
        let keys: Vec<&str> = Isa::ALL.iter().map(|i| i.key()).collect();
        format!("{s:?} is not a kernel: auto, {}", keys.join(", "))
    })
}

/// The output beside `trace` with `extension`, unless `out` names one.
#[must_use]
pub fn beside(trace: &Path, out: Option<&PathBuf>, extension: &str) -> PathBuf {
    out.cloned()
        .unwrap_or_else(|| trace.with_extension(extension))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_parse_in_plain_and_scientific_notation() {
        assert_eq!(parse_count("250000"), Ok(250_000));
        assert_eq!(parse_count("1e6"), Ok(1_000_000));
        assert_eq!(parse_count("2.5e5"), Ok(250_000));
        assert_eq!(parse_count("1_000"), Ok(1000));
        assert_eq!(parse_count("9223372036854775807"), Ok(i64::MAX as u64));
        assert_eq!(parse_count("9.2e18"), Ok(9_200_000_000_000_000_000));
        for bad in [
            "-1",
            "1.5",
            "abc",
            "1e30",
            "nan",
            "",
            "9223372036854775808",
            "9.223372036854775808e18",
            "1.8e19",
            "18446744073709551616",
            "340282366920938463463374607431768211456",
        ] {
            assert!(parse_count(bad).is_err(), "{bad}");
        }
    }
}
