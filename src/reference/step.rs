//! One fixed step of one lander: every leg's contact, then the rigid body.
//! The SIMD kernel (`kernels::step`) does the same, in the same order.

use super::contact::{self, LegState};
use super::model::{Leg, Model, StepControl};
use super::rigid_body::{self, Body};
use crate::control::Thrust;
use crate::slope::Surface;
use glam::{DMat3, DVec3};
use kernels::step::EVENT_DUST_S;

/// The state of one lander.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Time since the start of the sample, s.
    pub t_s: f64,
    /// What rounding has dropped from `t_s` so far (`add_time`), s.
    pub t_error_s: f64,
    /// The rigid body: CG position and velocity, attitude, body rates.
    pub body: Body,
    /// What each leg remembers between steps (damper stroke, friction anchor), in the
    /// order of `Model::legs`.
    pub legs: Vec<LegState>,
    /// The thrust until the next control event (none without a control loop).
    pub thrust: Thrust,
    /// The next step in contact: `Model::step_s`, or with a `StepControl`, what the error
    /// control of the last step chose (`control_step`), s.
    pub contact_step_s: f64,
    /// The last step's contact force (I), N, and moment about the CG (B), N m, without the
    /// thrust, and its length (0 before the first), s: the error control compares the next
    /// step's forces with them.
    pub force_n: DVec3,
    /// The last step's contact moment (see `force_n`), N m.
    pub moment_n_m: DVec3,
    /// The last step's length (see `force_n`), s.
    pub dt_s: f64,
}

/// One leg during one step, as computed at the start of the step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LegReport {
    /// Footpad position in I, m.
    pub tip_m: DVec3,
    /// Footpad velocity in I, m/s.
    pub tip_velocity_m_s: DVec3,
    /// Depth below the local surface (negative: clearance), m.
    pub penetration_m: f64,
    /// Normal force magnitude on the footpad, N (0 out of contact).
    pub normal_n: f64,
    /// Friction force magnitude on the footpad, N (0 out of contact).
    pub friction_n: f64,
    /// Whether the footpad slips (in contact, friction at its cap).
    pub slipping: bool,
    /// Damper stroke after the step, m.
    pub stroke_m: f64,
    /// The strut's axial load: the footpad's force along the strut towards the hip,
    /// compressive positive, N (0 out of contact; MODEL.md section 9).
    pub axial_force_n: f64,
    /// The strut's side load: the footpad's force across the strut, N (0 out of contact).
    pub side_force_n: f64,
}

impl LegReport {
    /// Whether the leg touches the surface.
    #[must_use]
    pub fn in_contact(&self) -> bool {
        self.penetration_m > 0.0
    }
}

/// What a step computed: the state it started from and the forces it applied.
#[derive(Debug, Clone, PartialEq)]
pub struct StepReport {
    /// Time at the start of the step, s.
    pub t_s: f64,
    /// Length of the step, s.
    pub dt_s: f64,
    /// The body at the start of the step.
    pub body: Body,
    /// Sum of the leg forces, in I, N.
    pub force_n: DVec3,
    /// Their moment about the CG, in B, N m.
    pub moment_n_m: DVec3,
    /// The thrust during the step.
    pub thrust: Thrust,
    /// Every leg during the step, in the order of `Model::legs`.
    pub legs: Vec<LegReport>,
    /// What the control loop is doing (scenarios with one; filled by `run`).
    pub control: Option<crate::control::ControlReport>,
}

impl StepReport {
    /// The specific force on the lander during the step, in I, N: the contact forces plus
    /// the thrust, without gravity (what an accelerometer at the CG reads, times the
    /// mass). `dv/dt` is this over the mass plus gravity.
    #[must_use]
    pub fn specific_force_n(&self) -> DVec3 {
        if self.thrust.force_b_n == DVec3::ZERO {
            // A passive lander (and a thruster-less segment): the contact forces alone.
            return self.force_n;
        }
        self.force_n + DMat3::from_quat(self.body.attitude) * self.thrust.force_b_n
    }

