//! `touchdown site` end to end: a spinning sphere's map against the closed form of its
//! gravity and slopes (and its roughness against the shape layer's), its facets' P(stable)
//! against direct sweeps at their own slope and gravity, and bad shapes and flags refused
//! with exit code 2.

use crate::common::{TempDir, arrow_column as column, touchdown};
use crate::shape::icosphere;
use touchdown::shape::{Mesh, roughness_deg};

/// The mesh as OBJ text, in metres.
pub(crate) fn obj(mesh: &Mesh) -> String {
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
pub(crate) const RADIUS_M: f64 = 30_000.0;
const DENSITY: f64 = 2000.0;
pub(crate) const PERIOD_H: f64 = 3.3;

/// A lander gentler than the default's, so that P(stable) spans 0.2-0.9 on the sphere.
pub(crate) const GENTLE: &str = "[inputs]\nrelease_height_m = { dist = \"uniform\", min = 0.5, max = 2.0 }\n\
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

/// Runs `touchdown site sphere.obj` (in metres, spinning in `PERIOD_H`) in `dir` with a
/// sample count, an output folder and `extra`.
fn run_sphere(dir: &TempDir, samples: &str, out: &str, extra: &[&str]) -> crate::common::Run {
    run_site(
        dir,
        &site_args(
            "sphere.obj",
            "m",
            &PERIOD_H.to_string(),
            samples,
            out,
            extra,
        ),
    )
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
    let moved = cube.replace("v 0", "v 0.5").replace("v 1", "v 1.5");
    let shifted: Vec<String> = faces
        .iter()
        .map(|f| {
            let v: Vec<u32> = f[2..]
                .split(' ')
                .map(|x| x.parse::<u32>().unwrap() + 8)
                .collect();
            format!("f {} {} {}", v[0], v[1], v[2])
        })
        .collect();
    let overlapping = format!(
        "{cube}{moved}{}\n{}\n",
        faces.join("\n"),
        shifted.join("\n")
    );
    for (name, text, expect) in [
        ("open", open.as_str(), "not closed"),
        ("inverted", inverted.as_str(), "inverted"),
        ("degenerate", degenerate.as_str(), "degenerate"),
        ("not OBJ", "v 1 2\n", "line 1"),
        // Two copies of the cube, the second moved by half its side: they overlap.
        (
            "overlapping",
            overlapping.as_str(),
            "intersects itself: facets",
        ),
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
    let run = run_sphere(&dir, "200", "map", &["--scenario", "spin.toml", "--quiet"]);
    run.assert_ok();
    let summary = std::fs::read_to_string(dir.join("map/site.md")).expect("site.md");
    assert!(
        summary.contains(
            "**P(stable) >= 0.99 with 95 % confidence (the low end of its Wilson interval) on \
             0.00 % of the surface** (0 m^2); by the point estimate (its share of samples \
             alone) on 0.00 % (0 m^2)."
        ),
        "{summary}"
    );
}

/// The `samples` column of a facets' table.
pub(crate) fn samples_of(path: &std::path::Path) -> Vec<u64> {
    let file = std::fs::File::open(path).expect("open the table");
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).expect("an Arrow file");
    let mut out = Vec::new();
    for b in reader {
        let b = b.expect("a batch");
        let c = b.column_by_name("samples").expect("a samples column");
        let c = c
            .as_any()
            .downcast_ref::<arrow_array::UInt64Array>()
            .expect("UInt64");
        out.extend(c.values().iter().copied());
    }
    out
}

/// The share of the surface a row of the summary's P(stable) table gives, %.
fn row_share(summary: &str, row: &str) -> f64 {
    summary
        .lines()
        .find(|l| l.starts_with(&format!("| {row}")))
        .and_then(|l| l.rsplit('|').nth(1))
        .and_then(|c| c.trim().trim_end_matches(" %").parse().ok())
        .unwrap_or_else(|| panic!("no row {row:?} in {summary}"))
}

/// Issue 45: facets that could be stood on but whose windows held no sample are "no
/// samples", not "too steep" (on a sphere whose steepest facet is 20 deg, nothing is too
/// steep); and `--samples` too few for a map is refused before its sweep, 0 as a sweep
/// refuses it, where before a map of 0 or 1 samples printed NaN shares.
#[test]
fn facets_without_samples_are_told_apart_from_steep_ones_and_too_few_samples_refused() {
    let dir = TempDir::new("site-no-samples");
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 2)));
    // +-0.05 deg of slope: about 1.5 samples a window, many facets with none.
    let fine = ["--slope-window", "0.05", "--quiet"];
    run_sphere(&dir, "2000", "fine", &fine).assert_ok();
    let table = dir.join("fine/facets.arrow");
    let (slope, area) = (
        column(&table, "slope_deg").unwrap(),
        column(&table, "area_m2").unwrap(),
    );
    // Every facet could be stood on (under 21 deg): those without shares had no samples.
    assert!(slope.iter().all(|s| *s < 21.0), "{slope:?}");
    let samples = samples_of(&table);
    let total: f64 = area.iter().sum();
    let empty: f64 = (0..area.len())
        .filter(|&i| samples[i] == 0)
        .map(|i| area[i])
        .sum::<f64>()
        / total;
    assert!(empty > 0.05, "{empty}");
    let summary = std::fs::read_to_string(dir.join("fine/site.md")).unwrap();
    let no_samples = row_share(&summary, "none: no samples in its window");
    assert!(
        (no_samples - 100.0 * empty).abs() < 0.006,
        "{no_samples}: {summary}"
    );
    assert_eq!(row_share(&summary, "none: too steep"), 0.0, "{summary}");
    assert!(
        summary.contains("Samples per facet a lander could stand on: 0 at least"),
        "{summary}"
    );
    assert!(!summary.contains("NaN"), "{summary}");
    // 0 as a sweep refuses it; 1, and 50 (0.04 a window), too few for this map: the message
    // names the flag and how many it needs.
    for (n, expect) in [
        ("0", "--samples must be at least 1"),
        ("1", "--samples 1: too few for this map"),
        ("50", "--samples 50: too few for this map"),
    ] {
        let run = run_sphere(&dir, n, &format!("few-{n}"), &fine);
        assert_eq!(run.code, Some(2), "{n}: {run}");
        assert!(run.stderr.contains(expect), "{n}: {run}");
        assert!(!dir.join(&format!("few-{n}/sweep.arrow")).exists(), "{n}");
    }
    // The least count accepted is the one named.
    let refused = run_sphere(&dir, "50", "few", &["--quiet"]);
    let needed = refused
        .stderr
        .split("needs at least ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .unwrap_or_else(|| panic!("{refused}"))
        .to_string();
    run_sphere(&dir, &needed, "enough", &["--quiet"]).assert_ok();
}

