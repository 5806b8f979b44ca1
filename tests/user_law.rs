//! A control law of the user's own (`control::Law`): the `touchdown` binary alone refuses
//! a scenario that names a law it does not have, naming the law, and the law of the
//! example program `examples/user_law` (its own code, included here) gives the same
//! outcomes in the kernels and in the scalar reference. (The example program's sweep is
//! tested in its own crate: examples/user_law/tests/sweep.rs.)

use crate::common::{TempDir, touchdown};
use std::path::Path;
use std::sync::atomic::AtomicUsize;
use touchdown::reference::{self, Model};
use touchdown::sampling;
use touchdown::scenario::Scenario;
use touchdown::sweep;

/// The example's law, `DampThenHold` (its `main` unused here).
#[allow(dead_code)]
#[path = "../examples/user_law/src/main.rs"]
mod example;

fn scenario_text() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/user-law.toml"))
        .unwrap()
}

#[test]
fn the_touchdown_binary_refuses_a_law_it_does_not_have() {
    let dir = TempDir::new("user_law_refused");
    let scenario = dir.write("scenario.toml", &scenario_text());
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            scenario.to_str().unwrap(),
            "--samples",
            "10",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr.contains("control.law") && run.stderr.contains("damp_then_hold"),
        "{run}"
    );
    assert!(
        dir.entries() == ["scenario.toml"],
        "no output file: {:?}",
        dir.entries()
    );
}

/// The example's law registered in this process: every sample of a sweep through the f64
/// kernels ends as the reference ends it. (The law only reads the sensors and a time, and
/// f64 kernels round as the reference does up to the order of sums: the measured
/// disagreement is none. A sample whose sensed contact or quantised command flips by a
/// rounding would show as a disagreement; the bound allows one in 200.)
#[test]
fn the_law_gives_the_same_outcomes_in_the_kernels_and_the_reference() {
    touchdown::control::register_law("damp_then_hold", example::DampThenHold);
    let scenario = Scenario::from_toml(&scenario_text()).unwrap();
    let model = Model::new(&scenario);
    let n = 200;
    let mut rows = Vec::new();
    let never = AtomicUsize::new(0);
    sweep::run_until(
        &scenario,
        &model,
        kernels::isa::Isa::detect(),
        0..n,
        64,
        &never,
        |r| {
            rows.extend(r);
            Ok(())
        },
    )
    .unwrap();
    let mut disagree = 0;
    let mut pushed = 0;
    for row in &rows {
        let r = reference::run(
            &model,
            &sampling::sample(&scenario, row.sample.index),
            |_| {},
        );
        let (rc, kc) = (r.control.unwrap(), row.summary.control.clone().unwrap());
        if r.outcome != row.summary.outcome {
            disagree += 1;
            continue;
        }
        // The user's law's push of 15 N along -Z_B once in contact is its hold-down: it
        // counts (the reference's as the kernels', to the propellant's tolerance).
        assert!(
            (rc.hold_down_impulse_n_s - kc.hold_down_impulse_n_s).abs()
                <= 1e-4 + 0.01 * rc.hold_down_impulse_n_s,
            "sample {}: hold-down impulse {} against {}",
            row.sample.index,
            rc.hold_down_impulse_n_s,
            kc.hold_down_impulse_n_s
        );
        assert!(
            (rc.propellant_kg - kc.propellant_kg).abs() <= 1e-6 + 0.01 * rc.propellant_kg,
            "sample {}: propellant {} against {}",
            row.sample.index,
            rc.propellant_kg,
            kc.propellant_kg
        );
        // 15 N for 8 s at Isp 220 s: 0.056 kg, besides the attitude firings.
        if kc.propellant_kg > 0.05 {
            pushed += 1;
            // Its 120 N s count as hold-down (0 before issue 29), give or take the on-times
            // quantised to whole 0.02 s (0.04 s for the 0.0375 s asked of each 10 N thruster
            // per 0.1 s period: +7 %) and the thrusters' 3 % magnitude errors: 122-134 N s
            // measured in 200 samples.
            assert!(
                (100.0..=150.0).contains(&kc.hold_down_impulse_n_s),
                "sample {}: hold-down impulse {}",
                row.sample.index,
                kc.hold_down_impulse_n_s
            );
        }
    }
    println!("{n} samples: {disagree} outcome disagreements, {pushed} pushed for 8 s");
    assert!(disagree * 200 <= n, "{disagree} of {n} disagree");
    assert!(
        pushed * 2 > n,
        "the law's hold-down ran in only {pushed} of {n}"
    );
}

