//! Interrupted sweeps: SIGINT or SIGTERM stops a sweep with a valid file of the rows done
//! beside the output (never under its name) and exit code 128 + signal; `--resume` then
//! finishes the file that an uninterrupted sweep writes, byte for byte.

use crate::common::{TempDir, read_bytes, touchdown};
use arrow_array::{Array, UInt64Array};
use arrow_ipc::reader::FileReader;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use touchdown::output::format::BATCH_ROWS as BATCH;

/// Flights cut at 5 s: about 60,000 samples/s on two cores, so that 300,000 samples run for
/// seconds, long enough to be interrupted, and more than four record batches.
const SHORT: &str = "[simulation]\nt_max_s = 5.0\n";

/// Flights cut at 60 s: about 9,000 samples/s on two cores (measured 9,190), so that 60,000
/// samples, fewer than a record batch holds, run for 6.5 s; with a limit on the side load,
/// which some samples break.
const LONGER: &str = "[simulation]\nt_max_s = 60.0\n[limits]\nside_force_n = 100.0\n";

/// The sample column of a sweep file (Arrow or Parquet).
fn sample_column(path: &Path) -> Vec<u64> {
    let file = std::fs::File::open(path).unwrap();
    let batches: Vec<_> = if read_bytes(path).starts_with(b"PAR1") {
        ParquetRecordBatchReaderBuilder::try_new(file)
            .unwrap()
            .build()
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap()
    } else {
        FileReader::try_new(file, None)
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap()
    };
    batches
        .iter()
        .flat_map(|b| {
            let s = b.column(0).as_any().downcast_ref::<UInt64Array>().unwrap();
            s.values().to_vec()
        })
        .collect()
}

/// Starts `touchdown ARGS` in `dir`, sends `signal` (`INT`, `TERM`) once it has run for a
/// while, and returns its exit code and stderr.
pub(crate) fn interrupt(
    dir: &TempDir,
    args: &[&str],
    out: &str,
    signal: &str,
) -> (Option<i32>, String) {
    let mut child = Command::new(crate::common::BIN)
        .args(args)
        .current_dir(dir.path())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the touchdown binary");
    // The temporary file appears when the sweep starts; let it run a second more.
    let partial = dir.join(&format!("{out}.partial"));
    let start = Instant::now();
    while !partial.exists() && start.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(10));
    }
    std::thread::sleep(Duration::from_millis(1000));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the sweep `{}` ended before it could be interrupted",
        args.join(" ")
    );
    let sent = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .expect("run kill");
    assert!(sent.success(), "kill -{signal} failed");
    let output = child.wait_with_output().expect("wait for the sweep");
    (
        output.status.code(),
        String::from_utf8(output.stderr).unwrap(),
    )
}

/// Checks an interrupted run: its exit code, its message, no file under the output name,
/// and a valid file of samples `first..first + n` beside it. Returns `n`.
fn check_interrupted(
    dir: &TempDir,
    out: &str,
    (code, stderr): (Option<i32>, String),
    expected_code: i32,
    first: u64,
) -> u64 {
    assert_eq!(code, Some(expected_code), "exit code; stderr:\n{stderr}");
    assert!(
        stderr.contains(&format!("continue with: touchdown sweep --resume {out}")),
        "stderr:\n{stderr}"
    );
    assert!(
        !dir.join(out).exists(),
        "an interrupted sweep left a file under the output name"
    );
    let samples = sample_column(&dir.join(&format!("{out}.interrupted")));
    let n = samples.len() as u64;
    assert_eq!(samples, (first..first + n).collect::<Vec<_>>());
    assert!(
        stderr.contains(&format!(": {n} of ")),
        "the message gives {n} rows done: {stderr}"
    );
    n
}

/// Runs the sweep `args` to completion into `out`, the file a resumed sweep must equal.
fn uninterrupted(dir: &TempDir, args: &[&str], out: &str) {
    let run = touchdown(dir.path(), &[args, &["--quiet", "--out", out]].concat());
    assert_eq!(run.code, Some(0), "{run}");
}

