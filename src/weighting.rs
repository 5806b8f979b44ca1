//! Outcome shares on a terrain: `touchdown report SWEEP --slope-distribution D` weighs each
//! sample of a sweep by the terrain's slope density over the sweep's sampling density at
//! its slope (importance weights), so that one sweep over a broad range of slopes answers
//! "how likely is a good landing on *this* terrain" for any terrain model.
//!
//! The estimate of a share is self-normalised, `P = sum w_i y_i / sum w_i`; its variance by
//! the delta method, `sum w_i^2 (y_i - P)^2 / (sum w_i)^2`; its 95 % interval the Wilson
//! score interval at the sample size whose binomial variance is that variance (Kish's
//! effective sample size where the share is 0 or 1). Refused where the terrain puts more
//! than `UNCOVERED_MAX` of its slopes where the sweep drew none.

use crate::dist::normal_cdf;
use crate::reference::Outcome;
use crate::scenario::{Design, Dist, Scenario};
use crate::stats::wilson;
use anyhow::{anyhow, bail};
use std::fmt::Write as _;
use std::path::Path;

/// The largest share of the terrain's slopes that may lie outside the sweep's range: the
/// weighted shares leave them out, so they are off by at most that much.
pub const UNCOVERED_MAX: f64 = 1e-3;

/// The smallest scale of a parametric slope distribution, deg (a narrower one is a fixed
/// slope, which a density cannot weigh).
const MIN_SCALE_DEG: f64 = 1e-3;

/// A terrain's distribution of slopes, deg, on [0, 90).
#[derive(Debug, Clone, PartialEq)]
pub enum SlopeDistribution {
    /// Bins `[min, max)` with their probabilities (summing to 1), uniform within a bin.
    Bins(Vec<(f64, f64, f64)>),
    /// Uniform on `[min, max]`.
    Uniform {
        /// The smallest slope, deg.
        min: f64,
        /// The largest slope, deg.
        max: f64,
    },
    /// Normal, truncated to [0, 90).
    Normal {
        /// Mean before truncation, deg.
        mean: f64,
        /// Standard deviation before truncation, deg.
        sd: f64,
    },
    /// Rayleigh of scale `sigma` (its mode), truncated to [0, 90).
    Rayleigh {
        /// Scale before truncation, deg.
        sigma: f64,
    },
    /// Exponential of mean `mean`, truncated to [0, 90).
    Exponential {
        /// Mean before truncation, deg.
        mean: f64,
    },
}

