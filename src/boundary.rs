//! `touchdown boundary`: the allowable slope of each azimuth sector (`stats::allowable_slope`)
//! found directly, by adaptive sampling, with its 95 % interval; or, the same way, the
//! allowable value of another drawn input (`--input`: the largest value with at least 99 %
//! of the samples at or below it stable), "slope" below standing for that input.
//!
//! The allowable slope is cumulative: it is read from the samples at or below a slope, over
//! the scenario's slope distribution. A uniform sweep spends most of its samples where they
//! no longer matter, above the boundary. Here each round draws, per unfinished sector, a
//! batch of the scenario's own samples with the slope redrawn from the scenario's slope
//! distribution conditioned on `[slope_min, u]`, `u` the upper end of the sector's current
//! interval. A sample of a round with upper slope `u` is a draw of the distribution
//! conditioned on `[slope_min, s]` for every `s <= u` at which its slope lies at or below
//! `s`, so the rounds pool at each candidate slope (`pooled_allowable`) and the report's
//! rules (`stats::allowable_of_counts`) give the estimate and interval after each round.
//!
//! The rounds themselves run in `run::boundary`; the command is `commands::boundary`.

use crate::scenario::Dist;
use crate::scenario::Sample;
use crate::scenario::stream_name;
use crate::stats::{
    Allowable, MIN_SAMPLES, SECTOR_DEG, SECTORS, allowable_of_counts, relative_azimuth_deg,
    sector_of,
};

/// `value` in `unit`, as messages and reports write it: `0.5 deg`, or the bare number
/// where the unit is "1" (a share, a coefficient).
#[must_use]
pub fn with_unit(value: impl std::fmt::Display, unit: &str) -> String {
    if unit == "1" {
        value.to_string()
    } else {
        format!("{value} {unit}")
    }
}

/// The sectors of relative azimuth (`stats::sector_of`) that samples drawn from
/// `downhill_azimuth` and `yaw` can fall in: every sector unless both are bounded and the
/// azimuth relative to the yaw spans less than a turn.
#[must_use]
pub fn reachable_sectors(downhill_azimuth: Dist, yaw: Dist) -> [bool; SECTORS] {
    if let (Dist::Fixed(d), Dist::Fixed(y)) = (downhill_azimuth, yaw) {
        let k = sector_of(relative_azimuth_deg(d, y));
        return std::array::from_fn(|i| i == k);
    }
    let (d, y) = (downhill_azimuth.support(), yaw.support());
    let (low, high) = (d.0 - y.1, d.1 - y.0);
    let width = high - low;
    if width.is_nan() || width >= 360.0 {
        return [true; SECTORS];
    }
    let start = low.rem_euclid(360.0);
    let end = start + width;
    std::array::from_fn(|k| {
        let (a, b) = (k as f64 * SECTOR_DEG, (k + 1) as f64 * SECTOR_DEG);
        [0.0, 360.0]
            .iter()
            .any(|turn| a + turn <= end && start < b + turn)
    })
}

/// The samples of one sector from one round: slopes drawn from the scenario's slope
/// distribution conditioned on `[slope_min, upper]`, and whether each was stable.
#[derive(Debug, Clone, PartialEq)]
pub struct Round {
    /// The upper end of the slopes this round drew, in the input's unit (deg for the slope;
    /// the lower end is `slope_min`).
    pub upper: f64,
    /// Each sample's slope, deg, and whether its outcome was stable.
    pub samples: Vec<(f64, bool)>,
}

