//! Limits where the results are shown: the sweep's closing summary counts the samples
//! within them and those that broke each, as `report` does; `trace` prints a sample's strut
//! peaks, stroke margins and broken limits, as its row has them; the exceedance picture
//! draws each limit as a line.

use super::Columns;
use crate::common::{TempDir, touchdown};

/// `scenarios/flat.toml` (gentle touchdowns on 90 psi dampers) with an axial limit of
/// 150 N, a side limit of 40 N and a least stroke margin of 49.9 mm: some of 400 samples
/// break one, some two, some none.
fn gear_scenario() -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/flat.toml");
    let flat = std::fs::read_to_string(path).unwrap();
    format!(
        "{flat}\n[limits]\naxial_force_n = 150.0\nside_force_n = 40.0\nstroke_margin_m = 0.0499\n"
    )
}

/// The count of the row of `text` (the sweep's summary, or the report's Markdown) that
/// starts with `name` after its indent or `| `.
fn count(text: &str, name: &str) -> u64 {
    let line = text
        .lines()
        .find(|l| {
            let l = l.trim_start_matches([' ', '|']).trim_start();
            l.starts_with(name) && l[name.len()..].starts_with([' ', '|'])
        })
        .unwrap_or_else(|| panic!("no row {name} in\n{text}"));
    line[line.find(name).unwrap() + name.len()..]
        .split([' ', '|'])
        .find(|w| !w.is_empty())
        .and_then(|w| w.parse().ok())
        .unwrap_or_else(|| panic!("no count in {line}"))
}

#[test]
fn the_sweep_summary_and_a_trace_show_the_limits() {
    let dir = TempDir::new("struts-limits-shown");
    dir.write("gear.toml", &gear_scenario());
    let args = ["sweep", "--scenario", "gear.toml", "--samples", "400"];
    let sweep = touchdown(
        dir.path(),
        &[&args[..], &["--out", "g.arrow", "--quiet"]].concat(),
    );
    assert_eq!(sweep.code, Some(0), "{sweep}");
    let report = touchdown(dir.path(), &["report", "g.arrow"]);
    report.assert_ok();
    let rows = [
        "stable within limits",
        "broke `axial_force`: peak axial strut load above 150 N",
        "broke `side_force`: peak side load above 40 N",
        "broke `stroke_margin`: stroke margin below 0.0499 m, or bottomed",
    ];
    for name in rows {
        assert_eq!(
            count(&sweep.stdout, name),
            count(&report.stdout, name),
            "{name}\n{sweep}\n{}",
            report.stdout
        );
    }
    // The limits split the samples: the counts say something.
    let some = |name| (1..400).contains(&count(&sweep.stdout, name));
    assert!(some(rows[0]) && some(rows[1]) && some(rows[2]), "{sweep}");

    // A sample that broke two limits, traced: its struts and limits as its row has them.
    let file = Columns::in_dir(&dir, "g.arrow");
    let broken = file.strings("limits_broken");
    let i = broken
        .iter()
        .position(|b| b.contains(','))
        .expect("a sample that broke two limits");
    let sample = i.to_string();
    let trace = touchdown(
        dir.path(),
        &[
            "trace", "--sweep", "g.arrow", "--sample", &sample, "--out", "t.arrow",
        ],
    );
    trace.assert_ok();
    let text = &trace.stdout;
    assert!(
        text.contains(&format!("\n  limits broken            {}\n", broken[i])),
        "sample {i}, {}:\n{text}",
        broken[i]
    );
    for k in 0..4 {
        let leg = |name: &str| file.options(&format!("leg{k}_{name}"))[i];
        let at = |s: Option<f64>| s.map_or("never".to_string(), |s| format!("{s:.3}"));
        let expected = format!(
            "  {k:>3}  {:>17.2}   {:>6}   {:>16.2}   {:>6}   {:>16.3}",
            leg("peak_axial_force_n").unwrap(),
            at(leg("peak_axial_force_s")),
            leg("peak_side_force_n").unwrap(),
            at(leg("peak_side_force_s")),
            1e3 * leg("stroke_margin_m").unwrap()
        );
        assert!(text.contains(&expected), "leg {k}: {expected}\n{text}");
    }
}

#[test]
fn the_exceedance_picture_marks_each_limit() {
    // The limit lines are drawn in the limit colour from the panel's foot to its top:
    // columns of many such pixels, one run of columns per limit (three), and none without
    // limits.
    let dir = TempDir::new("struts-limits-picture");
    dir.write("gear.toml", &gear_scenario());
    let flat = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/flat.toml");
    dir.write("plain.toml", &std::fs::read_to_string(flat).unwrap());
    let mut lines = Vec::new();
    for name in ["gear", "plain"] {
        let scenario = format!("{name}.toml");
        let out = format!("{name}.arrow");
        let args = [
            "--scenario",
            &scenario,
            "--samples",
            "200",
            "--out",
            &out,
            "--quiet",
        ];
        super::sweep(&dir, &args);
        touchdown(dir.path(), &["plot", &out, "--out-dir", "p"]).assert_ok();
        let png = crate::common::read_bytes(&dir.join(&format!("p/{name}-exceedance.png")));
        let img = image::load_from_memory(&png).unwrap().to_rgb8();
        let tall: Vec<u32> = (0..img.width())
            .filter(|&x| {
                (0..img.height())
                    .filter(|&y| img.get_pixel(x, y).0 == [200, 0, 200])
                    .count()
                    > 200
            })
            .collect();
        let runs =
            tall.windows(2).filter(|w| w[1] > w[0] + 1).count() + usize::from(!tall.is_empty());
        lines.push(runs);
    }
    assert_eq!(
        lines,
        [3, 0],
        "limit lines in the pictures with and without limits"
    );
}
