//! The report's gear section (issue 30 points 2 and 3): samples whose damper bottomed,
//! with dampers, and with `[limits]` the stable samples within them and the samples that
//! broke each limit.

use super::numbers::Share;
use crate::output::read::Texts;
use crate::output::sweep::SweepBatch;
use crate::reference::Outcome;
use crate::scenario::{Broken, LIMIT_NAMES, Limits, Scenario};
use arrow_array::UInt32Array;
use std::fmt::Write as _;

/// The columns of bottomed dampers and broken limits, where the file has them.
pub(super) struct GearColumns<'a> {
    bottomed: Option<&'a UInt32Array>,
    broken: Option<Texts<'a>>,
}

impl<'a> GearColumns<'a> {
    pub(super) fn of(b: &'a SweepBatch<'_>) -> anyhow::Result<GearColumns<'a>> {
        let limits = crate::output::sweep::LIMITS_COLUMN;
        Ok(GearColumns {
            bottomed: b
                .has("legs_bottomed")
                .then(|| b.u32s("legs_bottomed"))
                .transpose()?,
            broken: b.has(limits).then(|| b.strs(limits)).transpose()?,
        })
    }
}

/// The stable samples within `[limits]` and the samples that broke each limit
/// (`LIMIT_NAMES`), counted: the report's and the sweep's closing summary's alike.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct LimitCounts {
    /// Stable samples that broke no limit.
    pub within: u64,
    /// Samples that broke each limit, in the order of `LIMIT_NAMES`.
    pub each: [u64; LIMIT_NAMES.len()],
}

impl LimitCounts {
    /// Counts `n` samples of outcome `o` that broke the limits `broken`.
    pub fn add(&mut self, o: Outcome, broken: Broken, n: u64) {
        self.within += n * u64::from(o == Outcome::Stable && broken == Broken::default());
        for (i, count) in self.each.iter_mut().enumerate() {
            *count += n * u64::from(broken.has(i));
        }
    }

    /// Adds the counts of `o`.
    pub fn merge(&mut self, o: &LimitCounts) {
        self.within += o.within;
        for (c, k) in self.each.iter_mut().zip(o.each) {
            *c += k;
        }
    }
}

/// Samples with a bottomed damper, and with `[limits]` the stable samples that broke none
/// and the samples that broke each limit, counted over the rows.
#[derive(Default)]
pub(super) struct Gear {
    bottomed: u64,
    pub(super) limits: Option<LimitCounts>,
}

impl Gear {
    pub(super) fn push(&mut self, c: &GearColumns<'_>, i: usize, o: Outcome) {
        self.bottomed += c.bottomed.map_or(0, |b| u64::from(b.value(i) > 0));
        if let Some(broken) = &c.broken {
            let counts = self.limits.get_or_insert_default();
            counts.add(o, Broken::parse(broken.get(i).unwrap_or("")), 1);
        }
    }

    /// The section of `total` samples of `scenario`: `None` without dampers and `[limits]`.
    pub(super) fn section(&self, total: u64, scenario: Option<&Scenario>) -> Option<GearSection> {
        let dampers = scenario.is_some_and(|s| s.damper.enabled);
        let limits = scenario.and_then(|s| s.limits);
        if !dampers && limits.is_none() {
            return None;
        }
        let broken = match (limits, self.limits) {
            (Some(l), Some(counts)) => broken_limits(&l, &counts, total),
            _ => Vec::new(),
        };
        Some(GearSection {
            bottomed: dampers.then(|| Share::of(self.bottomed, total)),
            broken,
        })
    }
}

/// The limits `l` gives, each with what breaks it in words and the samples of `total`
/// that broke it (`counts`).
fn broken_limits(l: &Limits, counts: &LimitCounts, total: u64) -> Vec<BrokenLimit> {
    let given = [
        l.axial_force_n
            .map(|x| (x, format!("peak axial strut load above {x} N"))),
        l.side_force_n
            .map(|x| (x, format!("peak side load above {x} N"))),
        l.acceleration_m_s2
            .map(|x| (x, format!("peak CG acceleration above {x} m/s^2"))),
        l.stroke_margin_m
            .map(|x| (x, format!("stroke margin below {x} m, or bottomed"))),
    ];
    given
        .into_iter()
        .zip(counts.each)
        .zip(LIMIT_NAMES)
        .filter_map(|((limit, count), (name, key))| {
            limit.map(|(value, text)| BrokenLimit {
                name,
                key,
                value,
                text,
                samples: Share::of(count, total),
            })
        })
        .collect()
}

/// The rows a sweep's closing summary adds for the limits `l`, as the report words them:
/// "stable within limits" and its samples, then each limit given, "broke `name`: what
/// breaks it", and the samples that broke it (`counts`).
#[must_use]
pub fn limit_rows(l: &Limits, counts: &LimitCounts) -> (u64, Vec<(String, u64)>) {
    // The share is not read here: any total above 0 does.
    let rows = broken_limits(l, counts, 1)
        .into_iter()
        .map(|b| (b.label(), b.samples.count))
        .collect();
    (counts.within, rows)
}

/// A limit of `[limits]` and the samples that broke it.
pub(super) struct BrokenLimit {
    /// Its name in `limits_broken` (`axial_force`).
    pub(super) name: &'static str,
    /// Its key in `[limits]` (`axial_force_n`).
    pub(super) key: &'static str,
    /// Its value there.
    pub(super) value: f64,
    /// What breaks it, in words.
    pub(super) text: String,
    /// The samples that broke it.
    pub(super) samples: Share,
}

impl BrokenLimit {
    /// Its row's label: "broke `name`: what breaks it".
    fn label(&self) -> String {
        format!("broke `{}`: {}", self.name, self.text)
    }
}

/// The gear section of a sweep with dampers or `[limits]`.
pub(super) struct GearSection {
    /// With dampers: the samples in which a damper bottomed.
    pub(super) bottomed: Option<Share>,
    /// The limits given, each with the samples that broke it.
    pub(super) broken: Vec<BrokenLimit>,
}

impl GearSection {
    /// Its Markdown.
    pub(super) fn write(&self, t: &mut String) {
        let _ = writeln!(
            t,
            "\n## Gear\n\n| | samples | share | 95 % interval |\n|---|---:|---:|---:|"
        );
        if let Some(bottomed) = &self.bottomed {
            bottomed.row(t, "a damper bottomed");
        }
        for b in &self.broken {
            b.samples.row(t, &b.label());
        }
    }
}
