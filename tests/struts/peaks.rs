//! The sweep's strut-load peaks and their times against the trace of the same sample.

use super::Columns;
use crate::common::{TempDir, touchdown};
use touchdown::reference::{self, Model};
use touchdown::sampling;
use touchdown::scenario::Scenario;

/// The default sweep with dampers, flights cut at 20 s.
const DAMPED: &str = "[damper]\nenabled = true\n\n[simulation]\nt_max_s = 20.0\n";

/// The largest value of a trace's per-step column (every row but the last, the state at
/// the decision, which is no step) and the time of its first row.
fn trace_peak(t: &Columns, column: &str) -> (f64, Option<f64>) {
    let (values, times) = (t.f64s(column), t.f64s("t_s"));
    let steps = values.len() - 1;
    let mut peak = (0.0, None);
    for r in 0..steps {
        if values[r] > peak.0 {
            peak = (values[r], Some(times[r]));
        }
    }
    peak
}

/// Whether the trace's step starting within half a step (0.5 ms) of `t_s` reaches `peak`
/// in `column`, within 1e-9 of it.
fn reaches(t: &Columns, column: &str, t_s: f64, peak: f64) -> bool {
    let (values, times) = (t.f64s(column), t.f64s("t_s"));
    (0..values.len() - 1)
        .any(|r| (times[r] - t_s).abs() <= 0.5e-3 && values[r] >= peak - 1e-9 * peak)
}

#[test]
fn the_sweeps_peaks_and_times_are_the_maxima_of_the_traces_columns() {
    // For 8 samples of the default sweep with dampers (4 legs): each leg's peak axial and
    // side load, and the start of its step, against the trace of the sample (every step):
    // the reference's summary of the sample equals the trace's maximum and that row's time
    // bit for bit (both are the reference, the same steps); the sweep's row (the kernels)
    // equals the peak within 1e-9 of it, at the start of a step (within half a step,
    // 0.5 ms) where the trace reaches it: the kernels compute the same formulas with fused
    // multiply-adds, and the peak comes at an impact, before rounding can grow through
    // bounces (measured: within 3e-14 of the peak; where a crushing damper holds the load
    // at its crush force for many steps, the first of them may differ by rounding). A sample whose outcome kernel and reference decide otherwise
    // (none here) would be exempt, as in `agreement`.
    let dir = TempDir::new("struts-peaks");
    dir.write("damped.toml", DAMPED);
    let samples = 8;
    super::sweep(
        &dir,
        &[
            "--scenario",
            "damped.toml",
            "--samples",
            &samples.to_string(),
            "--out",
            "s.arrow",
            "--quiet",
        ],
    );
    let sweep = Columns::in_dir(&dir, "s.arrow");
    let scenario = Scenario::from_toml(DAMPED).unwrap();
    let model = Model::new(&scenario);
    let mut failures = Vec::new();
    for i in 0..samples {
        let out = format!("t{i}.arrow");
        touchdown(
            dir.path(),
            &[
                "trace",
                "--sweep",
                "s.arrow",
                "--sample",
                &i.to_string(),
                "--out",
                &out,
            ],
        )
        .assert_ok();
        let t = Columns::in_dir(&dir, &out);
        let summary = reference::run(&model, &sampling::sample(&scenario, i as u64), |_| {});
        for k in 0..4 {
            let leg = &summary.legs[k];
            for (what, reference_peak, reference_time) in [
                ("axial", leg.peak_axial_force_n, leg.peak_axial_force_s),
                ("side", leg.peak_side_force_n, leg.peak_side_force_s),
            ] {
                let (peak, time) = trace_peak(&t, &format!("leg{k}_{what}_force_n"));
                let swept = sweep.f64s(&format!("leg{k}_peak_{what}_force_n"))[i];
                let swept_time = sweep.options(&format!("leg{k}_peak_{what}_force_s"))[i];
                let case = format!("sample {i} leg {k} {what}");
                println!(
                    "{case}: trace {peak} N at {time:?} s, reference {reference_peak} N at {reference_time:?}, sweep {swept} N at {swept_time:?}"
                );
                if (reference_peak, reference_time) != (peak, time) {
                    failures.push(format!(
                        "{case}: reference {reference_peak} at {reference_time:?}, trace {peak} at {time:?}"
                    ));
                }
                // A crushing damper holds the axial load at its crush force for many
                // steps: the sweep's time is then a step at which the trace reaches the
                // peak (the first such step may differ by rounding).
                let close_time = match (swept_time, time) {
                    (Some(a), Some(_)) => reaches(&t, &format!("leg{k}_{what}_force_n"), a, peak),
                    (a, b) => a == b,
                };
                if (swept - peak).abs() > 1e-9 * peak || !close_time {
                    failures.push(format!(
                        "{case}: sweep {swept} at {swept_time:?}, trace {peak} at {time:?}"
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
