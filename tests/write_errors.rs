//! Every write error is an error (issue 33, points 3 and 9): a full disk on standard output
//! or on any output file exits 2 naming what could not be written, once with the system's
//! reason; a closed pipe ends quietly; an error that cannot even be told on stderr still
//! exits 2, no panic. And the messages of point 9: a run of more than a day says so without
//! a terminal, and Ctrl-C in `animate` leaves no unfinished file.
//!
//! `/dev/full` (Linux) fails every write with ENOSPC, as a full disk does.

use crate::common::{SHORT, TempDir, touchdown};
use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const FULL: &str = "/dev/full";
const NO_SPACE: &str = "No space left on device";

/// Whether this system has `/dev/full` (the tests skip with a note where not).
fn has_dev_full() -> bool {
    if Path::new(FULL).exists() {
        return true;
    }
    eprintln!("skipped: no {FULL} on this system");
    false
}

/// Runs `touchdown ARGS` in `dir` with stdout into `/dev/full`: its exit code and stderr.
fn with_stdout_full(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(crate::common::BIN)
        .args(args)
        .current_dir(dir)
        .stdout(File::create(FULL).expect("open /dev/full"))
        .output()
        .expect("run the touchdown binary");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// What is wrong with a run that met a full disk: it must exit 2, say `error:` with every
/// text of `expect` (what it could not write), give the system's reason exactly once, and
/// not panic.
fn check_failed(
    args: &[&str],
    (code, stderr): (Option<i32>, String),
    expect: &[&str],
) -> Vec<String> {
    let mut problems = Vec::new();
    if code != Some(2) {
        problems.push(format!("exit code {code:?}, expected 2"));
    }
    for s in expect.iter().chain(&["error:"]) {
        if !stderr.contains(s) {
            problems.push(format!("stderr lacks {s:?}"));
        }
    }
    let reasons = stderr.matches(NO_SPACE).count();
    if reasons != 1 {
        problems.push(format!(
            "stderr gives {NO_SPACE:?} {reasons} times, not once"
        ));
    }
    if stderr.contains("panicked") {
        problems.push("a panic".to_string());
    }
    if problems.is_empty() {
        Vec::new()
    } else {
        vec![format!(
            "`touchdown {}`: {}\n--- stderr ---\n{stderr}",
            args.join(" "),
            problems.join("; ")
        )]
    }
}

/// Runs every case (its arguments and what its message must say) with `run` and fails,
/// listing them all, unless each one failed properly on `what`.
fn assert_all_fail(
    cases: &[(&[&str], &str)],
    run: impl Fn(&[&str]) -> (Option<i32>, String),
    what: &str,
) {
    let failures: Vec<String> = cases
        .iter()
        .flat_map(|(args, expect)| check_failed(args, run(args), &[expect]))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} commands did not fail properly on {what}:\n\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n\n")
    );
}

