//! Every refusal comes before the work: an output (or the temporary or interrupted file
//! beside it) that is an input of the command is refused before the first sample or the
//! first file.

use crate::common::{SHORT, TempDir, touchdown};

/// Checks that `run` was refused (exit code 2) saying `says`.
fn refused(run: &crate::common::Run, says: &str) {
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains(says), "{run}");
}

#[test]
fn a_sweep_never_takes_an_input_s_name_for_its_side_files() {
    let dir = TempDir::new("sets-side-files");
    // Its temporary or interrupted file under its scenario's name: the scenario would be
    // emptied, or removed once the sweep finished.
    for (scenario, beside) in [
        ("r.arrow.partial", "its unfinished file"),
        ("r.arrow.interrupted", "an interrupted sweep's file"),
    ] {
        dir.write(scenario, SHORT);
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                scenario,
                "--samples",
                "200",
                "--quiet",
                "--out",
                "r.arrow",
            ],
        );
        refused(
            &run,
            &format!("cannot write r.arrow: {scenario}, the name of {beside}, is an input"),
        );
        assert_eq!(std::fs::read_to_string(dir.join(scenario)).unwrap(), SHORT);
        assert!(!dir.join("r.arrow").exists());
        std::fs::remove_file(dir.join(scenario)).unwrap();
    }
}