impl SlopeDistribution {
    /// Reads `text`: a parametric form (`uniform:MIN:MAX`, `normal:MEAN:SD`,
    /// `rayleigh:SIGMA`, `exponential:MEAN`, in degrees) or the path of a CSV file with the
    /// columns `slope_min_deg`, `slope_max_deg` and `probability` (relative frequencies
    /// are scaled to sum to 1).
    pub fn parse(text: &str) -> anyhow::Result<SlopeDistribution> {
        let mut parts = text.split(':');
        let form = parts.next().unwrap_or_default();
        let numbers: Vec<&str> = parts.collect();
        let known = ["uniform", "normal", "rayleigh", "exponential"];
        if !known.contains(&form) || numbers.is_empty() {
            return read_bins(Path::new(text));
        }
        let values = numbers
            .iter()
            .map(|n| n.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect::<Option<Vec<f64>>>()
            .ok_or_else(|| {
                anyhow!("--slope-distribution {text}: its parameters must be numbers")
            })?;
        let want = if matches!(form, "uniform" | "normal") {
            2
        } else {
            1
        };
        if values.len() != want {
            bail!(
                "--slope-distribution {text}: {form} takes {want} number{} (uniform:MIN:MAX, \
                 normal:MEAN:SD, rayleigh:SIGMA, exponential:MEAN, in degrees)",
                if want == 1 { "" } else { "s" }
            );
        }
        let d = match form {
            "uniform" => SlopeDistribution::Uniform {
                min: values[0],
                max: values[1],
            },
            "normal" => SlopeDistribution::Normal {
                mean: values[0],
                sd: values[1],
            },
            "rayleigh" => SlopeDistribution::Rayleigh { sigma: values[0] },
            _ => SlopeDistribution::Exponential { mean: values[0] },
        };
        let bad = match d {
            SlopeDistribution::Uniform { min, max } => !(0.0 <= min && min < max && max <= 90.0),
            SlopeDistribution::Normal { sd, .. } => sd < MIN_SCALE_DEG,
            SlopeDistribution::Rayleigh { sigma } => sigma < MIN_SCALE_DEG,
            SlopeDistribution::Exponential { mean } => mean < MIN_SCALE_DEG,
            SlopeDistribution::Bins(_) => false,
        };
        if bad {
            bail!(
                "--slope-distribution {text}: uniform needs 0 <= MIN < MAX <= 90, the others a \
                 scale (SD, SIGMA, MEAN) of at least {MIN_SCALE_DEG} deg"
            );
        }
        if d.cdf(90.0) <= 0.0 {
            bail!("--slope-distribution {text}: no probability below 90 deg");
        }
        Ok(d)
    }

    /// The untruncated CDF.
    fn raw_cdf(&self, x: f64) -> f64 {
        let x = x.max(0.0);
        match self {
            SlopeDistribution::Bins(bins) => bins
                .iter()
                .map(|&(a, b, p)| p * ((x.min(b) - a) / (b - a)).clamp(0.0, 1.0))
                .sum(),
            SlopeDistribution::Uniform { min, max } => ((x - min) / (max - min)).clamp(0.0, 1.0),
            // Below a negative mean, from the upper tail, where the CDF keeps its digits.
            SlopeDistribution::Normal { mean, sd } if *mean < 0.0 => {
                normal_cdf(mean / sd) - normal_cdf((mean - x) / sd)
            }
            SlopeDistribution::Normal { mean, sd } => {
                normal_cdf((x - mean) / sd) - normal_cdf(-mean / sd)
            }
            SlopeDistribution::Rayleigh { sigma } => 1.0 - (-x * x / (2.0 * sigma * sigma)).exp(),
            SlopeDistribution::Exponential { mean } => 1.0 - (-x / mean).exp(),
        }
    }

    /// The probability of a slope at most `x`, deg.
    #[must_use]
    pub fn cdf(&self, x: f64) -> f64 {
        let total = self.raw_cdf(90.0);
        if total <= 0.0 {
            return 0.0;
        }
        (self.raw_cdf(x.min(90.0)) / total).clamp(0.0, 1.0)
    }

    /// The density at slope `x`, 1/deg.
    #[must_use]
    pub fn pdf(&self, x: f64) -> f64 {
        if !(0.0..90.0).contains(&x) {
            return 0.0;
        }
        let raw = match self {
            SlopeDistribution::Bins(bins) => bins
                .iter()
                .filter(|&&(a, b, _)| a <= x && x < b)
                .map(|&(a, b, p)| p / (b - a))
                .sum(),
            SlopeDistribution::Uniform { min, max } => {
                if (*min..*max).contains(&x) {
                    1.0 / (max - min)
                } else {
                    0.0
                }
            }
            SlopeDistribution::Normal { mean, sd } => {
                let z = (x - mean) / sd;
                (-0.5 * z * z).exp() / (sd * (2.0 * std::f64::consts::PI).sqrt())
            }
            SlopeDistribution::Rayleigh { sigma } => {
                x / (sigma * sigma) * (-x * x / (2.0 * sigma * sigma)).exp()
            }
            SlopeDistribution::Exponential { mean } => (-x / mean).exp() / mean,
        };
        raw / self.raw_cdf(90.0)
    }

    /// How a report names it.
    #[must_use]
    pub fn describe(&self) -> String {
        match self {
            SlopeDistribution::Bins(b) => format!("{} bins from a file", b.len()),
            SlopeDistribution::Uniform { min, max } => format!("uniform on {min}-{max} deg"),
            SlopeDistribution::Normal { mean, sd } => {
                format!("normal, mean {mean} deg, sd {sd} deg, within 0-90 deg")
            }
            SlopeDistribution::Rayleigh { sigma } => {
                format!("Rayleigh, scale {sigma} deg, within 0-90 deg")
            }
            SlopeDistribution::Exponential { mean } => {
                format!("exponential, mean {mean} deg, within 0-90 deg")
            }
        }
    }
}

/// Reads a CSV of slope bins.
fn read_bins(path: &Path) -> anyhow::Result<SlopeDistribution> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        anyhow!(
            "--slope-distribution {}: neither a form (uniform:MIN:MAX, normal:MEAN:SD, \
             rayleigh:SIGMA, exponential:MEAN) nor a readable CSV file of bins: {e}",
            path.display()
        )
    })?;
    let mut r = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header: Vec<String> = r
        .headers()
        .map_err(|e| anyhow!("{}: {e}", path.display()))?
        .iter()
        .map(str::to_string)
        .collect();
    let want = ["slope_min_deg", "slope_max_deg", "probability"];
    let at = want
        .iter()
        .map(|w| header.iter().position(|h| h == w))
        .collect::<Option<Vec<usize>>>()
        .ok_or_else(|| {
            anyhow!(
                "{}: the columns must be slope_min_deg, slope_max_deg and probability (it has {})",
                path.display(),
                header.join(", ")
            )
        })?;
    let mut bins: Vec<(f64, f64, f64)> = Vec::new();
    for (row, record) in r.records().enumerate() {
        let record = record.map_err(|e| anyhow!("{}: {e}", path.display()))?;
        let line = record.position().map_or(0, csv::Position::line);
        let value = |j: usize| -> anyhow::Result<f64> {
            let cell = record.get(at[j]).unwrap_or_default();
            cell.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    anyhow!(
                        "{}: row {row} (line {line}), column {}: {cell:?} is not a number",
                        path.display(),
                        want[j]
                    )
                })
        };
        let (a, b, p) = (value(0)?, value(1)?, value(2)?);
        if !(0.0 <= a && a < b && b <= 90.0) || p < 0.0 {
            bail!(
                "{}: row {row} (line {line}): a bin is 0 <= slope_min_deg < slope_max_deg <= 90 \
                 with a probability of at least 0 (got {a}, {b}, {p})",
                path.display()
            );
        }
        bins.push((a, b, p));
    }
    bins.sort_by(|x, y| x.0.total_cmp(&y.0));
    if let Some(w) = bins.windows(2).find(|w| w[1].0 < w[0].1) {
        bail!(
            "{}: the bins {}-{} and {}-{} deg overlap",
            path.display(),
            w[0].0,
            w[0].1,
            w[1].0,
            w[1].1
        );
    }
    let total: f64 = bins.iter().map(|b| b.2).sum();
    if total <= 0.0 {
        bail!("{}: no bin has a probability above 0", path.display());
    }
    Ok(SlopeDistribution::Bins(
        bins.into_iter()
            .map(|(a, b, p)| (a, b, p / total))
            .collect(),
    ))
}

