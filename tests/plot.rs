//! `touchdown plot` on real engine output: every picture of a sweep (Arrow and Parquet) and
//! of a trace is written, decodes as a PNG of the promised size, and shows what the file
//! holds (the colours of exactly the outcomes that occur); bad input is refused with exit
//! code 2 and leaves no file.

use crate::common::{TempDir, read_bytes, touchdown};
use std::path::Path;

/// Landers dropped 5-20 cm onto slopes of 0-60 deg with 90 psi dampers: stable, tipped and
/// sliding samples, but none bouncing or diverged.
const MIXED: &str = r#"
[damper]
enabled = true
crush_strength_psi = 90.0
[inputs]
slope_deg = { dist = "uniform", min = 0.0, max = 60.0 }
release_height_m = { dist = "uniform", min = 0.05, max = 0.2 }
"#;

/// Outcome colours of the stability map (src/plot/mod.rs), in the order of the sweep's
/// summary: stable, tipped, sliding, bouncing, diverged.
const OUTCOMES: [(&str, [u8; 3]); 5] = [
    ("stable", [44, 160, 44]),
    ("tipped", [214, 39, 40]),
    ("sliding", [255, 127, 14]),
    ("bouncing", [31, 119, 180]),
    ("diverged", [0, 0, 0]),
];

/// The picture at `path`, decoded, with a check of its size.
fn picture(path: &Path, size: (u32, u32)) -> image::RgbImage {
    let bytes = read_bytes(path);
    assert!(
        bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
        "{} is not a PNG",
        path.display()
    );
    let img = image::load_from_memory(&bytes)
        .unwrap_or_else(|e| panic!("cannot decode {}: {e}", path.display()))
        .to_rgb8();
    assert_eq!(img.dimensions(), size, "size of {}", path.display());
    img
}

/// Pixels of exactly `colour`.
fn count(img: &image::RgbImage, colour: [u8; 3]) -> usize {
    img.pixels().filter(|p| p.0 == colour).count()
}

/// Share of pixels that are not white.
fn inked(img: &image::RgbImage) -> f64 {
    let n = img.pixels().filter(|p| p.0 != [255, 255, 255]).count();
    n as f64 / f64::from(img.width() * img.height())
}

/// The outcome counts of a sweep's closing summary, in the order of `OUTCOMES`.
fn summary_counts(stdout: &str) -> Vec<u64> {
    OUTCOMES
        .iter()
        .map(|(name, _)| {
            stdout
                .lines()
                .find_map(|l| {
                    let w: Vec<&str> = l.split_whitespace().collect();
                    (w.len() == 4 && w[0] == *name).then(|| w[1].parse().unwrap())
                })
                .unwrap_or_else(|| panic!("no {name} count in:\n{stdout}"))
        })
        .collect()
}

