//! A cell of the table, from a CSV field or an Arrow column, and a kept CSV column as an
//! Arrow array of the narrowest type that holds it.

use anyhow::anyhow;
use arrow_array::{Array, ArrayRef, cast::AsArray, types::*};
use arrow_schema::DataType;
use std::path::Path;
use std::sync::Arc;

/// A cell of the table: a whole number, a floating-point one, or text (or nothing).
pub(super) enum Cell<'a> {
    Int(i128),
    Float(f64),
    Text(&'a str),
    Null,
}

/// A reader of CSV text with a header row, fields trimmed.
pub(super) fn csv_reader<R: std::io::Read>(text: R) -> csv::Reader<R> {
    csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .from_reader(text)
}

/// An error of the CSV reader, with its line where it has one.
pub(super) fn csv_error(e: &csv::Error, path: &Path) -> anyhow::Error {
    match e.kind() {
        csv::ErrorKind::UnequalLengths {
            pos: Some(pos),
            expected_len,
            len,
        } => anyhow!(
            "{}: line {} has {len} fields, the header {expected_len}",
            path.display(),
            pos.line()
        ),
        _ => anyhow!("{}: {e}", path.display()),
    }
}

/// A CSV field as a cell: a whole number, a number, nothing (empty) or text.
pub(super) fn csv_cell(text: &str) -> Cell<'_> {
    if text.is_empty() {
        Cell::Null
    } else if let Ok(i) = text.parse::<i128>() {
        Cell::Int(i)
    } else if let Ok(x) = text.parse::<f64>() {
        Cell::Float(x)
    } else {
        Cell::Text(text)
    }
}

/// What a kept CSV column holds, field by field: the Arrow type it is kept as (64-bit
/// integers if every field is one, else floating-point numbers if every field is one, else
/// text; empty fields are null), and its bytes of text.
#[derive(Debug, Clone, Copy)]
pub(super) struct CsvKind {
    ints: bool,
    floats: bool,
    /// Bytes of its fields.
    pub(super) text_bytes: u64,
}

impl CsvKind {
    pub(super) fn new() -> CsvKind {
        CsvKind {
            ints: true,
            floats: true,
            text_bytes: 0,
        }
    }

    /// Takes one more field.
    pub(super) fn take(&mut self, t: &str) {
        if t.is_empty() {
            return;
        }
        self.text_bytes += t.len() as u64;
        // A whole number is a number too: floats need checking once ints fail.
        if self.ints && t.parse::<i64>().is_err() {
            self.ints = false;
        }
        if !self.ints && self.floats && t.parse::<f64>().is_err() {
            self.floats = false;
        }
    }

    pub(super) fn data_type(&self) -> DataType {
        if self.ints {
            DataType::Int64
        } else if self.floats {
            DataType::Float64
        } else {
            DataType::Utf8
        }
    }
}

/// The fields of a kept CSV column as an Arrow array of type `data_type`
/// (`CsvKind::data_type`, found over the whole column); empty fields are null.
pub(super) fn csv_array<'a>(
    data_type: &DataType,
    fields: impl Iterator<Item = &'a str>,
) -> ArrayRef {
    let opt = |t: &'a str| (!t.is_empty()).then_some(t);
    match data_type {
        DataType::Int64 => Arc::new(arrow_array::Int64Array::from_iter(
            fields.map(|t| opt(t).and_then(|t| t.parse::<i64>().ok())),
        )),
        DataType::Float64 => Arc::new(arrow_array::Float64Array::from_iter(
            fields.map(|t| opt(t).and_then(|t| t.parse::<f64>().ok())),
        )),
        _ => Arc::new(arrow_array::StringArray::from_iter(fields.map(opt))),
    }
}

pub(super) enum CellError {
    /// The column's type holds no numbers.
    Type(DataType),
    At(anyhow::Error),
}

/// Calls `f` on every cell of a numeric (or text) Arrow column, in row order.
pub(super) fn arrow_cells(
    a: &ArrayRef,
    f: &mut dyn FnMut(usize, Cell<'_>) -> anyhow::Result<()>,
) -> Result<(), CellError> {
    macro_rules! each {
        ($t:ty, $wrap:expr) => {{
            let p = a.as_primitive::<$t>();
            for row in 0..p.len() {
                let cell = if p.is_null(row) {
                    Cell::Null
                } else {
                    $wrap(p.value(row))
                };
                f(row, cell).map_err(CellError::At)?;
            }
        }};
    }
    match a.data_type() {
        DataType::Float64 => each!(Float64Type, Cell::Float),
        DataType::Float32 => each!(Float32Type, |x: f32| Cell::Float(f64::from(x))),
        DataType::Int64 => each!(Int64Type, |x| Cell::Int(i128::from(x))),
        DataType::Int32 => each!(Int32Type, |x| Cell::Int(i128::from(x))),
        DataType::Int16 => each!(Int16Type, |x| Cell::Int(i128::from(x))),
        DataType::Int8 => each!(Int8Type, |x| Cell::Int(i128::from(x))),
        DataType::UInt64 => each!(UInt64Type, |x| Cell::Int(i128::from(x))),
        DataType::UInt32 => each!(UInt32Type, |x| Cell::Int(i128::from(x))),
        DataType::UInt16 => each!(UInt16Type, |x| Cell::Int(i128::from(x))),
        DataType::UInt8 => each!(UInt8Type, |x| Cell::Int(i128::from(x))),
        DataType::Utf8 | DataType::LargeUtf8 | DataType::Utf8View => {
            let texts: Vec<Option<&str>> = match a.data_type() {
                DataType::Utf8 => a.as_string::<i32>().iter().collect(),
                DataType::LargeUtf8 => a.as_string::<i64>().iter().collect(),
                _ => a.as_string_view().iter().collect(),
            };
            for (row, t) in texts.into_iter().enumerate() {
                // Numbers written as text read as in a CSV file.
                let cell = t.map_or(Cell::Null, csv_cell);
                f(row, cell).map_err(CellError::At)?;
            }
        }
        t => return Err(CellError::Type(t.clone())),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{CsvKind, csv_array};
    use arrow_array::Array;
    use arrow_schema::DataType;

    #[test]
    fn csv_columns_keep_their_type() {
        let kind = |fields: &[&str]| {
            let mut k = CsvKind::new();
            fields.iter().for_each(|t| k.take(t));
            k
        };
        let ints = kind(&["1", "", "-3"]);
        assert_eq!(ints.data_type(), DataType::Int64);
        let array = csv_array(&ints.data_type(), ["1", "", "-3"].into_iter());
        assert_eq!(array.null_count(), 1);
        assert_eq!(kind(&["1", "2.5"]).data_type(), DataType::Float64);
        let text = kind(&["1", "a", ""]);
        assert_eq!(text.data_type(), DataType::Utf8);
        assert_eq!(text.text_bytes, 2);
    }
}
