//! Bad tables are refused before any work, naming row and column.

use crate::common::{TempDir, touchdown};
use arrow_array::{Array, ArrayRef, Float64Array, RecordBatch, StringArray};
use arrow_schema::{Field, Schema};
use parquet::arrow::ArrowWriter;
use std::sync::Arc;

/// One bad table: its file name and bytes, further arguments, and what the error says.
struct BadTable {
    name: &'static str,
    file: &'static str,
    bytes: Vec<u8>,
    args: &'static [&'static str],
    expect: &'static [&'static str],
}

fn csv(name: &'static str, text: &str, expect: &'static [&'static str]) -> BadTable {
    BadTable {
        name,
        file: "in.csv",
        bytes: text.as_bytes().to_vec(),
        args: &[],
        expect,
    }
}

fn parquet(name: &'static str, b: &RecordBatch, expect: &'static [&'static str]) -> BadTable {
    let mut bytes = Vec::new();
    let mut w = ArrowWriter::try_new(&mut bytes, b.schema(), None).unwrap();
    w.write(b).unwrap();
    w.close().unwrap();
    BadTable {
        name,
        file: "in.parquet",
        bytes,
        args: &[],
        expect,
    }
}

fn one_column(name: &str, a: ArrayRef) -> RecordBatch {
    RecordBatch::try_new(
        Arc::new(Schema::new(vec![Field::new(
            name,
            a.data_type().clone(),
            true,
        )])),
        vec![a],
    )
    .unwrap()
}

#[test]
fn bad_tables_are_refused_before_any_work_naming_row_and_column() {
    let mut cases = vec![
        csv(
            "not a number",
            "slope_deg,yaw_deg\n1,2\n3,4\nabc,5\n",
            &[
                "in.csv: row 2 (line 4), column slope_deg",
                "\"abc\" is not a number",
            ],
        ),
        csv(
            "NaN",
            "slope_deg,yaw_deg\n1,2\n3,NaN\n",
            &[
                "row 1 (line 3), column yaw_deg",
                "NaN is not a finite number",
            ],
        ),
        csv(
            "empty cell",
            "slope_deg,yaw_deg\n1,2\n,4\n",
            &["row 1 (line 3), column slope_deg", "empty"],
        ),
        csv(
            "slope out of range",
            "slope_deg\n10\n20\n95\n",
            &[
                "row 2 (line 4), column slope_deg",
                "95 is out of range",
                "90 deg",
            ],
        ),
        csv(
            "negative friction",
            "friction_coefficient\n0.5\n-0.1\n",
            &["row 1 (line 3), column friction_coefficient", "at least 0"],
        ),
        csv(
            "zero mass",
            "mass_kg\n0\n",
            &["row 0 (line 2), column mass_kg", "greater than 0"],
        ),
        csv(
            "unknown column",
            "slope_deg,slop_deg\n1,2\n",
            &["unknown column slop_deg", "--keep-columns"],
        ),
        csv(
            "a result column",
            "slope_deg,outcome\n1,stable\n",
            &["column outcome is a result of a sweep"],
        ),
        csv(
            "a column twice",
            "slope_deg,yaw_deg,slope_deg\n1,2,3\n",
            &["column slope_deg appears twice"],
        ),
        csv(
            "sample numbers not the rows",
            "sample,slope_deg\n0,1\n5,2\n",
            &["row 1 (line 3), column sample", "holds 5"],
        ),
        csv(
            "a row too short",
            "slope_deg,yaw_deg\n1,2\n3\n",
            &["line 3 has 1 fields, the header 2"],
        ),
        csv("no rows", "slope_deg,yaw_deg\n", &["the table has no rows"]),
        csv(
            "a blank line (an empty value in a one-column table)",
            "slope_deg\n1\n\n3\n",
            &["in.csv: line 3 is blank"],
        ),
        csv(
            "a seed written as a float",
            "sample_seed\n12.5\n",
            &["column sample_seed", "not a whole number"],
        ),
        csv(
            "a seed below 0",
            "sample_seed\n-1\n",
            &["column sample_seed", "-1 is not a seed"],
        ),
        csv(
            "a terrain tile on a flat surface",
            "terrain_tile\n0\n2\n",
            &["row 1, column terrain_tile", "the surface is flat"],
        ),
        csv(
            "a crush strength without dampers",
            "crush_strength_psi\n10\n",
            &[
                "column crush_strength_psi (damper.crush_strength_psi)",
                "damper.enabled = false",
            ],
        ),
        parquet(
            "text in a Parquet column",
            &one_column(
                "slope_deg",
                Arc::new(StringArray::from(vec!["1.0", "steep"])),
            ),
            &[
                "in.parquet: row 1, column slope_deg",
                "\"steep\" is not a number",
            ],
        ),
        parquet(
            "booleans in a Parquet column",
            &one_column(
                "yaw_deg",
                Arc::new(arrow_array::BooleanArray::from(vec![true, false])),
            ),
            &["column yaw_deg is of type Boolean"],
        ),
        parquet(
            "a null in a Parquet column",
            &one_column(
                "yaw_deg",
                Arc::new(Float64Array::from(vec![Some(1.0), None, Some(2.0)])),
            ),
            &["in.parquet: row 1, column yaw_deg", "empty"],
        ),
    ];
    cases.push(BadTable {
        args: &["--samples", "3"],
        ..csv(
            "more samples than rows",
            "slope_deg\n1\n2\n",
            &["--samples 3", "has 2 rows"],
        )
    });
    cases.push(BadTable {
        args: &["--design", "sobol-indices"],
        ..csv(
            "Saltelli's design",
            "slope_deg\n1\n2\n",
            &["sobol-indices", "a table gives each sample its own row"],
        )
    });
    cases.push(BadTable {
        file: "in.bin",
        bytes: vec![0x80, 0x81, 0x00, 0x01],
        ..csv(
            "not a table",
            "",
            &["in.bin is neither Parquet, Arrow nor CSV"],
        )
    });

    let mut problems = Vec::new();
    for case in &cases {
        let dir = TempDir::new("bad-table");
        std::fs::write(dir.join(case.file), &case.bytes).unwrap();
        let before = dir.entries();
        let run = touchdown(
            dir.path(),
            &[
                &["sweep", "--inputs", case.file, "--out", "out.arrow"],
                case.args,
            ]
            .concat(),
        );
        let mut wrong = Vec::new();
        if run.code != Some(2) {
            wrong.push(format!("exit code {:?}", run.code));
        }
        for s in case.expect {
            if !run.stderr.contains(s) {
                wrong.push(format!("stderr lacks {s:?}"));
            }
        }
        for s in ["panicked", "touchdown sweep:"] {
            if run.stderr.contains(s) {
                wrong.push(format!("stderr has {s:?}"));
            }
        }
        if dir.entries() != before {
            wrong.push(format!("files: {:?}", dir.entries()));
        }
        if !wrong.is_empty() {
            problems.push(format!("{}: {}\n{run}", case.name, wrong.join("; ")));
        }
    }
    // A missing table, and --keep-columns without a table.
    let dir = TempDir::new("bad-table");
    for (args, expect) in [
        (
            &["sweep", "--inputs", "none.csv"][..],
            "cannot read the input table none.csv",
        ),
        (&["sweep", "--keep-columns"], "--inputs"),
    ] {
        let run = touchdown(dir.path(), args);
        if run.code != Some(2) || !run.stderr.contains(expect) {
            problems.push(format!("{args:?}: expected exit 2 and {expect:?}\n{run}"));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));
}
