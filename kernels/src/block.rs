//! The state of `L::LANES` landers, field per field (structure of arrays), with the surface
//! each lane lands on and what its outcome tracking remembers.

use crate::lane::lane;
use crate::lane::{Lane, MAX_LANES, Mask, all_false};
use crate::params::Params;
use crate::rocks::RockClearance;
use crate::vec3::{Mat3, Quat, Vec3, mat3_of};

/// What a leg remembers between steps, per lane.
///
/// Aligned to 128 bytes, as `LegStep`: each block keeps its legs in heap buffers of its
/// own, and the buffers of the blocks of two threads must not meet within a 128-byte pair
/// of cache lines, which x86 cores fetch together (writes to one line of a pair by one core
/// and the other by another then cost like writes to a shared line: measured 20 % of a
/// two-thread sweep).
#[derive(Debug, Clone, Copy)]
#[repr(C, align(128))]
#[allow(missing_docs)]
pub struct LegLanes<L: Lane> {
    pub stroke_m: L,
    pub absorbed_j: L,
    pub anchor_m: Vec3<L>,
    /// Mask: the friction anchor is set (the leg touched in the previous step).
    pub anchored: L::Mask,
    /// On regolith: the deepest sinkage of the footprint, the soil's force there, and the
    /// energy earlier footprints absorbed (the reference's `LegState`).
    pub sinkage_max_m: L,
    pub soil_force_max_n: L,
    pub soil_absorbed_j: L,
    /// The friction anchor when the current rest began (see `outcome`).
    pub rest_anchor_m: Vec3<L>,
    pub peak_normal_n: L,
    /// The peak axial strut load (compressive positive) and the start of its step, NaN
    /// until the leg bears a positive one (MODEL.md section 9).
    pub peak_axial_n: L,
    pub peak_axial_s: L,
    /// The squared peak side load (its root, taken once at the end, is the peak of the
    /// roots) and the start of its step, NaN until the leg bears one.
    pub peak_side_squared: L,
    pub peak_side_s: L,
}

/// One leg during the current step, for the outcome tracking (aligned as `LegLanes`).
#[derive(Debug, Clone, Copy)]
#[repr(C, align(128))]
#[allow(missing_docs)]
pub struct LegStep<L: Lane> {
    /// The footpad's height above the base plane at the start of the step
    /// (`step::footpad_heights`).
    pub height_m: L,
    /// The damper stroke at the start of the step (with dampers only).
    pub start_stroke_m: L,
    /// The footpad's position at the start of the step, found by the outcome tracking
    /// where it needs it (`outcome::start_tips`): the step does not.
    pub tip_m: Vec3<L>,
    /// Where the leg touches in some lane of the block; left from an earlier step where
    /// it touches in none (the outcome tracking reads it only for footpads that touch).
    pub tip_velocity_m_s: Vec3<L>,
    pub penetration_m: L,
    pub normal_n: L,
    /// Mask: the footpad slips (in contact, friction at its cap).
    pub slipping: L::Mask,
    /// Among rocks, what the leg's last lookup found free around its footpad: kept from
    /// step to step, unlike the rest (`rocks::contact_lanes`).
    pub rock_clear: RockClearance<L>,
}

/// The surface of each lane.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct SurfaceLanes<L> {
    pub normal: Vec3<L>,
    pub tangent_u: Vec3<L>,
    pub tangent_v: Vec3<L>,
    pub offset_u_m: L,
    pub offset_v_m: L,
    /// The terrain tile of each lane (the first `L::LANES` used).
    pub tile: [usize; MAX_LANES],
    /// The rock tile of each lane and where the origin falls on it.
    pub rock_tile: [usize; MAX_LANES],
    pub rock_offset_u_m: L,
    pub rock_offset_v_m: L,
}

