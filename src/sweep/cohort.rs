//! A worker whose landers meet at their control instants (scenarios with a law of the
//! user's own): one call of the law per instant for every lander of the worker at it, not
//! one per block for the few lanes that happen to reach it together.
//!
//! Every sample's control instants lie at `k P` from its start, so samples started at one
//! instant meet at every later one. The worker holds up to `COHORT` landers: those stepping
//! in its block, and the others parked in blocks of their own (`Block::move_lane`: a lander
//! steps the same, to the bit, whatever lane holds it). A lander whose loop asks the law at
//! an instant leaves the block for the park, and a lander parked behind takes its lane; once
//! every lander the law commands has reached the instant, new samples start there (their
//! first instant is that one), the law is called once for all of them, and they step on.
//! Landers the law no longer commands (its `done`, or a phase of a built-in law) step on
//! without waiting. Rows, memory and the law's calls are each lander's own, so the file is
//! the same as the plain worker's (`Worker::run`) for any thread count.

use super::row::{LaneStats, Row};
use super::worker::{Feed, Worker};
use crate::control::{ControlModel, LAW_MEMORY, LawCommand, NamedLaw, Sensed, Truth};
use crate::reference::Model;
use crate::scenario::Scenario;
use kernels::isa::Kernel;
use kernels::params::Params;

/// The most landers a worker holds at once: the most rows a call of the law takes.
pub(super) const COHORT: usize = 512;

/// Where a lander waits: a parked block and its lane.
#[derive(Debug, Clone, Copy)]
struct Slot {
    block: usize,
    lane: usize,
}

/// A lander at a control instant, waiting for the law: where it is parked, what its
/// sensors read and the true state its loop's command is issued for.
struct Arrived {
    slot: Slot,
    sensed: Sensed,
    truth: Truth,
}

/// The landers of one worker and where each stands in the current control period.
pub(super) struct Cohort<K: Kernel> {
    /// The block that steps.
    run: Worker<K>,
    /// The parked landers' blocks.
    park: Vec<Worker<K>>,
    /// Parked lanes holding no lander.
    free: Vec<Slot>,
    /// Parked landers to step before the instant (their law has commanded them).
    behind: Vec<Slot>,
    /// Parked landers at the instant, waiting for the law.
    arrived: Vec<Arrived>,
    /// Landers held (stepping or parked).
    live: usize,
}

impl<K: Kernel> Cohort<K> {
    pub(super) fn new(params: &Params<K>, per_sample: bool) -> Cohort<K> {
        let blocks = COHORT.div_ceil(K::LANES);
        let park = (0..blocks)
            .map(|_| Worker::new(params, per_sample))
            .collect();
        // Taken from the end: the first slots first.
        let free = (0..blocks)
            .rev()
            .flat_map(|block| (0..K::LANES).rev().map(move |lane| Slot { block, lane }))
            .collect();
        Cohort {
            run: Worker::new(params, per_sample),
            park,
            free,
            behind: Vec::new(),
            arrived: Vec::new(),
            live: 0,
        }
    }

