//! The statistics every table of results shares: 95 % intervals (Wilson's, for shares),
//! quantiles, and the rules of the allowable slope per sector of downhill azimuth relative to
//! the lander. `report`, `weighting`, `compare`, `study` and `boundary` all count by these.

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
pub const Z95: f64 = 1.959_963_984_540_054;

/// The 95 % Wilson score interval of `k` successes in `n` trials.
#[must_use]
pub fn wilson_interval(k: u64, n: u64) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (lo, hi) = wilson(k as f64 / n as f64, n as f64);
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
    NoSlope {
        /// The 95 % upper bound of the allowable slope, deg.
        below_deg: f64,
    },
    /// The allowable slope, and its 95 % interval.
    Slope {
        /// The allowable slope, deg.
        slope_deg: f64,
        /// The low end of its 95 % interval, deg.
        low_deg: f64,
        /// The high end of its 95 % interval, deg.
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
pub fn allowable_of_counts(
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
pub fn quantile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let rank = ((q * values.len() as f64).ceil() as usize).clamp(1, values.len());
    values[rank - 1]
}

/// The 95 % Wilson score interval of a share `p` from `n` (not necessarily whole) trials.
#[must_use]
pub fn wilson(p: f64, n: f64) -> (f64, f64) {
    if n <= 0.0 || !n.is_finite() {
        return (0.0, 1.0);
    }
    let z = Z95;
    let centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
    let half = z / (1.0 + z * z / n) * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
    ((centre - half).max(0.0), (centre + half).min(1.0))
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
