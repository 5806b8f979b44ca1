//! Runs many samples through the SIMD kernels: blocks of lanes, lane refill, per-lane
//! clocks, rayon over the cores, rows handed on in sample order.
//!
//! Every thread streams samples through one block: a lane whose sample is decided takes
//! the next sample index at once, from a counter shared by the threads. Rows are passed on
//! a window of consecutive indices at a time, in order, so memory holds about two windows
//! of rows whatever the sample count; blocks keep their lanes from one window to the next,
//! so the last (longest) samples of a window do not leave the block half empty.

use crate::control::{ControlModel, LAW_MEMORY, LaneControl, LawCommand, Sensed, Thrust, Truth};
use crate::reference::outcome::{LegSummary, Outcome, Summary};
use crate::reference::{Model, initial_state};
use crate::sampling;
use crate::scenario::Sample;
use crate::scenario::Scenario;
use crate::slope::Surface;
use glam::{DQuat, DVec3};
use kernels::block::{Block, LaneInit, LaneThrust};
use kernels::isa::{Isa, Kernel, KernelKind, WithKernel};
use kernels::lane::lane;
use kernels::lane::{Lane, MAX_LANES};
use kernels::params::{HoneycombParams, LegParams, Params};
use kernels::terrain::Terrain;
use kernels::vec3::Vec3;
use rayon::prelude::*;
use std::ops::Range;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// The `index`-th of `count` disjoint, contiguous slices of a sweep's sample range (as a
/// Slurm array numbers its tasks: 0 to `count - 1`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: u64,
    pub count: u64,
}

impl Shard {
    /// The samples of this shard out of `samples`: `samples * index / count` up to
    /// `samples * (index + 1) / count`, so the shards cover the range once, in order, and
    /// differ in size by one sample at most.
    #[must_use]
    pub fn range(self, samples: u64) -> Range<u64> {
        let at = |k: u64| (u128::from(samples) * u128::from(k) / u128::from(self.count)) as u64;
        at(self.index)..at(self.index + 1)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// `K/N` with `0 <= K < N`.
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("{s:?} is not a shard K/N with K from 0 to N-1 (example: 0/4)");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (u64, u64) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

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
        terrain: m.terrain.clone(),
        step_s: lane(m.step_s),
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
        terrain_scale: lane(m.terrain.as_ref().map_or(1.0, Terrain::scale)),
        thrust: m.control.is_some(),
    }
}

/// The initial state of a sample, as a lane takes it (the reference's `initial_state`, with
/// the sample's own parameters: `Model::for_sample`).
#[must_use]
pub fn lane_init(model: &Model, sample: &Sample) -> LaneInit {
    sample_lane_init(&model.for_sample(sample), sample)
}

/// `lane_init` with the sample's own model (`Model::for_sample`) already made.
fn sample_lane_init(model: &Model, sample: &Sample) -> LaneInit {
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
fn lane_summary<L: Lane>(block: &Block<L>, i: usize) -> Summary {
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
    Summary {
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
        control: None,
    }
}

/// The truth lane `i`'s control loop reads (`contact`: a footpad of the lane touched in
/// the last step).
fn lane_truth<L: Lane>(block: &Block<L>, i: usize, contact: bool) -> Truth {
    Truth {
        t_s: block.t_s.lane(i),
        position_m: DVec3::from_array(block.position_m.lane(i)),
        velocity_m_s: DVec3::from_array(block.velocity_m_s.lane(i)),
        attitude: DQuat::from_array(block.attitude.lane(i)),
        rate_rad_s: DVec3::from_array(block.rate_rad_s.lane(i)),
        contact,
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

/// A value alone in its pair of cache lines: x86 cores fetch lines in pairs of 128 bytes,
/// so a line that one thread writes slows the threads that read the other line of its pair
/// as if they shared it (measured: 20 % of a two-thread sweep, when a counter the threads
/// write sat beside the parameters they read at every step).
#[repr(align(128))]
struct Padded<T>(T);

/// One block and the samples its lanes hold: a worker's state, kept from one window to the
/// next so that a block never waits, half empty, for the last samples of a window. Aligned
/// to 128 bytes: the workers of two threads sit side by side, and x86 cores fetch cache
/// lines in pairs (see `kernels::block::LegLanes`).
#[repr(align(128))]
struct Worker<L: Lane> {
    block: Block<L>,
    /// The parameters of each lane's sample, where the scenario draws parameters per sample
    /// (`Scenario::sampled`); otherwise the block steps with the sweep's, shared by all.
    own: Option<Params<L>>,
    /// The sample of each lane (the first `L::LANES` used).
    samples: [Option<Sample>; MAX_LANES],
    /// The control loop of each lane's sample (scenarios with one).
    control: [Option<LaneControl>; MAX_LANES],
}

/// The most steps a worker asks of the kernel at once: the kernel returns sooner when a
/// lane is decided. Between calls the worker sees whether the window is complete, so a
/// worker steps at most this many steps past it (a few milliseconds).
const STEPS_PER_CALL: u32 = 256;

/// Where a worker takes samples from, and when it may stop.
struct Feed<'a> {
    /// Nonzero: take no more samples (the lanes finish the samples they hold).
    stop: &'a AtomicUsize,
    /// The next sample index to take.
    next: &'a AtomicU64,
    /// Samples from `next` up to here may be taken.
    cap: u64,
    /// The end of the window being completed.
    window_end: u64,
    /// Samples below `window_end` not yet decided, in all workers.
    outstanding: &'a AtomicU64,
}

impl Feed<'_> {
    /// The next sample index, if one below `cap` is left.
    fn take(&self) -> Option<u64> {
        if self.stop.load(Ordering::Relaxed) != 0 {
            return None;
        }
        self.next
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |n| {
                (n < self.cap).then_some(n + 1)
            })
            .ok()
    }
}

