//! A command's outputs are one unit, and every refusal comes before the work: a command
//! that writes several files (plot, envelope, site, study) is refused at once, before it
//! writes any of them, while another run writes one of them, and never leaves files of two
//! runs side by side; an output (or the temporary or interrupted file beside it) that is an
//! input of the command is refused before the first sample or the first file.
//!
//! "Another run" is played here by the test itself: it holds the lock a run holds on the
//! temporary file it writes (`NAME.partial`), as a run still drawing that picture does.

use crate::collisions::Done as _;
use crate::common::{SHORT, TempDir, read_bytes, touchdown};
use std::os::unix::fs::MetadataExt;
use std::path::Path;

/// Sweeps `samples` of the short scenario (written as `s.toml`) into `dir/out`.
fn short_sweep(dir: &TempDir, samples: &str, out: &str) {
    dir.write("s.toml", SHORT);
    let args = ["sweep", "--scenario", "s.toml", "--samples", samples];
    touchdown(
        dir.path(),
        &[&args[..], &["--quiet", "--out", out]].concat(),
    )
    .assert_done();
}

/// The names of the files in `folder`, sorted.
fn files_in(folder: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Each file's inode: a file moved into place anew has another.
fn inodes(dir: &Path, files: &[&str]) -> Vec<u64> {
    files
        .iter()
        .map(|f| {
            std::fs::metadata(dir.join(f))
                .unwrap_or_else(|e| panic!("{f}: {e}"))
                .ino()
        })
        .collect()
}

/// Checks that `run` was refused (exit code 2) saying `says`.
fn refused(run: &crate::common::Run, says: &str) {
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains(says), "{run}");
}

/// Runs `second` while another run writes `busy` (a file of the set `files`, all in
/// `folder` of `dir`): it holds the lock a run holds on the temporary file it writes. The
/// second run must be refused at once, naming `busy`, and leave every file of the set as
/// the first run made it (a file moved into place anew has another inode).
fn refused_while_another_writes(
    dir: &TempDir,
    (folder, files): (&str, &[&str]),
    busy: &str,
    second: impl FnOnce() -> crate::common::Run,
) {
    let at = dir.join(folder);
    let before = inodes(&at, files);
    let partial = at.join(format!("{busy}.partial"));
    let held = std::fs::File::create(&partial).expect("make the temporary file");
    held.try_lock().expect("lock it");
    let run = second();
    let shown = Path::new(folder).join(busy);
    refused(
        &run,
        &format!("another run is writing {} now", shown.display()),
    );
    assert_eq!(
        inodes(&at, files),
        before,
        "the refused run replaced some of the first run's files:\n{run}"
    );
    drop(held);
    std::fs::remove_file(partial).unwrap();
}

#[test]
fn envelope_and_plot_write_all_their_files_or_none() {
    let dir = TempDir::new("sets-envelope-plot");
    short_sweep(&dir, "400", "s.arrow");
    touchdown(dir.path(), &["envelope", "s.arrow", "--bins", "4,3"]).assert_done();
    // A second envelope while another run draws the picture: refused before its table.
    refused_while_another_writes(
        &dir,
        (".", &["s-envelope.csv", "s-envelope.png"]),
        "s-envelope.png",
        || touchdown(dir.path(), &["envelope", "s.arrow", "--bins", "6,5"]),
    );

    // A trace's pictures: the second run, refused at its second picture, writes no first.
    touchdown(
        dir.path(),
        &["trace", "--scenario", "s.toml", "--out", "t.arrow"],
    )
    .assert_done();
    std::fs::create_dir(dir.join("p")).unwrap();
    touchdown(dir.path(), &["plot", "t.arrow", "--out-dir", "p"]).assert_done();
    let pictures = [
        "t-cg.png",
        "t-legs.png",
        "t-path-3d.png",
        "t-accel-z-body.png",
    ];
    touchdown(
        dir.path(),
        &[
            "trace",
            "--scenario",
            "s.toml",
            "--sample",
            "3",
            "--out",
            "t.arrow",
        ],
    )
    .assert_done();
    refused_while_another_writes(&dir, ("p", &pictures), "t-legs.png", || {
        touchdown(dir.path(), &["plot", "t.arrow", "--out-dir", "p"])
    });

    // A trace with thrusters, then one without under the same name: its thrust and sensor
    // pictures are the earlier run's, and go.
    dir.write(
        "hold.toml",
        &std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml"),
        )
        .unwrap(),
    );
    touchdown(
        dir.path(),
        &["trace", "--scenario", "hold.toml", "--out", "t.arrow"],
    )
    .assert_done();
    touchdown(dir.path(), &["plot", "t.arrow", "--out-dir", "p"]).assert_done();
    assert!(dir.join("p/t-thrust.png").is_file());
    touchdown(
        dir.path(),
        &["trace", "--scenario", "s.toml", "--out", "t.arrow"],
    )
    .assert_done();
    touchdown(dir.path(), &["plot", "t.arrow", "--out-dir", "p"]).assert_done();
    assert_eq!(
        files_in(&dir.join("p")),
        [
            "t-accel-z-body.png",
            "t-cg.png",
            "t-legs.png",
            "t-path-3d.png"
        ]
    );
}

