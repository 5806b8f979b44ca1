//! One worker: a block of lanes and the samples they hold, refilled from a shared counter,
//! stepped through the kernel (the hot loop) and through the control events.

use super::lanes::{kernel_params, lane_summary, lane_thrust, lane_truth, sample_lane_init};
use super::row::{LaneStats, Row};
use crate::control::{ControlModel, LAW_MEMORY, LaneControl, LawCommand, Phase, Sensed, Truth};
use crate::reference::Model;
use crate::sampling;
use crate::scenario::Sample;
use crate::scenario::Scenario;
use kernels::block::Block;
use kernels::isa::Kernel;
use kernels::lane::{Lane, MAX_LANES};
use kernels::params::Params;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex};

/// A value alone in its pair of cache lines: x86 cores fetch lines in pairs of 128 bytes,
/// so a line that one thread writes slows the threads that read the other line of its pair
/// as if they shared it (measured: 20 % of a two-thread sweep, when a counter the threads
/// write sat beside the parameters they read at every step).
#[repr(align(128))]
pub(super) struct Padded<T>(pub(super) T);

/// One block and the samples its lanes hold: a worker's state for the whole run, so that a
/// block never waits, half empty, for the last samples of a stretch. Aligned
/// to 128 bytes: the workers of two threads sit side by side, and x86 cores fetch cache
/// lines in pairs (see `kernels::block::LegLanes`).
#[repr(align(128))]
pub(super) struct Worker<L: Lane> {
    block: Block<L>,
    /// The parameters of each lane's sample, where the scenario draws parameters per sample
    /// (`Scenario::sampled`); otherwise the block steps with the sweep's, shared by all.
    own: Option<Params<L>>,
    /// The sample of each lane (the first `L::LANES` used).
    samples: [Option<Sample>; MAX_LANES],
    /// The control loop of each lane's sample (scenarios with one).
    /// (Boxed: the cohort moves landers between blocks at every control instant.)
    control: [Option<Box<LaneControl>>; MAX_LANES],
}

/// The most steps a worker asks of the kernel at once: the kernel returns sooner when a
/// lane is decided. Between calls the worker takes new samples into its empty lanes and
/// sees whether the run failed.
const STEPS_PER_CALL: u32 = 256;

/// Where a worker takes samples from, and when it may stop.
pub(super) struct Feed<'a> {
    /// Nonzero: take no more samples (the lanes finish the samples they hold).
    pub(super) stop: &'a AtomicUsize,
    /// Set: the run failed; the worker drops its lanes and returns.
    pub(super) failed: &'a AtomicBool,
    /// The next sample index to take.
    pub(super) next: &'a AtomicU64,
    /// Samples from `next` up to here may be taken now (the run moves it on as the rows
    /// before it are handed on).
    pub(super) cap: &'a AtomicU64,
    /// The end of the range.
    pub(super) end: u64,
    /// Guards the moves of `cap`, which `moved` announces.
    pub(super) sunk: &'a Mutex<u64>,
    pub(super) moved: &'a Condvar,
}

impl Feed<'_> {
    /// Whether the run failed.
    pub(super) fn failed(&self) -> bool {
        self.failed.load(Ordering::Relaxed)
    }

    /// The next sample index, if one below `cap` is left and the run goes on.
    pub(super) fn take(&self) -> Option<u64> {
        if self.stop.load(Ordering::Relaxed) != 0 || self.failed() {
            return None;
        }
        let cap = self.cap.load(Ordering::Relaxed);
        self.next
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |n| {
                (n < cap).then_some(n + 1)
            })
            .ok()
    }

    /// Whether no sample is left to take, ever.
    pub(super) fn exhausted(&self) -> bool {
        self.stop.load(Ordering::Relaxed) != 0
            || self.failed()
            || self.next.load(Ordering::Relaxed) >= self.end
    }

    /// Waits until `cap` moves (or a while, for a stop signal, which cannot wake it).
    pub(super) fn wait(&self) {
        let sunk = self.sunk.lock().expect("no thread panics holding it");
        if self.exhausted() || self.next.load(Ordering::Relaxed) < self.cap.load(Ordering::Relaxed)
        {
            return;
        }
        let _ = self
            .moved
            .wait_timeout(sunk, std::time::Duration::from_millis(20))
            .expect("no thread panics holding it");
    }
}

