//! `touchdown boundary`: the allowable slope of each azimuth sector (`stats::allowable_slope`)
//! found directly, by adaptive sampling, with its 95 % interval.
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

use crate::dist::quantile;
use crate::reference::Model;
use crate::reference::outcome::Outcome;
use crate::rng::{stream, uniform_open01};
use crate::sampling;
use crate::scenario::InputTable;
use crate::scenario::{Design, Dist};
use crate::scenario::{Sample, law_grid_size};
use crate::stats::{
    Allowable, MIN_SAMPLES, SECTOR_DEG, SECTORS, allowable_of_counts, relative_azimuth_deg,
    sector_of,
};
use anyhow::bail;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicUsize;

/// Flags of `touchdown boundary`.
#[derive(clap::Args, Debug)]
pub struct BoundaryArgs {
    /// Scenario file (TOML); without it, the default sweep of MODEL.md section 11. Its
    /// slope must be drawn from a distribution (uniform or normal).
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Seed (overrides the scenario's `seed`).
    #[arg(long, value_name = "S", value_parser = crate::cli::parse_seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// A sector is finished once its 95 % interval is at most this wide, deg.
    #[arg(
        long,
        value_name = "DEG",
        default_value = "0.5",
        allow_negative_numbers = true
    )]
    pub tolerance: f64,
    /// Samples per unfinished sector per round.
    #[arg(long, value_name = "N", default_value = "2000", value_parser = crate::cli::parse_count, allow_negative_numbers = true)]
    pub batch: u64,
    /// A sector is finished once it has run this many samples.
    #[arg(long, value_name = "N", default_value = "200000", value_parser = crate::cli::parse_count, allow_negative_numbers = true)]
    pub max_samples_per_sector: u64,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "T", value_parser = crate::cli::parse_threads, allow_negative_numbers = true)]
    pub threads: Option<usize>,
    /// No progress on stderr (there is none either when stderr is not a terminal).
    #[arg(long)]
    pub quiet: bool,
}

