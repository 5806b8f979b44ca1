//! `touchdown report`: what a sweep file says, for people. Outcome counts with 95 %
//! confidence intervals, the allowable slope per sector of downhill azimuth relative to the
//! lander, the peak loads, and (with thrusters) the propellant and firings. Markdown, so that it reads on a terminal and pastes into a
//! design note.

use crate::output::read::open_sweep;
use crate::reference::Outcome;
use anyhow::{anyhow, bail};
use arrow_array::{Array, Float64Array, RecordBatch, StringArray, UInt32Array};
use std::fmt::Write as _;
use std::path::Path;

/// Sectors of downhill azimuth relative to the lander (`downhill_azimuth - yaw`), deg.
pub const SECTOR_DEG: f64 = 45.0;

/// Number of sectors around the lander.
pub const SECTORS: usize = (360.0 / SECTOR_DEG) as usize;

/// The downhill azimuth relative to the lander, in [0, 360) deg.
#[must_use]
pub fn relative_azimuth_deg(downhill_azimuth_deg: f64, yaw_deg: f64) -> f64 {
    (downhill_azimuth_deg - yaw_deg).rem_euclid(360.0)
}

/// The sector of a relative azimuth: 0 for [0, 45) deg, 1 for [45, 90) deg, ...
#[must_use]
pub fn sector_of(relative_azimuth_deg: f64) -> usize {
    ((relative_azimuth_deg / SECTOR_DEG) as usize).min(SECTORS - 1)
}

/// The share of stable samples that makes a slope allowable.
pub const ALLOWABLE_STABLE: f64 = 0.99;

/// Fewest samples at or below a slope for its stable share to count.
pub const MIN_SAMPLES: usize = 100;

/// The 97.5 % quantile of the standard normal distribution: 95 % intervals are +-Z95
/// standard errors.
pub(crate) const Z95: f64 = 1.959_963_984_540_054;

/// The 95 % Wilson score interval of `k` successes in `n` trials.
#[must_use]
pub fn wilson_interval(k: u64, n: u64) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (lo, hi) = crate::weighting::wilson(k as f64 / n as f64, n as f64);
    // At k = 0 and k = n the bounds are 0 and 1 exactly; rounding would leave 1e-18.
    (if k == 0 { 0.0 } else { lo }, if k == n { 1.0 } else { hi })
}

/// The allowable slope of one sector's samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Allowable {
    /// Fewer than `MIN_SAMPLES` samples in the sector: nothing can be said.
    TooFewSamples(usize),
    /// No slope with at least `MIN_SAMPLES` samples at or below it has `ALLOWABLE_STABLE`
    /// of them stable; `below_deg` bounds the true allowable slope with 95 % confidence
    /// (it may be none at all).
    NoSlope { below_deg: f64 },
    /// The allowable slope, and its 95 % interval.
    Slope {
        slope_deg: f64,
        low_deg: f64,
        high_deg: f64,
    },
}

impl Allowable {
    /// The allowable slope, if there is one.
    #[must_use]
    pub fn slope_deg(self) -> Option<f64> {
        match self {
            Allowable::Slope { slope_deg, .. } => Some(slope_deg),
            _ => None,
        }
    }

    /// The report's cell: the slope, or why there is none.
    #[must_use]
    pub fn cell(self) -> String {
        match self {
            Allowable::TooFewSamples(n) => format!("too few samples ({n})"),
            Allowable::NoSlope { .. } => {
                format!("no slope with ≥ {:.0} % stable", 100.0 * ALLOWABLE_STABLE)
            }
            Allowable::Slope { slope_deg, .. } => format!("{slope_deg:.1} deg"),
        }
    }

    /// The report's cell of the 95 % interval.
    #[must_use]
    pub fn interval_cell(self) -> String {
        match self {
            Allowable::TooFewSamples(_) => "–".to_string(),
            Allowable::NoSlope { below_deg } => format!("0.0–{below_deg:.1} deg"),
            Allowable::Slope {
                low_deg, high_deg, ..
            } => format!("{low_deg:.1}–{high_deg:.1} deg"),
        }
    }
}

