//! Shards, merge, threads and `--keep-columns` behave for a table's sweep as for any sweep;
//! shards of another table do not merge.

use super::{assert_same_columns, read_sweep};
use crate::common::{TempDir, read_bytes, touchdown};
use arrow_array::{Array, Float64Array, StringArray};

/// A table of 5,000 samples of the default scenario with two columns the sweep does not
/// know: a label and a weight.
fn labelled_table(dir: &TempDir) {
    let mut text = String::from("slope_deg,case,yaw_deg,weight\n");
    for i in 0..5000 {
        let slope = f64::from(i % 400) * 0.1;
        let yaw = f64::from(i * 37 % 360);
        text.push_str(&format!(
            "{slope},case {},{yaw},{}\n",
            i % 3,
            0.5 + f64::from(i % 5)
        ));
    }
    dir.write("in.csv", &text);
}

#[test]
fn table_sweeps_shard_merge_and_keep_columns_like_any_sweep() {
    let dir = TempDir::new("inputs-shards");
    labelled_table(&dir);
    dir.write("s.toml", "[simulation]\nt_max_s = 10.0\n");
    let sweep = |args: &[&str]| {
        let run = touchdown(
            dir.path(),
            &[
                &[
                    "sweep",
                    "--scenario",
                    "s.toml",
                    "--inputs",
                    "in.csv",
                    "--quiet",
                ],
                args,
            ]
            .concat(),
        );
        assert_eq!(run.code, Some(0), "{run}");
        run
    };
    // Unknown columns are refused by name without --keep-columns.
    let run = touchdown(
        dir.path(),
        &["sweep", "--inputs", "in.csv", "--out", "x.arrow"],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("unknown column case"), "{run}");
    assert!(!dir.join("x.arrow").exists());

    sweep(&["--keep-columns", "--out", "one.arrow", "--threads", "1"]);
    sweep(&["--keep-columns", "--out", "two.arrow", "--threads", "2"]);
    assert!(
        read_bytes(&dir.join("one.arrow")) == read_bytes(&dir.join("two.arrow")),
        "1 and 2 threads give different files"
    );
    let one = read_sweep(&dir.join("one.arrow"));
    assert_eq!(one.num_rows(), 5000);
    // The kept columns come last, as the table has them.
    let fields = one.schema().fields().clone();
    let last: Vec<&str> = fields[fields.len() - 2..]
        .iter()
        .map(|f| f.name().as_str())
        .collect();
    assert_eq!(last, ["case", "weight"]);
    let case = one
        .column_by_name("case")
        .unwrap()
        .as_any()
        .downcast_ref::<StringArray>()
        .unwrap();
    let weight = one
        .column_by_name("weight")
        .unwrap()
        .as_any()
        .downcast_ref::<Float64Array>()
        .unwrap();
    let slope = one
        .column_by_name("slope_deg")
        .unwrap()
        .as_any()
        .downcast_ref::<Float64Array>()
        .unwrap();
    for i in 0..5000 {
        assert_eq!(case.value(i), format!("case {}", i % 3));
        assert_eq!(weight.value(i), 0.5 + (i % 5) as f64);
        assert_eq!(slope.value(i), (i % 400) as f64 * 0.1);
    }

    // Three shards merged: the file of one process, byte for byte; in Parquet too.
    for k in 0..3 {
        sweep(&[
            "--keep-columns",
            "--shard",
            &format!("{k}/3"),
            "--out",
            &format!("s{k}.arrow"),
        ]);
    }
    let run = touchdown(
        dir.path(),
        &[
            "merge",
            "s2.arrow",
            "s0.arrow",
            "s1.arrow",
            "--out",
            "merged.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(
        read_bytes(&dir.join("merged.arrow")) == read_bytes(&dir.join("one.arrow")),
        "merged shards differ from one process"
    );
    sweep(&["--keep-columns", "--out", "one.parquet"]);
    assert_same_columns(&one, &read_sweep(&dir.join("one.parquet")), &[], "Parquet");

    // --samples N runs the first N rows.
    sweep(&["--keep-columns", "--samples", "100", "--out", "first.arrow"]);
    let first = read_sweep(&dir.join("first.arrow"));
    assert_same_columns(&one.slice(0, 100), &first, &[], "the first 100 rows");

    // Shards of another table (one changed value) do not merge.
    let text = std::fs::read_to_string(dir.join("in.csv")).unwrap();
    dir.write("in.csv", &text.replacen("case 0", "case 9", 1));
    sweep(&["--keep-columns", "--shard", "0/3", "--out", "other0.arrow"]);
    let run = touchdown(
        dir.path(),
        &[
            "merge",
            "other0.arrow",
            "s1.arrow",
            "s2.arrow",
            "--out",
            "m2.arrow",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("table of inputs"), "{run}");
    assert!(!dir.join("m2.arrow").exists());
    // Nor does a trace of the first sweep take the changed table.
    let run = touchdown(
        dir.path(),
        &[
            "trace",
            "--sweep",
            "one.arrow",
            "--sample",
            "1",
            "--out",
            "t.arrow",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("is not the table of inputs"), "{run}");
    assert!(!dir.join("t.arrow").exists());
}
