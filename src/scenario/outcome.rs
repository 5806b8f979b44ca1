//! The `[outcome]` table: the thresholds of the outcome classification.

use super::error::ScenarioError;
use super::reader::Reader;

/// Thresholds of the outcome classification (MODEL.md section 8).
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// CG speed below which the lander may count as at rest.
    pub rest_speed_m_s: f64,
    /// Body rate below which the lander may count as at rest.
    pub rest_rate_deg_s: f64,
    /// How long the lander must stay at rest, upright and statically stable to be `stable`.
    pub hold_time_s: f64,
    /// Height the lowest footpad must reach after a lift-off for it to count as a bounce.
    pub bounce_clearance_m: f64,
    pub diverged_speed_m_s: f64,
    pub diverged_rate_deg_s: f64,
    pub diverged_penetration_m: f64,
    /// Decide `tipped` at the point of no return (MODEL.md section 8) instead of only when
    /// the tilt passes 90 deg.
    pub early_tipping: bool,
    /// Decide `sliding` once the lander slides steadily down a plane steeper than the
    /// friction angle (MODEL.md section 8) instead of running on to t_max.
    pub early_sliding: bool,
    /// Decide `bouncing` once the lander flies clear and can neither come back to the
    /// surface nor turn past 90 deg before t_max.
    pub early_bouncing: bool,
}

pub(super) fn read_outcome(top: &mut Reader, d: &Outcome) -> Result<Outcome, ScenarioError> {
    let Some(mut r) = top.table("outcome")? else {
        return Ok(d.clone());
    };
    let o = Outcome {
        rest_speed_m_s: r.positive("rest_speed_m_s", d.rest_speed_m_s)?,
        rest_rate_deg_s: r.positive("rest_rate_deg_s", d.rest_rate_deg_s)?,
        hold_time_s: r.positive("hold_time_s", d.hold_time_s)?,
        bounce_clearance_m: r.non_negative("bounce_clearance_m", d.bounce_clearance_m)?,
        diverged_speed_m_s: r.positive("diverged_speed_m_s", d.diverged_speed_m_s)?,
        diverged_rate_deg_s: r.positive("diverged_rate_deg_s", d.diverged_rate_deg_s)?,
        diverged_penetration_m: r.positive("diverged_penetration_m", d.diverged_penetration_m)?,
        early_tipping: r.bool("early_tipping", d.early_tipping)?,
        early_sliding: r.bool("early_sliding", d.early_sliding)?,
        early_bouncing: r.bool("early_bouncing", d.early_bouncing)?,
    };
    r.finish()?;
    Ok(o)
}
