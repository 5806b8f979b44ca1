//! `touchdown sweep --shard K/N` and `touchdown merge`: the shards of a sweep, run as
//! separate processes and merged, give the file of the sweep run in one process, byte for
//! byte; shards that do not belong together are refused with a message naming the files.

use crate::common::{TempDir, read_bytes, touchdown};

/// Flights cut at 5 s: the samples are cheap, and still of every outcome.
const SHORT: &str = "[simulation]\nt_max_s = 5.0\n";

/// More samples than two record batches (65,536 rows each), so that shard boundaries fall
/// inside batches and the merge has to cut batches as the one-process sweep does.
const SAMPLES: &str = "140000";

/// Runs `touchdown ARGS` in `dir` and panics unless it exits 0.
fn ok(dir: &TempDir, args: &[&str]) -> String {
    let run = touchdown(dir.path(), args);
    assert!(run.code == Some(0), "expected success of {run}");
    run.stdout
}

/// The outcome counts of a sweep's closing summary (`  name   count   pct %` lines).
fn outcome_counts(stdout: &str) -> Vec<(String, u64)> {
    stdout
        .lines()
        .filter(|l| l.starts_with("  ") && l.ends_with('%'))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w[0].to_string(), w[1].parse().expect("a count"))
        })
        .collect()
}

#[test]
fn merged_shards_are_the_one_process_sweep_byte_for_byte() {
    let dir = TempDir::new("shards-merge");
    dir.write("s.toml", SHORT);
    let base = [
        "sweep",
        "--scenario",
        "s.toml",
        "--samples",
        SAMPLES,
        "--quiet",
    ];
    let whole = ok(&dir, &[&base[..], &["--out", "whole.arrow"]].concat());

    // Three Arrow shards (uneven: 46,666 and 46,667 samples), merged out of order.
    let mut shard_counts: Vec<Vec<(String, u64)>> = Vec::new();
    for k in 0..3 {
        let (shard, out) = (format!("{k}/3"), format!("s{k}.arrow"));
        let stdout = ok(
            &dir,
            &[&base[..], &["--shard", &shard, "--out", &out]].concat(),
        );
        shard_counts.push(outcome_counts(&stdout));
    }
    let merged = ok(
        &dir,
        &[
            "merge", "s2.arrow", "s0.arrow", "s1.arrow", "--out", "m.arrow",
        ],
    );
    assert!(
        merged.contains("merged 3 shards, 140000 samples"),
        "merge summary: {merged}"
    );
    assert!(
        read_bytes(&dir.join("m.arrow")) == read_bytes(&dir.join("whole.arrow")),
        "the merged shards differ from the sweep run in one process"
    );

    // The shards' outcome counts add up to the whole sweep's.
    let whole_counts = outcome_counts(&whole);
    assert!(!whole_counts.is_empty(), "no outcome counts in {whole}");
    for (i, (name, count)) in whole_counts.iter().enumerate() {
        let sum: u64 = shard_counts
            .iter()
            .map(|c| {
                assert_eq!(&c[i].0, name, "outcome order of the summaries");
                c[i].1
            })
            .sum();
        assert_eq!(
            sum, *count,
            "{name}: shards add up to {sum}, the sweep has {count}"
        );
    }

    // Two Parquet shards merged into an Arrow file: the same bytes again.
    for k in 0..2 {
        let (shard, out) = (format!("{k}/2"), format!("p{k}.parquet"));
        ok(
            &dir,
            &[
                &base[..],
                &["--shard", &shard, "--format", "parquet", "--out", &out],
            ]
            .concat(),
        );
    }
    ok(
        &dir,
        &["merge", "p1.parquet", "p0.parquet", "--out", "mp.arrow"],
    );
    assert!(
        read_bytes(&dir.join("mp.arrow")) == read_bytes(&dir.join("whole.arrow")),
        "Parquet shards merged into Arrow differ from the sweep run in one process"
    );
}