    /// An empty report for `legs` legs.
    #[must_use]
    pub fn new(legs: usize) -> StepReport {
        StepReport {
            t_s: 0.0,
            dt_s: 0.0,
            body: Body {
                position_m: DVec3::ZERO,
                velocity_m_s: DVec3::ZERO,
                attitude: glam::DQuat::IDENTITY,
                rate_rad_s: DVec3::ZERO,
            },
            force_n: DVec3::ZERO,
            moment_n_m: DVec3::ZERO,
            thrust: Thrust::NONE,
            legs: vec![LegReport::default(); legs],
            control: None,
        }
    }
}

/// Advances `state` by `dt`, writing what it computed to `report`.
pub fn step(model: &Model, surface: &Surface, state: &mut State, dt: f64, report: &mut StepReport) {
    let body = state.body;
    let rotation = DMat3::from_quat(body.attitude);
    let rate_i = rotation * body.rate_rad_s;
    let rocks = model.rock_field();
    let normal_b = rotation.transpose() * surface.normal;
    let mut force_n = DVec3::ZERO;
    // Moments about the CG, summed in I and turned into B once: (R a) x (R b) = R (a x b).
    let mut moment_i = DVec3::ZERO;
    for ((leg, leg_state), out) in model.legs.iter().zip(&mut state.legs).zip(&mut report.legs) {
        let tip_b = leg.tip_m - leg.strut_axis * leg_state.stroke_m;
        let arm = rotation * tip_b;
        let tip = body.position_m + arm;
        let tip_velocity = body.velocity_m_s + rate_i.cross(arm);
        let height = footpad_height(surface, &body, normal_b, tip_b);
        let (penetration, normal, on_rock) =
            surface.contact_at(model.terrain.as_ref(), rocks.as_ref(), tip, height);
        // The strut direction, footpad to hip, in I: the damper's and the strut loads'.
        let strut_up = -(rotation * leg.strut_axis);
        let f = if penetration > 0.0 {
            contact::leg_force(
                &model.contact,
                // A footpad on a rock meets the elastic law (rocks do not give way).
                model.soil.as_ref().filter(|_| !on_rock),
                model.honeycomb.as_ref(),
                dt,
                penetration,
                normal,
                tip,
                tip_velocity,
                strut_up,
                leg_state,
            )
        } else {
            leg_state.anchored = false;
            contact::LegForce {
                force_n: DVec3::ZERO,
                normal_n: 0.0,
                friction_n: 0.0,
                slipping: false,
            }
        };
        force_n += f.force_n;
        moment_i += arm.cross(f.force_n);
        let (axial_force_n, side_force_n) = strut_loads(f.force_n, strut_up);
        *out = LegReport {
            tip_m: tip,
            tip_velocity_m_s: tip_velocity,
            penetration_m: penetration,
            normal_n: f.normal_n,
            friction_n: f.friction_n,
            slipping: f.slipping,
            stroke_m: leg_state.stroke_m,
            axial_force_n,
            side_force_n,
        };
    }
    let thrust = state.thrust;
    let contact_moment_n_m = rotation.transpose() * moment_i;
    // What the contact kicks the body with (`kick_scale`): the force and moment themselves
    // at a fixed step.
    let (mut kick_n, mut kick_moment_n_m) = (force_n, contact_moment_n_m);
    if let Some(control) = &model.step_control {
        let scale = kick_scale(state, dt);
        let touching = report.legs.iter().any(LegReport::in_contact);
        let nearest = report
            .legs
            .iter()
            .map(|l| -l.penetration_m)
            .fold(f64::INFINITY, f64::min);
        control_step(
            control,
            model,
            state,
            force_n,
            contact_moment_n_m,
            (touching, nearest, dt),
        );
        kick_n = force_n * scale;
        kick_moment_n_m = contact_moment_n_m * scale;
    }
    state.force_n = force_n;
    state.moment_n_m = contact_moment_n_m;
    state.dt_s = dt;
    let moment_n_m = kick_moment_n_m + thrust.moment_b_n_m;
    report.t_s = state.t_s;
    report.dt_s = dt;
    report.body = body;
    report.force_n = force_n;
    // What the contact computed (the kick's scaling aside), as `force_n`.
    report.moment_n_m = contact_moment_n_m + thrust.moment_b_n_m;
    report.thrust = thrust;
    rigid_body::integrate(
        &mut state.body,
        model.mass_kg,
        model.inertia_kg_m2,
        model.gravity_m_s2,
        kick_n,
        rotation * thrust.force_b_n,
        moment_n_m,
        dt,
    );
    state.thrust.event_in_s -= dt;
    add_time(&mut state.t_s, &mut state.t_error_s, dt);
}

