//! The `held` outcome (MODEL.md section 8): at `t_max`, a lander in contact whose control
//! loop is still powered (it may fire) is `held`, neither `stable` nor `sliding`: the rules
//! that tell those apart count no rest and no slide while a thruster may act. Its
//! boundaries: the same lander whose hold-down ends before `t_max` is decided by the
//! passive rules, and a lander airborne at `t_max` under a powered loop is `bouncing`.

use crate::common::{TempDir, touchdown};
use std::path::Path;
use touchdown::output::columns::Table;
use touchdown::reference::Outcome;

/// `hold-down.toml` set down on flat ground from a gentle 0.5 m release (no stepped
/// fall: contact within 0.02 s, hold-down sensed at the next instant, 0.1 s), a hold-down
/// of 20 N (delivering about 16 N: whole minimum on-times) for `duration_s`, and a run of
/// 20 s.
fn flat_hold_down(duration_s: f64) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let text = text
        .replace("start = \"release\"", "")
        .replace(
            "release_height_m = { dist = \"uniform\", min = 5.0, max = 10.0 }",
            "release_height_m = 0.5\nslope_deg = 0.0",
        )
        .replace(
            "thrust_n = { dist = \"uniform\", min = 0.0, max = 40.0 }",
            "thrust_n = 20.0",
        )
        .replace("duration_s = 10.0", &format!("duration_s = {duration_s}"));
    format!("{text}\n[simulation]\nt_max_s = 20.0\n")
}

/// The outcomes of the first `samples` samples of `text`: the sweep's (the kernel), and
/// the traces' of the first three (the reference).
fn outcomes(dir: &TempDir, name: &str, text: &str, samples: usize) -> Vec<Outcome> {
    let file = dir.write(&format!("{name}.toml"), text);
    let out = format!("{name}.arrow");
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            file.to_str().unwrap(),
            "--samples",
            &samples.to_string(),
            "--out",
            &out,
            "--quiet",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    let sweep = Table::read(&dir.join(&out), |_| false).unwrap();
    let kernel: Vec<Outcome> = sweep
        .outcome
        .iter()
        .map(|o| Outcome::ALL[usize::from(*o)])
        .collect();
    for (i, k) in kernel.iter().enumerate().take(3) {
        let trace = format!("{name}-{i}.arrow");
        let run = touchdown(
            dir.path(),
            &[
                "trace",
                "--sweep",
                &out,
                "--sample",
                &i.to_string(),
                "--out",
                &trace,
            ],
        );
        assert_eq!(run.code, Some(0), "{run}");
        assert!(
            run.stdout
                .contains(&format!("outcome                  {} at", k.name())),
            "{name} sample {i}: the kernel's {} against the reference's:\n{}",
            k.name(),
            run.stdout
        );
    }
    kernel
}

#[test]
fn a_lander_pushed_at_t_max_is_held() {
    let dir = TempDir::new("a_lander_pushed_at_t_max_is_held");
    let samples = 16;
    // Hold-down sensed at 0.1 s for 19.9 s: periods are counted from that instant, so it
    // pushes until 20.0 s, past t_max. Every lander stands on the flat ground, pressed by
    // 16 N, its loop powered at t_max: `held` (before `held` existed: `sliding`, none
    // moving).
    let pushed = outcomes(&dir, "pushed", &flat_hold_down(19.9), samples);
    assert!(
        pushed.iter().all(|o| *o == Outcome::Held),
        "hold-down past t_max: {pushed:?}"
    );
    // The other side of the boundary: the same landers with the hold-down over about 2 s
    // before t_max (its last firing ends at 18.2 s for a hold-down sensed at 0.1 s), the
    // loop off: the passive rules decide, and they settle, `stable`. (Ended only a few
    // tenths of a second before t_max, the legs' springs, pressed by the thrust, throw
    // most of them up by a fraction of a millimetre: `bouncing` at t_max.)
    let settled = outcomes(&dir, "settled", &flat_hold_down(18.0), samples);
    assert!(
        settled.iter().all(|o| *o == Outcome::Stable),
        "hold-down over 2 s before t_max: {settled:?}"
    );
}

#[test]
fn held_is_listed_only_where_a_lander_can_be_held() {
    // The report of a sweep with a control loop lists `held` (its share may be 0); the
    // report of a passive sweep does not (its landers cannot be held, and its report
    // stays as it was).
    let dir = TempDir::new("held_is_listed_only_where_a_lander_can_be_held");
    outcomes(&dir, "pushed", &flat_hold_down(19.9), 8);
    let report = touchdown(dir.path(), &["report", "pushed.arrow"]);
    assert_eq!(report.code, Some(0), "{report}");
    assert!(
        report.stdout.contains("| held | 8 | 100.00 % |"),
        "{}",
        report.stdout
    );
    let passive = dir.write("passive.toml", "[inputs]\nslope_deg = 0.0\n");
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            passive.to_str().unwrap(),
            "--samples",
            "8",
            "--out",
            "passive.arrow",
            "--quiet",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(!run.stdout.contains("held"), "{}", run.stdout);
    let report = touchdown(dir.path(), &["report", "passive.arrow"]);
    assert_eq!(report.code, Some(0), "{report}");
    assert!(!report.stdout.contains("held"), "{}", report.stdout);
    let compare = touchdown(dir.path(), &["compare", "pushed.arrow", "pushed.arrow"]);
    assert_eq!(compare.code, Some(0), "{compare}");
    assert!(
        compare.stdout.contains("| held | 100.00 % | 100.00 % |"),
        "{}",
        compare.stdout
    );
}