impl<K: Kernel> Worker<K> {
    pub(super) fn new(params: &Params<K>, per_sample: bool) -> Worker<K> {
        Worker {
            block: Block::new(params),
            own: per_sample.then(|| params.clone()),
            samples: [None; MAX_LANES],
            control: std::array::from_fn(|_| None),
        }
    }

    /// Puts the next sample of `feed` into lane `i`, or empties the lane if none is left
    /// now.
    fn refill(&mut self, scenario: &Scenario, model: &Model, feed: &Feed, i: usize) {
        if let Some(index) = feed.take() {
            self.load(scenario, model, i, index);
        } else {
            self.empty(i);
        }
    }

    /// Puts sample `index` into lane `i`.
    fn load(&mut self, scenario: &Scenario, model: &Model, i: usize, index: u64) {
        self.place(scenario, model, i, index);
        if let Some(m) = &model.control {
            // Its loop's start: its first instant, the law (if any) for it alone.
            self.block.take_touched(i);
            let truth = lane_truth(&self.block, i, false, false);
            let c = self.control[i].as_mut().expect("placed with its loop");
            self.block.set_thrust(i, &lane_thrust(&c.event(m, &truth)));
        }
    }

    /// Puts sample `index` into lane `i`, with its control loop not yet started (`load`
    /// starts it; the cohort, `begin_event` and `end_event`).
    pub(super) fn place(&mut self, scenario: &Scenario, model: &Model, i: usize, index: u64) {
        let s = sampling::sample(scenario, index);
        // The sample's own model, made once for its parameters and its initial state.
        let own_model = model.for_sample(&s);
        if let Some(own) = &mut self.own {
            own.copy_lane(i, &kernel_params(&own_model));
        }
        self.block.load(i, &sample_lane_init(&own_model, &s));
        self.samples[i] = Some(s);
        self.control[i] = model
            .control
            .as_ref()
            .map(|m| Box::new(LaneControl::new(m, &s)));
    }

    /// Number of lanes holding a lander.
    pub(super) fn busy(&self) -> usize {
        self.block.busy_lanes()
    }

    /// Whether lane `i` holds a lander.
    pub(super) fn holds(&self, i: usize) -> bool {
        self.samples[i].is_some()
    }

    /// Empties lane `i`.
    pub(super) fn empty(&mut self, i: usize) {
        self.block.retire(i);
        self.samples[i] = None;
        self.control[i] = None;
    }

    /// Takes the lander of lane `j` of `from` into lane `i` (which holds none): its state,
    /// parameters, sample and control loop; lane `j` of `from` is left empty.
    pub(super) fn take_lander(&mut self, i: usize, from: &mut Worker<K>, j: usize) {
        self.block.move_lane(i, &from.block, j);
        if let (Some(own), Some(theirs)) = (&mut self.own, &from.own) {
            own.copy_lane(i, theirs);
        }
        self.samples[i] = from.samples[j].take();
        self.control[i] = from.control[j].take();
        from.block.retire(j);
    }

    /// Whether a lander of the block will stop at its next control instant for the user's
    /// law: its loop is in the law's phase (the law has not said it is done).
    pub(super) fn any_bound(&self) -> bool {
        self.control
            .iter()
            .take(K::LANES)
            .flatten()
            .any(|c| c.phase() == Phase::User)
    }

    /// The law's memory of lane `i`'s lander.
    pub(super) fn memory(&mut self, i: usize) -> &mut [f64; LAW_MEMORY] {
        self.control[i]
            .as_mut()
            .expect("a lane with a loop")
            .memory()
    }

    /// The first half of lane `i`'s control event (`LaneControl::begin`): the reading the
    /// user's law must command, if it must, and the true state of the event.
    pub(super) fn begin_event(&mut self, m: &ControlModel, i: usize) -> (Option<Sensed>, Truth) {
        let touching = self
            .block
            .leg_step
            .iter()
            .any(|l| l.penetration_m.lane(i) > 0.0);
        let contact = self.block.take_touched(i);
        let truth = lane_truth(&self.block, i, contact, touching);
        let c = self.control[i]
            .as_mut()
            .expect("a lane with events has a loop");
        (c.begin(m, &truth), truth)
    }

