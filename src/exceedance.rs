//! Load exceedance (MODEL.md section 9): over the samples of a sweep, the probability that
//! a peak load, a stroke or the peak acceleration exceeds a value, per leg and over all
//! legs (the largest leg of each sample), with its 95 % band; and the design value at 99 %
//! and 99.9 % (the value exceeded by 1 % and 0.1 % of the samples) with its 95 % interval
//! from order statistics. Unweighted: each sample counts once, as the sweep drew it.

use crate::output::columns::Table;
use crate::output::sweep::SweepSource;
use crate::stats::wilson_interval;
use std::fmt::Write as _;

/// The levels a design value is given at: the share of samples at or below it.
pub const DESIGN_LEVELS: [f64; 2] = [0.99, 0.999];

/// The two-sided confidence of the intervals.
const CONFIDENCE: f64 = 0.95;

/// One quantity's peaks over the samples: one series per leg (none for a quantity of the
/// whole lander) and the overall series, each sorted ascending.
pub struct Quantity {
    /// Its key in the report's data: the column's name (per leg: without `leg{k}_`), with
    /// the unit it is given in.
    pub key: &'static str,
    /// What it is, for the report and the picture.
    pub name: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// Per leg `k`, the value of each sample, sorted.
    pub legs: Vec<Vec<f64>>,
    /// The value of each sample over all legs (the largest leg), sorted.
    pub overall: Vec<f64>,
}

/// The quantities: per leg (column `leg{k}_{suffix}`, the key, the name, the unit, and the
/// factor to that unit) and of the whole lander (the column is the key).
const PER_LEG: [(&str, &str, &str, &str, f64); 4] = [
    (
        "peak_normal_force_n",
        "peak_normal_force_n",
        "peak leg normal force",
        "N",
        1.0,
    ),
    (
        "peak_axial_force_n",
        "peak_axial_force_n",
        "peak axial strut load",
        "N",
        1.0,
    ),
    (
        "peak_side_force_n",
        "peak_side_force_n",
        "peak side strut load",
        "N",
        1.0,
    ),
    ("stroke_m", "stroke_mm", "damper stroke", "mm", 1e3),
];
const WHOLE: [(&str, &str, &str); 1] =
    [("peak_acceleration_m_s2", "peak CG acceleration", "m/s^2")];

/// The quantities of the sweep (a file, or held in memory) that it has: the strut loads
/// (files written before they existed have none), the stroke with dampers (`dampers`), the
/// acceleration.
pub fn gather(source: &SweepSource, dampers: bool) -> anyhow::Result<Vec<Quantity>> {
    let path = source.name();
    let (schema, batches) = source.batches()?;
    let mut t = Table::of_batches(&schema, batches, path, |n| {
        n.starts_with("leg") && PER_LEG.iter().any(|q| n.ends_with(q.0)) || n == WHOLE[0].0
    })?;
    let mut quantities = Vec::new();
    for (suffix, key, name, unit, factor) in PER_LEG {
        let legs = t.legs(suffix);
        if legs == 0 || (suffix == "stroke_m" && !dampers) {
            continue;
        }
        // Each column taken out of the table and scaled in place: no copy is kept.
        let mut columns = Vec::with_capacity(legs);
        for k in 0..legs {
            let name = format!("leg{k}_{suffix}");
            t.column(&name, path)?;
            let mut c = t.columns.remove(&name).unwrap_or_default();
            c.iter_mut().for_each(|v| *v *= factor);
            columns.push(c);
        }
        let overall = (0..t.rows)
            .map(|i| columns.iter().map(|c| c[i]).fold(0.0, f64::max))
            .collect();
        quantities.push(Quantity::new(key, name, unit, columns, overall));
    }
    for (column, name, unit) in WHOLE {
        t.column(column, path)?;
        let values = t.columns.remove(column).unwrap_or_default();
        quantities.push(Quantity::new(column, name, unit, Vec::new(), values));
    }
    Ok(quantities)
}

