//! What the control loop reads: a lander's true state at a control event, and what its
//! sensors report of it.

use glam::{DQuat, DVec3};

/// The true state of a lander at a control event, which the sensors read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Truth {
    /// Time since the start of the sample, s.
    pub t_s: f64,
    /// CG position in I, m.
    pub position_m: DVec3,
    /// CG velocity in I, m/s.
    pub velocity_m_s: DVec3,
    /// Attitude, B to I.
    pub attitude: DQuat,
    /// Body rates in B, rad/s.
    pub rate_rad_s: DVec3,
    /// Whether a footpad touched the surface in some step since the loop's last event (the
    /// touchdown switches close on it; the loop latches them).
    pub contact: bool,
    /// Whether a footpad touches the surface in the last step.
    pub touching: bool,
    /// The surface normal.
    pub normal: DVec3,
}

/// What the sensors report at a control instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensed {
    /// Time of the control instant, s: `k` periods at the `k`-th instant (the flight
    /// computer's clock).
    pub t_s: f64,
    /// Attitude, B to I.
    pub attitude: DQuat,
    /// Body rates in B, rad/s.
    pub rate_rad_s: DVec3,
    /// CG velocity in I, m/s.
    pub velocity_m_s: DVec3,
    /// CG height above the surface plane along its normal, m.
    pub altitude_m: f64,
    /// A touchdown switch closed since the last control instant: a switch latches at the
    /// first step its footpad touches and stays closed until the loop has read it, so a
    /// contact shorter than a period is not missed.
    pub contact: bool,
    /// A footpad touches the surface now (in the last step): the switches' latest state.
    pub touching: bool,
}
