//! A sweep run with `design = "sobol-indices"` read back: its rows gathered into base
//! points of the design, the four outputs of each, and their indices.

use super::estimate::{Indices, Outputs, indices};
use crate::output::sweep::SweepFile;
use crate::reference::Outcome;

/// The outputs whose indices `touchdown sensitivity` gives.
pub const OUTPUTS: [&str; 4] = [
    "P(stable)",
    "P(tipped)",
    "peak CG acceleration (m/s^2)",
    "longest damper stroke (mm)",
];

/// The indices of a sweep run with Saltelli's design (`analyse`).
pub struct Analysis {
    /// The column names of the varied inputs and parameters, in the design's order.
    pub names: Vec<&'static str>,
    /// Per output of `OUTPUTS`: the mean over A and B, and the indices (`None`: no
    /// variance).
    pub outputs: Vec<(f64, Option<Indices>)>,
    /// Whole base points of the design used.
    pub base_points: usize,
    /// Rows in the file.
    pub rows: u64,
    /// What to say of the file where it holds fewer samples than it asked for: an
    /// interrupted sweep's (`output::sweep::interrupted_note`).
    pub interrupted: Option<String>,
    /// The sweep's seed, which also seeds the bootstrap.
    pub seed: u64,
    /// Bootstrap replicates asked for per output.
    pub bootstrap: usize,
}

/// The indices of the sweep (or shard) at `path`, run with `design = "sobol-indices"`.
/// Blocks of the design that the file does not hold whole (a shard's first and last) are
/// left out.
pub fn analyse(path: &std::path::Path, bootstrap: usize) -> anyhow::Result<Analysis> {
    use crate::scenario::{Design, Scenario};
    use anyhow::{anyhow, bail};

    let mut file = SweepFile::open(path)?;
    let meta = file.metadata();
    let text = meta
        .get("touchdown.scenario")
        .ok_or_else(|| anyhow!("{}: no touchdown.scenario in its metadata", path.display()))?;
    let mut scenario = Scenario::from_toml(text)
        .map_err(|e| anyhow!("the scenario stored in {}: {e}", path.display()))?;
    if let Some(seed) = meta.get("touchdown.seed").and_then(|s| s.parse().ok()) {
        scenario.seed = seed;
    }
    if scenario.design != Design::SobolIndices {
        bail!(
            "{} was not run with design = \"sobol-indices\" (a top-level key of the scenario): \
             its samples are independent draws, from which no Sobol index can be estimated",
            path.display()
        );
    }
    if bootstrap == 0 || bootstrap > 100_000 {
        bail!("--bootstrap {bootstrap}: from 1 to 100000 replicates");
    }
    let asked = crate::output::sweep::samples_asked(|k| meta.get(k));
    let varied = crate::scenario::design_inputs(&scenario);
    let d = varied.len();
    let legs = file.legs();
    // Per base point, the four outputs of its d + 2 rows (NaN until seen).
    let mut blocks: std::collections::BTreeMap<u64, Vec<[f64; 4]>> = Default::default();
    let mut rows = 0u64;
    for b in file.batches() {
        let b = b?;
        let sample = b.u64s("sample")?;
        let outcomes = b.outcomes()?;
        let acc = b.f64s("peak_acceleration_m_s2")?;
        let strokes = b.per_leg(legs, "stroke_m")?;
        for (i, &o) in outcomes.iter().enumerate() {
            rows += 1;
            let (base, matrix) = crate::scenario::design_position(sample.value(i), d);
            let stroke = strokes.iter().map(|c| c.value(i)).fold(0.0, f64::max);
            let block = blocks
                .entry(base)
                .or_insert_with(|| vec![[f64::NAN; 4]; d + 2]);
            block[matrix] = [
                f64::from(u8::from(o == Outcome::Stable)),
                f64::from(u8::from(o == Outcome::Tipped)),
                acc.value(i),
                1e3 * stroke,
            ];
        }
    }
    let whole: Vec<&Vec<[f64; 4]>> = blocks
        .values()
        .filter(|b| b.iter().all(|r| r.iter().all(|v| v.is_finite())))
        .collect();
    let n = whole.len();
    if n < 2 {
        bail!(
            "{} holds {n} whole base points of the design ({rows} samples; a base point is {} \
             samples): at least 2 are needed, and hundreds for useful intervals",
            path.display(),
            d + 2
        );
    }
    let mut outputs = Vec::new();
    for o in 0..OUTPUTS.len() {
        let col = |m: usize| -> Vec<f64> { whole.iter().map(|b| b[m][o]).collect() };
        let (a, bb) = (col(0), col(1));
        let ab: Vec<Vec<f64>> = (0..d).map(|q| col(2 + q)).collect();
        let mean = (a.iter().sum::<f64>() + bb.iter().sum::<f64>()) / (2 * n) as f64;
        let ix = indices(
            &Outputs {
                a: &a,
                b: &bb,
                ab: &ab,
            },
            bootstrap,
            scenario.seed,
        )?;
        outputs.push((mean, ix));
    }
    Ok(Analysis {
        names: varied
            .iter()
            .map(|&k| crate::scenario::value_name(k))
            .collect(),
        outputs,
        base_points: n,
        rows,
        interrupted: crate::output::sweep::interrupted_note(path, rows, asked),
        seed: scenario.seed,
        bootstrap,
    })
}
