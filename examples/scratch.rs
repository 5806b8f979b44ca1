use touchdown::{
    reference, sampling,
    scenario::{Dist, Scenario},
};
fn main() {
    let mut s = Scenario::default();
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    s.inputs.slope_deg = Dist::Uniform {
        min: args[0],
        max: args[1],
    };
    s.inputs.release_height_m = Dist::Uniform {
        min: args[2],
        max: args[3],
    };
    let m = reference::Model::new(&s);
    let mut counts = std::collections::BTreeMap::new();
    let mut steps = 0;
    let mut bounces = 0;
    let mut tdec = 0.0;
    for i in 0..300 {
        let smp = sampling::sample(&s, i);
        let sum = reference::run(&m, &smp, |_| {});
        steps += sum.steps;
        bounces += sum.bounces;
        tdec += sum.decided_s;
        *counts.entry(sum.outcome.name()).or_insert(0) += 1;
    }
    println!(
        "{args:?} {counts:?} steps/sample {} bounces/sample {} t/sample {}",
        steps / 300,
        bounces as f64 / 300.0,
        tdec / 300.0
    );
}
