//! The lander's shape in B as a sketch: the model's lander is a rigid body with point
//! footpads, so the body (an octagonal prism, the thesis's lander), the struts' length and
//! the footpad discs are proportions of the leg geometry (on regolith and among rocks, the
//! footpads are the model's own).

use crate::reference::Model;
use glam::DVec3;

/// One leg of the sketch, in B.
#[derive(Debug, Clone, Copy)]
pub struct LegSketch {
    /// Top of the strut: `strut_length` above the footpad along the strut axis.
    pub hip: DVec3,
    /// The body's bottom corner that the leg's bracing meets.
    pub mount: DVec3,
    /// Footpad at zero stroke.
    pub tip0: DVec3,
    /// Unit strut axis, hip to footpad.
    pub axis: DVec3,
}

/// A thruster of the sketch, in B.
#[derive(Debug, Clone, Copy)]
pub struct ThrusterSketch {
    /// Where the thruster sits, in B, m.
    pub position: DVec3,
    /// Unit direction of its force on the lander (the plume points the other way).
    pub direction: DVec3,
    /// Its thrust at full throttle, N.
    pub max_thrust_n: f64,
}

/// The lander's shape in B (CG at the origin), m.
#[derive(Debug, Clone)]
pub struct Sketch {
    /// The body's bottom and top octagons, corners in the same order.
    pub bottom: Vec<DVec3>,
    /// The body's top octagon.
    pub top: Vec<DVec3>,
    /// The legs, by the user's number (`Model::leg_index`).
    pub legs: Vec<LegSketch>,
    /// Radius of the footpad discs, m.
    pub footpad_radius_m: f64,
    /// The control loop's thrusters (none without one).
    pub thrusters: Vec<ThrusterSketch>,
}

impl Sketch {
    /// The sketch of a model's lander. The default lander's CG sits 73.42 mm above its
    /// centre plate, 0.4289 m above the footpads (MODEL.md section 3); the body's bottom
    /// plate keeps that proportion of the CG height for any geometry, and the body's width
    /// and height are proportions of the footpad radius.
    pub(super) fn of(model: &Model) -> Sketch {
        let n = model.legs.len().max(1) as f64;
        let radius = model
            .legs
            .iter()
            .map(|l| l.tip_m.x.hypot(l.tip_m.y))
            .sum::<f64>()
            / n;
        let cg_height = model.legs.iter().map(|l| -l.tip_m.z).sum::<f64>() / n;
        let (cg_height, radius) = (cg_height.max(0.05), radius.max(0.1));
        let body_radius = 0.62 * radius;
        let z_bottom = -0.171 * cg_height;
        let z_top = z_bottom + 0.75 * radius;
        let corner = |k: usize, z: f64| {
            let a = std::f64::consts::PI / 8.0 * (2 * k + 1) as f64;
            DVec3::new(body_radius * a.cos(), body_radius * a.sin(), z)
        };
        let bottom: Vec<DVec3> = (0..8).map(|k| corner(k, z_bottom)).collect();
        let top = (0..8).map(|k| corner(k, z_top)).collect();
        let strut_length = 0.55 * cg_height;
        let legs = model
            .leg_index
            .iter()
            .map(|&i| {
                let l = &model.legs[i];
                let hip = l.tip_m - strut_length * l.strut_axis;
                let mount = *bottom
                    .iter()
                    .min_by(|a, b| {
                        a.truncate()
                            .distance(hip.truncate())
                            .total_cmp(&b.truncate().distance(hip.truncate()))
                    })
                    .unwrap_or(&bottom[0]);
                LegSketch {
                    hip,
                    mount,
                    tip0: l.tip_m,
                    axis: l.strut_axis,
                }
            })
            .collect();
        let thrusters = model
            .control
            .as_ref()
            .map(|c| {
                c.thrusters
                    .iter()
                    .map(|t| ThrusterSketch {
                        position: DVec3::from_array(t.position_m),
                        direction: DVec3::from_array(t.direction).normalize_or_zero(),
                        max_thrust_n: t.max_thrust_n,
                    })
                    .collect()
            })
            .unwrap_or_default();
        Sketch {
            bottom,
            top,
            legs,
            footpad_radius_m: if model.soil.is_some() || model.rocks.is_some() {
                // Where the footpad's size is physics (the sole that sinks, the sphere
                // that meets rocks), the footpad drawn is the model's.
                model.pad_radius_m()
            } else {
                0.12 * radius
            },
            thrusters,
        }
    }

    /// The distance from the CG to the farthest point of the sketch, m.
    #[must_use]
    pub fn reach_m(&self) -> f64 {
        self.top
            .iter()
            .chain(&self.bottom)
            .map(|p| p.length())
            .chain(
                self.legs
                    .iter()
                    .map(|l| l.tip0.length() + self.footpad_radius_m),
            )
            .fold(0.0, f64::max)
    }
}