impl Quantity {
    /// The quantity with its series sorted.
    fn new(
        key: &'static str,
        name: &'static str,
        unit: &'static str,
        legs: Vec<Vec<f64>>,
        overall: Vec<f64>,
    ) -> Self {
        let sort = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v
        };
        Quantity {
            key,
            name,
            unit,
            legs: legs.into_iter().map(sort).collect(),
            overall: sort(overall),
        }
    }
}

/// A limit of `[limits]` on a quantity's axis: what the exceedance picture marks.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitMark {
    /// The quantity's key (`Quantity::key`).
    pub key: &'static str,
    /// The limit in the quantity's unit.
    pub value: f64,
    /// What it is, for the picture: the key in `[limits]` and its value.
    pub label: String,
}

/// The limits of `scenario` on the axes of the quantities `gather` gives: the strut loads
/// and the acceleration at their values, a least stroke margin (with dampers) at the stroke
/// that leaves it, the usable stroke less the margin.
#[must_use]
pub fn limit_marks(scenario: &crate::scenario::Scenario) -> Vec<LimitMark> {
    let Some(l) = scenario.limits else {
        return Vec::new();
    };
    let mark = |key, value: Option<f64>, label: &dyn Fn(f64) -> String| {
        value.map(|v| LimitMark {
            key,
            value: v,
            label: label(v),
        })
    };
    let usable_m: f64 = scenario.damper.stages.iter().map(|s| s.stroke_m).sum();
    let stroke = l
        .stroke_margin_m
        .filter(|_| scenario.damper.enabled)
        .map(|m| 1e3 * (usable_m - m));
    [
        mark("peak_axial_force_n", l.axial_force_n, &|v| {
            format!("limit axial_force_n = {v} N")
        }),
        mark("peak_side_force_n", l.side_force_n, &|v| {
            format!("limit side_force_n = {v} N")
        }),
        mark("stroke_mm", stroke, &|v| {
            format!(
                "limit stroke_margin_m = {}: stroke {v} mm",
                l.stroke_margin_m.unwrap_or_default()
            )
        }),
        mark("peak_acceleration_m_s2", l.acceleration_m_s2, &|v| {
            format!("limit acceleration_m_s2 = {v} m/s^2")
        }),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// A design value: the `level`-quantile of the samples (nearest rank, as the report's
/// percentiles), and its interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DesignValue {
    /// The estimate.
    pub value: f64,
    /// The interval's lower end: `None` where too few samples lie below it to say.
    pub low: Option<f64>,
    /// The upper end: `None` where too few samples lie above the quantile (more samples
    /// are needed: at least about `3 / (1 - level)` for 99.9 %).
    pub high: Option<f64>,
}

/// The design value at `level` of `sorted` (ascending), with its distribution-free 95 %
/// interval `[x_(l), x_(u)]` (order statistics, 1-based): with `B` the binomial count of
/// samples at or below the true quantile (`n` trials, probability `level`), `l` is the
/// largest rank with `P(B < l) <= 2.5 %` and `u` the smallest with `P(B >= u) <= 2.5 %`,
/// so that the interval covers the quantile with at least 95 % (Hahn and Meeker, 1991,
/// section 5.2).
#[must_use]
pub fn design_value(sorted: &[f64], level: f64) -> Option<DesignValue> {
    let n = sorted.len();
    if n == 0 {
        return None;
    }
    let (l, u) = order_statistic_ranks(n, level);
    Some(DesignValue {
        // `stats::quantile`'s nearest rank, on values already sorted.
        value: sorted[((level * n as f64).ceil() as usize).clamp(1, n) - 1],
        low: l.map(|r| sorted[r - 1]),
        high: u.map(|r| sorted[r - 1]),
    })
}

/// The ranks `(l, u)` of `design_value` (`None`: no rank satisfies the bound).
#[must_use]
pub fn order_statistic_ranks(n: usize, level: f64) -> (Option<usize>, Option<usize>) {
    let tail = 0.5 * (1.0 - CONFIDENCE);
    // P(B <= k) for k = 0..n from the log pmf (lgamma: no underflow at n = 1e6).
    let nf = n as f64;
    let (lp, lq) = (level.ln(), (1.0 - level).ln());
    let lnn = libm::lgamma(nf + 1.0);
    // Outside 40 standard deviations of the mean the pmf is below e^-800: the sum starts
    // there, at 0 (the wide window covers the skew of a level near 1 at small n).
    let sd = (nf * level * (1.0 - level)).sqrt();
    let first = (nf * level - 40.0 * sd - 40.0).max(0.0) as usize;
    let last = ((nf * level + 40.0 * sd + 40.0) as usize).min(n);
    let mut cdf = 0.0;
    let (mut l, mut u) = (None, None);
    for k in first..=last {
        let kf = k as f64;
        let log_pmf =
            lnn - libm::lgamma(kf + 1.0) - libm::lgamma(nf - kf + 1.0) + kf * lp + (nf - kf) * lq;
        // Before adding pmf(k), `cdf` is P(B <= k - 1) = P(B < k): rank k may be `l`.
        if k >= 1 && cdf <= tail {
            l = Some(k);
        }
        cdf += log_pmf.exp();
        // Now `cdf` is P(B <= k), so P(B >= k + 1) = 1 - cdf: rank k + 1 may be `u`.
        if u.is_none() && 1.0 - cdf <= tail && k < n {
            u = Some(k + 1);
        }
    }
    (l, u)
}

/// Points of the exceedance curve of `sorted` (ascending): `(x, P(X > x), low, high)` with
/// the share's 95 % Wilson interval, at about `points` values spread evenly in the log of
/// the exceedance, from the smallest value to the largest (whose share is 0: the curve
/// ends at the last value exceeded, `1 / n`).
#[must_use]
pub fn curve(sorted: &[f64], points: usize) -> Vec<(f64, f64, f64, f64)> {
    let n = sorted.len();
    if n == 0 {
        return Vec::new();
    }
    let mut ranks: Vec<usize> = (0..=points)
        .map(|j| {
            // Exceeding counts from n - 1 down to 1, evenly in the log.
            let e = ((n as f64).ln() * (1.0 - j as f64 / points as f64)).exp();
            n - (e.round() as usize).clamp(1, n)
        })
        .collect();
    ranks.dedup();
    ranks
        .into_iter()
        .filter_map(|r| {
            let x = sorted[r];
            // Samples above x (ties with x do not exceed it).
            let above = n - sorted.partition_point(|v| *v <= x);
            (above > 0).then(|| {
                let (lo, hi) = wilson_interval(above as u64, n as u64);
                (x, above as f64 / n as f64, lo, hi)
            })
        })
        .collect()
}

/// The design values of one series of a quantity (a leg's, or over all legs): at each of
/// `DESIGN_LEVELS` (`None` without samples), and its largest value (0 without samples).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignRow {
    /// At 99 % and at 99.9 %.
    pub levels: [Option<DesignValue>; DESIGN_LEVELS.len()],
    /// The largest value.
    pub largest: f64,
}

