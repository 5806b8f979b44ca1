use touchdown::{reference, scenario::Scenario, sweep};
fn main() {
    let s = Scenario::default();
    let m = reference::Model::new(&s);
    let n: u64 = std::env::args()
        .nth(1)
        .map(|a| a.parse().unwrap())
        .unwrap_or(2000);
    let t = std::time::Instant::now();
    let mut rows = Vec::new();
    let stats = sweep::run(&s, &m, 0..n, 512, |r| {
        rows.extend(r);
        Ok(())
    })
    .unwrap();
    let tk = t.elapsed();
    let steps: u64 = rows.iter().map(|r| r.summary.steps).sum();
    println!(
        "kernel: {n} samples in {tk:?}, {:.1} ns/lander-step (wall, all threads), occupancy {:.3}, steps/sample {}",
        tk.as_nanos() as f64 / steps as f64,
        stats.occupancy(),
        steps / n
    );
    let t = std::time::Instant::now();
    let mut mism = 0;
    let mut maxdt = 0.0f64;
    let mut maxtilt = 0.0f64;
    for r in &rows {
        let refs = reference::run(&m, &r.sample, |_| {});
        if refs.outcome != r.summary.outcome {
            mism += 1;
            if mism < 6 {
                println!(
                    "mismatch {}: ref {:?} {} kern {:?} {}",
                    r.sample.index,
                    refs.outcome,
                    refs.decided_s,
                    r.summary.outcome,
                    r.summary.decided_s
                );
            }
        } else {
            maxdt = maxdt.max((refs.decided_s - r.summary.decided_s).abs());
            maxtilt = maxtilt.max((refs.max_tilt_deg - r.summary.max_tilt_deg).abs());
        }
    }
    println!(
        "reference: {:?}; mismatches {mism}/{n}, max |dt_decided| {maxdt}, max |d max tilt| {maxtilt}",
        t.elapsed()
    );
}
