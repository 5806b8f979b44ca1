//! The step kernel: every leg's contact, then the rigid body, for `LANES` landers at once,
//! each with its own step length. The reference's `step` module does the same in scalar.

use crate::block::{Block, LegLanes, SurfaceLanes};
use crate::contact::{self, tip_in_body};
use crate::lane::{Lane, Mask, all_false, min_into, select_into};
use crate::params::Params;
use crate::rigid_body;
use crate::rocks::{RockClearance, contact_lanes};
use crate::terrain::height_lanes;
use crate::vec3::Vec3;

/// Penetration below the local surface along the local normal, and that normal, of a
/// footpad `height` above the base plane (`height_m` of `footpad_heights`), at `tip` on
/// rough terrain (the plane needs no position: its penetration is `-height`); with `TERRAIN`
/// among rocks too, the deeper of the ground's and a rock's contact, with the mask of the
/// lanes where it is the rock's (the reference's `Surface::contact_at`; `clear`, the
/// leg's memory of the rocks near it, read only among rocks, spares the lookup where none
/// can be met).
#[inline(always)]
fn penetration<L: Lane, const TERRAIN: bool>(
    p: &Params<L>,
    s: &SurfaceLanes<L>,
    clear: &mut RockClearance<L>,
    tip: impl FnOnce() -> Vec3<L>,
    height: L,
) -> (L, Vec3<L>, L::Mask) {
    if !TERRAIN {
        // The plane itself: no height, and its normal is already a unit vector.
        return (-height, s.normal, all_false::<L>());
    }
    let tip = tip();
    let (penetration, normal) = ground::<L>(p, s, tip, height);
    let Some(rocks) = &p.rocks else {
        return (penetration, normal, all_false::<L>());
    };
    // The rock stands on the local ground: the footpad's height above it is its clearance.
    let (rock, n_u, n_v, n_n) = contact_lanes(
        rocks,
        &s.rock_tile,
        s.tangent_u.dot(tip) + s.rock_offset_u_m,
        s.tangent_v.dot(tip) + s.rock_offset_v_m,
        -penetration,
        p.pad_radius_m,
        p.rock_abundance,
        clear,
    );
    let on_rock = rock.simd_gt(penetration);
    if on_rock.to_bitmask() == 0 {
        return (penetration, normal, on_rock);
    }
    let rock_normal = s.tangent_u * n_u + s.tangent_v * n_v + s.normal * n_n;
    (
        on_rock.select(rock, penetration),
        Vec3::select(on_rock, rock_normal, normal),
        on_rock,
    )
}

/// The ground's part of `penetration`: the terrain's or the plane's.
#[inline(always)]
fn ground<L: Lane>(p: &Params<L>, s: &SurfaceLanes<L>, tip: Vec3<L>, height: L) -> (L, Vec3<L>) {
    match &p.terrain {
        Some(t) => {
            let (h, dh_du, dh_dv) = height_lanes(
                t,
                &s.tile,
                s.tangent_u.dot(tip) + s.offset_u_m,
                s.tangent_v.dot(tip) + s.offset_v_m,
            );
            // Each lane's roughness (`Terrain::height`: the same products).
            let k = p.terrain_scale;
            let (h, dh_du, dh_dv) = (h * k, dh_du * k, dh_dv * k);
            let m = s.normal - s.tangent_u * dh_du - s.tangent_v * dh_dv;
            let inv = L::splat(1.0) / m.length();
            ((h - height) * inv, m * inv)
        }
        None => (-height, s.normal),
    }
}

/// Advances every lane of `block` by its `dt` (0 for lanes that must not move), from the
/// footpad heights of `footpad_heights`; with `THRUST`, under the thrust of `block.thrust`,
/// counting down to its next event.
#[inline(always)]
pub fn step<
    L: Lane,
    const DAMPERS: bool,
    const TERRAIN: bool,
    const THRUST: bool,
    const REGOLITH: bool,
