//! `touchdown animate` and `touchdown view` as a user runs them: a GIF whose frames and
//! delays follow `--fps` and `--speed`, in which the lander's body moves when the lander
//! does and stays put when it rests; bad input refused with exit code 2 and no file made;
//! and the HTML page opened in headless Chromium (`tests/python/browser_view.py`): no
//! console error, a 3D view that is not blank, and a slider, orbit and zoom that change
//! the picture.

use crate::common::{SET_DOWN, TempDir, python, touchdown};
use std::io::Write as _;
use std::path::Path;
use std::process::Command;

/// A lander set down on a 60 deg slope, past the default gear's static limit (44.7 to
/// 54.4 deg, MODEL.md section 8), with friction high enough that it cannot slide: it tips.
fn tips() -> String {
    format!(
        "[surface]\nfriction_coefficient = 1.5\n[inputs]\nslope_deg = 60.0\n\
         downhill_azimuth_deg = 30.0\n{SET_DOWN}[initial]\nattitude_reference = \"surface\"\n\
         [simulation]\nt_max_s = 30.0\n"
    )
}

/// The same lander set down on level ground: it settles within micrometres and rests.
fn rests() -> String {
    format!("[inputs]\nslope_deg = 0.0\n{SET_DOWN}[simulation]\nt_max_s = 30.0\n")
}

/// Writes the trace of sample 0 of `scenario` as `name.arrow` in `dir`; returns its
/// outcome and its first and last times.
fn trace(dir: &TempDir, name: &str, scenario: &str) -> (String, f64, f64) {
    dir.write(&format!("{name}.toml"), scenario);
    let out = format!("{name}.arrow");
    touchdown(
        dir.path(),
        &[
            "trace",
            "--scenario",
            &format!("{name}.toml"),
            "--out",
            &out,
        ],
    )
    .assert_ok();
    let file = std::fs::File::open(dir.join(&out)).expect("open the trace");
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).expect("read the trace");
    let outcome = reader.schema().metadata()["touchdown.outcome"].clone();
    let mut times = Vec::new();
    for batch in reader {
        let batch = batch.expect("a batch");
        let t = batch
            .column_by_name("t_s")
            .expect("t_s")
            .as_any()
            .downcast_ref::<arrow_array::Float64Array>()
            .expect("t_s is Float64")
            .values()
            .to_vec();
        times.extend(t);
    }
    (outcome, times[0], times[times.len() - 1])
}

/// The frames of a GIF as the viewer shows them (each drawn over the ones before), RGBA,
/// with their delays in 1/100 s; and the picture's size.
pub(crate) fn frames(path: &Path) -> (Vec<Vec<u8>>, Vec<u16>, (usize, usize)) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(path).expect("open the GIF"))
        .expect("a GIF");
    let (w, h) = (decoder.width() as usize, decoder.height() as usize);
    let mut canvas = vec![0u8; w * h * 4];
    let (mut shown, mut delays) = (Vec::new(), Vec::new());
    while let Some(f) = decoder.read_next_frame().expect("a frame") {
        assert_eq!(
            f.dispose,
            gif::DisposalMethod::Keep,
            "frames build on each other"
        );
        for y in 0..f.height as usize {
            for x in 0..f.width as usize {
                let s = 4 * (y * f.width as usize + x);
                if f.buffer[s + 3] == 0 {
                    continue;
                }
                let d = 4 * ((y + f.top as usize) * w + x + f.left as usize);
                canvas[d..d + 4].copy_from_slice(&f.buffer[s..s + 4]);
            }
        }
        shown.push(canvas.clone());
        delays.push(f.delay);
    }
    (shown, delays, (w, h))
}