/// Issue 45: samples that diverged or never touched the ground are counted in the summary,
/// and the warning names the likely cause, the body's gravity from its density and units:
/// at 1e12 kg/m^3 every sample diverges (before: a map of 0 everywhere, a warning of a
/// release too high); on a 400 m body the default lander (made for 0.0168 m/s^2) often
/// leaves the ground for good.
#[test]
fn diverged_and_untouched_samples_are_counted_and_their_cause_named() {
    let dir = TempDir::new("site-failures");
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 1)));
    let period = PERIOD_H.to_string();
    let mut args = site_args("sphere.obj", "m", &period, "300", "dense", &["--quiet"]);
    args[5] = "1e12".into();
    let run = run_site(&dir, &args);
    assert_eq!(run.code, Some(0), "{run}");
    let summary = std::fs::read_to_string(dir.join("dense/site.md")).unwrap();
    assert!(
        summary.contains(
            "Of the sweep's 300 samples, 300 (100.00 %) diverged and 0 (0.00 %) never touched"
        ),
        "{summary}"
    );
    for text in [&summary, &run.stderr] {
        assert!(
            text.contains("300 of the 300 samples (100.00 %) diverged")
                && text.contains("--density 1000000000000 kg/m^3")
                && text.contains("check --density (kg/m^3) and --units"),
            "{text}"
        );
    }
    assert!(!run.stderr.contains("release too high"), "{run}");
    // A body of 400 m at 2000 kg/m^3: about 1.1e-4 m/s^2.
    dir.write("small.obj", &obj(&icosphere(200.0, 1)));
    let run = run_site(
        &dir,
        &site_args("small.obj", "m", "12", "300", "small", &["--quiet"]),
    );
    assert_eq!(run.code, Some(0), "{run}");
    let summary = std::fs::read_to_string(dir.join("small/site.md")).unwrap();
    let untouched = summary
        .split("diverged and ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse::<u64>().ok())
        .unwrap_or_else(|| panic!("{summary}"));
    // The default scenario's upward velocity errors (sd 0.05 m/s) outrun its touchdown
    // speed here (sqrt(2 g h) = 0.03-0.05 m/s) in about a quarter of the samples.
    assert!((30..=150).contains(&untouched), "{untouched}: {summary}");
    let warning = format!("{untouched} of the 300 samples");
    for text in [&summary, &run.stderr] {
        assert!(
            text.contains(&warning)
                && text.contains("never touched the ground")
                && text.contains("check --density and --units"),
            "{text}"
        );
    }
    assert!(!run.stderr.contains("release too high"), "{run}");
}

