//! Strut loads, stroke margins, bottoming and structural limits (issue 30 points 2 and 3,
//! MODEL.md section 9), end to end: closed forms read from traces, the sweep's peaks
//! against its traces, bottomed cartridges and broken limits counted by `report`.

use crate::common::TempDir;
use arrow_array::{Array, BooleanArray, Float64Array, RecordBatch, UInt32Array};
use arrow_ipc::reader::FileReader;
use std::path::Path;

mod at_rest;
mod bottoming;
mod crush;
mod limits;
mod peaks;
mod shown;

/// An Arrow IPC file (a sweep or a trace) read whole, its columns by name, nulls kept.
struct Columns {
    batches: Vec<RecordBatch>,
    meta: arrow_schema::Metadata,
}

impl Columns {
    fn read(path: &Path) -> Columns {
        let file = std::fs::File::open(path)
            .unwrap_or_else(|e| panic!("cannot open {}: {e}", path.display()));
        let reader = FileReader::try_new(file, None)
            .unwrap_or_else(|e| panic!("{} is not an Arrow IPC file: {e}", path.display()));
        let meta = reader.schema().metadata().clone();
        let batches = reader.map(|b| b.expect("a record batch")).collect();
        Columns { batches, meta }
    }

    fn in_dir(dir: &TempDir, name: &str) -> Columns {
        Columns::read(&dir.join(name))
    }

    fn has(&self, name: &str) -> bool {
        self.batches
            .first()
            .is_some_and(|b| b.column_by_name(name).is_some())
    }

    fn values<A: Array + 'static, T>(&self, name: &str, get: impl Fn(&A, usize) -> T) -> Vec<T> {
        let mut v = Vec::new();
        for b in &self.batches {
            let col = b
                .column_by_name(name)
                .unwrap_or_else(|| panic!("no column {name}"));
            let a = col
                .as_any()
                .downcast_ref::<A>()
                .unwrap_or_else(|| panic!("column {name} is {}", col.data_type()));
            v.extend((0..a.len()).map(|i| get(a, i)));
        }
        v
    }

    /// A Float64 column, null as `None`.
    fn options(&self, name: &str) -> Vec<Option<f64>> {
        self.values(name, |a: &Float64Array, i| {
            a.is_valid(i).then(|| a.value(i))
        })
    }

    /// A Float64 column without nulls.
    fn f64s(&self, name: &str) -> Vec<f64> {
        self.options(name)
            .into_iter()
            .map(|x| x.unwrap_or_else(|| panic!("a null in {name}")))
            .collect()
    }

    fn u32s(&self, name: &str) -> Vec<u32> {
        self.values(name, |a: &UInt32Array, i| a.value(i))
    }

    fn bools(&self, name: &str) -> Vec<bool> {
        self.values(name, |a: &BooleanArray, i| a.value(i))
    }

    fn strings(&self, name: &str) -> Vec<String> {
        crate::common::batch_texts(&self.batches, name)
    }

    fn meta(&self, key: &str) -> &str {
        self.meta
            .get(key)
            .unwrap_or_else(|| panic!("no metadata {key}"))
    }
}

/// Runs `touchdown sweep ARGS` in `dir`; panics unless it succeeded (its banner and
/// summary are on stderr and stdout).
fn sweep(dir: &TempDir, args: &[&str]) {
    let run = crate::common::touchdown(dir.path(), &[&["sweep"], args].concat());
    assert_eq!(run.code, Some(0), "{run}");
}

/// `[inputs]` of one level touchdown from `release_height` m, no errors, no rates.
fn level_drop(release_height: f64) -> String {
    format!(
        "[inputs]\nslope_deg = 0.0\ndownhill_azimuth_deg = 0.0\nyaw_deg = 0.0\n{}",
        crate::common::set_down_lines!("{h}", "0.0").replace("{h}", &release_height.to_string())
    )
}