#[test]
fn plots_of_a_sweep_show_its_outcomes() {
    let dir = TempDir::new("plot-sweep");
    dir.write("mixed.toml", MIXED);
    std::fs::create_dir(dir.join("pictures")).unwrap();
    let mut counts = Vec::new();
    for (file, format) in [("a.arrow", "arrow"), ("p.parquet", "parquet")] {
        let args = [
            "sweep",
            "--scenario",
            "mixed.toml",
            "--samples",
            "3000",
            "--quiet",
            "--out",
            file,
            "--format",
            format,
        ];
        let sweep = touchdown(dir.path(), &args);
        assert_eq!(sweep.code, Some(0), "{sweep}");
        counts = summary_counts(&sweep.stdout);
        let run = touchdown(dir.path(), &["plot", file, "--out-dir", "pictures"]);
        run.assert_ok();
        let stem = file.split('.').next().unwrap();
        let names = ["stability-map", "tipped-by-slope", "loads", "exceedance"];
        let expected: String = names
            .iter()
            .map(|n| {
                format!(
                    "wrote {}\n",
                    Path::new("pictures")
                        .join(format!("{stem}-{n}.png"))
                        .display()
                )
            })
            .collect();
        assert_eq!(run.stdout, expected);
    }
    // The scenario gives the mix this test is about.
    assert!(
        counts[..3].iter().all(|n| *n > 30) && counts[3..].iter().all(|n| *n == 0),
        "outcome counts {counts:?}"
    );
    let pictures = dir.join("pictures");
    // Both files hold the same rows: the pictures are the same, byte for byte.
    for n in ["stability-map", "tipped-by-slope", "loads", "exceedance"] {
        assert!(
            read_bytes(&pictures.join(format!("a-{n}.png")))
                == read_bytes(&pictures.join(format!("p-{n}.png"))),
            "{n}: the Arrow and Parquet pictures differ"
        );
    }

    let map = picture(&pictures.join("a-stability-map.png"), (1000, 680));
    // A dot (and a legend entry) in the colour of each outcome that occurs; no trace of
    // the others (diverged is black like the axes and the limit curve: not checked).
    for ((name, colour), n) in OUTCOMES.iter().zip(&counts).take(4) {
        let pixels = count(&map, *colour);
        if *n > 0 {
            assert!(
                pixels >= 10 * *n as usize,
                "{name}: {n} samples but {pixels} pixels in its colour"
            );
        } else {
            assert_eq!(pixels, 0, "{name}: no samples but {pixels} pixels");
        }
    }
    let tipped = picture(&pictures.join("a-tipped-by-slope.png"), (1000, 620));
    for (name, colour) in &OUTCOMES[..2] {
        assert!(
            count(&tipped, *colour) > 500,
            "no {name} line in the share plot"
        );
    }
    let loads = picture(&pictures.join("a-loads.png"), (1200, 520));
    assert!(inked(&loads) > 0.05, "the load histograms are nearly blank");
}

#[test]
fn plots_of_a_trace_are_drawn_beside_it() {
    let dir = TempDir::new("plot-trace");
    dir.write("mixed.toml", MIXED);
    let trace = touchdown(
        dir.path(),
        &[
            "trace",
            "--scenario",
            "mixed.toml",
            "--sample",
            "3",
            "--out",
            "t.arrow",
        ],
    );
    assert_eq!(trace.code, Some(0), "{trace}");
    // Without --out-dir the pictures go beside the file.
    let run = touchdown(dir.path(), &["plot", "t.arrow"]);
    run.assert_ok();
    for (name, size) in [
        ("cg", (1100, 1300)),
        ("legs", (1100, 1300)),
        ("path-3d", (1000, 900)),
        ("accel-z-body", (1100, 800)),
    ] {
        let file = format!("t-{name}.png");
        assert!(run.stdout.contains(&file), "{run}");
        let img = picture(&dir.join(&file), size);
        // Lines, grids and labels; a picture with only axes inks about 2 %.
        let share = inked(&img);
        assert!(share > 0.04, "{file}: only {:.1} % inked", 100.0 * share);
    }
    assert!(
        !dir.entries().iter().any(|e| e.ends_with(".partial")),
        "{:?}",
        dir.entries()
    );
}

/// A lander let go 0.5 m above a level frictionless plane, drifting at 0.1 m/s along one
/// horizontal axis of I: it drops, then slides on in a straight line.
fn drift(axis: char) -> String {
    format!(
        "[surface]\nfriction_coefficient = 0.0\n\n[inputs]\nslope_deg = 0.0\n\
         release_height_m = 0.0\nvelocity_error_x_m_s = {}\nvelocity_error_y_m_s = {}\n\
         velocity_error_z_m_s = 0.0\nroll_deg = 0.0\npitch_deg = 0.0\nrate_x_deg_s = 0.0\n\
         rate_y_deg_s = 0.0\nrate_z_deg_s = 0.0\n\n[initial]\nclearance_m = 0.5\n\n\
         [simulation]\nt_max_s = 20.0\n",
        if axis == 'x' { 0.1 } else { 0.0 },
        if axis == 'y' { 0.1 } else { 0.0 },
    )
}

/// Pixels of exactly `colour`, as (column, row).
fn pixels(img: &image::RgbImage, colour: [u8; 3]) -> Vec<[f64; 2]> {
    img.enumerate_pixels()
        .filter(|(_, _, p)| p.0 == colour)
        .map(|(x, y, _)| [f64::from(x), f64::from(y)])
        .collect()
}