/// The Didymos model shipped in the repository.
fn didymos() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("bodies/didymos/didymos.obj")
}

/// `touchdown site SHAPE` (Didymos's units, density and spin), 2000 samples, into `out`,
/// then `extra`.
fn site(dir: &TempDir, shape: &Path, out: &str, extra: &[&str]) -> crate::common::Run {
    let shape = shape.to_string_lossy();
    let mut args = vec![
        "site",
        &shape,
        "--units",
        "km",
        "--density",
        "2170",
        "--spin-period",
        "2.26",
        "--samples",
        "2000",
        "--quiet",
        "--out-dir",
        out,
    ];
    args.extend(extra);
    touchdown(dir.path(), &args)
}

/// `touchdown study` of `scenario`, two footpad radii of 300 samples, into `out`.
fn study(dir: &TempDir, scenario: &str, out: &str) -> crate::common::Run {
    let vary = [
        "--vary",
        "lander.footpad_radius_m=0.6:0.8:2",
        "--samples",
        "300",
    ];
    let args = ["study", "--scenario", scenario, "--quiet", "--out-dir", out];
    touchdown(dir.path(), &[&args[..], &vary].concat())
}

#[test]
fn a_map_and_a_study_write_their_files_as_one() {
    let dir = TempDir::new("sets-site-study");
    let map = ["facets.arrow", "site.md", "map.png", "site.html"];
    let first = site(&dir, &didymos(), "m", &[]);
    assert_eq!(first.code, Some(0), "{first}");
    refused_while_another_writes(&dir, ("m", &map), "map.png", || {
        site(&dir, &didymos(), "m", &[])
    });

    dir.write("s.toml", SHORT);
    let first = study(&dir, "s.toml", "st");
    assert_eq!(first.code, Some(0), "{first}");
    let table = ["study.arrow", "study.md", "study.png"];
    refused_while_another_writes(&dir, ("st", &table), "study.png", || {
        study(&dir, "s.toml", "st")
    });
}

#[test]
fn an_input_among_the_outputs_is_refused_before_any_work() {
    let dir = TempDir::new("sets-inputs");
    // The shape model under a name the map writes, in its folder: refused before the sweep.
    std::fs::create_dir(dir.join("m")).unwrap();
    std::fs::copy(didymos(), dir.join("m/site.md")).unwrap();
    let run = site(&dir, &dir.join("m/site.md"), "m", &[]);
    refused(&run, "site.md: it is an input of this command");
    assert_eq!(files_in(&dir.join("m")), ["site.md"], "{run}");

    // The scenario under the name of the map's page.
    std::fs::create_dir(dir.join("n")).unwrap();
    dir.write("n/site.html", "[simulation]\nt_max_s = 20.0\n");
    let run = site(&dir, &didymos(), "n", &["--scenario", "n/site.html"]);
    refused(&run, "site.html: it is an input of this command");
    assert_eq!(files_in(&dir.join("n")), ["site.html"], "{run}");

    // A study's scenario under the name of its Markdown: refused before the first sample.
    std::fs::create_dir(dir.join("st")).unwrap();
    dir.write("st/study.md", SHORT);
    let run = study(&dir, "st/study.md", "st");
    refused(&run, "study.md: it is an input of this command");
    assert_eq!(files_in(&dir.join("st")), ["study.md"], "{run}");

    // The envelope's picture a hard link to its sweep: refused before its table.
    short_sweep(&dir, "300", "e.arrow");
    std::fs::hard_link(dir.join("e.arrow"), dir.join("e-envelope.png")).unwrap();
    let sweep = read_bytes(&dir.join("e.arrow"));
    let run = touchdown(dir.path(), &["envelope", "e.arrow"]);
    refused(
        &run,
        "cannot write ./e-envelope.png: it is the input e.arrow under another name",
    );
    assert!(!dir.join("e-envelope.csv").exists(), "{run}");
    assert!(read_bytes(&dir.join("e.arrow")) == sweep);
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
