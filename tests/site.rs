//! `touchdown site` end to end: a spinning sphere's map against the closed form of its
//! gravity and slopes (and its roughness against the shape layer's), its facets' P(stable)
//! against direct sweeps at their own slope and gravity, and bad shapes and flags refused
//! with exit code 2.

use crate::common::{TempDir, arrow_column as column, touchdown};
use crate::shape::icosphere;
use touchdown::shape::{Mesh, roughness_deg};

/// The mesh as OBJ text, in metres.
fn obj(mesh: &Mesh) -> String {
    let mut s = String::from("# a test body\n");
    for v in &mesh.vertices {
        s += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in &mesh.facets {
        s += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    s
}

/// The names of the Arrow file's columns, in order.
fn column_names(path: &std::path::Path) -> Vec<String> {
    let file = std::fs::File::open(path).expect("open the table");
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).expect("an Arrow file");
    reader
        .schema()
        .fields()
        .iter()
        .map(|f| f.name().clone())
        .collect()
}

/// A sphere of radius 30 km and density 2000 kg/m^3 (surface gravity 0.0168 m/s^2, the
/// default scenario's), spinning in 3.3 h: `w^2 R` is half its gravity, so the effective
/// gravity falls from `g` at the poles to `g / 2` at the equator and slopes reach 19.5 deg
/// at 45 deg of latitude.
const RADIUS_M: f64 = 30_000.0;
const DENSITY: f64 = 2000.0;
const PERIOD_H: f64 = 3.3;

/// A lander gentler than the default's, so that P(stable) spans 0.2-0.9 on the sphere.
const GENTLE: &str = "[inputs]\nrelease_height_m = { dist = \"uniform\", min = 0.5, max = 2.0 }\n\
    rate_x_deg_s = { dist = \"normal\", mean = 0.0, sd = 0.2 }\n\
    rate_y_deg_s = { dist = \"normal\", mean = 0.0, sd = 0.2 }\n\
    rate_z_deg_s = { dist = \"normal\", mean = 0.0, sd = 0.2 }\n\
    [simulation]\nt_max_s = 60.0\n";

/// `touchdown site SHAPE` at 2000 kg/m^3 with the body's units and spin period, a sample
/// count and an output folder, then `extra` (the tests' common arguments).
fn site_args(
    shape: &str,
    units: &str,
    period: &str,
    samples: &str,
    out: &str,
    extra: &[&str],
) -> Vec<String> {
    let mut args: Vec<String> = [
        "site",
        shape,
        "--units",
        units,
        "--density",
        "2000",
        "--spin-period",
        period,
        "--samples",
        samples,
        "--out-dir",
        out,
    ]
    .iter()
    .map(|s| (*s).to_string())
    .collect();
    args.extend(extra.iter().map(|s| (*s).to_string()));
    args
}

/// Runs `touchdown` in `dir` with `args`.
fn run_site(dir: &TempDir, args: &[String]) -> crate::common::Run {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    touchdown(dir.path(), &args)
}

/// The stable count and the sample count a sweep's summary prints.
fn stable_of(stdout: &str) -> (u64, u64) {
    let number = |key: &str| {
        stdout
            .lines()
            .find_map(|l| l.trim().strip_prefix(key))
            .and_then(|r| r.split_whitespace().next())
            .and_then(|n| n.parse::<u64>().ok())
            .unwrap_or_else(|| panic!("no {key:?} line in {stdout}"))
    };
    (number("stable"), number("samples"))
}

#[test]
fn a_spinning_spheres_map_matches_its_closed_form_and_direct_sweeps() {
    let dir = TempDir::new("site-sphere");
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 3)));
    dir.write("gentle.toml", GENTLE);
    let period = PERIOD_H.to_string();
    let args = site_args(
        "sphere.obj",
        "m",
        &period,
        "20000",
        "map",
        &["--scenario", "gentle.toml", "--quiet"],
    );
    let run = run_site(&dir, &args);
    assert_eq!(run.code, Some(0), "{run}");
    let table = dir.join("map/facets.arrow");
    for f in [
        "map/sweep.arrow",
        "map/site.md",
        "map/map.png",
        "map/site.html",
    ] {
        assert!(dir.join(f).is_file(), "no {f}: {run}");
    }
    let get = |name: &str| column(&table, name).unwrap_or_else(|| panic!("no column {name}"));
    let (lat, slope, g) = (get("latitude_deg"), get("slope_deg"), get("gravity_m_s2"));
    assert_eq!(lat.len(), 1280);
    // The closed form of a spinning sphere: at latitude phi the effective gravity has the
    // components `g - w^2 R cos^2 phi` (radial) and `w^2 R cos phi sin phi` (towards the
    // equator), its slope is their angle. A facet of this icosphere (1280 facets) is up to
    // 4.4 deg wide, its centroid 0.3 % inside the sphere and its normal up to ~2 deg off the
    // radial: slopes within 2.5 deg and gravity within 1.5 % of the closed form at the
    // centroid's latitude (the attraction of the polyhedron, 0.2 % under the sphere's
    // volume, and the centroid's depth make up the latter).
    let g0 = 4.0 / 3.0 * std::f64::consts::PI * 6.674_30e-11 * DENSITY * RADIUS_M;
    let w2r = (2.0 * std::f64::consts::PI / (PERIOD_H * 3600.0)).powi(2) * RADIUS_M;
    for i in 0..lat.len() {
        let phi = lat[i].to_radians();
        let (radial, along) = (
            g0 - w2r * phi.cos().powi(2),
            w2r * phi.cos() * phi.sin().abs(),
        );
        let closed_slope = along.atan2(radial).to_degrees();
        let closed_g = radial.hypot(along);
        assert!(
            (slope[i] - closed_slope).abs() < 2.5,
            "facet {i} at {:.1} deg: slope {} against {closed_slope}",
            lat[i],
            slope[i]
        );
        assert!(
            (g[i] / closed_g - 1.0).abs() < 0.015,
            "facet {i}: gravity {} against {closed_g}",
            g[i]
        );
    }
    // The roughness is the shape layer's, facet by facet: the OBJ text writes each
    // coordinate in the shortest form that reads back the same, in metres, so the map's mesh
    // is the test's to the bit and the values agree to their rounding (1e-12 deg allows for
    // none). And it sits next to the slope in the table.
    let rough = get("roughness_deg");
    let expected = roughness_deg(&icosphere(RADIUS_M, 3).check().expect("a sound mesh"));
    assert_eq!(rough.len(), expected.len());
    for (i, (r, e)) in rough.iter().zip(&expected).enumerate() {
        assert!(
            (r - e).abs() <= 1e-12,
            "facet {i}: roughness {r} against {e}"
        );
    }
    let names = column_names(&table);
    let at = |name: &str| names.iter().position(|n| n == name);
    assert_eq!(
        at("roughness_deg"),
        at("slope_deg").map(|k| k + 1),
        "{names:?}"
    );
    // The summary's line: the mean by area and the largest, as the table has them.
    let area = get("area_m2");
    let total: f64 = area.iter().sum();
    let mean = rough.iter().zip(&area).map(|(r, a)| r * a).sum::<f64>() / total;
    let roughest = rough.iter().copied().fold(0.0, f64::max);
    let summary = std::fs::read_to_string(dir.join("map/site.md")).unwrap();
    let line = summary
        .lines()
        .find(|l| l.starts_with("| roughness |"))
        .unwrap_or_else(|| panic!("no roughness line in {summary}"));
    assert!(
        line.starts_with(&format!(
            "| roughness | mean {mean:.2} deg by area, median "
        )) && line.contains(&format!(", roughest {roughest:.2} ")),
        "{line}"
    );
    // Three facets' P(stable) against a direct sweep at their own slope and gravity (3,000
    // samples each, the lander otherwise drawn as in the map): the 95 % intervals must
    // overlap. The map's share averages P over +-1 deg and +-5 % of gravity; P changes by
    // at most ~3 % per degree here, so that averaging moves it well inside the intervals.
    let (p, lo, hi) = (get("p_stable"), get("p_stable_low"), get("p_stable_high"));
    let mut order: Vec<usize> = (0..lat.len()).collect();
    order.sort_by(|a, b| slope[*a].total_cmp(&slope[*b]));
    for &i in &[order[20], order[640], order[1260]] {
        let text = format!(
            "gravity_m_s2 = {}\n{}",
            g[i],
            GENTLE.replace(
                "[inputs]\n",
                &format!("[inputs]\nslope_deg = {}\n", slope[i])
            )
        );
        dir.write("direct.toml", &text);
        let out = format!("direct-{i}.arrow");
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                "direct.toml",
                "--samples",
                "3000",
                "--out",
                &out,
            ],
        );
        assert_eq!(run.code, Some(0), "{run}");
        let (k, n) = stable_of(&run.stdout);
        let q = k as f64 / n as f64;
        let z = 1.96 * (q * (1.0 - q) / n as f64).sqrt();
        assert!(
            q - z <= hi[i] && q + z >= lo[i],
            "facet {i} (slope {:.2} deg, g {:.4e}): map {:.3} [{:.3}, {:.3}], direct {q:.3} +- {z:.3}",
            slope[i],
            g[i],
            p[i],
            lo[i],
            hi[i]
        );
    }
    // Run again: the sweep is kept, and the table is the same.
    let before = std::fs::read(&table).unwrap();
    let again = run_site(&dir, &args);
    assert!(again.stdout.contains("kept (done before)"), "{again}");
    assert_eq!(std::fs::read(&table).unwrap(), before);
}

