//! The README's Python lines make tables that replay.

use super::{assert_same_columns, metadata, read_sweep, take};
use crate::common::{TempDir, touchdown};
use std::path::Path;

/// The `sh` block of the README's section `heading`.
fn readme_block(heading: &str) -> String {
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"))
        .expect("README.md");
    let section = readme
        .split(&format!("\n{heading}\n"))
        .nth(1)
        .unwrap_or_else(|| panic!("no section {heading} in the README"));
    let block = section
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("\n```").next())
        .unwrap_or_else(|| panic!("no sh block in the README's {heading}"));
    block.to_string()
}

#[test]
fn the_readme_python_lines_make_tables_that_replay() {
    if !crate::common::python_readers_available("the_readme_python_lines_make_tables_that_replay") {
        return;
    }
    let dir = TempDir::new("inputs-readme");
    // `python3` and `touchdown` as the README's lines call them: the tests' environment
    // and this build.
    let path = crate::common::readme_path(&dir);
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--samples",
            "3000",
            "--quiet",
            "--out",
            "sweep.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    // The "changed" scenario of the example is the default one here, so that the tipped
    // landers tip again, exactly.
    dir.write("changed.toml", "# the default scenario\n");
    let block = readme_block("### Your own inputs");
    let o = std::process::Command::new("sh")
        .args(["-e", "-c", &block])
        .current_dir(dir.path())
        .env("PATH", path)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "the README's lines failed:\n{block}\n--- stdout ---\n{}\n--- stderr ---\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let gnc = read_sweep(&dir.join("gnc.arrow"));
    assert_eq!(gnc.num_rows(), 500);
    assert_eq!(
        metadata(&dir.join("gnc.arrow"), "touchdown.inputs.columns").as_deref(),
        Some("roll_deg,pitch_deg,velocity_error_z_m_s")
    );
    // Tipped again, every one, with the same results.
    let whole = read_sweep(&dir.join("sweep.arrow"));
    let outcome = crate::common::texts(whole.column_by_name("outcome").unwrap().as_ref());
    let tipped: Vec<u64> = (0..whole.num_rows())
        .filter(|&i| outcome[i] == "tipped")
        .map(|i| i as u64)
        .collect();
    assert!(tipped.len() > 100, "{} tipped", tipped.len());
    let again = read_sweep(&dir.join("tipped-again.arrow"));
    assert_same_columns(&take(&whole, &tipped), &again, &["sample"], "tipped again");
}
