//! The charts of a `touchdown view` page: only what the trace has (a damper stroke with
//! dampers, a sinkage on regolith, every line's series in the page), and the tick labels of
//! the trace page's charts and the site page's colour scale never read `-0.0`.

use crate::common::{TempDir, touchdown};
use std::path::Path;
use std::process::Command;

/// The elastic plane, no dampers: a level-ish touchdown of 6 s.
const PLANE: &str = "[inputs]\nslope_deg = 3.0\n[simulation]\nt_max_s = 6.0\n";

/// The same on soil weak enough for the footpads to sink (as `ground_pictures::SOFT`).
const SOIL: &str = "[surface]\nkind = \"regolith\"\ndamping_n_s_per_m = 5.0\n\
    [surface.regolith]\nbekker_k_phi = 3000.0\nbekker_k_c = 20.0\ncohesion_pa = 5.0\n\
    [inputs]\nslope_deg = 3.0\n[simulation]\nt_max_s = 6.0\n";

/// The JSON of the page `name.html` in `dir`.
fn page_data(dir: &TempDir, name: &str) -> serde_json::Value {
    let page = std::fs::read_to_string(dir.join(&format!("{name}.html"))).unwrap();
    crate::common::page_json(&page, "trace-data")
}

#[test]
fn a_page_charts_only_what_its_trace_has() {
    let dir = TempDir::new("view-charts");
    let dampers = format!("[damper]\nenabled = true\n{PLANE}");
    for (name, scenario) in [
        ("plane", PLANE),
        ("dampers", dampers.as_str()),
        ("soil", SOIL),
    ] {
        dir.write(&format!("{name}.toml"), scenario);
        let (toml, out) = (format!("{name}.toml"), format!("{name}.arrow"));
        let args = ["trace", "--scenario", &toml, "--out", &out];
        touchdown(dir.path(), &args).assert_ok();
        touchdown(dir.path(), &["view", &out]).assert_ok();
    }
    let stroke = "damper stroke per leg (mm)";
    let sinkage = "footpad sinkage per leg (mm)";
    for (name, expected) in [
        ("plane", &[][..]),
        ("dampers", &[stroke][..]),
        ("soil", &[sinkage][..]),
    ] {
        let d = page_data(&dir, name);
        let charts = d["charts"].as_array().expect("charts");
        let titles: Vec<&str> = charts
            .iter()
            .map(|c| c["title"].as_str().unwrap())
            .collect();
        let ground: Vec<&str> = titles
            .iter()
            .copied()
            .filter(|t| *t == stroke || *t == sinkage)
            .collect();
        assert_eq!(ground, expected, "{name}: {titles:?}");
        // Every line is of a series the page holds, one value per time.
        let times = d["time"].as_array().unwrap().len();
        for line in charts.iter().flat_map(|c| c["lines"].as_array().unwrap()) {
            let series = line["series"].as_str().unwrap();
            let values = d["series"][series].as_array();
            assert_eq!(values.map(Vec::len), Some(times), "{name}: {series}");
        }
    }
    // The soil's chart: each leg sunk, as the page's footpads are.
    let d = page_data(&dir, "soil");
    for k in 0..4 {
        let values = d["series"][format!("leg{k}_sinkage_m")].as_array().unwrap();
        assert_eq!(values, d["sinkage_m"][k].as_array().unwrap(), "leg {k}");
        assert!(values.last().unwrap().as_f64().unwrap() > 0.01, "leg {k}");
    }
}

/// The text of the JavaScript function `name` in `page` (from `function name(` to the
/// closing brace at the start of a line).
fn function(page: &str, name: &str) -> String {
    let start = page
        .find(&format!("\nfunction {name}("))
        .unwrap_or_else(|| panic!("no function {name}"));
    let end = start + page[start..].find("\n}\n").unwrap() + 3;
    page[start..end].to_string()
}

#[test]
fn tick_labels_never_read_minus_zero() {
    // Ranges across 0 of many widths and offsets, their ticks labelled as the trace page's
    // charts (`toFixed` to the ticks' digits) and the site page's colour scale (`fmt` to 3
    // digits) label them: no label is a negative zero, and a range across 0 has a tick 0.
    let node = Command::new("node").arg("--version").output();
    if !node.is_ok_and(|o| o.status.success()) {
        eprintln!("SKIPPED tick_labels_never_read_minus_zero (no node)");
        return;
    }
    let dir = TempDir::new("view-ticks");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/view");
    let viewer = std::fs::read_to_string(src.join("viewer.html")).unwrap();
    let site = std::fs::read_to_string(src.join("site.html")).unwrap();
    let script = format!(
        "const fin = Number.isFinite;\n\
         const viewer = (() => {{ {} return ticks; }})();\n\
         const site = (() => {{ {} {} return (a, b, n) => ticks(a, b, n).map((v) => fmt(v, 3)); }})();\n\
         const bad = [];\n\
         for (const w of [0.003, 0.3, 0.7, 1.3, 3, 7, 45, 130]) for (let f = 0.05; f < 1; f += 0.1) {{\n\
           const a = -w * f, b = w * (1 - f);\n\
           for (const n of [3, 4, 5, 6, 8]) {{\n\
             const t = viewer(a, b, n), labels = t.values.map((v) => v.toFixed(t.digits));\n\
             const s = site(a, b, n);\n\
             for (const l of labels.concat(s)) if (/^-0(\\.0*)?$/.test(l) || /e-1[0-9]/.test(l)) bad.push([a, b, n, l]);\n\
             if (!labels.some((l) => Number(l) === 0) || !s.includes('0')) bad.push([a, b, n, 'no 0', labels, s]);\n\
           }}\n\
         }}\n\
         console.log(JSON.stringify(bad.slice(0, 10)));\n",
        function(&viewer, "ticks"),
        function(&site, "ticks"),
        function(&site, "fmt"),
    );
    dir.write("ticks.js", &script);
    let o = Command::new("node")
        .arg(dir.join("ticks.js"))
        .output()
        .expect("run node");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        stdout.trim(),
        "[]",
        "labels that read a negative zero or miss 0"
    );
}
