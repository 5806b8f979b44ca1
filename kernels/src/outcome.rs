//! Outcome tracking over lanes: the reference's `outcome::Tracker::observe`, rule for rule
//! and in the same order (see there for the rules).

use crate::block::{Block, LegStep};
use crate::contact::tip_in_body;
use crate::lane::{Lane, Mask, all_false, all_true, max_into, min_into};
use crate::params::Params;
use crate::vec3::{Mat3, Vec3};

/// Outcome codes, in the order of the reference's `Outcome::ALL`.
pub const STABLE: f64 = 0.0;
/// Code of `tipped`.
pub const TIPPED: f64 = 1.0;
/// Code of `sliding`.
pub const SLIDING: f64 = 2.0;
/// Code of `bouncing`.
pub const BOUNCING: f64 = 3.0;
/// Code of `diverged`.
pub const DIVERGED: f64 = 4.0;
/// Code of `held` (in contact at `t_max`, the control loop still powered).
pub const HELD: f64 = 5.0;

/// A leg within this gap of the surface bears on it for the rest rule of `stable`, m. A
/// lander balanced on two footpads with a third one hovering at nanometres, on and off
/// contact with forces of 0.01 N, is at rest on three legs: without the gap the rule never
/// held for the hold time and such landers ended `sliding` at t_max though they did not
/// move. 1 micrometre is far below any penetration of the contact law under load.
pub const REST_GAP_M: f64 = 1e-6;

/// A footpad whose friction anchor moved by more than this since the rest began has slipped,
/// m, and the lander is not at rest. The anchor moves only while the friction is at its cap
/// (MODEL.md section 5), so a lander that slides moves it at its own speed: set down from
/// rest 1 deg above the friction angle it slides ~0.5 mm within a 2 s hold. A footpad that
/// only sits at its cap (the damping of the half-step gravity velocity keeps a loaded
/// downhill footpad there) leaves its anchor where it is. A speed threshold cannot tell the
/// two apart: both are slower than any rest speed in milligravity.
pub const REST_SLIP_M: f64 = 1e-6;

/// The early `sliding` rule's band on the contact force: the normal forces of a settled
/// slide sum to the weight's normal share `m g cos(slope)` within this fraction of it. The
/// band excludes impacts and rocking (the sum swings far beyond it) and admits the settled
/// slide, whose sum stayed within 1.1e-3 of the share over the last 4.7 s of a traced
/// slide (sample 59 of the MuJoCo-matched scenario, rules off).
pub const SLIDE_FORCE_BAND: f64 = 0.1;

/// The early `sliding` rule's least share of a leg: every leg bears at least this fraction
/// of the mean normal force. A slide tips over a leg only after the legs behind it unload;
/// the settled slide of the MuJoCo-matched lander (friction 0.5) loads its lightest leg
/// with `1 - mu h / r` = 0.47 of the mean sliding along a side (computed), and with at
/// least 0.33 in the traced slide of `SLIDE_FORCE_BAND`, which turns as it slides.
pub const SLIDE_LEG_SHARE: f64 = 0.25;

/// The early `sliding` rule's margin against tipping in a slide: the CG's foot on the plane
/// lies inside every edge of the support polygon by more than this times `mu h` (`h` the
/// CG's height). Sliding, the contact force meets the plane `mu h` ahead of the CG's foot
/// in the direction of the slide; a lander that turns about the normal as it slides may
/// bring any edge to face that way, so every edge must be clear of it.
pub const SLIDE_EDGE_MARGIN: f64 = 1.25;

/// The early `bouncing` rule's margin on the fastest turn `|L| / I_min`: the integrator
/// keeps `|L|` of a free flight to 1.5e-5 at 0.5 rad/s and the longest flight step
/// (measured in the reference's `free_flight_keeps_the_angular_momentum`); 10 % more turn
/// than the bound allows covers that thousands of times.
pub const TURN_MARGIN: f64 = 1.1;