>(
    p: &Params<L>,
    block: &mut Block<L>,
    dt: L,
) {
    let zero = L::splat(0.0);
    let rotation = block.rotation;
    let rate_i = rotation.mul_vec3(block.rate_rad_s);
    let mut force_n = Vec3::ZERO;
    // Moments about the CG, summed in I and turned into B once: (R a) x (R b) = R (a x b).
    let mut moment_i = Vec3::ZERO;
    let position = block.position_m;
    // Lanes with a footpad on the surface, and the least clearance of a footpad above the
    // local surface (for the error control alone).
    let mut touching = all_false::<L>();
    let mut nearest = L::splat(f64::INFINITY);
    let legs = p.legs.iter().zip(&mut block.legs).zip(&mut block.leg_step);
    for ((leg, leg_state), out) in legs {
        let tip_b = tip_in_body::<L, DAMPERS>(leg, leg_state.stroke_m);
        if DAMPERS {
            out.start_stroke_m = leg_state.stroke_m;
        }
        let (penetration, normal, on_rock) = penetration::<L, TERRAIN>(
            p,
            &block.surface,
            &mut out.rock_clear,
            move || position + rotation.mul_vec3(tip_b),
            out.height_m,
        );
        let contact = penetration.simd_gt(zero);
        touching |= contact;
        nearest = min_into(nearest, -penetration);
        // As the reference's `if penetration > 0`, for the whole block at once: a leg that
        // no lander (holding a sample) has on the surface adds nothing and forgets its
        // anchor. (Only legs on the surface need the footpad's position and velocity: the
        // outcome tracking reads the velocity of those alone, and finds the positions
        // itself where it needs them, `start_tips`.)
        let (normal_n, slipping) = if (contact & block.active).to_bitmask() == 0 {
            leg_state.anchored = all_false::<L>();
            (zero, all_false::<L>())
        } else {
            let arm = rotation.mul_vec3(tip_b);
            let tip = position + arm;
            let tip_velocity = block.velocity_m_s + rate_i.cross(arm);
            out.tip_velocity_m_s = tip_velocity;
            // The strut direction, footpad to hip, in I: the dampers' and the strut loads'.
            let strut_up = if p.struts_along_z {
                rotation.z_axis
            } else {
                -rotation.mul_vec3(leg.strut_axis)
            };
            let (f, normal_n, slipping) = contact::leg_force::<L, DAMPERS, REGOLITH>(
                p,
                dt,
                contact,
                penetration,
                normal,
                tip,
                tip_velocity,
                strut_up,
                on_rock,
                leg_state,
            );
            force_n += f;
            moment_i += arm.cross(f);
            strut_peaks(leg_state, f, strut_up, block.t_s);
            (normal_n, slipping)
        };
        out.penetration_m = penetration;
        out.normal_n = normal_n;
        out.slipping = slipping;
    }
    let contact_moment_n_m = rotation.transpose_mul_vec3(moment_i);
    // What the contact kicks the body with (`kick_scale`): the force and moment themselves
    // at a fixed step.
    let (mut kick_n, mut moment_n_m) = (force_n, contact_moment_n_m);
    if p.step_control {
        let scale = kick_scale(block, dt);
        control_step(p, block, force_n, contact_moment_n_m, touching, nearest, dt);
        kick_n = force_n * scale;
        moment_n_m = contact_moment_n_m * scale;
    }
    let mut thrust_n = Vec3::ZERO;
    if THRUST {
        thrust_n = rotation.mul_vec3(block.thrust.force_b_n);
        moment_n_m += block.thrust.moment_b_n_m;
        block.thrust.event_in_s -= dt;
    }
    block.start_t_s = block.t_s;
    block.dt_s = dt;
    block.start_position_m = block.position_m;
    block.start_velocity_m_s = block.velocity_m_s;
    block.start_rotation = rotation;
    block.start_rate_rad_s = block.rate_rad_s;
    block.force_n = force_n;
    block.moment_n_m = contact_moment_n_m;
    rigid_body::integrate::<L, THRUST>(
        &mut block.position_m,
        &mut block.velocity_m_s,
        &mut block.attitude,
        &mut block.rate_rad_s,
        p.inverse_mass_per_kg,
        p.inverse_inertia,
        p.gyroscopic,
        p.gravity_m_s2,
        kick_n,
        thrust_n,
        moment_n_m,
        dt,
    );
    block.rotation = block.attitude.to_mat3();
    add_time(&mut block.t_s, &mut block.t_error_s, dt);
}

