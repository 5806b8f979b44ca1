//! The report's section on a sweep on regolith: how deep the footpads' footprints are and
//! how much energy the soil kept (the sweep's `leg{k}_sinkage_m` and
//! `leg{k}_soil_absorbed_j`, `output::sweep::REGOLITH_COLUMNS`).

use super::numbers::{Named, Summary, summaries, write_summaries};
use crate::output::sweep::SweepBatch;
use arrow_array::Float64Array;

/// The regolith columns of a batch of a sweep on regolith: each leg's footprint depth and
/// the energy the soil kept under it.
pub(super) struct GroundColumns<'a> {
    sinkage_m: Vec<&'a Float64Array>,
    soil_absorbed_j: Vec<&'a Float64Array>,
}

impl<'a> GroundColumns<'a> {
    /// The columns of `b` (`legs` legs), or `None` in a sweep not on regolith.
    pub(super) fn of(
        b: &'a SweepBatch<'_>,
        legs: usize,
    ) -> anyhow::Result<Option<GroundColumns<'a>>> {
        if !b.has("leg0_sinkage_m") {
            return Ok(None);
        }
        Ok(Some(GroundColumns {
            sinkage_m: b.per_leg(legs, "sinkage_m")?,
            soil_absorbed_j: b.per_leg(legs, "soil_absorbed_j")?,
        }))
    }
}

/// The quantities of the section, in the order of `Ground::values`.
const QUANTITIES: [Named; 2] = [
    (
        "sinkage_mm",
        "footprint depth once unloaded (deepest leg)",
        "mm",
    ),
    ("soil_absorbed_j", "energy the soil kept (all legs)", "J"),
];

/// Each sample's deepest footprint (mm) and the energy its soil kept (J), gathered from
/// the rows of a sweep on regolith.
#[derive(Default)]
pub(super) struct Ground {
    values: [Vec<f64>; 2],
}

impl Ground {
    pub(super) fn push(&mut self, c: &GroundColumns<'_>, i: usize) {
        let deepest = c.sinkage_m.iter().map(|s| s.value(i)).fold(0.0, f64::max);
        let kept = c.soil_absorbed_j.iter().map(|e| e.value(i)).sum();
        self.values[0].push(1e3 * deepest);
        self.values[1].push(kept);
    }

    /// The section (`None` for a sweep not on regolith); sorts the values.
    pub(super) fn section(&mut self) -> Option<GroundSection> {
        if self.values[0].is_empty() {
            return None;
        }
        Some(GroundSection {
            quantities: summaries(&mut self.values, &QUANTITIES),
        })
    }
}

/// The soil of a sweep on regolith: footprint depth and the energy the soil kept.
pub(super) struct GroundSection {
    /// The footprint depth of the deepest leg and the energy the soil kept under all legs.
    pub(super) quantities: Vec<Summary>,
}

impl GroundSection {
    /// Its Markdown.
    pub(super) fn write(&self, t: &mut String) {
        t.push_str(
            "\n## Regolith\n\nPer sample, the deepest footprint of its legs once unloaded \
             (`leg{k}_sinkage_m`) and the energy the soil kept under all its legs \
             (`leg{k}_soil_absorbed_j`):\n\n",
        );
        write_summaries(t, &self.quantities);
    }
}
