//! Outcome tracking over lanes: the reference's `outcome::Tracker::observe`, rule for rule
//! and in the same order (see there for the rules).

use crate::block::Block;
use crate::lane::{Lane, all_false, all_true, max_into, min_into};
use crate::params::Params;
use crate::vec3::Vec3;

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

/// Mask: every one of `xs` is finite. `x * 0` is 0 for a finite `x` and NaN for an infinite
/// or NaN one, so the sum of the products is 0 exactly when all are finite.
#[inline(always)]
fn all_finite<L: Lane, const N: usize>(xs: [L; N]) -> L {
    let zero = L::splat(0.0);
    xs.iter()
        .fold(zero, |sum, x| x.mul_add(zero, sum))
        .simd_eq(zero)
}

/// Takes in the step just made; returns the mask of lanes decided by it (their code is in
/// `block.track.outcome`).
#[inline(always)]
pub fn observe<L: Lane>(p: &Params<L>, block: &mut Block<L>) -> L {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let active = block.active & block.track.outcome.simd_lt(zero);
    let t = &mut block.track;
    t.steps += active.select(one, zero);
    let acceleration = block.force_n * p.inverse_mass_per_kg;
    // The accumulators below (peaks, least tilt cosine, deepest penetration) start finite
    // and never become NaN: `max_into` and `min_into` apply.
    t.peak_acceleration_squared =
        max_into(t.peak_acceleration_squared, acceleration.length_squared());
    let z_body = block.start_z_body;
    t.peak_acceleration_z = max_into(t.peak_acceleration_z, acceleration.dot(z_body).abs());
    let cos_tilt = z_body.dot(block.surface.normal);
    t.min_cos_tilt = min_into(t.min_cos_tilt, cos_tilt);

    let mut contacts = zero;
    let mut resting = zero;
    let mut deepest = L::splat(f64::NEG_INFINITY);
    let rest_gap = L::splat(-REST_GAP_M);
    for (leg, step) in block.legs.iter_mut().zip(&block.leg_step) {
        leg.peak_normal_n = max_into(leg.peak_normal_n, step.normal_n);
        contacts += step.penetration_m.simd_gt(zero).select(one, zero);
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
    let finite = all_finite([
        x.x, x.y, x.z, v.x, v.y, v.z, w.x, w.y, w.z, q.x, q.y, q.z, q.w,
    ]);
    let diverged = !finite
        | block
            .velocity_m_s
            .length_squared()
            .simd_gt(p.diverged_speed_squared)
        | block
            .rate_rad_s
            .length_squared()
            .simd_gt(p.diverged_rate_squared)
        | deepest.simd_gt(p.diverged_penetration_m);

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
    let mut tipping = all_false();
    let quasi_static = block
        .force_n
        .length_squared()
        .simd_le(p.quasi_static_force_squared);
    let two_contacts = contacts.simd_eq(L::splat(2.0));
    // The edges matter only to a lane that may pivot on two footpads (early tipping) or may
    // be at rest (CG over the polygon); a block with neither in any lane (in flight, or
    // moving on more legs) skips them: `tipping` and `inside` would change nothing.
    let pivot_or_rest = (if p.early_tipping {
        two_contacts
    } else {
        all_false()
    }) | slow;
    if !p.edges.is_empty() && pivot_or_rest.to_bitmask() != 0 {
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
    let tipped = cos_tilt.simd_lt(zero)
        | (if p.early_tipping {
            tipping
        } else {
            all_false()
        });

    let at_rest = slow & stuck & inside;
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
    let at_end = at_rest.select(
        L::splat(STABLE),
        touching.select(L::splat(SLIDING), L::splat(BOUNCING)),
    );

    let code = diverged.select(
        L::splat(DIVERGED),
        tipped.select(L::splat(TIPPED), stable.select(L::splat(STABLE), at_end)),
    );
    let decided = active & (diverged | tipped | stable | ended);
    t.outcome = decided.select(code, t.outcome);
    decided
}
