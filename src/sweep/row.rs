//! What a run hands on: one finished sample per row, and how busy the lanes were.

use crate::reference::outcome::Summary;
use crate::scenario::Sample;

/// One finished sample: its inputs and its results.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The sample's drawn inputs.
    pub sample: Sample,
    /// Its results (outcome, peaks, time steps).
    pub summary: Summary,
}

/// Lane bookkeeping of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LaneStats {
    /// Lane-steps that advanced a sample.
    pub busy_lane_steps: u64,
    /// All lane-steps, busy or idle.
    pub lane_steps: u64,
}

impl LaneStats {
    /// Busy lane-steps over all lane-steps.
    #[must_use]
    pub fn occupancy(&self) -> f64 {
        self.busy_lane_steps as f64 / self.lane_steps.max(1) as f64
    }

    pub(super) fn add(self, o: LaneStats) -> LaneStats {
        LaneStats {
            busy_lane_steps: self.busy_lane_steps + o.busy_lane_steps,
            lane_steps: self.lane_steps + o.lane_steps,
        }
    }
}
