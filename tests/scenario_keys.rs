//! `touchdown scenario` against the scenario reader: every key the reader accepts, in every
//! table, stands in the printout (live or commented out), each commented-out key shows its
//! default, the printout reads as the default scenario, and its list of the parameters that
//! may be drawn per sample is the model's and the README's.

use crate::common::BIN;
use std::collections::BTreeSet;
use std::process::Command;
use toml::{Table, Value};
use touchdown::scenario::{Parameter, Scenario, ScenarioError, keys};

/// What `touchdown scenario` prints.
fn printout() -> String {
    let out = Command::new(BIN).arg("scenario").output().unwrap();
    assert!(out.status.success(), "{out:?}");
    String::from_utf8(out.stdout).unwrap()
}

/// A line of the printout as TOML: a commented-out key or table header (`# key = value`,
/// `# [table]`) without its `# `, where it reads as TOML on its own; other lines as they are.
fn uncommented(line: &str) -> &str {
    match line.strip_prefix("# ") {
        Some(rest)
            if rest.starts_with('[') || rest.parse::<Table>().is_ok_and(|t| t.len() == 1) =>
        {
            rest
        }
        _ => line,
    }
}

/// The key a line of the printout gives (live or commented out), if it gives one.
fn key_of(line: &str) -> Option<&str> {
    let (name, _) = line.trim_start_matches("# ").split_once('=')?;
    let name = name.trim();
    let is_key = !name.is_empty()
        && name
            .bytes()
            .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_');
    is_key.then_some(name)
}

/// Every key the printout shows, live or commented out, by its dotted path (the tables of a
/// list of tables without their index), and whether it is commented out, in order.
fn shown(text: &str) -> Vec<(String, bool)> {
    let mut table = String::new();
    let mut keys = Vec::new();
    for line in text.lines() {
        let toml = uncommented(line);
        if let Some(header) = toml.strip_prefix('[') {
            let name = header.trim_start_matches('[');
            table = name[..name.find(']').unwrap()].to_string();
            // A table is a key of the table above it.
            keys.push((table.clone(), toml != line));
        } else if let Some(key) = key_of(line) {
            let path = if table.is_empty() {
                key.to_string()
            } else {
                format!("{table}.{key}")
            };
            keys.push((path, line.starts_with('#')));
        }
    }
    keys
}

/// The printout with every commented-out key and table read as given.
fn all_given(text: &str) -> Table {
    let lines: Vec<&str> = text.lines().map(uncommented).collect();
    lines.join("\n").parse().unwrap()
}

/// `all_given` on regolith (its table is read only there): every table of the reader at
/// once.
fn everything(text: &str) -> Table {
    let mut table = all_given(text);
    keys::set(&mut table, "surface.kind", Value::from("regolith")).unwrap();
    table
}

/// The keys the reader knows in the table at `path` of `scenario`: its refusal of a key it
/// does not know lists them.
fn known(scenario: &Table, path: &str) -> Vec<String> {
    let mut probe = scenario.clone();
    let key = if path.is_empty() {
        "not_a_key".to_string()
    } else {
        format!("{path}.not_a_key")
    };
    keys::set(&mut probe, &key, Value::from(0)).unwrap();
    match Scenario::from_toml(&toml::to_string(&probe).unwrap()) {
        Err(ScenarioError::UnknownKey { key, known, .. }) if key.ends_with("not_a_key") => {
            known.split(", ").map(String::from).collect()
        }
        other => panic!("a key unknown to [{path}]: {other:?}"),
    }
}

/// The keys the reader knows in the table at `path` and every table below it, missing from
/// `shown`.
fn missing(scenario: &Table, path: &str, shown: &BTreeSet<String>, out: &mut Vec<String>) {
    for key in known(scenario, path) {
        let full = if path.is_empty() {
            key
        } else {
            format!("{path}.{key}")
        };
        let without_index: Vec<&str> = full
            .split('.')
            .filter(|n| !n.bytes().all(|b| b.is_ascii_digit()))
            .collect();
        if !shown.contains(&without_index.join(".")) {
            out.push(full.clone());
        }
        match keys::get(scenario, &full) {
            Some(Value::Table(t)) if !t.contains_key("dist") => {
                missing(scenario, &full, shown, out)
            }
            Some(Value::Array(a)) if a.first().is_some_and(Value::is_table) => {
                missing(scenario, &format!("{full}.0"), shown, out);
            }
            _ => {}
        }
    }
}

