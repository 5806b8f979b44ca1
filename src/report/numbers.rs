//! The numbers every section of the report gives: a count of samples with its share and
//! 95 % interval (`Share`), and a quantity's distribution over the samples (`Summary`).

use crate::stats::{quantile, wilson_interval};
use std::fmt::Write as _;

/// `count` samples of `total`: their share and its 95 % Wilson interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Share {
    /// The samples counted.
    pub(super) count: u64,
    /// The samples they are counted among.
    pub(super) total: u64,
    /// `count / total`.
    pub(super) share: f64,
    /// The low end of the share's 95 % Wilson interval.
    pub(super) low: f64,
    /// Its high end.
    pub(super) high: f64,
}

impl Share {
    /// `count` of `total` samples (`total` above 0).
    pub(super) fn of(count: u64, total: u64) -> Share {
        let (low, high) = wilson_interval(count, total);
        Share {
            count,
            total,
            share: fraction(count, total),
            low,
            high,
        }
    }

    /// The share in percent as the Markdown writes it, `100 count / total`: one rounding
    /// (100 times `share` would round twice, and could end a digit apart where the percent
    /// lies on a half of the last digit written).
    pub(super) fn percent(&self) -> f64 {
        percent(self.count, self.total)
    }

    /// Its row of a Markdown table: `name`, the count, the share and its interval.
    pub(super) fn row(&self, t: &mut String, name: &str) {
        let _ = writeln!(
            t,
            "| {name} | {} | {:.2} % | {:.2} – {:.2} % |",
            self.count,
            self.percent(),
            100.0 * self.low,
            100.0 * self.high
        );
    }
}

/// `k / n`, the share of `k` samples of `n`.
pub(super) fn fraction(k: u64, n: u64) -> f64 {
    k as f64 / n as f64
}

/// `100 k / n`, the percent of `k` samples of `n` (`Share::percent`).
pub(super) fn percent(k: u64, n: u64) -> f64 {
    100.0 * k as f64 / n as f64
}

/// What a quantity is: its key in the JSON report (the column's name with the unit it is
/// given in), its name in the Markdown, and its unit.
pub(super) type Named = (&'static str, &'static str, &'static str);

/// A quantity over the samples: its mean, smallest, median, 99th percentile (nearest rank,
/// `stats::quantile`) and largest value; all 0 without samples.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Summary {
    /// Its key in the JSON report: the column's name with the unit it is given in.
    pub(super) key: &'static str,
    /// What it is, in the Markdown.
    pub(super) name: &'static str,
    /// Its unit.
    pub(super) unit: &'static str,
    /// The mean.
    pub(super) mean: f64,
    /// The smallest value.
    pub(super) min: f64,
    /// The median.
    pub(super) median: f64,
    /// The 99th percentile.
    pub(super) p99: f64,
    /// The largest value.
    pub(super) max: f64,
}

impl Summary {
    /// The summary of `values` (sorted by it), of the quantity `(key, name, unit)`.
    pub(super) fn of(values: &mut [f64], (key, name, unit): Named) -> Summary {
        // The mean in the samples' order, before they are sorted.
        let mean = values.iter().sum::<f64>() / values.len().max(1) as f64;
        let median = quantile(values, 0.5);
        let p99 = quantile(values, 0.99);
        Summary {
            key,
            name,
            unit,
            mean,
            min: values.first().copied().unwrap_or(0.0),
            median,
            p99,
            max: values.last().copied().unwrap_or(0.0),
        }
    }
}

/// The summaries of `values`, each of the quantity of `named` beside it (each sorted by it).
pub(super) fn summaries(values: &mut [Vec<f64>], named: &[Named]) -> Vec<Summary> {
    values
        .iter_mut()
        .zip(named)
        .map(|(v, &named)| Summary::of(v, named))
        .collect()
}

/// The table of `quantities`: each one's mean, smallest, median, 99th percentile and
/// largest value, under its header.
pub(super) fn write_summaries(t: &mut String, quantities: &[Summary]) {
    let _ = writeln!(
        t,
        "| quantity | mean | smallest | median | 99th percentile | largest |\n\
         |---|---:|---:|---:|---:|---:|"
    );
    for q in quantities {
        let _ = writeln!(
            t,
            "| {} ({}) | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} |",
            q.name, q.unit, q.mean, q.min, q.median, q.p99, q.max
        );
    }
}
