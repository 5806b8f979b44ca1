//! Throughput: the SIMD step kernel and the scalar reference on the same states
//! (lander-steps/s), and whole small sweeps of the default and the MuJoCo-matched scenario
//! (samples/s).
//!
//! The states are the first second of eight touchdowns of the default sweep: legs in and
//! out of contact, the expensive part of a sample (free flight takes long steps).

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use kernels::block::Block;
use kernels::isa::{Isa, Kernel, WithKernel};
use kernels::lane::LANES;
use std::hint::black_box;
use touchdown::reference::model::Surface;
use touchdown::reference::outcome::Tracker;
use touchdown::reference::step::{step, step_size};
use touchdown::reference::{Model, StepReport, initial_state};
use touchdown::sampling::sample;
use touchdown::scenario::Scenario;
use touchdown::sweep::{kernel_params, lane_init};

const STEPS: u64 = 1000;

fn kernel_vs_reference(c: &mut Criterion) {
    let scenario = Scenario::default();
    let model = Model::new(&scenario);
    let samples: Vec<_> = (0..LANES as u64).map(|i| sample(&scenario, i)).collect();

    let mut g = c.benchmark_group("step");
    g.throughput(Throughput::Elements(LANES as u64 * STEPS));
    // Every kernel this CPU runs, on the same states.
    struct Bench<'a, 'b> {
        group: &'a mut criterion::BenchmarkGroup<'b, criterion::measurement::WallTime>,
        model: &'a Model,
        samples: &'a [touchdown::sampling::Sample],
        key: &'static str,
    }
    impl WithKernel for Bench<'_, '_> {
        type Output = ();
        fn run<K: Kernel>(self) {
            let params = kernel_params::<K>(self.model);
            let mut block = Block::new(&params);
            for (i, s) in self.samples.iter().enumerate() {
                block.load(i, &lane_init(self.model, s));
            }
            self.group
                .bench_function(format!("kernel_f64x8_{}", self.key), |b| {
                    b.iter_batched_ref(
                        || block.clone(),
                        |blk| {
                            for _ in 0..STEPS {
                                black_box(K::advance(&params, blk));
                            }
                        },
                        BatchSize::SmallInput,
                    );
                });
        }
    }
    for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
        isa.dispatch(Bench {
            group: &mut g,
            model: &model,
            samples: &samples,
            key: isa.key(),
        });
    }
    let starts: Vec<_> = samples
        .iter()
        .map(|s| {
            let surface = Surface::of(s);
            (surface, initial_state(&model, &surface, s))
        })
        .collect();
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
    let scenario = Scenario::from_toml("[simulation]\nt_max_s = 20.0").unwrap();
    let model = Model::new(&scenario);
    let n = 2000;
    let mut g = c.benchmark_group("sweep");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n));
    g.bench_function("default_scenario_t_max_20s", |b| {
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
    // The scenario matched to the MuJoCo reference run (../shared/anchors/mujoco/): the
    // samples/s to compare with MuJoCo's, taken right after it on the same machine.
    let matched = Scenario::from_toml(include_str!("../scenarios/mujoco-matched.toml")).unwrap();
    let matched_model = Model::new(&matched);
    let n_matched = 1000;
    g.throughput(Throughput::Elements(n_matched));
    g.bench_function("mujoco_matched_scenario", |b| {
        b.iter(|| {
            let mut rows = 0;
            touchdown::sweep::run(&matched, &matched_model, 0..n_matched, 256, |r| {
                rows += r.len();
                Ok(())
            })
            .unwrap();
            black_box(rows)
        });
    });
    g.finish();
}

criterion_group!(benches, kernel_vs_reference, sweep);
criterion_main!(benches);