/// Resumes the sweep to `out` and checks that it ends as `whole`, with nothing left beside
/// but the files `inputs` (a scenario and a table); returns the run.
fn resume_to_the_end(
    dir: &TempDir,
    out: &str,
    whole: &str,
    samples: u64,
    inputs: &[&str],
) -> crate::common::Run {
    let resumed = touchdown(dir.path(), &["sweep", "--resume", out, "--quiet"]);
    assert_eq!(resumed.code, Some(0), "{resumed}");
    assert!(
        read_bytes(&dir.join(out)) == read_bytes(&dir.join(whole)),
        "the resumed sweep {out} differs from the uninterrupted {whole}"
    );
    assert!(
        resumed
            .stdout
            .contains(&format!("samples                 {samples}\n")),
        "{resumed}"
    );
    // Its outcome counts are of every row of the file, those it took over included (the
    // rows of limits, after them, are counted below).
    let counted: u64 = resumed
        .stdout
        .lines()
        .take_while(|l| *l != "limits")
        .filter(|l| l.starts_with("  ") && l.ends_with('%') && !l.contains("within limits"))
        .map(|l| {
            l.split_whitespace()
                .nth(1)
                .and_then(|n| n.parse::<u64>().ok())
        })
        .map(|n| n.unwrap_or_else(|| panic!("cannot read the outcome lines of\n{resumed}")))
        .sum();
    assert_eq!(
        counted, samples,
        "outcome counts of the resumed sweep:\n{resumed}"
    );
    let mut expected: Vec<&str> = [&[out, whole][..], inputs].concat();
    expected.sort_unstable();
    assert_eq!(dir.entries(), expected);
    resumed
}

/// Runs the sweep of `scenario` (as `s.toml`) with `samples` on two threads to the end into
/// `whole.arrow`, then into `r.arrow` stopped by SIGINT; returns the rows it had done.
fn whole_then_interrupted(dir: &TempDir, scenario: &str, samples: &str) -> u64 {
    dir.write("s.toml", scenario);
    let args = [
        "sweep",
        "--scenario",
        "s.toml",
        "--samples",
        samples,
        "--threads",
        "2",
    ];
    uninterrupted(dir, &args, "whole.arrow");
    let run = interrupt(
        dir,
        &[&args[..], &["--out", "r.arrow"]].concat(),
        "r.arrow",
        "INT",
    );
    let done = check_interrupted(dir, "r.arrow", run, 130, 0);
    assert!(
        done > 0 && done < samples.parse().unwrap(),
        "{done} rows done"
    );
    done
}

#[test]
fn sigint_then_resume_gives_the_uninterrupted_file() {
    let dir = TempDir::new("interrupt-int");
    whole_then_interrupted(&dir, SHORT, "300000");
    resume_to_the_end(&dir, "r.arrow", "whole.arrow", 300_000, &["s.toml"]);
}

#[test]
fn a_file_interrupted_before_the_coded_outcome_resumes_to_the_uninterrupted_file() {
    let dir = TempDir::new("interrupt-plain");
    whole_then_interrupted(&dir, SHORT, "300000");
    // Its text columns as a build before the coded outcome wrote them (plain text).
    let interrupted = dir.join("r.arrow.interrupted");
    crate::common::plain_copy(&interrupted, &dir.join("plain.arrow"));
    std::fs::rename(dir.join("plain.arrow"), &interrupted).unwrap();
    resume_to_the_end(&dir, "r.arrow", "whole.arrow", 300_000, &["s.toml"]);
}

