//! The accuracy contract of the contact step's error control (MODEL.md section 2.1): a
//! controlled sweep is at least as accurate as the fixed 1 ms step, both judged against the
//! same sweep at a quarter of that step, paired sample by sample (one seed). Each outcome
//! share may differ from the quarter step's by no more than the fixed step's does, or by
//! 0.5 points, whichever is larger; the design values at 99 % (the largest leg's peak axial
//! strut load, its stroke where dampers crush, the peak CG acceleration) by at most 1 %.
//!
//! Here on the MuJoCo-matched scenario (stiff contact, 3e5 N/m: where the fixed step is
//! least converged), 5000 samples; `tests/step-contract/run.sh` runs the whole contract over
//! every scenario of `scenarios/` with the CLI (`touchdown compare`). The contract must be
//! able to fail: at ten times the recommended tolerance it does.

use kernels::isa::Isa;
use std::sync::atomic::AtomicUsize;
use touchdown::exceedance::design_value;
use touchdown::reference::{Model, Outcome, Summary};
use touchdown::scenario::Scenario;

/// Samples of each sweep: enough that a share's paired difference has a 95 % interval of
/// about +-0.3 points where few samples change outcome (the contract's 0.5 points is then
/// not lost in the noise of the draws; the sweeps are deterministic, so the test is too).
const SAMPLES: u64 = 5000;

/// The recommended tolerance (README, MODEL.md section 2.1), m/s.
const TOLERANCE_M_S: f64 = 1e-4;

fn matched() -> Scenario {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/mujoco-matched.toml");
    Scenario::from_toml(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The summaries of `SAMPLES` samples of `scenario`, in sample order.
fn sweep(scenario: &Scenario) -> Vec<Summary> {
    let model = Model::new(scenario);
    let never = AtomicUsize::new(0);
    let mut rows = Vec::new();
    touchdown::sweep::run_until(
        scenario,
        &model,
        Isa::detect(),
        0..SAMPLES,
        256,
        &never,
        |r| {
            rows.extend(r);
            Ok(())
        },
    )
    .unwrap();
    rows.sort_by_key(|r| r.sample.index);
    rows.into_iter().map(|r| r.summary).collect()
}

/// What the contract compares: the share of each outcome, and the design values at 99 %.
struct Answers {
    shares: Vec<(Outcome, f64)>,
    design: Vec<(&'static str, f64)>,
}

fn answers(rows: &[Summary]) -> Answers {
    let n = rows.len() as f64;
    let shares = Outcome::ALL
        .iter()
        .map(|&o| (o, rows.iter().filter(|r| r.outcome == o).count() as f64 / n))
        .collect();
    let at_99 = |f: &dyn Fn(&Summary) -> f64| {
        let mut v: Vec<f64> = rows.iter().map(f).collect();
        v.sort_by(f64::total_cmp);
        design_value(&v, 0.99).map_or(0.0, |d| d.value)
    };
    let largest = |f: fn(&touchdown::reference::outcome::LegSummary) -> f64| {
        move |r: &Summary| r.legs.iter().map(f).fold(0.0, f64::max)
    };
    let design = vec![
        (
            "peak axial strut load",
            at_99(&largest(|l| l.peak_axial_force_n)),
        ),
        ("damper stroke", at_99(&largest(|l| l.stroke_m))),
        ("peak CG acceleration", at_99(&|r| r.peak_acceleration_m_s2)),
    ];
    Answers { shares, design }
}

/// Where `controlled` breaks the contract against `quarter`, with `fixed` the fixed step's
/// answers: one line per broken point (none: it holds).
fn broken(controlled: &Answers, fixed: &Answers, quarter: &Answers) -> Vec<String> {
    let mut out = Vec::new();
    for ((&(o, c), &(_, f)), &(_, q)) in controlled
        .shares
        .iter()
        .zip(&fixed.shares)
        .zip(&quarter.shares)
    {
        let allowed = (f - q).abs().max(0.005);
        if (c - q).abs() > allowed + 1e-12 {
            out.push(format!(
                "{}: {:.2} % against the quarter step's {:.2} % (allowed +-{:.2} points)",
                o.name(),
                100.0 * c,
                100.0 * q,
                100.0 * allowed
            ));
        }
    }
    for (&(name, c), &(_, q)) in controlled.design.iter().zip(&quarter.design) {
        if q == 0.0 && c == 0.0 {
            continue; // no dampers: no stroke
        }
        if (c - q).abs() > 0.01 * q.abs() {
            out.push(format!(
                "{name} at 99 %: {c:.4} against the quarter step's {q:.4} (allowed 1 %)"
            ));
        }
    }
    out
}

#[test]
fn the_error_control_is_as_accurate_as_the_fixed_step() {
    let scenario = matched();
    let at = |step_s: f64, tolerance: Option<f64>| {
        let mut s = scenario.clone();
        s.simulation.step_s = step_s;
        s.simulation.step_min_s = step_s / 8.0;
        s.simulation.step_max_s = 2.0 * step_s;
        s.simulation.tolerance_m_s = tolerance;
        sweep(&s)
    };
    let step_s = scenario.simulation.step_s;
    let quarter = answers(&at(step_s / 4.0, None));
    let fixed_rows = at(step_s, None);
    let fixed = answers(&fixed_rows);
    let controlled_rows = at(step_s, Some(TOLERANCE_M_S));
    let controlled = answers(&controlled_rows);
    let loose = answers(&at(step_s, Some(10.0 * TOLERANCE_M_S)));
    let steps =
        |rows: &[Summary]| rows.iter().map(|r| r.steps).sum::<u64>() as f64 / rows.len() as f64;
    println!(
        "steps a sample: fixed {:.0}, controlled {:.0}",
        steps(&fixed_rows),
        steps(&controlled_rows)
    );
    for (name, a) in [
        ("quarter", &quarter),
        ("fixed", &fixed),
        ("controlled", &controlled),
        ("loose", &loose),
    ] {
        let shares: Vec<String> = a
            .shares
            .iter()
            .map(|(o, s)| format!("{} {:.2} %", o.name(), 100.0 * s))
            .collect();
        let design: Vec<String> = a
            .design
            .iter()
            .map(|(n, v)| format!("{n} {v:.4}"))
            .collect();
        println!("{name}: {}; {}", shares.join(", "), design.join(", "));
    }
    let at_tolerance = broken(&controlled, &fixed, &quarter);
    assert!(
        at_tolerance.is_empty(),
        "the contract breaks at {TOLERANCE_M_S} m/s:\n{}",
        at_tolerance.join("\n")
    );
    let tenfold = broken(&loose, &fixed, &quarter);
    println!("at ten times the tolerance:\n{}", tenfold.join("\n"));
    assert!(
        !tenfold.is_empty(),
        "the contract holds even at ten times the tolerance: it tests nothing"
    );
}