/// Pixels of text in `colour`, as (column, row): the colour itself or, at the edges of
/// glyphs, mixed with at most 50 % of a light grey background (solving p = (1 - t) c + t v
/// for the share t and the grey v, which a line of another colour does not fit).
fn text_pixels(img: &image::RgbImage, colour: [u8; 3]) -> Vec<[f64; 2]> {
    let c = colour.map(f64::from);
    // The two channels in which the colour differs most.
    let (i, j) = [(0, 1), (0, 2), (1, 2)]
        .into_iter()
        .max_by(|a, b| (c[a.0] - c[a.1]).abs().total_cmp(&(c[b.0] - c[b.1]).abs()))
        .unwrap();
    let fits = |p: [u8; 3]| {
        let p = p.map(f64::from);
        let keep = (p[i] - p[j]) / (c[i] - c[j]);
        let t = 1.0 - keep;
        if t < 0.02 {
            return (0..3).all(|k| (p[k] - c[k]).abs() <= 3.0);
        }
        let greys: Vec<f64> = (0..3).map(|k| (p[k] - keep * c[k]) / t).collect();
        let (lo, hi) = greys
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), v| (l.min(*v), h.max(*v)));
        t <= 0.5 && lo >= 150.0 && hi <= 258.0 && hi - lo <= 10.0
    };
    img.enumerate_pixels()
        .filter(|(_, _, p)| fits(p.0))
        .map(|(x, y, _)| [f64::from(x), f64::from(y)])
        .collect()
}

