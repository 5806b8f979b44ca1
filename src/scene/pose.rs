//! The lander's pose at any time of a trace: between rows interpolated, with the peaks of
//! the forces and thrusts since the previous look.

use super::read::Scene;
use glam::{DQuat, DVec3};

/// The lander at one moment, and what acted on it since the previous one looked at.
#[derive(Debug, Clone)]
pub struct Pose {
    /// The moment, s.
    pub t_s: f64,
    /// The CG in I, m.
    pub cg: DVec3,
    /// Body to I.
    pub attitude: DQuat,
    /// Footpads in I, stroke included.
    pub tips: Vec<DVec3>,
    /// Damper stroke per leg, m.
    pub strokes: Vec<f64>,
    /// Largest normal force per leg over the interval, N.
    pub normal_n: Vec<f64>,
    /// Largest thrust per thruster over the interval, N.
    pub thrust_n: Vec<f64>,
    /// Tilt of Z_B from the slope normal, deg.
    pub tilt_deg: f64,
    /// The control loop's phase, if any.
    pub phase: Option<String>,
}

impl Scene {
    /// The pose at `t`, with the peaks of the forces and thrusts since `since` (a frame
    /// shows an impact or a firing shorter than the time between frames).
    #[must_use]
    pub fn pose(&self, since: f64, t: f64) -> Pose {
        let tr = &self.trace;
        let here = tr.locate(t);
        let from = tr.locate(since.min(t)).0;
        let rows = from..=here.0;
        let v =
            |x: &str, y: &str, z: &str| DVec3::new(tr.at(x, here), tr.at(y, here), tr.at(z, here));
        let cg = v("x_m", "y_m", "z_m");
        // Between rows: the attitude by normalised linear interpolation (rows of a trace
        // written at every step are at most one flight step apart, over which the lander
        // turns little; a trace of every N steps is smoothed over more).
        let q = |i: usize| {
            let c = |n: &str| tr.column(n)[i];
            DQuat::from_xyzw(c("qx"), c("qy"), c("qz"), c("qw"))
        };
        let (i, f) = here;
        let attitude = if i + 1 < tr.time.len() && f > 0.0 {
            let (a, mut b) = (q(i), q(i + 1));
            if a.dot(b) < 0.0 {
                b = -b;
            }
            (a * (1.0 - f) + b * f).normalize()
        } else {
            q(i).normalize()
        };
        let tips = (0..tr.legs)
            .map(|k| {
                v(
                    &format!("leg{k}_tip_x_m"),
                    &format!("leg{k}_tip_y_m"),
                    &format!("leg{k}_tip_z_m"),
                )
            })
            .collect();
        let strokes = (0..tr.legs)
            .map(|k| tr.at(&format!("leg{k}_stroke_m"), here))
            .collect();
        let normal_n = (0..tr.legs)
            .map(|k| tr.peak(&format!("leg{k}_normal_force_n"), rows.clone()))
            .collect();
        let thrust_n = (0..tr.thrusters)
            .map(|j| tr.peak(&format!("thruster{j}_thrust_n"), rows.clone()))
            .collect();
        let z_b = attitude * DVec3::Z;
        let tilt_deg = z_b
            .dot(self.surface.normal)
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees();
        Pose {
            t_s: t,
            cg,
            attitude,
            tips,
            strokes,
            normal_n,
            thrust_n,
            tilt_deg,
            phase: tr.phases().and_then(|p| p.get(i)).cloned(),
        }
    }
}
