//! The boundary search run: rounds of the scenario's own samples, their slopes (or the
//! values of the input searched) drawn below each unfinished sector's interval so far
//! (`boundary`'s rules), run through the kernels until every sector stops.

use super::workers::{CHUNK, worker_pool};
use crate::boundary::{
    Round, Stop, next_upper, pooled_allowable, reachable_sectors, stop_rule, with_unit,
    with_value_below,
};
use crate::reference::Model;
use crate::reference::outcome::Outcome;
use crate::sampling;
use crate::scenario::InputTable;
use crate::scenario::Sample;
use crate::scenario::{Design, Dist, Scenario, value_dists, value_key, value_name, value_unit};
use crate::stats::{Allowable, SECTORS, relative_azimuth_deg, sector_of};
use anyhow::bail;
use std::sync::Arc;
use std::sync::atomic::AtomicUsize;

/// The settings of a search (`touchdown boundary`'s flags, checked).
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// The value searched (`Sample::values`; 0, the slope, by default).
    pub input: usize,
    /// A sector is finished once its 95 % interval is at most this wide, in the input's
    /// unit; `None`: `SLOPE_TOLERANCE_DEG` for the slope, else `TOLERANCE_OF_RANGE` of the
    /// input's range.
    pub tolerance: Option<f64>,
    /// Samples per unfinished sector per round.
    pub batch: u64,
    /// A sector is finished once it has run this many samples.
    pub max_samples_per_sector: u64,
}

/// The default tolerance for the slope, deg.
pub const SLOPE_TOLERANCE_DEG: f64 = 0.5;

/// The default tolerance of another input, as a fraction of its range: as 0.5 deg is of
/// the default scenario's slopes, 0 to 45 deg.
pub const TOLERANCE_OF_RANGE: f64 = 1.0 / 90.0;

/// Candidates drawn per sample a round wants, at most, before a sector the scenario's
/// azimuth and yaw do not reach is given up.
const DRAWS_PER_WANTED: u64 = 64;

/// One sector's search.
pub struct Sector {
    /// Its rounds so far, in order.
    pub rounds: Vec<Round>,
    /// Samples it has run, over all its rounds.
    pub used: u64,
    /// Its allowable slope (value of the input) pooled over the rounds, with the 95 %
    /// interval.
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
    /// The scenario's distribution of the input searched.
    pub dist: Dist,
    /// The scenario's design (the search draws independently).
    pub design: Design,
    /// The value searched (`Settings::input`).
    pub input: usize,
    /// The tolerance it ran with (`Settings::tolerance`, or its default).
    pub tolerance: f64,
}