#[test]
fn merge_refuses_shards_that_do_not_belong_together() {
    let dir = TempDir::new("shards-refused");
    dir.write("s.toml", SHORT);
    dir.write("other.toml", "[simulation]\nt_max_s = 6.0\n");
    // Shards of 300 samples unless the arguments say otherwise.
    let shard = |args: &[&str], out: &str| {
        let mut all = vec!["sweep", "--quiet", "--out", out];
        if !args.contains(&"--samples") {
            all.extend(["--samples", "300"]);
        }
        all.extend(args);
        ok(&dir, &all);
    };
    for k in 0..4 {
        shard(
            &["--scenario", "s.toml", "--shard", &format!("{k}/4")],
            &format!("s{k}.arrow"),
        );
    }
    shard(
        &["--scenario", "s.toml", "--shard", "3/4", "--seed", "2"],
        "seed2.arrow",
    );
    shard(
        &["--scenario", "other.toml", "--shard", "3/4"],
        "scenario.arrow",
    );
    shard(
        &["--scenario", "s.toml", "--shard", "3/4", "--samples", "400"],
        "count.arrow",
    );
    shard(&["--scenario", "s.toml", "--shard", "2/3"], "thirds.arrow");
    shard(&["--scenario", "s.toml"], "whole.arrow");
    ok(
        &dir,
        &["trace", "--scenario", "s.toml", "--out", "trace.arrow"],
    );
    let s1 = read_bytes(&dir.join("s1.arrow"));
    std::fs::write(dir.join("cut.arrow"), &s1[..s1.len() / 2]).unwrap();

    let cases: [(&str, &[&str], &[&str]); 11] = [
        (
            "another seed",
            &["s0.arrow", "s1.arrow", "s2.arrow", "seed2.arrow"],
            &[
                "s0.arrow and seed2.arrow",
                "seed differs",
                "\"1\" against \"2\"",
            ],
        ),
        (
            "another scenario",
            &["s0.arrow", "s1.arrow", "s2.arrow", "scenario.arrow"],
            &["s0.arrow and scenario.arrow", "scenario differs"],
        ),
        (
            "another sample count",
            &["s0.arrow", "s1.arrow", "s2.arrow", "count.arrow"],
            &[
                "count.arrow",
                "sample count differs",
                "\"300\" against \"400\"",
            ],
        ),
        (
            "another shard count",
            &["s0.arrow", "s1.arrow", "thirds.arrow", "s3.arrow"],
            &["thirds.arrow", "shard 0/4 against shard 2/3"],
        ),
        (
            "a missing shard",
            &["s0.arrow", "s1.arrow", "s3.arrow"],
            &["4 shards", "missing: 2/4"],
        ),
        (
            "a shard given twice",
            &["s0.arrow", "s1.arrow", "s2.arrow", "s3.arrow", "s1.arrow"],
            &["shard 1/4 is given twice"],
        ),
        (
            "a whole sweep",
            &["s0.arrow", "whole.arrow"],
            &["whole.arrow is a whole sweep, not a shard"],
        ),
        (
            "a trace",
            &["s0.arrow", "trace.arrow"],
            &["trace.arrow is a trace file, not a sweep shard"],
        ),
        (
            "not an Arrow or Parquet file",
            &["s0.arrow", "s.toml"],
            &["s.toml is neither an Arrow IPC file nor a Parquet file"],
        ),
        (
            "a cut-off file",
            &["s0.arrow", "cut.arrow", "s2.arrow", "s3.arrow"],
            &["cannot read cut.arrow"],
        ),
        (
            "the output is a shard",
            &[
                "s0.arrow", "s1.arrow", "s2.arrow", "s3.arrow", "--out", "s0.arrow",
            ],
            &["cannot write s0.arrow: it is an input of this command"],
        ),
    ];
    let mut failures = Vec::new();
    for (name, args, expect) in cases {
        let before = dir.entries();
        let mut all = vec!["merge"];
        all.extend(args);
        if !args.contains(&"--out") {
            all.extend(["--out", "merged.arrow"]);
        }
        let run = touchdown(dir.path(), &all);
        let mut problems = Vec::new();
        if run.code != Some(2) {
            problems.push(format!("exit code {:?}, expected 2", run.code));
        }
        for s in expect {
            if !run.stderr.contains(s) {
                problems.push(format!("stderr lacks {s:?}"));
            }
        }
        if run.stderr.contains("panicked") {
            problems.push("panicked".to_string());
        }
        if dir.entries() != before {
            problems.push(format!("files changed: {:?}", dir.entries()));
        }
        if !problems.is_empty() {
            failures.push(format!("{name}: {}\n{run}", problems.join("; ")));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // The shards that do belong together still merge.
    ok(
        &dir,
        &[
            "merge",
            "s3.arrow",
            "s2.arrow",
            "s1.arrow",
            "s0.arrow",
            "--out",
            "merged.arrow",
        ],
    );
}

/// f32 lanes: the same sweep with 1 and 2 threads, and as 3 shards merged, gives one file
/// byte for byte; the file records its f32 arithmetic, and a merge of an f32 shard with an
/// f64 shard of the same samples is refused.
#[test]
fn f32_sweeps_repeat_byte_for_byte_over_threads_and_shards() {
    let dir = TempDir::new("shards-f32");
    dir.write(
        "s32.toml",
        "[simulation]\nt_max_s = 5.0\nprecision = \"f32\"\n",
    );
    dir.write("s64.toml", SHORT);
    // More than a thread's window (4 x 1024 samples), so that threads share windows.
    let base = |scenario: &'static str| {
        [
            "sweep",
            "--scenario",
            scenario,
            "--samples",
            "20000",
            "--quiet",
        ]
    };
    let one = ok(
        &dir,
        &[
            &base("s32.toml")[..],
            &["--threads", "1", "--out", "t1.arrow"],
        ]
        .concat(),
    );
    ok(
        &dir,
        &[
            &base("s32.toml")[..],
            &["--threads", "2", "--out", "t2.arrow"],
        ]
        .concat(),
    );
    assert!(
        read_bytes(&dir.join("t1.arrow")) == read_bytes(&dir.join("t2.arrow")),
        "f32: --threads 1 and --threads 2 wrote different files"
    );
    let bytes = read_bytes(&dir.join("t1.arrow"));
    assert!(
        bytes.windows(10).any(|w| w == b"f32x16-fma")
            || bytes.windows(12).any(|w| w == b"f32x16-nofma"),
        "the file records f32 arithmetic"
    );
    assert!(!outcome_counts(&one).is_empty(), "outcome counts in {one}");
    for k in 0..3 {
        let (shard, out) = (format!("{k}/3"), format!("s{k}.arrow"));
        ok(
            &dir,
            &[&base("s32.toml")[..], &["--shard", &shard, "--out", &out]].concat(),
        );
    }
    ok(
        &dir,
        &[
            "merge", "s1.arrow", "s2.arrow", "s0.arrow", "--out", "m.arrow",
        ],
    );
    assert!(
        read_bytes(&dir.join("m.arrow")) == read_bytes(&dir.join("t1.arrow")),
        "f32: the merged shards differ from the sweep run in one process"
    );
    // Shard 1 of the same samples in f64: not part of the f32 sweep.
    ok(
        &dir,
        &[
            &base("s64.toml")[..],
            &["--shard", "1/3", "--out", "f1.arrow"],
        ]
        .concat(),
    );
    let run = touchdown(
        dir.path(),
        &[
            "merge", "s0.arrow", "f1.arrow", "s2.arrow", "--out", "x.arrow",
        ],
    );
    assert_eq!(run.code, Some(2), "mixed precisions refused: {run}");
    assert!(
        run.stderr.contains("f32x16"),
        "the refusal names the precisions: {run}"
    );
    assert!(
        !dir.join("x.arrow").exists(),
        "no file from a refused merge"
    );
}

/// Sliders that go tens of metres down the slope (three legs, dampers, 120 s): f32 lanes
/// move their origin along (`Block::recentre`), so their positions stay small and their
/// contact resolved. Without it, f32 positions 30 m from the origin round to 2e-6 m, a
/// few roundings of a footpad's static contact deflection (1.1e-5 m): measured at 100,000
/// samples, 4,664 sliders at 120 s were called `bouncing` (none in f64); with it, every
/// outcome share agrees within 3 binomial standard errors. Here 2,000 samples in both
/// precisions: no `bouncing` in either (4.7 % of them were, without recentring), and every
/// share within 3 standard errors of f64's (at 2,000 samples, 3 SE of the sliding share
/// of 20 % is 2.7 %; flips near thresholds measured 0.5 % at 100,000).
#[test]
fn f32_long_slides_keep_their_contact() {
    let dir = TempDir::new("f32-slides");
    let legs3 = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/legs-3.toml"),
    )
    .unwrap();
    let f32 = legs3.replace("[simulation]\n", "[simulation]\nprecision = \"f32\"\n");
    assert_ne!(f32, legs3, "the f32 copy says so");
    dir.write("s64.toml", &legs3);
    dir.write("s32.toml", &f32);
    let n = 2000u64;
    let counts: Vec<Vec<(String, u64)>> = ["s64.toml", "s32.toml"]
        .iter()
        .map(|s| {
            outcome_counts(&ok(
                &dir,
                &[
                    "sweep",
                    "--scenario",
                    s,
                    "--samples",
                    "2000",
                    "--out",
                    "o.arrow",
                ],
            ))
        })
        .collect();
    for ((name, a), (_, b)) in counts[0].iter().zip(&counts[1]) {
        let p = (*a as f64 / n as f64).max(1.0 / n as f64);
        let se = (p * (1.0 - p) / n as f64).sqrt();
        let d = (*b as f64 - *a as f64) / n as f64;
        assert!(
            d.abs() <= 3.0 * se,
            "{name}: f64 {a}, f32 {b} of {n}: {d:.4} against 3 SE {:.4}",
            3.0 * se
        );
        if name == "bouncing" {
            assert_eq!((*a, *b), (0, 0), "no sliders called bouncing");
        }
    }
    assert!(
        counts[0].iter().any(|(n, c)| n == "sliding" && *c > 200),
        "{counts:?}"
    );
}
