//! `bodies/convert.py`, which makes the worked example's shape model from its PDS product
//! (the file itself is not kept: bodies/itokawa/SOURCE.md): a plate model in kilometres
//! becomes an OBJ in metres, exactly, with its header, that `touchdown site` reads; a bad
//! mesh fails its checks.

use crate::common::TempDir;
use std::process::Command;

/// An octahedron of half-diagonal `a` km in the PDS plate form (`v` rows in km, then `f`
/// rows, 1-based, counter-clockwise seen from outside), CRLF line ends as the PDS file has.
fn octahedron_tab(a: &str, flip_last: bool) -> String {
    let v = [
        format!("{a} 0 0"),
        format!("-{a} 0 0"),
        format!("0 {a} 0"),
        format!("0 -{a} 0"),
        format!("0 0 {a}"),
        format!("0 0 -{a}"),
    ];
    let mut f = vec![
        [1, 3, 5],
        [3, 2, 5],
        [2, 4, 5],
        [4, 1, 5],
        [3, 1, 6],
        [2, 3, 6],
        [4, 2, 6],
        [1, 4, 6],
    ];
    if flip_last {
        f[7].swap(1, 2);
    }
    let mut s = String::new();
    for r in &v {
        s += &format!("v {r}\r\n");
    }
    for r in &f {
        s += &format!("f {} {} {}\r\n", r[0], r[1], r[2]);
    }
    s
}

/// Runs convert.py in `dir` with `args`.
fn convert(dir: &TempDir, args: &[&str]) -> std::process::Output {
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("bodies/convert.py");
    Command::new("python3")
        .arg(script)
        .args(args)
        .current_dir(dir.path())
        .output()
        .expect("python3 runs")
}

#[test]
fn a_pds_plate_model_becomes_an_obj_in_metres_that_site_reads() {
    let dir = TempDir::new("bodies-convert");
    // 0.1234567 km: seven digits, so a float product (123.45670000000001) would show.
    dir.write("body.tab", &octahedron_tab("0.1234567", false));
    dir.write("header.txt", "a test body\n  its second line\n");
    let out = convert(&dir, &["body.tab", "body.obj", "header.txt"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && stdout.contains("ALL CHECKS PASS"),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let obj = std::fs::read_to_string(dir.join("body.obj")).unwrap();
    assert!(!obj.contains('\r'), "LF line ends");
    let lines: Vec<&str> = obj.lines().collect();
    assert_eq!(lines[..2], ["# a test body", "#   its second line"]);
    assert_eq!(lines[2], "v 123.4567 0 0", "km to m exactly");
    assert_eq!(lines[3], "v -123.4567 0 0");
    assert_eq!(lines[8], "f 1 3 5", "facets as given, 1-based");
    assert_eq!(lines.len(), 2 + 6 + 8);
    // The engine reads it as metres: the octahedron's volume is 4/3 a^3 (to rounding).
    let mesh = touchdown::shape::read_obj(&dir.join("body.obj"), 1.0)
        .unwrap()
        .check()
        .unwrap();
    let a: f64 = 123.4567;
    assert!((mesh.volume_m3() / (4.0 / 3.0 * a.powi(3)) - 1.0).abs() < 1e-12);
    // And `--check` of the result passes alone.
    let again = convert(&dir, &["--check", "body.obj"]);
    assert!(again.status.success(), "{again:?}");
}

#[test]
fn a_mesh_with_a_flipped_facet_fails_the_converters_checks() {
    let dir = TempDir::new("bodies-flipped");
    dir.write("body.tab", &octahedron_tab("0.1", true));
    dir.write("header.txt", "a flipped body\n");
    let out = convert(&dir, &["body.tab", "body.obj", "header.txt"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        !out.status.success() && !stdout.contains("ALL CHECKS PASS"),
        "a flipped facet must fail: {stdout}"
    );
}

#[test]
fn the_itokawa_header_is_the_one_the_readme_map_was_made_with() {
    // SOURCE.md gives the sha256 of the OBJ that the README's map was made from; the header
    // is part of those bytes, so it must be the header of that file to the byte (its sha256
    // here; a change to it changes the OBJ's, and SOURCE.md and this test must say so).
    let header = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("bodies/itokawa/header.txt");
    let out = Command::new("python3")
        .args([
            "-c",
            "import hashlib, sys; print(hashlib.sha256(open(sys.argv[1], 'rb').read()).hexdigest())",
        ])
        .arg(&header)
        .output()
        .expect("python3 runs");
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        "524c47b063fd92a81c6df17b578ee9bbf6a658bfd0ec92dc0c388c4918dc4a1a",
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