/// Searches the allowable slope of every sector of `scenario` on `threads` workers,
/// reporting each round on stderr if `progress`.
pub fn search(
    mut scenario: Scenario,
    settings: &Settings,
    threads: Option<usize>,
    progress: bool,
) -> anyhow::Result<Search> {
    let k = settings.input;
    let dist = input_distribution(&scenario, k)?;
    check_memory(settings)?;
    let range = dist.support();
    let tolerance = match settings.tolerance {
        Some(t) => t,
        None if k == 0 => SLOPE_TOLERANCE_DEG,
        None if (range.1 - range.0).is_finite() => (range.1 - range.0) * TOLERANCE_OF_RANGE,
        None => bail!(
            "--input {}: the scenario draws it without an upper bound ({} = {}), so it has \
             no default tolerance: give --tolerance (in {})",
            value_name(k),
            value_key(k),
            dist.toml(),
            value_unit(k)
        ),
    };
    // A tolerance as wide as the range would end every sector's search before it began,
    // "allowable up to the top" whatever the samples say.
    if tolerance >= range.1 - range.0 {
        let unit = value_unit(k);
        anyhow::bail!(
            "--tolerance {}: must be less than the width of the range of {}, {} (from {} to \
             {}), or every sector stops before it is searched",
            with_unit(tolerance, unit),
            value_key(k),
            with_unit(range.1 - range.0, unit),
            range.0,
            with_unit(range.1, unit)
        );
    }
    // Candidates are independent draws; a row of a round takes a candidate's values.
    let design = scenario.design;
    scenario.design = Design::Independent;
    let pool = worker_pool(threads)?;
    let model = Model::new(&scenario);
    let isa = kernels::isa::Isa::detect();
    let never = AtomicUsize::new(0);
    // A sector no sample can fall in (a fixed azimuth and yaw put every sample in one) is
    // not searched: drawing for it would spend its whole budget of candidates in vain.
    let inputs = value_dists(&scenario);
    let reachable = reachable_sectors(
        inputs[value_index("downhill_azimuth_deg")],
        inputs[value_index("yaw_deg")],
    );
    let mut sectors: Vec<Sector> = reachable
        .iter()
        .map(|&reached| Sector {
            rounds: Vec::new(),
            used: 0,
            allowable: Allowable::TooFewSamples(0),
            stop: (!reached).then_some(Stop::Unreached),
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
            .map(|s| next_upper(s.allowable, range, tolerance))
            .collect();
        let mut draw = RoundDraw::new(&wanted, next_candidate);
        for (sector, s) in sectors.iter_mut().enumerate() {
            if wanted[sector] > 0 {
                s.rounds.push(Round {
                    upper: upper[sector],
                    samples: Vec::new(),
                });
            }
        }
        // The round in pieces of at most `PIECE_ROWS` rows, each run when drawn: the same
        // rows in the same order as the round at once (a row's results are its sample's),
        // in memory of one piece.
        let mut ran_round = 0u64;
        loop {
            let (rows, row_sector) = draw.piece(&scenario, (k, dist), &upper, &mut next_candidate);
            if rows.is_empty() {
                break;
            }
            ran_round += rows.len() as u64;
            let count = rows.len() as u64;
            let mut round = scenario.clone();
            round.table = Some(Arc::new(InputTable::from_samples(rows)));
            pool.install(|| {
                crate::sweep::run_until(&round, &model, isa, 0..count, CHUNK, &never, |ran| {
                    for r in ran {
                        let sector = row_sector[r.sample.index as usize];
                        let stable = r.summary.outcome == Outcome::Stable;
                        let last = sectors[sector]
                            .rounds
                            .last_mut()
                            .expect("the round is pushed");
                        last.samples.push((r.sample.values()[k], stable));
                    }
                    Ok(())
                })
            })?;
        }
        let got = draw.got;
        for (sector, s) in sectors.iter_mut().enumerate() {
            if wanted[sector] > 0 && got[sector] == 0 {
                s.stop = Some(Stop::Unreached);
            }
        }
        total += ran_round;
        close_round(
            &mut sectors,
            &wanted,
            &got,
            &upper,
            range,
            tolerance,
            settings,
        );
        if progress {
            let open = sectors.iter().filter(|s| s.stop.is_none()).count();
            super::workers::tell(&format!(
                "touchdown boundary: round {}: {ran_round} samples ({total} in all), {open} \
                 sectors open\n",
                sectors.iter().map(|s| s.rounds.len()).max().unwrap_or(0),
            ));
        }
    }
    Ok(Search {
        sectors,
        total,
        candidates: next_candidate,
        dist,
        design,
        input: k,
        tolerance,
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
    tolerance: f64,
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
            tolerance,
            upper[k],
            (sector.used, settings.max_samples_per_sector),
        ));
    }
}

/// Bytes a search holds per sample it keeps: its slope and outcome (16), with room for
/// its sector's vector to grow (16 more).
const BYTES_PER_KEPT: u64 = 32;

/// Bytes a sector's interval takes per sample of it while it is found
/// (`pooled_allowable`: each sample with its round, and the counts at each slope).
const BYTES_PER_POOLED: u64 = 48;

/// Refuses a search whose samples would not fit in memory: each sector keeps up to
/// `--max-samples-per-sector` samples, and a round runs in pieces of `PIECE_ROWS`.
fn check_memory(settings: &Settings) -> anyhow::Result<()> {
    let max = settings.max_samples_per_sector;
    let bytes = (SECTORS as u64)
        .saturating_mul(max)
        .saturating_mul(BYTES_PER_KEPT)
        .saturating_add(max.saturating_mul(BYTES_PER_POOLED))
        .saturating_add(PIECE_ROWS as u64 * 2 * std::mem::size_of::<Sample>() as u64);
    super::memory::check_fits(bytes, || {
        format!(
            "--max-samples-per-sector {max}: the search keeps every sample it runs \
             ({BYTES_PER_KEPT} bytes each, up to {SECTORS} sectors x {max}) to find each \
             sector's interval; it"
        )
    })
}

