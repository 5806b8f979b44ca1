//! The columns of a trace: the body's, 9 per leg, and what a control loop adds (every
//! thruster's thrust and commanded on-time, the thrust on the lander, the loop's phase, and
//! what its sensors read), each with its unit and description.

/// A column: name, unit, description.
pub(super) type Column = (String, &'static str, String);

/// Columns of the body, then 9 columns per leg. With a control loop (`controlled`) the
/// accelerometer's column says that thrust is in it (a passive trace's says what it said
/// before there was thrust).
pub(super) fn columns(legs: usize, controlled: bool) -> Vec<Column> {
    let mut c: Vec<Column> = [
        ("t_s", "s", "time at the start of the step"),
        ("dt_s", "s", "length of the step"),
        ("x_m", "m", "CG position, X_I"),
        ("y_m", "m", "CG position, Y_I"),
        ("z_m", "m", "CG position, Z_I (up)"),
        ("vx_m_s", "m/s", "CG velocity, X_I"),
        ("vy_m_s", "m/s", "CG velocity, Y_I"),
        ("vz_m_s", "m/s", "CG velocity, Z_I"),
        ("ax_m_s2", "m/s^2", "CG acceleration dv/dt, X_I"),
        ("ay_m_s2", "m/s^2", "CG acceleration dv/dt, Y_I"),
        (
            "az_m_s2",
            "m/s^2",
            "CG acceleration dv/dt, Z_I (gravity included)",
        ),
        (
            "accel_z_body_m_s2",
            "m/s^2",
            if controlled {
                "specific force over the mass along Z_B: contact and thrust, not gravity (what \
                 an accelerometer on the body axis reads)"
            } else {
                "contact acceleration along Z_B (what an accelerometer on the body axis reads)"
            },
        ),
        ("qw", "1", "attitude quaternion body to I, scalar part"),
        ("qx", "1", "attitude quaternion, x"),
        ("qy", "1", "attitude quaternion, y"),
        ("qz", "1", "attitude quaternion, z"),
        (
            "roll_deg",
            "deg",
            "Euler roll phi, R_IB = Rz(psi) Ry(theta) Rx(phi)",
        ),
        ("pitch_deg", "deg", "Euler pitch theta"),
        ("yaw_deg", "deg", "Euler yaw psi"),
        ("rate_x_deg_s", "deg/s", "body rate about X_B"),
        ("rate_y_deg_s", "deg/s", "body rate about Y_B"),
        ("rate_z_deg_s", "deg/s", "body rate about Z_B"),
    ]
    .iter()
    .map(|(n, u, d)| (n.to_string(), *u, d.to_string()))
    .collect();
    for k in 0..legs {
        for (n, u, d) in [
            ("tip_x_m", "m", "footpad position, X_I"),
            ("tip_y_m", "m", "footpad position, Y_I"),
            ("tip_z_m", "m", "footpad position, Z_I"),
            (
                "penetration_m",
                "m",
                "depth below the local surface (negative: clearance)",
            ),
            ("normal_force_n", "N", "normal contact force"),
            ("friction_force_n", "N", "friction force magnitude"),
            ("stroke_m", "m", "damper stroke"),
            (
                "axial_force_n",
                "N",
                "axial strut load: the footpad's force along the strut, compressive positive",
            ),
            (
                "side_force_n",
                "N",
                "side load: the footpad's force across the strut",
            ),
        ] {
            c.push((format!("leg{k}_{n}"), u, format!("leg {k}: {d}")));
        }
    }
    c
}

/// The text column of a control loop's phase.
pub const PHASE_COLUMN: &str = "control_phase";

/// What a control loop adds to the columns of a lander with `thrusters` thrusters: numbers
/// that every row has (two per thruster, then the thrust on the lander, the propellant and
/// the true tilt and altitude the sensors read), then, after the text column of the phase
/// (`PHASE_COLUMN`), the sensors' reading at the last control instant (null before the
/// first).
pub(super) fn control_columns(thrusters: usize) -> (Vec<Column>, Vec<Column>) {
    let own = |list: &[(&str, &'static str, &str)]| -> Vec<Column> {
        list.iter()
            .map(|(n, u, d)| (n.to_string(), *u, d.to_string()))
            .collect()
    };
    let mut numbers = Vec::new();
    for j in 0..thrusters {
        for (n, u, d) in [
            (
                "thrust_n",
                "N",
                "thrust during the step (as built: magnitude error included; 0 when off)",
            ),
            (
                "command_on_s",
                "s",
                "on-time commanded for the current control period",
            ),
        ] {
            numbers.push((format!("thruster{j}_{n}"), u, format!("thruster {j}: {d}")));
        }
    }
    numbers.extend(own(&[
        ("thrust_b_x_n", "N", "thrust force on the lander, X_B"),
        ("thrust_b_y_n", "N", "thrust force on the lander, Y_B"),
        ("thrust_b_z_n", "N", "thrust force on the lander, Z_B"),
        (
            "thrust_moment_b_x_n_m",
            "N m",
            "thrust moment about the CG, X_B",
        ),
        (
            "thrust_moment_b_y_n_m",
            "N m",
            "thrust moment about the CG, Y_B",
        ),
        (
            "thrust_moment_b_z_n_m",
            "N m",
            "thrust moment about the CG, Z_B",
        ),
        (
            "thrust_total_n",
            "N",
            "sum of the firing thrusters' thrust magnitudes (what burns propellant)",
        ),
        (
            "propellant_used_kg",
            "kg",
            "propellant used before the start of the step: thrust integral over Isp g0",
        ),
        (
            "altitude_m",
            "m",
            "true CG height above the surface plane along its normal (what the altimeter reads)",
        ),
        ("tilt_deg", "deg", "true angle between Z_B and Z_I (up)"),
    ]));
    let sensed = own(&[
        (
            "sensed_t_s",
            "s",
            "time of the last control instant, whose sensor reading the sensed_ columns hold \
             (null before the first)",
        ),
        (
            "sensed_roll_deg",
            "deg",
            "sensed Euler roll (noise and bias included), as roll_deg",
        ),
        (
            "sensed_pitch_deg",
            "deg",
            "sensed Euler pitch, as pitch_deg",
        ),
        ("sensed_yaw_deg", "deg", "sensed Euler yaw, as yaw_deg"),
        (
            "sensed_tilt_deg",
            "deg",
            "sensed angle between Z_B and Z_I, as tilt_deg",
        ),
        ("sensed_rate_x_deg_s", "deg/s", "sensed body rate about X_B"),
        ("sensed_rate_y_deg_s", "deg/s", "sensed body rate about Y_B"),
        ("sensed_rate_z_deg_s", "deg/s", "sensed body rate about Z_B"),
        ("sensed_vx_m_s", "m/s", "sensed CG velocity, X_I"),
        ("sensed_vy_m_s", "m/s", "sensed CG velocity, Y_I"),
        ("sensed_vz_m_s", "m/s", "sensed CG velocity, Z_I"),
        (
            "sensed_altitude_m",
            "m",
            "sensed CG height above the surface plane, as altitude_m",
        ),
    ]);
    (numbers, sensed)
}
