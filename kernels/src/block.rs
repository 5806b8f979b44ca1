//! The state of `LANES` landers, field per field (structure of arrays), with the surface
//! each lane lands on and what its outcome tracking remembers.

use crate::lane::{LANES, Lane, all_false, splat};
use crate::params::Params;
use crate::vec3::{Mat3, Quat, Vec3};

/// What a leg remembers between steps, per lane.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct LegLanes {
    pub stroke_m: Lane,
    pub absorbed_j: Lane,
    pub anchor_m: Vec3,
    /// Mask: the friction anchor is set (the leg touched in the previous step).
    pub anchored: Lane,
    /// The friction anchor when the current rest began (see `outcome`).
    pub rest_anchor_m: Vec3,
    pub peak_normal_n: Lane,
}

/// One leg during the current step, for the outcome tracking.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct LegStep {
    pub tip_m: Vec3,
    pub tip_velocity_m_s: Vec3,
    pub penetration_m: Lane,
    pub normal_n: Lane,
    /// Mask: the footpad slips (in contact, friction at its cap).
    pub slipping: Lane,
}

/// The surface of each lane.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct SurfaceLanes {
    pub normal: Vec3,
    pub tangent_u: Vec3,
    pub tangent_v: Vec3,
    pub offset_u_m: Lane,
    pub offset_v_m: Lane,
    pub tile: [usize; LANES],
}

/// What the outcome tracking remembers, per lane.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct Track {
    pub start_m: Vec3,
    pub rest_s: Lane,
    pub min_cos_tilt: Lane,
    /// The squared peak contact acceleration (its root, taken once at the end, is the
    /// peak of the roots).
    pub peak_acceleration_squared: Lane,
    pub peak_acceleration_z: Lane,
    pub bounces: Lane,
    /// Mask: touched since the last lift-off.
    pub touched: Lane,
    /// Time of first contact, NaN until then.
    pub first_contact_s: Lane,
    pub max_penetration: Lane,
    pub steps: Lane,
    /// Outcome code once decided (see `outcome`), -1 before.
    pub outcome: Lane,
}

/// `LANES` landers.
#[derive(Debug, Clone)]
#[allow(missing_docs)]
pub struct Block {
    pub t_s: Lane,
    pub position_m: Vec3,
    pub velocity_m_s: Vec3,
    pub attitude: Quat,
    /// The rotation matrix of `attitude`, kept with it (by `step` and `load`) so that
    /// `step_size`, `step` and `observe` do not each rebuild it.
    pub rotation: Mat3,
    pub rate_rad_s: Vec3,
    pub legs: Vec<LegLanes>,
    pub surface: SurfaceLanes,
    pub track: Track,
    /// Mask: the lane holds a sample.
    pub active: Lane,
    /// The current step of every leg (scratch, overwritten by every step).
    pub leg_step: Vec<LegStep>,
    /// Contact force (I) and moment (B) of the current step, and the body at its start.
    pub force_n: Vec3,
    pub moment_n_m: Vec3,
    pub start_position_m: Vec3,
    pub start_velocity_m_s: Vec3,
    /// `Z_B` in I at the start of the step (the third column of its rotation).
    pub start_z_body: Vec3,
    pub start_rate_rad_s: Vec3,
    pub start_t_s: Lane,
    pub dt_s: Lane,
}

/// The initial state of one lane (computed outside the kernels, where trigonometry is fine).
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct LaneInit {
    pub position_m: [f64; 3],
    pub velocity_m_s: [f64; 3],
    /// `[x, y, z, w]`.
    pub attitude: [f64; 4],
    pub rate_rad_s: [f64; 3],
    pub normal: [f64; 3],
    pub tangent_u: [f64; 3],
    pub tangent_v: [f64; 3],
    pub offset_m: [f64; 2],
    pub tile: usize,
}

