//! The gain of the quasi-random design: the error of P(stable) against the sample count,
//! independent draws against the scrambled Sobol sequence (`design = "sobol-sequence"`), over
//! 20 seeds of each. Both estimates are unbiased (Owen's scrambling makes each Sobol point
//! uniform), so their spread over the seeds is their root-mean-square error.
//!
//!   cargo run --release --example sobol_error [-- SCENARIO.toml [SEEDS [LOG2_MAX]]]
//!
//! Without a scenario it runs the default one. Prints a Markdown table: per sample count
//! (powers of 2, the counts at which the Sobol points are balanced), the mean estimate and
//! the RMS error of each design, and their ratio.
use touchdown::reference::{Model, Outcome};
use touchdown::scenario::{Design, Scenario};
use touchdown::sweep;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (base, name) = match args.first() {
        Some(path) => (
            Scenario::from_file(std::path::Path::new(path))?,
            path.clone(),
        ),
        None => (Scenario::default(), "the default scenario".to_string()),
    };
    let seeds: u64 = args.get(1).map_or(Ok(20), |s| s.parse())?;
    let log2_max: u32 = args.get(2).map_or(Ok(14), |s| s.parse())?;
    let n_max = 1u64 << log2_max;
    let counts: Vec<u64> = (6..=log2_max).map(|m| 1u64 << m).collect();
    // estimates[design][count][seed]
    let mut estimates = vec![vec![Vec::new(); counts.len()]; 2];
    let started = std::time::Instant::now();
    for (d, design) in [Design::Independent, Design::SobolSequence]
        .into_iter()
        .enumerate()
    {
        for seed in 1..=seeds {
            let mut s = base.clone();
            s.design = design;
            s.seed = seed;
            let model = Model::new(&s);
            let mut stable = Vec::with_capacity(n_max as usize);
            sweep::run(&s, &model, 0..n_max, 1024, |rows| {
                stable.extend(rows.iter().map(|r| r.summary.outcome == Outcome::Stable));
                Ok(())
            })?;
            for (k, &n) in counts.iter().enumerate() {
                let share = stable[..n as usize].iter().filter(|&&x| x).count() as f64 / n as f64;
                estimates[d][k].push(share);
            }
        }
    }
    println!(
        "P(stable) of {name}: {seeds} seeds per design, {} samples in all, {:.0} s\n",
        2 * seeds * n_max,
        started.elapsed().as_secs_f64()
    );
    println!("| samples | independent: mean | RMS error | Sobol: mean | RMS error | error ratio |");
    println!("|---:|---:|---:|---:|---:|---:|");
    let spread = |x: &[f64]| {
        let m = x.iter().sum::<f64>() / x.len() as f64;
        let v = x.iter().map(|e| (e - m).powi(2)).sum::<f64>() / (x.len() - 1) as f64;
        (m, v.sqrt())
    };
    for (k, n) in counts.iter().enumerate() {
        let (mi, ei) = spread(&estimates[0][k]);
        let (ms, es) = spread(&estimates[1][k]);
        println!(
            "| {n} | {mi:.4} | {ei:.5} | {ms:.4} | {es:.5} | {:.2} |",
            ei / es
        );
    }
    Ok(())
}