/// Puts every footpad's position at the start of the step into `leg_step` (`tip_m`), for
/// the rules that need them (the step itself finds them only for legs on the surface).
#[inline(always)]
fn start_tips<L: Lane, const DAMPERS: bool>(
    p: &Params<L>,
    legs: &mut [LegStep<L>],
    x: Vec3<L>,
    r: Mat3<L>,
) {
    for (leg, step) in p.legs.iter().zip(legs) {
        step.tip_m = x + r.mul_vec3(tip_in_body::<L, DAMPERS>(leg, step.start_stroke_m));
    }
}

/// Mask: every one of `xs` is finite. `x * 0` is 0 for a finite `x` and NaN for an infinite
/// or NaN one, so the sum of the products is 0 exactly when all are finite.
#[inline(always)]
fn all_finite<L: Lane, const N: usize>(xs: [L; N]) -> L::Mask {
    let zero = L::splat(0.0);
    xs.iter()
        .fold(zero, |sum, x| x.mul_add(zero, sum))
        .simd_eq(zero)
}

/// Takes in the step just made; returns the mask of lanes decided by it (their code is in
/// `block.track.outcome`).
#[inline(always)]
pub fn observe<L: Lane, const DAMPERS: bool, const THRUST: bool>(
    p: &Params<L>,
    block: &mut Block<L>,
) -> L::Mask {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let active = block.active & block.track.outcome.simd_lt(zero);
    let t = &mut block.track;
    t.steps += active.select(one, zero);
    // The specific force (what an accelerometer reads): contact and, with a control loop,
    // the thrust of the step (in I, turned as the step turned it), not gravity.
    let mut force = block.force_n;
    if THRUST {
        force += block.start_rotation.mul_vec3(block.thrust.force_b_n);
    }
    let acceleration = force * p.inverse_mass_per_kg;
    // The accumulators below (peaks, least tilt cosine, deepest penetration) start finite
    // and never become NaN: `max_into` and `min_into` apply.
    t.peak_acceleration_squared =
        max_into(t.peak_acceleration_squared, acceleration.length_squared());
    let z_body = block.start_rotation.z_axis;
    t.peak_acceleration_z = max_into(t.peak_acceleration_z, acceleration.dot(z_body).abs());
    let cos_tilt = z_body.dot(block.surface.normal);
    t.min_cos_tilt = min_into(t.min_cos_tilt, cos_tilt);

    let mut contacts = zero;
    let mut resting = zero;
    let mut deepest = L::splat(f64::NEG_INFINITY);
    let rest_gap = L::splat(-REST_GAP_M);
    let mut all_slipping = all_true::<L>();
    for (leg, step) in block.legs.iter_mut().zip(&block.leg_step) {
        leg.peak_normal_n = max_into(leg.peak_normal_n, step.normal_n);
        contacts += step.penetration_m.simd_gt(zero).select(one, zero);
        all_slipping &= step.slipping;
        resting += step.penetration_m.simd_gt(rest_gap).select(one, zero);
        deepest = max_into(deepest, step.penetration_m);
    }
    // From the second step of a rest on: every footpad on the surface still sticks where it
    // stuck when the rest began. (Only blocks with a lane at rest load the anchors.)
    let in_rest = t.rest_s.simd_gt(zero);
    let mut stuck = all_true::<L>();
    if (in_rest & active).to_bitmask() != 0 {
        let rest_slip_squared = L::splat(REST_SLIP_M * REST_SLIP_M);
        for leg in &block.legs {
            let slid = (leg.anchor_m - leg.rest_anchor_m).length_squared();
            stuck &= !leg.anchored | slid.simd_le(rest_slip_squared);
        }
        stuck |= !in_rest;
    }
    t.max_penetration = max_into(t.max_penetration, deepest);
    let touching = contacts.simd_gt(zero);
    if THRUST {
        block.thrust.touched |= touching;
    }
    // The state at the start of the first contact's step, and its deepest leg, by the
    // user's number (the lowest on a tie).
    let first = touching & t.first_contact_s.is_nan();
    if first.to_bitmask() != 0 {
        let (mut leg, mut deepest) = (zero, L::splat(f64::NEG_INFINITY));
        for (k, &i) in p.leg_index.iter().enumerate() {
            let step = &block.leg_step[i];
            let deeper = step.penetration_m.simd_gt(deepest);
            leg = deeper.select(L::splat(k as f64), leg);
            deepest = deeper.select(step.penetration_m, deepest);
        }
        let r = &block.start_rotation;
        t.met_velocity_m_s = Vec3::select(first, block.start_velocity_m_s, t.met_velocity_m_s);
        t.met_rate_rad_s = Vec3::select(first, block.start_rate_rad_s, t.met_rate_rad_s);
        t.met_x_body = Vec3::select(first, r.x_axis, t.met_x_body);
        t.met_z_body = Vec3::select(first, r.z_axis, t.met_z_body);
        t.met_leg = first.select(leg, t.met_leg);
    }
    t.first_contact_s =
        (touching & t.first_contact_s.is_nan()).select(block.start_t_s, t.first_contact_s);
    let lifted = !touching & t.touched & (-deepest).simd_gt(p.bounce_clearance_m);
    t.bounces += lifted.select(one, zero);
    t.touched = touching | (t.touched & !lifted);

    let (x, v, w, q) = (
        &block.position_m,
        &block.velocity_m_s,
        &block.rate_rad_s,
        &block.attitude,
    );
    // A NaN or infinite velocity or rate fails its bound (every compare with NaN is
    // false), so only the position and the attitude need the test of finiteness.
    let bounded = all_finite([x.x, x.y, x.z, q.x, q.y, q.z, q.w])
        & v.length_squared().simd_le(p.diverged_speed_squared)
        & w.length_squared().simd_le(p.diverged_rate_squared);
    let diverged = !bounded | deepest.simd_gt(p.diverged_penetration_m);

    // The rest rule's tests of speed, rate and legs, before its tests of the footpads and
    // the support polygon.
    let slow = block
        .start_velocity_m_s
        .length_squared()
        .simd_lt(p.rest_speed_squared)
        & block
            .start_rate_rad_s
            .length_squared()
            .simd_lt(p.rest_rate_squared)
        & resting.simd_ge(p.rest_contacts);
    let mut inside = !all_false::<L>();
    let mut tipping = all_false::<L>();
    let two_contacts = contacts.simd_eq(L::splat(2.0));
    // The edges matter only to a lane that may pivot on two footpads (early tipping) or may
    // be at rest (CG over the polygon); a block with neither in any lane (in flight, or
    // moving on more legs) skips them: `tipping` and `inside` would change nothing.
    let pivot_or_rest = (if p.early_tipping {
        two_contacts
    } else {
        all_false::<L>()
    }) | slow;
    if !p.edges.is_empty() && pivot_or_rest.to_bitmask() != 0 {
        start_tips::<L, DAMPERS>(
            p,
            &mut block.leg_step,
            block.start_position_m,
            block.start_rotation,
        );
        let quasi_static = block
            .force_n
            .length_squared()
            .simd_le(p.quasi_static_force_squared);
        let n = block.leg_step.len() as f64;
        let centroid =
            block.leg_step.iter().fold(Vec3::ZERO, |c, l| c + l.tip_m) * L::splat(1.0 / n);
        // Seen along gravity: `outward` is horizontal, so only x and y enter its products.
        for [i, j] in &p.edges {
            let (a, c) = (&block.leg_step[*i], &block.leg_step[*j]);
            let edge = c.tip_m - a.tip_m;
            let mut outward = Vec3::new(edge.y, -edge.x, zero);
            outward = Vec3::select(
                outward.dot_xy(centroid - a.tip_m).simd_gt(zero),
                -outward,
                outward,
            );
            let beyond = outward
                .dot_xy(block.start_position_m - a.tip_m)
                .simd_gt(zero);
            inside &= !beyond;
            let pivot = two_contacts
                & a.penetration_m.simd_gt(zero)
                & c.penetration_m.simd_gt(zero)
                & !a.slipping
                & !c.slipping;
            let away = outward
                .dot_xy(block.start_velocity_m_s - a.tip_velocity_m_s)
                .simd_gt(zero);
            tipping |= beyond & pivot & away & quasi_static;
        }
    }
    // A lander whose control loop may still fire is not left to itself: no rest, and no
    // early rule, counts for it (MODEL.md section 8).
    let passive = if THRUST {
        !block.thrust.powered
    } else {
        all_true::<L>()
    };
    let tipped = cos_tilt.simd_lt(zero)
        | (if p.early_tipping {
            tipping & passive
        } else {
            all_false::<L>()
        });

    let at_rest = slow & stuck & inside & passive;
    // A rest that begins with this step remembers where the footpads stick.
    let starting = at_rest & !in_rest;
    if (starting & active).to_bitmask() != 0 {
        for leg in &mut block.legs {
            leg.rest_anchor_m = Vec3::select(starting, leg.anchor_m, leg.rest_anchor_m);
        }
    }
    t.rest_s = at_rest.select(t.rest_s + block.dt_s, zero);
    let stable = t.rest_s.simd_ge(p.hold_time_s);
    let ended = block.t_s.simd_ge(p.t_max_s);

    // The early rules, in lanes that no rule above decided. (Only blocks with a lane where
    // every footpad slips, or with one in flight, compute them.)
    let open = active & !(diverged | tipped | stable | ended) & passive;
    let mut slide = all_false::<L>();
    if p.early_sliding && (all_slipping & open).to_bitmask() != 0 {
        slide = all_slipping & steady_slide::<L, DAMPERS>(p, block) & passive;
    }
    let mut flight_over = all_false::<L>();
    if p.early_bouncing {
        let flying = !touching;
        if (flying & open).to_bitmask() != 0 {
            flight_over = flying & cannot_return(p, block) & passive;
        }
    }

    let decided = active & (diverged | tipped | stable | ended | slide | flight_over);
    // Most steps decide nothing: they need no outcome code.
    if decided.to_bitmask() != 0 {
        // At t_max, at rest since before this step: its footpads were seen to stick (on
        // the first step of a rest they are not checked, and a slow slider would pass every
        // other step).
        // In contact with the loop still powered: `held` (only lanes with a control loop).
        let on_surface = if THRUST {
            passive.select(L::splat(SLIDING), L::splat(HELD))
        } else {
            L::splat(SLIDING)
        };
        let at_end = (at_rest & in_rest).select(
            L::splat(STABLE),
            touching.select(on_surface, L::splat(BOUNCING)),
        );
        let code = diverged.select(
            L::splat(DIVERGED),
            tipped.select(
                L::splat(TIPPED),
                stable.select(
                    L::splat(STABLE),
                    ended.select(at_end, slide.select(L::splat(SLIDING), L::splat(BOUNCING))),
                ),
            ),
        );
        block.track.outcome = decided.select(code, block.track.outcome);
    }
    decided
}