/// What the contact force and moment of a step of length `dt` are scaled by, with the
/// error control (MODEL.md section 2.1): `(dt_s + dt) / (2 dt)`, `dt_s` the last step's
/// length (0 before the first); 1 for a step of no length.
///
/// The step is symplectic Euler, a leapfrog whose velocities lie half a step after the
/// positions: the force at a step's start kicks the velocity from the middle of the last
/// step to the middle of this one, a time of `(dt_s + dt) / 2`. At a fixed step that is
/// `dt`; where the length changes, a kick of `dt` errs by `(dt_s - dt) / 2` times the
/// acceleration, an error of the first order that no tolerance removes (with it, every
/// controlled run of the MuJoCo-matched scenario lost 1-1.5 points of its stable share
/// against the quarter step, the tighter the tolerance the more). It holds at a contact's
/// first step too: contact began within the last (flight) step, on average at its middle.
/// Gravity and the thrust are not scaled (they enter exactly over the step, for exact
/// ballistic arcs), so where the contact balances them, on a lander at rest or held down,
/// a change of length leaves `g (dt - dt_s) / 2` in its velocity, which the opposite change
/// takes back (8e-6 m/s per doubling of 1 ms at the default gravity; 5e-3 m/s is at rest).
#[must_use]
pub fn kick_scale(state: &State, dt: f64) -> f64 {
    if dt > 0.0 {
        0.5 * (state.dt_s + dt) / dt
    } else {
        1.0
    }
}

/// The error control of the contact step (MODEL.md section 2.1), after the contact forces
/// of a step, `force_n` (I) and `moment_n_m` (B, without the thrust), are known: from how
/// much the acceleration of the footpads changed since the last step's forces, it sets the
/// next contact step, `state.contact_step_s`.
///
/// A step holds the forces of its start, so what it adds to a velocity differs from the
/// trapezoidal rule's, which takes the mean of the forces at its start and at its end, by
/// `h/2` times their difference: with the acceleration changing at the rate `|da| / dt` of
/// the last step (`da` its change over that step, of length `dt`), a step of length `h`
/// errs by `e(h) = h^2 |da| / (2 dt)` in velocity. `da` is the CG's plus that of the
/// footpads' rotation about it (the change of the angular acceleration times the leg
/// reach), added as squares (no square root in the step). Where `e(h)` exceeds the
/// tolerance the next step is half as long; where `e(2h)` would stay below half of it
/// (`e(h)` below an eighth), twice as long; never below `step_min_s` nor above
/// `step_max_s`. A step is never repeated (the estimate comes after it), so a contact
/// starts short: a lander with no footpad on the surface (`touching` false) takes as its
/// next contact step half the time its footpads need, at the fastest approach (`step_size`'s
/// bound), to cover what this step (of length `dt`) leaves of their least clearance above
/// the local surface (`nearest`), between `step_min_s` and `step_s`; and the flight steps
/// that bring it down onto a plane end within `step_min_s` of the contact (`step_size`). A
/// last step shorter than `step_min_s` (cut by a control event or `t_max_s`) measures
/// nothing.
pub fn control_step(
    control: &StepControl,
    model: &Model,
    state: &mut State,
    force_n: DVec3,
    moment_n_m: DVec3,
    (touching, nearest, dt): (bool, f64, f64),
) {
    let previous = state.dt_s;
    let jump = (force_n - state.force_n) / model.mass_kg;
    let turn = (moment_n_m - state.moment_n_m) / model.inertia_kg_m2;
    let reach = model.leg_reach_m();
    let change_squared = jump.length_squared() + turn.length_squared() * (reach * reach);
    let mut h = state.contact_step_s;
    let per = h * h / previous;
    let error_squared = 0.25 * per * per * change_squared;
    let tolerance_squared = control.tolerance_m_s * control.tolerance_m_s;
    if previous >= control.step_min_s {
        if error_squared > tolerance_squared {
            h = (0.5 * h).max(control.step_min_s);
        } else if 64.0 * error_squared < tolerance_squared {
            h = (2.0 * h).min(control.step_max_s);
        }
    }
    state.contact_step_s = if touching {
        h
    } else {
        let body = &state.body;
        let speed = body.rate_rad_s.length() * model.leg_reach_m()
            + (body.velocity_m_s.length() + model.gravity_m_s2 * model.flight_step_max_s)
            + state.thrust.approach_m_s;
        (0.5 * nearest / speed - 0.5 * dt)
            .max(control.step_min_s)
            .min(model.step_s)
    };
}