/// Issue 45: the safe-area headline counts the facets whose P(stable) is at least 0.99
/// with 95 % confidence (the low end of the Wilson interval), the point estimate beside it:
/// a lander that always stays is "1.0" on every facet, yet a few hundred samples a window
/// cannot show 0.99 with confidence (n / (n + 1.96^2) < 0.99 below 381 samples).
#[test]
fn the_safe_area_counts_facets_sure_to_be_safe() {
    let dir = TempDir::new("site-sure");
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 1)));
    // Set down gently with no errors, on a sphere spinning slowly (slopes under 1 deg).
    dir.write(
        "calm.toml",
        "[inputs]\nrelease_height_m = 0.05\nrate_x_deg_s = 0.0\nrate_y_deg_s = 0.0\n\
         rate_z_deg_s = 0.0\nroll_deg = 0.0\npitch_deg = 0.0\nvelocity_error_x_m_s = 0.0\n\
         velocity_error_y_m_s = 0.0\nvelocity_error_z_m_s = 0.0\n[simulation]\nt_max_s = 30.0\n",
    );
    let run = run_site(
        &dir,
        &site_args(
            "sphere.obj",
            "m",
            "1000",
            "300",
            "map",
            &["--scenario", "calm.toml", "--quiet"],
        ),
    );
    run.assert_ok();
    let table = dir.join("map/facets.arrow");
    let get = |name: &str| column(&table, name).unwrap();
    let (p, low, area) = (get("p_stable"), get("p_stable_low"), get("area_m2"));
    let total: f64 = area.iter().sum();
    let share = |keep: &dyn Fn(usize) -> bool| {
        // `+ 0.0`: an empty sum is -0.0.
        100.0
            * (0..p.len())
                .filter(|&i| keep(i))
                .map(|i| area[i])
                .sum::<f64>()
            / total
            + 0.0
    };
    let sure = share(&|i| low[i] >= 0.99);
    let point = share(&|i| p[i] >= 0.99);
    // Every lander stays, and no window is large enough to be sure of it.
    assert!(point > 99.99 && sure < 0.01, "{point} {sure}");
    let summary = std::fs::read_to_string(dir.join("map/site.md")).unwrap();
    assert!(
        summary.contains(&format!(
            "**P(stable) >= 0.99 with 95 % confidence (the low end of its Wilson interval) on \
             {sure:.2} % of the surface** (0 m^2); by the point estimate (its share of samples \
             alone) on {point:.2} % ("
        )),
        "{summary}"
    );
}