#[test]
fn every_key_the_reader_accepts_is_printed() {
    let text = printout();
    let shown: BTreeSet<String> = shown(&text).into_iter().map(|(k, _)| k).collect();
    let scenario = everything(&text);
    let mut out = Vec::new();
    missing(&scenario, "", &shown, &mut out);
    assert!(
        out.is_empty(),
        "keys the reader accepts that `touchdown scenario` does not show: {out:?}"
    );
    // A key left out of the printout is found missing.
    let mut fewer = shown.clone();
    fewer.remove("limits.side_force_n");
    let mut out = Vec::new();
    missing(&scenario, "", &fewer, &mut out);
    assert_eq!(out, ["limits.side_force_n"]);
    // The walk reached the optional tables and keys.
    for key in [
        "limits.stroke_margin_m",
        "surface.regolith.bekker_n",
        "surface.rocks.abundance",
        "initial.normal_speed_m_s",
        "lander.footpad_area_m2",
        "control.descent.null_lateral_velocity",
        "thrusters.min_on_time_s",
    ] {
        assert!(shown.contains(key), "{key}");
    }
}

/// The commented-out keys show their defaults: each, given as shown, reads as the scenario
/// that leaves it out (the keys without a default show an example, which the printout says).
#[test]
fn the_commented_out_keys_show_their_defaults() {
    const EXAMPLES: [&str; 8] = [
        "limits",
        "thrusters",
        "initial.normal_speed_m_s",
        "initial.tangential_speed_m_s",
        "initial.tangential_azimuth_deg",
        "control.law",
        "control.hold_down.stop_tilt_deg",
        "simulation.tolerance_m_s",
    ];
    let text = printout();
    let given = all_given(&text);
    let mut checked = 0;
    for (key, commented) in shown(&text) {
        let example = EXAMPLES
            .iter()
            .any(|e| key == *e || key.starts_with(&format!("{e}.")));
        let value = keys::get(&given, &key);
        if !commented || example || value.is_none_or(Value::is_table) {
            continue;
        }
        let mut without: Table = text.parse().unwrap();
        if key.starts_with("surface.regolith.") {
            keys::set(&mut without, "surface.kind", Value::from("regolith")).unwrap();
        }
        keys::parent_table(&mut without, &key).unwrap();
        let mut with = without.clone();
        keys::set(&mut with, &key, value.unwrap().clone()).unwrap();
        let read = |t: &Table| Scenario::from_toml(&toml::to_string(t).unwrap()).unwrap();
        assert_eq!(read(&with), read(&without), "{key}");
        checked += 1;
    }
    assert!(checked >= 30, "{checked}");
}

#[test]
fn the_printout_is_the_default_scenario() {
    assert_eq!(
        Scenario::from_toml(&printout()).unwrap(),
        Scenario::default()
    );
}

/// The keys of a list that names them: the items of the lines `#   KEY, KEY, ...` of the
/// printout's opening comments.
fn header_parameters(text: &str) -> BTreeSet<String> {
    let is_key = |s: &str| {
        !s.is_empty()
            && s.bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_' || b == b'.')
    };
    text.lines()
        .take_while(|l| l.starts_with('#') || l.is_empty())
        .filter_map(|l| l.strip_prefix("#   "))
        .filter(|l| {
            l.split(',')
                .map(str::trim)
                .filter(|s| !s.is_empty())
                .all(is_key)
        })
        .flat_map(|l| l.split(',').map(str::trim).filter(|s| !s.is_empty()))
        .map(String::from)
        .collect()
}

#[test]
fn the_drawable_parameters_are_the_models_and_the_readmes() {
    let text = printout();
    let printed = header_parameters(&text);
    let model: BTreeSet<String> = Parameter::ALL.iter().map(|p| p.key().to_string()).collect();
    assert_eq!(printed, model);

    // The README's list: the scenario's numbers that its paragraph names in backticks, a
    // table's `*` standing for every number of the table.
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let section = &readme[readme
        .find("### Uncertain surface and lander parameters")
        .unwrap()..];
    let paragraph =
        &section[section.find("They are").unwrap()..section.find("Each\ndrawn").unwrap()];
    let everything = everything(&text);
    let is_number = |key: &str| {
        matches!(
            keys::get(&everything, key),
            Some(Value::Float(_) | Value::Integer(_))
        )
    };
    let mut listed = BTreeSet::new();
    for name in paragraph.split('`').skip(1).step_by(2) {
        if let Some(table) = name.strip_suffix(".*") {
            let Some(Value::Table(t)) = keys::get(&everything, table) else {
                panic!("README: `{name}` is no table of the scenario")
            };
            listed.extend(
                t.keys()
                    .map(|k| format!("{table}.{k}"))
                    .filter(|k| is_number(k)),
            );
        } else if is_number(name) {
            listed.insert(name.to_string());
        }
    }
    assert_eq!(listed, printed, "README against `touchdown scenario`");
}
