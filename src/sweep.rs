//! Runs many samples through the SIMD kernels: blocks of lanes, lane refill, per-lane
//! clocks, rayon over the cores, rows handed on in sample order.
//!
//! The sample range is cut into chunks of consecutive indices. A worker takes a chunk and
//! streams it through one block: a lane whose sample is decided takes the next sample of
//! the chunk at once. Chunks are processed a window at a time in parallel and their rows
//! passed on in order, so memory holds one window of rows whatever the sample count.

use crate::reference::model::Surface;
use crate::reference::outcome::{LegSummary, Outcome, Summary};
use crate::reference::{Model, initial_state};
use crate::sampling::{self, Sample};
use crate::scenario::Scenario;
use glam::{DQuat, DVec3};
use kernels::block::{Block, LaneInit};
use kernels::lane::{LANES, mask_to};
use kernels::params::{HoneycombParams, LegParams, Params, lane};
use kernels::vec3::Vec3;
use rayon::prelude::*;
use std::ops::Range;

/// One finished sample: its inputs and its results.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub sample: Sample,
    pub summary: Summary,
}

/// Lane bookkeeping of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LaneStats {
    /// Lane-steps that advanced a sample.
    pub busy_lane_steps: u64,
    /// All lane-steps, busy or idle.
    pub lane_steps: u64,
}

impl LaneStats {
    /// Busy lane-steps over all lane-steps.
    #[must_use]
    pub fn occupancy(&self) -> f64 {
        self.busy_lane_steps as f64 / self.lane_steps.max(1) as f64
    }

    fn add(self, o: LaneStats) -> LaneStats {
        LaneStats {
            busy_lane_steps: self.busy_lane_steps + o.busy_lane_steps,
            lane_steps: self.lane_steps + o.lane_steps,
        }
    }
}

/// The kernels' parameters of a model, broadcast to lanes.
#[must_use]
pub fn kernel_params(m: &Model) -> Params {
    let v = |d: DVec3| Vec3::splat(d.to_array());
    Params {
        gravity_m_s2: lane(m.gravity_m_s2),
        mass_kg: lane(m.mass_kg),
        inertia_kg_m2: v(m.inertia_kg_m2),
        legs: m
            .legs
            .iter()
            .map(|l| LegParams {
                tip_m: v(l.tip_m),
                strut_axis: v(l.strut_axis),
            })
            .collect(),
        edges: m.edges.clone(),
        stiffness_n_per_m: lane(m.contact.stiffness_n_per_m),
        damping_n_s_per_m: lane(m.contact.damping_n_s_per_m),
        friction_coefficient: lane(m.contact.friction_coefficient),
        friction_stiffness_n_per_m: lane(m.contact.friction_stiffness_n_per_m),
        friction_damping_n_s_per_m: lane(m.contact.friction_damping_n_s_per_m),
        honeycomb: m.honeycomb.as_ref().map(|h| HoneycombParams {
            stages: h.stages.iter().map(|(e, f)| (lane(*e), lane(*f))).collect(),
            peak_force_n: lane(h.peak_force_n),
            peak_stroke_m: lane(h.peak_stroke_m),
            usable_stroke_m: lane(h.usable_stroke_m()),
        }),
        terrain: m.terrain.clone(),
        step_s: lane(m.step_s),
        flight_step_max_s: lane(m.flight_step_max_s),
        long_flight_steps: m.flight_step_max_s > m.step_s,
        t_max_s: lane(m.t_max_s),
        leg_reach_m: lane(m.leg_reach_m()),
        rest_speed_m_s: lane(m.thresholds.rest_speed_m_s),
        rest_rate_rad_s: lane(m.thresholds.rest_rate_rad_s),
        hold_time_s: lane(m.thresholds.hold_time_s),
        bounce_clearance_m: lane(m.thresholds.bounce_clearance_m),
        diverged_speed_m_s: lane(m.thresholds.diverged_speed_m_s),
        diverged_rate_rad_s: lane(m.thresholds.diverged_rate_rad_s),
        diverged_penetration_m: lane(m.thresholds.diverged_penetration_m),
        rest_contacts: lane(m.legs.len().min(3) as f64),
    }
}

/// The initial state of a sample, as a lane takes it (the reference's `initial_state`).
#[must_use]
pub fn lane_init(model: &Model, sample: &Sample) -> LaneInit {
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
    }
}

