//! Numbers packed for a page: columns of quantized integers, each stored as the wrapping
//! differences of successive values, zigzagged (0, -1, 1, -2, ... as 0, 1, 2, 3, ...) and
//! split into four byte planes (all low bytes, then the next, ...), the columns one after
//! the other, compressed with zlib's deflate and written as base64. Smooth columns turn
//! into small differences, whose high planes are nearly all zero; deflate takes those to
//! almost nothing. A page reads them back with `DecompressionStream("deflate")`.
//!
//! A column's integer `n` reads as the number `offset + scale * n` (`Scale::Linear`) or
//! `2^(scale * n)` (`Scale::Log2`: the same relative step at every size); [`MISSING`] is a
//! missing number.

use flate2::Compression;
use flate2::write::ZlibEncoder;
use std::fmt::Write as _;
use std::io::Write as _;

/// The integer of a missing (or not finite) number.
pub const MISSING: i32 = i32::MIN;

/// How a column's integers read as numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scale {
    /// `offset + scale * n`.
    Linear {
        /// The number of `n = 0`.
        offset: f64,
        /// The step between successive integers.
        scale: f64,
    },
    /// `2^(scale * n)`: for a positive number known to a relative step of about
    /// `scale * ln 2`.
    Log2 {
        /// The step of `log2` of the number between successive integers.
        scale: f64,
    },
}

impl Scale {
    /// The integer nearest `v` on this scale; [`MISSING`] when `v` is not finite (or, on a
    /// log scale, not positive) or falls outside the integers this format keeps
    /// (|n| < 2^30: far beyond any column of a page).
    #[must_use]
    pub fn quantize(self, v: f64) -> i32 {
        let n = match self {
            Self::Linear { offset, scale } => ((v - offset) / scale).round(),
            Self::Log2 { scale } if v > 0.0 => (v.log2() / scale).round(),
            Self::Log2 { .. } => f64::NAN,
        };
        if n.is_finite() && n.abs() < f64::from(1u32 << 30) {
            n as i32
        } else {
            MISSING
        }
    }
}

/// Columns being packed, and the JSON list that names them.
#[derive(Debug, Default)]
pub struct Packed {
    planes: Vec<u8>,
    names: String,
}

impl Packed {
    /// Appends the column `name` of integers `values` (read on `scale`).
    pub fn column(&mut self, name: &str, scale: Scale, values: impl ExactSizeIterator<Item = i32>) {
        let n = values.len();
        let start = self.planes.len();
        self.planes.resize(start + 4 * n, 0);
        let planes = &mut self.planes[start..];
        let mut last = 0i32;
        for (i, v) in values.enumerate() {
            let d = v.wrapping_sub(last);
            last = v;
            let z = ((d << 1) ^ (d >> 31)) as u32;
            for (p, byte) in z.to_le_bytes().into_iter().enumerate() {
                planes[p * n + i] = byte;
            }
        }
        if !self.names.is_empty() {
            self.names.push(',');
        }
        let _ = write!(self.names, "{{\"name\":\"{name}\",\"count\":{n},");
        let _ = match scale {
            Scale::Linear { offset, scale } => write!(
                self.names,
                "\"scale\":\"linear\",\"offset\":{offset:e},\"step\":{scale:e}}}"
            ),
            Scale::Log2 { scale } => write!(self.names, "\"scale\":\"log2\",\"step\":{scale:e}}}"),
        };
    }

    /// Appends the column `name` of numbers `values`, quantized on `scale`.
    pub fn numbers(
        &mut self,
        name: &str,
        scale: Scale,
        values: impl ExactSizeIterator<Item = f64>,
    ) {
        self.column(name, scale, values.map(|v| scale.quantize(v)));
    }

    /// The columns as JSON: `"columns":[{"name":..,"count":..,"scale":..,..},..],"data":"…"`
    /// (the planes deflated, in base64).
    ///
    /// # Errors
    /// The deflater's error, should it give one (into memory it does not).
    pub fn finish(self) -> std::io::Result<String> {
        let mut z = ZlibEncoder::new(
            Vec::with_capacity(self.planes.len() / 3),
            Compression::best(),
        );
        z.write_all(&self.planes)?;
        let deflated = z.finish()?;
        let mut o = String::with_capacity(deflated.len() * 4 / 3 + self.names.len() + 64);
        let _ = write!(o, "\"columns\":[{}],\"data\":\"", self.names);
        base64(&mut o, &deflated);
        o.push('"');
        Ok(o)
    }
}

/// `bytes` in base64 (RFC 4648, with padding).
pub fn base64(o: &mut String, bytes: &[u8]) {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                o.push(char::from(ALPHABET[(n >> (18 - 6 * k)) as usize & 63]));
            } else {
                o.push('=');
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The number integer `n` stands for on `scale`, as the page reads it (NaN for
    /// `MISSING`).
    fn value(scale: Scale, n: i32) -> f64 {
        match (n, scale) {
            (MISSING, _) => f64::NAN,
            (n, Scale::Linear { offset, scale }) => offset + scale * f64::from(n),
            (n, Scale::Log2 { scale }) => (scale * f64::from(n)).exp2(),
        }
    }

    #[test]
    fn base64_is_rfc_4648() {
        // RFC 4648, section 10.
        for (input, out) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            let mut o = String::new();
            base64(&mut o, input.as_bytes());
            assert_eq!(o, out);
        }
    }

    #[test]
    fn a_column_is_differences_zigzagged_in_byte_planes() {
        let mut p = Packed::default();
        p.column(
            "a",
            Scale::Linear {
                offset: 0.0,
                scale: 1.0,
            },
            [3, 1, 1, MISSING, 2].into_iter(),
        );
        // Differences 3, -2, 0, MISSING - 1 (wrapping: i32::MAX) and 2 - MISSING (wrapping:
        // -(2^31 - 2)), zigzagged: 2 d for d >= 0, -2 d - 1 for d < 0.
        let z = [6u32, 3, 0, u32::MAX - 1, u32::MAX - 4];
        let planes: Vec<u8> = (0..4)
            .flat_map(|b| z.iter().map(move |v| (v >> (8 * b)) as u8))
            .collect();
        assert_eq!(p.planes, planes);
        assert!(p.names.contains("\"name\":\"a\",\"count\":5,"));
    }

    #[test]
    fn scales_round_trip_within_half_a_step() {
        let lin = Scale::Linear {
            offset: -2.0,
            scale: 0.01,
        };
        for v in [-2.0, -1.234_56, 0.0, 89.995, 1e6] {
            assert!(
                (value(lin, lin.quantize(v)) - v).abs() <= 0.005 + 1e-12,
                "{v}"
            );
        }
        let log = Scale::Log2 {
            scale: 1.0 / 65536.0,
        };
        for v in [1e-9, 3.3e-5, 0.0168, 9.81, 1e20] {
            let back = value(log, log.quantize(v));
            // Half a step of log2: a factor 2^(1/131072), 5.3e-6.
            assert!((back / v - 1.0).abs() <= 5.3e-6, "{v} {back}");
        }
        for v in [f64::NAN, f64::INFINITY, 1e300] {
            assert_eq!(lin.quantize(v), MISSING);
        }
        for v in [0.0, -1.0, f64::NAN] {
            assert_eq!(log.quantize(v), MISSING);
        }
        assert!(value(lin, MISSING).is_nan() && value(log, MISSING).is_nan());
    }
}
