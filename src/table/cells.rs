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
pub(super) fn csv_reader(text: &[u8]) -> csv::Reader<&[u8]> {
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

/// A kept CSV column as an Arrow array: 64-bit integers if every field is one, else
/// floating-point numbers if every field is one, else text; empty fields are null.
pub(super) fn csv_array<'a>(fields: impl Iterator<Item = &'a str> + Clone) -> ArrayRef {
    let cells = || fields.clone().filter(|t| !t.is_empty());
    let opt = |t: &'a str| (!t.is_empty()).then_some(t);
    if cells().all(|t| t.parse::<i64>().is_ok()) {
        Arc::new(arrow_array::Int64Array::from_iter(
            fields.map(|t| opt(t).map(|t| t.parse::<i64>().expect("checked"))),
        ))
    } else if cells().all(|t| t.parse::<f64>().is_ok()) {
        Arc::new(arrow_array::Float64Array::from_iter(
            fields.map(|t| opt(t).map(|t| t.parse::<f64>().expect("checked"))),
        ))
    } else {
        Arc::new(arrow_array::StringArray::from_iter(fields.map(opt)))
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
    use super::csv_array;
    use arrow_array::Array;
    use arrow_schema::DataType;

    #[test]
    fn csv_columns_keep_their_type() {
        let ints = csv_array(["1", "", "-3"].into_iter());
        assert_eq!(ints.data_type(), &DataType::Int64);
        assert_eq!(ints.null_count(), 1);
        let floats = csv_array(["1", "2.5"].into_iter());
        assert_eq!(floats.data_type(), &DataType::Float64);
        let text = csv_array(["1", "a"].into_iter());
        assert_eq!(text.data_type(), &DataType::Utf8);
    }
}