/// The pixels of the lander's body: its gold, in any of its shades but the darkest (no
/// other part, the ground, the captions or the outcome colours is that hue).
fn body_pixels(rgba: &[u8]) -> Vec<usize> {
    rgba.chunks_exact(4)
        .enumerate()
        .filter(|(_, p)| {
            let (r, g, b) = (f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
            r - b > 90.0 && g > 0.6 * r && g < 0.9 * r
        })
        .map(|(i, _)| i)
        .collect()
}

/// The share of the body's pixels in `a` or `b` that are not in both.
fn body_change(a: &[u8], b: &[u8]) -> (f64, usize) {
    let (a, b) = (body_pixels(a), body_pixels(b));
    let set: std::collections::HashSet<usize> = a.iter().copied().collect();
    let both = b.iter().filter(|i| set.contains(i)).count();
    let either = a.len() + b.len() - both;
    (
        (either - both) as f64 / either.max(1) as f64,
        a.len().min(b.len()),
    )
}

#[test]
fn frames_and_delays_follow_fps_and_speed() {
    let dir = TempDir::new("animate-clock");
    let (outcome, t0, t1) = trace(&dir, "tips", &tips());
    assert_eq!(outcome, "tipped");
    for (fps, speed) in [(10u32, 2.0f64), (25, 5.0), (4, 0.5)] {
        let out = format!("tips-{fps}-{speed}.gif");
        touchdown(
            dir.path(),
            &[
                "animate",
                "tips.arrow",
                "--out",
                &out,
                "--fps",
                &fps.to_string(),
                "--speed",
                &speed.to_string(),
                "--size",
                "320x240",
            ],
        )
        .assert_ok();
        let (shown, delays, size) = frames(&dir.join(&out));
        assert_eq!(size, (320, 240));
        // One frame every speed/fps trace seconds from the first time, and one at the
        // decision: the frames before the last span less than the trace, all of them at
        // least the trace.
        let step = speed / f64::from(fps);
        let n = shown.len() as f64;
        assert!(
            (n - 2.0) * step < t1 - t0 && (n - 1.0) * step >= t1 - t0 - 1e-9,
            "{n} frames at {fps} fps and {speed}x for {} s",
            t1 - t0
        );
        // 100/fps hundredths each (whole here), the last held 2 s more.
        let each = (100 / fps) as u16;
        assert!(
            delays[..delays.len() - 1].iter().all(|d| *d == each),
            "{delays:?}"
        );
        assert_eq!(delays[delays.len() - 1], each + 200);
    }
    // The default: 15 frames per second, the trace in 15 s of playback (real time if it
    // is shorter), into the trace's name with .gif.
    touchdown(dir.path(), &["animate", "tips.arrow"]).assert_ok();
    let (shown, delays, size) = frames(&dir.join("tips.gif"));
    assert_eq!(size, (640, 480));
    let speed = ((t1 - t0) / 15.0).max(1.0);
    assert_eq!(
        shown.len(),
        ((t1 - t0) * 15.0 / speed - 1e-9).ceil() as usize + 1
    );
    let playback: u32 = delays.iter().map(|d| u32::from(*d)).sum();
    let expected = 100.0 * (t1 - t0) / speed + 200.0;
    // Within one frame (7/100 s at 15 fps): the last frame ends at the decision.
    assert!(
        (f64::from(playback) - expected).abs() <= 7.0,
        "plays for {playback}/100 s, expected {expected:.0}"
    );
}

#[test]
fn the_body_moves_when_the_lander_does_and_stays_put_at_rest() {
    let dir = TempDir::new("animate-body");
    let (outcome, ..) = trace(&dir, "tips", &tips());
    assert_eq!(outcome, "tipped");
    let (outcome, t0, t1) = trace(&dir, "rests", &rests());
    assert_eq!(outcome, "stable");
    for name in ["tips", "rests"] {
        touchdown(
            dir.path(),
            &[
                "animate",
                &format!("{name}.arrow"),
                "--fps",
                "5",
                "--size",
                "400x300",
            ],
        )
        .assert_ok();
    }
    let (tips, ..) = frames(&dir.join("tips.gif"));
    let (change, least) = body_change(&tips[0], &tips[tips.len() - 1]);
    assert!(least > 500, "the body shows: {least} pixels");
    assert!(
        change > 0.5,
        "the tipping body moved: {change:.3} of its pixels changed"
    );
    // Frame to frame too, while it tips (the frames after the first change somewhere).
    let moved = tips
        .windows(2)
        .filter(|w| body_change(&w[0], &w[1]).0 > 0.0)
        .count();
    assert!(
        moved >= tips.len() / 2,
        "{moved} of {} frames moved",
        tips.len()
    );

    let (rests, ..) = frames(&dir.join("rests.gif"));
    assert!(
        rests.len() >= 10,
        "{} frames over {} s",
        rests.len(),
        t1 - t0
    );
    // The lander starts 1 mm above the ground (the scenario's clearance), a tenth of a
    // pixel at this size: an edge pixel of the body may flip as it drops.
    for f in &rests[1..] {
        let (change, least) = body_change(&rests[0], f);
        assert!(least > 500, "the body shows: {least} pixels");
        assert!(
            change < 0.002,
            "the resting body changed {change:.4} of its pixels"
        );
    }
    // Once down (0.35 s: sqrt(2 h / g) for 1 mm at 0.0168 m/s^2; frame 3 is at 0.6 s) it
    // settles by micrometres under its weight: not one of its pixels changes.
    for f in &rests[3..] {
        let (change, _) = body_change(&rests[3], f);
        assert_eq!(
            change, 0.0,
            "the resting body changed {change:.4} of its pixels"
        );
    }
}

/// Files that `animate` and `view` must refuse, made in `dir`: a sweep file, a trace cut
/// off half-way, a text file.
fn bad_files(dir: &TempDir) {
    trace(dir, "tips", &tips());
    let bytes = std::fs::read(dir.join("tips.arrow")).expect("read the trace");
    std::fs::write(dir.join("cut.arrow"), &bytes[..bytes.len() / 2]).expect("write");
    dir.write("notes.arrow", "not a trace\n");
    dir.write("sweep.toml", "[simulation]\nt_max_s = 5.0\n");
    touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--samples",
            "16",
            "--scenario",
            "sweep.toml",
            "--out",
            "sweep.arrow",
        ],
    );
    assert!(dir.join("sweep.arrow").is_file());
}

