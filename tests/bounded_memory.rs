//! Memory bounded by the work, not by the inputs (issue 33, point 7): a table of inputs is
//! streamed, never held whole, so a huge table run for a few samples takes little memory;
//! a CSV table's unknown columns are refused from its header, before its rows are read; a
//! kept text column too long for Arrow is refused, not a panic; a boundary search that
//! could not fit is refused with its estimate before any work.

use crate::common::{BIN, TempDir, touchdown};
use arrow_array::{Float64Array, RecordBatch};
use arrow_schema::{DataType, Field, Schema};
use std::io::{Read, Write};
use std::path::Path;
use std::sync::Arc;

/// What a run of the binary gave, with its peak resident memory.
struct Measured {
    code: Option<i32>,
    stderr: String,
    /// Peak resident set size, bytes (the kernel's `ru_maxrss` of the child).
    peak_rss: u64,
}

unsafe extern "C" {
    /// `wait4(2)`: waits for child `pid` and fills `rusage` (a `struct rusage`).
    fn wait4(pid: i32, status: *mut i32, options: i32, rusage: *mut i64) -> i32;
}

/// Runs `touchdown ARGS` in `dir` and reads its peak resident memory from the kernel's
/// account of that child alone (`wait4`), so that no other test's child counts.
#[allow(
    clippy::zombie_processes,
    reason = "reaped by wait4, which std does not know of"
)]
fn run_measured(dir: &Path, args: &[&str]) -> Measured {
    let mut child = std::process::Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run the touchdown binary");
    let mut pipe = child.stderr.take().expect("piped");
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        pipe.read_to_string(&mut text).expect("stderr is UTF-8");
        text
    });
    let pid = i32::try_from(child.id()).expect("a pid");
    let mut status = 0i32;
    // `struct rusage` on 64-bit Linux: two `timeval`s (4 longs), then `ru_maxrss` (KiB)
    // and 13 more longs.
    let mut usage = [0i64; 18];
    // SAFETY: `status` and `usage` are valid for writes of an `int` and a `struct rusage`
    // (144 bytes on 64-bit Linux); `pid` is our child, reaped here and nowhere else.
    let got = unsafe { wait4(pid, &raw mut status, 0, usage.as_mut_ptr()) };
    assert_eq!(got, pid, "wait4 of the touchdown binary");
    let stderr = reader.join().expect("stderr read");
    let exited = status & 0x7f == 0;
    Measured {
        code: exited.then_some((status >> 8) & 0xff),
        stderr,
        peak_rss: u64::try_from(usage[4]).expect("a size") * 1024,
    }
}

/// A Parquet file of `rows` rows of one column, `slope_deg` = 10, in row groups of 2^20
/// rows: a few hundred kilobytes on disk, since every value is the same.
fn constant_parquet(path: &Path, rows: usize) {
    let schema = Arc::new(Schema::new(vec![Field::new(
        "slope_deg",
        DataType::Float64,
        false,
    )]));
    let chunk = 1 << 20;
    let batch = RecordBatch::try_new(
        schema.clone(),
        vec![Arc::new(Float64Array::from(vec![10.0; chunk]))],
    )
    .unwrap();
    let props = parquet::file::properties::WriterProperties::builder()
        .set_max_row_group_row_count(Some(chunk))
        .build();
    let file = std::fs::File::create(path).unwrap();
    let mut w = parquet::arrow::ArrowWriter::try_new(file, schema, Some(props)).unwrap();
    let mut left = rows;
    while left > 0 {
        let n = left.min(chunk);
        w.write(&batch.slice(0, n)).unwrap();
        left -= n;
    }
    w.close().unwrap();
}

#[test]
#[cfg(target_os = "linux")]
fn a_huge_table_run_for_ten_samples_takes_little_memory() {
    let dir = TempDir::new("huge_table_ten_samples");
    constant_parquet(&dir.join("t.parquet"), 100_000_000);
    let run = run_measured(
        dir.path(),
        &[
            "sweep",
            "--inputs",
            "t.parquet",
            "--samples",
            "10",
            "--out",
            "s.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    // The table's 1e8 values alone are 800 MB; a sweep of 10 samples with the table
    // streamed holds a few tens of MB (12 MB measured). 200 MB is the bound.
    assert!(
        run.peak_rss < 200_000_000,
        "peak resident memory {} MB",
        run.peak_rss / 1_000_000
    );
    // The whole table is still checked and counted.
    assert!(
        run.stderr.contains("(100000000 rows, 1 columns)"),
        "{}",
        run.stderr
    );
}

#[test]
fn unknown_csv_columns_are_refused_from_the_header() {
    let dir = TempDir::new("unknown_csv_columns");
    // Rows that could not be read (not UTF-8 at the end): the header alone decides.
    let mut bytes = b"slope_deg,my_label\n10,a\n20,b\n".to_vec();
    bytes.extend_from_slice(&[0xff, 0xfe, b'\n']);
    std::fs::write(dir.join("t.csv"), bytes).unwrap();
    let run = touchdown(
        dir.path(),
        &["sweep", "--inputs", "t.csv", "--out", "s.arrow"],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("unknown column my_label"), "{run}");
}

#[test]
fn a_kept_text_column_over_2_gib_is_refused() {
    let dir = TempDir::new("kept_text_over_2_gib");
    let path = dir.join("t.csv");
    // 2,100 rows of a 1 MiB label: 2.2 GB of text in one column, more than an Arrow text
    // column's 32-bit offsets reach.
    let mut w = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
    let label = "a".repeat(1 << 20);
    writeln!(w, "slope_deg,label").unwrap();
    for _ in 0..2100 {
        writeln!(w, "10,{label}").unwrap();
    }
    w.flush().unwrap();
    drop(w);
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--inputs",
            "t.csv",
            "--keep-columns",
            "--samples",
            "1",
            "--out",
            "s.arrow",
        ],
    );
    std::fs::remove_file(&path).unwrap();
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr
            .contains("column label holds 2202009600 bytes of text"),
        "{run}"
    );
}

#[test]
fn a_boundary_search_that_cannot_fit_is_refused_before_any_work() {
    let dir = TempDir::new("boundary_cannot_fit");
    let run = touchdown(
        dir.path(),
        &[
            "boundary",
            "--batch",
            "1e9",
            "--max-samples-per-sector",
            "1e12",
            "--quiet",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr
            .contains("--max-samples-per-sector 1000000000000")
            && run.stderr.contains("would hold about")
            && run.stderr.contains("GB of memory"),
        "{run}"
    );
    assert!(run.stdout.is_empty(), "{run}");
}