    /// As `Worker::run`, with the law of `model`'s control loop (which it must have)
    /// called once per instant for every lander at it.
    pub(super) fn run(
        &mut self,
        scenario: &Scenario,
        model: &Model,
        params: &Params<K>,
        feed: &Feed,
        mut deliver: impl FnMut(Row),
    ) -> LaneStats {
        let m = model.control.as_ref().expect("a control loop");
        let law = m.law.as_ref().expect("a law of the user's own");
        let mut stats = LaneStats::default();
        loop {
            if feed.failed() {
                return stats;
            }
            self.fill();
            if self.behind.is_empty() && !self.run.any_bound() {
                // Every lander the law commands is at the instant: new samples start here,
                // and the law commands them all at once.
                self.start_samples(scenario, model, m, feed);
                self.command(m, law);
                self.fill();
            }
            if self.run.busy() == 0 {
                if self.live == 0 {
                    if feed.exhausted() {
                        return stats;
                    }
                    feed.wait();
                }
                continue;
            }
            let (decided, events) = self.run.advance(params, &mut stats);
            for i in (0..K::LANES).filter(|i| decided & (1 << i) != 0) {
                deliver(self.run.finish(model, params, i));
                self.run.empty(i);
                self.live -= 1;
            }
            for i in (0..K::LANES).filter(|i| events & (1 << i) != 0) {
                let (asked, truth) = self.run.begin_event(m, i);
                match asked {
                    Some(sensed) => {
                        let slot = self.free.pop().expect("a lane for every lander held");
                        self.park[slot.block].take_lander(slot.lane, &mut self.run, i);
                        self.arrived.push(Arrived {
                            slot,
                            sensed,
                            truth,
                        });
                    }
                    None => self.run.end_event(m, i, &truth, None),
                }
            }
        }
    }

    /// Fills the stepping block's empty lanes with parked landers behind the instant.
    fn fill(&mut self) {
        for i in 0..K::LANES {
            if self.run.holds(i) {
                continue;
            }
            let Some(slot) = self.behind.pop() else {
                return;
            };
            self.run
                .take_lander(i, &mut self.park[slot.block], slot.lane);
            self.free.push(slot);
        }
    }

    /// Starts new samples of `feed` in free parked lanes, up to `COHORT` landers held: at
    /// their first instant, waiting for the law or behind it.
    fn start_samples(&mut self, scenario: &Scenario, model: &Model, m: &ControlModel, feed: &Feed) {
        while self.live < COHORT {
            let Some(&slot) = self.free.last() else {
                return;
            };
            let Some(index) = feed.take() else {
                return;
            };
            self.free.pop();
            let parked = &mut self.park[slot.block];
            parked.place(scenario, model, slot.lane, index);
            self.live += 1;
            let (asked, truth) = parked.begin_event(m, slot.lane);
            match asked {
                Some(sensed) => self.arrived.push(Arrived {
                    slot,
                    sensed,
                    truth,
                }),
                None => {
                    parked.end_event(m, slot.lane, &truth, None);
                    self.behind.push(slot);
                }
            }
        }
    }

