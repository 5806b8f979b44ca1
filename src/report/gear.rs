//! The report's gear section (issue 30 points 2 and 3): samples whose damper bottomed,
//! with dampers, and with `[limits]` the stable samples within them and the samples that
//! broke each limit.

use super::numbers::Share;
use crate::output::sweep::SweepBatch;
use crate::reference::Outcome;
use crate::scenario::{LIMIT_NAMES, Scenario};
use arrow_array::{StringArray, UInt32Array};
use std::fmt::Write as _;

/// The columns of bottomed dampers and broken limits, where the file has them.
pub(super) struct GearColumns<'a> {
    bottomed: Option<&'a UInt32Array>,
    broken: Option<&'a StringArray>,
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

/// Samples with a bottomed damper, and with `[limits]` the stable samples that broke none
/// and the samples that broke each limit (`LIMIT_NAMES`), counted over the rows.
#[derive(Default)]
pub(super) struct Gear {
    bottomed: u64,
    pub(super) limits: Option<(u64, [u64; LIMIT_NAMES.len()])>,
}

impl Gear {
    pub(super) fn push(&mut self, c: &GearColumns<'_>, i: usize, o: Outcome) {
        self.bottomed += c.bottomed.map_or(0, |b| u64::from(b.value(i) > 0));
        if let Some(broken) = c.broken {
            let (within, each) = self.limits.get_or_insert_default();
            let names = broken.value(i);
            *within += u64::from(o == Outcome::Stable && names.is_empty());
            for (count, (name, _)) in each.iter_mut().zip(LIMIT_NAMES) {
                *count += u64::from(names.split(',').any(|n| n == name));
            }
        }
    }

    /// The section of `total` samples of `scenario`: `None` without dampers and `[limits]`.
    pub(super) fn section(&self, total: u64, scenario: Option<&Scenario>) -> Option<GearSection> {
        let dampers = scenario.is_some_and(|s| s.damper.enabled);
        let limits = scenario.and_then(|s| s.limits);
        if !dampers && limits.is_none() {
            return None;
        }
        let mut broken = Vec::new();
        if let (Some(l), Some((_, each))) = (limits, self.limits) {
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
            for ((limit, count), (name, key)) in given.into_iter().zip(each).zip(LIMIT_NAMES) {
                if let Some((value, text)) = limit {
                    broken.push(Broken {
                        name,
                        key,
                        value,
                        text,
                        samples: Share::of(count, total),
                    });
                }
            }
        }
        Some(GearSection {
            bottomed: dampers.then(|| Share::of(self.bottomed, total)),
            broken,
        })
    }
}

/// A limit of `[limits]` and the samples that broke it.
pub(super) struct Broken {
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

/// The gear section of a sweep with dampers or `[limits]`.
pub(super) struct GearSection {
    /// With dampers: the samples in which a damper bottomed.
    pub(super) bottomed: Option<Share>,
    /// The limits given, each with the samples that broke it.
    pub(super) broken: Vec<Broken>,
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
            b.samples.row(t, &format!("broke `{}`: {}", b.name, b.text));
        }
    }
}