/// Mask: the speed stays below the divergence threshold until `t_max` (the reference's
/// `speed_bounded`).
#[inline(always)]
fn speed_bounded<L: Lane>(p: &Params<L>, block: &Block<L>) -> L::Mask {
    let two = L::splat(2.0);
    let g_remaining = p.gravity_m_s2 * (p.t_max_s - block.t_s);
    (two * block.velocity_m_s.length_squared() + two * (g_remaining * g_remaining))
        .simd_lt(p.diverged_speed_squared)
}

/// Mask: the step just made is one of a steady slide (the reference's `steady_slide`; the
/// caller checks that every footpad slips). The cheap tests first: a block where no lane
/// passes them skips the rest.
#[inline(always)]
fn steady_slide<L: Lane, const DAMPERS: bool>(p: &Params<L>, block: &mut Block<L>) -> L::Mask {
    let zero = L::splat(0.0);
    let n = block.surface.normal;
    let steep = (n.x * n.x + n.y * n.y).simd_gt(p.friction_coefficient_squared * (n.z * n.z));
    let moving_down = block.velocity_m_s.z.simd_lt(zero);
    let weight_share = p.weight_n * n.z;
    let mut total = zero;
    let mut least = L::splat(f64::INFINITY);
    for step in &block.leg_step {
        total += step.normal_n;
        least = min_into(least, step.normal_n);
    }
    let settled = (total - weight_share)
        .abs()
        .simd_le(L::splat(SLIDE_FORCE_BAND) * weight_share);
    let borne = least.simd_ge(L::splat(SLIDE_LEG_SHARE) / p.leg_count * total);
    let cheap = steep & moving_down & settled & borne & block.active;
    if cheap.to_bitmask() == 0 {
        return all_false::<L>();
    }
    let w = block.rate_rad_s;
    let spin = w.dot(block.rotation.transpose_mul_vec3(n));
    let rocking_squared = w.length_squared() - spin * spin;
    let steady_attitude = rocking_squared.simd_lt(p.rest_rate_squared);
    start_tips::<L, DAMPERS>(
        p,
        &mut block.leg_step,
        block.start_position_m,
        block.start_rotation,
    );
    cheap & steady_attitude & inside_by(p, block) & speed_bounded(p, block)
}

