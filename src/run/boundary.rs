//! The boundary search run: rounds of the scenario's own samples, their slopes drawn below
//! each unfinished sector's interval so far (`boundary`'s rules), run through the kernels
//! until every sector stops.

use super::workers::{CHUNK, worker_pool};
use crate::boundary::{Round, Stop, next_upper, pooled_allowable, stop_rule, with_slope_below};
use crate::reference::Model;
use crate::reference::outcome::Outcome;
use crate::sampling;
use crate::scenario::InputTable;
use crate::scenario::Sample;
use crate::scenario::{Design, Dist, Scenario};
use crate::stats::{Allowable, SECTORS, relative_azimuth_deg, sector_of};
use anyhow::bail;
use std::sync::Arc;
use std::sync::atomic::AtomicUsize;

/// The settings of a search (`touchdown boundary`'s flags, checked).
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// A sector is finished once its 95 % interval is at most this wide, deg.
    pub tolerance: f64,
    /// Samples per unfinished sector per round.
    pub batch: u64,
    /// A sector is finished once it has run this many samples.
    pub max_samples_per_sector: u64,
}

/// Candidates drawn per sample a round wants, at most, before a sector the scenario's
/// azimuth and yaw do not reach is given up.
const DRAWS_PER_WANTED: u64 = 64;

/// One sector's search.
pub struct Sector {
    /// Its rounds so far, in order.
    pub rounds: Vec<Round>,
    /// Samples it has run, over all its rounds.
    pub used: u64,
    /// Its allowable slope pooled over the rounds, with the 95 % interval.
    pub allowable: Allowable,
    /// Why its search stopped; `None` while it goes on.
    pub stop: Option<Stop>,
}

/// What a search found.
pub struct Search {
    /// The sectors, in order of azimuth.
    pub sectors: Vec<Sector>,
    /// Samples simulated.
    pub total: u64,
    /// Candidates drawn.
    pub candidates: u64,
    /// The scenario's slope distribution.
    pub dist: Dist,
    /// The scenario's design (the search draws independently).
    pub design: Design,
}

/// Searches the allowable slope of every sector of `scenario` on `threads` workers,
/// reporting each round on stderr if `progress`.
pub fn search(
    mut scenario: Scenario,
    settings: &Settings,
    threads: Option<usize>,
    progress: bool,
) -> anyhow::Result<Search> {
    let dist = slope_distribution(&scenario)?;
    let range = dist.support();
    // Candidates are independent draws; a row of a round takes a candidate's values.
    let design = scenario.design;
    scenario.design = Design::Independent;
    let pool = worker_pool(threads)?;
    let model = Model::new(&scenario);
    let isa = kernels::isa::Isa::detect();
    let never = AtomicUsize::new(0);
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
                None => settings.batch.min(settings.max_samples_per_sector - s.used),
                Some(_) => 0,
            })
            .collect();
        let upper: Vec<f64> = sectors
            .iter()
            .map(|s| next_upper(s.allowable, range, settings.tolerance))
            .collect();
        let (rows, row_sector, got) =
            draw_round(&scenario, dist, &wanted, &upper, &mut next_candidate);
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
        round.table = Some(Arc::new(InputTable::from_samples(rows.clone())));
        pool.install(|| {
            crate::sweep::run_until(
                &round,
                &model,
                isa,
                0..rows.len() as u64,
                CHUNK,
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
        close_round(&mut sectors, &wanted, &got, &upper, range, settings);
        if progress {
            let open = sectors.iter().filter(|s| s.stop.is_none()).count();
            eprintln!(
                "touchdown boundary: round {}: {} samples ({total} in all), {open} sectors open",
                sectors.iter().map(|s| s.rounds.len()).max().unwrap_or(0),
                rows.len()
            );
        }
    }
    Ok(Search {
        sectors,
        total,
        candidates: next_candidate,
        dist,
        design,
    })
}

/// Each sector that took part in a round after its samples ran: its samples counted, its
/// allowable slope pooled over its rounds, and whether it stops.
fn close_round(
    sectors: &mut [Sector],
    wanted: &[u64],
    got: &[u64],
    upper: &[f64],
    range: (f64, f64),
    settings: &Settings,
) {
    for (k, sector) in sectors.iter_mut().enumerate() {
        if wanted[k] == 0 {
            continue;
        }
        sector.used += got[k];
        sector.allowable = pooled_allowable(&sector.rounds);
        sector.stop = sector.stop.or(stop_rule(
            sector.allowable,
            range,
            settings.tolerance,
            upper[k],
            (sector.used, settings.max_samples_per_sector),
        ));
    }
}

/// The slope distribution of `scenario`, refused where the search cannot draw below a bound
/// or cannot keep the scenario's grid of control-law parameters.
fn slope_distribution(scenario: &Scenario) -> anyhow::Result<Dist> {
    let dist = scenario.inputs.slope_deg;
    if !matches!(dist, Dist::Uniform { .. } | Dist::Normal { .. }) {
        bail!(
            "the scenario's slope_deg is {}: the boundary search draws slopes below a bound, \
             so it needs slope_deg drawn from a distribution (uniform or normal)",
            dist.toml()
        );
    }
    if crate::scenario::law_grid_size(scenario.control.as_ref()) > 1 {
        bail!(
            "the scenario puts control-law parameters on a grid: their cell follows a \
             sample's place in a sweep, which the boundary search does not keep"
        );
    }
    Ok(dist)
}

/// The rows of one round: candidates drawn in order from `next`, each kept for its sector
/// while the sector wants more (`wanted`), its slope redrawn below the sector's upper slope
/// (`upper`); with the sector of each row and the rows each sector got.
fn draw_round(
    scenario: &Scenario,
    dist: Dist,
    wanted: &[u64],
    upper: &[f64],
    next: &mut u64,
) -> (Vec<Sample>, Vec<usize>, [u64; SECTORS]) {
    let want: u64 = wanted.iter().sum();
    let mut got = [0u64; SECTORS];
    let mut rows: Vec<Sample> = Vec::with_capacity(want as usize);
    let mut row_sector: Vec<usize> = Vec::with_capacity(want as usize);
    let budget = *next + DRAWS_PER_WANTED * want;
    while (rows.len() as u64) < want && *next < budget {
        let s = sampling::sample(scenario, *next);
        *next += 1;
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
    (rows, row_sector, got)
}
