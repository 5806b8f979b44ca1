//! Leaner sweep files (issue 47, point 4): `outcome` and `limits_broken` coded into one
//! fixed dictionary of every text they can hold, the same in every batch and file; Parquet
//! compressed with zstd, without dictionaries on the columns whose values seldom repeat,
//! well below the Arrow file; and files whose text columns are plain (as sweeps wrote them
//! before) read as before.

use crate::common::{TempDir, plain_copy, texts, touchdown};
use arrow_array::cast::AsArray;
use arrow_array::{ArrayRef, RecordBatch};
use arrow_schema::{DataType, SchemaRef};
use std::path::Path;

/// The short default scenario, dampers on, with limits that some samples break and some
/// do not.
const LIMITS: &str = "[simulation]\nt_max_s = 20.0\n\n[damper]\nenabled = true\n\n\
                      [limits]\naxial_force_n = 400.0\nside_force_n = 150.0\n\
                      acceleration_m_s2 = 30.0\nstroke_margin_m = 0.0\n";

/// The schema and batches of a sweep file, Arrow or Parquet, as touchdown reads them.
fn read(path: &Path) -> (SchemaRef, Vec<RecordBatch>) {
    let format = touchdown::output::read::format_of(path).expect("a sweep file");
    let (schema, batches) = touchdown::output::read::open(path, format).expect("readable");
    (schema, batches.map(|b| b.expect("a batch")).collect())
}

/// The texts of a coded column's dictionary (a panic if the column is not coded).
fn dictionary(column: &ArrayRef) -> Vec<String> {
    let d = column.as_any_dictionary_opt().expect("a coded column");
    texts(d.values().as_ref())
}

/// Runs the sweep of `scenario` (the default if empty) into `out`; returns its summary.
fn sweep(dir: &TempDir, scenario: &str, samples: &str, out: &str) -> String {
    let mut args = vec!["sweep", "--samples", samples, "--quiet", "--out", out];
    if !scenario.is_empty() {
        args.extend(["--scenario", scenario]);
    }
    let run = touchdown(dir.path(), &args);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    run.stdout
}

#[test]
fn outcome_and_limits_are_coded_into_one_dictionary_of_every_text() {
    let dir = TempDir::new("lean_coded");
    dir.write("limits.toml", LIMITS);
    let coded = DataType::Dictionary(Box::new(DataType::Int8), Box::new(DataType::Utf8));
    // Written out, not taken from the code that writes them: a file's codes are its API.
    let outcomes = [
        "stable", "tipped", "sliding", "bouncing", "diverged", "held",
    ];
    let limits = ["axial_force", "side_force", "acceleration", "stroke_margin"];
    let sets: Vec<String> = (0..16)
        .map(|bits: usize| {
            let names = (0..4).filter(|i| bits & (1 << i) != 0).map(|i| limits[i]);
            names.collect::<Vec<_>>().join(",")
        })
        .collect();
    let mut read_back = Vec::new();
    let mut summary = String::new();
    // 20,000 rows: three batches of 8,192 rows, so the dictionary must hold across batches.
    for out in ["s.arrow", "s.parquet"] {
        summary = sweep(&dir, "limits.toml", "20000", out);
        let (schema, batches) = read(&dir.join(out));
        assert!(batches.len() >= 3, "{out}: {} batches", batches.len());
        for name in ["outcome", "limits_broken"] {
            assert_eq!(schema.field_with_name(name).unwrap().data_type(), &coded);
        }
        let (mut rows_outcome, mut rows_limits) = (Vec::new(), Vec::new());
        for b in &batches {
            let (o, l) = (&b["outcome"], &b["limits_broken"]);
            // Parquet keeps the texts and their type, not the dictionary: its reader makes
            // each row group's of the texts the row group holds.
            if out.ends_with(".arrow") {
                assert_eq!(
                    dictionary(o),
                    outcomes,
                    "{out}: the outcomes at their codes"
                );
                assert_eq!(
                    dictionary(l),
                    sets,
                    "{out}: the sets of limits at their bits"
                );
            }
            rows_outcome.extend(texts(o.as_ref()));
            rows_limits.extend(texts(l.as_ref()));
        }
        read_back.push((rows_outcome, rows_limits));
    }
    let (outcome, limits) = &read_back[0];
    assert_eq!(outcome.len(), 20_000);
    assert_eq!(
        read_back[0], read_back[1],
        "Arrow and Parquet hold the same texts"
    );
    // More than one code in each column: the codes are read as what they code.
    let distinct = |v: &[String]| v.iter().collect::<std::collections::BTreeSet<_>>().len();
    assert!(distinct(outcome) >= 2, "outcomes: {}", distinct(outcome));
    assert!(
        distinct(limits) >= 3,
        "sets of limits: {}",
        distinct(limits)
    );
    // The texts say what the sweep counted as it ran (its closing summary).
    for o in &outcomes[..5] {
        let n = outcome.iter().filter(|t| t == o).count();
        assert!(
            summary
                .lines()
                .any(|l| l.split_whitespace().take(2).eq([*o, &n.to_string()])),
            "{n} {o} in the file; the summary:\n{summary}"
        );
    }
}