impl<K: Kernel> Worker<K> {
    fn new(params: &Params<K>, per_sample: bool) -> Worker<K> {
        Worker {
            block: Block::new(params),
            own: per_sample.then(|| params.clone()),
            samples: [None; MAX_LANES],
            control: std::array::from_fn(|_| None),
        }
    }

    /// Puts the next sample of `feed` into lane `i`, or empties the lane if none is left.
    fn refill(&mut self, scenario: &Scenario, model: &Model, feed: &Feed, i: usize) {
        if let Some(index) = feed.take() {
            let s = sampling::sample(scenario, index);
            // The sample's own model, made once for its parameters and its initial state.
            let own_model = model.for_sample(&s);
            if let Some(own) = &mut self.own {
                own.copy_lane(i, &kernel_params(&own_model));
            }
            self.block.load(i, &sample_lane_init(&own_model, &s));
            self.samples[i] = Some(s);
            if let Some(m) = &model.control {
                let mut c = LaneControl::new(m, &s);
                let truth = lane_truth(&self.block, i, false);
                self.block.set_thrust(i, &lane_thrust(&c.event(m, &truth)));
                self.control[i] = Some(c);
            }
        } else {
            self.block.retire(i);
            self.samples[i] = None;
        }
    }

    /// The control events of the lanes of `events` (lane `i` in bit `i`): each lane's loop
    /// takes in its event and sets its thrust until the next; the lanes at a control
    /// instant whose loop runs the user's law are handed to it together.
    fn control_events(&mut self, m: &ControlModel, events: u32) {
        let mut truths = [None; MAX_LANES];
        let mut asking = [0usize; MAX_LANES];
        let mut sensed = [None; MAX_LANES];
        let mut count = 0;
        for i in (0..K::LANES).filter(|i| events & (1 << i) != 0) {
            let contact = self
                .block
                .leg_step
                .iter()
                .any(|l| l.penetration_m.lane(i) > 0.0);
            let truth = lane_truth(&self.block, i, contact);
            let c = self.control[i]
                .as_mut()
                .expect("a lane with events has a loop");
            if let Some(s) = c.begin(m, &truth) {
                asking[count] = i;
                sensed[count] = Some(s);
                count += 1;
            }
            truths[i] = Some(truth);
        }
        let mut commands = [LawCommand::default(); MAX_LANES];
        if count > 0
            && let Some(law) = &m.law
        {
            let readings: [Sensed; MAX_LANES] =
                std::array::from_fn(|k| sensed[k].unwrap_or(sensed[0].expect("one asks")));
            let mut memory = [[0.0; LAW_MEMORY]; MAX_LANES];
            for (k, &i) in asking[..count].iter().enumerate() {
                memory[k] = *self.control[i]
                    .as_mut()
                    .expect("asking lanes have a loop")
                    .memory();
            }
            law.law.command(
                &readings[..count],
                &mut memory[..count],
                &mut commands[..count],
            );
            for (k, &i) in asking[..count].iter().enumerate() {
                *self.control[i]
                    .as_mut()
                    .expect("asking lanes have a loop")
                    .memory() = memory[k];
            }
        }
        for i in (0..K::LANES).filter(|i| events & (1 << i) != 0) {
            let truth = truths[i].expect("every event lane has its truth");
            let user = asking[..count]
                .iter()
                .position(|&a| a == i)
                .map(|k| &commands[k]);
            let c = self.control[i]
                .as_mut()
                .expect("a lane with events has a loop");
            self.block
                .set_thrust(i, &lane_thrust(&c.end(m, &truth, user)));
        }
    }