/// The allowable slope of a sector's `rounds`, by `stats::allowable_slope`'s rules, with
/// the counts at each candidate slope `s` (each distinct sample slope) pooled over the
/// rounds whose upper slope is at least `s`: their samples at or below `s` are draws of
/// the slope distribution conditioned on `[slope_min, s]`, as a uniform sweep's are. With one
/// round at the top of the range it is `allowable_slope` of its samples.
#[must_use]
pub fn pooled_allowable(rounds: &[Round]) -> Allowable {
    let total: usize = rounds.iter().map(|r| r.samples.len()).sum();
    if total < MIN_SAMPLES {
        return Allowable::TooFewSamples(total);
    }
    let mut all: Vec<(f64, bool, usize)> = rounds
        .iter()
        .enumerate()
        .flat_map(|(r, round)| round.samples.iter().map(move |&(s, ok)| (s, ok, r)))
        .collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Rounds leave the pool, lowest upper slope first, as `s` passes their upper slope.
    let mut by_upper: Vec<usize> = (0..rounds.len()).collect();
    by_upper.sort_by(|&a, &b| rounds[a].upper.total_cmp(&rounds[b].upper));
    let mut left = by_upper.iter().peekable();
    let mut counts = vec![(0u64, 0u64); rounds.len()];
    let mut pooled = vec![true; rounds.len()];
    let (mut n, mut k) = (0u64, 0u64);
    let mut at_or_below = Vec::new();
    let mut i = 0;
    while i < all.len() {
        let s = all[i].0;
        while let Some(&&r) = left.peek() {
            if rounds[r].upper >= s {
                break;
            }
            pooled[r] = false;
            n -= counts[r].0;
            k -= counts[r].1;
            left.next();
        }
        while let Some(&(slope, ok, r)) = all.get(i)
            && slope == s
        {
            // A round's slopes are at or below its upper slope: it is still in the pool.
            if pooled[r] {
                counts[r].0 += 1;
                counts[r].1 += u64::from(ok);
                n += 1;
                k += u64::from(ok);
            }
            i += 1;
        }
        at_or_below.push((s, n, k));
    }
    allowable_of_counts(at_or_below, total)
}

/// Why a sector's search stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The 95 % interval is at most the tolerance wide.
    Tolerance,
    /// The allowable slope is the top of the slope range, within the tolerance.
    WholeRange,
    /// No slope is allowable, and the bound is within the tolerance of the smallest slope.
    NoSlope,
    /// The sector ran `--max-samples-per-sector`.
    SampleLimit,
    /// The scenario's azimuth and yaw put no candidate in the sector in a round's draws.
    Unreached,
}

impl Stop {
    /// The report's cell, for a search of `what` ("slope", "value").
    #[must_use]
    pub fn cell(self, what: &str) -> String {
        match self {
            Stop::Tolerance => "interval within tolerance".to_string(),
            Stop::WholeRange => format!("allowable up to the top of the {what} range"),
            Stop::NoSlope => format!("no allowable {what}"),
            Stop::SampleLimit => "sample limit".to_string(),
            Stop::Unreached => "no samples in this sector".to_string(),
        }
    }
}

/// Whether a sector whose samples give `allowable` is finished, on slopes from `min` to
/// `max` with `tolerance` (deg), its last round drawn up to `last_upper`, having run `used`
/// of at most `limit` samples.
///
/// An interval whose upper end lies within half the tolerance below `last_upper` (short of
/// `max`) is not final: there the pooled counts fall, and the upper end may be where the
/// last round's samples end rather than where the stable share does.
#[must_use]
pub fn stop_rule(
    allowable: Allowable,
    (min, max): (f64, f64),
    tolerance: f64,
    last_upper: f64,
    (used, limit): (u64, u64),
) -> Option<Stop> {
    let censored = |high: f64| last_upper < max && high > last_upper - 0.5 * tolerance;
    let rule = match allowable {
        Allowable::Slope { high_deg, .. } if censored(high_deg) => None,
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => {
            // No slope resolved as allowable (low 0): the interval starts at the range's.
            let low = low_deg.max(min);
            if slope_deg >= max - tolerance && low >= max - tolerance {
                Some(Stop::WholeRange)
            } else {
                (high_deg - low <= tolerance).then_some(Stop::Tolerance)
            }
        }
        Allowable::NoSlope { below_deg } => {
            (below_deg - min <= tolerance && !censored(below_deg)).then_some(Stop::NoSlope)
        }
        Allowable::TooFewSamples(_) => None,
    };
    rule.or((used >= limit).then_some(Stop::SampleLimit))
}

/// The upper slope of a sector's next round, within `[min, max]`: the upper end of its
/// interval, plus a margin of the interval's width, at least `tolerance`.
///
/// Not the upper end alone: the samples of a round stop at its upper slope, so the pooled
/// counts fall there, and a round drawn below an upper end that is too low would confirm
/// it (its samples narrow the interval up to it, and only earlier rounds speak above it):
/// the interval would close on the wrong slope. With the margin, an upper end at the last
/// round's (`stop_rule`: not final) moves up by at least the tolerance a round, and the
/// round a sector stops after has samples above its upper end, as a uniform sweep has.
#[must_use]
pub fn next_upper(allowable: Allowable, (min, max): (f64, f64), tolerance: f64) -> f64 {
    let (low, high) = match allowable {
        Allowable::Slope {
            low_deg, high_deg, ..
        } => (low_deg.max(min), high_deg),
        Allowable::NoSlope { below_deg } => (min, below_deg),
        Allowable::TooFewSamples(_) => return max,
    };
    (high + (high - low).max(tolerance)).clamp(min, max)
}

