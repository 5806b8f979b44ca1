//! `touchdown report --json` (issue 31): the report as data gives the sweep's own counts,
//! shares and Wilson intervals, and the very numbers its Markdown rounds (allowable slopes,
//! peak loads, exceedance design values, gear, thrust, release and terrain sections); and a
//! sweep held in memory (`SweepSource::Memory`) reports as its file does.

use crate::common::{SHORT, TempDir, touchdown};
use serde_json::Value;
use std::path::{Path, PathBuf};
use touchdown::output::columns::Table;
use touchdown::output::sweep::SweepSource;
use touchdown::reference::Outcome;
use touchdown::stats::wilson_interval;

/// A scenario of `scenarios/`, with `extra` appended.
fn scenario(name: &str, extra: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(name);
    format!("{}\n{extra}", std::fs::read_to_string(path).unwrap())
}

/// Sweeps `samples` of `scenario` into `dir/out`.
fn sweep(dir: &TempDir, scenario: &str, samples: &str, out: &str) -> PathBuf {
    let name = format!("{out}.toml");
    dir.write(&name, scenario);
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            &name,
            "--samples",
            samples,
            "--out",
            out,
            "--quiet",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    dir.join(out)
}

/// The report of `out` in Markdown and as JSON (parsed), with `extra` arguments.
fn reports(dir: &TempDir, out: &str, extra: &[&str]) -> (String, Value) {
    let markdown = touchdown(dir.path(), &[&["report", out], extra].concat());
    markdown.assert_ok();
    let json = touchdown(dir.path(), &[&["report", out, "--json"], extra].concat());
    json.assert_ok();
    let value = serde_json::from_str(&json.stdout)
        .unwrap_or_else(|e| panic!("not JSON ({e}):\n{}", json.stdout));
    (markdown.stdout, value)
}

/// The cells of the Markdown table row of section `section` whose first cell is `first`.
fn row(markdown: &str, section: &str, first: &str) -> Vec<String> {
    let body = markdown
        .split(&format!("## {section}"))
        .nth(1)
        .unwrap_or_else(|| panic!("no section {section} in\n{markdown}"));
    let line = body
        .lines()
        .take_while(|l| !l.starts_with("## "))
        .find(|l| l.starts_with(&format!("| {first} |")))
        .unwrap_or_else(|| panic!("no row {first:?} in section {section}:\n{body}"));
    line.trim_matches('|')
        .split('|')
        .map(|c| c.trim().to_string())
        .collect()
}

/// A number of the JSON (`serde_json` parses with `float_roundtrip` in the tests: the
/// number written is the number read, bit for bit).
fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

/// A share's JSON (`count`, `share`, `low`, `high`): `count` of `total`, its share and
/// Wilson interval exactly, and its Markdown row `row` ("name | count | share | interval").
fn check_share(share: &Value, count: u64, total: u64, row: &[String]) {
    assert_eq!(share["count"], count, "{share}");
    assert_eq!(f(&share["share"]), count as f64 / total as f64, "{share}");
    let (low, high) = wilson_interval(count, total);
    assert_eq!(
        (f(&share["low"]), f(&share["high"])),
        (low, high),
        "{share}"
    );
    assert_eq!(row[1], count.to_string());
    assert_eq!(
        row[3],
        format!("{:.2} – {:.2} %", 100.0 * low, 100.0 * high)
    );
}

/// `x` as the Markdown writes it to four decimals.
fn four(v: &Value) -> String {
    format!("{:.4}", f(v))
}

/// The outcome counts of the sweep file's own column.
fn outcome_counts(path: &Path) -> ([u64; Outcome::ALL.len()], u64) {
    let t = Table::read(path, |_| false).unwrap();
    let mut counts = [0u64; Outcome::ALL.len()];
    for &o in &t.outcome {
        counts[o as usize] += 1;
    }
    (counts, t.rows as u64)
}