    /// Steps the block, refilling lanes from `feed`, until every sample below
    /// `feed.window_end` is decided (in this worker or another), or until this block is
    /// empty and nothing is left to take. Lanes may hold samples of the next window when it
    /// returns; their rows come with a later call. Rows in no particular order.
    fn run(
        &mut self,
        scenario: &Scenario,
        model: &Model,
        params: &Params<K>,
        feed: &Feed,
    ) -> (Vec<Row>, LaneStats) {
        let mut rows = Vec::new();
        let mut stats = LaneStats::default();
        for i in 0..K::LANES {
            if self.samples[i].is_none() {
                self.refill(scenario, model, feed, i);
            }
        }
        while feed.outstanding.load(Ordering::Relaxed) > 0 {
            let busy = self.block.busy_lanes() as u64;
            if busy == 0 {
                break;
            }
            // The lanes change only between calls (a decision stops the kernel), so `busy`
            // holds for every step of one.
            let params = self.own.as_ref().unwrap_or(params);
            let advanced = K::advance(params, &mut self.block, STEPS_PER_CALL);
            stats.busy_lane_steps += busy * u64::from(advanced.steps);
            stats.lane_steps += K::LANES as u64 * u64::from(advanced.steps);
            let (decided, far) = (advanced.bits & 0xffff, advanced.bits >> 16);
            if far != 0 {
                for i in (0..K::LANES).filter(|i| far & (1 << i) != 0) {
                    self.block.recentre(i);
                }
            }
            if decided != 0 {
                for i in 0..K::LANES {
                    if decided & (1 << i) != 0 {
                        let sample = self.samples[i].expect("a decided lane holds a sample");
                        if sample.index < feed.window_end {
                            feed.outstanding.fetch_sub(1, Ordering::Relaxed);
                        }
                        let mut summary = lane_summary(&self.block, i);
                        if let (Some(m), Some(c)) = (&model.control, &mut self.control[i]) {
                            let left = self.block.thrust.event_in_s.lane(i);
                            summary.control = Some(Box::new(c.finish(m, left)));
                        }
                        rows.push(Row { sample, summary });
                        self.refill(scenario, model, feed, i);
                    }
                }
            }
            if advanced.events != 0
                && let Some(m) = &model.control
            {
                self.control_events(m, advanced.events);
            }
        }
        (rows, stats)
    }
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ran {
    pub stats: LaneStats,
    /// The first sample not handed to the sink: the end of the range, or where a stop left
    /// the rows (every sample before it was handed on, none after).
    pub end: u64,
}

/// Runs `range` on the current rayon pool with the widest kernel this CPU has, in the
/// scenario's precision (`simulation.precision`), one worker
/// (one block) per thread, handing rows to `sink` a window of `4 * chunk` samples per
/// thread at a time, in sample order. Stops early when `sink` returns an error.
pub fn run(
    scenario: &Scenario,
    model: &Model,
    range: Range<u64>,
    chunk: u64,
    sink: impl FnMut(Vec<Row>) -> anyhow::Result<()>,
) -> anyhow::Result<LaneStats> {
    let never = AtomicUsize::new(0);
    Ok(run_until(scenario, model, Isa::detect(), range, chunk, &never, sink)?.stats)
}

/// `run` with the kernel of `isa` (which this CPU must have), until `stop` becomes nonzero:
/// then no lane takes another sample, the samples in the lanes finish, and the rows of the
/// unbroken run of samples from the start of the range go to `sink` (a later sample whose
/// predecessors did not all finish is dropped).
///
/// The workers take samples one at a time from a shared counter. Once the samples of a
/// window run out, lanes go on to those of the next window while the last samples of this
/// one finish; their rows are kept for the next window. Memory holds two windows of rows
/// whatever the sample count.
pub fn run_until(
    scenario: &Scenario,
    model: &Model,
    isa: Isa,
    range: Range<u64>,
    chunk: u64,
    stop: &AtomicUsize,
    sink: impl FnMut(Vec<Row>) -> anyhow::Result<()>,
) -> anyhow::Result<Ran> {
    KernelKind {
        isa,
        precision: scenario.simulation.precision,
    }
    .dispatch(Sweep {
        scenario,
        model,
        range,
        chunk,
        stop,
        sink,
    })
}

/// The arguments of `run_until`, to run with the kernel `dispatch` picks.
struct Sweep<'a, F> {
    scenario: &'a Scenario,
    model: &'a Model,
    range: Range<u64>,
    chunk: u64,
    stop: &'a AtomicUsize,
    sink: F,
}