/// A density of slopes, 1/deg.
type Density = Box<dyn Fn(f64) -> f64>;

/// The density of the slopes a sweep of `scenario` draws, and their range.
fn sampling_density(scenario: &Scenario) -> anyhow::Result<(Density, f64, f64)> {
    if scenario.table.is_some() {
        bail!("its slopes come from a table of inputs, not from a distribution");
    }
    match scenario.design {
        Design::SobolIndices => bail!(
            "its design is \"sobol-indices\", whose samples are made from each other, not drawn \
             independently"
        ),
        Design::Independent | Design::SobolSequence => {}
    }
    match scenario.inputs.slope_deg {
        Dist::Uniform { min, max } if max > min => Ok((
            Box::new(move |x| {
                if (min..=max).contains(&x) {
                    1.0 / (max - min)
                } else {
                    0.0
                }
            }),
            min,
            max,
        )),
        Dist::Normal { mean, sd, min, max } => {
            let mass = normal_cdf((max - mean) / sd) - normal_cdf((min - mean) / sd);
            Ok((
                Box::new(move |x| {
                    if (min..=max).contains(&x) {
                        let z = (x - mean) / sd;
                        (-0.5 * z * z).exp() / (sd * (2.0 * std::f64::consts::PI).sqrt() * mass)
                    } else {
                        0.0
                    }
                }),
                min.max(0.0),
                max.min(90.0),
            ))
        }
        Dist::Uniform { .. } => bail!("its slope_deg is a range of width 0: one slope"),
        d => bail!(
            "its slope_deg is {} (a weighting needs slopes drawn from a uniform or normal \
             distribution)",
            d.toml()
        ),
    }
}