/// What the outcome tracking remembers, per lane.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct Track<L: Lane> {
    pub start_m: Vec3<L>,
    pub rest_s: L,
    pub min_cos_tilt: L,
    /// The squared peak contact acceleration (its root, taken once at the end, is the
    /// peak of the roots).
    pub peak_acceleration_squared: L,
    pub peak_acceleration_z: L,
    pub bounces: L,
    /// Mask: touched since the last lift-off.
    pub touched: L::Mask,
    /// Time of first contact, NaN until then.
    pub first_contact_s: L,
    /// At the start of the first contact's step (read once `first_contact_s` is set): the
    /// CG velocity, the body rates, `X_B` and `Z_B`, and the deepest leg (the reference's
    /// `touchdown::Met`).
    pub met_velocity_m_s: Vec3<L>,
    pub met_rate_rad_s: Vec3<L>,
    pub met_x_body: Vec3<L>,
    pub met_z_body: Vec3<L>,
    /// The user's number of the deepest leg at the first contact (`Params::leg_index`).
    pub met_leg: L,
    pub max_penetration: L,
    pub steps: L,
    /// Outcome code once decided (see `outcome`), -1 before.
    pub outcome: L,
}

/// The thrust on each lane (MODEL.md section 7), constant from one event of the lane's
/// control loop to the next: the control loop (outside the kernels) sets it at every event,
/// and the step never passes the next one. A lander without a control loop keeps no
/// thrust, no event and `powered` false.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct ThrustLanes<L: Lane> {
    /// Sum of the firing thrusters' forces, in B, N.
    pub force_b_n: Vec3<L>,
    /// Their moment about the CG, in B, N m.
    pub moment_b_n_m: Vec3<L>,
    /// Time to the lane's next control event (a thruster stops, or a control instant), s;
    /// infinite where none comes.
    pub event_in_s: L,
    /// What the thrust can add, within a longest flight step, to the speed at which a
    /// footpad approaches the surface (`step_size`), m/s.
    pub approach_m_s: L,
    /// Mask: the control loop may still fire; the rest clock and the early rules wait
    /// (MODEL.md section 8).
    pub powered: L::Mask,
    /// Mask: a footpad touched the surface in some step since the lane's last control
    /// event (the touchdown switches; `take_touched` reads and clears it).
    pub touched: L::Mask,
}

/// `LANES` landers.
#[derive(Debug, Clone)]
#[allow(missing_docs)]
pub struct Block<L: Lane> {
    pub t_s: L,
    /// What rounding has dropped from `t_s` so far (see `step::add_time`).
    pub t_error_s: L,
    pub position_m: Vec3<L>,
    pub velocity_m_s: Vec3<L>,
    pub attitude: Quat<L>,
    /// The rotation matrix of `attitude`, kept with it (by `step` and `load`) so that
    /// `step_size`, `step` and `observe` do not each rebuild it.
    pub rotation: Mat3<L>,
    pub rate_rad_s: Vec3<L>,
    pub legs: Vec<LegLanes<L>>,
    pub surface: SurfaceLanes<L>,
    pub track: Track<L>,
    /// Mask: the lane holds a sample.
    pub active: L::Mask,
    /// The current step of every leg (scratch, overwritten by every step, but for its
    /// `rock_clear`).
    pub leg_step: Vec<LegStep<L>>,
    /// The next step in contact: `Params::step_s`, or with `Params::step_control`, what
    /// the error control of the last step chose (`step::control_step`).
    pub contact_step_s: L,
    /// Contact force (I) of the current step, its moment about the CG (B, without the
    /// thrust), and the body at its start.
    pub force_n: Vec3<L>,
    pub moment_n_m: Vec3<L>,
    pub start_position_m: Vec3<L>,
    pub start_velocity_m_s: Vec3<L>,
    /// The rotation at the start of the step.
    pub start_rotation: Mat3<L>,
    pub start_rate_rad_s: Vec3<L>,
    pub start_t_s: L,
    pub dt_s: L,
    /// The thrust of each lane (all zero without thrusters).
    pub thrust: ThrustLanes<L>,
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
    pub rock_offset_m: [f64; 2],
    pub rock_tile: usize,
    /// The first contact step (`Params::step_s`).
    pub step_s: f64,
}

/// The thrust of one lane until its next control event (`ThrustLanes`, one lane).
#[derive(Debug, Clone, Copy, PartialEq)]
#[allow(missing_docs)]
pub struct LaneThrust {
    pub force_b_n: [f64; 3],
    pub moment_b_n_m: [f64; 3],
    pub event_in_s: f64,
    pub approach_m_s: f64,
    pub powered: bool,
}

impl LaneThrust {
    /// No thrust, no event to come: a passive lander.
    pub const NONE: LaneThrust = LaneThrust {
        force_b_n: [0.0; 3],
        moment_b_n_m: [0.0; 3],
        event_in_s: f64::INFINITY,
        approach_m_s: 0.0,
        powered: false,
    };
}

