//! The report as data: every number of it computed once, from one reading of the sweep's
//! rows (and one of its load columns for the exceedance), for the Markdown and the JSON to
//! write alike.

use super::gather::{Gathered, LOADS};
use super::gear::GearSection;
use super::ground::GroundSection;
use super::numbers::{Share, Summary, summaries};
use super::release::ReleaseSection;
use super::thrust::ThrustSection;
use crate::exceedance::DesignValues;
use crate::output::sweep::SweepSource;
use crate::reference::Outcome;
use crate::scenario::Scenario;
use crate::stats::{Allowable, SECTOR_DEG, allowable_slope};
use crate::weighting::{SlopeDistribution, Weighted};
use anyhow::{anyhow, bail};
use std::path::PathBuf;

/// Where the sweep came from.
pub(super) struct Provenance {
    /// The sweep file's path, or the name of a sweep held in memory.
    pub(super) sweep: PathBuf,
    /// Whether it was held in memory.
    pub(super) in_memory: bool,
    /// Its samples.
    pub(super) samples: u64,
    /// Its seed, as its metadata gives it.
    pub(super) seed: Option<String>,
    /// The engine that ran it, as its metadata gives it.
    pub(super) engine: Option<String>,
    /// Whether the scenario stored in it has its dampers on (`None`: it does not read).
    pub(super) dampers: Option<bool>,
    /// The samples it asked for, where it holds fewer (an interrupted sweep's file), and
    /// what to say of it (`output::sweep::interrupted_note`).
    pub(super) interrupted: Option<(u64, String)>,
}

/// The allowable slope of one sector of downhill azimuth relative to the lander.
pub(super) struct Sector {
    /// Its bounds, deg.
    pub(super) azimuth_deg: (f64, f64),
    /// Its samples.
    pub(super) samples: u64,
    /// The stable ones.
    pub(super) stable: u64,
    /// The allowable slope, or why there is none.
    pub(super) allowable: Allowable,
}

/// The outcome shares on a terrain of a `--slope-distribution`.
pub(super) struct Terrain {
    /// The distribution as given (`rayleigh:12`, or the path of a CSV file of bins).
    pub(super) text: String,
    /// What it is, in words.
    pub(super) description: String,
    /// The shares.
    pub(super) weighted: Weighted,
}

/// Everything the report says of a sweep.
pub(super) struct Report {
    /// Where the sweep came from.
    pub(super) provenance: Provenance,
    /// The samples of each outcome listed (`Outcome::listed`: `held` with a control loop).
    pub(super) outcomes: Vec<(Outcome, Share)>,
    /// With `[limits]` (the `limits_broken` column): the stable samples within them.
    pub(super) stable_within_limits: Option<Share>,
    /// With dampers or `[limits]`: bottomed dampers and broken limits.
    pub(super) gear: Option<GearSection>,
    /// On regolith: the footprints' depth and the energy the soil kept.
    pub(super) ground: Option<GroundSection>,
    /// With `--slope-distribution`: the outcome shares on that terrain.
    pub(super) terrain: Option<Terrain>,
    /// Per sector of downhill azimuth relative to the lander.
    pub(super) allowable: Vec<Sector>,
    /// The peak loads (`gather::LOADS`).
    pub(super) loads: Vec<Summary>,
    /// The load exceedance's design values.
    pub(super) exceedance: DesignValues,
    /// With a control loop: propellant and firings.
    pub(super) thrust: Option<ThrustSection>,
    /// With a descent: the release of the landers.
    pub(super) release: Option<ReleaseSection>,
}

