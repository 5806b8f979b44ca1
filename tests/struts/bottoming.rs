//! A cartridge that runs out of stroke is counted: per leg, per sample and by `report`.

use super::{Columns, level_drop};
use crate::common::{TempDir, touchdown};

/// Weak (5 psi on 4.5 cm^2: 15.5 N per leg) cartridges of `stroke_m` usable stroke, under
/// a level drop from `release_height` m.
fn cartridge(stroke_m: f64, release_height: f64) -> String {
    format!(
        "[damper]\nenabled = true\ncrush_strength_psi = 5.0\nusable_stroke_m = {stroke_m}\n\n[simulation]\nt_max_s = 30.0\n\n{}",
        level_drop(release_height)
    )
}

/// Runs `samples` samples of `scenario` into `out`; returns the file and `report`'s text.
fn sweep(dir: &TempDir, name: &str, scenario: &str, samples: u32) -> (Columns, String) {
    dir.write(&format!("{name}.toml"), scenario);
    let out = format!("{name}.arrow");
    super::sweep(
        dir,
        &[
            "--scenario",
            &format!("{name}.toml"),
            "--samples",
            &samples.to_string(),
            "--out",
            &out,
            "--quiet",
        ],
    );
    let report = touchdown(dir.path(), &["report", &out]);
    report.assert_ok();
    (Columns::in_dir(dir, &out), report.stdout)
}

#[test]
fn a_hard_drop_on_a_weak_short_cartridge_bottoms_every_leg_and_is_counted() {
    // Hard: 10 m of fall (0.58 m/s, 16.8 J) against four cartridges that take 15.5 N x
    // 5 mm = 0.08 J each: every one runs out of stroke (margin 0, bottomed) in every
    // sample, and `report` counts them all. Gentle: 5 cm (0.041 m/s, 0.084 J) on 5 cm of
    // stroke: the impact (about v sqrt(4 k m) / 4 = 45 N per leg) crushes them a little
    // (about 0.084 J / 62 N = 1.4 mm in all), never to the end: the margin is the usable
    // stroke less the stroke, to the bit, and `report` counts none.
    let dir = TempDir::new("struts-bottoming");
    let samples = 5;
    let (hard, report) = sweep(&dir, "hard", &cartridge(0.005, 10.0), samples);
    assert_eq!(hard.u32s("legs_bottomed"), vec![4; samples as usize]);
    for k in 0..4 {
        assert!(hard.bools(&format!("leg{k}_bottomed")).iter().all(|b| *b));
        assert!(
            hard.f64s(&format!("leg{k}_stroke_margin_m"))
                .iter()
                .all(|m| *m == 0.0),
            "leg {k}: margins {:?}",
            hard.f64s(&format!("leg{k}_stroke_margin_m"))
        );
    }
    assert!(
        report.contains("| a damper bottomed | 5 | 100.00 % |"),
        "{report}"
    );
    let (gentle, report) = sweep(&dir, "gentle", &cartridge(0.05, 0.05), samples);
    assert_eq!(gentle.u32s("legs_bottomed"), vec![0; samples as usize]);
    for k in 0..4 {
        let strokes = gentle.f64s(&format!("leg{k}_stroke_m"));
        let margins = gentle.f64s(&format!("leg{k}_stroke_margin_m"));
        assert!(gentle.bools(&format!("leg{k}_bottomed")).iter().all(|b| !b));
        for (s, m) in strokes.iter().zip(&margins) {
            assert!(*s > 1e-4, "leg {k}: the cartridge crushes ({s} m)");
            assert_eq!(*m, 0.05 - s, "leg {k}: margin {m} of stroke {s}");
        }
    }
    assert!(
        report.contains("| a damper bottomed | 0 | 0.00 % |"),
        "{report}"
    );
}

#[test]
fn without_dampers_the_margin_is_null_and_the_report_says_nothing_of_them() {
    // Rigid legs have no stroke: the margin column is null, nothing bottoms, and the
    // report keeps its sections (no "Gear" without dampers or limits).
    let dir = TempDir::new("struts-rigid");
    let (rigid, report) = sweep(&dir, "rigid", "[simulation]\nt_max_s = 20.0\n", 16);
    for k in 0..4 {
        assert!(
            rigid
                .options(&format!("leg{k}_stroke_margin_m"))
                .iter()
                .all(Option::is_none)
        );
    }
    assert!(rigid.u32s("legs_bottomed").iter().all(|n| *n == 0));
    assert!(!rigid.has("limits_broken"));
    assert!(!report.contains("## Gear"), "{report}");
}