impl<L: Lane> Block<L> {
    /// A block with every lane empty.
    #[must_use]
    pub fn new(params: &Params<L>) -> Block<L> {
        // Through memory only (see `params::lane`).
        let zero = L::ZERO;
        let one = lane(1.0);
        let leg = LegLanes {
            stroke_m: zero,
            absorbed_j: zero,
            anchor_m: Vec3::ZERO,
            anchored: all_false::<L>(),
            sinkage_max_m: zero,
            soil_force_max_n: zero,
            soil_absorbed_j: zero,
            rest_anchor_m: Vec3::ZERO,
            peak_normal_n: zero,
            peak_axial_n: zero,
            peak_axial_s: lane(f64::NAN),
            peak_side_squared: zero,
            peak_side_s: lane(f64::NAN),
        };
        let leg_step = LegStep {
            height_m: zero,
            start_stroke_m: zero,
            tip_m: Vec3::ZERO,
            tip_velocity_m_s: Vec3::ZERO,
            penetration_m: zero,
            normal_n: zero,
            slipping: all_false::<L>(),
            rock_clear: RockClearance::new(),
        };
        let identity = Quat {
            x: zero,
            y: zero,
            z: zero,
            w: one,
        };
        Block {
            t_s: zero,
            t_error_s: zero,
            position_m: Vec3::ZERO,
            velocity_m_s: Vec3::ZERO,
            attitude: identity,
            rotation: Mat3 {
                x_axis: Vec3::new(one, zero, zero),
                y_axis: Vec3::new(zero, one, zero),
                z_axis: Vec3::new(zero, zero, one),
            },
            rate_rad_s: Vec3::ZERO,
            legs: vec![leg; params.legs.len()],
            surface: SurfaceLanes {
                normal: Vec3::splat([0.0, 0.0, 1.0]),
                tangent_u: Vec3::splat([1.0, 0.0, 0.0]),
                tangent_v: Vec3::splat([0.0, 1.0, 0.0]),
                offset_u_m: zero,
                offset_v_m: zero,
                tile: [0; MAX_LANES],
                rock_tile: [0; MAX_LANES],
                rock_offset_u_m: zero,
                rock_offset_v_m: zero,
            },
            track: Track {
                start_m: Vec3::ZERO,
                rest_s: zero,
                min_cos_tilt: one,
                peak_acceleration_squared: zero,
                peak_acceleration_z: zero,
                bounces: zero,
                touched: all_false::<L>(),
                first_contact_s: lane(f64::NAN),
                met_velocity_m_s: Vec3::ZERO,
                met_rate_rad_s: Vec3::ZERO,
                met_x_body: Vec3::ZERO,
                met_z_body: Vec3::ZERO,
                met_leg: zero,
                max_penetration: zero,
                steps: zero,
                outcome: lane(-1.0),
            },
            active: all_false::<L>(),
            leg_step: vec![leg_step; params.legs.len()],
            contact_step_s: zero,
            force_n: Vec3::ZERO,
            moment_n_m: Vec3::ZERO,
            start_position_m: Vec3::ZERO,
            start_velocity_m_s: Vec3::ZERO,
            start_rotation: Mat3 {
                x_axis: Vec3::new(one, zero, zero),
                y_axis: Vec3::new(zero, one, zero),
                z_axis: Vec3::new(zero, zero, one),
            },
            start_rate_rad_s: Vec3::ZERO,
            start_t_s: zero,
            dt_s: zero,
            thrust: ThrustLanes {
                force_b_n: Vec3::ZERO,
                moment_b_n_m: Vec3::ZERO,
                event_in_s: lane(f64::INFINITY),
                approach_m_s: zero,
                powered: all_false::<L>(),
                touched: all_false::<L>(),
            },
        }
    }