/// The summary of the sample decided in lane `i` (the reference's `Tracker::finish`).
fn lane_summary(block: &Block, i: usize) -> Summary {
    let at = |l: &kernels::lane::Lane| l.as_array()[i];
    let t = &block.track;
    let normal = DVec3::from_array(block.surface.normal.lane(i));
    let attitude = DQuat::from_array(block.attitude.lane(i));
    let cos_tilt = (attitude * DVec3::Z).dot(normal);
    let moved = DVec3::from_array(block.position_m.lane(i)) - DVec3::from_array(t.start_m.lane(i));
    let along = moved - normal * normal.dot(moved);
    let finite_or_zero = |x: f64| if x.is_finite() { x } else { 0.0 };
    let first = at(&t.first_contact_s);
    Summary {
        outcome: Outcome::ALL[at(&t.outcome) as usize],
        decided_s: at(&block.t_s),
        steps: at(&t.steps) as u64,
        final_tilt_deg: finite_or_zero(cos_tilt.clamp(-1.0, 1.0).acos().to_degrees()),
        max_tilt_deg: at(&t.min_cos_tilt).clamp(-1.0, 1.0).acos().to_degrees(),
        displacement_m: finite_or_zero(along.length()),
        peak_acceleration_m_s2: finite_or_zero(at(&t.peak_acceleration)),
        peak_acceleration_z_body_m_s2: finite_or_zero(at(&t.peak_acceleration_z)),
        bounces: at(&t.bounces) as u32,
        first_contact_s: (!first.is_nan()).then_some(first),
        max_penetration_m: finite_or_zero(at(&t.max_penetration)),
        legs: block
            .legs
            .iter()
            .map(|l| LegSummary {
                peak_normal_force_n: finite_or_zero(at(&l.peak_normal_n)),
                stroke_m: finite_or_zero(at(&l.stroke_m)),
                absorbed_j: finite_or_zero(at(&l.absorbed_j)),
            })
            .collect(),
    }
}

/// Runs the samples of `range` through one block with lane refill; rows in sample order.
#[must_use]
pub fn run_chunk(
    scenario: &Scenario,
    model: &Model,
    params: &Params,
    range: Range<u64>,
) -> (Vec<Row>, LaneStats) {
    let mut block = Block::new(params);
    let mut samples: [Option<Sample>; LANES] = [None; LANES];
    let mut next = range.start;
    let mut rows = Vec::with_capacity((range.end - range.start) as usize);
    let mut stats = LaneStats::default();
    let refill = |block: &mut Block, slot: &mut Option<Sample>, i: usize, next: &mut u64| {
        if *next < range.end {
            let s = sampling::sample(scenario, *next);
            block.load(i, &lane_init(model, &s));
            *slot = Some(s);
            *next += 1;
        } else {
            block.retire(i);
            *slot = None;
        }
    };
    for (i, slot) in samples.iter_mut().enumerate() {
        refill(&mut block, slot, i, &mut next);
    }
    loop {
        let busy = block.active.to_bitmask().count_ones() as u64;
        if busy == 0 {
            break;
        }
        stats.busy_lane_steps += busy;
        stats.lane_steps += LANES as u64;
        let dt = kernels::step::step_size(params, &block);
        kernels::step::step(params, &mut block, dt);
        let decided = kernels::outcome::observe(params, &mut block);
        if decided.to_bitmask() != 0 {
            for (i, done) in mask_to(decided).into_iter().enumerate() {
                if done {
                    let sample = samples[i].expect("a decided lane holds a sample");
                    rows.push(Row {
                        sample,
                        summary: lane_summary(&block, i),
                    });
                    refill(&mut block, &mut samples[i], i, &mut next);
                }
            }
        }
    }
    rows.sort_unstable_by_key(|r| r.sample.index);
    (rows, stats)
}

/// Runs `range` on the current rayon pool, `chunk` samples per task, handing each window of
/// rows, in sample order, to `sink`. Stops early when `sink` returns an error.
pub fn run(
    scenario: &Scenario,
    model: &Model,
    range: Range<u64>,
    chunk: u64,
    mut sink: impl FnMut(Vec<Row>) -> anyhow::Result<()>,
) -> anyhow::Result<LaneStats> {
    let params = kernel_params(model);
    let window = chunk * 4 * rayon::current_num_threads() as u64;
    let mut stats = LaneStats::default();
    let mut start = range.start;
    while start < range.end {
        let end = (start + window).min(range.end);
        let chunks: Vec<Range<u64>> = (start..end)
            .step_by(chunk as usize)
            .map(|s| s..(s + chunk).min(end))
            .collect();
        let results: Vec<(Vec<Row>, LaneStats)> = chunks
            .into_par_iter()
            .map(|r| run_chunk(scenario, model, &params, r))
            .collect();
        let mut rows = Vec::with_capacity((end - start) as usize);
        for (r, s) in results {
            rows.extend(r);
            stats = stats.add(s);
        }
        sink(rows)?;
        start = end;
    }
    Ok(stats)
}