/// Mask: the CG's foot on the plane lies inside every edge of the support polygon by more
/// than `SLIDE_EDGE_MARGIN mu h` (the reference's `inside_by`).
#[inline(always)]
fn inside_by<L: Lane>(p: &Params<L>, block: &Block<L>) -> L::Mask {
    let zero = L::splat(0.0);
    let n = block.surface.normal;
    let x = block.start_position_m;
    let height = n.dot(x);
    let foot = x - n * height;
    let least = L::splat(SLIDE_EDGE_MARGIN) * p.friction_coefficient * height;
    let legs = &block.leg_step;
    let centroid =
        legs.iter().fold(Vec3::ZERO, |c, l| c + l.tip_m) * L::splat(1.0 / legs.len() as f64);
    let mut inside = if p.edges.is_empty() {
        all_false::<L>()
    } else {
        all_true::<L>()
    };
    for [i, j] in &p.edges {
        let a = legs[*i].tip_m;
        let edge = legs[*j].tip_m - a;
        // (No closure here: it would not be inlined into the kernel's instruction set.)
        let foot_side = edge.cross(foot - a).dot(n);
        let centroid_side = edge.cross(centroid - a).dot(n);
        inside &= (foot_side * centroid_side).simd_gt(zero)
            & (foot_side * foot_side).simd_gt(least * least * edge.length_squared());
    }
    inside
}