/// What the contact force and moment of a step of length `dt` are scaled by with the error
/// control (the reference's `kick_scale`, which says why): `(dt_s + dt) / (2 dt)`, `dt_s`
/// the last step's length, where this one has a length; else 1.
#[inline(always)]
fn kick_scale<L: Lane>(block: &Block<L>, dt: L) -> L {
    let moving = dt.simd_gt(L::splat(0.0));
    moving.select(L::splat(0.5) * (block.dt_s + dt) / dt, L::splat(1.0))
}

/// The error control of the contact step (the reference's `control_step`, which says
/// why), from this step's contact force `force_n` (I) and moment `moment_n_m` (B) against
/// the last step's (`Block::force_n`, `moment_n_m`, `dt_s`, not yet overwritten): the next
/// contact step into `Block::contact_step_s`; in lanes with no footpad on the surface
/// (`touching`), the approach step from the footpads' least clearance `nearest` and this
/// step's length `dt`.
#[inline(always)]
fn control_step<L: Lane>(
    p: &Params<L>,
    block: &mut Block<L>,
    force_n: Vec3<L>,
    moment_n_m: Vec3<L>,
    touching: L::Mask,
    nearest: L,
    dt: L,
) {
    let previous = block.dt_s;
    let jump = (force_n - block.force_n) * p.inverse_mass_per_kg;
    let (change, inv) = (moment_n_m - block.moment_n_m, p.inverse_inertia);
    let turn = Vec3::new(change.x * inv.x, change.y * inv.y, change.z * inv.z);
    let reach = p.leg_reach_m;
    let change_squared = jump.length_squared() + turn.length_squared() * (reach * reach);
    let h = block.contact_step_s;
    let per = h * h / previous;
    let error_squared = L::splat(0.25) * per * per * change_squared;
    let measured = previous.simd_ge(p.step_min_s);
    let shrink = measured & error_squared.simd_gt(p.tolerance_squared);
    let grow = measured & (L::splat(64.0) * error_squared).simd_lt(p.tolerance_squared);
    let h = shrink.select(
        (L::splat(0.5) * h).fast_max(p.step_min_s),
        grow.select((L::splat(2.0) * h).fast_min(p.step_max_s), h),
    );
    // As the reference: half the time to cover what this step leaves of the clearance at
    // the fastest approach, between `step_min_s` and `step_s`.
    let speed = block.rate_rad_s.length().mul_add(
        p.leg_reach_m,
        block.velocity_m_s.length() + p.gravity_m_s2 * p.flight_step_max_s,
    ) + block.thrust.approach_m_s;
    let half = L::splat(0.5);
    let approach = (half * nearest / speed - half * dt)
        .fast_max(p.step_min_s)
        .fast_min(p.step_s);
    block.contact_step_s = touching.select(h, approach);
}