/// The slope distribution `dist` conditioned on `[min, upper]` (`upper` within its range).
fn conditioned(dist: Dist, upper: f64) -> Dist {
    match dist {
        Dist::Uniform { min, .. } => Dist::Uniform { min, max: upper },
        Dist::LogUniform { min, .. } => Dist::LogUniform { min, max: upper },
        Dist::Normal { mean, sd, min, .. } => Dist::Normal {
            mean,
            sd,
            min,
            max: upper,
        },
        other => other,
    }
}

/// `sample` with its value `k` (`Sample::values`: the slope is 0) redrawn from `dist`
/// conditioned on `[min, upper]`, from the sample's own uniform of that value's stream
/// (`stream_name`): the inverse CDF of `U * F(upper)`. Everything else stays. At the top of
/// the range it is the sample's own value.
#[must_use]
pub fn with_value_below(mut sample: Sample, k: usize, dist: Dist, upper: f64) -> Sample {
    let mut stream = crate::rng::stream(sample.seed, stream_name(k));
    let u = crate::rng::uniform_open01(&mut stream);
    let mut values = sample.values();
    values[k] = crate::dist::quantile(&conditioned(dist, upper), u, 0);
    sample.set_values(values);
    sample
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Scenario;
    use crate::stats::allowable_slope;
    use rand_core::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

    #[test]
    fn the_sectors_a_fixed_or_narrow_azimuth_reaches() {
        let uniform = |min, max| Dist::Uniform { min, max };
        let sectors = |d, y| -> Vec<usize> {
            let r = reachable_sectors(d, y);
            (0..SECTORS).filter(|&k| r[k]).collect()
        };
        assert_eq!(sectors(Dist::Fixed(100.0), Dist::Fixed(0.0)), [2]);
        assert_eq!(sectors(Dist::Fixed(10.0), Dist::Fixed(30.0)), [7]);
        assert_eq!(sectors(uniform(0.0, 100.0), Dist::Fixed(0.0)), [0, 1, 2]);
        // Across a turn: 350 to 370 deg relative to the yaw.
        assert_eq!(sectors(uniform(340.0, 360.0), uniform(-10.0, 0.0)), [0, 7]);
        assert_eq!(
            sectors(uniform(0.0, 360.0), Dist::Fixed(0.0)).len(),
            SECTORS
        );
        let normal = Dist::Normal {
            mean: 0.0,
            sd: 1.0,
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
        };
        assert_eq!(sectors(normal, Dist::Fixed(0.0)).len(), SECTORS);
    }

    #[test]
    fn one_round_at_the_top_is_the_reports_allowable_slope() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        for boundary in [5.0, 20.0, 44.0] {
            let samples: Vec<(f64, bool)> = (0..5000)
                .map(|_| {
                    let s = 45.0 * crate::rng::uniform01(&mut rng);
                    let p = if s < boundary { 0.999 } else { 0.8 };
                    (s, crate::rng::uniform01(&mut rng) < p)
                })
                .collect();
            let round = Round {
                upper: 45.0,
                samples: samples.clone(),
            };
            assert_eq!(
                pooled_allowable(&[round]),
                allowable_slope(&mut samples.clone()),
                "boundary {boundary}"
            );
        }
        let few = Round {
            upper: 45.0,
            samples: vec![(1.0, true); 50],
        };
        assert_eq!(pooled_allowable(&[few]), Allowable::TooFewSamples(50));
    }

    #[test]
    fn a_round_counts_only_at_or_below_its_upper_slope() {
        // Round 0 over 0-40 deg, unstable from 10 deg on; round 1 below 12 deg, all stable:
        // at s <= 12 both count, past 12 round 1 leaves the pool.
        let round0 = Round {
            upper: 40.0,
            samples: (0..400).map(|i| (f64::from(i) / 10.0, i < 100)).collect(),
        };
        let round1 = Round {
            upper: 12.0,
            samples: (0..1200).map(|i| (f64::from(i) / 100.0, true)).collect(),
        };
        let pooled = pooled_allowable(&[round0.clone(), round1.clone()]);
        // Alone, round 0 has 100 stable of the first 100 (0.0-9.9 deg), then 100/n: the
        // share at or below 10.1 deg is 100/102 < 0.99, and at 10.0 100/101 >= 0.99.
        assert_eq!(
            allowable_slope(&mut round0.samples.clone()).slope_deg(),
            Some(10.0)
        );
        // Pooled, round 0's slopes are tenths, round 1's hundredths. At 11.19 deg: round 0's
        // 112 samples (12 unstable) and round 1's 1120: 1220/1232 = 0.99026 >= 0.99; at
        // 11.2: 113 (13 unstable) and 1121: 1221/1234 = 0.98946; at 12.0 both count, 1300
        // of 1321 stable; past 12 round 1 leaves the pool and round 0 alone is far below.
        assert_eq!(pooled.slope_deg(), Some(11.19), "{pooled:?}");
    }

    /// The search of `with_slope_below`, `pooled_allowable`, `stop_rule` and `next_upper` on
    /// slopes uniform on 0-45 deg with `p_stable(slope)`, its first round's upper slope that
    /// of `first`: the allowable slope and its interval, the samples used and why it stopped.
    fn search(
        p_stable: impl Fn(f64) -> f64,
        seed: u64,
        first: Allowable,
    ) -> (Allowable, u64, Stop) {
        let dist = Dist::Uniform {
            min: 0.0,
            max: 45.0,
        };
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut rounds = Vec::new();
        let mut allowable = first;
        let mut used = 0;
        loop {
            let upper = next_upper(allowable, (0.0, 45.0), 0.5);
            let samples = (0..2000)
                .map(|_| {
                    let u = crate::rng::uniform_open01(&mut rng);
                    let s = crate::dist::quantile(&conditioned(dist, upper), u, 0);
                    (s, crate::rng::uniform01(&mut rng) < p_stable(s))
                })
                .collect();
            rounds.push(Round { upper, samples });
            used += 2000;
            allowable = pooled_allowable(&rounds);
            if let Some(stop) = stop_rule(allowable, (0.0, 45.0), 0.5, upper, (used, 400_000)) {
                return (allowable, used, stop);
            }
        }
    }

    #[test]
    fn a_known_cumulative_boundary_is_inside_the_interval() {
        // A step: stable below 30 deg, never above. The stable share at or below s > 30 is
        // 30 / s, 0.99 at s = 30.303.
        // A ramp: p = 1 - 0.02 (s - 20) above 20 deg; the share at or below s is
        // 1 - 0.01 (s - 20)^2 / s, 0.99 at s = 25.
        let step = |s: f64| if s < 30.0 { 1.0 } else { 0.0 };
        let ramp = |s: f64| 1.0 - 0.02 * (s - 20.0).max(0.0);
        for (name, truth, found) in [
            (
                "step",
                30.0 / 0.99,
                search(step, 1, Allowable::TooFewSamples(0)),
            ),
            ("ramp", 25.0, search(ramp, 2, Allowable::TooFewSamples(0))),
            // As if an unlucky first round had put the upper end 10 deg too low: the rounds
            // drawn above it bring it back (drawn up to the upper end alone, they would
            // close the interval at 20.2 deg).
            (
                "step, from too low",
                30.0 / 0.99,
                search(
                    step,
                    3,
                    Allowable::Slope {
                        slope_deg: 20.0,
                        low_deg: 19.8,
                        high_deg: 20.2,
                    },
                ),
            ),
        ] {
            let (allowable, used, stop) = found;
            let Allowable::Slope {
                low_deg, high_deg, ..
            } = allowable
            else {
                panic!("{name}: {allowable:?}")
            };
            assert!(
                (low_deg..=high_deg).contains(&truth),
                "{name}: {truth} outside {allowable:?}"
            );
            assert_eq!(stop, Stop::Tolerance, "{name}: {allowable:?} after {used}");
            assert!(used < 400_000, "{name}: {used} samples");
        }
    }

    #[test]
    fn at_the_top_of_the_range_a_redrawn_slope_is_the_samples_own() {
        let mut scenario = Scenario::default();
        for dist in [
            scenario.inputs.slope_deg,
            Dist::Normal {
                mean: 10.0,
                sd: 8.0,
                min: 0.0,
                max: 40.0,
            },
        ] {
            scenario.inputs.slope_deg = dist;
            for i in 0..200 {
                let s = crate::sampling::sample(&scenario, i);
                assert_eq!(with_value_below(s, 0, dist, dist.support().1), s);
                let below = with_value_below(s, 0, dist, 12.0);
                assert!(below.inputs.slope_deg <= 12.0, "{below:?}");
                assert_eq!(
                    (below.seed, below.inputs.yaw_deg, below.parameters),
                    (s.seed, s.inputs.yaw_deg, s.parameters)
                );
            }
        }
    }
}
