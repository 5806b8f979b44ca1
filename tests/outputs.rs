//! Outputs that are not regular files: a device, a FIFO, or a symbolic link to one is
//! written into and left what it was (a sweep once renamed its finished file onto
//! `/dev/null`, breaking the machine); `-` streams Arrow IPC to standard output for pipes.
//! For `sweep`, `trace`, `merge` and `plot`, in a private temporary folder.

use crate::common::{BIN, SHORT, TempDir, read_bytes, touchdown};
use std::io::Read;
use std::os::unix::fs::{FileTypeExt, MetadataExt};
use std::path::Path;
use std::process::{Command, Stdio};

/// The commands under test, writing to `out`: a sweep, a trace, a merge of two shards
/// (which `prepare` makes), and the picture of a trace.
fn commands(out: &str) -> Vec<Vec<String>> {
    let v = |a: &[&str]| a.iter().map(ToString::to_string).collect::<Vec<_>>();
    vec![
        v(&[
            "sweep",
            "--scenario",
            "short.toml",
            "--samples",
            "300",
            "--quiet",
            "--out",
            out,
        ]),
        v(&[
            "trace",
            "--scenario",
            "short.toml",
            "--sample",
            "3",
            "--every",
            "5",
            "--out",
            out,
        ]),
        v(&["merge", "part0.arrow", "part1.arrow", "--out", out]),
    ]
}

/// The scenario and the two shards `merge` joins.
fn prepare(dir: &TempDir) {
    dir.write("short.toml", SHORT);
    for k in 0..2 {
        let shard = format!("{k}/2");
        let out = format!("part{k}.arrow");
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                "short.toml",
                "--samples",
                "300",
                "--quiet",
                "--shard",
                &shard,
                "--out",
                &out,
            ],
        );
        assert_eq!(run.code, Some(0), "{run}");
    }
}

/// Runs `touchdown ARGS` in `dir`; panics unless it succeeds. Returns stdout's bytes.
fn run_ok(dir: &Path, args: &[String]) -> Vec<u8> {
    let o = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run touchdown");
    assert!(
        o.status.success(),
        "touchdown {args:?}: exit {:?}\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
    o.stdout
}

/// What a path is, following no link: kind, and the device numbers of a device.
fn kind(path: &Path) -> (String, u64) {
    let m = std::fs::symlink_metadata(path).expect("the path is still there");
    let t = m.file_type();
    let name = if t.is_symlink() {
        "symlink"
    } else if t.is_fifo() {
        "fifo"
    } else if t.is_char_device() {
        "char device"
    } else if t.is_file() {
        "file"
    } else {
        "other"
    };
    (name.to_string(), m.rdev())
}

#[test]
fn a_fifo_gets_the_bytes_of_the_file_and_stays_a_fifo() {
    let dir = TempDir::new("fifo");
    prepare(&dir);
    let fifo = dir.join("fifo");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("run mkfifo");
    assert!(made.success(), "mkfifo");
    for (file_args, fifo_args) in commands("file.arrow").into_iter().zip(commands("fifo")) {
        run_ok(dir.path(), &file_args);
        let expected = read_bytes(&dir.join("file.arrow"));
        // A reader on the FIFO, as `cat fifo > x` would be.
        let path = fifo.clone();
        let reader = std::thread::spawn(move || {
            let mut bytes = Vec::new();
            std::fs::File::open(path)
                .and_then(|mut f| f.read_to_end(&mut bytes))
                .expect("read the FIFO");
            bytes
        });
        run_ok(dir.path(), &fifo_args);
        let got = reader.join().expect("the FIFO reader");
        assert!(
            got == expected,
            "{fifo_args:?}: the FIFO got other bytes than the file"
        );
        assert_eq!(kind(&fifo).0, "fifo", "{fifo_args:?}");
    }
    assert!(
        !dir.entries().iter().any(|e| e.ends_with(".partial")),
        "{:?}",
        dir.entries()
    );
}

#[test]
fn a_symlink_to_a_character_device_stays_one() {
    let dir = TempDir::new("device");
    prepare(&dir);
    // A null device of our own (root only), so that nothing outside the folder is at stake.
    let made = Command::new("mknod")
        .args(["null", "c", "1", "3"])
        .current_dir(dir.path())
        .stderr(Stdio::null())
        .status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("SKIPPED a_symlink_to_a_character_device_stays_one: mknod needs root");
        return;
    }
    std::os::unix::fs::symlink("null", dir.join("link")).expect("symlink");
    let before = (kind(&dir.join("null")), kind(&dir.join("link")));
    assert_eq!(
        (before.0.0.as_str(), before.1.0.as_str()),
        ("char device", "symlink")
    );
    for args in commands("link").into_iter().chain(commands("null")) {
        run_ok(dir.path(), &args);
        let after = (kind(&dir.join("null")), kind(&dir.join("link")));
        assert_eq!(after, before, "{args:?} changed the device or the link");
    }
    // The picture of a trace, where the picture's name is a link to the device.
    run_ok(dir.path(), &commands("t.arrow")[1]);
    std::os::unix::fs::symlink("null", dir.join("t-cg.png")).expect("symlink");
    run_ok(dir.path(), &["plot".into(), "t.arrow".into()]);
    assert_eq!(
        kind(&dir.join("t-cg.png")),
        before.1,
        "plot replaced the link"
    );
    assert_eq!(kind(&dir.join("null")), before.0, "plot changed the device");
    let entries = dir.entries();
    assert!(
        !entries
            .iter()
            .any(|e| e.ends_with(".partial") || e.starts_with("null.")),
        "{entries:?}"
    );
}

