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
        let names = ["stability-map", "tipped-by-slope", "loads"];
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
    for n in ["stability-map", "tipped-by-slope", "loads"] {
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