/// The strut loads of a leg whose footpad takes the force `f` (in I; 0 where it does not
/// touch), `strut_up` its strut's direction from the footpad to the hip: along the strut,
/// compressive positive, `A = f . strut_up`, and across it squared, `|f|^2 - A^2` (its root
/// only once, for the summary; the reference's `step::strut_loads`), into the leg's peaks
/// with the start `t_s` of the step (the first step of a peak: a NaN load, of a lane whose
/// state turned non-finite, is never above it). A leg off the surface in every lane takes
/// no step here: its loads are 0, never above a peak. Four selects every contact step,
/// without a test whether a lane set a peak: measured faster than the test (whose branch
/// goes both ways while loads rise), the same bytes; each stored whole (`select_into`), not
/// as a masked store.
#[inline(always)]
fn strut_peaks<L: Lane>(leg: &mut LegLanes<L>, f: Vec3<L>, strut_up: Vec3<L>, t_s: L) {
    let axial = f.dot(strut_up);
    let side_squared = axial.mul_neg_add(axial, f.length_squared());
    let higher = axial.simd_gt(leg.peak_axial_n);
    let higher_side = side_squared.simd_gt(leg.peak_side_squared);
    select_into(&mut leg.peak_axial_n, higher, axial);
    select_into(&mut leg.peak_axial_s, higher, t_s);
    select_into(&mut leg.peak_side_squared, higher_side, side_squared);
    select_into(&mut leg.peak_side_s, higher_side, t_s);
}

/// `t += dt`, compensated (Kahan): `error` keeps what rounding dropped and the next step
/// adds it back, so the time stays exact to a rounding of `t` however many steps are
/// summed: plain sums of 1 ms steps in f32 lose 27 ms by t = 70 s and 54 ms by 120 s (every
/// addition in a binade rounds alike), compensated ones stay within half an ulp (test
/// `compensated_time_stays_within_a_rounding`). The same in f64 and in the reference.
#[inline(always)]
pub fn add_time<L: Lane>(t: &mut L, error: &mut L, dt: L) {
    let y = dt - *error;
    let sum = *t + y;
    *error = (sum - *t) - y;
    *t = sum;
}

/// Every footpad's height above the base plane at the start of the step, into `leg_step`
/// (`height_m`), and the least of them: the CG's height plus the footpad's offset from it
/// along the normal, taken in B, where the footpads are (the reference's `footpad_height`).
#[inline(always)]
pub fn footpad_heights<L: Lane, const DAMPERS: bool>(p: &Params<L>, block: &mut Block<L>) -> L {
    let normal = block.surface.normal;
    let normal_b = block.rotation.transpose_mul_vec3(normal);
    let height = normal.dot(block.position_m);
    let mut lowest = L::splat(f64::INFINITY);
    let legs = p.legs.iter().zip(&block.legs).zip(&mut block.leg_step);
    for ((leg, state), out) in legs {
        out.height_m = height + normal_b.dot(tip_in_body::<L, DAMPERS>(leg, state.stroke_m));
        lowest = min_into(lowest, out.height_m);
    }
    lowest
}

/// Below this, what would be left of the time to a control event after a step is the
/// rounding of the steps subtracted from it, not time, s: the step ends on the event
/// instead of leaving a step of 1e-17 s to reach it (the reference's `step_size` too).
pub const EVENT_DUST_S: f64 = 1e-12;

