//! The thrust on a lander between two events of its control loop: what the loop hands the
//! step (the reference's `State::thrust`, the kernels' `ThrustLanes`).

use glam::DVec3;

/// The thrust on the lander from one event of its control loop to the next (MODEL.md
/// section 7; the kernels' `ThrustLanes`, one lane).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thrust {
    /// Sum of the firing thrusters' forces, in B, N.
    pub force_b_n: DVec3,
    /// Their moment about the CG, in B, N m.
    pub moment_b_n_m: DVec3,
    /// Time to the next control event, s (infinite where none comes).
    pub event_in_s: f64,
    /// What the thrust can add, within a longest flight step, to the speed at which a
    /// footpad approaches the surface (`step_size`), m/s.
    pub approach_m_s: f64,
    /// The control loop may still fire: no rest and no early rule counts.
    pub powered: bool,
    /// Sum of the firing thrusters' thrust magnitudes (what burns propellant), N.
    pub flow_n: f64,
}

impl Thrust {
    /// No thrust and no event to come: a passive lander.
    pub const NONE: Thrust = Thrust {
        force_b_n: DVec3::ZERO,
        moment_b_n_m: DVec3::ZERO,
        event_in_s: f64::INFINITY,
        approach_m_s: 0.0,
        powered: false,
        flow_n: 0.0,
    };
}
