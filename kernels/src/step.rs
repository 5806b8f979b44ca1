//! The step kernel: every leg's contact, then the rigid body, for `LANES` landers at once,
//! each with its own step length. The reference's `step` module does the same in scalar.

use crate::block::{Block, LegStep};
use crate::contact;
use crate::lane::{Lane, splat};
use crate::params::Params;
use crate::rigid_body;
use crate::terrain::height_lanes;
use crate::vec3::Vec3;

/// Penetration below the local surface along the local normal, and that normal.
#[inline(always)]
fn penetration(p: &Params, block: &Block, tip: Vec3) -> (Lane, Vec3) {
    let s = &block.surface;
    let (h, dh_du, dh_dv) = match &p.terrain {
        None => (splat(0.0), splat(0.0), splat(0.0)),
        Some(t) => height_lanes(
            t,
            &s.tile,
            s.tangent_u.dot(tip) + s.offset_u_m,
            s.tangent_v.dot(tip) + s.offset_v_m,
        ),
    };
    let m = s.normal - s.tangent_u * dh_du - s.tangent_v * dh_dv;
    let inv = splat(1.0) / m.length();
    ((h - s.normal.dot(tip)) * inv, m * inv)
}

/// Advances every lane of `block` by its `dt` (0 for lanes that must not move).
#[inline(never)]
pub fn step(p: &Params, block: &mut Block, dt: Lane) {
    let rotation = block.attitude.to_mat3();
    let rate_i = rotation.mul_vec3(block.rate_rad_s);
    let mut force_n = Vec3::ZERO;
    let mut moment_n_m = Vec3::ZERO;
    for k in 0..p.legs.len() {
        let leg = &p.legs[k];
        let tip_b = leg.tip_m - leg.strut_axis * block.legs[k].stroke_m;
        let arm = rotation.mul_vec3(tip_b);
        let tip = block.position_m + arm;
        let tip_velocity = block.velocity_m_s + rate_i.cross(arm);
        let (penetration, normal) = penetration(p, block, tip);
        let contact = penetration.simd_gt(splat(0.0));
        let (f, normal_n, friction_n) = contact::leg_force(
            p,
            dt,
            contact,
            penetration,
            normal,
            tip,
            tip_velocity,
            -rotation.mul_vec3(leg.strut_axis),
            &mut block.legs[k],
        );
        force_n += f;
        moment_n_m += tip_b.cross(rotation.transpose_mul_vec3(f));
        block.leg_step[k] = LegStep {
            tip_m: tip,
            tip_velocity_m_s: tip_velocity,
            penetration_m: penetration,
            normal_n,
            friction_n,
        };
    }
    block.start_t_s = block.t_s;
    block.dt_s = dt;
    block.start_position_m = block.position_m;
    block.start_velocity_m_s = block.velocity_m_s;
    block.start_attitude = block.attitude;
    block.start_rate_rad_s = block.rate_rad_s;
    block.force_n = force_n;
    block.moment_n_m = moment_n_m;
    rigid_body::integrate(
        &mut block.position_m,
        &mut block.velocity_m_s,
        &mut block.attitude,
        &mut block.rate_rad_s,
        p.mass_kg,
        p.inertia_kg_m2,
        p.gravity_m_s2,
        force_n,
        moment_n_m,
        dt,
    );
    block.t_s += dt;
}

/// The step every lane takes (see the reference's `step_size`): `step_s` near the surface,
/// longer in free flight where no footpad can reach the terrain within it; 0 for empty lanes.
#[inline(never)]
#[must_use]
pub fn step_size(p: &Params, block: &Block) -> Lane {
    let remaining = p.t_max_s - block.t_s;
    let mut dt = p.step_s;
    if p.long_flight_steps {
        let rotation = block.attitude.to_mat3();
        let top = splat(p.terrain.as_ref().map_or(0.0, |t| t.height_max_m()));
        let mut clearance = splat(f64::INFINITY);
        for (leg, state) in p.legs.iter().zip(&block.legs) {
            let tip =
                block.position_m + rotation.mul_vec3(leg.tip_m - leg.strut_axis * state.stroke_m);
            clearance = clearance.min(block.surface.normal.dot(tip) - top);
        }
        let speed = block.velocity_m_s.length() + block.rate_rad_s.length() * p.leg_reach_m;
        let reach = splat(2.0) * clearance
            / (speed + (speed * speed + splat(2.0) * p.gravity_m_s2 * clearance).sqrt());
        let free = (splat(0.5) * reach).max(p.step_s).min(p.flight_step_max_s);
        dt = clearance.simd_gt(splat(0.0)).select(free, dt);
    }
    block.active.select(dt.min(remaining), splat(0.0))
}