/// Mask: a flight that cannot end before `t_max` (the reference's `cannot_return`), on the
/// state after a step without contact. A block where no lane is above the legs' reach now
/// and at `t_max` skips the rest (most flights of a hopping lander stay below it, and
/// most above it come down).
#[inline(always)]
fn cannot_return<L: Lane>(p: &Params<L>, block: &Block<L>) -> L::Mask {
    let zero = L::splat(0.0);
    let n = block.surface.normal;
    let height = n.dot(block.position_m) - p.terrain_top_m - p.leg_reach_m;
    let high = height.simd_gt(zero) & block.active;
    if high.to_bitmask() == 0 {
        return all_false::<L>();
    }
    let remaining = p.t_max_s - block.t_s;
    let fall = L::splat(0.5) * p.gravity_m_s2 * n.z * remaining;
    let height_at_end = height + remaining * (n.dot(block.velocity_m_s) - fall);
    let clear = high & height_at_end.simd_gt(zero);
    // Nor where none is still above it at t_max (a lander on its way down).
    if clear.to_bitmask() == 0 {
        return all_false::<L>();
    }
    let i = p.inertia_kg_m2;
    let w = block.rate_rad_s;
    let momentum_squared = Vec3::new(i.x * w.x, i.y * w.y, i.z * w.z).length_squared();
    let cos_tilt = block.rotation.z_axis.dot(n);
    let turn = L::splat(TURN_MARGIN) * remaining;
    let tilt_margin = cos_tilt * p.inertia_min_kg_m2;
    let upright = cos_tilt.simd_gt(zero)
        & (tilt_margin * tilt_margin).simd_gt(momentum_squared * (turn * turn));
    let turning_bounded = momentum_squared.simd_lt(p.diverged_momentum_squared);
    clear & upright & turning_bounded & speed_bounded(p, block)
}
