//! The report's section on a sweep with a control loop: the propellant, thruster on-time,
//! firings and hold-down impulse over the samples, and the mean propellant per outcome.

use super::numbers::{Named, Summary, summaries};
use crate::output::sweep::SweepBatch;
use crate::reference::Outcome;
use arrow_array::{Float64Array, UInt32Array};
use std::fmt::Write as _;

/// The columns of what the thrusters did, in a batch of a sweep with a control loop.
pub(super) struct ThrustColumns<'a> {
    propellant_kg: &'a Float64Array,
    on_time_s: &'a Float64Array,
    firings: &'a UInt32Array,
    hold_down_impulse_n_s: &'a Float64Array,
}

impl<'a> ThrustColumns<'a> {
    /// The columns of `b`, or `None` in a sweep without a control loop (no `propellant_kg`).
    pub(super) fn of(b: &'a SweepBatch<'_>) -> anyhow::Result<Option<ThrustColumns<'a>>> {
        if !b.has("propellant_kg") {
            return Ok(None);
        }
        let firings = b.u32s("firings")?;
        Ok(Some(ThrustColumns {
            propellant_kg: b.f64s("propellant_kg")?,
            on_time_s: b.f64s("thrust_on_time_s")?,
            firings,
            hold_down_impulse_n_s: b.f64s("hold_down_impulse_n_s")?,
        }))
    }
}

/// The quantities of the section, in the order of `Thrust::values`.
const QUANTITIES: [Named; 4] = [
    ("propellant_kg", "propellant used", "kg"),
    ("thrust_on_time_s", "thruster on-time, all thrusters", "s"),
    ("firings", "firings", "1"),
    ("hold_down_impulse_n_s", "hold-down impulse", "N s"),
];

/// Propellant and firings over a sweep with a control loop, gathered from its rows.
#[derive(Default)]
pub(super) struct Thrust {
    /// Propellant (kg), thruster on-time (s), firings, hold-down impulse (N s), per sample.
    values: [Vec<f64>; 4],
    /// Propellant (kg) summed per outcome, and the samples of each.
    by_outcome: [(f64, u64); Outcome::ALL.len()],
}

impl Thrust {
    pub(super) fn push(&mut self, c: &ThrustColumns<'_>, i: usize, o: Outcome) {
        let propellant = c.propellant_kg.value(i);
        for (v, x) in self.values.iter_mut().zip([
            propellant,
            c.on_time_s.value(i),
            f64::from(c.firings.value(i)),
            c.hold_down_impulse_n_s.value(i),
        ]) {
            v.push(x);
        }
        self.by_outcome[o as usize].0 += propellant;
        self.by_outcome[o as usize].1 += 1;
    }

    /// Whether the sweep has a control loop (its rows carry propellant).
    pub(super) fn controlled(&self) -> bool {
        !self.values[0].is_empty()
    }

    /// The section (`None` for a sweep without a control loop); sorts the values.
    pub(super) fn section(&mut self) -> Option<ThrustSection> {
        if !self.controlled() {
            return None;
        }
        Some(ThrustSection {
            samples: self.values[0].len(),
            fired: self.values[2].iter().filter(|&&f| f > 0.0).count(),
            propellant_kg: self.values[0].iter().sum(),
            quantities: summaries(&mut self.values, &QUANTITIES),
            by_outcome: Outcome::ALL
                .iter()
                .zip(&self.by_outcome)
                .filter(|(_, (_, k))| *k > 0)
                .map(|(&o, &(kg, k))| (o, k, kg / k as f64))
                .collect(),
        })
    }
}

/// What the thrusters of a sweep with a control loop did.
pub(super) struct ThrustSection {
    /// The samples.
    pub(super) samples: usize,
    /// The samples that fired a thruster.
    pub(super) fired: usize,
    /// The propellant over all samples, kg.
    pub(super) propellant_kg: f64,
    /// Propellant, on-time, firings and hold-down impulse over the samples.
    pub(super) quantities: Vec<Summary>,
    /// Per outcome that some sample ended in: the samples and their mean propellant, kg.
    pub(super) by_outcome: Vec<(Outcome, u64, f64)>,
}

impl ThrustSection {
    /// Its Markdown.
    pub(super) fn write(&self, t: &mut String) {
        let _ = writeln!(
            t,
            "\n## Propellant and firings\n\n{} of {} samples fired a thruster; {:.4} kg \
             of propellant over all samples.\n\n\
             | quantity | mean | median | 99th percentile | largest |\n|---|---:|---:|---:|---:|",
            self.fired, self.samples, self.propellant_kg
        );
        for q in &self.quantities {
            let _ = writeln!(
                t,
                "| {} ({}) | {:.4} | {:.4} | {:.4} | {:.4} |",
                q.name, q.unit, q.mean, q.median, q.p99, q.max
            );
        }
        let _ = writeln!(
            t,
            "\n| outcome | samples | mean propellant (kg) |\n|---|---:|---:|"
        );
        for (o, k, kg) in &self.by_outcome {
            let _ = writeln!(t, "| {} | {k} | {kg:.4} |", o.name());
        }
    }
}