impl Block {
    /// A block with every lane empty.
    #[must_use]
    pub fn new(params: &Params) -> Block {
        let zero = splat(0.0);
        let leg = LegLanes {
            stroke_m: zero,
            absorbed_j: zero,
            anchor_m: Vec3::ZERO,
            anchored: all_false(),
            rest_anchor_m: Vec3::ZERO,
            peak_normal_n: zero,
        };
        let leg_step = LegStep {
            tip_m: Vec3::ZERO,
            tip_velocity_m_s: Vec3::ZERO,
            penetration_m: zero,
            normal_n: zero,
            slipping: all_false(),
        };
        let identity = Quat {
            x: zero,
            y: zero,
            z: zero,
            w: splat(1.0),
        };
        Block {
            t_s: zero,
            position_m: Vec3::ZERO,
            velocity_m_s: Vec3::ZERO,
            attitude: identity,
            rotation: identity.to_mat3(),
            rate_rad_s: Vec3::ZERO,
            legs: vec![leg; params.legs.len()],
            surface: SurfaceLanes {
                normal: Vec3::splat([0.0, 0.0, 1.0]),
                tangent_u: Vec3::splat([1.0, 0.0, 0.0]),
                tangent_v: Vec3::splat([0.0, 1.0, 0.0]),
                offset_u_m: zero,
                offset_v_m: zero,
                tile: [0; LANES],
            },
            track: Track {
                start_m: Vec3::ZERO,
                rest_s: zero,
                min_cos_tilt: splat(1.0),
                peak_acceleration_squared: zero,
                peak_acceleration_z: zero,
                bounces: zero,
                touched: all_false(),
                first_contact_s: splat(f64::NAN),
                max_penetration: zero,
                steps: zero,
                outcome: splat(-1.0),
            },
            active: all_false(),
            leg_step: vec![leg_step; params.legs.len()],
            force_n: Vec3::ZERO,
            moment_n_m: Vec3::ZERO,
            start_position_m: Vec3::ZERO,
            start_velocity_m_s: Vec3::ZERO,
            start_z_body: Vec3::splat([0.0, 0.0, 1.0]),
            start_rate_rad_s: Vec3::ZERO,
            start_t_s: zero,
            dt_s: zero,
        }
    }

    /// Puts a new sample into lane `i`.
    pub fn load(&mut self, i: usize, init: &LaneInit) {
        let set = |l: &mut Lane, x: f64| l.as_mut_array()[i] = x;
        set(&mut self.t_s, 0.0);
        self.position_m.set_lane(i, init.position_m);
        self.velocity_m_s.set_lane(i, init.velocity_m_s);
        self.attitude.set_lane(i, init.attitude);
        // The other lanes get what they hold already: the same formula of the same inputs.
        self.rotation = self.attitude.to_mat3();
        self.rate_rad_s.set_lane(i, init.rate_rad_s);
        for leg in &mut self.legs {
            set(&mut leg.stroke_m, 0.0);
            set(&mut leg.absorbed_j, 0.0);
            leg.anchor_m.set_lane(i, [0.0; 3]);
            set(&mut leg.anchored, 0.0);
            leg.rest_anchor_m.set_lane(i, [0.0; 3]);
            set(&mut leg.peak_normal_n, 0.0);
        }
        let s = &mut self.surface;
        s.normal.set_lane(i, init.normal);
        s.tangent_u.set_lane(i, init.tangent_u);
        s.tangent_v.set_lane(i, init.tangent_v);
        set(&mut s.offset_u_m, init.offset_m[0]);
        set(&mut s.offset_v_m, init.offset_m[1]);
        s.tile[i] = init.tile;
        let t = &mut self.track;
        t.start_m.set_lane(i, init.position_m);
        set(&mut t.rest_s, 0.0);
        set(&mut t.min_cos_tilt, 1.0);
        set(&mut t.peak_acceleration_squared, 0.0);
        set(&mut t.peak_acceleration_z, 0.0);
        set(&mut t.bounces, 0.0);
        set(&mut t.touched, 0.0);
        set(&mut t.first_contact_s, f64::NAN);
        set(&mut t.max_penetration, 0.0);
        set(&mut t.steps, 0.0);
        set(&mut t.outcome, -1.0);
        set(&mut self.active, f64::from_bits(u64::MAX));
    }

    /// Empties lane `i`: it takes no more steps and decides nothing.
    pub fn retire(&mut self, i: usize) {
        self.active.as_mut_array()[i] = 0.0;
    }
}