impl<F: FnMut(Vec<Row>) -> anyhow::Result<()>> WithKernel for Sweep<'_, F> {
    type Output = anyhow::Result<Ran>;

    fn run<K: Kernel>(self) -> anyhow::Result<Ran> {
        let Sweep {
            scenario,
            model,
            range,
            chunk,
            stop,
            mut sink,
        } = self;
        // Read by every thread at every step: never in a pair of cache lines with the
        // counters the threads write (see `Padded`).
        let params = Padded(kernel_params::<K>(model));
        let params = &params.0;
        let threads = rayon::current_num_threads();
        let window = chunk.max(1) * 4 * threads as u64;
        let per_sample = scenario.sampled.iter().any(Option::is_some);
        let mut workers: Vec<Worker<K>> = (0..threads)
            .map(|_| Worker::new(params, per_sample))
            .collect();
        let next = Padded(AtomicU64::new(range.start));
        let next = &next.0;
        let mut carried: Vec<Row> = Vec::new();
        let mut stats = LaneStats::default();
        let mut start = range.start;
        while start < range.end {
            let end = start.saturating_add(window).min(range.end);
            let done = carried.len() as u64;
            let outstanding = Padded(AtomicU64::new(end - start - done));
            let outstanding = &outstanding.0;
            let feed = Feed {
                stop,
                next,
                cap: end.saturating_add(window).min(range.end),
                window_end: end,
                outstanding,
            };
            let results: Vec<(Vec<Row>, LaneStats)> = if outstanding.load(Ordering::Relaxed) == 0 {
                Vec::new()
            } else {
                workers
                    .par_iter_mut()
                    .map(|w| w.run(scenario, model, params, &feed))
                    .collect()
            };
            let mut rows = std::mem::take(&mut carried);
            for (r, s) in results {
                stats = stats.add(s);
                for row in r {
                    if row.sample.index < end {
                        rows.push(row);
                    } else {
                        carried.push(row);
                    }
                }
            }
            rows.sort_unstable_by_key(|r| r.sample.index);
            if outstanding.load(Ordering::Relaxed) > 0 {
                // Stopped: keep the unbroken run from `start`, the rows of the next window too.
                rows.append(&mut carried);
                rows.sort_unstable_by_key(|r| r.sample.index);
                let unbroken = rows
                    .iter()
                    .zip(start..)
                    .take_while(|(r, i)| r.sample.index == *i)
                    .count();
                rows.truncate(unbroken);
                sink(rows)?;
                return Ok(Ran {
                    stats,
                    end: start + unbroken as u64,
                });
            }
            debug_assert_eq!(rows.len() as u64, end - start);
            sink(rows)?;
            start = end;
        }
        Ok(Ran {
            stats,
            end: range.end,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::{Model, Outcome, Scenario, Shard, kernel_params, lane_init, lane_summary};
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
            let s = lane_summary(&block, lane);
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
                numbers.extend([l.peak_normal_force_n, l.stroke_m, l.absorbed_j]);
            }
            assert!(
                numbers.iter().all(|x| x.is_finite()),
                "{what}: a result is not finite: {s:?}"
            );
        }
    }

    #[test]
    fn shards_cover_the_range_once_in_order() {
        for samples in [0, 1, 3, 4, 7, 1000, 1_000_003, u64::MAX] {
            for count in [1, 2, 3, 4, 7, 16] {
                let ranges: Vec<_> = (0..count)
                    .map(|index| Shard { index, count }.range(samples))
                    .collect();
                assert_eq!(ranges[0].start, 0);
                assert_eq!(ranges[ranges.len() - 1].end, samples);
                for w in ranges.windows(2) {
                    assert_eq!(w[0].end, w[1].start, "{samples} samples in {count} shards");
                }
                let sizes: Vec<u64> = ranges.iter().map(|r| r.end - r.start).collect();
                let (min, max) = (sizes.iter().min().unwrap(), sizes.iter().max().unwrap());
                assert!(max - min <= 1, "{samples} in {count}: sizes {sizes:?}");
            }
        }
    }

    #[test]
    fn shards_parse_as_k_of_n() {
        assert_eq!("0/4".parse(), Ok(Shard { index: 0, count: 4 }));
        assert_eq!("3/4".parse(), Ok(Shard { index: 3, count: 4 }));
        assert_eq!("0/1".parse(), Ok(Shard { index: 0, count: 1 }));
        for bad in ["4/4", "1/0", "0/0", "-1/4", "1", "a/b", "1/4/2", ""] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