/// Issue 45: a body whose size or gravity no small body has for the given `--units` is
/// warned of, naming the flag: a model in kilometres read as metres is a 0.78 m, 500 kg
/// body with a gravity of 2.4e-7 m/s^2 (before: mapped silently).
#[test]
fn a_body_implausible_for_its_units_is_warned_of() {
    let dir = TempDir::new("site-units");
    // Didymos's size in km (0.39 km in radius), read as metres.
    dir.write("km.obj", &obj(&icosphere(0.39, 1)));
    let mut args = site_args("km.obj", "m", "5", "200", "map", &["--quiet"]);
    args[5] = "2170".into();
    let run = run_site(&dir, &args);
    assert_eq!(run.code, Some(0), "{run}");
    assert!(
        run.stderr.contains("km.obj: implausible for a small body")
            && run.stderr.contains("--units km makes it")
            && run.stderr.contains("its gravity, about 2."),
        "{run}"
    );
    // The same in km: no warning of it.
    args[3] = "km".into();
    args[11] = "inkm".into();
    let run = run_site(&dir, &args);
    assert_eq!(run.code, Some(0), "{run}");
    assert!(!run.stderr.contains("implausible"), "{run}");
}

/// Issue 45: a gravity that will take more than a few minutes says so, with its
/// estimate, before it starts, on a pipe as on a terminal (before: only a terminal's bar).
/// 327,680 facets summed exactly (`--gravity exact`; by default so many are summed by the
/// tree, in under a minute) on one thread take over an hour (a few thousand facets a
/// second); the run is stopped once it has said so.
#[test]
fn a_long_gravity_says_how_long_before_it_starts() {
    use std::io::BufRead as _;
    let dir = TempDir::new("site-long-gravity");
    dir.write("big.obj", &obj(&icosphere(RADIUS_M, 7)));
    let args = site_args(
        "big.obj",
        "m",
        &PERIOD_H.to_string(),
        "1000",
        "map",
        &["--threads", "1", "--quiet", "--gravity", "exact"],
    );
    let mut child = std::process::Command::new(crate::common::BIN)
        .args(&args)
        .current_dir(dir.path())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("start touchdown");
    let stderr = child.stderr.take().unwrap();
    let (send, lines) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(stderr)
            .lines()
            .map_while(Result::ok)
        {
            let _ = send.send(line);
        }
    });
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    let mut told = None;
    while let Some(left) = deadline.checked_duration_since(std::time::Instant::now()) {
        match lines.recv_timeout(left) {
            Ok(line) if line.contains("the gravity of its") => {
                told = Some(line);
                break;
            }
            Ok(_) => {}
            Err(_) => break,
        }
    }
    let _ = child.kill();
    let _ = child.wait();
    let told = told.expect("no estimate of the gravity's time within 60 s");
    assert!(
        told.contains("big.obj: the gravity of its 327680 facets summed exactly will take about ")
            && told.contains("on 1 thread (measured on ")
            && told.contains("takes about 10 min; --gravity tree sums it"),
        "{told}"
    );
}