/// The allowable slope of `samples` (slope, stable) of one sector: the largest slope `s`
/// such that at least `ALLOWABLE_STABLE` of the samples with a slope at most `s` are
/// stable, counting only slopes with at least `MIN_SAMPLES` samples at or below them.
///
/// Its 95 % interval inverts the Wilson test of "the stable share at or below `s` is
/// `ALLOWABLE_STABLE`": it runs from the largest slope whose share's 95 % Wilson interval
/// lies wholly at or above it (0 when none does: the true slope may be below the smallest
/// one resolved) to the largest slope whose interval still reaches it (where the share
/// falls with the slope, as it does, the true allowable slope is inside with 95 %
/// confidence). Sorts `samples`.
#[must_use]
pub fn allowable_slope(samples: &mut [(f64, bool)]) -> Allowable {
    if samples.len() < MIN_SAMPLES {
        return Allowable::TooFewSamples(samples.len());
    }
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut stable = 0u64;
    let at_or_below = samples.iter().enumerate().filter_map(|(i, (slope, ok))| {
        stable += u64::from(*ok);
        let n = i + 1;
        let last_of_slope = samples.get(n).is_none_or(|next| next.0 > *slope);
        last_of_slope.then_some((*slope, n as u64, stable))
    });
    allowable_of_counts(at_or_below, samples.len())
}

/// `allowable_slope`'s rules applied to `(s, n, k)` for each candidate slope `s` in
/// increasing order: `n` samples at or below `s` count, `k` of them stable. `total` is the
/// sector's sample count, for `TooFewSamples` when no slope has `MIN_SAMPLES` at or below
/// it. `boundary` gives it the counts of samples pooled over rounds drawn below different
/// slopes.
pub(crate) fn allowable_of_counts(
    at_or_below: impl IntoIterator<Item = (f64, u64, u64)>,
    total: usize,
) -> Allowable {
    let (mut best, mut low, mut high, mut first) = (None, None, None, None);
    for (slope, n, stable) in at_or_below {
        if n < MIN_SAMPLES as u64 {
            continue;
        }
        first.get_or_insert(slope);
        let (lo, hi) = wilson_interval(stable, n);
        if stable as f64 >= ALLOWABLE_STABLE * n as f64 {
            best = Some(slope);
        }
        if lo >= ALLOWABLE_STABLE {
            low = Some(slope);
        }
        if hi >= ALLOWABLE_STABLE {
            high = Some(slope);
        }
    }
    let Some(resolved) = first else {
        return Allowable::TooFewSamples(total);
    };
    match best {
        None => Allowable::NoSlope {
            below_deg: high.unwrap_or(resolved),
        },
        Some(slope_deg) => Allowable::Slope {
            slope_deg,
            low_deg: low.unwrap_or(0.0),
            high_deg: high.unwrap_or(slope_deg),
        },
    }
}

/// The `q`-quantile of `values` (nearest rank), 0 for none; sorts `values`.
pub(crate) fn quantile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let rank = ((q * values.len() as f64).ceil() as usize).clamp(1, values.len());
    values[rank - 1]
}

/// A load column gathered over the file.
struct Load {
    name: &'static str,
    unit: &'static str,
    values: Vec<f64>,
}