/// The landers of each call of `Gathered`.
static CALLS: std::sync::Mutex<Vec<usize>> = std::sync::Mutex::new(Vec::new());

/// The example's law, gathered (`Law::gathered`): the sweep calls it once per control
/// instant for every lander of a worker at it; it counts the landers of each call.
struct Gathered;

impl touchdown::control::Law for Gathered {
    fn command(
        &self,
        sensed: &[touchdown::control::Sensed],
        memory: &mut [[f64; touchdown::control::LAW_MEMORY]],
        out: &mut [touchdown::control::LawCommand],
    ) {
        CALLS.lock().unwrap().push(sensed.len());
        touchdown::control::Law::command(&example::DampThenHold, sensed, memory, out);
    }

    fn gathered(&self) -> bool {
        true
    }
}

/// The rows of a sweep of `scenario`'s samples `0..n` on `threads` workers.
fn rows_of(scenario: &Scenario, n: u64, threads: usize) -> Vec<sweep::Row> {
    let model = Model::new(scenario);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let mut rows = Vec::new();
    pool.install(|| {
        sweep::run(scenario, &model, 0..n, 64, |r| {
            rows.extend(r);
            Ok(())
        })
    })
    .unwrap();
    rows
}

/// The landers gathered at their control instants (`sweep::cohort`: moved between blocks
/// at every instant, new samples started only at one) step exactly as in their own lanes:
/// every row equals the plain worker's, to the bit, on one worker and on two; and the
/// calls hold hundreds of landers (on one worker the median call at least 256, measured
/// 508; a worker holds at most 512), not the one or two of the plain worker's block.
#[test]
fn gathered_landers_give_the_same_rows_in_calls_of_hundreds() {
    touchdown::control::register_law("damp_then_hold", example::DampThenHold);
    touchdown::control::register_law("damp_then_hold_gathered", Gathered);
    let plain = Scenario::from_toml(&scenario_text()).unwrap();
    let gathered = Scenario::from_toml(
        &scenario_text().replace("\"damp_then_hold\"", "\"damp_then_hold_gathered\""),
    )
    .unwrap();
    let n = 1500;
    let expected = rows_of(&plain, n, 2);
    assert_eq!(expected.len(), n as usize);
    for threads in [1, 2] {
        CALLS.lock().unwrap().clear();
        let rows = rows_of(&gathered, n, threads);
        assert_eq!(rows.len(), expected.len(), "{threads} threads");
        // (Compared as printed: every number to the bit, and NaN, which the law's
        // columns hold where a built-in law's parameters are not drawn, equal to NaN.)
        for (a, b) in expected.iter().zip(&rows) {
            assert_eq!(
                format!("{a:?}"),
                format!("{b:?}"),
                "sample {} on {threads} threads",
                a.sample.index
            );
        }
        let mut sizes = CALLS.lock().unwrap().clone();
        sizes.sort_unstable();
        let median = sizes[sizes.len() / 2];
        let total: usize = sizes.iter().sum();
        println!(
            "{threads} threads: {} calls, {total} landers, median {median}, largest {}",
            sizes.len(),
            sizes.last().unwrap()
        );
        assert!(*sizes.last().unwrap() <= 512);
        // On one worker the calls are the same in every run (on two, how the workers
        // share the samples decides them: 316 landers the median call, measured).
        if threads == 1 {
            assert!(median >= 256, "median call {median} landers on one worker");
        }
    }
}