/// A share on the terrain: its estimate and 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Share {
    /// The weighted share: `sum w_i y_i / sum w_i`.
    pub p: f64,
    /// The low end of its 95 % interval.
    pub low: f64,
    /// The high end of its 95 % interval.
    pub high: f64,
    /// The standard error by the delta method.
    pub se: f64,
}

/// The outcome shares of a sweep weighted onto a terrain.
#[derive(Debug, Clone, PartialEq)]
pub struct Weighted {
    /// One per outcome (`Outcome::ALL`).
    pub shares: Vec<Share>,
    /// Kish's effective sample size, `(sum w)^2 / sum w^2`.
    pub effective_samples: f64,
    /// Samples of the sweep weighed.
    pub samples: usize,
    /// The terrain's probability of slopes outside the sweep's range.
    pub uncovered: f64,
    /// The sweep's range of slopes, deg.
    pub range: (f64, f64),
    /// Whether the sweep has a control loop (only then is `held` listed).
    pub controlled: bool,
}

/// Weighs samples `(slope, outcome)` of a sweep of `scenario` onto `terrain`.
pub fn weigh(
    scenario: &Scenario,
    samples: &[(f64, Outcome)],
    terrain: &SlopeDistribution,
) -> anyhow::Result<Weighted> {
    let (density, min, max) = sampling_density(scenario)?;
    let uncovered = 1.0 - (terrain.cdf(max) - terrain.cdf(min));
    if uncovered > UNCOVERED_MAX {
        let below = terrain.cdf(min);
        let above = 1.0 - terrain.cdf(max);
        let mut sides = Vec::new();
        if below > 0.0 {
            sides.push(format!(
                "{:.2} % of its slopes below {min} deg",
                100.0 * below
            ));
        }
        if above > 0.0 {
            sides.push(format!(
                "{:.2} % of its slopes above {max} deg",
                100.0 * above
            ));
        }
        bail!(
            "the sweep's slopes ({min}-{max} deg) do not cover the terrain's: it has {} (at most \
             {} % may be left out); run a sweep whose slope_deg spans them",
            sides.join(" and "),
            100.0 * UNCOVERED_MAX
        );
    }
    let weights: Vec<f64> = samples
        .iter()
        .map(|(s, _)| {
            let q = density(*s);
            if q > 0.0 { terrain.pdf(*s) / q } else { 0.0 }
        })
        .collect();
    let (sum, sum2): (f64, f64) = weights
        .iter()
        .fold((0.0, 0.0), |(a, b), w| (a + w, b + w * w));
    if sum <= 0.0 {
        bail!("no sample of the sweep has a slope the terrain has");
    }
    let effective_samples = sum * sum / sum2;
    let shares = Outcome::ALL
        .iter()
        .map(|o| {
            let p = samples
                .iter()
                .zip(&weights)
                .filter(|((_, x), _)| x == o)
                .map(|(_, w)| w)
                .fold(0.0, |a, w| a + w)
                / sum;
            let var = samples
                .iter()
                .zip(&weights)
                .map(|((_, x), w)| {
                    let y = f64::from(u8::from(x == o));
                    w * w * (y - p) * (y - p)
                })
                .sum::<f64>()
                / (sum * sum);
            // The sample size whose binomial variance is the delta method's.
            let n = if var > 0.0 && p > 0.0 && p < 1.0 {
                p * (1.0 - p) / var
            } else {
                effective_samples
            };
            let (low, high) = wilson(p, n);
            Share {
                p,
                low,
                high,
                se: var.sqrt(),
            }
        })
        .collect();
    Ok(Weighted {
        shares,
        effective_samples,
        samples: samples.len(),
        uncovered: uncovered.max(0.0),
        range: (min, max),
        controlled: scenario.control.is_some() || samples.iter().any(|(_, o)| *o == Outcome::Held),
    })
}