    /// Puts a new sample into lane `i`.
    pub fn load(&mut self, i: usize, init: &LaneInit) {
        let set = |l: &mut L, x: f64| l.set_lane(i, x);
        set(&mut self.t_s, 0.0);
        set(&mut self.t_error_s, 0.0);
        // The error control's memory: the first contact step, and no last step.
        set(&mut self.contact_step_s, init.step_s);
        self.force_n.set_lane(i, [0.0; 3]);
        self.moment_n_m.set_lane(i, [0.0; 3]);
        set(&mut self.dt_s, 0.0);
        self.position_m.set_lane(i, init.position_m);
        self.velocity_m_s.set_lane(i, init.velocity_m_s);
        self.attitude.set_lane(i, init.attitude);
        self.rotation.set_lane(i, mat3_of(init.attitude));
        self.rate_rad_s.set_lane(i, init.rate_rad_s);
        for leg in &mut self.legs {
            set(&mut leg.stroke_m, 0.0);
            set(&mut leg.absorbed_j, 0.0);
            leg.anchor_m.set_lane(i, [0.0; 3]);
            leg.anchored.set_lane(i, false);
            set(&mut leg.sinkage_max_m, 0.0);
            set(&mut leg.soil_force_max_n, 0.0);
            set(&mut leg.soil_absorbed_j, 0.0);
            leg.rest_anchor_m.set_lane(i, [0.0; 3]);
            set(&mut leg.peak_normal_n, 0.0);
            set(&mut leg.peak_axial_n, 0.0);
            set(&mut leg.peak_axial_s, f64::NAN);
            set(&mut leg.peak_side_squared, 0.0);
            set(&mut leg.peak_side_s, f64::NAN);
        }
        let s = &mut self.surface;
        s.normal.set_lane(i, init.normal);
        s.tangent_u.set_lane(i, init.tangent_u);
        s.tangent_v.set_lane(i, init.tangent_v);
        set(&mut s.offset_u_m, init.offset_m[0]);
        set(&mut s.offset_v_m, init.offset_m[1]);
        s.tile[i] = init.tile;
        s.rock_tile[i] = init.rock_tile;
        set(&mut s.rock_offset_u_m, init.rock_offset_m[0]);
        set(&mut s.rock_offset_v_m, init.rock_offset_m[1]);
        for leg in &mut self.leg_step {
            leg.rock_clear.forget(i);
        }
        let t = &mut self.track;
        t.start_m.set_lane(i, init.position_m);
        set(&mut t.rest_s, 0.0);
        set(&mut t.min_cos_tilt, 1.0);
        set(&mut t.peak_acceleration_squared, 0.0);
        set(&mut t.peak_acceleration_z, 0.0);
        set(&mut t.bounces, 0.0);
        t.touched.set_lane(i, false);
        set(&mut t.first_contact_s, f64::NAN);
        set(&mut t.max_penetration, 0.0);
        set(&mut t.steps, 0.0);
        set(&mut t.outcome, -1.0);
        self.set_thrust(i, &LaneThrust::NONE);
        self.active.set_lane(i, true);
    }

    /// Sets lane `i`'s thrust until its next control event (outside the kernels).
    pub fn set_thrust(&mut self, i: usize, thrust: &LaneThrust) {
        let t = &mut self.thrust;
        t.force_b_n.set_lane(i, thrust.force_b_n);
        t.moment_b_n_m.set_lane(i, thrust.moment_b_n_m);
        t.event_in_s.set_lane(i, thrust.event_in_s);
        t.approach_m_s.set_lane(i, thrust.approach_m_s);
        t.powered.set_lane(i, thrust.powered);
    }

    /// Whether a footpad of lane `i` touched the surface in some step since this was last
    /// asked (outside the kernels: its control loop's touchdown switches); clears it.
    pub fn take_touched(&mut self, i: usize) -> bool {
        let touched = self.thrust.touched.lane(i);
        self.thrust.touched.set_lane(i, false);
        touched
    }

    /// Number of lanes holding a sample (read through memory, outside the kernels).
    #[must_use]
    pub fn busy_lanes(&self) -> usize {
        (0..L::LANES).filter(|&i| self.active.lane(i)).count()
    }

