//! The bodies of `bodies/`. The shipped one, Didymos: its file is the one its SOURCE.md
//! names, and its map holds Gauss's law and the published size. And `bodies/convert.py`,
//! which makes the Itokawa model from its PDS product (the file itself is not kept:
//! bodies/itokawa/SOURCE.md): a plate model in kilometres becomes an OBJ in metres, exactly,
//! with its header, that `touchdown site` reads; a bad mesh fails its checks.

use crate::common::{TempDir, arrow_column as column, touchdown};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A path in the repository.
fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// The sha256 of a file, by Python's standard library (as a user would check it).
fn sha256(path: &Path) -> String {
    let out = Command::new("python3")
        .args([
            "-c",
            "import hashlib, sys; print(hashlib.sha256(open(sys.argv[1], 'rb').read()).hexdigest())",
        ])
        .arg(path)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).trim().to_string()
}

/// The sha256 of the shipped Didymos model, as bodies/didymos/SOURCE.md gives it.
const DIDYMOS_SHA256: &str = "f761022cc2c001fcb2f6ed55562248a911dbb24c8fb215319a602b2d3f3b5fff";

#[test]
fn the_shipped_didymos_model_is_the_file_its_source_names() {
    // SOURCE.md says where the file comes from and gives its sha256; the README's map was
    // made from these bytes. A changed file, or a SOURCE.md that no longer names it, fails.
    assert_eq!(sha256(&repo("bodies/didymos/didymos.obj")), DIDYMOS_SHA256);
    let source = std::fs::read_to_string(repo("bodies/didymos/SOURCE.md")).expect("SOURCE.md");
    assert!(
        source.contains(DIDYMOS_SHA256),
        "SOURCE.md must give the file's sha256"
    );
    assert!(
        repo("bodies/didymos/LICENSE").is_file(),
        "the licence ships with the file"
    );
}

#[test]
fn the_didymos_map_holds_gauss_law_and_the_published_size() {
    // The map of the shipped body at the README's density and spin (1,000 samples: the
    // body's numbers do not depend on the sweep, and a map of this body refuses fewer than
    // about 800, too few for its median facet's window to hold one).
    let dir = TempDir::new("bodies-didymos");
    let (shape, scenario) = (
        repo("bodies/didymos/didymos.obj"),
        repo("scenarios/didymos.toml"),
    );
    let (density, period_h) = (2170.0_f64, 2.26_f64);
    let run = touchdown(
        dir.path(),
        &[
            "site",
            shape.to_str().unwrap(),
            "--units",
            "km",
            "--density",
            "2170",
            "--spin-period",
            "2.26",
            "--scenario",
            scenario.to_str().unwrap(),
            "--samples",
            "1000",
            "--out-dir",
            "map",
            "--quiet",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    let table = dir.join("map/facets.arrow");
    let get = |name: &str| column(&table, name).unwrap_or_else(|| panic!("no column {name}"));
    let c = [
        get("centroid_x_m"),
        get("centroid_y_m"),
        get("centroid_z_m"),
    ];
    let n = [get("normal_x"), get("normal_y"), get("normal_z")];
    let g = [
        get("effective_gravity_x_m_s2"),
        get("effective_gravity_y_m_s2"),
        get("effective_gravity_z_m_s2"),
    ];
    let area = get("area_m2");
    assert_eq!(area.len(), 1996, "the radar model's 1,996 facets");
    let dot = |a: &[Vec<f64>; 3], b: &[Vec<f64>; 3], i: usize| {
        a[0][i] * b[0][i] + a[1][i] * b[1][i] + a[2][i] * b[2][i]
    };
    // The volume by the divergence theorem, exact for flat facets (c . n is the same at every
    // point of one): the radar model's volume-equivalent diameter is 780 +- 30 m (Naidu et
    // al. 2020). A wrong unit is a factor of 1000 off.
    let volume: f64 = (0..area.len())
        .map(|i| dot(&c, &n, i) * area[i] / 3.0)
        .sum();
    let diameter = 2.0 * (3.0 * volume / (4.0 * std::f64::consts::PI)).cbrt();
    assert!((diameter - 780.0).abs() < 30.0, "diameter {diameter} m");
    // Gauss's law for the effective gravity: the attraction's flux out of the body is
    // -4 pi G M, and the centrifugal acceleration w^2 (x, y, 0) has divergence 2 w^2, so
    // the flux of the sum is -4 pi G rho V + 2 w^2 V. The two terms (-452 and +297 m^3/s^2
    // here) nearly cancel, so an error of 1 % in the density or 0.3 % in the spin rate moves
    // the sum by more than 1 %. The map gives the field at each facet's centroid only: the
    // one-point rule over facets about 48 m wide on a 390 m body was measured 0.42 % off;
    // 1 % allows for that. Gauss's law holds for any mass inside, so this checks the mass,
    // G, the units and the spin's rate and sense, not the field's shape (tests/site.rs and
    // tests/shape/gravity.rs check that against closed forms).
    let w = 2.0 * std::f64::consts::PI / (period_h * 3600.0);
    let expected =
        -4.0 * std::f64::consts::PI * 6.674_30e-11 * density * volume + 2.0 * w * w * volume;
    let flux: f64 = (0..area.len()).map(|i| dot(&g, &n, i) * area[i]).sum();
    assert!(
        (flux / expected - 1.0).abs() < 0.01,
        "flux {flux} m^3/s^2 against {expected}"
    );
    // Near the equator the spin takes more than the attraction gives: the effective gravity
    // points off the ground (slope over 90 deg). The summary gives that share of the surface
    // on its own row, and it is the table's, to the summary's two decimals.
    let slope = get("slope_deg");
    let total: f64 = area.iter().sum();
    let off: f64 = (0..area.len())
        .filter(|&i| slope[i] > 90.0)
        .map(|i| area[i])
        .sum();
    assert!(off > 0.0, "no facet past 90 deg");
    let summary = std::fs::read_to_string(dir.join("map/site.md")).expect("site.md");
    let row = format!(
        "| none: the effective gravity points off the ground (slope over 90 deg) | {:.2} % |",
        100.0 * off / total
    );
    assert!(summary.contains(&row), "no {row:?} in {summary}");
}

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
    let script = repo("bodies/convert.py");
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
    assert_eq!(
        sha256(&repo("bodies/itokawa/header.txt")),
        "524c47b063fd92a81c6df17b578ee9bbf6a658bfd0ec92dc0c388c4918dc4a1a"
    );
}