#[test]
fn bad_shapes_and_flags_are_refused_naming_them() {
    let dir = TempDir::new("site-bad");
    let cube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
    let faces = [
        "f 1 3 2", "f 1 4 3", "f 5 6 7", "f 5 7 8", "f 1 2 6", "f 1 6 5", "f 2 3 7", "f 2 7 6",
        "f 3 4 8", "f 3 8 7", "f 4 1 5", "f 4 5 8",
    ];
    let whole = format!("{cube}{}\n", faces.join("\n"));
    let open = format!("{cube}{}\n", faces[..11].join("\n"));
    let inverted = whole
        .lines()
        .map(|l| match l.strip_prefix("f ") {
            Some(r) => {
                let v: Vec<&str> = r.split(' ').collect();
                format!("f {} {} {}", v[0], v[2], v[1])
            }
            None => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n");
    let degenerate = format!("{whole}v 2 0 0\nv 3 0 0\nf 1 9 10\n");
    for (name, text, expect) in [
        ("open", open.as_str(), "not closed"),
        ("inverted", inverted.as_str(), "inverted"),
        ("degenerate", degenerate.as_str(), "degenerate"),
        ("not OBJ", "v 1 2\n", "line 1"),
    ] {
        dir.write("body.obj", text);
        let run = run_site(
            &dir,
            &site_args("body.obj", "km", "5", "100", "out", &["--quiet"]),
        );
        assert_eq!(run.code, Some(2), "{name}: {run}");
        assert!(
            run.stderr.contains(expect) && run.stderr.contains("body.obj"),
            "{name}: no {expect:?} in {run}"
        );
        assert!(!run.stderr.contains("panicked"), "{name}: {run}");
        assert!(!dir.join("out/sweep.arrow").exists(), "{name}");
    }
    dir.write("body.obj", &whole);
    for (name, flags, expect) in [
        (
            "no units",
            vec!["--density", "2000", "--spin-period", "5"],
            "--units",
        ),
        (
            "a density of 0",
            vec!["--units", "m", "--density", "0", "--spin-period", "5"],
            "--density",
        ),
        (
            "a zero spin axis",
            vec!["--spin-axis", "0,0,0"],
            "--spin-axis",
        ),
        (
            "a gravity window of 1",
            vec!["--gravity-window", "1"],
            "--gravity-window",
        ),
        // Windows so fine that the grid counting the samples would outgrow any machine:
        // refused before the sweep (which would run 1e6 samples here), not an abort after.
        (
            "a gravity window too fine to count in",
            vec!["--gravity-window", "1e-9"],
            "--gravity-window 0.000000001",
        ),
        (
            "a slope window too fine to count in",
            vec!["--slope-window", "1e-12"],
            "--slope-window 0.000000000001 and --gravity-window",
        ),
    ] {
        let mut args = vec!["site", "body.obj", "--out-dir", "out", "--quiet"];
        // The body's flags where the case is not about them.
        if flags.len() == 2 {
            args.extend(["--units", "m", "--density", "2000", "--spin-period", "5"]);
        }
        args.extend(flags);
        let run = touchdown(dir.path(), &args);
        assert_eq!(run.code, Some(2), "{name}: {run}");
        assert!(
            run.stderr.contains(expect),
            "{name}: no {expect:?} in {run}"
        );
    }
}

/// A map whose sweep ran as shards (`--shard K/N`, as a cluster runs them) is the map of
/// one process, byte for byte; a missing shard is named, and a shard makes no map.
#[test]
fn a_maps_sweep_run_in_shards_gives_the_same_map() {
    let dir = TempDir::new("site-shards");
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 2)));
    dir.write("gentle.toml", GENTLE);
    let period = PERIOD_H.to_string();
    let run = |extra: &[&str], out: &'static str| {
        let mut a = site_args(
            "sphere.obj",
            "m",
            &period,
            "3000",
            out,
            &["--scenario", "gentle.toml", "--quiet"],
        );
        a.extend(extra.iter().map(|s| (*s).to_string()));
        run_site(&dir, &a)
    };
    run(&[], "whole").assert_ok();
    let first = run(&["--shard", "0/2"], "cut");
    first.assert_ok();
    assert!(
        dir.join("cut/sweep.shard-0-of-2.arrow").is_file()
            && !dir.join("cut/facets.arrow").exists()
            && !dir.join("cut/sweep.arrow").exists(),
        "a shard makes its slice and no map: {first}"
    );
    assert!(
        first.stdout.contains("shard 0/2 of the map's sweep"),
        "{first}"
    );
    let missing = run(&[], "cut");
    assert_eq!(missing.code, Some(2), "{missing}");
    assert!(missing.stderr.contains("lacks shard 1/2"), "{missing}");
    // Refused by the shards' names alone, before the facets' gravity: before the shape is
    // even read (this one is not closed, and that is not what is said).
    dir.write("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let early = run_site(&dir, &site_args("open.obj", "m", "3.3", "3000", "cut", &[]));
    assert_eq!(early.code, Some(2), "{early}");
    assert!(
        early
            .stderr
            .contains("the map's sweep is sharded 2 ways and lacks shard 1/2"),
        "{early}"
    );
    run(&["--shard", "1/2"], "cut").assert_ok();
    let merged = run(&[], "cut");
    merged.assert_ok();
    assert!(
        merged
            .stdout
            .contains("merged from 2 shards (3000 samples)"),
        "{merged}"
    );
    for f in [
        "sweep.arrow",
        "facets.arrow",
        "site.md",
        "map.png",
        "site.html",
    ] {
        let (a, b) = (
            std::fs::read(dir.join(&format!("whole/{f}"))).unwrap(),
            std::fs::read(dir.join(&format!("cut/{f}"))).unwrap(),
        );
        assert!(
            a == b,
            "{f} differs between the sharded map and the whole one"
        );
    }
    // The same command again keeps the merged sweep.
    let again = run(&[], "cut");
    again.assert_ok();
    assert!(again.stdout.contains("kept (done before)"), "{again}");
}

