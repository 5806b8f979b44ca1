//! Between the reference model and a lane: the kernels' parameters of a model, a sample's
//! initial state as a lane takes it, a decided lane's summary and the truth and thrust of
//! its control loop.

use crate::control::{Thrust, Truth};
use crate::reference::outcome::{LegSummary, Outcome, Summary};
use crate::reference::touchdown::{Met, Touchdown};
use crate::reference::{Model, initial_state};
use crate::scenario::Sample;
use crate::slope::Surface;
use glam::{DQuat, DVec3};
use kernels::block::{Block, LaneInit, LaneThrust};
use kernels::lane::Lane;
use kernels::lane::lane;
use kernels::params::{HoneycombParams, LegParams, Params, SoilParams};
use kernels::terrain::Terrain;
use kernels::vec3::Vec3;

/// The kernels' parameters of a model, broadcast to lanes.
#[must_use]
pub fn kernel_params<L: Lane>(m: &Model) -> Params<L> {
    let v = |d: DVec3| Vec3::splat(d.to_array());
    Params {
        gravity_m_s2: lane(m.gravity_m_s2),
        inverse_mass_per_kg: lane(1.0 / m.mass_kg),
        inertia_kg_m2: v(m.inertia_kg_m2),
        inverse_inertia: v(m.inertia_kg_m2.recip()),
        gyroscopic: v(crate::reference::rigid_body::gyroscopic(m.inertia_kg_m2)),
        legs: m
            .legs
            .iter()
            .map(|l| LegParams {
                tip_m: v(l.tip_m),
                strut_axis: v(l.strut_axis),
            })
            .collect(),
        leg_index: m.leg_index.clone(),
        edges: m.edges.clone(),
        stiffness_n_per_m: lane(m.contact.stiffness_n_per_m),
        damping_n_s_per_m: lane(m.contact.damping_n_s_per_m),
        friction_coefficient: lane(m.contact.friction_coefficient),
        friction_stiffness_n_per_m: lane(m.contact.friction_stiffness_n_per_m),
        friction_compliance_m_per_n: lane(1.0 / m.contact.friction_stiffness_n_per_m),
        friction_damping_n_s_per_m: lane(m.contact.friction_damping_n_s_per_m),
        honeycomb: m.honeycomb.as_ref().map(|h| HoneycombParams {
            stages: h.stages.iter().map(|(e, f)| (lane(*e), lane(*f))).collect(),
            peak_force_n: lane(h.peak_force_n),
            peak_stroke_m: lane(h.peak_stroke_m),
            usable_stroke_m: lane(h.usable_stroke_m()),
        }),
        soil: m.soil.as_ref().map(|s| SoilParams {
            virgin_n: lane(s.virgin_n),
            exponent: lane(s.exponent),
            unloading_n_per_m: lane(s.unloading_n_per_m),
            passive_linear_n_per_m: lane(s.passive_linear_n_per_m),
            passive_quadratic_n_per_m2: lane(s.passive_quadratic_n_per_m2),
            pad_radius_m: lane(s.pad_radius_m),
        }),
        terrain: m.terrain.clone(),
        rocks: m.rocks.clone(),
        rock_abundance: lane(m.rock_abundance),
        pad_radius_m: lane(m.pad_radius_m()),
        step_s: lane(m.step_s),
        step_control: m.step_control.is_some(),
        tolerance_squared: lane(m.step_control.map_or(0.0, |c| c.tolerance_m_s.powi(2))),
        step_min_s: lane(m.step_control.map_or(m.step_s, |c| c.step_min_s)),
        step_max_s: lane(m.step_control.map_or(m.step_s, |c| c.step_max_s)),
        flight_step_max_s: lane(m.flight_step_max_s),
        long_flight_steps: m.flight_step_max_s > m.step_s,
        t_max_s: lane(m.t_max_s),
        leg_reach_m: lane(m.leg_reach_m()),
        rest_speed_squared: lane(m.thresholds.rest_speed_m_s.powi(2)),
        rest_rate_squared: lane(m.thresholds.rest_rate_rad_s.powi(2)),
        hold_time_s: lane(m.thresholds.hold_time_s),
        bounce_clearance_m: lane(m.thresholds.bounce_clearance_m),
        diverged_speed_squared: lane(m.thresholds.diverged_speed_m_s.powi(2)),
        diverged_rate_squared: lane(m.thresholds.diverged_rate_rad_s.powi(2)),
        diverged_penetration_m: lane(m.thresholds.diverged_penetration_m),
        early_tipping: m.thresholds.early_tipping,
        quasi_static_force_squared: lane((2.0 * m.mass_kg * m.gravity_m_s2).powi(2)),
        rest_contacts: lane(m.legs.len().min(3) as f64),
        early_sliding: m.slides_decidable(),
        early_bouncing: m.thresholds.early_bouncing,
        leg_count: lane(m.legs.len() as f64),
        weight_n: lane(m.mass_kg * m.gravity_m_s2),
        friction_coefficient_squared: lane(m.contact.friction_coefficient.powi(2)),
        inertia_min_kg_m2: lane(m.inertia_kg_m2.min_element()),
        diverged_momentum_squared: lane(
            (m.inertia_kg_m2.min_element() * m.thresholds.diverged_rate_rad_s).powi(2),
        ),
        terrain_top_m: lane(m.terrain_top_m()),
        ground_top_m: lane(m.ground_top_m()),
        terrain_scale: lane(m.terrain.as_ref().map_or(1.0, Terrain::scale)),
        thrust: m.control.is_some(),
        struts_along_z: m.legs.iter().all(|l| l.strut_axis == -DVec3::Z),
    }
}