/// What every report has: outcomes, allowable slopes, peak loads and exceedance, its JSON
/// against the file's column and its Markdown.
fn check_common(path: &Path, markdown: &str, r: &Value, controlled: bool) {
    let (counts, total) = outcome_counts(path);
    assert_eq!(r["provenance"]["samples"], total);
    assert_eq!(r["provenance"]["seed"], 1);
    assert_eq!(r["provenance"]["in_memory"], false);
    let outcomes = r["outcomes"].as_object().unwrap();
    let listed: Vec<Outcome> = Outcome::listed(controlled).collect();
    assert_eq!(outcomes.len(), listed.len(), "{outcomes:?}");
    for o in listed {
        let cells = row(markdown, "Outcomes", o.name());
        check_share(&r["outcomes"][o.name()], counts[o as usize], total, &cells);
    }

    let sectors = r["allowable_slope"].as_array().unwrap();
    assert_eq!(sectors.len(), 8);
    for (k, s) in sectors.iter().enumerate() {
        let cells = row(
            markdown,
            "Allowable slope",
            &format!("{}–{} deg", 45 * k, 45 * (k + 1)),
        );
        assert_eq!(cells[1], s["samples"].to_string());
        let (slope, cell) = (&s["slope_deg"], &cells[3]);
        match s["reason"].as_str() {
            None => {
                assert_eq!(*cell, format!("{:.1} deg", f(slope)));
                assert_eq!(
                    cells[4],
                    format!("{:.1}–{:.1} deg", f(&s["low_deg"]), f(&s["high_deg"]))
                );
            }
            Some("too few samples") => {
                assert!(slope.is_null());
                assert_eq!(*cell, format!("too few samples ({})", s["samples"]));
            }
            Some(reason) => {
                assert!(slope.is_null() && reason.starts_with("no slope"), "{s}");
                assert!(cell.starts_with("no slope with"), "{cell}");
                assert_eq!(cells[4], format!("0.0–{:.1} deg", f(&s["high_deg"])));
            }
        }
    }

    for (key, l) in r["peak_loads"].as_object().unwrap() {
        let name = format!(
            "{} ({})",
            l["name"].as_str().unwrap(),
            l["unit"].as_str().unwrap()
        );
        let cells = row(markdown, "Peak loads", &name);
        assert_eq!(
            cells[1..],
            [four(&l["mean"]), four(&l["p99"]), four(&l["max"])],
            "{key}"
        );
    }

    let exceedance = &r["exceedance"];
    assert_eq!(exceedance["samples"], total);
    for (key, q) in exceedance["quantities"].as_object().unwrap() {
        let name = format!(
            "{} ({})",
            q["name"].as_str().unwrap(),
            q["unit"].as_str().unwrap()
        );
        let legs = q["legs"].as_array().unwrap();
        let mut rows = vec![(
            if legs.is_empty() { "–" } else { "all legs" }.to_string(),
            &q["overall"],
        )];
        rows.extend(legs.iter().enumerate().map(|(k, l)| (k.to_string(), l)));
        for (leg, values) in rows {
            let line = markdown
                .lines()
                .find(|l| l.starts_with(&format!("| {name} | {leg} |")))
                .unwrap_or_else(|| panic!("no exceedance row {name}, {leg}"));
            let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
            for (cell, level) in cells[2..4].iter().zip(["p99", "p99_9"]) {
                let d = &values[level];
                let end = |v: &Value, none: &str| {
                    if v.is_null() {
                        none.to_string()
                    } else {
                        four(v)
                    }
                };
                let expected = format!(
                    "{} ({} – {})",
                    four(&d["value"]),
                    end(&d["low"], "?"),
                    end(&d["high"], "more samples needed")
                );
                assert_eq!(*cell, expected, "{key} leg {leg} {level}");
                assert_eq!(
                    d["reason"] == "more samples needed",
                    d["high"].is_null(),
                    "{key} leg {leg} {level}: {d}"
                );
            }
            assert_eq!(cells[4], four(&values["max"]), "{key} leg {leg}");
        }
    }
}