impl Report {
    /// The report of the sweep `source`; with `terrain` (a `--slope-distribution` and its
    /// text), its outcome shares on that terrain.
    pub(super) fn of(
        source: &SweepSource,
        terrain: Option<(&SlopeDistribution, &str)>,
    ) -> anyhow::Result<Report> {
        let path = source.name();
        let mut file = source.open()?;
        let Gathered {
            counts,
            mut sectors,
            mut loads,
            mut thrust,
            mut release,
            slopes,
            gear,
            mut ground,
        } = Gathered::read(&mut file, terrain.is_some())?;
        let meta = file.metadata();
        let total: u64 = counts.iter().sum();
        if total == 0 {
            bail!("{} holds no samples", path.display());
        }
        let scenario = meta
            .get("touchdown.scenario")
            .and_then(|text| Scenario::from_toml(text).ok());
        // `held` is listed where a lander can be held: in a sweep with a control loop.
        let controlled = thrust.controlled() || counts[Outcome::Held as usize] > 0;
        let terrain = match terrain {
            Some((t, text)) => Some(weigh(source, meta, &slopes, t, text)?),
            None => None,
        };
        let allowable = sectors
            .iter_mut()
            .enumerate()
            .map(|(k, s)| Sector {
                azimuth_deg: (k as f64 * SECTOR_DEG, (k + 1) as f64 * SECTOR_DEG),
                samples: s.len() as u64,
                stable: s.iter().filter(|x| x.1).count() as u64,
                allowable: allowable_slope(s),
            })
            .collect();
        let loads = summaries(&mut loads, &LOADS);
        // Their values are summarised: the memory goes to the exceedance's.
        drop((sectors, slopes));
        let dampers = scenario.as_ref().map(|s| s.damper.enabled);
        let exceedance = crate::exceedance::design_values(&crate::exceedance::gather(
            source,
            dampers == Some(true),
        )?);
        Ok(Report {
            provenance: Provenance {
                sweep: path.to_path_buf(),
                in_memory: matches!(source, SweepSource::Memory { .. }),
                samples: total,
                seed: meta.get("touchdown.seed").cloned(),
                engine: meta.get("touchdown.engine").cloned(),
                dampers,
                interrupted: interrupted(source, meta, total),
            },
            outcomes: Outcome::listed(controlled)
                .map(|o| (o, Share::of(counts[o as usize], total)))
                .collect(),
            stable_within_limits: gear.limits.map(|c| Share::of(c.within, total)),
            gear: gear.section(total, scenario.as_ref()),
            ground: ground.section(),
            terrain,
            allowable,
            loads,
            exceedance,
            thrust: thrust.section(),
            release: release.section(),
        })
    }
}

/// The samples the sweep file `source` asked for and what to say of it, where it holds
/// fewer than that (`total`): an interrupted sweep's rows. A sweep held in memory is whole.
fn interrupted(
    source: &SweepSource,
    meta: &arrow_schema::Metadata,
    total: u64,
) -> Option<(u64, String)> {
    let SweepSource::Path(path) = source else {
        return None;
    };
    let asked = crate::output::sweep::samples_asked(|k| meta.get(k));
    let note = crate::output::sweep::interrupted_note(path, total, asked)?;
    Some((asked?, note))
}

/// The outcome shares of `slopes` (each sample's slope and outcome) weighed onto the
/// terrain `t` given as `text`.
fn weigh(
    source: &SweepSource,
    meta: &arrow_schema::Metadata,
    slopes: &[(f64, Outcome)],
    t: &SlopeDistribution,
    text: &str,
) -> anyhow::Result<Terrain> {
    let path = source.name().display();
    if meta.contains_key(crate::scenario::METADATA_KEYS[1]) {
        bail!(
            "--slope-distribution: {path} cannot be weighed onto a terrain: its slopes come \
             from a table of inputs, not from a distribution"
        );
    }
    let scenario = meta
        .get("touchdown.scenario")
        .ok_or_else(|| anyhow!("{path}: no touchdown.scenario in its metadata"))
        .and_then(|text| {
            Scenario::from_toml(text).map_err(|e| anyhow!("the scenario stored in {path}: {e}"))
        })?;
    let weighted = crate::weighting::weigh(&scenario, slopes, t).map_err(|e| {
        anyhow!("--slope-distribution: {path} cannot be weighed onto this terrain: {e}")
    })?;
    Ok(Terrain {
        text: text.to_string(),
        description: t.describe(),
        weighted,
    })
}