impl DesignRow {
    /// The design values of `sorted` (ascending).
    #[must_use]
    pub fn of(sorted: &[f64]) -> DesignRow {
        DesignRow {
            levels: DESIGN_LEVELS.map(|level| design_value(sorted, level)),
            largest: sorted.last().copied().unwrap_or(0.0),
        }
    }
}

/// The design values of one quantity: over all legs (or of the whole lander) and per leg.
#[derive(Debug, Clone, PartialEq)]
pub struct QuantityValues {
    /// Its key (`Quantity::key`).
    pub key: &'static str,
    /// What it is.
    pub name: &'static str,
    /// Its unit.
    pub unit: &'static str,
    /// Over all legs (the largest leg of each sample), or of the whole lander.
    pub overall: DesignRow,
    /// Per leg `k` (none for a quantity of the whole lander).
    pub legs: Vec<DesignRow>,
}

/// What the report's section says: the design values of each quantity of `samples`.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignValues {
    /// The samples they are of.
    pub samples: usize,
    /// Per quantity, in the order of `gather`.
    pub quantities: Vec<QuantityValues>,
}

/// The design values of `quantities` (`gather`'s).
#[must_use]
pub fn design_values(quantities: &[Quantity]) -> DesignValues {
    DesignValues {
        samples: quantities.first().map_or(0, |q| q.overall.len()),
        quantities: quantities
            .iter()
            .map(|q| QuantityValues {
                key: q.key,
                name: q.name,
                unit: q.unit,
                overall: DesignRow::of(&q.overall),
                legs: q.legs.iter().map(|v| DesignRow::of(v)).collect(),
            })
            .collect(),
    }
}