/// The report of the sweep file at `path`, as Markdown.
/// With `terrain` (a `--slope-distribution` and its text), the outcome shares on that
/// terrain follow the sweep's own (`weighting`).
pub fn report(
    path: &Path,
    terrain: Option<(&crate::weighting::SlopeDistribution, &str)>,
) -> anyhow::Result<String> {
    let (schema, batches) = open_sweep(path)?;
    let meta = schema.metadata();
    let legs = crate::output::read::leg_count(&schema);
    let mut counts = [0u64; Outcome::ALL.len()];
    let mut sectors: Vec<Vec<(f64, bool)>> = vec![Vec::new(); SECTORS];
    let mut loads = [
        Load {
            name: "peak CG acceleration",
            unit: "m/s^2",
            values: Vec::new(),
        },
        Load {
            name: "peak acceleration along Z_B",
            unit: "m/s^2",
            values: Vec::new(),
        },
        Load {
            name: "peak leg normal force (largest leg)",
            unit: "N",
            values: Vec::new(),
        },
        Load {
            name: "damper stroke (longest leg)",
            unit: "mm",
            values: Vec::new(),
        },
        Load {
            name: "energy absorbed by the dampers (all legs)",
            unit: "J",
            values: Vec::new(),
        },
    ];
    let mut thrust = Thrust::default();
    let mut slopes: Vec<(f64, Outcome)> = Vec::new();
    for b in batches {
        let b = b.map_err(|e| anyhow!("cannot read {}: {e}", path.display()))?;
        let f = |name: &str| float_column(&b, name, path);
        let control = ThrustColumns::of(&b, path)?;
        let outcome = b
            .column_by_name("outcome")
            .and_then(|c| c.as_any().downcast_ref::<StringArray>())
            .ok_or_else(|| anyhow!("{}: no outcome column", path.display()))?;
        let (slope, azimuth, yaw) = (f("slope_deg")?, f("downhill_azimuth_deg")?, f("yaw_deg")?);
        let (acc, acc_z) = (
            f("peak_acceleration_m_s2")?,
            f("peak_acceleration_z_body_m_s2")?,
        );
        let per_leg = |what: &str| -> anyhow::Result<Vec<&Float64Array>> {
            (0..legs).map(|k| f(&format!("leg{k}_{what}"))).collect()
        };
        let (force, stroke, energy) = (
            per_leg("peak_normal_force_n")?,
            per_leg("stroke_m")?,
            per_leg("absorbed_j")?,
        );
        for i in 0..b.num_rows() {
            let name = outcome.value(i);
            let o = Outcome::from_name(name)
                .ok_or_else(|| anyhow!("{}: unknown outcome {name:?}", path.display()))?;
            counts[o as usize] += 1;
            if terrain.is_some() {
                slopes.push((slope.value(i), o));
            }
            let relative = relative_azimuth_deg(azimuth.value(i), yaw.value(i));
            sectors[sector_of(relative)].push((slope.value(i), o == Outcome::Stable));
            let max_of =
                |cols: &[&Float64Array]| cols.iter().map(|c| c.value(i)).fold(0.0, f64::max);
            loads[0].values.push(acc.value(i));
            loads[1].values.push(acc_z.value(i));
            loads[2].values.push(max_of(&force));
            loads[3].values.push(1e3 * max_of(&stroke));
            loads[4]
                .values
                .push(energy.iter().map(|c| c.value(i)).sum());
            if let Some(c) = &control {
                thrust.push(c, i, o);
            }
        }
    }
    let total: u64 = counts.iter().sum();
    if total == 0 {
        bail!("{} holds no samples", path.display());
    }

    let mut t = String::new();
    let _ = writeln!(t, "# touchdown report: {}\n", path.display());
    let _ = writeln!(
        t,
        "{total} samples, seed {}, {}.\n",
        meta.get("touchdown.seed").map_or("?", String::as_str),
        meta.get("touchdown.engine").map_or("?", String::as_str)
    );
    let _ = writeln!(t, "## Outcomes\n");
    let _ = writeln!(
        t,
        "| outcome | samples | share | 95 % interval |\n|---|---:|---:|---:|"
    );
    for (name, k) in Outcome::ALL.iter().map(|o| o.name()).zip(&counts) {
        let (lo, hi) = wilson_interval(*k, total);
        let _ = writeln!(
            t,
            "| {name} | {k} | {:.2} % | {:.2} – {:.2} % |",
            100.0 * *k as f64 / total as f64,
            100.0 * lo,
            100.0 * hi
        );
    }
    if let Some((terrain, text)) = terrain {
        if meta.contains_key(crate::table::METADATA_KEYS[1]) {
            anyhow::bail!(
                "--slope-distribution: {} cannot be weighed onto a terrain: its slopes come \
                 from a table of inputs, not from a distribution",
                path.display()
            );
        }
        let scenario = meta
            .get("touchdown.scenario")
            .ok_or_else(|| anyhow!("{}: no touchdown.scenario in its metadata", path.display()))
            .and_then(|text| {
                crate::scenario::Scenario::from_toml(text)
                    .map_err(|e| anyhow!("the scenario stored in {}: {e}", path.display()))
            })?;
        let w = crate::weighting::weigh(&scenario, &slopes, terrain).map_err(|e| {
            anyhow!(
                "--slope-distribution: {} cannot be weighed onto this terrain: {e}",
                path.display()
            )
        })?;
        let _ = write!(t, "\n{}", crate::weighting::markdown(&w, terrain, text));
    }
    let _ = writeln!(
        t,
        "\n## Allowable slope\n\nThe largest slope at or below which at least {stable:.0} % of \
         the samples are stable, per sector of downhill azimuth relative to the lander \
         (`downhill_azimuth_deg - yaw_deg`); only slopes with at least {MIN_SAMPLES} samples \
         at or below them count (\"too few samples\": the sector has fewer). The 95 % \
         interval runs from the largest slope whose stable share's 95 % Wilson interval lies \
         at or above {stable:.0} % to the largest whose interval still reaches it.\n",
        stable = 100.0 * ALLOWABLE_STABLE
    );
    let _ = writeln!(
        t,
        "| azimuth sector | samples | stable | allowable slope | 95 % interval |\n|---|---:|---:|---:|---:|"
    );
    for (k, s) in sectors.iter_mut().enumerate() {
        let stable = s.iter().filter(|x| x.1).count();
        let allowable = allowable_slope(s);
        let _ = writeln!(
            t,
            "| {:.0}–{:.0} deg | {} | {:.1} % | {} | {} |",
            k as f64 * SECTOR_DEG,
            (k + 1) as f64 * SECTOR_DEG,
            s.len(),
            100.0 * stable as f64 / s.len().max(1) as f64,
            allowable.cell(),
            allowable.interval_cell()
        );
    }
    let _ = writeln!(
        t,
        "\n## Peak loads\n\n| quantity | mean | 99th percentile | largest |\n|---|---:|---:|---:|"
    );
    for l in &mut loads {
        let mean = l.values.iter().sum::<f64>() / l.values.len().max(1) as f64;
        let p99 = quantile(&mut l.values, 0.99);
        let max = l.values.last().copied().unwrap_or(0.0);
        let _ = writeln!(
            t,
            "| {} ({}) | {mean:.4} | {p99:.4} | {max:.4} |",
            l.name, l.unit
        );
    }
    thrust.write(&mut t);
    let dampers_off = meta
        .get("touchdown.scenario")
        .and_then(|text| crate::scenario::Scenario::from_toml(text).ok())
        .is_some_and(|s| !s.damper.enabled);
    if dampers_off {
        let _ = writeln!(
            t,
            "\nThe dampers are off in this scenario (`damper.enabled = false`): the legs are \
             rigid struts, so stroke and absorbed energy are 0."
        );
    }
    let _ = writeln!(
        t,
        "\n## One sample in detail\n\n`touchdown trace --sweep {} --sample I` runs the sample \
         of index I (the `sample` column) again with this file's scenario and seed and writes \
         its time history; `touchdown plot` draws it.",
        path.display()
    );
    Ok(t)
}