/// The files the commands below read: a short sweep, a Sobol-indices sweep, two shards
/// and a trace.
fn inputs(dir: &TempDir) {
    dir.write("short.toml", SHORT);
    let sweep = [
        "sweep",
        "--scenario",
        "short.toml",
        "--samples",
        "64",
        "--quiet",
    ];
    for extra in [
        &["--out", "s.arrow"][..],
        &["--shard", "0/2", "--out", "p0.arrow"],
        &["--shard", "1/2", "--out", "p1.arrow"],
        &["--design", "sobol-indices", "--out", "i.arrow"],
    ] {
        let run = touchdown(dir.path(), &[&sweep[..], extra].concat());
        assert_eq!(run.code, Some(0), "{run}");
    }
    let run = touchdown(
        dir.path(),
        &[
            "trace",
            "--scenario",
            "short.toml",
            "--every",
            "10",
            "--out",
            "t.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
}

/// Standard output on a full disk: every command that writes to it fails, naming what it
/// could not write (on main they all exited 0 with nothing written).
#[test]
fn a_full_standard_output_is_an_error() {
    if !has_dev_full() {
        return;
    }
    let dir = TempDir::new("stdout-full");
    inputs(&dir);
    let cases: &[(&[&str], &str)] = &[
        (
            &["scenario"],
            "cannot write the scenario to standard output",
        ),
        (
            &["report", "s.arrow"],
            "cannot write the report to standard output",
        ),
        (
            &["compare", "s.arrow", "s.arrow"],
            "cannot write the comparison to standard output",
        ),
        (
            &["sensitivity", "i.arrow", "--bootstrap", "10"],
            "cannot write the indices to standard output",
        ),
        (
            &[
                "sweep",
                "--scenario",
                "short.toml",
                "--samples",
                "16",
                "--quiet",
                "--out",
                "x.arrow",
            ],
            "cannot write the sweep's summary to standard output",
        ),
        (
            &[
                "sweep",
                "--scenario",
                "short.toml",
                "--samples",
                "16",
                "--quiet",
                "--out",
                "-",
            ],
            "cannot write to standard output",
        ),
        (
            &[
                "trace",
                "--scenario",
                "short.toml",
                "--out",
                "x-trace.arrow",
            ],
            "cannot write the trace's summary to standard output",
        ),
        (
            &["trace", "--scenario", "short.toml", "--out", "-"],
            "cannot write to standard output",
        ),
        (
            &[
                "study",
                "--scenario",
                "short.toml",
                "--vary",
                "lander.footpad_radius_m=0.05:0.1:2",
                "--samples",
                "16",
                "--quiet",
                "--out-dir",
                "st",
            ],
            "cannot write the study's log to standard output",
        ),
        (
            &[
                "boundary",
                "--scenario",
                "short.toml",
                "--batch",
                "50",
                "--max-samples-per-sector",
                "50",
                "--quiet",
            ],
            "cannot write the search's report to standard output",
        ),
        (
            &["merge", "p0.arrow", "p1.arrow", "--out", "m.arrow"],
            "cannot write the merge's summary to standard output",
        ),
        (
            &["plot", "s.arrow", "--out-dir", "pictures"],
            "cannot write the list of pictures to standard output",
        ),
        (
            &["animate", "t.arrow", "--size", "160x120", "--out", "x.gif"],
            "cannot write the animation's summary to standard output",
        ),
        (
            &["view", "t.arrow", "--out", "x.html"],
            "cannot write the page's summary to standard output",
        ),
    ];
    assert_all_fail(
        cases,
        |args| with_stdout_full(dir.path(), args),
        "a full stdout",
    );
}

/// Output files on a full disk (`--out /dev/full`, or a symbolic link to it where the name
/// is the command's own): each command fails naming the file, the system's reason once (on
/// main a trace and a study's table named no file and gave the reason twice).
#[test]
fn a_full_output_file_is_an_error_naming_it() {
    if !has_dev_full() {
        return;
    }
    let dir = TempDir::new("file-full");
    inputs(&dir);
    std::fs::create_dir(dir.join("pictures")).unwrap();
    std::os::unix::fs::symlink(FULL, dir.join("pictures/s-stability-map.png")).unwrap();
    std::fs::create_dir(dir.join("st")).unwrap();
    std::os::unix::fs::symlink(FULL, dir.join("st/study.arrow")).unwrap();
    let full = "cannot write output file /dev/full";
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "sweep",
                "--scenario",
                "short.toml",
                "--samples",
                "16",
                "--quiet",
                "--out",
                FULL,
            ],
            full,
        ),
        (
            &[
                "sweep",
                "--scenario",
                "short.toml",
                "--samples",
                "16",
                "--quiet",
                "--out",
                FULL,
                "--format",
                "parquet",
            ],
            full,
        ),
        (&["trace", "--scenario", "short.toml", "--out", FULL], full),
        (&["merge", "p0.arrow", "p1.arrow", "--out", FULL], full),
        (
            &["animate", "t.arrow", "--size", "160x120", "--out", FULL],
            full,
        ),
        (&["view", "t.arrow", "--out", FULL], full),
        (
            &["sensitivity", "i.arrow", "--bootstrap", "10", "--png", FULL],
            full,
        ),
        (
            &["plot", "s.arrow", "--out-dir", "pictures"],
            "cannot write output file pictures/s-stability-map.png",
        ),
        (
            &[
                "study",
                "--scenario",
                "short.toml",
                "--vary",
                "lander.footpad_radius_m=0.05:0.1:2",
                "--samples",
                "16",
                "--quiet",
                "--out-dir",
                "st",
            ],
            "cannot write output file st/study.arrow",
        ),
    ];
    assert_all_fail(
        cases,
        |args| with_stdout_null(dir.path(), args),
        "a full disk",
    );
}

