//! What a sample did to its struts (MODEL.md section 9): the peaks of each leg's axial and
//! side load with the time of each, the damper's stroke margin at the end and whether it
//! bottomed. The kernels track the same peaks (`LegLanes::peak_axial_n`, ...);
//! `Summary::judge` finishes the summaries of both, with the limits (`[limits]`) broken.

use super::step::LegReport;

/// A damper whose stroke comes within this fraction of the usable stroke has bottomed. The
/// crush of a step stops at the end of its piece of the force curve (`honeycomb::crush`):
/// the last increment, `usable - s` added to `s`, lands on the usable stroke to a rounding
/// (exactly where `s` is at least half of it), and f32 lanes round the stroke to 6e-8 of
/// it; a millionth (50 nm of a 5 cm cartridge) covers both and is far below any stroke
/// that matters.
pub const BOTTOMED_WITHIN: f64 = 1e-6;

/// The peaks of one leg's strut loads so far, and the start of the step of each (its first
/// step, on a tie; NaN until the leg bears a load above 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrutPeaks {
    /// Peak axial load, N.
    pub axial_n: f64,
    /// Start of its step, s.
    pub axial_s: f64,
    /// Peak side load, N.
    pub side_n: f64,
    /// Start of its step, s.
    pub side_s: f64,
}

impl StrutPeaks {
    /// No load yet.
    pub const NONE: StrutPeaks = StrutPeaks {
        axial_n: 0.0,
        axial_s: f64::NAN,
        side_n: 0.0,
        side_s: f64::NAN,
    };

    /// Takes in the step starting at `t_s` (a NaN load is never above a peak).
    pub fn observe(&mut self, leg: &LegReport, t_s: f64) {
        if leg.axial_force_n > self.axial_n {
            (self.axial_n, self.axial_s) = (leg.axial_force_n, t_s);
        }
        if leg.side_force_n > self.side_n {
            (self.side_n, self.side_s) = (leg.side_force_n, t_s);
        }
    }
}

/// The stroke margin left of `usable_m` at stroke `stroke_m`, and whether the damper
/// bottomed (then the margin is 0: see `BOTTOMED_WITHIN`).
#[must_use]
pub fn stroke_margin(usable_m: f64, stroke_m: f64) -> (f64, bool) {
    let margin = usable_m - stroke_m;
    if margin <= BOTTOMED_WITHIN * usable_m {
        (0.0, true)
    } else {
        (margin, false)
    }
}