#[test]
fn report_json_gives_the_sweeps_counts_and_the_markdowns_numbers() {
    let dir = TempDir::new("report-json");

    // The default sweep, cut at 20 s: no gear, thrust or release section.
    sweep(&dir, SHORT, "400", "default.arrow");
    let (markdown, r) = reports(&dir, "default.arrow", &[]);
    check_common(&dir.join("default.arrow"), &markdown, &r, false);
    for section in [
        "gear",
        "stable_within_limits",
        "regolith",
        "terrain",
        "thrust",
        "release",
    ] {
        assert!(r[section].is_null(), "{section}: {}", r[section]);
    }
    // Few samples: 99.9 % design values need more, and say so.
    let acc = &r["exceedance"]["quantities"]["peak_acceleration_m_s2"]["overall"]["p99_9"];
    assert!(
        acc["high"].is_null() && acc["reason"] == "more samples needed",
        "{acc}"
    );

    // Landers set down on two sectors of azimuth (`report::GENTLE`, 0-80 deg): an allowable
    // slope in one, none in the other, too few samples in the rest.
    let gentle = crate::report::GENTLE.replace("max = 360.0", "max = 80.0");
    let path = sweep(&dir, &gentle, "400", "gentle.arrow");
    let (markdown, r) = reports(&dir, "gentle.arrow", &[]);
    check_common(&path, &markdown, &r, false);
    let reasons: Vec<&str> = r["allowable_slope"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["reason"].as_str().unwrap_or("a slope"))
        .collect();
    assert_eq!(
        reasons[..2],
        ["a slope", "no slope with at least 99 % stable"]
    );
    assert!(
        reasons[2..].iter().all(|r| *r == "too few samples"),
        "{reasons:?}"
    );

    // On a terrain: the weighted shares of the Markdown.
    let (markdown, r) = reports(
        &dir,
        "default.arrow",
        &["--slope-distribution", "rayleigh:12"],
    );
    let terrain = &r["terrain"];
    assert_eq!(terrain["distribution"], "rayleigh:12");
    assert_eq!(terrain["samples"], 400);
    for o in Outcome::listed(false) {
        let s = &terrain["outcomes"][o.name()];
        let cells = row(&markdown, "On a terrain", o.name());
        assert_eq!(cells[1], format!("{:.2} %", 100.0 * f(&s["share"])));
        assert_eq!(
            cells[2],
            format!(
                "{:.2} – {:.2} %",
                100.0 * f(&s["low"]),
                100.0 * f(&s["high"])
            )
        );
    }

    // Gentle touchdowns on dampers with every limit: the gear section and the stable
    // samples within the limits, as the Markdown counts them.
    let limits = "[limits]\naxial_force_n = 150.0\nside_force_n = 40.0\n\
                  acceleration_m_s2 = 2.0\nstroke_margin_m = 0.01\n";
    let path = sweep(&dir, &scenario("flat.toml", limits), "300", "limits.arrow");
    let (markdown, r) = reports(&dir, "limits.arrow", &[]);
    check_common(&path, &markdown, &r, false);
    let total = 300;
    let within = &r["stable_within_limits"];
    let cells = row(&markdown, "Outcomes", "stable within limits");
    check_share(within, within["count"].as_u64().unwrap(), total, &cells);
    let gear = &r["gear"];
    let bottomed = &gear["damper_bottomed"];
    let cells = row(&markdown, "Gear", "a damper bottomed");
    check_share(bottomed, bottomed["count"].as_u64().unwrap(), total, &cells);
    let broken = gear["limits_broken"].as_object().unwrap();
    assert_eq!(
        broken.keys().collect::<Vec<_>>(),
        // Sorted: the tests' `serde_json` keeps no order of keys.
        ["acceleration", "axial_force", "side_force", "stroke_margin"]
    );
    for (name, b) in broken {
        let first = format!("broke `{name}`: {}", b["description"].as_str().unwrap());
        let cells = row(&markdown, "Gear", &first);
        check_share(b, b["count"].as_u64().unwrap(), total, &cells);
    }
    assert_eq!(broken["axial_force"]["limit"], 150.0);
    assert_eq!(broken["axial_force"]["limit_key"], "axial_force_n");

    // A hold-down control loop: `held` listed, and the thrust section.
    let path = sweep(&dir, &scenario("hold-down.toml", ""), "200", "hold.arrow");
    let (markdown, r) = reports(&dir, "hold.arrow", &[]);
    check_common(&path, &markdown, &r, true);
    let thrust = &r["thrust"];
    assert_eq!(thrust["samples"], 200);
    for q in thrust["quantities"].as_object().unwrap().values() {
        let name = format!(
            "{} ({})",
            q["name"].as_str().unwrap(),
            q["unit"].as_str().unwrap()
        );
        let cells = row(&markdown, "Propellant and firings", &name);
        let expected = ["mean", "median", "p99", "max"].map(|k| four(&q[k]));
        assert_eq!(cells[1..], expected, "{name}");
    }
    for (o, v) in thrust["by_outcome"].as_object().unwrap() {
        let cells = row(&markdown, "Propellant and firings", o);
        assert_eq!(
            cells[1..],
            [v["samples"].to_string(), four(&v["mean_propellant_kg"])]
        );
    }

    // A powered descent: the release section.
    let path = sweep(&dir, &scenario("descent.toml", ""), "200", "descent.arrow");
    let (markdown, r) = reports(&dir, "descent.arrow", &[]);
    check_common(&path, &markdown, &r, true);
    let release = &r["release"];
    assert_eq!(release["samples"], 200);
    assert!(
        markdown.contains(&format!(
            "{} of 200 samples released by the descent law",
            release["released"]
        )),
        "{markdown}"
    );
    for q in release["quantities"].as_object().unwrap().values() {
        let name = format!(
            "{} ({})",
            q["name"].as_str().unwrap(),
            q["unit"].as_str().unwrap()
        );
        let cells = row(&markdown, "Release of the descent", &name);
        let expected = ["mean", "min", "median", "p99", "max"].map(|k| four(&q[k]));
        assert_eq!(cells[1..], expected, "{name}");
    }
}

