//! `touchdown compare A B`: two sweeps of the same seed, sample by sample. Sample `i` draws
//! the same value of every input whose distribution the two scenarios share (common random
//! numbers), so the change from A to B is measured on the same landers: the interval of a
//! difference in outcome shares comes from the samples that changed, not from the noise of
//! two independent sweeps.

use crate::output::sweep::SweepFile;
use crate::reference::Outcome;
use crate::stats::Z95;
use anyhow::{anyhow, bail};
use std::fmt::Write as _;
use std::path::Path;

/// A sweep's seed and its outcomes by sample index.
struct Outcomes {
    seed: String,
    /// The engine that wrote it (its sampling rules decide which inputs a seed draws).
    engine: String,
    /// (sample, outcome code), in file order.
    rows: Vec<(u64, u8)>,
    /// Whether the sweep has a control loop (a `propellant_kg` column): only then can a
    /// lander end `held`.
    controlled: bool,
    /// What to say of the file where it holds fewer samples than it asked for: an
    /// interrupted sweep's (`output::sweep::interrupted_note`).
    interrupted: Option<String>,
}

fn read(path: &Path) -> anyhow::Result<Outcomes> {
    let mut file = SweepFile::open(path)?;
    let meta = file.metadata();
    let seed = meta
        .get("touchdown.seed")
        .cloned()
        .ok_or_else(|| anyhow!("{}: no touchdown.seed", path.display()))?;
    let engine = meta
        .get("touchdown.engine")
        .cloned()
        .ok_or_else(|| anyhow!("{}: no touchdown.engine", path.display()))?;
    let controlled = file.schema().field_with_name("propellant_kg").is_ok();
    let asked = crate::output::sweep::samples_asked(|k| meta.get(k));
    let mut rows = Vec::new();
    for b in file.batches() {
        let b = b?;
        let sample = b.u64s("sample")?;
        for (i, o) in b.outcomes()?.into_iter().enumerate() {
            rows.push((sample.value(i), o as u8));
        }
    }
    rows.sort_unstable_by_key(|r| r.0);
    Ok(Outcomes {
        seed,
        engine,
        interrupted: crate::output::sweep::interrupted_note(path, rows.len() as u64, asked),
        rows,
        controlled,
    })
}

/// The difference of one outcome's share, B minus A, over `n` paired samples of which
/// `gained` have it in B only and `lost` in A only; and its 95 % half-widths, paired (from
/// the per-sample differences) and as if the sweeps were independent.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Difference {
    difference: f64,
    paired_half_width: f64,
    independent_half_width: f64,
}

/// See `Difference`: `a` and `b` are the samples with the outcome in A and in B.
#[must_use]
fn difference(n: u64, a: u64, b: u64, gained: u64, lost: u64) -> Difference {
    let n = n as f64;
    let (pa, pb) = (a as f64 / n, b as f64 / n);
    let d = pb - pa;
    // The per-sample difference is +1 (gained), -1 (lost) or 0: its variance is
    // (gained + lost) / n - d^2, and the mean's standard error its root over sqrt(n).
    let var = ((gained + lost) as f64 / n - d * d).max(0.0);
    Difference {
        difference: d,
        paired_half_width: Z95 * (var / n).sqrt(),
        independent_half_width: Z95 * ((pa * (1.0 - pa) + pb * (1.0 - pb)) / n).sqrt(),
    }
}

