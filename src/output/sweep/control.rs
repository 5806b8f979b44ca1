//! The columns of a sweep with a control loop: what the loop did, its sampled law
//! parameters, and with a descent the state it released the lander in.

/// The columns of what a control loop did, and of its sampled law parameters: name, unit,
/// description, and the law a parameter belongs to (empty: every control loop).
pub const CONTROL_COLUMNS: [(&str, &str, &str, &str); 26] = [
    (
        "propellant_kg",
        "kg",
        "propellant used: thrust integral over Isp g0",
        "",
    ),
    (
        "thrust_on_time_s",
        "s",
        "sum of every thruster's time on",
        "",
    ),
    (
        "firings",
        "1",
        "thruster firings (a thruster on in a control period counts once)",
        "",
    ),
    (
        "hold_down_impulse_n_s",
        "N s",
        "thrust integral of the hold-down firings: the built-in hold_down's, and a user's \
         law's commands that ask for a force along -Z_B once contact has been sensed",
        "",
    ),
    (
        "hold_down_thrust_n",
        "N",
        "sampled law parameter: hold-down thrust",
        "hold_down",
    ),
    (
        "hold_down_duration_s",
        "s",
        "sampled law parameter: hold-down duration",
        "hold_down",
    ),
    (
        "attitude_kp_n_m_per_rad",
        "N m/rad",
        "sampled law parameter: attitude hold proportional gain",
        "attitude_hold",
    ),
    (
        "attitude_kd_n_m_s_per_rad",
        "N m s/rad",
        "sampled law parameter: attitude hold rate gain",
        "attitude_hold",
    ),
    (
        "descent_start_altitude_m",
        "m",
        "sampled law parameter: height of the lowest footpad at the descent's start",
        "descent",
    ),
    (
        "descent_start_speed_m_s",
        "m/s",
        "sampled law parameter: descent speed at the start, down Z_I",
        "descent",
    ),
    (
        "descent_braking_m_s2",
        "m/s^2",
        "sampled law parameter: braking of the descent's profile",
        "descent",
    ),
    (
        "descent_gain_per_s",
        "1/s",
        "sampled law parameter: the descent's approach-rate gain",
        "descent",
    ),
    (
        "descent_release_speed_m_s",
        "m/s",
        "sampled law parameter: approach rate below which the descent releases",
        "descent",
    ),
    (
        "release_time_s",
        "s",
        "when the descent law released the lander (NaN: contact came first)",
        "descent",
    ),
    (
        "release_altitude_m",
        "m",
        "true height of the footpads at release: CG altitude above the surface plane less \
         the footpads' depth below the CG",
        "descent",
    ),
    (
        "release_vx_m_s",
        "m/s",
        "true CG velocity at release, X_I (the residual velocity of the descent)",
        "descent",
    ),
    (
        "release_vy_m_s",
        "m/s",
        "true CG velocity at release, Y_I",
        "descent",
    ),
    (
        "release_vz_m_s",
        "m/s",
        "true CG velocity at release, Z_I",
        "descent",
    ),
    (
        "release_normal_speed_m_s",
        "m/s",
        "the touchdown state's columns at the release (NaN: contact came first): speed \
         towards the surface plane, -n . v",
        "descent",
    ),
    (
        "release_tangential_speed_m_s",
        "m/s",
        "speed along the surface plane at the release",
        "descent",
    ),
    (
        "release_tangential_azimuth_deg",
        "deg",
        "direction of the velocity along the surface at the release, from downhill, \
         positive towards n x downhill (NaN where that speed is 0)",
        "descent",
    ),
    (
        "release_tangential_azimuth_body_deg",
        "deg",
        "the same from X_B projected on the surface (relative to the legs)",
        "descent",
    ),
    (
        "release_tilt_deg",
        "deg",
        "tilt of Z_B from the surface normal at the release",
        "descent",
    ),
    (
        "release_rate_x_deg_s",
        "deg/s",
        "body rate about X_B at the release",
        "descent",
    ),
    (
        "release_rate_y_deg_s",
        "deg/s",
        "body rate about Y_B at the release",
        "descent",
    ),
    (
        "release_rate_z_deg_s",
        "deg/s",
        "body rate about Z_B at the release",
        "descent",
    ),
];

/// The names of the `CONTROL_COLUMNS` a sweep of `scenario` writes.
#[must_use]
pub fn control_columns(scenario: &crate::scenario::Scenario) -> Vec<&'static str> {
    let Some(c) = &scenario.control else {
        return Vec::new();
    };
    CONTROL_COLUMNS
        .iter()
        .filter(|(_, _, _, law)| match *law {
            "hold_down" => c.hold_down.is_some(),
            "attitude_hold" => c.attitude_hold.is_some(),
            "descent" => c.descent.is_some(),
            _ => true,
        })
        .map(|c| c.0)
        .collect()
}