#[test]
fn resume_keeps_every_row_and_readers_say_the_file_is_unfinished() {
    let dir = TempDir::new("interrupt-rows");
    // Fewer samples than a record batch holds: every row done is in a batch not yet full.
    let done = whole_then_interrupted(&dir, LONGER, "60000");

    // Its readers say what it is, under its name and renamed (the file says how many
    // samples its sweep asked for).
    std::fs::copy(dir.join("r.arrow.interrupted"), dir.join("part.arrow")).unwrap();
    let note = " of 60,000 samples: an interrupted sweep; `touchdown sweep --resume";
    for (args, says) in [
        (
            &["report", "r.arrow.interrupted"][..],
            "r.arrow` finishes it",
        ),
        (
            &["report", "part.arrow"],
            "OUT` finishes it once it is named",
        ),
        (
            &["report", "part.arrow", "--json"],
            "\"samples_asked\": 60000",
        ),
        (&["envelope", "part.arrow", "--out-dir", "e"], note),
    ] {
        let run = touchdown(dir.path(), args);
        assert_eq!(run.code, Some(0), "{run}");
        assert!(
            run.stdout.contains(note) && run.stdout.contains(says),
            "{run}"
        );
    }
    std::fs::remove_file(dir.join("part.arrow")).unwrap();
    std::fs::remove_dir_all(dir.join("e")).unwrap();

    // Resumed, it keeps every row done, not only whole batches, and counts the limits of
    // every row as the report of the whole file does.
    let resumed = resume_to_the_end(&dir, "r.arrow", "whole.arrow", 60_000, &["s.toml"]);
    let report = touchdown(dir.path(), &["report", "whole.arrow"]);
    assert_eq!(report.code, Some(0), "{report}");
    for name in [
        "stable within limits",
        "broke `side_force`: peak side load above 100 N",
    ] {
        let count = |text: &str, bar: &str| -> u64 {
            let line = text
                .lines()
                .find(|l| l.trim_start_matches(bar).trim_start().starts_with(name));
            let after = line.map(|l| &l[l.find(name).unwrap() + name.len()..]);
            after
                .and_then(|a| a.split([' ', '|']).find(|w| !w.is_empty())?.parse().ok())
                .unwrap_or_else(|| panic!("no {name} in\n{text}"))
        };
        let n = count(&resumed.stdout, " ");
        assert_eq!(n, count(&report.stdout, "|"), "{name}\n{resumed}");
        assert!(n > 0 && n < 60_000, "{name}: {n}");
    }
    assert!(
        resumed
            .stderr
            .contains(&format!("({done} rows kept of {done})")),
        "{resumed}"
    );
}

#[test]
fn sigterm_twice_then_resume_gives_the_uninterrupted_shard() {
    let dir = TempDir::new("interrupt-term");
    dir.write("s.toml", SHORT);
    // The second half of 600,000 samples, as Parquet: samples 300,000..600,000.
    let args = [
        "sweep",
        "--scenario",
        "s.toml",
        "--samples",
        "600000",
        "--shard",
        "1/2",
        "--format",
        "parquet",
        "--threads",
        "2",
    ];
    uninterrupted(&dir, &args, "whole.parquet");

    let run = interrupt(
        &dir,
        &[&args[..], &["--out", "r.parquet"]].concat(),
        "r.parquet",
        "TERM",
    );
    let first = check_interrupted(&dir, "r.parquet", run, 143, 300_000);
    // The resumed sweep, interrupted in turn, keeps at least the whole batches it took over.
    let run = interrupt(
        &dir,
        &["sweep", "--resume", "r.parquet", "--threads", "2"],
        "r.parquet",
        "TERM",
    );
    let second = check_interrupted(&dir, "r.parquet", run, 143, 300_000);
    assert!(
        second >= first / BATCH as u64 * BATCH as u64,
        "{second} rows after the second stop, {first} after the first"
    );

    resume_to_the_end(&dir, "r.parquet", "whole.parquet", 300_000, &["s.toml"]);
}

#[test]
fn a_sweep_of_a_table_resumes_with_that_table_alone() {
    let dir = TempDir::new("interrupt-table");
    dir.write("s.toml", SHORT);
    let mut text = String::from("slope_deg,note,yaw_deg\n");
    for i in 0..300_000u32 {
        text.push_str(&format!("{},n{},{}\n", i % 45, i % 7, i % 360));
    }
    dir.write("in.csv", &text);
    let args = [
        "sweep",
        "--scenario",
        "s.toml",
        "--inputs",
        "in.csv",
        "--keep-columns",
        "--threads",
        "2",
    ];
    uninterrupted(&dir, &args, "whole.arrow");
    let run = interrupt(
        &dir,
        &[&args[..], &["--out", "r.arrow"]].concat(),
        "r.arrow",
        "INT",
    );
    let done = check_interrupted(&dir, "r.arrow", run, 130, 0);
    assert!(done < 300_000);

    // Another table under the name is refused, and so is a table where none ran.
    dir.write("in.csv", &text.replacen("n0", "n9", 1));
    let refused = touchdown(dir.path(), &["sweep", "--resume", "r.arrow"]);
    assert_eq!(refused.code, Some(2), "{refused}");
    assert!(
        refused.stderr.contains("is not the table of inputs"),
        "{refused}"
    );
    dir.write("in.csv", &text);
    resume_to_the_end(
        &dir,
        "r.arrow",
        "whole.arrow",
        300_000,
        &["in.csv", "s.toml"],
    );
}