#[test]
fn a_symlink_to_a_regular_file_keeps_pointing_at_the_new_file() {
    let dir = TempDir::new("link-file");
    prepare(&dir);
    std::fs::create_dir(dir.join("real")).expect("mkdir");
    dir.write("real/sweep.arrow", "old");
    std::os::unix::fs::symlink("real/sweep.arrow", dir.join("link.arrow")).expect("symlink");
    run_ok(dir.path(), &commands("link.arrow")[0]);
    run_ok(dir.path(), &commands("file.arrow")[0]);
    assert_eq!(kind(&dir.join("link.arrow")).0, "symlink");
    assert!(read_bytes(&dir.join("real/sweep.arrow")) == read_bytes(&dir.join("file.arrow")));
}

/// The record batches of an Arrow IPC file or stream.
fn batches(bytes: &[u8], stream: bool) -> Vec<arrow_array::RecordBatch> {
    let read: Vec<Result<_, _>> = if stream {
        arrow_ipc::reader::StreamReader::try_new(bytes, None)
            .expect("an IPC stream")
            .collect()
    } else {
        arrow_ipc::reader::FileReader::try_new(std::io::Cursor::new(bytes), None)
            .expect("an IPC file")
            .collect()
    };
    read.into_iter().map(|b| b.expect("a batch")).collect()
}

#[test]
fn out_dash_streams_the_table_of_the_file_to_a_pipe() {
    let dir = TempDir::new("stdout");
    prepare(&dir);
    for (file_args, pipe_args) in commands("file.arrow").into_iter().zip(commands("-")) {
        run_ok(dir.path(), &file_args);
        let file = batches(&read_bytes(&dir.join("file.arrow")), false);
        // Piped into a reader as it comes, not buffered by the test.
        let mut child = Command::new(BIN)
            .args(&pipe_args)
            .current_dir(dir.path())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run touchdown");
        let reader = arrow_ipc::reader::StreamReader::try_new(child.stdout.take().unwrap(), None)
            .expect("an IPC stream on stdout");
        let piped: Vec<_> = reader.map(|b| b.expect("a batch")).collect();
        let o = child.wait_with_output().expect("wait");
        assert!(o.status.success(), "{pipe_args:?}");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(
            stderr.contains("wrote standard output"),
            "{pipe_args:?}: {stderr}"
        );
        assert_eq!(piped, file, "{pipe_args:?}: the stream holds another table");
        assert_eq!(
            piped[0].schema().metadata(),
            file[0].schema().metadata(),
            "{pipe_args:?}: metadata"
        );
    }
    assert_eq!(
        batches(&run_ok(dir.path(), &commands("-")[0]), true).len(),
        1,
        "300 rows in one batch"
    );
}