/// The samples of one sector from one round: slopes drawn from the scenario's slope
/// distribution conditioned on `[slope_min, upper_deg]`, and whether each was stable.
#[derive(Debug, Clone, PartialEq)]
pub struct Round {
    pub upper_deg: f64,
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
    by_upper.sort_by(|&a, &b| rounds[a].upper_deg.total_cmp(&rounds[b].upper_deg));
    let mut left = by_upper.iter().peekable();
    let mut counts = vec![(0u64, 0u64); rounds.len()];
    let mut pooled = vec![true; rounds.len()];
    let (mut n, mut k) = (0u64, 0u64);
    let mut at_or_below = Vec::new();
    let mut i = 0;
    while i < all.len() {
        let s = all[i].0;
        while let Some(&&r) = left.peek() {
            if rounds[r].upper_deg >= s {
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
    /// The report's cell.
    #[must_use]
    pub fn cell(self) -> &'static str {
        match self {
            Stop::Tolerance => "interval within tolerance",
            Stop::WholeRange => "allowable up to the top of the slope range",
            Stop::NoSlope => "no allowable slope",
            Stop::SampleLimit => "sample limit",
            Stop::Unreached => "no samples in this sector",
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
        Dist::Normal { mean, sd, min, .. } => Dist::Normal {
            mean,
            sd,
            min,
            max: upper,
        },
        other => other,
    }
}

/// `sample` with its slope redrawn from `dist` conditioned on `[min, upper]`, from the
/// sample's own uniform of its slope stream: the inverse CDF of `U * F(upper)`. Everything
/// else stays. At the top of the range it is the sample's own slope.
#[must_use]
pub fn with_slope_below(mut sample: Sample, dist: Dist, upper: f64) -> Sample {
    let u = uniform_open01(&mut stream(sample.seed, "slope_deg"));
    sample.inputs.slope_deg = quantile(&conditioned(dist, upper), u, 0);
    sample
}

/// Candidates drawn per sample a round wants, at most, before a sector the scenario's
/// azimuth and yaw do not reach is given up.
const DRAWS_PER_WANTED: u64 = 64;

/// One sector's search.
struct Sector {
    rounds: Vec<Round>,
    used: u64,
    allowable: Allowable,
    stop: Option<Stop>,
}

/// Runs `touchdown boundary`.
pub fn run(args: &BoundaryArgs) -> anyhow::Result<()> {
    use std::io::IsTerminal;
    let started = std::time::Instant::now();
    if !(args.tolerance > 0.0 && args.tolerance.is_finite()) {
        bail!(
            "--tolerance {}: must be a width in deg above 0",
            args.tolerance
        );
    }
    if args.batch == 0 {
        bail!("--batch 0: each round needs at least 1 sample per sector");
    }
    if args.max_samples_per_sector == 0 {
        bail!("--max-samples-per-sector 0: a sector needs at least 1 sample");
    }
    let (mut scenario, _) = crate::cli::load_scenario(args.scenario.as_ref(), args.seed)?;
    let dist = scenario.inputs.slope_deg;
    if !matches!(dist, Dist::Uniform { .. } | Dist::Normal { .. }) {
        bail!(
            "the scenario's slope_deg is {}: the boundary search draws slopes below a bound, \
             so it needs slope_deg drawn from a distribution (uniform or normal)",
            dist.toml()
        );
    }
    if law_grid_size(scenario.control.as_ref()) > 1 {
        bail!(
            "the scenario puts control-law parameters on a grid: their cell follows a \
             sample's place in a sweep, which the boundary search does not keep"
        );
    }
    let range = dist.support();
    // Candidates are independent draws; a row of a round takes a candidate's values.
    let design = scenario.design;
    scenario.design = Design::Independent;
    let pool = crate::cli::worker_pool(args.threads)?;
    let model = Model::new(&scenario);
    let isa = kernels::isa::Isa::detect();
    let never = AtomicUsize::new(0);
    let progress = !args.quiet && std::io::stderr().is_terminal();
    let mut sectors: Vec<Sector> = (0..SECTORS)
        .map(|_| Sector {
            rounds: Vec::new(),
            used: 0,
            allowable: Allowable::TooFewSamples(0),
            stop: None,
        })
        .collect();
    let mut next_candidate = 0u64;
    let mut total = 0u64;
    while sectors.iter().any(|s| s.stop.is_none()) {
        let wanted: Vec<u64> = sectors
            .iter()
            .map(|s| match s.stop {
                None => args.batch.min(args.max_samples_per_sector - s.used),
                Some(_) => 0,
            })
            .collect();
        let upper: Vec<f64> = sectors
            .iter()
            .map(|s| next_upper(s.allowable, range, args.tolerance))
            .collect();
        let want: u64 = wanted.iter().sum();
        let mut got = [0u64; SECTORS];
        let mut rows: Vec<Sample> = Vec::with_capacity(want as usize);
        let mut row_sector: Vec<usize> = Vec::with_capacity(want as usize);
        let budget = next_candidate + DRAWS_PER_WANTED * want;
        while (rows.len() as u64) < want && next_candidate < budget {
            let s = sampling::sample(&scenario, next_candidate);
            next_candidate += 1;
            let k = sector_of(relative_azimuth_deg(
                s.inputs.downhill_azimuth_deg,
                s.inputs.yaw_deg,
            ));
            if got[k] < wanted[k] {
                got[k] += 1;
                rows.push(with_slope_below(s, dist, upper[k]));
                row_sector.push(k);
            }
        }
        for (k, sector) in sectors.iter_mut().enumerate() {
            if wanted[k] > 0 {
                sector.rounds.push(Round {
                    upper_deg: upper[k],
                    samples: Vec::with_capacity(got[k] as usize),
                });
                if got[k] == 0 {
                    sector.stop = Some(Stop::Unreached);
                }
            }
        }
        let mut round = scenario.clone();
        round.table = Some(Arc::new(InputTable::from_samples(&rows)));
        pool.install(|| {
            crate::sweep::run_until(
                &round,
                &model,
                isa,
                0..rows.len() as u64,
                crate::cli::CHUNK,
                &never,
                |ran| {
                    for r in ran {
                        let k = row_sector[r.sample.index as usize];
                        let stable = r.summary.outcome == Outcome::Stable;
                        let last = sectors[k].rounds.last_mut().expect("the round is pushed");
                        last.samples.push((r.sample.inputs.slope_deg, stable));
                    }
                    Ok(())
                },
            )
        })?;
        total += rows.len() as u64;
        for (k, sector) in sectors.iter_mut().enumerate() {
            if wanted[k] == 0 {
                continue;
            }
            sector.used += got[k];
            sector.allowable = pooled_allowable(&sector.rounds);
            sector.stop = sector.stop.or(stop_rule(
                sector.allowable,
                range,
                args.tolerance,
                upper[k],
                (sector.used, args.max_samples_per_sector),
            ));
        }
        if progress {
            let open = sectors.iter().filter(|s| s.stop.is_none()).count();
            eprintln!(
                "touchdown boundary: round {}: {} samples ({total} in all), {open} sectors open",
                sectors.iter().map(|s| s.rounds.len()).max().unwrap_or(0),
                rows.len()
            );
        }
    }
    let name = args.scenario.as_ref().map_or_else(
        || "the default scenario".to_string(),
        |p| p.display().to_string(),
    );
    let mut t = String::new();
    let _ = writeln!(t, "# touchdown boundary: {name}\n");
    let _ = writeln!(
        t,
        "Seed {}, slope_deg = {}, tolerance {} deg, batch {} per sector, at most {} samples \
         per sector{}. {total} samples simulated ({next_candidate} candidates drawn) in \
         {:.1} s.\n",
        scenario.seed,
        dist.toml(),
        args.tolerance,
        args.batch,
        args.max_samples_per_sector,
        if design == Design::Independent {
            ""
        } else {
            "; inputs drawn independently (the scenario's design is not)"
        },
        started.elapsed().as_secs_f64()
    );
    let _ = writeln!(
        t,
        "## Allowable slope\n\nAs `touchdown report` defines it, per sector of downhill \
         azimuth relative to the lander; each round drew a sector's slopes below the upper \
         end of its interval so far, and the interval pools all its rounds.\n"
    );
    let _ = writeln!(
        t,
        "| azimuth sector | samples | rounds | allowable slope | 95 % interval | stopped |\n\
         |---|---:|---:|---:|---:|---|"
    );
    for (k, s) in sectors.iter().enumerate() {
        let _ = writeln!(
            t,
            "| {:.0}–{:.0} deg | {} | {} | {} | {} | {} |",
            k as f64 * SECTOR_DEG,
            (k + 1) as f64 * SECTOR_DEG,
            s.used,
            s.rounds.len(),
            s.allowable.cell(),
            s.allowable.interval_cell(),
            s.stop.map_or("", Stop::cell)
        );
    }
    crate::cli::print_out(&t);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Scenario;
    use crate::stats::allowable_slope;
    use rand_core::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

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
                upper_deg: 45.0,
                samples: samples.clone(),
            };
            assert_eq!(
                pooled_allowable(&[round]),
                allowable_slope(&mut samples.clone()),
                "boundary {boundary}"
            );
        }
        let few = Round {
            upper_deg: 45.0,
            samples: vec![(1.0, true); 50],
        };
        assert_eq!(pooled_allowable(&[few]), Allowable::TooFewSamples(50));
    }

    #[test]
    fn a_round_counts_only_at_or_below_its_upper_slope() {
        // Round 0 over 0-40 deg, unstable from 10 deg on; round 1 below 12 deg, all stable:
        // at s <= 12 both count, past 12 round 1 leaves the pool.
        let round0 = Round {
            upper_deg: 40.0,
            samples: (0..400).map(|i| (f64::from(i) / 10.0, i < 100)).collect(),
        };
        let round1 = Round {
            upper_deg: 12.0,
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
                    let u = uniform_open01(&mut rng);
                    let s = quantile(&conditioned(dist, upper), u, 0);
                    (s, crate::rng::uniform01(&mut rng) < p_stable(s))
                })
                .collect();
            rounds.push(Round {
                upper_deg: upper,
                samples,
            });
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
                let s = sampling::sample(&scenario, i);
                assert_eq!(with_slope_below(s, dist, dist.support().1), s);
                let below = with_slope_below(s, dist, 12.0);
                assert!(below.inputs.slope_deg <= 12.0, "{below:?}");
                assert_eq!(
                    (below.seed, below.inputs.yaw_deg, below.parameters),
                    (s.seed, s.inputs.yaw_deg, s.parameters)
                );
            }
        }
    }
}
