//! Leg-surface contact over lanes: the reference's `contact::leg_force`, in the same order,
//! with `select` where the reference branches.

use crate::block::LegLanes;
use crate::honeycomb;
use crate::lane::{Lane, Mask};
use crate::params::{LegParams, Params};
use crate::regolith;
use crate::vec3::Vec3;

/// Footpad position in B: `tip_m - s strut_axis` at stroke `s`. Without dampers the stroke
/// stays 0 and the footpad where the parameters put it.
#[inline(always)]
pub(crate) fn tip_in_body<L: Lane, const DAMPERS: bool>(
    leg: &LegParams<L>,
    stroke_m: L,
) -> Vec3<L> {
    if DAMPERS {
        leg.tip_m - leg.strut_axis * stroke_m
    } else {
        leg.tip_m
    }
}

/// The force of one leg on every lane (zero where `contact` is false), with its normal
/// magnitude and the mask of lanes where the footpad slips, on the elastic plane or, with
/// `REGOLITH`, on the soil of `p.soil` (but in the lanes of `on_rock`, whose footpad meets a
/// rock: rocks do not give way). Updates the friction anchor, the footprint and the damper
/// of the leg. (The reference also returns the friction magnitude, for the trace;
/// nothing in a sweep reads it.)
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn leg_force<L: Lane, const DAMPERS: bool, const REGOLITH: bool>(
    p: &Params<L>,
    dt: L,
    contact: L::Mask,
    penetration: L,
    normal: Vec3<L>,
    tip: Vec3<L>,
    tip_velocity: Vec3<L>,
    strut_up: Vec3<L>,
    on_rock: L::Mask,
    leg: &mut LegLanes<L>,
) -> (Vec3<L>, L, L::Mask) {
    let zero = L::splat(0.0);
    let normal_velocity = normal.dot(tip_velocity);
    let mut normal_n = match (REGOLITH, &p.soil) {
        (true, Some(s)) => {
            // The soil's push in place of the spring (a touchdown away from the footprint
            // first leaves it for virgin soil); a footpad on a rock meets the spring.
            let on_soil = contact & !on_rock;
            let soil_touches_down = contact & !leg.anchored & !on_rock;
            if soil_touches_down.to_bitmask() != 0 {
                regolith::footprint(
                    s,
                    soil_touches_down,
                    tip - leg.anchor_m,
                    normal,
                    &mut leg.sinkage_max_m,
                    &mut leg.soil_force_max_n,
                    &mut leg.soil_absorbed_j,
                );
            }
            let soil = regolith::soil_force(
                s,
                on_soil,
                penetration,
                &mut leg.sinkage_max_m,
                &mut leg.soil_force_max_n,
            );
            let spring = on_rock.select(p.stiffness_n_per_m * penetration, soil);
            p.damping_n_s_per_m
                .mul_neg_add(normal_velocity, spring)
                .max(zero)
        }
        _ => p
            .stiffness_n_per_m
            .mul_sub(penetration, p.damping_n_s_per_m * normal_velocity)
            .max(zero),
    };

    // The passive earth pressure on a sunk footpad's side (not on a rock), taken once for
    // both friction caps below.
    let passive = match (REGOLITH, &p.soil) {
        (true, Some(s)) => on_rock.select(zero, regolith::passive_force(s, penetration)),
        _ => zero,
    };

    // As the reference's `if !leg.anchored`: lanes touching down anchor at the footpad
    // (rare, so the block only writes the anchors when one does).
    let touches_down = contact & !leg.anchored;
    if touches_down.to_bitmask() != 0 {
        leg.anchor_m = Vec3::select(touches_down, tip, leg.anchor_m);
    }
    leg.anchored = contact;
    let slip = tip - leg.anchor_m;
    let slip_t = normal.mul_neg_add(normal.dot(slip), slip);
    let velocity_t = normal.mul_neg_add(normal_velocity, tip_velocity);
    // -(slip_t k) - velocity_t c, each component one multiply and one fused multiply-add.
    let (k, c) = (p.friction_stiffness_n_per_m, p.friction_damping_n_s_per_m);
    let mut friction = Vec3::new(
        slip_t.x.mul_neg_sub(k, velocity_t.x * c),
        slip_t.y.mul_neg_sub(k, velocity_t.y * c),
        slip_t.z.mul_neg_sub(k, velocity_t.z * c),
    );

    if let (true, Some(h)) = (DAMPERS, &p.honeycomb) {
        let friction_on_strut = honeycomb::Friction {
            magnitude_n: friction.length(),
            along_strut_n: friction.dot(strut_up),
            mu: p.friction_coefficient,
            passive_n: passive,
        };
        // The normal force falls with the stroke along the contact's spring: the plane's,
        // or the soil's unloading line.
        let spring_n_per_m = match (REGOLITH, &p.soil) {
            (true, Some(s)) => on_rock.select(p.stiffness_n_per_m, s.unloading_n_per_m),
            _ => p.stiffness_n_per_m,
        };
        let relief = spring_n_per_m + p.damping_n_s_per_m / dt;
        let (ds, relieved) = honeycomb::crush(
            h,
            contact,
            leg.stroke_m,
            normal_n,
            normal.dot(strut_up),
            relief,
            &friction_on_strut,
        );
        leg.absorbed_j += honeycomb::absorbed_between(h, leg.stroke_m, leg.stroke_m + ds);
        leg.stroke_m += ds;
        normal_n = relieved;
    }

    let cap = friction_cap::<L, REGOLITH>(p, normal_n, passive);
    // `|friction| > cap`, compared squared (both sides are >= 0): only slipping lanes need
    // the root and the division.
    let magnitude_squared = friction.length_squared();
    let slips = magnitude_squared.simd_gt(cap * cap) & contact;
    if slips.to_bitmask() != 0 {
        friction = friction * slips.select(cap / magnitude_squared.sqrt(), L::splat(1.0));
        // Slip: move the anchor so that the spring alone would give the capped force.
        leg.anchor_m = Vec3::select(
            slips,
            friction.mul_add(p.friction_compliance_m_per_n, tip),
            leg.anchor_m,
        );
    }
    let normal_n = contact.select(normal_n, zero);
    let force = Vec3::select(contact, normal.mul_add(normal_n, friction), Vec3::ZERO);
    (force, normal_n, slips)
}

/// The most the friction spring may pull with: Coulomb's `mu F_N`, and on regolith the
/// passive earth pressure `passive` on the side of the sunk footpad besides (0 on a rock).
#[inline(always)]
fn friction_cap<L: Lane, const REGOLITH: bool>(p: &Params<L>, normal_n: L, passive: L) -> L {
    match (REGOLITH, &p.soil) {
        (true, Some(_)) => p.friction_coefficient.mul_add(normal_n, passive),
        _ => p.friction_coefficient * normal_n,
    }
}