/// The initial state of a sample, as a lane takes it (the reference's `initial_state`, with
/// the sample's own parameters: `Model::for_sample`).
#[must_use]
pub fn lane_init(model: &Model, sample: &Sample) -> LaneInit {
    sample_lane_init(&model.for_sample(sample), sample)
}

/// `lane_init` with the sample's own model (`Model::for_sample`) already made.
pub(super) fn sample_lane_init(model: &Model, sample: &Sample) -> LaneInit {
    let surface = Surface::of(sample);
    let s = initial_state(model, &surface, sample);
    LaneInit {
        position_m: s.body.position_m.to_array(),
        velocity_m_s: s.body.velocity_m_s.to_array(),
        attitude: s.body.attitude.to_array(),
        rate_rad_s: s.body.rate_rad_s.to_array(),
        normal: surface.normal.to_array(),
        tangent_u: surface.tangent_u.to_array(),
        tangent_v: surface.tangent_v.to_array(),
        offset_m: surface.offset_m,
        tile: surface.tile,
        rock_offset_m: surface.rock_offset_m,
        rock_tile: surface.rock_tile,
        step_s: model.step_s,
    }
}

/// The summary of the sample of `model` decided in lane `i` (the reference's
/// `Tracker::finish`, then `Summary::judge`), on the soil of `soil` (the lane's
/// parameters' soil: each lane's own values where the samples draw them).
pub(super) fn lane_summary<L: Lane>(
    model: &Model,
    soil: Option<&SoilParams<L>>,
    block: &Block<L>,
    i: usize,
) -> Summary {
    let at = |l: &L| l.lane(i);
    let t = &block.track;
    let normal = DVec3::from_array(block.surface.normal.lane(i));
    let attitude = DQuat::from_array(block.attitude.lane(i));
    let cos_tilt = (attitude * DVec3::Z).dot(normal);
    // With the final state, as the reference's `finish`: the maximum is never below it.
    let min_cos_tilt = at(&t.min_cos_tilt).min(cos_tilt);
    let moved = DVec3::from_array(block.position_m.lane(i)) - DVec3::from_array(t.start_m.lane(i));
    let along = moved - normal * normal.dot(moved);
    let finite_or_zero = |x: f64| if x.is_finite() { x } else { 0.0 };
    let first = at(&t.first_contact_s);
    let time = |s: f64| (!s.is_nan()).then_some(s);
    let mut summary = Summary {
        outcome: Outcome::ALL[at(&t.outcome) as usize],
        decided_s: at(&block.t_s),
        steps: at(&t.steps) as u64,
        final_tilt_deg: finite_or_zero(libm::acos(cos_tilt.clamp(-1.0, 1.0)).to_degrees()),
        max_tilt_deg: libm::acos(min_cos_tilt.clamp(-1.0, 1.0)).to_degrees(),
        displacement_m: finite_or_zero(along.length()),
        peak_acceleration_m_s2: finite_or_zero(at(&t.peak_acceleration_squared).sqrt()),
        peak_acceleration_z_body_m_s2: finite_or_zero(at(&t.peak_acceleration_z)),
        bounces: at(&t.bounces) as u32,
        first_contact_s: (!first.is_nan()).then_some(first),
        touchdown: (!first.is_nan()).then(|| {
            let v3 = |v: &Vec3<L>| DVec3::from_array(v.lane(i));
            let met = Met {
                velocity_m_s: v3(&t.met_velocity_m_s),
                rate_rad_s: v3(&t.met_rate_rad_s),
                x_body: v3(&t.met_x_body),
                z_body: v3(&t.met_z_body),
                first_leg: at(&t.met_leg) as usize,
            };
            let s = &block.surface;
            Touchdown::of(&met, normal, v3(&s.tangent_u), v3(&s.tangent_v))
        }),
        max_penetration_m: finite_or_zero(at(&t.max_penetration)),
        legs: model
            .leg_index
            .iter()
            .map(|&i| {
                let l = &block.legs[i];
                let (sinkage_m, soil_absorbed_j) = soil.map_or((0.0, 0.0), |s| {
                    kernels::regolith::leg_results(
                        at(&s.exponent),
                        at(&s.unloading_n_per_m),
                        at(&l.sinkage_max_m),
                        at(&l.soil_force_max_n),
                        at(&l.soil_absorbed_j),
                    )
                });
                LegSummary {
                    peak_normal_force_n: finite_or_zero(at(&l.peak_normal_n)),
                    stroke_m: finite_or_zero(at(&l.stroke_m)),
                    absorbed_j: finite_or_zero(at(&l.absorbed_j)),
                    peak_axial_force_n: finite_or_zero(at(&l.peak_axial_n)),
                    peak_axial_force_s: time(at(&l.peak_axial_s)),
                    peak_side_force_n: finite_or_zero(at(&l.peak_side_squared).sqrt()),
                    peak_side_force_s: time(at(&l.peak_side_s)),
                    stroke_margin_m: None,
                    bottomed: false,
                    sinkage_m: finite_or_zero(sinkage_m),
                    soil_absorbed_j: finite_or_zero(soil_absorbed_j),
                }
            })
            .collect(),
        control: None,
        limits_broken: None,
    };
    summary.judge(model);
    summary
}