#[test]
fn parquet_is_zstd_without_dictionaries_where_values_seldom_repeat_and_well_below_arrow() {
    use parquet::basic::{Compression, Encoding};
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let dir = TempDir::new("lean_parquet");
    sweep(&dir, "", "3000", "s.arrow");
    sweep(&dir, "", "3000", "s.parquet");
    let file = std::fs::File::open(dir.join("s.parquet")).unwrap();
    let meta = SerializedFileReader::new(file).unwrap().metadata().clone();
    let (schema, _) = read(&dir.join("s.arrow"));
    let mut floats = 0;
    for rg in meta.row_groups() {
        for c in rg.columns() {
            let name = c.column_path().string();
            assert!(
                matches!(c.compression(), Compression::ZSTD(_)),
                "{name}: {:?}",
                c.compression()
            );
            let has_dictionary = c.dictionary_page_offset().is_some()
                || c.encodings().any(|e| e == Encoding::RLE_DICTIONARY);
            match schema.field_with_name(&name).unwrap().data_type() {
                DataType::Float64 | DataType::UInt64 => {
                    floats += 1;
                    assert!(!has_dictionary, "{name}: a dictionary");
                }
                DataType::Dictionary(..) | DataType::UInt32 => {
                    assert!(has_dictionary, "{name}: no dictionary");
                }
                _ => {}
            }
        }
    }
    assert!(
        floats > 50,
        "{floats} chunks of floating-point or 64-bit columns"
    );
    // Measured: 0.58 of the Arrow file at 3,000 samples (0.57 at 1e5). The encoding before
    // (snappy, a dictionary on every column) gave 0.72, so the bound tells the two apart.
    let size = |f: &str| std::fs::metadata(dir.join(f)).unwrap().len() as f64;
    let ratio = size("s.parquet") / size("s.arrow");
    assert!(ratio < 0.65, "Parquet at {ratio:.3} of the Arrow file");
}

#[test]
fn files_whose_text_columns_are_plain_read_as_before() {
    let dir = TempDir::new("lean_plain");
    dir.write("limits.toml", LIMITS);
    sweep(&dir, "limits.toml", "3000", "coded.arrow");
    plain_copy(&dir.join("coded.arrow"), &dir.join("plain.arrow"));
    let (schema, _) = read(&dir.join("plain.arrow"));
    assert_eq!(
        schema.field_with_name("outcome").unwrap().data_type(),
        &DataType::Utf8
    );
    let report = |f: &str| {
        let run = touchdown(dir.path(), &["report", f]);
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        run.stdout.replace(f, "SWEEP")
    };
    let coded = report("coded.arrow");
    assert!(coded.contains("within limits"), "{coded}");
    assert_eq!(report("plain.arrow"), coded);
    let compare = touchdown(dir.path(), &["compare", "coded.arrow", "plain.arrow"]);
    assert_eq!(compare.code, Some(0), "{}", compare.stderr);
    let envelope = |f: &str| {
        let stem = f.trim_end_matches(".arrow");
        let run = touchdown(dir.path(), &["envelope", f, "--out-dir", stem]);
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        run.stdout.replace(stem, "SWEEP")
    };
    assert_eq!(envelope("plain.arrow"), envelope("coded.arrow"));
    assert_eq!(
        std::fs::read(dir.join("plain/plain-envelope.csv")).unwrap(),
        std::fs::read(dir.join("coded/coded-envelope.csv")).unwrap()
    );
}

#[test]
fn shards_written_before_the_coded_outcome_merge_with_new_ones_into_one_process_bytes() {
    let dir = TempDir::new("lean_merge");
    dir.write("limits.toml", LIMITS);
    // 20,000 samples: shards of several batches, merged into re-cut batches.
    for out in ["whole.arrow", "whole.parquet"] {
        sweep(&dir, "limits.toml", "20000", out);
    }
    // Shards 0 and 1 as Arrow, shard 2 as Parquet (whose reader makes a dictionary per row
    // group); shard 1 then as a build before the coded outcome wrote it.
    for (shard, out) in [
        ("0/3", "s0.arrow"),
        ("1/3", "s1.arrow"),
        ("2/3", "s2.parquet"),
    ] {
        let args = ["sweep", "--scenario", "limits.toml", "--samples", "20000"];
        let run = touchdown(
            dir.path(),
            &[&args[..], &["--quiet", "--shard", shard, "--out", out]].concat(),
        );
        assert_eq!(run.code, Some(0), "{}", run.stderr);
    }
    plain_copy(&dir.join("s1.arrow"), &dir.join("p1.arrow"));
    for (out, whole) in [("m.arrow", "whole.arrow"), ("m.parquet", "whole.parquet")] {
        let run = touchdown(
            dir.path(),
            &["merge", "s0.arrow", "p1.arrow", "s2.parquet", "--out", out],
        );
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        assert!(
            std::fs::read(dir.join(out)).unwrap() == std::fs::read(dir.join(whole)).unwrap(),
            "{out} is not the bytes of {whole}"
        );
    }
}
