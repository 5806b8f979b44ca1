//! `[control.hold_down] stop_tilt_deg` (MODEL.md section 7): the hold-down stops at the
//! first control instant at which the sensed tilt of `Z_B` from the surface normal
//! exceeds the limit; bad values are refused naming the key.

use crate::common::{TempDir, touchdown};
use glam::DVec3;
use std::path::Path;
use touchdown::reference::{self, Model};
use touchdown::sampling;
use touchdown::scenario::Scenario;
use touchdown::slope::Surface;

/// The limit of the tests, deg.
const LIMIT_DEG: f64 = 20.0;

/// `hold-down.toml` with perfect sensors (no noise, no bias: the sensed tilt is the true
/// one), no latency (a command acts in the period of its instant), a hold-down of 30 N for
/// 10 s, and `stop` as its `stop_tilt_deg` line (empty: none).
fn text(stop: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml");
    let mut text = std::fs::read_to_string(path).unwrap();
    let sensors = text.find("[control.sensors]").unwrap();
    let hold_down = text.find("[control.hold_down]").unwrap();
    text.replace_range(sensors..hold_down, "");
    text.replace("latency_periods = 1", "latency_periods = 0")
        .replace(
            "thrust_n = { dist = \"uniform\", min = 0.0, max = 40.0 }",
            &format!("thrust_n = 30.0\n{stop}"),
        )
}

/// Per control instant of sample `index` of `scenario` (the reference): the sensed tilt
/// from the surface normal (deg) and the loop's phase after it; and whether any thruster
/// fired after the hold-down was over.
fn instants(scenario: &Scenario, index: u64) -> (Vec<(f64, &'static str)>, bool) {
    let model = Model::new(scenario);
    let sample = sampling::sample(scenario, index);
    let normal = Surface::of(&sample).normal;
    let mut seen = Vec::new();
    let mut last = f64::NAN;
    let mut fired_after = false;
    reference::run(&model, &sample, |r| {
        let c = r.control.as_ref().expect("a control loop");
        if let Some(s) = c.sensed
            && s.t_s != last
        {
            last = s.t_s;
            let tilt = (s.attitude * DVec3::Z).dot(normal).clamp(-1.0, 1.0);
            seen.push((tilt.acos().to_degrees(), c.phase));
        }
        fired_after |= c.phase == "done" && r.thrust.flow_n > 0.0;
    });
    (seen, fired_after)
}

#[test]
fn hold_down_stops_at_the_first_instant_past_the_tilt_limit() {
    // Samples 0-59 (slopes 0-45 deg, landers tilted by their residual rates): at every
    // control instant at which the sensed tilt exceeds the limit, the hold-down is over
    // (phase `done`, at that very instant: with no latency no thruster fires after it);
    // while it lasts, every instant reads a tilt within the limit. The same samples
    // without the key push on at those instants. Instants within 1e-6 deg of the limit
    // (the comparison of cosines rounds) are left out; none came so near.
    let with = Scenario::from_toml(&text(&format!("stop_tilt_deg = {LIMIT_DEG}"))).unwrap();
    let without = Scenario::from_toml(&text("")).unwrap();
    let (mut at_contact, mut while_pushing) = (0, 0);
    for index in 0..60 {
        let (seen, fired_after) = instants(&with, index);
        assert!(!fired_after, "sample {index}: fired after the hold-down");
        let (unlimited, _) = instants(&without, index);
        let mut pushed = false;
        for (k, &(tilt, phase)) in seen.iter().enumerate() {
            if (tilt - LIMIT_DEG).abs() < 1e-6 {
                continue;
            }
            if phase == "hold_down" {
                assert!(
                    tilt <= LIMIT_DEG,
                    "sample {index}, instant {k}: pushes at a sensed tilt of {tilt} deg"
                );
                pushed = true;
            }
            let stopped_here = phase == "done" && (k == 0 || seen[k - 1].1 != "done");
            if stopped_here && tilt > LIMIT_DEG {
                // The same lander without the limit: still (or just now) in hold-down.
                assert_eq!(
                    unlimited[k],
                    (tilt, "hold_down"),
                    "sample {index}, instant {k}: without stop_tilt_deg"
                );
                if pushed {
                    while_pushing += 1;
                } else {
                    at_contact += 1;
                }
            }
        }
    }
    println!(
        "hold-down stopped by a tilt past {LIMIT_DEG} deg: {at_contact} samples at the instant \
         contact was sensed, {while_pushing} after pushing"
    );
    // Landers that meet the surface tilted past the limit are the ones it stops (measured:
    // 31 of the 60, all at the instant contact was sensed: once a hold-down has started
    // within the limit it presses the lander onto its footpads, and none of 300 samples,
    // nor a lander set down on flat ground rolling at 5-40 deg/s, tilted past 20 deg
    // under it).
    assert!(at_contact > 0, "no hold-down stopped by the tilt");
}

#[test]
fn stop_tilt_is_checked() {
    // Refused with the key named and exit code 2: no tilt, a tilt of 90 deg or more (the
    // lander has tipped), a negative one, a word. Accepted: 20 deg.
    let dir = TempDir::new("stop_tilt_is_checked");
    for (value, ok) in [
        ("0.0", false),
        ("90.0", false),
        ("120.0", false),
        ("-5.0", false),
        ("\"steep\"", false),
        ("20.0", true),
    ] {
        let file = dir.write("s.toml", &text(&format!("stop_tilt_deg = {value}")));
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                file.to_str().unwrap(),
                "--samples",
                "2",
                "--out",
                "s.arrow",
                "--quiet",
            ],
        );
        if ok {
            assert_eq!(run.code, Some(0), "{run}");
        } else {
            assert_eq!(run.code, Some(2), "{run}");
            assert!(
                run.stderr.contains("control.hold_down.stop_tilt_deg"),
                "{run}"
            );
        }
    }
}