/// The truth lane `i`'s control loop reads (`contact`: a footpad of the lane touched in
/// the last step).
pub(super) fn lane_truth<L: Lane>(
    block: &Block<L>,
    i: usize,
    contact: bool,
    touching: bool,
) -> Truth {
    Truth {
        t_s: block.t_s.lane(i),
        position_m: DVec3::from_array(block.position_m.lane(i)),
        velocity_m_s: DVec3::from_array(block.velocity_m_s.lane(i)),
        attitude: DQuat::from_array(block.attitude.lane(i)),
        rate_rad_s: DVec3::from_array(block.rate_rad_s.lane(i)),
        contact,
        touching,
        normal: DVec3::from_array(block.surface.normal.lane(i)),
    }
}

/// The thrust the control loop returned, as a lane takes it.
#[must_use]
pub fn lane_thrust(t: &Thrust) -> LaneThrust {
    LaneThrust {
        force_b_n: t.force_b_n.to_array(),
        moment_b_n_m: t.moment_b_n_m.to_array(),
        event_in_s: t.event_in_s,
        approach_m_s: t.approach_m_s,
        powered: t.powered,
    }
}

#[cfg(test)]
mod tests {
    use super::{Model, Outcome, kernel_params, lane_init, lane_summary};
    use crate::scenario::Scenario;
    use kernels::block::Block;
    use kernels::isa::{Isa, Kernel, KernelKind, Precision, WithKernel};

    /// A lane whose state turns non-finite mid-flight ends at once as `diverged`, with
    /// finite numbers in every result, and the lanes beside it go on untouched; with every
    /// kernel this CPU has.
    #[test]
    fn a_lane_turned_non_finite_ends_as_diverged_without_nan_results() {
        struct Poisoned;
        impl WithKernel for Poisoned {
            type Output = ();
            fn run<K: Kernel>(self) {
                poisoned_lane_ends_alone::<K>();
            }
        }
        for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
            for precision in Precision::ALL {
                KernelKind { isa, precision }.dispatch(Poisoned);
            }
        }
    }

    fn poisoned_lane_ends_alone<K: Kernel>() {
        let scenario = Scenario::default();
        let model = Model::new(&scenario);
        let params = kernel_params::<K>(&model);
        type Poison<K> = fn(&mut Block<K>, usize);
        let poisons: [(&str, Poison<K>); 4] = [
            ("velocity NaN", |b, i| {
                b.velocity_m_s.x.set_lane(i, f64::NAN);
            }),
            ("position infinite", |b, i| {
                b.position_m.z.set_lane(i, f64::INFINITY);
            }),
            ("body rate NaN", |b, i| {
                b.rate_rad_s.y.set_lane(i, f64::NAN);
            }),
            ("attitude NaN", |b, i| {
                b.attitude.w.set_lane(i, f64::NAN);
            }),
        ];
        for (what, poison) in poisons {
            let what = format!("{}: {what}", K::NAME);
            let mut block = Block::new(&params);
            for i in 0..K::LANES {
                let sample = crate::sampling::sample(&scenario, i as u64);
                block.load(i, &lane_init(&model, &sample));
            }
            let advanced = K::advance(&params, &mut block, 20);
            assert_eq!(advanced.steps, 20, "{what}: nothing decided yet");
            assert_eq!(advanced.bits, 0, "{what}: nothing decided yet");
            let lane = 3;
            poison(&mut block, lane);
            let decided = K::advance(&params, &mut block, 1).bits;
            assert_eq!(decided, 1 << lane, "{what}: only the poisoned lane ends");
            let s = lane_summary(&model, params.soil.as_ref(), &block, lane);
            assert_eq!(s.outcome, Outcome::Diverged, "{what}");
            let mut numbers = vec![
                s.decided_s,
                s.final_tilt_deg,
                s.max_tilt_deg,
                s.displacement_m,
                s.peak_acceleration_m_s2,
                s.peak_acceleration_z_body_m_s2,
                s.max_penetration_m,
            ];
            numbers.extend(s.first_contact_s);
            for l in &s.legs {
                numbers.extend([
                    l.peak_normal_force_n,
                    l.stroke_m,
                    l.absorbed_j,
                    l.peak_axial_force_n,
                    l.peak_side_force_n,
                ]);
                numbers.extend(l.peak_axial_force_s.into_iter().chain(l.peak_side_force_s));
            }
            assert!(
                numbers.iter().all(|x| x.is_finite()),
                "{what}: a result is not finite: {s:?}"
            );
        }
    }
}