/// The distribution of value `k` of `scenario`'s samples (the slope, or another input
/// `--input` names), refused where the search cannot draw below a bound (not uniform or
/// normal, or reaching below 0, where `stats` starts an interval that resolves no value),
/// where the value places the sectors (the downhill azimuth, the yaw), or where the search
/// cannot keep the scenario's grid of control-law parameters.
fn input_distribution(scenario: &Scenario, k: usize) -> anyhow::Result<Dist> {
    let dist = value_dists(scenario)[k];
    let name = value_name(k);
    if !matches!(dist, Dist::Uniform { .. } | Dist::Normal { .. }) {
        if k == 0 {
            bail!(
                "the scenario's slope_deg is {}: the boundary search draws slopes below a \
                 bound, so it needs slope_deg drawn from a distribution (uniform or normal)",
                dist.toml()
            );
        }
        bail!(
            "--input {name}: the scenario's {} is {}: the boundary search draws the input \
             below a bound, so it needs it drawn from a distribution (uniform or normal)",
            value_key(k),
            dist.toml()
        );
    }
    if ["downhill_azimuth_deg", "yaw_deg"].contains(&name) {
        bail!(
            "--input {name}: the sectors are those of the downhill azimuth relative to the \
             yaw, so the search cannot draw {name} below a bound; search another input"
        );
    }
    if dist.support().0 < 0.0 {
        bail!(
            "--input {name}: the scenario's {} = {} reaches below 0; the search's interval \
             starts at 0 where no value is resolved as allowable, so it needs an input of \
             values of at least 0",
            value_key(k),
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

/// The position in `Sample::values` of the value named `name`.
fn value_index(name: &str) -> usize {
    (0..crate::scenario::VALUES)
        .find(|&k| value_name(k) == name)
        .expect("a value of every sample")
}

/// Rows of a round run at once, at most: about 200 bytes of sample each, twice (the rows
/// and the table made of them).
const PIECE_ROWS: usize = 65_536;

/// The drawing of one round's rows: candidates drawn in order, each kept for its sector
/// while the sector wants more (`wanted`), its slope (the input searched) redrawn below the
/// sector's upper end, until every sector has its rows or the candidates allowed run out.
struct RoundDraw {
    wanted: [u64; SECTORS],
    /// Rows each sector got so far.
    got: [u64; SECTORS],
    /// The candidate at which the round gives up.
    budget: u64,
}

impl RoundDraw {
    fn new(wanted: &[u64], next: u64) -> RoundDraw {
        let want: u64 = wanted.iter().sum();
        RoundDraw {
            wanted: std::array::from_fn(|k| wanted[k]),
            got: [0; SECTORS],
            budget: next.saturating_add(DRAWS_PER_WANTED.saturating_mul(want)),
        }
    }

    /// The next rows of the round, at most `PIECE_ROWS` (none once it is complete), drawn
    /// from candidate `next` on, with the sector of each row.
    fn piece(
        &mut self,
        scenario: &Scenario,
        (input, dist): (usize, Dist),
        upper: &[f64],
        next: &mut u64,
    ) -> (Vec<Sample>, Vec<usize>) {
        let want: u64 = self.wanted.iter().sum();
        let left = (want - self.got.iter().sum::<u64>()).min(PIECE_ROWS as u64) as usize;
        let mut rows: Vec<Sample> = Vec::with_capacity(left);
        let mut row_sector: Vec<usize> = Vec::with_capacity(left);
        while rows.len() < left && *next < self.budget {
            let s = sampling::sample(scenario, *next);
            *next += 1;
            let k = sector_of(relative_azimuth_deg(
                s.inputs.downhill_azimuth_deg,
                s.inputs.yaw_deg,
            ));
            if self.got[k] < self.wanted[k] {
                self.got[k] += 1;
                rows.push(with_value_below(s, input, dist, upper[k]));
                row_sector.push(k);
            }
        }
        (rows, row_sector)
    }
}