/// The columns of what the thrusters did, in a batch of a sweep with a control loop.
struct ThrustColumns<'a> {
    propellant_kg: &'a Float64Array,
    on_time_s: &'a Float64Array,
    firings: &'a UInt32Array,
    hold_down_impulse_n_s: &'a Float64Array,
}

impl<'a> ThrustColumns<'a> {
    /// The columns of `b`, or `None` in a sweep without a control loop (no `propellant_kg`).
    fn of(b: &'a RecordBatch, path: &Path) -> anyhow::Result<Option<ThrustColumns<'a>>> {
        if b.column_by_name("propellant_kg").is_none() {
            return Ok(None);
        }
        let firings = b
            .column_by_name("firings")
            .and_then(|c| c.as_any().downcast_ref::<UInt32Array>())
            .ok_or_else(|| anyhow!("{}: no UInt32 column firings", path.display()))?;
        Ok(Some(ThrustColumns {
            propellant_kg: float_column(b, "propellant_kg", path)?,
            on_time_s: float_column(b, "thrust_on_time_s", path)?,
            firings,
            hold_down_impulse_n_s: float_column(b, "hold_down_impulse_n_s", path)?,
        }))
    }
}

/// Propellant and firings over a sweep with a control loop: their distributions, and the
/// propellant per outcome.
#[derive(Default)]
struct Thrust {
    /// Propellant (kg), thruster on-time (s), firings, hold-down impulse (N s), per sample.
    values: [Vec<f64>; 4],
    /// Propellant (kg) summed per outcome, and the samples of each.
    by_outcome: [(f64, u64); Outcome::ALL.len()],
}

impl Thrust {
    fn push(&mut self, c: &ThrustColumns<'_>, i: usize, o: Outcome) {
        let propellant = c.propellant_kg.value(i);
        for (v, x) in self.values.iter_mut().zip([
            propellant,
            c.on_time_s.value(i),
            f64::from(c.firings.value(i)),
            c.hold_down_impulse_n_s.value(i),
        ]) {
            v.push(x);
        }
        self.by_outcome[o as usize].0 += propellant;
        self.by_outcome[o as usize].1 += 1;
    }

