//! Throughput: the SIMD step kernel and the scalar reference on the same states
//! (lander-steps/s), and whole small sweeps of the default and the MuJoCo-matched scenario
//! (samples/s).
//!
//! The states are the first second of the first touchdowns of the default sweep (eight for
//! f64 lanes, sixteen for f32, in as many blocks as the kernel's width takes: one of
//! AVX-512, two of AVX2): legs in and out of contact, the expensive part of a sample (free
//! flight takes long steps). The reference steps the first eight.
//!
//! Every kernel this CPU runs, in both precisions: `step/kernel_f64x8_avx512`,
//! `step/kernel_f32x16_avx512`, `step/kernel_f64x4_avx2`, ...; sweeps in f64 and f32.

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use kernels::block::Block;
use kernels::isa::{Isa, Kernel, KernelKind, Precision, WithKernel};
use std::hint::black_box;
use touchdown::reference::outcome::Tracker;
use touchdown::reference::step::{step, step_size};
use touchdown::reference::{Model, StepReport, initial_state};
use touchdown::sampling::sample;
use touchdown::scenario::Scenario;
use touchdown::slope::Surface;
use touchdown::sweep::{kernel_params, lane_init};

const STEPS: u64 = 1000;

fn kernel_vs_reference(c: &mut Criterion) {
    let scenario = Scenario::default();
    let model = Model::new(&scenario);
    let samples: Vec<_> = (0..16).map(|i| sample(&scenario, i)).collect();

    let mut g = c.benchmark_group("step");
    // Every kernel this CPU runs, on the same states.
    struct Bench<'a, 'b> {
        group: &'a mut criterion::BenchmarkGroup<'b, criterion::measurement::WallTime>,
        model: &'a Model,
        samples: &'a [touchdown::scenario::Sample],
        key: &'static str,
        precision: Precision,
    }
    impl WithKernel for Bench<'_, '_> {
        type Output = ();
        fn run<K: Kernel>(self) {
            let params = kernel_params::<K>(self.model);
            // The same landers for every width of the precision.
            let landers = match self.precision {
                Precision::F64 => 8,
                Precision::F32 => 16,
            };
            let blocks: Vec<_> = self.samples[..landers]
                .chunks(K::LANES)
                .map(|samples| {
                    let mut block = Block::new(&params);
                    for (i, s) in samples.iter().enumerate() {
                        block.load(i, &lane_init(self.model, s));
                    }
                    block
                })
                .collect();
            let lanes = format!("{}x{}", self.precision.key(), K::LANES);
            self.group
                .throughput(Throughput::Elements(landers as u64 * STEPS))
                .bench_function(format!("kernel_{lanes}_{}", self.key), |b| {
                    b.iter_batched_ref(
                        || blocks.clone(),
                        |blocks| {
                            // As a sweep calls it: many steps at once, back after a step
                            // that decides a lane (the bench keeps it in the block, where
                            // it steps on, reported no more) or moves one far enough to
                            // be recentred (f32: as the sweep, it is).
                            for blk in blocks.iter_mut() {
                                let mut taken = 0;
                                while taken < STEPS {
                                    let advanced = K::advance(&params, blk, (STEPS - taken) as u32);
                                    taken += u64::from(advanced.steps);
                                    for i in
                                        (0..K::LANES).filter(|i| advanced.bits >> 16 & 1 << i != 0)
                                    {
                                        blk.recentre(i);
                                    }
                                }
                                black_box(&blk.t_s);
                            }
                        },
                        BatchSize::SmallInput,
                    );
                });
        }
    }
    for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
        for precision in Precision::ALL {
            KernelKind { isa, precision }.dispatch(Bench {
                group: &mut g,
                model: &model,
                samples: &samples,
                key: isa.key(),
                precision,
            });
        }
    }
    let starts: Vec<_> = samples[..8]
        .iter()
        .map(|s| {
            let surface = Surface::of(s);
            (surface, initial_state(&model, &surface, s))
        })
        .collect();
    g.throughput(Throughput::Elements(starts.len() as u64 * STEPS));
    g.bench_function("reference_scalar", |b| {
        b.iter_batched_ref(
            || starts.clone(),
            |landers| {
                let mut report = StepReport::new(model.legs.len());
                for (surface, state) in landers.iter_mut() {
                    let mut tracker = Tracker::new(&model, state);
                    for _ in 0..STEPS {
                        let dt = step_size(&model, surface, state);
                        step(&model, surface, state, dt, &mut report);
                        black_box(tracker.observe(&model, surface, &report, state));
                    }
                }
            },
            BatchSize::SmallInput,
        );
    });
    g.finish();
}

fn sweep(c: &mut Criterion) {
    let mut g = c.benchmark_group("sweep");
    g.sample_size(10);
    // The default scenario to 20 s, and the scenario matched to the MuJoCo reference run
    // (../shared/anchors/mujoco/): the samples/s to compare with MuJoCo's, taken right
    // after it on the same machine. Each in f64 and in f32 lanes.
    let default = Scenario::from_toml("[simulation]\nt_max_s = 20.0").unwrap();
    let matched = Scenario::from_toml(include_str!("../scenarios/mujoco-matched.toml")).unwrap();
    for (name, scenario, n) in [
        ("default_scenario_t_max_20s", default, 2000),
        ("mujoco_matched_scenario", matched, 1000),
    ] {
        for precision in Precision::ALL {
            let mut scenario = scenario.clone();
            scenario.simulation.precision = precision;
            let model = Model::new(&scenario);
            g.throughput(Throughput::Elements(n));
            let id = match precision {
                Precision::F64 => name.to_string(),
                Precision::F32 => format!("{name}_f32"),
            };
            g.bench_function(id, |b| {
                b.iter(|| {
                    let mut rows = 0;
                    touchdown::sweep::run(&scenario, &model, 0..n, 256, |r| {
                        rows += r.len();
                        Ok(())
                    })
                    .unwrap();
                    black_box(rows)
                });
            });
        }
    }
    g.finish();
}

criterion_group!(benches, kernel_vs_reference, sweep);
criterion_main!(benches);