#[test]
fn bad_input_exits_2_with_a_message_and_leaves_no_file() {
    let dir = TempDir::new("animate-bad");
    bad_files(&dir);
    let cases: &[(&[&str], &str)] = &[
        (&["missing.arrow"], "missing.arrow: no such trace file"),
        (&["cut.arrow"], "cannot read cut.arrow"),
        (
            &["notes.arrow"],
            "neither an Arrow IPC file nor a Parquet file",
        ),
        (
            &["sweep.arrow"],
            "is not a trace file of touchdown (it is a sweep file",
        ),
    ];
    let options: &[(&[&str], &str)] = &[
        (&["--fps", "0"], "--fps 0: from 1 to 50"),
        (&["--fps", "60"], "--fps 60: from 1 to 50"),
        (
            &["--speed", "-2"],
            "--speed -2: a playback speed greater than 0",
        ),
        (
            &["--speed", "0"],
            "--speed 0: a playback speed greater than 0",
        ),
        (
            &["--size", "20x20"],
            "--size 20x20: from 160x120 to 1920x1080",
        ),
        (&["--size", "big"], "not a size WIDTHxHEIGHT"),
        (
            &["--speed", "1e-8"],
            "more than 10000; a larger --speed or a smaller --fps",
        ),
        (&["--out", "tips.arrow"], "it is an input of this command"),
        (&["--out", "no-such-folder/x.gif"], "no-such-folder"),
    ];
    let mut runs: Vec<Vec<&str>> = Vec::new();
    let mut expect = Vec::new();
    for command in ["animate", "view"] {
        for (args, message) in cases {
            let mut a = vec![command];
            a.extend(*args);
            a.extend(["--out", "out.file"]);
            runs.push(a);
            expect.push(*message);
        }
    }
    for (args, message) in options {
        let mut a = vec!["animate", "tips.arrow"];
        a.extend(*args);
        runs.push(a);
        expect.push(*message);
    }
    let before = dir.entries();
    let mut problems = Vec::new();
    for (args, message) in runs.iter().zip(expect) {
        let run = touchdown(dir.path(), args);
        if run.code != Some(2) || !run.stderr.contains(message) || run.stderr.contains("panicked") {
            problems.push(format!(
                "{args:?}: expected exit 2 and {message:?}, got {run}"
            ));
        }
        if dir.entries() != before {
            problems.push(format!("{args:?} left files: {:?}", dir.entries()));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Chromium, if it is here; when it is not, the test is skipped with a note (CI installs
/// Debian's `chromium` and sets `TOUCHDOWN_REQUIRE_CHROMIUM=1`, which makes a missing
/// browser a failure).
pub(crate) fn chromium(test: &str) -> Option<String> {
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        if Command::new(name)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
        {
            return Some(name.to_string());
        }
    }
    assert!(
        std::env::var("TOUCHDOWN_REQUIRE_CHROMIUM").as_deref() != Ok("1"),
        "chromium is missing but TOUCHDOWN_REQUIRE_CHROMIUM=1"
    );
    let _ = writeln!(
        std::io::stderr(),
        "\nSKIPPED {test}: no Chromium found (Debian: apt-get install chromium)"
    );
    None
}

#[test]
fn the_page_opens_in_a_browser_and_its_slider_moves_the_lander() {
    let Some(browser) = chromium("the_page_opens_in_a_browser_and_its_slider_moves_the_lander")
    else {
        return;
    };
    let dir = TempDir::new("view-browser");
    trace(&dir, "tips", &tips());
    let run = touchdown(dir.path(), &["view", "tips.arrow"]);
    run.assert_ok();
    assert!(run.stdout.contains("wrote tips.html"), "{run}");
    let page = std::fs::read_to_string(dir.join("tips.html")).expect("read the page");
    // Self-contained: nothing is fetched.
    for remote in ["http://", "https://", "src=\"//", "@import"] {
        assert!(!page.contains(remote), "the page refers to {remote}");
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/browser_view.py");
    let o = Command::new(python())
        .arg(&script)
        .arg(&browser)
        .arg(dir.join("tips.html"))
        .arg(dir.join("shots"))
        .output()
        .expect("run the browser test");
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    if o.status.code() == Some(3)
        && std::env::var("TOUCHDOWN_REQUIRE_CHROMIUM").as_deref() != Ok("1")
    {
        let _ = writeln!(
            std::io::stderr(),
            "\nSKIPPED the browser test: Chromium would not start here:\n{stdout}{stderr}"
        );
        return;
    }
    assert!(
        o.status.success(),
        "the browser test failed ({:?}):\n{stdout}{stderr}",
        o.status.code()
    );
    for check in [
        "ok: no console errors",
        "ok: 3D canvas drawn",
        "ok: slider moved by the mouse",
        "ok: screenshots differ",
        "ok: 3D canvas changed with the slider",
        "ok: orbit drag changed",
        "ok: wheel zoom changed",
    ] {
        assert!(stdout.contains(check), "no {check:?} in:\n{stdout}");
    }
}
