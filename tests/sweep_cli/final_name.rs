//! No incomplete file under the final name: an output in a missing folder is refused before
//! any work, finished sweeps leave no partial file, failed and killed ones leave the old file.

use super::{check_sweep_file, sweep};
use crate::common::{SHORT, TempDir, read_bytes, touchdown};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

#[test]
fn output_in_a_missing_folder_is_refused_before_any_work() {
    let dir = TempDir::new("sweep-missing-folder");
    dir.write("short.toml", SHORT);
    std::fs::create_dir(dir.join("present")).unwrap();
    for (out, folder) in [
        ("missing/sweep.arrow", "missing"),
        ("present/missing/sweep.parquet", "present/missing"),
    ] {
        let before = dir.entries();
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                "short.toml",
                "--samples",
                "2000",
                "--format",
                out.rsplit('.').next().unwrap(),
                "--out",
                out,
            ],
        );
        assert_eq!(run.code, Some(2), "{run}");
        assert!(
            run.stderr
                .contains(&format!("cannot write output file {out}"))
                && run
                    .stderr
                    .contains(&format!("folder {folder} does not exist")),
            "the message does not name the path: {run}"
        );
        assert!(
            !run.stderr.contains("touchdown sweep:"),
            "the sweep started: {run}"
        );
        assert!(run.stdout.is_empty(), "{run}");
        assert_eq!(dir.entries(), before, "{run}");
        assert!(
            std::fs::read_dir(dir.join("present"))
                .unwrap()
                .next()
                .is_none()
        );
    }
}

#[test]
fn finished_sweeps_leave_no_partial_file_and_failed_ones_leave_the_old_file() {
    let dir = TempDir::new("sweep-partial");
    dir.write("short.toml", SHORT);
    dir.write("bad.toml", "[lander]\nmass_kg = 0\n");
    // An existing file is replaced whole.
    dir.write("sweep.arrow", "an older file");
    for format in ["arrow", "parquet"] {
        let out = format!("sweep.{format}");
        let (_, s) = sweep(
            &dir,
            &[
                "--scenario",
                "short.toml",
                "--samples",
                "1500",
                "--format",
                format,
                "--out",
                &out,
            ],
        );
        check_sweep_file(&dir.join(&out), &s, 1, SHORT);
    }
    assert_eq!(
        dir.entries(),
        ["bad.toml", "short.toml", "sweep.arrow", "sweep.parquet"]
    );

    // A sweep refused leaves the file of the last one as it was.
    let before = read_bytes(&dir.join("sweep.arrow"));
    let run = touchdown(
        dir.path(),
        &["sweep", "--scenario", "bad.toml", "--out", "sweep.arrow"],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("`lander.mass_kg` = 0 "), "{run}");
    assert!(read_bytes(&dir.join("sweep.arrow")) == before);
    assert_eq!(
        dir.entries(),
        ["bad.toml", "short.toml", "sweep.arrow", "sweep.parquet"]
    );
}

/// Starts a sweep too long to finish (to `out` in `dir`) and kills it while it runs.
fn kill_a_running_sweep(dir: &TempDir, out: &str) {
    let mut child = Command::new(crate::common::BIN)
        .args([
            "sweep",
            "--scenario",
            "short.toml",
            "--samples",
            "1e9",
            "--threads",
            "1",
            "--quiet",
            "--out",
            out,
        ])
        .current_dir(dir.path())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start the touchdown binary");
    // The temporary file appears when the sweep starts; let it run a little more.
    let partial = dir.join(&format!("{out}.partial"));
    let start = Instant::now();
    while !partial.exists() && start.elapsed() < Duration::from_secs(30) {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the sweep ended early: {status}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let appeared = partial.exists();
    if appeared {
        std::thread::sleep(Duration::from_millis(300));
    }
    let still_running = child.try_wait().unwrap().is_none();
    child.kill().expect("kill the sweep");
    child.wait().expect("wait for the killed sweep");
    assert!(appeared, "no {} within 30 s", partial.display());
    assert!(still_running, "the sweep of 1e9 samples ended by itself");
}

#[test]
fn a_killed_sweep_leaves_no_file_under_its_name() {
    let dir = TempDir::new("sweep-killed");
    dir.write("short.toml", SHORT);
    kill_a_running_sweep(&dir, "new.arrow");
    assert!(
        !dir.join("new.arrow").exists(),
        "a killed sweep left a file under its final name"
    );
    dir.write("old.arrow", "an older file");
    kill_a_running_sweep(&dir, "old.arrow");
    assert!(
        read_bytes(&dir.join("old.arrow")) == b"an older file",
        "a killed sweep changed the file under its final name"
    );
}