    /// Calls the law once for every lander at the instant and gives each its command: they
    /// are behind the next instant.
    fn command(&mut self, m: &ControlModel, law: &NamedLaw) {
        if self.arrived.is_empty() {
            return;
        }
        let sensed: Vec<Sensed> = self.arrived.iter().map(|a| a.sensed).collect();
        let mut memory: Vec<[f64; LAW_MEMORY]> = self
            .arrived
            .iter()
            .map(|a| *self.park[a.slot.block].memory(a.slot.lane))
            .collect();
        let mut commands = vec![LawCommand::default(); sensed.len()];
        law.law.command(&sensed, &mut memory, &mut commands);
        // Behind in the order they arrived (taken from the end: the last first).
        for ((a, memory), command) in self.arrived.drain(..).zip(&memory).zip(&commands) {
            let parked = &mut self.park[a.slot.block];
            *parked.memory(a.slot.lane) = *memory;
            parked.end_event(m, a.slot.lane, &a.truth, Some(command));
            self.behind.push(a.slot);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::reference::Model;
    use crate::scenario::Scenario;
    use crate::sweep::kernel_params;
    use kernels::block::Block;
    use kernels::isa::{Isa, Kernel, KernelKind, Precision, WithKernel};

    /// Writes `base`, `base + 1`, ... into every 8 bytes of `x` (a struct of lanes of
    /// numbers and masks: any bits are a value of it).
    fn fill<T: Copy>(x: &mut T, base: f64) {
        let p = std::ptr::from_mut(x).cast::<f64>();
        for k in 0..size_of::<T>() / 8 {
            // SAFETY: within `x`, whose fields are numbers of any bits.
            unsafe { p.add(k).write_unaligned(base + k as f64) };
        }
    }

    /// Every number of `b`'s state a distinct value from `base` on.
    fn filled<K: Kernel>(b: &mut Block<K>, base: f64) {
        let mut at = base;
        let mut next = || {
            at += 1000.0;
            at
        };
        for leg in &mut b.legs {
            fill(leg, next());
        }
        for step in &mut b.leg_step {
            fill(step, next());
        }
        fill(&mut b.surface, next());
        // (The tiles' arrays are `MAX_LANES` long: past `K::LANES`, no lane's, as new.)
        b.surface.tile[K::LANES..].fill(0);
        b.surface.rock_tile[K::LANES..].fill(0);
        fill(&mut b.track, next());
        fill(&mut b.thrust, next());
        fill(&mut b.t_s, next());
        fill(&mut b.t_error_s, next());
        fill(&mut b.position_m, next());
        fill(&mut b.velocity_m_s, next());
        fill(&mut b.attitude, next());
        fill(&mut b.rotation, next());
        fill(&mut b.rate_rad_s, next());
        fill(&mut b.active, next());
        fill(&mut b.contact_step_s, next());
        fill(&mut b.force_n, next());
        fill(&mut b.moment_n_m, next());
        fill(&mut b.start_position_m, next());
        fill(&mut b.start_velocity_m_s, next());
        fill(&mut b.start_rotation, next());
        fill(&mut b.start_rate_rad_s, next());
        fill(&mut b.start_t_s, next());
        fill(&mut b.dt_s, next());
    }

    /// `Block::move_lane` moves every number of a lander's state: a block whose every
    /// number is distinct, moved lane by lane into a block of other numbers in another
    /// order and back into a third, comes back as it was (printed: masks as the lanes
    /// hold them). A field `move_lane` forgot would keep the third block's number. The
    /// sub-structs (legs, steps, surface, track, thrust) are filled whole, so a field added
    /// to them is checked without naming it here; with every f64 kernel this CPU has.
    #[test]
    fn a_moved_lane_carries_every_number_of_its_state() {
        struct Moves;
        impl WithKernel for Moves {
            type Output = ();
            fn run<K: Kernel>(self) {
                let model = Model::new(&Scenario::default());
                let params = kernel_params::<K>(&model);
                let fresh = || Block::<K>::new(&params);
                let (mut a, mut canonical, mut b, mut c) = (fresh(), fresh(), fresh(), fresh());
                filled(&mut a, 0.5);
                // Moved once, its masks hold what a lane's mask holds (all bits or none).
                for i in 0..K::LANES {
                    canonical.move_lane(i, &a, i);
                }
                filled(&mut b, 1e6 + 0.25);
                filled(&mut c, 2e6 + 0.75);
                let other = |i: usize| (i + 3) % K::LANES;
                for i in 0..K::LANES {
                    b.move_lane(other(i), &canonical, i);
                }
                for i in 0..K::LANES {
                    c.move_lane(i, &b, other(i));
                }
                let (got, want) = (format!("{c:?}"), format!("{canonical:?}"));
                // Where they part, with the field before it.
                let at = got
                    .bytes()
                    .zip(want.bytes())
                    .position(|(a, b)| a != b)
                    .unwrap_or(got.len().min(want.len()));
                let from = got[..at]
                    .rfind(": ")
                    .map_or(0, |i| got[..i].rfind(' ').unwrap_or(0));
                assert!(
                    got == want,
                    "{}: a number not moved, at {}",
                    K::NAME,
                    &got[from..(at + 40).min(got.len())]
                );
                assert_ne!(format!("{b:?}"), format!("{canonical:?}"), "{}", K::NAME);
            }
        }
        for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
            KernelKind {
                isa,
                precision: Precision::F64,
            }
            .dispatch(Moves);
        }
    }
}
