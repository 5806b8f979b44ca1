//! Memory bounded by the work, not by the inputs (issue 33, point 7): a table of inputs is
//! streamed, never held whole, so a huge table run for a few samples takes little memory;
//! a CSV table's unknown columns are refused from its header, before its rows are read; a
//! kept text column too long for Arrow is refused, not a panic; a boundary search that
//! could not fit is refused with its estimate before any work.

use crate::common::{BIN, TempDir, touchdown};
use arrow_array::{Float64Array, RecordBatch};
use arrow_schema::{DataType, Field, Schema};
use std::io::Write;
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

/// The variable that makes `peak_rss_helper` run touchdown: its folder, then its arguments,
/// separated by `\x1f`.
const HELPER_ARGS: &str = "TOUCHDOWN_PEAK_RSS_ARGS";

/// Runs `touchdown ARGS` in `dir` and measures its peak resident memory. Linux counts in a
/// child's peak the peak of the process that started it (the memory it shared until its
/// `exec`), and this test process may hold much: so a fresh, small process of this test
/// binary (`peak_rss_helper`) starts touchdown and reads the kernel's account of that
/// child alone (`wait4`).
fn run_measured(dir: &Path, args: &[&str]) -> Measured {
    let mut spec = vec![dir.to_str().expect("a UTF-8 path")];
    spec.extend_from_slice(args);
    let out = std::process::Command::new(std::env::current_exe().expect("the test binary"))
        .args([
            "--exact",
            "bounded_memory::peak_rss_helper",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(HELPER_ARGS, spec.join("\x1f"))
        .output()
        .expect("run the helper");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let field = |key: &str| -> Option<String> {
        // libtest prints the test's name on the line before the helper's words.
        let at = stdout.find("PEAK_RSS ")?;
        let line = stdout[at..].lines().next()?;
        let v = line.split_whitespace().find_map(|w| w.strip_prefix(key))?;
        Some(v.to_string())
    };
    Measured {
        code: field("code=").and_then(|c| c.parse().ok()),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        peak_rss: field("bytes=")
            .and_then(|b| b.parse().ok())
            .unwrap_or_else(|| panic!("no measurement from the helper:\n{stdout}")),
    }
}

/// Not a test of its own: run by `run_measured` in a process of its own, it runs
/// touchdown as `HELPER_ARGS` says and prints its exit code and peak resident memory.
#[test]
#[allow(
    clippy::zombie_processes,
    reason = "reaped by wait4, which std does not know of"
)]
fn peak_rss_helper() {
    let Ok(spec) = std::env::var(HELPER_ARGS) else {
        return;
    };
    let mut spec = spec.split('\x1f');
    let dir = spec.next().expect("a folder");
    let child = std::process::Command::new(BIN)
        .args(spec)
        .current_dir(dir)
        // touchdown's own choice of malloc arenas, whatever the shell set.
        .env_remove("MALLOC_ARENA_MAX")
        .stdout(std::process::Stdio::null())
        .spawn()
        .expect("run the touchdown binary");
    let pid = i32::try_from(child.id()).expect("a pid");
    let mut status = 0i32;
    // `struct rusage` on 64-bit Linux: two `timeval`s (4 longs), then `ru_maxrss` (KiB)
    // and 13 more longs.
    let mut usage = [0i64; 18];
    // SAFETY: `status` and `usage` are valid for writes of an `int` and a `struct rusage`
    // (144 bytes on 64-bit Linux); `pid` is our child, reaped here and nowhere else.
    let got = unsafe { wait4(pid, &raw mut status, 0, usage.as_mut_ptr()) };
    assert_eq!(got, pid, "wait4 of the touchdown binary");
    let code = if status & 0x7f == 0 {
        ((status >> 8) & 0xff).to_string()
    } else {
        "none".to_string()
    };
    println!("PEAK_RSS code={code} bytes={}", usage[4] * 1024);
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

/// Memory that does not grow with the threads (issue 47, point 3: "growing by at most a few
/// MB per added thread"): a Parquet sweep of the default scenario on 8 threads peaks within
/// 3 MB a thread added of the same sweep on 1. Each worker builds and encodes its stretch's
/// record batch; with an arena of glibc's malloc to each thread, every arena kept the peak
/// of what its worker once held, and the same sweeps peaked at 48 and 102 MB (the build
/// before `run::memory::one_malloc_arena`, on the 2-core AVX2 machine: 6.7 MB a thread
/// added); with one arena, 46 and 47 MB. The bound leaves the 8 threads 21 MB for their
/// stacks, blocks and rows in flight (measured: 1 MB).
#[test]
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn memory_does_not_grow_with_the_threads() {
    let dir = TempDir::new("memory_and_threads");
    let peak = |threads: &str| {
        let run = run_measured(
            dir.path(),
            &[
                "sweep",
                "--samples",
                "6e4",
                "--threads",
                threads,
                "--out",
                "s.parquet",
            ],
        );
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        run.peak_rss
    };
    let (one, eight) = (peak("1"), peak("8"));
    let added_per_thread = eight.saturating_sub(one) as f64 / 7.0 / 1e6;
    println!(
        "peak resident memory: {} MB on 1 thread, {} MB on 8 ({added_per_thread:.1} MB a \
         thread added)",
        one / 1_000_000,
        eight / 1_000_000
    );
    assert!(
        added_per_thread <= 3.0,
        "{added_per_thread:.1} MB a thread added (1 thread: {} MB, 8: {} MB)",
        one / 1_000_000,
        eight / 1_000_000
    );
}