/// The step every lane takes (see the reference's `step_size`), given the least height of
/// its footpads above the base plane (`footpad_heights`): `contact_step_s` near the surface
/// (`step_s`, or what the error control chose), longer in free flight where no footpad can
/// reach the terrain within it (among rocks, the rocks near it: `rock_clearance`); 0 for
/// empty lanes. With `THRUST`, never past the lane's next control event, and onto it where
/// it is less than `EVENT_DUST_S` further. Rocks come only with `TERRAIN`: the loops of the
/// plane do not hold their code.
#[inline(always)]
#[must_use]
pub fn step_size<L: Lane, const DAMPERS: bool, const TERRAIN: bool, const THRUST: bool>(
    p: &Params<L>,
    block: &Block<L>,
    lowest: L,
) -> L {
    let remaining = p.t_max_s - block.t_s;
    let mut dt = block.contact_step_s;
    if p.long_flight_steps {
        // As the reference's `if clearance > 0`: only lanes in free flight need the rest
        // (among rocks, those clear of the ground may be).
        let clearance = lowest - p.ground_top_m;
        let above = clearance.simd_gt(L::splat(0.0)) & block.active;
        if above.to_bitmask() != 0 {
            // As the reference: the fastest approach within a longest flight step.
            let mut speed = block.rate_rad_s.length().mul_add(
                p.leg_reach_m,
                block.velocity_m_s.length() + p.gravity_m_s2 * p.flight_step_max_s,
            );
            if THRUST {
                speed += block.thrust.approach_m_s;
            }
            let rocks = TERRAIN && p.rocks.is_some();
            let (clearance, free) = match (rocks, p.step_control) {
                (false, false) => (clearance, L::splat(0.5) * clearance / speed),
                (false, true) => (
                    clearance,
                    footpad_flight_step::<L, DAMPERS, THRUST, false>(p, block, above, speed).1,
                ),
                (true, false) => {
                    let clearance = least_clearance::<L, DAMPERS>(p, block, above);
                    (clearance, L::splat(0.5) * clearance / speed)
                }
                (true, true) => {
                    footpad_flight_step::<L, DAMPERS, THRUST, true>(p, block, above, speed)
                }
            };
            let flying = clearance.simd_gt(L::splat(0.0));
            // (The bounds are never NaN: `fast_` versions give the same.)
            // (`step_min_s` is `step_s` without the error control.)
            let free = free.fast_max(p.step_min_s).fast_min(p.flight_step_max_s);
            dt = flying.select(free, dt);
        }
    }
    let dt = block.active.select(dt.min(remaining), L::splat(0.0));
    if THRUST {
        let event = block.thrust.event_in_s;
        let onto = event.simd_lt(dt + L::splat(EVENT_DUST_S)) & block.active;
        onto.select(event, dt.min(event))
    } else {
        dt
    }
}

/// The reference's `rock_clearance` for one leg of every lane of `near` (whose footpads
/// are all clear of the ground; in the other lanes, `height - terrain_top_m`, which its
/// lowest footpad's clearance of the ground bounds anyway): how far the footpad, `height`
/// above the base plane, can move in any direction and meet no rock. A scalar lookup per
/// lane of `near` (`Rocks::contact_clear`), on the plane; on rough terrain, the terrain's
/// top.
#[inline(always)]
fn rock_clearance<L: Lane>(
    p: &Params<L>,
    block: &Block<L>,
    tip_b: Vec3<L>,
    height: L,
    near: L::Mask,
) -> L {
    let mut clear = height - p.terrain_top_m;
    let (Some(rocks), None) = (&p.rocks, &p.terrain) else {
        return clear;
    };
    let s = &block.surface;
    let tip = block.position_m + block.rotation.mul_vec3(tip_b);
    let (u, v) = (
        s.tangent_u.dot(tip) + s.rock_offset_u_m,
        s.tangent_v.dot(tip) + s.rock_offset_v_m,
    );
    let mut lanes = near.to_bitmask();
    while lanes != 0 {
        let i = lanes.trailing_zeros() as usize;
        lanes &= lanes - 1;
        let (height, pad_radius) = (height.lane(i), p.pad_radius_m.lane(i));
        let (_, gap) = rocks.contact_clear(
            s.rock_tile[i],
            u.lane(i),
            v.lane(i),
            height,
            pad_radius,
            p.rock_abundance.lane(i),
            rocks.skin_m(pad_radius),
        );
        clear.set_lane(i, gap.max(clear.lane(i)));
    }
    clear
}

/// Among rocks, without the error control, the least clearance of a lane's footpads: of
/// the ground and of the rocks (`rock_clearance`), for the lanes of `near`.
#[inline(always)]
fn least_clearance<L: Lane, const DAMPERS: bool>(
    p: &Params<L>,
    block: &Block<L>,
    near: L::Mask,
) -> L {
    let mut least = L::splat(f64::INFINITY);
    let mut near = near;
    let legs = p.legs.iter().zip(&block.legs).zip(&block.leg_step);
    for ((leg, state), at) in legs {
        let tip_b = tip_in_body::<L, DAMPERS>(leg, state.stroke_m);
        let ground = at.height_m - p.ground_top_m;
        let rocks = rock_clearance(p, block, tip_b, at.height_m, near);
        least = min_into(least, ground.min(rocks));
        // A lane with a footpad on a rock is not in free flight: no more lookups for it.
        near &= least.simd_gt(L::splat(0.0));
    }
    least
}

