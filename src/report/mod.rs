//! `touchdown report`: what a sweep says, for people (Markdown) and for programs (JSON).
//! Outcome counts with 95 % confidence intervals, the allowable slope per sector of
//! downhill azimuth relative to the lander, the peak loads and their exceedance, (with
//! thrusters) the propellant and firings, and (with a descent) the state the descent
//! released the lander in; with dampers or `[limits]`, the samples that bottomed a damper
//! or broke a limit (`gear`); on regolith, the footprints' depth and the energy the soil
//! kept (`ground`); with a `--slope-distribution`, the outcome shares on that
//! terrain.
//!
//! The folder: `gather` reads the rows once (the sections' own columns and counts in
//! `gear`, `thrust` and `release`), `data` computes every number of the report from them
//! (`numbers`: shares and summaries), and `markdown` and `json` write the same data.

mod data;
mod gather;
mod gear;
mod ground;
mod json;
mod markdown;
mod numbers;
mod release;
mod thrust;

pub use gear::{LimitCounts, limit_rows};

use crate::output::sweep::SweepSource;
use crate::weighting::SlopeDistribution;

/// The report of the sweep `source` (a file, or held in memory), as Markdown.
/// With `terrain` (a `--slope-distribution` and its text), the outcome shares on that
/// terrain follow the sweep's own (`weighting`).
pub fn report(
    source: &SweepSource,
    terrain: Option<(&SlopeDistribution, &str)>,
) -> anyhow::Result<String> {
    Ok(markdown::markdown(&data::Report::of(source, terrain)?))
}

/// The report of the sweep `source` as one JSON document: the numbers of `report`,
/// unrounded, under snake_case keys (`["outcomes"]["stable"]["share"]`,
/// `["allowable_slope"][k]["slope_deg"]`, `["exceedance"]["quantities"]
/// ["peak_axial_force_n"]["overall"]["p99"]["value"]`).
pub fn report_json(
    source: &SweepSource,
    terrain: Option<(&SlopeDistribution, &str)>,
) -> anyhow::Result<String> {
    Ok(json::json(&data::Report::of(source, terrain)?))
}