    /// The section of the report (nothing for a sweep without a control loop).
    fn write(&mut self, t: &mut String) {
        if self.values[0].is_empty() {
            return;
        }
        let total: f64 = self.values[0].iter().sum();
        let fired = self.values[2].iter().filter(|&&f| f > 0.0).count();
        let n = self.values[0].len();
        let _ = writeln!(
            t,
            "\n## Propellant and firings\n\n{fired} of {n} samples fired a thruster; {total:.4} kg \
             of propellant over all samples.\n\n\
             | quantity | mean | median | 99th percentile | largest |\n|---|---:|---:|---:|---:|"
        );
        for (v, (name, unit)) in self.values.iter_mut().zip([
            ("propellant used", "kg"),
            ("thruster on-time, all thrusters", "s"),
            ("firings", "1"),
            ("hold-down impulse", "N s"),
        ]) {
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let median = quantile(v, 0.5);
            let p99 = quantile(v, 0.99);
            let max = v.last().copied().unwrap_or(0.0);
            let _ = writeln!(
                t,
                "| {name} ({unit}) | {mean:.4} | {median:.4} | {p99:.4} | {max:.4} |"
            );
        }
        let _ = writeln!(
            t,
            "\n| outcome | samples | mean propellant (kg) |\n|---|---:|---:|"
        );
        for (o, (kg, k)) in Outcome::ALL.iter().zip(&self.by_outcome) {
            if *k > 0 {
                let _ = writeln!(t, "| {} | {k} | {:.4} |", o.name(), kg / *k as f64);
            }
        }
    }
}

/// A Float64 column of a batch, by name.
pub(crate) fn float_column<'a>(
    b: &'a RecordBatch,
    name: &str,
    path: &Path,
) -> anyhow::Result<&'a Float64Array> {
    b.column_by_name(name)
        .and_then(|c| c.as_any().downcast_ref::<Float64Array>())
        .ok_or_else(|| anyhow!("{}: no Float64 column {name}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wilson_interval_matches_known_values() {
        // Wilson 95 % intervals computed by hand from the closed form.
        let (lo, hi) = wilson_interval(50, 100);
        assert!(
            (lo - 0.4038).abs() < 1e-4 && (hi - 0.5962).abs() < 1e-4,
            "{lo} {hi}"
        );
        let (lo, hi) = wilson_interval(0, 100);
        assert!(lo == 0.0 && (hi - 0.0370).abs() < 1e-4, "{lo} {hi}");
        let (lo, hi) = wilson_interval(100, 100);
        assert!((lo - 0.9630).abs() < 1e-4 && hi == 1.0, "{lo} {hi}");
    }

    #[test]
    fn allowable_slope_is_where_the_stable_share_falls_below_99_percent() {
        // 1000 samples on slopes 0.0, 0.1, ..., 99.9: stable below 40 deg, none above. The
        // share at or below s stays 1 up to 39.9; past 40 it is 400 / n, below 0.99 from
        // n = 405 (s = 40.4) on; at s = 40.0..40.3 it is 400/401..400/404 >= 0.99.
        let mut s: Vec<(f64, bool)> = (0..1000).map(|i| (f64::from(i) / 10.0, i < 400)).collect();
        let a = allowable_slope(&mut s);
        assert_eq!(a.slope_deg(), Some(40.3));
        // The interval, from the closed form: Wilson's lower bound is n / (n + z^2) = 0.99049
        // at n = 400, all stable (s = 39.9), and 0.98601 at 400/401 (s = 40.0); the upper
        // bound of 400/n is 0.99003 at n = 408 (s = 40.7) and 0.98838 at n = 409.
        let Allowable::Slope {
            low_deg, high_deg, ..
        } = a
        else {
            panic!("{a:?}")
        };
        assert_eq!((low_deg, high_deg), (39.9, 40.7), "{a:?}");
        assert_eq!(a.cell(), "40.3 deg");
        assert_eq!(a.interval_cell(), "39.9–40.7 deg");
        // Fewer than MIN_SAMPLES in the sector: too few to say anything.
        let mut few: Vec<(f64, bool)> = (0..50).map(|i| (f64::from(i), true)).collect();
        assert_eq!(allowable_slope(&mut few), Allowable::TooFewSamples(50));
        assert_eq!(allowable_slope(&mut few).cell(), "too few samples (50)");
        // Everything unstable: no slope, and below the first resolved slope (the 100th
        // sample, 99 deg) with 95 % confidence.
        let mut none: Vec<(f64, bool)> = (0..500).map(|i| (f64::from(i), false)).collect();
        assert_eq!(
            allowable_slope(&mut none),
            Allowable::NoSlope { below_deg: 99.0 }
        );
        assert_eq!(
            allowable_slope(&mut none).cell(),
            "no slope with ≥ 99 % stable"
        );
    }
}