/// With the error control, each lane's free-flight step from each footpad's own clearance
/// and approach (the reference's `footpad_flight_step`, which says why), from the footpad
/// heights of `footpad_heights`; with `ROCKS`, also half the time in which the footpad
/// could reach a rock at `speed` (`rock_clearance`), and the least clearance of its
/// footpads of the ground and the rocks, as `least_clearance` (without, its first part is
/// not computed).
#[inline(always)]
fn footpad_flight_step<L: Lane, const DAMPERS: bool, const THRUST: bool, const ROCKS: bool>(
    p: &Params<L>,
    block: &Block<L>,
    mut near: L::Mask,
    speed: L,
) -> (L, L) {
    let zero = L::splat(0.0);
    let w = block.rate_rad_s;
    let reach = p.leg_reach_m;
    let mut gain =
        (L::splat(2.0) * w.length_squared()).mul_add(reach, p.gravity_m_s2) * p.flight_step_max_s;
    if THRUST {
        gain += block.thrust.approach_m_s;
    }
    let normal = block.surface.normal;
    let along = normal.dot(block.velocity_m_s);
    let normal_b = block.rotation.transpose_mul_vec3(normal);
    let mut least_clearance = L::splat(f64::INFINITY);
    let mut least = L::splat(f64::INFINITY);
    let legs = p.legs.iter().zip(&block.legs).zip(&block.leg_step);
    for ((leg, state), at) in legs {
        let tip_b = tip_in_body::<L, DAMPERS>(leg, state.stroke_m);
        let clearance = at.height_m - p.ground_top_m;
        let v_n = along + w.dot(tip_b.cross(normal_b));
        let mut free = L::splat(0.5) * clearance / ((-v_n).fast_max(zero) + gain);
        if ROCKS {
            let rocks = rock_clearance(p, block, tip_b, at.height_m, near);
            least_clearance = min_into(least_clearance, clearance.min(rocks));
            free = free.min(L::splat(0.5) * rocks / speed);
            // A lane with a footpad on a rock is not in free flight (its step is not this
            // one): no more lookups for it.
            near &= least_clearance.simd_gt(zero);
        }
        least = min_into(least, free);
    }
    (least_clearance, least)
}

/// What `advance` did: how many steps it took, `outcome_bits` of the last one, and the
/// lanes it brought to a control event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Advanced {
    /// Steps taken (at least 1, at most the number asked for).
    pub steps: u32,
    /// `outcome_bits` of the last step: 0 when it decided no lane and needs no recentring.
    pub bits: u32,
    /// Lanes (lane `i` in bit `i`) whose next control event came with the last step: the
    /// control loop must set their thrust (`Block::set_thrust`) before the next step.
    pub events: u32,
}