    /// Moves lane `i`'s origin along its surface's base plane to the foot of its CG, outside
    /// the kernels (in f64): every position it keeps (CG, friction and rest anchors, the
    /// start of its track) moves by the same in-plane vector `s`, and its terrain's and rocks'
    /// offsets by `s` along the plane's axes, so that nothing it computes changes but the rounding
    /// of its positions, which then stay small. The kernels ask for it (`outcome_bits`)
    /// when the CG's foot is farther than `L::RECENTRE_M` from the origin: f32 lanes only.
    pub fn recentre(&mut self, i: usize) {
        let n = self.surface.normal.lane(i);
        let p = self.position_m.lane(i);
        let height = n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
        let s: [f64; 3] = std::array::from_fn(|k| p[k] - height * n[k]);
        let shift = |v: &mut Vec3<L>| {
            let x = v.lane(i);
            v.set_lane(i, std::array::from_fn(|k| x[k] - s[k]));
        };
        shift(&mut self.position_m);
        shift(&mut self.start_position_m);
        shift(&mut self.track.start_m);
        for leg in &mut self.legs {
            shift(&mut leg.anchor_m);
            shift(&mut leg.rest_anchor_m);
        }
        let along = |t: &Vec3<L>| {
            let t = t.lane(i);
            t[0] * s[0] + t[1] * s[1] + t[2] * s[2]
        };
        let (du, dv) = (
            along(&self.surface.tangent_u),
            along(&self.surface.tangent_v),
        );
        let u = self.surface.offset_u_m.lane(i);
        self.surface.offset_u_m.set_lane(i, u + du);
        let v = self.surface.offset_v_m.lane(i);
        self.surface.offset_v_m.set_lane(i, v + dv);
        // The rocks stay where they are on the ground, as the terrain does.
        let u = self.surface.rock_offset_u_m.lane(i);
        self.surface.rock_offset_u_m.set_lane(i, u + du);
        let v = self.surface.rock_offset_v_m.lane(i);
        self.surface.rock_offset_v_m.set_lane(i, v + dv);
        // The footpads' tile coordinates are the same but for their rounding: read again.
        for leg in &mut self.leg_step {
            leg.rock_clear.forget(i);
        }
    }

