//! The Python package (python/, README "Python"): its wheel built by maturin from this
//! checkout, then its pytest suite (python/tests: scenarios, sweeps against the command
//! line's files, traces, reports, laws in Python against the same law in Rust, Ctrl-C, the
//! example notebook run in a Jupyter kernel) run on that wheel.
//!
//! The wheel is built with the release profile into this build's target folder, so that
//! only the extension module and PyO3 compile (the library is the one the tests built).
//! It is installed into a folder of its own under target/ (`pip install --target`) and
//! imported from there: nothing goes into any Python environment, the tests' own included.

use crate::common::{python, python_readers_available};
use std::path::Path;
use std::process::Command;

/// Runs `command`; its stdout and stderr, or a panic with both and what it was for.
fn run(command: &mut Command, what: &str) -> String {
    let o = command
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot run it: {e}"));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        o.status.success(),
        "{what} failed ({:?}):\n{text}",
        o.status.code()
    );
    text
}

#[test]
fn python_package_builds_and_its_tests_pass() {
    if !python_readers_available("python_package_builds_and_its_tests_pass") {
        return;
    }
    let python = python();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let (wheels, site) = (tmp.join("python-wheels"), tmp.join("python-package"));
    for dir in [&wheels, &site] {
        let _ = std::fs::remove_dir_all(dir);
    }
    let binaries = Path::new(env!("CARGO_BIN_EXE_touchdown"))
        .parent()
        .expect("the binary's folder");
    // The target folder this build uses (…/target/release/touchdown → …/target).
    let target = binaries.parent().expect("the target folder");
    run(
        Command::new(&python)
            .args(["-m", "maturin", "build", "--release", "--manifest-path"])
            .arg(root.join("python/Cargo.toml"))
            .arg("--out")
            .arg(&wheels)
            .env("CARGO_TARGET_DIR", target)
            .current_dir(root),
        "maturin build --release (the wheel)",
    );
    let wheel = std::fs::read_dir(&wheels)
        .expect("the wheels' folder")
        .filter_map(Result::ok)
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|e| e == "whl"))
        .expect("maturin wrote a wheel");
    let name = wheel.file_name().unwrap().to_string_lossy().into_owned();
    assert!(
        name.starts_with("touchdown-") && name.contains("-cp39-abi3-"),
        "an abi3 wheel for CPython 3.9 and later: {name}"
    );
    run(
        Command::new(&python)
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--disable-pip-version-check",
            ])
            .args(["--no-deps", "--target"])
            .arg(&site)
            .arg(&wheel),
        "pip install --target (the wheel into a folder of its own)",
    );
    let out = run(
        Command::new(&python)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(root.join("python/tests"))
            .env("PYTHONPATH", &site)
            .env("TOUCHDOWN_BIN_DIR", binaries)
            .current_dir(tmp),
        "pytest python/tests",
    );
    // pytest's closing line, kept in the test's output (`--nocapture` shows it).
    let summary = out
        .lines()
        .rev()
        .find(|l| l.contains(" passed"))
        .unwrap_or("");
    println!("python/tests: {summary}");
    assert!(
        !summary.contains("failed") && !summary.contains("error"),
        "{out}"
    );
}