/// The loads of a strut whose footpad takes the force `force_n` (in I), `strut_up` its
/// unit direction from the footpad to the hip (in I): along it, compressive positive,
/// `A = F . strut_up` (`-F_B . u` in B), and across it, `|F - A strut_up|`, as
/// `sqrt(|F|^2 - A^2)` (0 where rounding makes that negative), N. (Off by up to 1e-8 |F|
/// where the side load is near 0, by the difference of squares: far below any load that
/// matters.)
#[must_use]
pub fn strut_loads(force_n: DVec3, strut_up: DVec3) -> (f64, f64) {
    let axial = force_n.dot(strut_up);
    (
        axial,
        (force_n.length_squared() - axial * axial).max(0.0).sqrt(),
    )
}

/// Height above the base plane of the footpad at `tip_b` (in B): that of the CG, plus the
/// footpad's offset from the CG along the normal, taken in B, where the footpads are
/// (`normal_b`, the surface normal in B).
#[must_use]
pub fn footpad_height(surface: &Surface, body: &Body, normal_b: DVec3, tip_b: DVec3) -> f64 {
    surface.normal.dot(body.position_m) + normal_b.dot(tip_b)
}

/// `t += dt`, compensated (Kahan): `error` keeps what rounding dropped and the next step
/// adds it back, so the time stays exact to a rounding of `t` however many steps are
/// summed: plain sums of 1 ms steps in f32 lose 27 ms by t = 70 s and 54 ms by 120 s (every
/// addition in a binade rounds alike), compensated ones stay within half an ulp (test
/// `compensated_time_stays_within_a_rounding` in the kernels). The same in the kernels.
pub fn add_time(t: &mut f64, error: &mut f64, dt: f64) {
    let y = dt - *error;
    let sum = *t + y;
    *error = (sum - *t) - y;
    *t = sum;
}

/// How far a footpad at `tip` (in I), its lowest point `height` above the base plane, can
/// move in any direction and meet no rock (MODEL.md section 2.1, "Rocks bound the step by
/// what is near"): on the plane, its gap to the nearest rock present, at least `SKIN_M`
/// read around it (`Rocks::contact_clear`), or its height above the highest rock where
/// more; on rough terrain, its height above the terrain's top (rocks included); infinite
/// without rocks. So a footpad hopping among rocks is held to short steps only where a
/// rock is near, not wherever the highest rock of every tile is higher.
#[must_use]
pub fn rock_clearance(model: &Model, surface: &Surface, tip: DVec3, height: f64) -> f64 {
    let Some(rocks) = &model.rocks else {
        return f64::INFINITY;
    };
    let above_all = height - model.terrain_top_m();
    if model.terrain.is_some() {
        return above_all;
    }
    let pad_radius = model.pad_radius_m();
    let (_, gap) = rocks.contact_clear(
        surface.rock_tile,
        surface.tangent_u.dot(tip) + surface.rock_offset_m[0],
        surface.tangent_v.dot(tip) + surface.rock_offset_m[1],
        height,
        pad_radius,
        model.rock_abundance,
        rocks.skin_m(pad_radius),
    );
    gap.max(above_all)
}

