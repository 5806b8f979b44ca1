//! Hostile scenario files, by property tests: random text, TOML-like token soup, and the
//! default scenario with one value replaced by something of another type or out of range,
//! or with a key it does not have. The reader never panics, and every refusal of a bad
//! value or an unknown key names that key.

use proptest::prelude::*;
use touchdown::scenario::{DEFAULT_TOML, Scenario, ScenarioError};

/// Every leaf of the default scenario as a dotted path (arrays are leaves).
fn leaf_paths() -> Vec<Vec<String>> {
    fn walk(prefix: &[String], table: &toml::Table, out: &mut Vec<Vec<String>>) {
        for (k, v) in table {
            let mut path = prefix.to_vec();
            path.push(k.clone());
            match v {
                toml::Value::Table(t) => walk(&path, t, out),
                _ => out.push(path),
            }
        }
    }
    let table: toml::Table = DEFAULT_TOML.parse().expect("the default scenario is TOML");
    let mut out = Vec::new();
    walk(&[], &table, &mut out);
    out
}

/// The tables of the default scenario (the top level as the empty path).
fn table_paths() -> Vec<Vec<String>> {
    let mut tables: Vec<Vec<String>> = leaf_paths()
        .into_iter()
        .map(|mut p| {
            p.pop();
            p
        })
        .collect();
    tables.sort();
    tables.dedup();
    tables
}

/// The default scenario with the value at `path` set to `value`.
fn with_value(path: &[String], value: toml::Value) -> String {
    let mut table: toml::Table = DEFAULT_TOML.parse().unwrap();
    let mut t = &mut table;
    for k in &path[..path.len() - 1] {
        t = t.get_mut(k).and_then(toml::Value::as_table_mut).unwrap();
    }
    t.insert(path[path.len() - 1].clone(), value);
    toml::to_string(&table).expect("serialise the scenario")
}

/// Values of every TOML type, and numbers where a scenario allows few.
fn hostile_value() -> impl Strategy<Value = toml::Value> {
    prop_oneof![
        Just(toml::Value::Float(f64::NAN)),
        Just(toml::Value::Float(f64::INFINITY)),
        Just(toml::Value::Float(f64::NEG_INFINITY)),
        Just(toml::Value::Float(-1.0e300)),
        Just(toml::Value::Float(1.0e300)),
        Just(toml::Value::Integer(i64::MIN)),
        Just(toml::Value::Integer(i64::MAX)),
        Just(toml::Value::Integer(0)),
        any::<f64>().prop_map(toml::Value::Float),
        any::<i64>().prop_map(toml::Value::Integer),
        any::<bool>().prop_map(toml::Value::Boolean),
        "[a-z ]{0,12}".prop_map(toml::Value::String),
        Just(toml::Value::Array(vec![])),
        prop::collection::vec(any::<f64>().prop_map(toml::Value::Float), 1..5)
            .prop_map(toml::Value::Array),
        Just(toml::Value::Table(toml::Table::new())),
    ]
}

/// The dotted key a refusal names.
fn named_key(e: &ScenarioError) -> Option<&str> {
    match e {
        ScenarioError::Invalid { key, .. } | ScenarioError::UnknownKey { key, .. } => Some(key),
        ScenarioError::Io { .. } | ScenarioError::Syntax(_) => None,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Any text at all: read or refused, never a panic.
    #[test]
    fn any_text_is_read_or_refused(text in "\\PC{0,200}") {
        let _ = Scenario::from_toml(&text);
    }

    /// Text made of the scenario's own words and TOML punctuation, more often near-valid.
    #[test]
    fn toml_token_soup_is_read_or_refused(tokens in prop::collection::vec(prop_oneof![
        Just("[".to_string()), Just("]".to_string()), Just("[[".to_string()),
        Just("=".to_string()), Just("{".to_string()), Just("}".to_string()),
        Just(",".to_string()), Just("\n".to_string()), Just("\"".to_string()),
        Just(" ".to_string()), Just("nan".to_string()), Just("inf".to_string()),
        Just("-".to_string()), Just(".".to_string()),
        prop::sample::select(vec![
            "lander", "surface", "roughness", "damper", "inputs", "simulation", "outcome",
            "mass_kg", "legs", "leg_tips_m", "slope_deg", "dist", "uniform", "normal",
            "grid", "count", "min", "max", "sd", "stages", "step_s", "seed", "samples",
        ]).prop_map(str::to_string),
        any::<f64>().prop_map(|x| x.to_string()),
        any::<i64>().prop_map(|x| x.to_string()),
    ], 0..60)) {
        let _ = Scenario::from_toml(&tokens.concat());
    }

    /// One value of the default scenario replaced: accepted, or refused naming its key
    /// (or the table it belongs to, for a check across the table's keys, or naming it in
    /// the reason, for a check across tables such as "the run reaches the surface").
    #[test]
    fn a_bad_value_is_refused_naming_its_key(
        path in prop::sample::select(leaf_paths()),
        value in hostile_value(),
    ) {
        let text = with_value(&path, value.clone());
        if let Err(e) = Scenario::from_toml(&text) {
            let dotted = path.join(".");
            let key = named_key(&e);
            prop_assert!(
                key.is_some_and(|k| dotted.starts_with(k) || k.starts_with(&dotted)
                    || path.len() > 1 && k.starts_with(&path[..path.len() - 1].join(".")))
                    || e.to_string().contains(&format!("{} ", path[..path.len().min(2)].join("."))),
                "`{dotted}` = {value}: refused with {e}"
            );
        }
    }

    /// A key the scenario does not have, in any of its tables: refused, naming it.
    #[test]
    fn an_unknown_key_is_refused_naming_it(
        table in prop::sample::select(table_paths()),
        name in "[a-z][a-z_]{0,15}",
        value in hostile_value(),
    ) {
        let mut path = table.clone();
        path.push(name.clone());
        prop_assume!(!leaf_paths().contains(&path) && !table_paths().contains(&path));
        let text = with_value(&path, value);
        match Scenario::from_toml(&text) {
            Ok(_) => {
                // Keys the default leaves out (alternatives such as `leg_tips_m`) are
                // known too; an unknown one is never accepted.
                prop_assert!(known_alternative(&path), "`{}` was accepted", path.join("."));
            }
            Err(e) => {
                let dotted = path.join(".");
                prop_assert!(
                    named_key(&e).is_some_and(|k| k == dotted || dotted.starts_with(k)),
                    "unknown `{dotted}`: refused with {e}"
                );
            }
        }
    }
}

/// Keys a scenario may have that the default file leaves out (commented alternatives).
fn known_alternative(path: &[String]) -> bool {
    let dotted = path.join(".");
    DEFAULT_TOML
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("# "))
        .any(|l| {
            l.split_once(" = ")
                .is_some_and(|(k, _)| path.last().is_some_and(|last| k.trim() == last))
        })
        || dotted.is_empty()
}
