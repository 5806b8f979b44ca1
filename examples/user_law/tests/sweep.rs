//! The example program sweeps the scenario that names its law, and its report counts the
//! law's push once in contact as hold-down impulse. (The law's agreement between kernels and
//! reference, and the `touchdown` binary's refusal of the scenario, are tested with the
//! rest of touchdown: tests/user_law.rs.)

use std::path::Path;
use std::process::Command;

#[test]
fn the_example_program_sweeps_with_its_law() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("user_law_example");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("sweep.arrow");
    let program = env!("CARGO_BIN_EXE_user_law");
    let sweep = Command::new(program)
        .arg("sweep")
        .arg("--scenario")
        .arg(root.join("examples/user-law.toml"))
        .args(["--samples", "64", "--quiet", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        sweep.status.success(),
        "{}",
        String::from_utf8_lossy(&sweep.stderr)
    );
    let report = Command::new(program)
        .arg("report")
        .arg(&out)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&report.stdout);
    assert!(report.status.success(), "{text}");
    // The law pushes with 15 N for 8 s once in contact: 120 N s of hold-down impulse in
    // the landers it pushes (nearly all: 195 of 200), 0 where a user's law's push was not
    // counted.
    let row = text
        .lines()
        .find(|l| l.starts_with("| hold-down impulse"))
        .unwrap_or_else(|| panic!("no hold-down impulse in the report:\n{text}"));
    let mean: f64 = row.split('|').nth(2).unwrap().trim().parse().unwrap();
    assert!(mean > 100.0, "{row}");
}