    /// The second half (`LaneControl::end`), with the law's command `user` where
    /// `begin_event` asked for one: the lane's thrust until its next event.
    pub(super) fn end_event(
        &mut self,
        m: &ControlModel,
        i: usize,
        truth: &Truth,
        user: Option<&LawCommand>,
    ) {
        let c = self.control[i]
            .as_mut()
            .expect("a lane with events has a loop");
        self.block
            .set_thrust(i, &lane_thrust(&c.end(m, truth, user)));
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
            let (asked, truth) = self.begin_event(m, i);
            if let Some(s) = asked {
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
                memory[k] = *self.memory(i);
            }
            law.law.command(
                &readings[..count],
                &mut memory[..count],
                &mut commands[..count],
            );
            for (k, &i) in asking[..count].iter().enumerate() {
                *self.memory(i) = memory[k];
            }
        }
        for i in (0..K::LANES).filter(|i| events & (1 << i) != 0) {
            let truth = truths[i].expect("every event lane has its truth");
            let user = asking[..count]
                .iter()
                .position(|&a| a == i)
                .map(|k| &commands[k]);
            self.end_event(m, i, &truth, user);
        }
    }

    /// Steps the block once through the kernel (at most `STEPS_PER_CALL` steps, fewer where
    /// a lane is decided or at a control event), counting its lanes' steps into `stats`
    /// and recentring the lanes that ask for it: the lanes decided and the lanes at a
    /// control event, lane `i` in bit `i` of each.
    pub(super) fn advance(&mut self, params: &Params<K>, stats: &mut LaneStats) -> (u32, u32) {
        // The lanes change only between calls (a decision stops the kernel), so `busy`
        // holds for every step of one.
        let busy = self.block.busy_lanes() as u64;
        let lane_params = self.own.as_ref().unwrap_or(params);
        let advanced = K::advance(lane_params, &mut self.block, STEPS_PER_CALL);
        stats.busy_lane_steps += busy * u64::from(advanced.steps);
        stats.lane_steps += K::LANES as u64 * u64::from(advanced.steps);
        let (decided, far) = (advanced.bits & 0xffff, advanced.bits >> 16);
        if far != 0 {
            for i in (0..K::LANES).filter(|i| far & (1 << i) != 0) {
                self.block.recentre(i);
            }
        }
        (decided, advanced.events)
    }

    /// The row of lane `i`'s decided sample.
    pub(super) fn finish(&mut self, model: &Model, params: &Params<K>, i: usize) -> Row {
        let sample = self.samples[i].expect("a decided lane holds a sample");
        let soil = self.own.as_ref().unwrap_or(params).soil.as_ref();
        let mut summary = lane_summary(model, soil, &self.block, i);
        if let (Some(m), Some(c)) = (&model.control, &mut self.control[i]) {
            let left = self.block.thrust.event_in_s.lane(i);
            summary.control = Some(Box::new(c.finish(m, left)));
        }
        Row { sample, summary }
    }

    /// Steps the block, refilling lanes from `feed`, handing each decided sample's row to
    /// `deliver`, until nothing is left to take and the lanes are empty (or the run
    /// failed). A worker whose lanes are all empty while the feed holds samples back waits
    /// for it.
    pub(super) fn run(
        &mut self,
        scenario: &Scenario,
        model: &Model,
        params: &Params<K>,
        feed: &Feed,
        mut deliver: impl FnMut(Row),
    ) -> LaneStats {
        let mut stats = LaneStats::default();
        loop {
            if feed.failed() {
                return stats;
            }
            for i in 0..K::LANES {
                if self.samples[i].is_none()
                    && let Some(index) = feed.take()
                {
                    self.load(scenario, model, i, index);
                }
            }
            if self.block.busy_lanes() == 0 {
                if feed.exhausted() {
                    return stats;
                }
                feed.wait();
                continue;
            }
            let (decided, events) = self.advance(params, &mut stats);
            for i in (0..K::LANES).filter(|i| decided & (1 << i) != 0) {
                deliver(self.finish(model, params, i));
                self.refill(scenario, model, feed, i);
            }
            if events != 0
                && let Some(m) = &model.control
            {
                self.control_events(m, events);
            }
        }
    }
}