/// A design value as a table cell: the value and its interval.
fn cell(d: Option<DesignValue>) -> String {
    let Some(d) = d else {
        return "–".to_string();
    };
    let end = |v: Option<f64>, none: &str| v.map_or(none.to_string(), |v| format!("{v:.4}"));
    format!(
        "{:.4} ({} – {})",
        d.value,
        end(d.low, "?"),
        end(d.high, "more samples needed")
    )
}

/// The report's section: per quantity, the design values over all legs and per leg.
#[must_use]
pub fn markdown(values: &DesignValues) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "\n## Load exceedance\n\nThe design value at 99 % (99.9 %) is the value that 1 % (0.1 %) \
         of the {} samples exceed; in brackets its 95 % interval from order statistics (no \
         assumed distribution). \"all legs\" takes the largest leg of each sample. \
         `touchdown plot` draws the exceedance curves.\n\n\
         | quantity | leg | 99 % (95 % interval) | 99.9 % (95 % interval) | largest |\n\
         |---|---|---:|---:|---:|",
        values.samples
    );
    for q in &values.quantities {
        let rows: Vec<(String, &DesignRow)> = if q.legs.is_empty() {
            vec![("–".to_string(), &q.overall)]
        } else {
            std::iter::once(("all legs".to_string(), &q.overall))
                .chain(q.legs.iter().enumerate().map(|(k, r)| (k.to_string(), r)))
                .collect()
        };
        for (leg, r) in rows {
            let _ = writeln!(
                t,
                "| {} ({}) | {leg} | {} | {} | {:.4} |",
                q.name,
                q.unit,
                cell(r.levels[0]),
                cell(r.levels[1]),
                r.largest
            );
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranks_cover_the_quantile_as_the_binomial_says() {
        // n = 1000, level 0.99: B ~ Bin(1000, 0.99) has mean 990, sd 3.15. P(B <= 982) =
        // 0.0138 and P(B <= 983) = 0.0264 (summed from the pmf), so l = 983 (P(B < 983) <=
        // 0.025 < P(B < 984)); P(B >= 996) = 0.0287 and P(B >= 997) = 0.0101, so u = 997.
        let (l, u) = order_statistic_ranks(1000, 0.99);
        assert_eq!((l, u), (Some(983), Some(997)));
        // Too few samples above the 99.9 % quantile of 1000: P(B >= 1000) = 0.368.
        assert_eq!(order_statistic_ranks(1000, 0.999).1, None);
    }

    #[test]
    fn curve_counts_what_lies_above() {
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        let c = curve(&v, 20);
        // The first point: the smallest value, 99 of 100 above it.
        assert_eq!((c[0].0, c[0].1), (1.0, 0.99));
        // The last: 99, one value above.
        let last = c.last().unwrap();
        assert_eq!((last.0, last.1), (99.0, 0.01));
        assert!(c.iter().all(|p| p.2 <= p.1 && p.1 <= p.3));
    }
}
