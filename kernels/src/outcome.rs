//! Outcome tracking over lanes: the reference's `outcome::Tracker::observe`, rule for rule
//! and in the same order (see there for the rules).

use crate::block::Block;
use crate::lane::{Lane, all_false, splat};
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

/// Takes in the step just made; returns the mask of lanes decided by it (their code is in
/// `block.track.outcome`).
#[inline(never)]
pub fn observe(p: &Params, block: &mut Block) -> Lane {
    let zero = splat(0.0);
    let one = splat(1.0);
    let active = block.active & block.track.outcome.simd_lt(zero);
    let t = &mut block.track;
    t.steps += active.select(one, zero);
    let rotation = block.start_attitude.to_mat3();
    let acceleration = block.force_n * (one / p.mass_kg);
    t.peak_acceleration = t.peak_acceleration.max(acceleration.length());
    let z_body = rotation.z_axis;
    t.peak_acceleration_z = t.peak_acceleration_z.max(acceleration.dot(z_body).abs());
    let cos_tilt = z_body.dot(block.surface.normal);
    t.min_cos_tilt = t.min_cos_tilt.min(cos_tilt);

    let mut contacts = zero;
    let mut deepest = splat(f64::NEG_INFINITY);
    for (leg, step) in block.legs.iter_mut().zip(&block.leg_step) {
        leg.peak_normal_n = leg.peak_normal_n.max(step.normal_n);
        contacts += step.penetration_m.simd_gt(zero).select(one, zero);
        deepest = deepest.max(step.penetration_m);
    }
    t.max_penetration = t.max_penetration.max(deepest);
    let touching = contacts.simd_gt(zero);
    t.first_contact_s =
        (touching & t.first_contact_s.is_nan()).select(block.start_t_s, t.first_contact_s);
    let lifted = !touching & t.touched & (-deepest).simd_gt(p.bounce_clearance_m);
    t.bounces += lifted.select(one, zero);
    t.touched = touching | (t.touched & !lifted);

    let finite = block.position_m.x.is_finite()
        & block.position_m.y.is_finite()
        & block.position_m.z.is_finite()
        & block.velocity_m_s.length().is_finite()
        & block.rate_rad_s.length().is_finite()
        & block.attitude.w.is_finite()
        & block.attitude.x.is_finite()
        & block.attitude.y.is_finite()
        & block.attitude.z.is_finite();
    let diverged = !finite
        | block.velocity_m_s.length().simd_gt(p.diverged_speed_m_s)
        | block.rate_rad_s.length().simd_gt(p.diverged_rate_rad_s)
        | deepest.simd_gt(p.diverged_penetration_m);

    let mut inside = !all_false();
    let mut tipping = all_false();
    if !p.edges.is_empty() {
        let n = block.leg_step.len() as f64;
        let centroid = block.leg_step.iter().fold(Vec3::ZERO, |c, l| c + l.tip_m) * splat(1.0 / n);
        for [i, j] in &p.edges {
            let (a, c) = (&block.leg_step[*i], &block.leg_step[*j]);
            let edge = c.tip_m - a.tip_m;
            let mut outward = Vec3::new(edge.y, -edge.x, zero);
            outward = Vec3::select(
                outward.dot(centroid - a.tip_m).simd_gt(zero),
                -outward,
                outward,
            );
            let beyond = outward.dot(block.start_position_m - a.tip_m).simd_gt(zero);
            inside = inside & !beyond;
            let away = outward
                .dot(block.start_velocity_m_s - a.tip_velocity_m_s)
                .simd_gt(zero);
            let edge_touches = a.penetration_m.simd_gt(zero) | c.penetration_m.simd_gt(zero);
            tipping = tipping | (beyond & away & edge_touches);
        }
    }
    let tipped = cos_tilt.simd_lt(zero) | tipping;

    let at_rest = block.start_velocity_m_s.length().simd_lt(p.rest_speed_m_s)
        & block.start_rate_rad_s.length().simd_lt(p.rest_rate_rad_s)
        & contacts.simd_ge(p.rest_contacts)
        & inside;
    t.rest_s = at_rest.select(t.rest_s + block.dt_s, zero);
    let stable = t.rest_s.simd_ge(p.hold_time_s);
    let ended = block.t_s.simd_ge(p.t_max_s);
    let at_end = at_rest.select(
        splat(STABLE),
        touching.select(splat(SLIDING), splat(BOUNCING)),
    );

    let code = diverged.select(
        splat(DIVERGED),
        tipped.select(splat(TIPPED), stable.select(splat(STABLE), at_end)),
    );
    let decided = active & (diverged | tipped | stable | ended);
    t.outcome = decided.select(code, t.outcome);
    decided
}
