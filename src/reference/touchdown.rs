//! The state in which a lander met the surface (MODEL.md section 9): at the start of the
//! first step in which a footpad touches, its velocity in the surface's frame, its tilt and
//! rates, and the leg that touched first. The reference and the kernels record the same raw
//! state (`Met`) and derive the columns with the same function (`Touchdown::of`).

use glam::DVec3;

/// What the tracking records at the first contact: the state at the start of its step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Met {
    /// CG velocity in I, m/s.
    pub velocity_m_s: DVec3,
    /// Body rates in B, rad/s.
    pub rate_rad_s: DVec3,
    /// `X_B` in I.
    pub x_body: DVec3,
    /// `Z_B` in I.
    pub z_body: DVec3,
    /// The leg that touched first: the deepest on that step, by the user's number (the
    /// lowest on a tie; `Model::leg_index`).
    pub first_leg: usize,
}

/// The touchdown state of a sample, in the frame of its surface plane (normal `n`,
/// downhill `u`, `v = n x u`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Touchdown {
    /// Speed towards the surface, `-n . v` (positive approaching), m/s.
    pub normal_speed_m_s: f64,
    /// Speed along the surface, `|v - (n . v) n|`, m/s.
    pub tangential_speed_m_s: f64,
    /// Direction of the velocity along the surface from the downhill direction `u`,
    /// positive towards `v`, in (-180, 180] deg; NaN where the speed along it is 0.
    pub tangential_azimuth_deg: f64,
    /// The same from `X_B` projected on the surface (relative to the legs, whose azimuths
    /// in B the scenario gives); NaN where either is 0.
    pub tangential_azimuth_body_deg: f64,
    /// Tilt of `Z_B` from the normal, deg.
    pub tilt_deg: f64,
    /// Body rates, deg/s.
    pub rate_deg_s: [f64; 3],
    /// The leg that touched first.
    pub first_leg: u32,
}

impl Touchdown {
    /// The touchdown state of `met` on the plane of normal `normal` and downhill
    /// `tangent_u` (`tangent_v = normal x tangent_u`).
    #[must_use]
    pub fn of(met: &Met, normal: DVec3, tangent_u: DVec3, tangent_v: DVec3) -> Touchdown {
        let v = met.velocity_m_s;
        let along = v - normal * normal.dot(v);
        let speed = along.length();
        let azimuth = |x: f64, y: f64| {
            if speed > 0.0 && (x != 0.0 || y != 0.0) {
                libm::atan2(y, x).to_degrees()
            } else {
                f64::NAN
            }
        };
        // X_B on the plane, and the plane's axis a quarter turn from it (same length).
        let x_on = met.x_body - normal * normal.dot(met.x_body);
        let y_on = normal.cross(x_on);
        Touchdown {
            normal_speed_m_s: -normal.dot(v),
            tangential_speed_m_s: speed,
            tangential_azimuth_deg: azimuth(along.dot(tangent_u), along.dot(tangent_v)),
            tangential_azimuth_body_deg: azimuth(along.dot(x_on), along.dot(y_on)),
            tilt_deg: libm::acos(met.z_body.dot(normal).clamp(-1.0, 1.0)).to_degrees(),
            rate_deg_s: (met.rate_rad_s * (1.0f64).to_degrees()).to_array(),
            first_leg: met.first_leg as u32,
        }
    }
}
