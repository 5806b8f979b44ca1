//! The report's section on a sweep with a descent: how many landers the descent law
//! released, and their release time, footpad height and velocity.

use super::numbers::{Named, Summary, summaries, write_summaries};
use crate::output::sweep::SweepBatch;
use arrow_array::Float64Array;
use std::fmt::Write as _;

/// The release columns of a batch of a sweep with a descent.
pub(super) struct ReleaseColumns<'a> {
    time_s: &'a Float64Array,
    altitude_m: &'a Float64Array,
    velocity_m_s: [&'a Float64Array; 3],
}

impl<'a> ReleaseColumns<'a> {
    /// The columns of `b`, or `None` in a sweep without a descent (no `release_time_s`).
    pub(super) fn of(b: &'a SweepBatch<'_>) -> anyhow::Result<Option<ReleaseColumns<'a>>> {
        if !b.has("release_time_s") {
            return Ok(None);
        }
        Ok(Some(ReleaseColumns {
            time_s: b.f64s("release_time_s")?,
            altitude_m: b.f64s("release_altitude_m")?,
            velocity_m_s: [
                b.f64s("release_vx_m_s")?,
                b.f64s("release_vy_m_s")?,
                b.f64s("release_vz_m_s")?,
            ],
        }))
    }
}

/// The quantities of the section, in the order of `Release::values`.
const QUANTITIES: [Named; 4] = [
    ("release_time_s", "release time", "s"),
    ("release_altitude_m", "footpad height at release", "m"),
    ("release_vz_m_s", "vertical velocity at release, up", "m/s"),
    (
        "release_horizontal_speed_m_s",
        "horizontal speed at release",
        "m/s",
    ),
];

/// The state a descent released its landers in, gathered from the rows of a sweep with
/// one: time, footpad height, and the velocity down and along the ground.
#[derive(Default)]
pub(super) struct Release {
    /// Samples of a sweep with a descent.
    samples: u64,
    /// Of the released samples: release time (s), footpad height (m), vertical velocity
    /// (m/s, up positive), horizontal speed (m/s).
    values: [Vec<f64>; 4],
}

impl Release {
    pub(super) fn push(&mut self, c: &ReleaseColumns<'_>, i: usize) {
        self.samples += 1;
        let time = c.time_s.value(i);
        // NaN: contact came before the release.
        if time.is_nan() {
            return;
        }
        let [vx, vy, vz] = c.velocity_m_s.map(|v| v.value(i));
        for (v, x) in self
            .values
            .iter_mut()
            .zip([time, c.altitude_m.value(i), vz, vx.hypot(vy)])
        {
            v.push(x);
        }
    }

    /// The section (`None` for a sweep without a descent); sorts the values.
    pub(super) fn section(&mut self) -> Option<ReleaseSection> {
        if self.samples == 0 {
            return None;
        }
        let released = self.values[0].len() as u64;
        let quantities = if released == 0 {
            Vec::new()
        } else {
            summaries(&mut self.values, &QUANTITIES)
        };
        Some(ReleaseSection {
            samples: self.samples,
            released,
            quantities,
        })
    }
}

/// The release of the landers of a sweep with a descent.
pub(super) struct ReleaseSection {
    /// The samples.
    pub(super) samples: u64,
    /// The samples the descent law released (in the others contact came first).
    pub(super) released: u64,
    /// Of the released: release time, footpad height, vertical velocity (up) and
    /// horizontal speed; none when none was released.
    pub(super) quantities: Vec<Summary>,
}

impl ReleaseSection {
    /// Its Markdown.
    pub(super) fn write(&self, t: &mut String) {
        let first = self.samples - self.released;
        let _ = write!(
            t,
            "\n## Release of the descent\n\n{} of {} samples released by the descent law",
            self.released, self.samples
        );
        if first > 0 {
            let _ = write!(
                t,
                "; in the other {first} contact came first (`release_time_s` NaN)"
            );
        }
        t.push_str(". Of the released (the `release_*` columns; velocity in I):\n\n");
        write_summaries(t, &self.quantities);
    }
}
