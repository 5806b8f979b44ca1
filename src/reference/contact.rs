//! Leg-surface contact (MODEL.md section 5): a spring-damper normal force that never pulls
//! (on regolith, the soil's push in place of the spring: `regolith`), stick-slip Coulomb
//! friction, and the honeycomb damper in series.
//!
//! Friction is a tangential spring-damper anchored where the footpad touched down. Its
//! force is capped at `mu F_N`; while capped the anchor follows the footpad (slip), so a
//! lander on a slope with `tan(alpha) < mu` holds still instead of creeping. The anchor
//! is forgotten when the leg lifts off.

use super::honeycomb;
use super::model::{Contact, Honeycomb};
use super::regolith::{self, Soil};
use glam::DVec3;

/// What a leg remembers between steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegState {
    /// Damper stroke, m.
    pub stroke_m: f64,
    /// Energy the damper absorbed, J.
    pub absorbed_j: f64,
    /// Friction anchor in I (meaningful while `anchored`).
    pub anchor_m: DVec3,
    /// Whether the footpad is in contact with an anchor set: set at touchdown, cleared at
    /// lift-off.
    pub anchored: bool,
    /// On regolith: the deepest sinkage of the footprint the footpad is in, m.
    pub sinkage_max_m: f64,
    /// On regolith: the soil's force at that sinkage (on the loading curve), N.
    pub soil_force_max_n: f64,
    /// On regolith: the energy the footpad's earlier footprints absorbed, J.
    pub soil_absorbed_j: f64,
}

impl Default for LegState {
    fn default() -> Self {
        LegState {
            stroke_m: 0.0,
            absorbed_j: 0.0,
            anchor_m: DVec3::ZERO,
            anchored: false,
            sinkage_max_m: 0.0,
            soil_force_max_n: 0.0,
            soil_absorbed_j: 0.0,
        }
    }
}

/// The force of one leg in contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegForce {
    /// Total force on the lander at the footpad, in I, N.
    pub force_n: DVec3,
    /// Normal force magnitude, N.
    pub normal_n: f64,
    /// Friction force magnitude, N.
    pub friction_n: f64,
    /// Whether the footpad slips: friction at its cap, the anchor dragged along.
    pub slipping: bool,
}

/// Force of a leg whose footpad at `tip` (in I) with velocity `tip_velocity` penetrates the
/// surface by `penetration > 0` along the local normal `normal`, on the elastic plane or,
/// with `soil`, on regolith. `strut_up` is the strut direction from footpad to hip in I.
/// Updates the friction anchor, the footprint and the damper.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn leg_force(
    contact: &Contact,
    soil: Option<&Soil>,
    honeycomb: Option<&Honeycomb>,
    dt: f64,
    penetration: f64,
    normal: DVec3,
    tip: DVec3,
    tip_velocity: DVec3,
    strut_up: DVec3,
    leg: &mut LegState,
) -> LegForce {
    let normal_velocity = normal.dot(tip_velocity);
    // The spring: the elastic plane's `k d`, or the soil's push (a touchdown away from the
    // footprint first leaves it for virgin soil).
    let spring = match soil {
        None => contact.stiffness_n_per_m * penetration,
        Some(s) => {
            if !leg.anchored {
                regolith::footprint(
                    s,
                    tip - leg.anchor_m,
                    normal,
                    &mut leg.sinkage_max_m,
                    &mut leg.soil_force_max_n,
                    &mut leg.soil_absorbed_j,
                );
            }
            regolith::soil_force(
                s,
                penetration,
                &mut leg.sinkage_max_m,
                &mut leg.soil_force_max_n,
            )
        }
    };
    let mut normal_n = (spring - contact.damping_n_s_per_m * normal_velocity).max(0.0);
    // The passive earth pressure on a sunk footpad's side, taken once for both caps below.
    let passive = soil.map_or(0.0, |s| regolith::passive_force(s, penetration));

    if !leg.anchored {
        leg.anchor_m = tip;
        leg.anchored = true;
    }
    let slip = tip - leg.anchor_m;
    let slip_t = slip - normal * normal.dot(slip);
    let velocity_t = tip_velocity - normal * normal_velocity;
    let mut friction = -slip_t * contact.friction_stiffness_n_per_m
        - velocity_t * contact.friction_damping_n_s_per_m;

    if let Some(h) = honeycomb {
        let friction_on_strut = honeycomb::Friction {
            magnitude_n: friction.length(),
            along_strut_n: friction.dot(strut_up),
            mu: contact.friction_coefficient,
            passive_n: passive,
        };
        // The normal force falls with the stroke along the contact's spring: the plane's,
        // or the soil's unloading line.
        let spring_n_per_m = soil.map_or(contact.stiffness_n_per_m, |s| s.unloading_n_per_m);
        let relief = spring_n_per_m + contact.damping_n_s_per_m / dt;
        let (ds, relieved) = honeycomb::crush(
            h,
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

    let cap = friction_cap(contact, soil, normal_n, passive);
    let magnitude = friction.length();
    let slipping = magnitude > cap;
    if slipping {
        friction *= cap / magnitude;
        // Slip: move the anchor so that the spring alone would give the capped force.
        leg.anchor_m = tip + friction / contact.friction_stiffness_n_per_m;
    }
    LegForce {
        force_n: normal * normal_n + friction,
        normal_n,
        friction_n: friction.length(),
        slipping,
    }
}

/// The most the friction spring may pull with: Coulomb's `mu F_N`, and on regolith the
/// passive earth pressure `passive` on the side of the sunk footpad besides.
#[inline]
fn friction_cap(contact: &Contact, soil: Option<&Soil>, normal_n: f64, passive: f64) -> f64 {
    match soil {
        None => contact.friction_coefficient * normal_n,
        Some(_) => contact.friction_coefficient * normal_n + passive,
    }
}
