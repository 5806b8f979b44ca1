//! A table of a sweep's input columns, replayed, gives that sweep's rows (every column, bit
//! for bit), in CSV, Arrow and Parquet, in any row order given the seeds; values the table
//! does not give are drawn as the scenario draws them.

use super::{
    SCENARIO, assert_same_columns, input_columns, metadata, read_sweep, select, take, write_arrow,
    write_csv, write_parquet,
};
use crate::common::{TempDir, read_bytes, touchdown};
use arrow_array::{Array, ArrayRef, Float64Array, RecordBatch, UInt64Array};
use std::sync::Arc;

#[test]
fn a_replayed_table_gives_the_rows_of_the_sweep_it_came_from() {
    let dir = TempDir::new("inputs-replay");
    dir.write("s.toml", SCENARIO);
    let sweep = |args: &[&str]| {
        let run = touchdown(
            dir.path(),
            &[&["sweep", "--scenario", "s.toml", "--quiet"], args].concat(),
        );
        assert_eq!(run.code, Some(0), "{run}");
    };
    sweep(&["--samples", "600", "--out", "a.arrow"]);
    let a = read_sweep(&dir.join("a.arrow"));
    let outcomes = crate::common::texts(a.column_by_name("outcome").unwrap().as_ref())
        .into_iter()
        .collect::<std::collections::BTreeSet<_>>();
    assert!(outcomes.len() >= 2, "one outcome only: {outcomes:?}");
    let names = input_columns(&a);
    // The 12 inputs and the 4 drawn parameters.
    assert_eq!(names.len(), 16, "{names:?}");
    let table = select(&a, &names);
    write_csv(&dir.join("in.csv"), &table);
    write_arrow(&dir.join("in.arrow"), &table);
    write_parquet(&dir.join("in.parquet"), &table);
    for (t, out) in [
        ("in.csv", "b.arrow"),
        ("in.arrow", "c.arrow"),
        ("in.parquet", "d.parquet"),
    ] {
        sweep(&["--inputs", t, "--out", out]);
        let b = read_sweep(&dir.join(out));
        // Every column: sample, seed, inputs, terrain, every result, the parameters.
        assert_eq!(b.num_columns(), a.num_columns());
        assert_same_columns(&a, &b, &[], &format!("{t} replayed"));
        assert_eq!(
            metadata(&dir.join(out), "touchdown.inputs.sha256").as_deref(),
            Some(touchdown::table::sha256_hex(&read_bytes(&dir.join(t))).as_str()),
            "{t}: the table's SHA-256 in the file's metadata"
        );
    }

    // Some rows, backwards, with their seeds and terrain: each replayed row is the row it
    // came from (but for its place, the `sample` column).
    let rows: Vec<u64> = (0..600).rev().step_by(7).collect();
    let with_seeds = [
        &["sample_seed"][..],
        &names,
        &["terrain_tile", "terrain_offset_u_m", "terrain_offset_v_m"],
    ]
    .concat();
    write_csv(
        &dir.join("some.csv"),
        &take(&select(&a, &with_seeds), &rows),
    );
    sweep(&["--inputs", "some.csv", "--out", "some.arrow"]);
    let some = read_sweep(&dir.join("some.arrow"));
    assert_same_columns(&take(&a, &rows), &some, &["sample"], "rows backwards");
    let samples = some.column_by_name("sample").unwrap();
    let expected: ArrayRef = Arc::new(UInt64Array::from_iter_values(0..rows.len() as u64));
    assert_eq!(samples.to_data(), expected.to_data());

    // A trace of a row runs its table's values: the row's seed, inputs and parameters.
    let run = touchdown(
        dir.path(),
        &[
            "trace",
            "--sweep",
            "some.arrow",
            "--sample",
            "3",
            "--out",
            "t.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    let trace_meta = |k: &str| {
        let r = arrow_ipc::reader::FileReader::try_new(
            std::fs::File::open(dir.join("t.arrow")).unwrap(),
            None,
        )
        .unwrap();
        r.schema().metadata().get(k).cloned().unwrap()
    };
    let f64_at = |b: &RecordBatch, name: &str, row: usize| {
        b.column_by_name(name)
            .unwrap()
            .as_any()
            .downcast_ref::<Float64Array>()
            .unwrap()
            .value(row)
    };
    let source = rows[3] as usize;
    let seed = a
        .column_by_name("sample_seed")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt64Array>()
        .unwrap()
        .value(source);
    assert_eq!(trace_meta("touchdown.sample_seed"), seed.to_string());
    for name in ["slope_deg", "yaw_deg"] {
        assert_eq!(
            trace_meta(&format!("touchdown.input.{name}")),
            f64_at(&a, name, source).to_string()
        );
    }
    assert_eq!(
        trace_meta("touchdown.parameter.friction_coefficient"),
        f64_at(&a, "friction_coefficient", source).to_string()
    );
    let outcome = &crate::common::texts(a.column_by_name("outcome").unwrap().as_ref())[source];
    assert_eq!(&trace_meta("touchdown.outcome"), outcome);
}

#[test]
fn values_a_table_does_not_give_are_drawn_as_the_scenario_draws_them() {
    // A table that gives every sample a 10 deg slope and nothing else runs as the scenario
    // with the slope fixed at 10 deg: the other inputs, the parameters and the terrain are
    // drawn by row index, as without a table (common random numbers).
    let dir = TempDir::new("inputs-partial");
    dir.write("s.toml", SCENARIO);
    dir.write(
        "fixed.toml",
        &format!("{SCENARIO}[inputs]\nslope_deg = 10.0\n"),
    );
    dir.write("slope.csv", &format!("slope_deg\n{}", "10\n".repeat(300)));
    for (args, out) in [
        (
            &["--scenario", "s.toml", "--inputs", "slope.csv"][..],
            "table.arrow",
        ),
        (
            &["--scenario", "fixed.toml", "--samples", "300"],
            "fixed.arrow",
        ),
    ] {
        let run = touchdown(
            dir.path(),
            &[&["sweep", "--quiet", "--out", out], args].concat(),
        );
        assert_eq!(run.code, Some(0), "{run}");
    }
    let (t, f) = (
        read_sweep(&dir.join("table.arrow")),
        read_sweep(&dir.join("fixed.arrow")),
    );
    assert_same_columns(&f, &t, &[], "slope from the table against slope fixed");
}