/// The median column and row of `points`: the middle of a name even if a few pixels of a
/// line happen to fit its colour.
fn middle(points: &[[f64; 2]]) -> [f64; 2] {
    let median = |k: usize| {
        let mut v: Vec<f64> = points.iter().map(|p| p[k]).collect();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    [median(0), median(1)]
}

#[test]
fn path_picture_names_each_axis_beside_the_motion_along_it() {
    // Two drifts, along +X_I and along +Y_I, the same in all else: the boxes of the two
    // pictures are the same, and so is the projection. Footpad 0's path (its own colour)
    // runs from its highest point on the screen (the release) to the point farthest from
    // it: that vector is the image of the motion, mostly along the axis (the 0.5 m drop
    // adds the same part to both, which cancels in their difference).
    //
    // The names sit beside the middle of the edge that carries their ticks: X_I at the
    // X_I edge on the Y_I max side, Y_I at the Y_I edge on the X_I max side. So from the
    // Y_I name to the X_I name is about half the image of +Y_I minus half that of +X_I:
    // along (motion Y - motion X), positive. Names at the wrong edges (or at the corners
    // X_I max / Y_I max, as before 0.2) make it negative.
    const FOOTPAD_0: [u8; 3] = [31, 119, 180];
    const X_NAME: [u8; 3] = [170, 20, 20];
    const Y_NAME: [u8; 3] = [20, 120, 20];
    const Z_NAME: [u8; 3] = [20, 20, 170];
    let dir = TempDir::new("plot-axes");
    let mut motion = Vec::new();
    let mut names = Vec::new();
    for axis in ['x', 'y'] {
        dir.write(&format!("{axis}.toml"), &drift(axis));
        let (scenario, out) = (format!("{axis}.toml"), format!("{axis}.arrow"));
        let trace = touchdown(
            dir.path(),
            &[
                "trace",
                "--scenario",
                &scenario,
                "--every",
                "10",
                "--out",
                &out,
            ],
        );
        assert_eq!(trace.code, Some(0), "{trace}");
        touchdown(dir.path(), &["plot", &out]).assert_ok();
        let img = picture(&dir.join(&format!("{axis}-path-3d.png")), (1000, 900));
        // Footpad 0's path, without its sample line in the legend (upper left).
        let ink: Vec<[f64; 2]> = pixels(&img, FOOTPAD_0)
            .into_iter()
            .filter(|p| p[0] > 200.0 || p[1] > 200.0)
            .collect();
        let start = *ink
            .iter()
            .min_by(|a, b| a[1].total_cmp(&b[1]))
            .expect("footpad 0 drawn");
        let distance = |p: &[f64; 2]| (p[0] - start[0]).hypot(p[1] - start[1]);
        let end = *ink
            .iter()
            .max_by(|a, b| distance(a).total_cmp(&distance(b)))
            .unwrap();
        assert!(
            distance(&end) > 200.0,
            "{axis}: footpad 0 moved only {:.0} px",
            distance(&end)
        );
        motion.push([end[0] - start[0], end[1] - start[1]]);
        names.push([X_NAME, Y_NAME, Z_NAME].map(|c| {
            let ink = text_pixels(&img, c);
            assert!(
                ink.len() > 30,
                "{axis}: {} pixels of the name in {c:?}",
                ink.len()
            );
            middle(&ink)
        }));
    }
    // The names are where they are whatever the drift.
    for (k, (a, b)) in names[0].iter().zip(&names[1]).enumerate() {
        assert!(
            (a[0] - b[0]).hypot(a[1] - b[1]) < 3.0,
            "axis name {k} moved with the drift: {a:?} and {b:?}"
        );
    }
    let [x_name, y_name, z_name] = names[0];
    let from_y_to_x = [x_name[0] - y_name[0], x_name[1] - y_name[1]];
    let y_minus_x = [motion[1][0] - motion[0][0], motion[1][1] - motion[0][1]];
    let dot = from_y_to_x[0] * y_minus_x[0] + from_y_to_x[1] * y_minus_x[1];
    let cos = dot / from_y_to_x[0].hypot(from_y_to_x[1]) / y_minus_x[0].hypot(y_minus_x[1]);
    assert!(
        cos > 0.5,
        "the axis names are not beside the motions along their axes: X_I name at {x_name:?}, \
         Y_I name at {y_name:?}, motion along +X_I {:?}, along +Y_I {:?} (cos {cos:.2})",
        motion[0],
        motion[1]
    );
    // Z_I, up, is named above both.
    assert!(
        z_name[1] < x_name[1] - 100.0 && z_name[1] < y_name[1] - 100.0,
        "Z_I name at {z_name:?}"
    );
}

#[test]
fn plot_refuses_what_it_cannot_draw() {
    let dir = TempDir::new("plot-bad");
    dir.write("notes.txt", "not a touchdown file\n");
    let sweep = touchdown(
        dir.path(),
        &["sweep", "--samples", "100", "--quiet", "--out", "s.arrow"],
    );
    assert_eq!(sweep.code, Some(0), "{sweep}");
    let bytes = read_bytes(&dir.join("s.arrow"));
    std::fs::write(dir.join("cut.arrow"), &bytes[..bytes.len() / 2]).unwrap();
    for (args, expect) in [
        (&["plot", "missing.arrow"][..], "missing.arrow"),
        (&["plot", "notes.txt"][..], "notes.txt is neither"),
        (&["plot", "cut.arrow"][..], "cut.arrow"),
        (
            &["plot", "s.arrow", "--out-dir", "notes.txt/pictures"][..],
            "cannot make output folder notes.txt/pictures",
        ),
        (
            &["plot", "s.arrow", "--out-dir", "notes.txt"][..],
            "notes.txt is a file",
        ),
        // A file that cannot be drawn makes no folder.
        (
            &["plot", "notes.txt", "--out-dir", "new"][..],
            "notes.txt is neither",
        ),
    ] {
        let before = dir.entries();
        let run = touchdown(dir.path(), args);
        assert_eq!(run.code, Some(2), "{run}");
        assert!(
            run.stderr.contains("error:") && run.stderr.contains(expect),
            "expected {expect:?}: {run}"
        );
        assert!(!run.stderr.contains("panicked"), "{run}");
        assert_eq!(dir.entries(), before, "{run}");
    }
}

#[test]
fn plot_makes_the_output_folder() {
    let dir = TempDir::new("plot-folder");
    let run = touchdown(dir.path(), &["trace", "--every", "20", "--out", "t.arrow"]);
    assert_eq!(run.code, Some(0), "{run}");
    let run = touchdown(dir.path(), &["plot", "t.arrow", "--out-dir", "new/deeper"]);
    run.assert_ok();
    assert!(dir.join("new/deeper/t-cg.png").is_file(), "{run}");
}