/// Runs `touchdown ARGS` in `dir` with stdout discarded: its exit code and stderr.
fn with_stdout_null(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(crate::common::BIN)
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .output()
        .expect("run the touchdown binary");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A reader that stops reading (`| head -1`) is no error: the command ends quietly with
/// exit code 0, whether it wrote text or an Arrow stream (on main `sweep --out -` and
/// `trace --out -` exited 2 with "Broken pipe").
#[test]
fn a_closed_pipe_ends_quietly() {
    let dir = TempDir::new("closed-pipe");
    inputs(&dir);
    for args in [
        &["report", "s.arrow"][..],
        &[
            "sweep",
            "--scenario",
            "short.toml",
            "--samples",
            "20000",
            "--quiet",
            "--out",
            "-",
        ],
        &["trace", "--scenario", "short.toml", "--out", "-"],
    ] {
        let mut child = Command::new(crate::common::BIN)
            .args(args)
            .current_dir(dir.path())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run the touchdown binary");
        // The reader goes away before reading anything.
        drop(child.stdout.take());
        let out = child.wait_with_output().expect("wait for touchdown");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(0),
            "`touchdown {}`: {stderr}",
            args.join(" ")
        );
        assert!(
            !stderr.contains("error"),
            "`touchdown {}`: {stderr}",
            args.join(" ")
        );
    }
}

/// An error that cannot be told (stderr on a full disk, as a terminal gone after SIGHUP
/// fails writes) still exits 2: on main the failed `eprintln!` panicked (exit 101).
#[test]
fn an_error_that_cannot_be_told_still_exits_2() {
    if !has_dev_full() {
        return;
    }
    let dir = TempDir::new("stderr-full");
    for args in [&["report", "missing.arrow"][..], &["scenario"]] {
        let out = Command::new(crate::common::BIN)
            .args(args)
            .current_dir(dir.path())
            .stdout(File::create(FULL).unwrap())
            .stderr(File::create(FULL).unwrap())
            .status()
            .expect("run the touchdown binary");
        assert_eq!(out.code(), Some(2), "`touchdown {}`", args.join(" "));
    }
}

/// `--samples 1e12` in a batch job (stderr not a terminal) says at once that it takes more
/// than a day; on main it started silently (a terminal showed an ETA of 52 weeks).
#[test]
fn a_run_of_more_than_a_day_says_so_without_a_terminal() {
    let dir = TempDir::new("long-run");
    let mut child = Command::new(crate::common::BIN)
        .args([
            "sweep",
            "--samples",
            "1e12",
            "--threads",
            "2",
            "--quiet",
            "--out",
            "long.arrow",
        ])
        .current_dir(dir.path())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the touchdown binary");
    // Read stderr in a thread; stop the sweep once the warning came, or after a minute
    // without it (a bound on the test's time, not a measurement: the warning comes before
    // the first sample's result).
    let stderr = child.stderr.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    let reader = std::thread::spawn(move || {
        let mut all = String::new();
        for line in BufReader::new(stderr).lines() {
            let line = line.unwrap_or_default();
            if line.contains("more than a day") {
                let _ = tx.send(());
            }
            all.push_str(&line);
            all.push('\n');
        }
        all
    });
    let start = Instant::now();
    while rx.try_recv().is_err() && start.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(50));
    }
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("run kill");
    assert!(sent.success());
    let code = child.wait().expect("wait for the sweep").code();
    let stderr = reader.join().unwrap();
    assert!(
        stderr.contains(
            "touchdown: warning: this run of 1000000000000 samples takes more than a day"
        ),
        "stderr:\n{stderr}"
    );
    assert_eq!(code, Some(130), "stderr:\n{stderr}");
}

/// Ctrl-C in `animate` removes its unfinished GIF and exits 130, as the other commands do
/// (on main the signal killed it and left `OUT.partial`).
#[test]
fn an_interrupted_animation_leaves_no_file() {
    let dir = TempDir::new("animate-interrupted");
    let run = touchdown(dir.path(), &["trace", "--out", "t.arrow"]);
    assert_eq!(run.code, Some(0), "{run}");
    // About 3,300 frames at 640x480: tens of seconds of work, stopped after one.
    let (code, stderr) = crate::interrupt::interrupt(
        &dir,
        &[
            "animate", "t.arrow", "--fps", "50", "--speed", "0.1", "--out", "t.gif",
        ],
        "t.gif",
        "INT",
    );
    assert_eq!(code, Some(130), "stderr:\n{stderr}");
    assert!(
        stderr.contains("interrupted by SIGINT"),
        "stderr:\n{stderr}"
    );
    assert_eq!(dir.entries(), ["t.arrow"], "stderr:\n{stderr}");
}