/// The comparison of sweep files `a` and `b`, as Markdown.
pub fn compare(a: &Path, b: &Path) -> anyhow::Result<String> {
    let (x, y) = (read(a)?, read(b)?);
    if x.seed != y.seed {
        bail!(
            "{} has seed {} and {} seed {}: their samples are not the same landers; run both \
             with one seed",
            a.display(),
            x.seed,
            b.display(),
            y.seed
        );
    }
    if x.engine != y.engine {
        bail!(
            "{} was written by {} and {} by {}: engines of other versions may draw other \
             inputs for the same seed, so their samples are not the same landers; run both \
             with one engine",
            a.display(),
            x.engine,
            b.display(),
            y.engine
        );
    }
    // What to say of an interrupted sweep's file among them.
    let notes: String = [(a, &x), (b, &y)]
        .iter()
        .filter_map(|(p, o)| Some(format!("{}: {}", p.display(), o.interrupted.as_ref()?)))
        .collect::<Vec<_>>()
        .join("; ");
    if x.rows.len() != y.rows.len() || x.rows.iter().zip(&y.rows).any(|(p, q)| p.0 != q.0) {
        bail!(
            "{} ({} samples) and {} ({} samples) do not hold the same sample indices{}",
            a.display(),
            x.rows.len(),
            b.display(),
            y.rows.len(),
            if notes.is_empty() {
                String::new()
            } else {
                format!(" ({notes})")
            }
        );
    }
    let n = x.rows.len() as u64;
    if n == 0 {
        bail!("{} holds no samples", a.display());
    }
    let k = Outcome::ALL.len();
    let mut table = vec![vec![0u64; k]; k];
    for (p, q) in x.rows.iter().zip(&y.rows) {
        table[usize::from(p.1)][usize::from(q.1)] += 1;
    }
    // `held` is listed where a lander can be held: with a control loop in A or B.
    let held = Outcome::Held as usize;
    let controlled = x.controlled || y.controlled || table[held].iter().sum::<u64>() > 0;
    let listed: Vec<usize> = Outcome::listed(controlled).map(|o| o as usize).collect();
    let mut t = String::new();
    let _ = writeln!(
        t,
        "# touchdown compare: {} (A) against {} (B)\n\n{n} samples of seed {}, paired by \
         index: sample i is the same lander in both wherever the two scenarios draw an input \
         alike.\n",
        a.display(),
        b.display(),
        x.seed
    );
    if !notes.is_empty() {
        let _ = writeln!(t, "**{notes}.**\n");
    }
    let _ = writeln!(
        t,
        "## Outcome shares\n\n| outcome | A | B | B − A | 95 % interval, paired | 95 % interval, \
         were they independent |\n|---|---:|---:|---:|---:|---:|"
    );
    for &o in &listed {
        let outcome = Outcome::ALL[o];
        let in_a: u64 = table[o].iter().sum();
        let in_b: u64 = table.iter().map(|r| r[o]).sum();
        let gained = in_b - table[o][o];
        let lost = in_a - table[o][o];
        let d = difference(n, in_a, in_b, gained, lost);
        let pct = |x: f64| 100.0 * x;
        let _ = writeln!(
            t,
            "| {} | {:.2} % | {:.2} % | {:+.2} % | {:+.2} to {:+.2} % | {:+.2} to {:+.2} % |",
            outcome.name(),
            pct(in_a as f64 / n as f64),
            pct(in_b as f64 / n as f64),
            pct(d.difference),
            pct(d.difference - d.paired_half_width),
            pct(d.difference + d.paired_half_width),
            pct(d.difference - d.independent_half_width),
            pct(d.difference + d.independent_half_width),
        );
    }
    let _ = writeln!(
        t,
        "\n## Samples by outcome in A (rows) and in B (columns)\n\n| A \\ B | {} |\n|---|{}",
        listed
            .iter()
            .map(|&o| Outcome::ALL[o].name())
            .collect::<Vec<_>>()
            .join(" | "),
        "---:|".repeat(listed.len())
    );
    for &o in &listed {
        let cells: Vec<String> = listed.iter().map(|&q| table[o][q].to_string()).collect();
        let _ = writeln!(t, "| {} | {} |", Outcome::ALL[o].name(), cells.join(" | "));
    }
    let changed: u64 = n - (0..k).map(|o| table[o][o]).sum::<u64>();
    let _ = writeln!(
        t,
        "\n{changed} of {n} samples ({:.2} %) end otherwise in B than in A.",
        100.0 * changed as f64 / n as f64
    );
    t.push_str(&design_values(a, b)?);
    Ok(t)
}

/// The section on the design values at 99 % (`exceedance`) of the quantities both sweeps
/// have, over all legs: A's, B's and their relative difference; a quantity that is 0 in
/// both (the stroke without dampers) is left out.
fn design_values(a: &Path, b: &Path) -> anyhow::Result<String> {
    use crate::exceedance::{DESIGN_LEVELS, design_value, gather};
    use crate::output::sweep::SweepSource;
    let (x, y) = (
        gather(&SweepSource::Path(a.to_path_buf()), true)?,
        gather(&SweepSource::Path(b.to_path_buf()), true)?,
    );
    let level = DESIGN_LEVELS[0];
    let mut t = format!(
        "\n## Design values at {:.0} %\n\nThe value that {:.0} % of the samples exceed, over all \
         legs (the largest leg of each sample).\n\n| quantity | A | B | (B − A) / A |\n\
         |---|---:|---:|---:|\n",
        100.0 * level,
        100.0 * (1.0 - level)
    );
    for q in &x {
        let Some(r) = y.iter().find(|r| r.key == q.key) else {
            continue;
        };
        let (Some(va), Some(vb)) = (
            design_value(&q.overall, level),
            design_value(&r.overall, level),
        ) else {
            continue;
        };
        if va.value == 0.0 && vb.value == 0.0 {
            continue;
        }
        let _ = writeln!(
            t,
            "| {} ({}) | {:.4} | {:.4} | {:+.2} % |",
            q.name,
            q.unit,
            va.value,
            vb.value,
            100.0 * (vb.value - va.value) / va.value
        );
    }
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paired_intervals_come_from_the_samples_that_changed() {
        // 10 000 samples, 40 % stable in A; B keeps them all and gains 200: d = +2 %, and
        // the per-sample difference is 1 in 200 samples: sd = sqrt(0.02 - 0.0004) = 0.14,
        // half-width 1.96 * 0.14 / 100 = 0.274 %. Independent sweeps of 40 % and 42 %
        // would give 1.96 * sqrt((0.24 + 0.2436) / 10 000) = 1.363 %.
        let d = difference(10_000, 4000, 4200, 200, 0);
        assert!((d.difference - 0.02).abs() < 1e-15);
        assert!((d.paired_half_width - 0.002_744).abs() < 1e-6, "{d:?}");
        assert!((d.independent_half_width - 0.013_63).abs() < 1e-5, "{d:?}");
        // Nothing changed: no doubt about a zero difference.
        let same = difference(500, 100, 100, 0, 0);
        assert_eq!((same.difference, same.paired_half_width), (0.0, 0.0));
    }
}