/// Up to `steps` steps of every lane holding a sample (each its step size, the step, the
/// outcome tracking), stopping after the first step that decides a lane, asks for a
/// lane to be recentred or brings one to a control event: the caller then takes over, with
/// `bits` and `events` saying which lanes.
/// A call runs many steps, so the three parts are inlined into one loop and nothing but
/// the block's state crosses from one step to the next (one call per step, with the parts
/// as functions of their own, measured 15-19 % slower).
///
/// The loop is compiled once for each combination of dampers, rough terrain, thrust and
/// regolith, and the parameters pick one: the step then tests for none of them (a test per
/// leg and step, and code that the compiler would otherwise hoist out of the tests: a
/// division per step for dampers that are not there), and a lander without thrusters or
/// regolith pays nothing for them. `C` (`Loop`) compiles each combination's loop for the
/// lane type's instruction set (`isa`).
#[inline(always)]
pub fn advance<L: Lane, C: Loop<L>>(p: &Params<L>, block: &mut Block<L>, steps: u32) -> Advanced {
    match (
        p.honeycomb.is_some(),
        p.terrain.is_some() || p.rocks.is_some(),
        p.thrust,
        p.soil.is_some(),
    ) {
        (false, false, false, false) => C::run::<false, false, false, false>(p, block, steps),
        (true, false, false, false) => C::run::<true, false, false, false>(p, block, steps),
        (false, true, false, false) => C::run::<false, true, false, false>(p, block, steps),
        (true, true, false, false) => C::run::<true, true, false, false>(p, block, steps),
        (false, false, true, false) => C::run::<false, false, true, false>(p, block, steps),
        (true, false, true, false) => C::run::<true, false, true, false>(p, block, steps),
        (false, true, true, false) => C::run::<false, true, true, false>(p, block, steps),
        (true, true, true, false) => C::run::<true, true, true, false>(p, block, steps),
        (false, false, false, true) => C::run::<false, false, false, true>(p, block, steps),
        (true, false, false, true) => C::run::<true, false, false, true>(p, block, steps),
        (false, true, false, true) => C::run::<false, true, false, true>(p, block, steps),
        (true, true, false, true) => C::run::<true, true, false, true>(p, block, steps),
        (false, false, true, true) => C::run::<false, false, true, true>(p, block, steps),
        (true, false, true, true) => C::run::<true, false, true, true>(p, block, steps),
        (false, true, true, true) => C::run::<false, true, true, true>(p, block, steps),
        (true, true, true, true) => C::run::<true, true, true, true>(p, block, steps),
    }
}

/// How a lane type compiles the loop of each combination (`advance_with`). The AVX2 and
/// AVX-512 kernels give each its own function: the sixteen inlined into one, as they were,
/// ran the default sweep at 0.89x (f64 AVX2 on the 2-core AMD EPYC machine, alternated, 2e5
/// samples, 1 thread; f32 at 0.96x): the register allocation of the one huge function
/// spilled more in the hot loop.
pub trait Loop<L: Lane> {
    /// `advance_with::<L, DAMPERS, TERRAIN, THRUST, REGOLITH>`.
    fn run<const DAMPERS: bool, const TERRAIN: bool, const THRUST: bool, const REGOLITH: bool>(
        p: &Params<L>,
        block: &mut Block<L>,
        steps: u32,
    ) -> Advanced;
}

/// `Loop` for lane types compiled for the target's own instruction set (the portable
/// ones): each combination inlined where `advance` is, the sixteen in the one function
/// (`#[inline(never)]`) of the lane type's `Kernel::advance`. Apart, the SSE2 kernel ran the
/// default sweep (f64, 5e4 samples, 1 thread, on the AMD EPYC machine) at 0.93x of
/// c1e5b60's, alternated; inlined, at 0.98x.
pub struct PlainLoop;

impl<L: Lane> Loop<L> for PlainLoop {
    #[inline(always)]
    fn run<const DAMPERS: bool, const TERRAIN: bool, const THRUST: bool, const REGOLITH: bool>(
        p: &Params<L>,
        block: &mut Block<L>,
        steps: u32,
    ) -> Advanced {
        advance_with::<L, DAMPERS, TERRAIN, THRUST, REGOLITH>(p, block, steps)
    }
}

/// `advance` with (`DAMPERS`) or without dampers, on rough terrain or among rocks
/// (`TERRAIN`) or on a plane,
/// with (`THRUST`) or without a control loop, on regolith (`REGOLITH`) or the elastic
/// surface.
#[inline(always)]
pub fn advance_with<
    L: Lane,
    const DAMPERS: bool,
    const TERRAIN: bool,
    const THRUST: bool,
    const REGOLITH: bool,