/// With the error control (MODEL.md section 2.1), the free-flight step of a lander whose
/// every footpad is clear of the terrain (`clearance` of each leg and its state: of the
/// ground and of the rocks, `rock_clearance`): the least,
/// over the footpads, of half the time in which each could reach it, from its own
/// clearance `c` and its own speed towards the surface, `max(0, -v_n)` (`v_n = n . (v +
/// w x r)`, its velocity along the normal, `n . (w x r) = w_B . (r_B x n_B)` in B), plus
/// what that speed can gain within a longest flight step: gravity and the thrust
/// (`Thrust::approach_m_s`), and the rotation, whose acceleration at a footpad is at most
/// `|w|^2 r` centripetal plus `|dw/dt| r` gyroscopic, `|dw/dt| <= |w|^2` torque-free (each
/// `|I_j - I_k| <= I_i`), with `r` the leg reach. So a footpad rising or drifting along a
/// low hop is not held to the steps of one falling at the lander's whole speed. A rock can
/// be met from any side: half the time to cover its clearance at the whole `speed` (as
/// without the error control).
#[must_use]
pub fn footpad_flight_step(
    model: &Model,
    surface: &Surface,
    state: &State,
    normal_b: DVec3,
    speed: f64,
    clearance: impl Fn(&Leg, &LegState) -> (f64, f64),
) -> f64 {
    let body = &state.body;
    let reach = model.leg_reach_m();
    let gain = (model.gravity_m_s2 + 2.0 * body.rate_rad_s.length_squared() * reach)
        * model.flight_step_max_s
        + state.thrust.approach_m_s;
    let along = surface.normal.dot(body.velocity_m_s);
    model
        .legs
        .iter()
        .zip(&state.legs)
        .map(|(leg, ls)| {
            let tip_b = leg.tip_m - leg.strut_axis * ls.stroke_m;
            let v_n = along + body.rate_rad_s.dot(tip_b.cross(normal_b));
            let (ground, rocks) = clearance(leg, ls);
            (0.5 * ground / ((-v_n).max(0.0) + gain)).min(0.5 * rocks / speed)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The step to take from `state`: near the surface `contact_step_s` (`step_s`, or what the
/// error control chose); in free flight up to `flight_step_max_s`, but only half the time
/// in which a footpad could reach the terrain (the ground's top, or a rock near it:
/// `rock_clearance`), approaching at the
/// CG speed plus rate times leg reach plus the speed gravity and thrust add within a
/// longest flight step, and not below `step_s` (with the error control, each footpad at its
/// own approach, `footpad_flight_step`, and not below `step_min_s`). Never beyond
/// `t_max_s`, nor past the next control event, and onto it where it is less than
/// `EVENT_DUST_S` further (what is left after the steps subtracted from it is their
/// rounding, not time).
#[must_use]
pub fn step_size(model: &Model, surface: &Surface, state: &State) -> f64 {
    let remaining = model.t_max_s - state.t_s;
    let mut dt = state.contact_step_s;
    if model.flight_step_max_s > model.step_s {
        let body = &state.body;
        let rotation = DMat3::from_quat(body.attitude);
        let normal_b = rotation.transpose() * surface.normal;
        // The footpads approach the terrain no faster than the CG's speed plus the rate
        // times the leg reach, plus what gravity adds within a longest flight step: in a
        // step `dt` of at most that length they cover at most `speed dt`, and half the
        // time to cover the clearance at `speed` keeps them off the terrain by half of it.
        // (No root of the fall under gravity: one division, no square root.)
        let speed = body.rate_rad_s.length() * model.leg_reach_m()
            + (body.velocity_m_s.length() + model.gravity_m_s2 * model.flight_step_max_s)
            + state.thrust.approach_m_s;
        // Each footpad's clearance of the ground's top and of the rocks.
        let clearance_of = |leg: &Leg, ls: &LegState| {
            let tip_b = leg.tip_m - leg.strut_axis * ls.stroke_m;
            let height = footpad_height(surface, body, normal_b, tip_b);
            let tip = body.position_m + rotation * tip_b;
            (
                height - model.ground_top_m(),
                rock_clearance(model, surface, tip, height),
            )
        };
        let clearance = model
            .legs
            .iter()
            .zip(&state.legs)
            .map(|(leg, ls)| {
                let (ground, rocks) = clearance_of(leg, ls);
                ground.min(rocks)
            })
            .fold(f64::INFINITY, f64::min);
        if clearance > 0.0 {
            let free = if model.step_control.is_some() {
                footpad_flight_step(model, surface, state, normal_b, speed, clearance_of)
            } else {
                0.5 * clearance / speed
            };
            // With the error control, down to its shortest step: the footpads land on the
            // surface within that, not within `step_s`.
            let floor = model.step_control.map_or(model.step_s, |c| c.step_min_s);
            dt = free.clamp(floor, model.flight_step_max_s);
        }
    }
    let dt = dt.min(remaining);
    let event = state.thrust.event_in_s;
    if event < dt + EVENT_DUST_S { event } else { dt }
}
