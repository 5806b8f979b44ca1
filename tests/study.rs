//! `touchdown study`: its table equals what `touchdown report` says of separate sweeps at
//! the same values; it shards, merges and resumes like a sweep; bad studies are refused.

use crate::common::{
    BadInput, TempDir, bad_args, check_bad_input, read_bytes, set_down_lines, touchdown,
};
use arrow_array::{Array, Float64Array, RecordBatch, UInt64Array};
use std::path::Path;

/// Landers set down (drops of at most 1 cm, no velocity or rate errors, attitude errors of
/// 2 deg) on a gripping surface: the footpad radius moves the allowable slope of every
/// sector (none at 0.4 m, about 37 deg at 0.6 m, about 51 deg at 0.8 m), so the table has
/// both kinds of cells. About 1,500 samples/s.
const SET_DOWN: &str = concat!(
    "seed = 1
[surface]
friction_coefficient = 1.5
[inputs]
slope_deg = { dist = \"uniform\", min = 0.0, max = 60.0 }
yaw_deg = { dist = \"uniform\", min = 0.0, max = 360.0 }
",
    set_down_lines!(
        "{ dist = \"uniform\", min = 0.0, max = 0.01 }",
        "{ dist = \"normal\", mean = 0.0, sd = 2.0 }"
    ),
    "[initial]
attitude_reference = \"surface\"
[simulation]
t_max_s = 20.0
"
);

const VALUES: [&str; 3] = ["0.4", "0.6", "0.8"];
const FILES: [&str; 3] = [
    "00-footpad_radius_m-0.4.arrow",
    "01-footpad_radius_m-0.6.arrow",
    "02-footpad_radius_m-0.8.arrow",
];

/// An Arrow file as one batch.
fn read_arrow(path: &Path) -> RecordBatch {
    let file = std::fs::File::open(path).unwrap();
    let r = arrow_ipc::reader::FileReader::try_new(file, None).unwrap();
    let schema = r.schema();
    let batches: Vec<RecordBatch> = r.collect::<Result<_, _>>().unwrap();
    arrow_select::concat::concat_batches(&schema, &batches).unwrap()
}

/// The study's number in `column` at `row` (`None`: null).
fn number(b: &RecordBatch, column: &str, row: usize) -> Option<f64> {
    let c = b
        .column_by_name(column)
        .unwrap_or_else(|| panic!("the study table has no column {column}"));
    if c.is_null(row) {
        return None;
    }
    if let Some(f) = c.as_any().downcast_ref::<Float64Array>() {
        return Some(f.value(row));
    }
    let u = c.as_any().downcast_ref::<UInt64Array>().unwrap();
    Some(u.value(row) as f64)
}

fn study(dir: &TempDir, out: &str, extra: &[&str]) -> crate::common::Run {
    let args = [
        &[
            "study",
            "--scenario",
            "s.toml",
            "--vary",
            "lander.footpad_radius_m=0.4:0.8:3",
            "--samples",
            "4000",
            "--seed",
            "5",
            "--out-dir",
            out,
            "--quiet",
        ][..],
        extra,
    ]
    .concat();
    touchdown(dir.path(), &args)
}

#[test]
fn a_study_equals_separate_sweeps_at_its_values() {
    let dir = TempDir::new("study");
    dir.write("s.toml", SET_DOWN);
    let run = study(&dir, "st", &[]);
    run.assert_ok();
    assert!(
        run.stdout
            .contains("# touchdown study: lander.footpad_radius_m")
    );
    let listed: Vec<String> = std::fs::read_dir(dir.join("st"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    for f in FILES
        .iter()
        .chain(&["study.arrow", "study.md", "study.png"])
    {
        assert!(listed.iter().any(|l| l == f), "{f} not in {listed:?}");
    }
    assert_eq!(listed.len(), 6, "{listed:?}");
    let table = read_arrow(&dir.join("st/study.arrow"));
    assert_eq!(table.num_rows(), 3);
    let mut slopes_seen = 0;
    for (i, value) in VALUES.iter().enumerate() {
        assert_eq!(
            number(&table, "lander.footpad_radius_m", i),
            Some(value.parse().unwrap())
        );
        // The same value by hand: the scenario file with the key written in, swept alone.
        let name = format!("v{i}");
        dir.write(
            &format!("{name}.toml"),
            &format!("{SET_DOWN}[lander]\nfootpad_radius_m = {value}\n"),
        );
        let sweep = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                &format!("{name}.toml"),
                "--samples",
                "4000",
                "--seed",
                "5",
                "--out",
                &format!("{name}.arrow"),
                "--quiet",
            ],
        );
        assert_eq!(sweep.code, Some(0), "{sweep}");
        // Every row of the study's sweep file is the separate sweep's (only the scenario
        // text in the metadata differs: the study writes its key into the parsed file).
        let (a, b) = (
            read_arrow(&dir.join("st").join(FILES[i])),
            read_arrow(&dir.join(&format!("{name}.arrow"))),
        );
        assert_eq!(a.schema().fields(), b.schema().fields());
        assert_eq!(a.columns(), b.columns(), "value {value}: rows differ");
        // Its line of the table is what `touchdown report` says of the separate sweep, to
        // the report's digits.
        let report = touchdown(dir.path(), &["report", &format!("{name}.arrow")]);
        report.assert_ok();
        for line in report.stdout.lines() {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            if cells.len() == 6
                && ["stable", "tipped", "sliding", "bouncing", "diverged"].contains(&cells[1])
            {
                let o = cells[1];
                let count = number(&table, o, i).unwrap();
                assert_eq!(format!("{count}"), cells[2], "{value} {o} count");
                let share = number(&table, &format!("{o}_share"), i).unwrap();
                assert_eq!(share, count / 4000.0, "{value} {o} share");
                // As the report rounds it (100 k / n, not 100 (k / n)).
                assert_eq!(
                    format!("{:.2} %", 100.0 * count / 4000.0),
                    cells[3],
                    "{value} {o}"
                );
                let (lo, hi) = (
                    number(&table, &format!("{o}_low"), i).unwrap(),
                    number(&table, &format!("{o}_high"), i).unwrap(),
                );
                assert_eq!(
                    format!("{:.2} – {:.2} %", 100.0 * lo, 100.0 * hi),
                    cells[4],
                    "{value} {o} interval"
                );
            }
            if cells.len() == 7 && cells[1].ends_with(" deg") && cells[1].contains('–') {
                // | 0–45 deg | samples | stable | allowable | interval |
                let sector = cells[1].trim_end_matches(" deg").replace('–', "_");
                let column = format!("allowable_slope_{sector}_deg");
                let (s, lo, hi) = (
                    number(&table, &column, i),
                    number(&table, &format!("allowable_slope_{sector}_low_deg"), i),
                    number(&table, &format!("allowable_slope_{sector}_high_deg"), i),
                );
                match s {
                    Some(s) => {
                        slopes_seen += 1;
                        assert_eq!(format!("{s:.1} deg"), cells[4], "{value} {column}");
                        assert_eq!(
                            format!("{:.1}–{:.1} deg", lo.unwrap(), hi.unwrap()),
                            cells[5],
                            "{value} {column} interval"
                        );
                    }
                    None => {
                        assert!(cells[4].starts_with("no slope"), "{value} {column}: {line}");
                        assert_eq!(
                            format!("0.0–{:.1} deg", hi.unwrap()),
                            cells[5],
                            "{value} {column} bound"
                        );
                    }
                }
            }
        }
    }
    // The scenario gives both kinds of cells: 8 sectors with a slope at 0.6 and 0.8 m.
    assert_eq!(slopes_seen, 16, "allowable slopes in the table");

    // The same command again keeps every sweep and writes the same table.
    let before = read_bytes(&dir.join("st/study.arrow"));
    let again = study(&dir, "st", &[]);
    again.assert_ok();
    assert_eq!(
        again.stdout.matches("kept (done before)").count(),
        3,
        "{again}"
    );
    assert!(read_bytes(&dir.join("st/study.arrow")) == before);

    // Sharded in two, then merged by the command without --shard: the same files.
    for k in ["0/2", "1/2"] {
        let shard = study(&dir, "sh", &["--shard", k]);
        shard.assert_ok();
        assert!(
            shard.stdout.contains("once all 2 shards are done"),
            "{shard}"
        );
    }
    assert!(!dir.join("sh/study.arrow").exists());
    let merged = study(&dir, "sh", &[]);
    merged.assert_ok();
    assert_eq!(
        merged.stdout.matches("merged from 2 shards").count(),
        3,
        "{merged}"
    );
    for f in FILES.iter().chain(&["study.arrow", "study.md"]) {
        assert!(
            read_bytes(&dir.join("sh").join(f)) == read_bytes(&dir.join("st").join(f)),
            "sharded {f} differs"
        );
    }
}

#[test]
fn an_interrupted_study_continues_where_it_stopped() {
    let dir = TempDir::new("study-interrupt");
    // Flights cut at 5 s, about 60,000 samples/s: 150,000 per value run for seconds.
    dir.write("s.toml", "[simulation]\nt_max_s = 5.0\n");
    let args = [
        "study",
        "--scenario",
        "s.toml",
        "--vary",
        "lander.cg_height_m=0.4:0.5:2",
        "--samples",
        "150000",
        "--out-dir",
        "st",
        "--quiet",
    ];
    let (code, stderr) =
        crate::interrupt::interrupt(&dir, &args, "st/00-cg_height_m-0.4.arrow", "INT");
    assert_eq!(code, Some(130), "{stderr}");
    assert!(
        stderr.contains("continue with: the same touchdown study command again"),
        "{stderr}"
    );
    assert!(dir.join("st/00-cg_height_m-0.4.arrow.interrupted").exists());
    assert!(!dir.join("st/study.arrow").exists());
    let resumed = touchdown(dir.path(), &args);
    resumed.assert_ok();
    assert!(resumed.stdout.contains("resumed: "), "{resumed}");
    let whole = touchdown(
        dir.path(),
        &[&args[..7], &["--out-dir", "whole", "--quiet"]].concat(),
    );
    whole.assert_ok();
    for f in [
        "00-cg_height_m-0.4.arrow",
        "01-cg_height_m-0.5.arrow",
        "study.arrow",
        "study.md",
    ] {
        assert!(
            read_bytes(&dir.join("st").join(f)) == read_bytes(&dir.join("whole").join(f)),
            "resumed {f} differs from the uninterrupted study's"
        );
    }
    assert!(!dir.join("st/00-cg_height_m-0.4.arrow.interrupted").exists());
}

#[test]
fn bad_studies_are_refused_with_the_reason() {
    const CASES: &[BadInput] = &[
        bad_args("no --vary", &["--samples", "10"], &["--vary"]),
        bad_args(
            "no equals sign",
            &["--vary", "lander.footpad_radius_m"],
            &["no '='"],
        ),
        bad_args("seed", &["--vary", "seed=1:2:2"], &["not a key to vary"]),
        bad_args(
            "unknown key",
            &["--vary", "lander.footpad_radius_mm=0.5:0.6:2"],
            &["footpad_radius_mm", "did you mean `footpad_radius_m`"],
        ),
        bad_args(
            "a value the scenario refuses",
            &["--vary", "lander.footpad_radius_m=-0.5:0.6:2"],
            &["at lander.footpad_radius_m = -0.5"],
        ),
        // (A distribution, `inputs.slope_deg`, takes the value in its place.)
        bad_args(
            "a table",
            &["--vary", "surface.roughness=1:2:2"],
            &["table of settings", "surface.roughness"],
        ),
        bad_args(
            "a fraction where a whole number goes",
            &["--vary", "lander.legs=3:4:3"],
            &["lander.legs", "3.5 is not one"],
        ),
        bad_args(
            "zero samples",
            &["--vary", "lander.legs=3:4:2", "--samples", "0"],
            &["--samples must be at least 1"],
        ),
    ];
    let mut problems = Vec::new();
    for case in CASES {
        for p in check_bad_input("study", case, &["touchdown study:"]) {
            problems.push(format!("{}: {p}", case.name));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));

    // A folder holding another study's sweep at a value: refused, the file left alone.
    let dir = TempDir::new("study-foreign");
    dir.write("s.toml", "[simulation]\nt_max_s = 5.0\n");
    let args = |seed: &'static str| {
        [
            "study",
            "--scenario",
            "s.toml",
            "--vary",
            "lander.cg_height_m=0.4:0.5:2",
            "--samples",
            "200",
            "--seed",
            seed,
            "--quiet",
        ]
    };
    touchdown(dir.path(), &args("1")).assert_ok();
    let before = read_bytes(&dir.join("study/00-cg_height_m-0.4.arrow"));
    let other = touchdown(dir.path(), &args("2"));
    assert_eq!(other.code, Some(2), "{other}");
    assert!(
        other
            .stderr
            .contains("holds another study (lander.cg_height_m = 0.4:0.5:2, seed 1"),
        "{other}"
    );
    assert!(read_bytes(&dir.join("study/00-cg_height_m-0.4.arrow")) == before);
    // A shard missing.
    let shard = touchdown(
        dir.path(),
        &[&args("3")[..], &["--out-dir", "sh", "--shard", "0/2"]].concat(),
    );
    shard.assert_ok();
    let missing = touchdown(dir.path(), &[&args("3")[..], &["--out-dir", "sh"]].concat());
    assert_eq!(missing.code, Some(2), "{missing}");
    assert!(missing.stderr.contains("lacks shard 1/2"), "{missing}");
    // Shards of two counts: which to keep is the user's to say.
    touchdown(
        dir.path(),
        &[&args("3")[..], &["--out-dir", "sh", "--shard", "2/3"]].concat(),
    )
    .assert_ok();
    let mixed = touchdown(dir.path(), &[&args("3")[..], &["--out-dir", "sh"]].concat());
    assert_eq!(mixed.code, Some(2), "{mixed}");
    assert!(
        mixed.stderr.contains(
            "holds shards of the sweep at lander.cg_height_m = 0.4 cut 2 and 3 ways: keep those \
             of one --shard count"
        ),
        "{mixed}"
    );
    // --out-dir a file.
    dir.write("f", "x");
    let file = touchdown(dir.path(), &[&args("1")[..], &["--out-dir", "f"]].concat());
    assert_eq!(file.code, Some(2), "{file}");
    assert!(
        file.stderr.contains("that is a file, not a folder"),
        "{file}"
    );
}
