//! What stays fixed over a sweep: a scenario's control loop, its thrusters as designed and
//! their allocation, and a sample's drawn descent.

use super::allocation::Allocation;
use super::laws::{DescentDraw, NamedLaw, registered};
use crate::scenario::{Control, G0_M_S2, Sample, Scenario, Thruster};

/// What stays fixed over a sweep: the control loop of the scenario, the thrusters as
/// designed, and what the step-size bound needs.
#[derive(Debug, Clone)]
pub struct ControlModel {
    /// The scenario's `[control]` table: rate, latency, sensors, built-in laws.
    pub(super) config: Control,
    /// The user's law the scenario names (`[control] law`), if any.
    pub law: Option<NamedLaw>,
    /// The thrusters as designed (nominal position, direction and thrust, in B).
    pub thrusters: Vec<Thruster>,
    /// How a commanded wrench is shared among `thrusters`, from their nominal columns.
    pub allocation: Allocation,
    /// Control period `P = 1 / rate_hz`, s.
    pub period_s: f64,
    /// `isp g0`, m/s: propellant used is the thrust's integral over it.
    pub exhaust_speed_m_s: f64,
    /// Standard deviation of each thruster's relative thrust error (drawn per sample,
    /// truncated at 3 sd).
    pub(super) thrust_error_sd: f64,
    /// Standard deviation of each thruster's misalignment about either axis across its
    /// direction (drawn per sample, truncated at 3 sd).
    pub(super) misalignment_sd_rad: f64,
    /// Lander mass, for the descent law's force and the thrust's approach bound.
    pub(super) mass_kg: f64,
    /// Gravity `g0`, which the descent law cancels.
    pub(super) gravity_m_s2: f64,
    /// Depth of the lowest footpad below the CG along `-Z_B`, m: the descent law takes the
    /// footpads' height as the altimeter's CG altitude less this.
    pub footpad_depth_m: f64,
    /// Smallest principal moment of inertia: with `leg_reach_m` and `flight_step_max_s`,
    /// the fastest a thrust's moment can turn a footpad toward the surface within a
    /// longest flight step (`Thrust::approach_m_s`).
    pub(super) inertia_min_kg_m2: f64,
    /// Largest distance of a footpad from the CG.
    pub(super) leg_reach_m: f64,
    /// Longest step in free flight.
    pub(super) flight_step_max_s: f64,
    /// The outcome's rest speed: `hold_down` with `until_rest` stops once sensed below it
    /// (and below `rest_rate_rad_s`) for `hold_time_s`.
    pub(super) rest_speed_m_s: f64,
    /// The outcome's rest body rate.
    pub(super) rest_rate_rad_s: f64,
    /// The outcome's hold time.
    pub(super) hold_time_s: f64,
}

impl ControlModel {
    /// The control loop of a validated scenario, if it has one.
    #[must_use]
    pub fn of(s: &Scenario, leg_reach_m: f64, footpad_depth_m: f64) -> Option<ControlModel> {
        let config = s.control.clone()?;
        Some(ControlModel {
            law: config.law.as_deref().and_then(registered),
            period_s: 1.0 / config.rate_hz,
            config,
            thrusters: s.thrusters.clone(),
            allocation: Allocation::new(&s.thrusters),
            exhaust_speed_m_s: s.propulsion.isp_s * G0_M_S2,
            thrust_error_sd: s.propulsion.thrust_error_sd,
            misalignment_sd_rad: s.propulsion.misalignment_sd_deg.to_radians(),
            mass_kg: s.lander.mass_kg,
            gravity_m_s2: s.gravity_m_s2,
            footpad_depth_m,
            inertia_min_kg_m2: s
                .lander
                .inertia_kg_m2
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min),
            leg_reach_m,
            flight_step_max_s: s.simulation.flight_step_max_s,
            rest_speed_m_s: s.outcome.rest_speed_m_s,
            rest_rate_rad_s: s.outcome.rest_rate_deg_s.to_radians(),
            hold_time_s: s.outcome.hold_time_s,
        })
    }
}

impl ControlModel {
    /// The descent of `sample`, if the loop has one: its parameters are the sample's
    /// (`Sample::law`, drawn with its other values). The initial state (a descent's start)
    /// and the loop both take it from here.
    #[must_use]
    pub fn descent_draw(&self, sample: &Sample) -> Option<DescentDraw> {
        let d = self.config.descent.as_ref()?;
        let [
            _,
            _,
            _,
            _,
            start_altitude_m,
            start_speed_m_s,
            braking_m_s2,
            gain_per_s,
            release_speed_m_s,
        ] = sample.law;
        Some(DescentDraw {
            start_altitude_m,
            start_speed_m_s,
            braking_m_s2,
            gain_per_s,
            release_speed_m_s,
            null_lateral_velocity: d.null_lateral_velocity,
        })
    }
}