    /// Empties lane `i`: it takes no more steps and decides nothing.
    pub fn retire(&mut self, i: usize) {
        self.active.set_lane(i, false);
    }
    /// Puts the lander of lane `j` of `from` into lane `i`, every number of its state to
    /// the bit (outside the kernels): a lander steps the same whatever lane or block holds
    /// it, so the worker that meets its landers at their control instants may move them
    /// between blocks. Lane `j` of `from` is left as it was (retire it).
    pub fn move_lane(&mut self, i: usize, from: &Block<L>, j: usize) {
        fn one<L: Lane>(to: &mut L, from: &L, i: usize, j: usize) {
            to.set_lane(i, from.lane(j));
        }
        fn three<L: Lane>(to: &mut Vec3<L>, from: &Vec3<L>, i: usize, j: usize) {
            to.set_lane(i, from.lane(j));
        }
        fn nine<L: Lane>(to: &mut Mat3<L>, from: &Mat3<L>, i: usize, j: usize) {
            three(&mut to.x_axis, &from.x_axis, i, j);
            three(&mut to.y_axis, &from.y_axis, i, j);
            three(&mut to.z_axis, &from.z_axis, i, j);
        }
        fn flag<M: Mask>(to: &mut M, from: &M, i: usize, j: usize) {
            Mask::set_lane(to, i, Mask::lane(from, j));
        }
        assert!(
            self.legs.len() == from.legs.len(),
            "blocks of the same lander"
        );
        one(&mut self.t_s, &from.t_s, i, j);
        one(&mut self.t_error_s, &from.t_error_s, i, j);
        three(&mut self.position_m, &from.position_m, i, j);
        three(&mut self.velocity_m_s, &from.velocity_m_s, i, j);
        self.attitude.set_lane(i, from.attitude.lane(j));
        nine(&mut self.rotation, &from.rotation, i, j);
        three(&mut self.rate_rad_s, &from.rate_rad_s, i, j);
        for (to, from) in self.legs.iter_mut().zip(&from.legs) {
            one(&mut to.stroke_m, &from.stroke_m, i, j);
            one(&mut to.absorbed_j, &from.absorbed_j, i, j);
            three(&mut to.anchor_m, &from.anchor_m, i, j);
            flag(&mut to.anchored, &from.anchored, i, j);
            one(&mut to.sinkage_max_m, &from.sinkage_max_m, i, j);
            one(&mut to.soil_force_max_n, &from.soil_force_max_n, i, j);
            one(&mut to.soil_absorbed_j, &from.soil_absorbed_j, i, j);
            three(&mut to.rest_anchor_m, &from.rest_anchor_m, i, j);
            one(&mut to.peak_normal_n, &from.peak_normal_n, i, j);
            one(&mut to.peak_axial_n, &from.peak_axial_n, i, j);
            one(&mut to.peak_axial_s, &from.peak_axial_s, i, j);
            one(&mut to.peak_side_squared, &from.peak_side_squared, i, j);
            one(&mut to.peak_side_s, &from.peak_side_s, i, j);
        }
        let (to, f) = (&mut self.surface, &from.surface);
        three(&mut to.normal, &f.normal, i, j);
        three(&mut to.tangent_u, &f.tangent_u, i, j);
        three(&mut to.tangent_v, &f.tangent_v, i, j);
        one(&mut to.offset_u_m, &f.offset_u_m, i, j);
        one(&mut to.offset_v_m, &f.offset_v_m, i, j);
        to.tile[i] = f.tile[j];
        to.rock_tile[i] = f.rock_tile[j];
        one(&mut to.rock_offset_u_m, &f.rock_offset_u_m, i, j);
        one(&mut to.rock_offset_v_m, &f.rock_offset_v_m, i, j);
        let (to, f) = (&mut self.track, &from.track);
        three(&mut to.start_m, &f.start_m, i, j);
        one(&mut to.rest_s, &f.rest_s, i, j);
        one(&mut to.min_cos_tilt, &f.min_cos_tilt, i, j);
        one(
            &mut to.peak_acceleration_squared,
            &f.peak_acceleration_squared,
            i,
            j,
        );
        one(&mut to.peak_acceleration_z, &f.peak_acceleration_z, i, j);
        one(&mut to.bounces, &f.bounces, i, j);
        flag(&mut to.touched, &f.touched, i, j);
        one(&mut to.first_contact_s, &f.first_contact_s, i, j);
        three(&mut to.met_velocity_m_s, &f.met_velocity_m_s, i, j);
        three(&mut to.met_rate_rad_s, &f.met_rate_rad_s, i, j);
        three(&mut to.met_x_body, &f.met_x_body, i, j);
        three(&mut to.met_z_body, &f.met_z_body, i, j);
        one(&mut to.met_leg, &f.met_leg, i, j);
        one(&mut to.max_penetration, &f.max_penetration, i, j);
        one(&mut to.steps, &f.steps, i, j);
        one(&mut to.outcome, &f.outcome, i, j);
        flag(&mut self.active, &from.active, i, j);
        for (to, from) in self.leg_step.iter_mut().zip(&from.leg_step) {
            one(&mut to.height_m, &from.height_m, i, j);
            one(&mut to.start_stroke_m, &from.start_stroke_m, i, j);
            three(&mut to.tip_m, &from.tip_m, i, j);
            three(&mut to.tip_velocity_m_s, &from.tip_velocity_m_s, i, j);
            one(&mut to.penetration_m, &from.penetration_m, i, j);
            one(&mut to.normal_n, &from.normal_n, i, j);
            flag(&mut to.slipping, &from.slipping, i, j);
            let (to, f) = (&mut to.rock_clear, &from.rock_clear);
            one(&mut to.u_m, &f.u_m, i, j);
            one(&mut to.v_m, &f.v_m, i, j);
            one(&mut to.height_m, &f.height_m, i, j);
            one(&mut to.free_m, &f.free_m, i, j);
        }
        one(&mut self.contact_step_s, &from.contact_step_s, i, j);
        three(&mut self.force_n, &from.force_n, i, j);
        three(&mut self.moment_n_m, &from.moment_n_m, i, j);
        three(&mut self.start_position_m, &from.start_position_m, i, j);
        three(&mut self.start_velocity_m_s, &from.start_velocity_m_s, i, j);
        nine(&mut self.start_rotation, &from.start_rotation, i, j);
        three(&mut self.start_rate_rad_s, &from.start_rate_rad_s, i, j);
        one(&mut self.start_t_s, &from.start_t_s, i, j);
        one(&mut self.dt_s, &from.dt_s, i, j);
        let (to, f) = (&mut self.thrust, &from.thrust);
        three(&mut to.force_b_n, &f.force_b_n, i, j);
        three(&mut to.moment_b_n_m, &f.moment_b_n_m, i, j);
        one(&mut to.event_in_s, &f.event_in_s, i, j);
        one(&mut to.approach_m_s, &f.approach_m_s, i, j);
        flag(&mut to.powered, &f.powered, i, j);
        flag(&mut to.touched, &f.touched, i, j);
    }
}
