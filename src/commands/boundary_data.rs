//! `touchdown boundary --json` and `--csv`: the search's sectors as data, the numbers
//! unrounded, for a program to read rather than a person (the Markdown report is
//! `boundary`'s). Only the sectors the scenario's azimuth and yaw can put samples in are
//! given, as the report shows them.

use crate::boundary::Stop;
use crate::run::boundary::{Search, Sector, Settings};
use crate::scenario::{value_key, value_name, value_unit};
use crate::stats::{Allowable, SECTOR_DEG};
use serde_json::{Value, json};
use std::fmt::Write as _;

/// What a search ran: its scenario (as messages name it), seed and settings, and how long
/// it took.
pub(super) struct About {
    pub(super) scenario: String,
    pub(super) seed: u64,
    pub(super) settings: Settings,
    pub(super) seconds: f64,
}

/// A sector's result: its allowable value, its 95 % interval (`None` where the samples
/// resolve none), and a word for which it is; values below `min`, the input's least, are
/// taken to it (as the report does).
fn result(allowable: Allowable, min: f64) -> (&'static str, Option<f64>, Option<f64>, Option<f64>) {
    match allowable {
        Allowable::TooFewSamples(_) => ("too_few_samples", None, None, None),
        Allowable::NoSlope { below_deg } => {
            ("no_allowable_value", None, Some(min), Some(below_deg))
        }
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => (
            "allowable",
            Some(slope_deg),
            Some(low_deg.max(min)),
            Some(high_deg),
        ),
    }
}

/// Why a sector's search stopped, as a word.
fn stopped(stop: Option<Stop>) -> &'static str {
    match stop {
        None => "",
        Some(Stop::Tolerance) => "tolerance",
        Some(Stop::WholeRange) => "whole_range",
        Some(Stop::NoSlope) => "no_allowable_value",
        Some(Stop::SampleLimit) => "sample_limit",
        Some(Stop::Unreached) => "unreached",
    }
}

/// The sectors searched (those the scenario's azimuth and yaw reach), with their index.
pub(super) fn searched(found: &Search) -> impl Iterator<Item = (usize, &Sector)> {
    found
        .sectors
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.rounds.is_empty())
}

/// The search as one JSON document: what ran, then each searched sector.
pub(super) fn json(about: &About, found: &Search) -> String {
    let min = found.dist.support().0;
    let sectors: Vec<Value> = searched(found)
        .map(|(k, s)| {
            let (result, value, low, high) = result(s.allowable, min);
            json!({
                "azimuth_min_deg": k as f64 * SECTOR_DEG,
                "azimuth_max_deg": (k + 1) as f64 * SECTOR_DEG,
                "samples": s.used,
                "rounds": s.rounds.len(),
                "result": result,
                "allowable": value,
                "interval_low": low,
                "interval_high": high,
                "stopped": stopped(s.stop),
            })
        })
        .collect();
    let k = found.input;
    let document = json!({
        "scenario": about.scenario,
        "seed": about.seed,
        "input": value_name(k),
        "key": value_key(k),
        "unit": value_unit(k),
        "distribution": found.dist.toml(),
        "tolerance": found.tolerance,
        "batch": about.settings.batch,
        "max_samples_per_sector": about.settings.max_samples_per_sector,
        "samples": found.total,
        "candidates": found.candidates,
        "seconds": about.seconds,
        "sectors": sectors,
    });
    let mut text = serde_json::to_string_pretty(&document).expect("JSON of plain values");
    text.push('\n');
    text
}

/// The searched sectors as CSV, one row each; the value columns are named after the input
/// (`allowable_slope_deg`, its unit in its name).
pub(super) fn csv(found: &Search) -> String {
    let name = value_name(found.input);
    let min = found.dist.support().0;
    let mut t = format!(
        "azimuth_min_deg,azimuth_max_deg,samples,rounds,result,allowable_{name},\
         allowable_{name}_low,allowable_{name}_high,stopped\n"
    );
    let cell = |x: Option<f64>| x.map_or(String::new(), |x| x.to_string());
    for (k, s) in searched(found) {
        let (result, value, low, high) = result(s.allowable, min);
        let _ = writeln!(
            t,
            "{},{},{},{},{result},{},{},{},{}",
            k as f64 * SECTOR_DEG,
            (k + 1) as f64 * SECTOR_DEG,
            s.used,
            s.rounds.len(),
            cell(value),
            cell(low),
            cell(high),
            stopped(s.stop)
        );
    }
    t
}