/// The schema and batches of the Arrow file at `path`, as Python would hold them.
fn batches(path: &Path) -> (arrow_schema::SchemaRef, Vec<arrow_array::RecordBatch>) {
    let file = std::fs::File::open(path).unwrap();
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).unwrap();
    let schema = reader.schema();
    (schema, reader.map(Result::unwrap).collect())
}

#[test]
fn a_sweep_in_memory_reports_as_its_file_does() {
    let dir = TempDir::new("report-memory");
    let path = sweep(&dir, SHORT, "300", "s.arrow");
    let file = SweepSource::Path(path.clone());
    let (schema, rows) = batches(&path);
    let memory = SweepSource::Memory {
        name: path.display().to_string(),
        schema: schema.clone(),
        batches: rows.clone(),
    };
    let terrain = touchdown::weighting::SlopeDistribution::parse("rayleigh:12").unwrap();
    for terrain in [None, Some((&terrain, "rayleigh:12"))] {
        let report = |s: &SweepSource| touchdown::report::report(s, terrain).unwrap();
        assert_eq!(report(&memory), report(&file));
        let json = |s: &SweepSource| -> Value {
            serde_json::from_str(&touchdown::report::report_json(s, terrain).unwrap()).unwrap()
        };
        let (mut from_memory, from_file) = (json(&memory), json(&file));
        assert_eq!(from_memory["provenance"]["in_memory"], true);
        from_memory["provenance"]["in_memory"] = false.into();
        assert_eq!(from_memory, from_file);
    }

    // A table without the sweep's metadata (a conversion dropped it) is refused, by name.
    let bare = std::sync::Arc::new(arrow_schema::Schema::new(schema.fields().clone()));
    let stripped = SweepSource::Memory {
        name: "my table".to_string(),
        schema: bare.clone(),
        batches: rows
            .iter()
            .map(|b| arrow_array::RecordBatch::try_new(bare.clone(), b.columns().to_vec()).unwrap())
            .collect(),
    };
    let e = touchdown::report::report_json(&stripped, None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("my table is not a sweep of touchdown") && e.contains("touchdown.kind"),
        "{e}"
    );
}
