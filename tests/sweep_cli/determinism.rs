//! Determinism: sweeps repeat byte for byte whatever the thread count.

use super::{Summary, check_sweep_file, read_sweep, sweep};
use crate::common::{SHORT, TempDir, read_bytes};

#[test]
fn sweeps_repeat_byte_for_byte_whatever_the_thread_count() {
    let dir = TempDir::new("sweep-threads");
    dir.write("short.toml", SHORT);
    // More samples than one thread's window of chunks (4 x 1024), so that one thread runs
    // two windows where two or three threads run one.
    let samples = "5000";
    let mut files = Vec::new();
    for format in ["arrow", "parquet"] {
        let mut first: Option<(String, Summary)> = None;
        for threads in ["1", "2", "3"] {
            let out = format!("t{threads}.{format}");
            let (b, s) = sweep(
                &dir,
                &[
                    "--scenario",
                    "short.toml",
                    "--samples",
                    samples,
                    "--seed",
                    "21",
                    "--threads",
                    threads,
                    "--format",
                    format,
                    "--out",
                    &out,
                ],
            );
            assert_eq!(b.threads.to_string(), threads);
            assert_eq!(s.wrote, out);
            match &first {
                None => {
                    check_sweep_file(&dir.join(&out), &s, 21, SHORT);
                    first = Some((out, s));
                }
                Some((first_out, first_s)) => {
                    assert_eq!(
                        s.outcomes, first_s.outcomes,
                        "outcomes of --threads {threads} and --threads 1 ({format})"
                    );
                    assert!(
                        read_bytes(&dir.join(&out)) == read_bytes(&dir.join(first_out)),
                        "--threads {threads} and --threads 1 wrote different {format} files"
                    );
                }
            }
        }
        files.push(dir.join(&format!("t1.{format}")));
    }

    // The Parquet file holds the same schema and data as the Arrow file.
    let (arrow, parquet) = (read_sweep(&files[0]), read_sweep(&files[1]));
    assert_eq!(arrow.schema.fields(), parquet.schema.fields());
    for (k, v) in arrow.schema.metadata() {
        assert_eq!(parquet.meta(k), Some(v.as_str()), "schema metadata {k}");
    }
    assert_eq!(arrow.batches.len(), parquet.batches.len());
    for (a, p) in arrow.batches.iter().zip(&parquet.batches) {
        for (f, (x, y)) in arrow
            .schema
            .fields()
            .iter()
            .zip(a.columns().iter().zip(p.columns()))
        {
            assert!(
                x == y,
                "column {} differs between the Arrow and Parquet files",
                f.name()
            );
        }
    }
}