/// The Markdown section of a report on a terrain (`description`: its `describe()`; `text`:
/// the distribution as given).
#[must_use]
pub fn markdown(w: &Weighted, description: &str, text: &str) -> String {
    let mut t = format!(
        "## On a terrain: --slope-distribution {text}\n\nEach sample weighed by the terrain's \
         slope density ({}) over the sweep's at its slope: {} samples worth {:.0} unweighted \
         ones (Kish's effective sample size). 95 % intervals: Wilson's at the sample size of \
         the weighted estimate's variance (delta method).\n\n| outcome | on the terrain | 95 % \
         interval |\n|---|---:|---:|\n",
        description, w.samples, w.effective_samples
    );
    for o in Outcome::listed(w.controlled) {
        let s = &w.shares[o as usize];
        let _ = writeln!(
            t,
            "| {} | {:.2} % | {:.2} – {:.2} % |",
            o.name(),
            100.0 * s.p,
            100.0 * s.low,
            100.0 * s.high
        );
    }
    if w.uncovered > 0.0 {
        let _ = writeln!(
            t,
            "\nThe terrain has {:.3} % of its slopes outside the sweep's {}-{} deg, left out: \
             the shares are those of the rest, off by at most that much.",
            100.0 * w.uncovered,
            w.range.0,
            w.range.1
        );
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn densities_integrate_to_their_cdfs() {
        // The midpoint rule over 0.001 deg steps against the CDF: errors of order h^2 f''.
        let forms = [
            SlopeDistribution::Uniform {
                min: 10.0,
                max: 30.0,
            },
            SlopeDistribution::Normal {
                mean: 20.0,
                sd: 8.0,
            },
            SlopeDistribution::Normal {
                mean: -45.0,
                sd: 5.0,
            },
            SlopeDistribution::Rayleigh { sigma: 12.0 },
            SlopeDistribution::Exponential { mean: 9.0 },
            SlopeDistribution::Bins(vec![(0.0, 10.0, 0.25), (20.0, 45.0, 0.75)]),
        ];
        for d in &forms {
            let h = 1e-3;
            let mut integral = 0.0;
            for i in 0..90_000 {
                let x = (f64::from(i) + 0.5) * h;
                integral += d.pdf(x) * h;
                if i % 5000 == 4999 {
                    let at = f64::from(i + 1) * h;
                    assert!(
                        (integral - d.cdf(at)).abs() < 1e-6,
                        "{d:?} at {at}: {integral} against {}",
                        d.cdf(at)
                    );
                }
            }
            assert!((d.cdf(90.0) - 1.0).abs() < 1e-12, "{d:?}");
        }
    }

    #[test]
    fn forms_parse_and_bad_ones_are_refused() {
        assert_eq!(
            SlopeDistribution::parse("rayleigh:12").unwrap(),
            SlopeDistribution::Rayleigh { sigma: 12.0 }
        );
        assert_eq!(
            SlopeDistribution::parse("normal:20:5").unwrap(),
            SlopeDistribution::Normal {
                mean: 20.0,
                sd: 5.0
            }
        );
        for bad in [
            "rayleigh:0",
            "normal:20",
            "uniform:30:10",
            "exponential:x",
            "uniform:0:95",
        ] {
            assert!(SlopeDistribution::parse(bad).is_err(), "{bad}");
        }
    }
}
