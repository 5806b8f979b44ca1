//! The `[outcome]` table: the thresholds of the outcome classification.

use super::reader::table;

table! {
    /// Thresholds of the outcome classification (MODEL.md section 8).
    #[derive(Debug, Clone, PartialEq)]
    pub struct Outcome;
    fn read_outcome(r) with key {
        /// CG speed below which the lander may count as at rest.
        rest_speed_m_s: f64 = r.positive(key)?,
        /// Body rate below which the lander may count as at rest.
        rest_rate_deg_s: f64 = r.positive(key)?,
        /// How long the lander must stay at rest, upright and statically stable to be
        /// `stable`.
        hold_time_s: f64 = r.positive(key)?,
        /// Height the lowest footpad must reach after a lift-off for it to count as a bounce.
        bounce_clearance_m: f64 = r.non_negative(key)?,
        /// CG speed beyond which the sample has `diverged`.
        diverged_speed_m_s: f64 = r.positive(key)?,
        /// Body rate beyond which the sample has `diverged`.
        diverged_rate_deg_s: f64 = r.positive(key)?,
        /// Penetration of a footpad beyond which the sample has `diverged`.
        diverged_penetration_m: f64 = r.positive(key)?,
        /// Decide `tipped` at the point of no return (MODEL.md section 8) instead of only
        /// when the tilt passes 90 deg.
        early_tipping: bool = r.bool(key)?,
        /// Decide `sliding` once the lander slides steadily down a plane steeper than the
        /// friction angle (MODEL.md section 8) instead of running on to t_max.
        early_sliding: bool = r.bool(key)?,
        /// Decide `bouncing` once the lander flies clear and can neither come back to the
        /// surface nor turn past 90 deg before t_max.
        early_bouncing: bool = r.bool(key)?,
    }
}