/// Messages name the actual cause: a coordinate that overflows (at its vertex), a density
/// that overflows the mass (not the spin), a plate header of numbers that are no counts (not
/// an OBJ statement), a slope window other than the map's sweep's (not just "its
/// scenario"), and a spin period of 1e300 h shown as such, not as 301 digits.
#[test]
fn messages_name_the_actual_cause() {
    let dir = TempDir::new("site-causes");
    let sphere = obj(&icosphere(RADIUS_M, 1));
    let first_vertex = sphere.lines().find(|l| l.starts_with("v ")).unwrap();
    let far = sphere.replacen(first_vertex, "v 0 0 1e300", 1);
    dir.write("far.obj", &far);
    let run = run_site(
        &dir,
        &site_args("far.obj", "m", "5", "200", "far", &["--quiet"]),
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr
            .contains("far.obj: shape model refused: vertex 1 (of facet ")
            && run.stderr.contains("[0.0, 0.0, 1e300] m overflows"),
        "{run}"
    );
    assert!(!run.stderr.contains("degenerate"), "{run}");

    dir.write("sphere.obj", &sphere);
    let mut args = site_args("sphere.obj", "m", "5", "200", "dense", &["--quiet"]);
    args[5] = "1e300".into();
    let run = run_site(&dir, &args);
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr
            .contains("--density 1e300 kg/m^3: the body's mass")
            && run.stderr.contains("overflows"),
        "{run}"
    );
    assert!(!run.stderr.contains("spin"), "{run}");

    dir.write("neg.tab", "-5 320\n1 0 0 0\n");
    let run = run_site(
        &dir,
        &site_args("neg.tab", "m", "5", "200", "neg", &["--quiet"]),
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr
            .contains("neg.tab, line 1: '-5' is not a count of vertices"),
        "{run}"
    );

    let run = run_sphere(&dir, "200", "map", &["--quiet"]);
    run.assert_ok();
    let run = run_sphere(&dir, "200", "map", &["--quiet", "--slope-window", "2"]);
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr.contains(
            "is not this map's sweep: it differs in its scenario's inputs.slope_deg (the slopes \
             drawn, from 0 to the steepest facet's plus --slope-window)"
        ),
        "{run}"
    );

    let run = run_site(
        &dir,
        &site_args("sphere.obj", "m", "1e300", "200", "slow", &["--quiet"]),
    );
    run.assert_ok();
    let summary = std::fs::read_to_string(dir.join("slow/site.md")).unwrap();
    assert!(
        summary.contains("| spin | period 1e300 h about"),
        "{summary}"
    );
    assert!(!summary.contains("0000000000"), "{summary}");
}

/// The top-level help names both formats `site` reads.
#[test]
fn the_help_names_the_formats_site_reads() {
    let run = touchdown(std::path::Path::new("."), &["--help"]);
    run.assert_ok();
    let site = run
        .stdout
        .lines()
        .find(|l| l.trim_start().starts_with("site "))
        .unwrap();
    assert!(
        site.contains("Wavefront OBJ file, or a vertex-facet plate file: PDS .tab, SBMT .plt"),
        "{site}"
    );
}

/// `--gravity tree` maps a model by the tree of its facets (issue 50): its facets'
/// effective gravities within 1e-4 of the exact sum's (the tree's tested 5e-5 of the
/// attraction, tests/shape/tree.rs, doubled: the spin takes up to half of the attraction
/// here), the log and the table's metadata say which sum was taken, and `auto` sums this
/// model of 1,280 facets exactly.
#[test]
fn the_tree_maps_a_body_as_the_exact_sum_does_and_says_so() {
    let dir = TempDir::new("site-tree");
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 3)));
    let exact = run_sphere(&dir, "300", "exact", &["--quiet"]);
    let tree = run_sphere(&dir, "300", "tree", &["--quiet", "--gravity", "tree"]);
    assert_eq!(
        (exact.code, tree.code),
        (Some(0), Some(0)),
        "{exact}\n{tree}"
    );
    assert!(exact.stdout.contains(", summed exactly\n"), "{exact}");
    assert!(
        tree.stdout
            .contains(", summed by the tree of the facets (opening 0.4, moments to degree 5)\n"),
        "{tree}"
    );
    let gravity = |out: &str| column(&dir.join(out).join("facets.arrow"), "gravity_m_s2").unwrap();
    let (e, t) = (gravity("exact"), gravity("tree"));
    assert_eq!(e.len(), 1280);
    let worst = e
        .iter()
        .zip(&t)
        .map(|(e, t)| (t / e - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst > 0.0 && worst < 1e-4, "{worst:e}");
    let said = |out: &str| {
        let file = std::fs::File::open(dir.join(out).join("facets.arrow")).unwrap();
        let reader = arrow_ipc::reader::FileReader::try_new(file, None).unwrap();
        reader.schema().metadata()["touchdown.site.gravity"].clone()
    };
    assert_eq!(said("exact"), "summed exactly");
    assert_eq!(
        said("tree"),
        "summed by the tree of the facets (opening 0.4, moments to degree 5)"
    );
}