>(
    p: &Params<L>,
    block: &mut Block<L>,
    steps: u32,
) -> Advanced {
    for taken in 1..=steps {
        let lowest = footpad_heights::<L, DAMPERS>(p, block);
        let dt = step_size::<L, DAMPERS, TERRAIN, THRUST>(p, block, lowest);
        step::<L, DAMPERS, TERRAIN, THRUST, REGOLITH>(p, block, dt);
        let decided = crate::outcome::observe::<L, DAMPERS, THRUST>(p, block);
        let bits = outcome_bits(block, decided);
        let events = if THRUST {
            (block.thrust.event_in_s.simd_le(L::splat(0.0)) & block.active & !decided).to_bitmask()
        } else {
            0
        };
        if bits != 0 || events != 0 {
            return Advanced {
                steps: taken,
                bits,
                events,
            };
        }
    }
    Advanced {
        steps,
        bits: 0,
        events: 0,
    }
}

/// What `advance` returns: the lanes decided (mask `decided`) in bits 0-15 (lane `i` in
/// bit `i`), and in bits 16-31 the undecided lanes whose CG's foot on the base plane is
/// farther than `L::RECENTRE_M` from the origin, for `Block::recentre` (never, in f64
/// lanes). The foot, not the CG: recentring moves the origin along the plane, so a lander
/// high above it would otherwise ask again at every step.
#[inline(always)]
#[must_use]
pub fn outcome_bits<L: Lane>(block: &Block<L>, decided: L::Mask) -> u32 {
    if L::RECENTRE_M.is_infinite() {
        // f64 lanes: nothing to compute (a constant, so the test costs nothing either).
        return decided.to_bitmask();
    }
    let reach = L::splat(L::RECENTRE_M * L::RECENTRE_M);
    let x = block.position_m;
    let height = block.surface.normal.dot(x);
    let along_squared = height.mul_neg_add(height, x.length_squared());
    let far = along_squared.simd_gt(reach) & block.active & !decided;
    decided.to_bitmask() | (far.to_bitmask() << 16)
}

#[cfg(test)]
mod tests {
    use super::add_time;
    use crate::lane::Lane;
    use wide::{f32x16, f64x8};

    /// Sums `n` steps of `dt` (as the lanes hold it) plainly and with `add_time`; returns
    /// both errors against the exact sum (in f64, exact for these counts: n dt has at most
    /// 24 + 19 significant bits), s.
    fn errors<L: Lane>(dt: f64, n: u32) -> (f64, f64) {
        let dt = L::splat(dt);
        let (mut plain, mut t, mut error) = (L::ZERO, L::ZERO, L::ZERO);
        for _ in 0..n {
            plain += dt;
            add_time(&mut t, &mut error, dt);
        }
        let exact = dt.lane(0) * f64::from(n);
        (plain.lane(0) - exact, t.lane(0) - exact)
    }

    /// 120 s of 1 ms steps and 70 s of 0.5 ms and 1 ms steps: in f32 a plain sum drifts by
    /// milliseconds (every addition rounds the same way within a binade), the compensated
    /// one stays within a rounding of its value (half an ulp: 3.8e-6 s at 64-128 s); in f64
    /// both are close, the compensated one again within half an ulp (7.1e-15 s).
    #[test]
    fn compensated_time_stays_within_a_rounding() {
        for (dt, n) in [
            (1e-3, 120_000),
            (1e-3, 70_000),
            (5e-4, 140_000),
            (1e-4, 300_000),
        ] {
            let (plain, compensated) = errors::<f32x16>(dt, n);
            println!(
                "f32 {dt} s x {n}: plain sum off by {plain:.3e} s, compensated {compensated:.3e} s"
            );
            let t = dt * f64::from(n);
            let half_ulp = f64::from(f32::EPSILON) * t.log2().floor().exp2() / 2.0;
            assert!(
                compensated.abs() <= half_ulp,
                "f32 {dt} x {n}: {compensated}"
            );
            assert!(
                plain.abs() > 1e-3,
                "f32 {dt} x {n}: plain sum off by only {plain}"
            );
            let (_, compensated) = errors::<f64x8>(dt, n);
            let half_ulp = f64::EPSILON * t.log2().floor().exp2() / 2.0;
            assert!(
                compensated.abs() <= half_ulp,
                "f64 {dt} x {n}: {compensated}"
            );
        }
    }
}