/// A shape model whose centre of mass lies away from its frame's origin (about which the
/// spin turns) is mapped with a warning that gives where it lies; a centred one is not.
#[test]
fn a_body_off_its_origin_is_warned_of() {
    let dir = TempDir::new("site-off-centre");
    let mut sphere = icosphere(RADIUS_M, 2);
    let run = |dir: &TempDir, name: &str| {
        let file = format!("{name}.obj");
        run_site(
            dir,
            &site_args(&file, "m", "3.3", "200", name, &["--quiet"]),
        )
    };
    dir.write("centred.obj", &obj(&sphere));
    let centred = run(&dir, "centred");
    centred.assert_ok();
    assert!(!centred.stderr.contains("centre of mass"), "{centred}");
    // Moved by 0.1 R along x: 5 % of the bounding box's diagonal (2 R sqrt(3)), past the 1 %
    // a map warns at. The centre of mass of a polyhedron moves with it exactly.
    for v in &mut sphere.vertices {
        v[0] += 0.1 * RADIUS_M;
    }
    dir.write("moved.obj", &obj(&sphere));
    let moved = run(&dir, "moved");
    assert_eq!(moved.code, Some(0), "{moved}");
    assert!(
        moved
            .stderr
            .contains("moved.obj: its centre of mass at constant density lies 3000.000 m"),
        "{moved}"
    );
    assert!(
        moved
            .stdout
            .contains("| centre of mass | (3000.00, 0.00, 0.00) m from the origin"),
        "{moved}"
    );
}

/// A map where no facet is a landing site says so plainly: an area of none is "0 m^2".
#[test]
fn a_map_without_a_landing_site_says_none() {
    let dir = TempDir::new("site-none");
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 1)));
    // Spun at 200 deg/s, every lander tips over.
    dir.write(
        "spin.toml",
        "[inputs]\nrate_x_deg_s = 200.0\n[simulation]\nt_max_s = 20.0\n",
    );
    let period = PERIOD_H.to_string();
    let run = run_site(
        &dir,
        &site_args(
            "sphere.obj",
            "m",
            &period,
            "200",
            "map",
            &["--scenario", "spin.toml", "--quiet"],
        ),
    );
    run.assert_ok();
    let summary = std::fs::read_to_string(dir.join("map/site.md")).expect("site.md");
    assert!(
        summary.contains("**P(stable) >= 0.99 on 0.00 % of the surface** (0 m^2)."),
        "{summary}"
    );
}
