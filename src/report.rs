//! `touchdown report`: what a sweep file says, for people. Outcome counts with 95 %
//! confidence intervals, the allowable slope per sector of downhill azimuth relative to the
//! lander, the peak loads, (with thrusters) the propellant and firings, and (with a
//! descent) the state the descent released the lander in; with dampers or `[limits]`, the
//! samples that bottomed a damper or broke a limit (`gear`). Markdown, so that it reads on a
//! terminal and pastes into a design note.

use crate::output::sweep::{SweepBatch, SweepFile};
use crate::reference::Outcome;
use crate::stats::{
    ALLOWABLE_STABLE, MIN_SAMPLES, SECTOR_DEG, SECTORS, allowable_slope, quantile,
    relative_azimuth_deg, sector_of, wilson_interval,
};
use anyhow::{anyhow, bail};
use arrow_array::{Float64Array, UInt32Array};
use gear::{Gear, GearColumns};
use std::fmt::Write as _;
use std::path::Path;

mod gear;

/// A load column gathered over the file.
struct Load {
    name: &'static str,
    unit: &'static str,
    values: Vec<f64>,
}

/// What the report gathers from the rows of a sweep file.
struct Gathered {
    /// Samples per outcome, in the order of `Outcome::ALL`.
    counts: [u64; Outcome::ALL.len()],
    /// Per sector of downhill azimuth relative to the lander: each sample's slope and
    /// whether it stood.
    sectors: Vec<Vec<(f64, bool)>>,
    loads: [Load; 5],
    thrust: Thrust,
    release: Release,
    /// Each sample's slope and outcome, where the report weighs them onto a terrain.
    slopes: Vec<(f64, Outcome)>,
    gear: Gear,
}

impl Gathered {
    /// The rows of `file`, gathered; each sample's slope and outcome kept if `keep_slopes`.
    fn read(file: &mut SweepFile, keep_slopes: bool) -> anyhow::Result<Gathered> {
        let legs = file.legs();
        let mut gear = Gear::default();
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
        let mut release = Release::default();
        let mut slopes: Vec<(f64, Outcome)> = Vec::new();
        for b in file.batches() {
            let b = b?;
            let f = |name: &str| b.f64s(name);
            let control = ThrustColumns::of(&b)?;
            let released = ReleaseColumns::of(&b)?;
            let outcomes = b.outcomes()?;
            let gear_columns = GearColumns::of(&b)?;
            let (slope, azimuth, yaw) =
                (f("slope_deg")?, f("downhill_azimuth_deg")?, f("yaw_deg")?);
            let (acc, acc_z) = (
                f("peak_acceleration_m_s2")?,
                f("peak_acceleration_z_body_m_s2")?,
            );
            let (force, stroke, energy) = (
                b.per_leg(legs, "peak_normal_force_n")?,
                b.per_leg(legs, "stroke_m")?,
                b.per_leg(legs, "absorbed_j")?,
            );
            for (i, &o) in outcomes.iter().enumerate() {
                counts[o as usize] += 1;
                if keep_slopes {
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
                if let Some(r) = &released {
                    release.push(r, i);
                }
                gear.push(&gear_columns, i, o);
            }
        }
        Ok(Gathered {
            counts,
            sectors,
            loads,
            thrust,
            release,
            slopes,
            gear,
        })
    }
}

/// The report of the sweep file at `path`, as Markdown.
/// With `terrain` (a `--slope-distribution` and its text), the outcome shares on that
/// terrain follow the sweep's own (`weighting`).
pub fn report(
    path: &Path,
    terrain: Option<(&crate::weighting::SlopeDistribution, &str)>,
) -> anyhow::Result<String> {
    let mut file = SweepFile::open(path)?;
    let Gathered {
        counts,
        mut sectors,
        mut loads,
        mut thrust,
        mut release,
        slopes,
        gear,
    } = Gathered::read(&mut file, terrain.is_some())?;
    let meta = file.metadata();
    let total: u64 = counts.iter().sum();
    if total == 0 {
        bail!("{} holds no samples", path.display());
    }

    // `held` is listed where a lander can be held: in a sweep with a control loop.
    let controlled = thrust.controlled() || counts[Outcome::Held as usize] > 0;
    let mut t = String::new();
    write_outcomes(&mut t, path, meta, &counts, total, controlled, &gear);
    let scenario = meta
        .get("touchdown.scenario")
        .and_then(|text| crate::scenario::Scenario::from_toml(text).ok());
    gear.write(&mut t, total, scenario.as_ref());
    if let Some((terrain, text)) = terrain {
        write_terrain(&mut t, path, meta, &slopes, terrain, text)?;
    }
    write_allowable(&mut t, &mut sectors);
    write_loads(&mut t, &mut loads);
    // Their values are written: the memory goes to the exceedance's.
    drop((sectors, loads, slopes));
    t.push_str(&crate::exceedance::markdown(&crate::exceedance::gather(
        path,
        dampers(meta) == Some(true),
    )?));
    thrust.write(&mut t);
    release.write(&mut t);
    write_end(&mut t, path, meta);
    Ok(t)
}

/// The title, the samples and the outcome shares with their intervals (of every outcome
/// but `held` in a sweep without a control loop, `controlled` false).
fn write_outcomes(
    t: &mut String,
    path: &Path,
    meta: &arrow_schema::Metadata,
    counts: &[u64; Outcome::ALL.len()],
    total: u64,
    controlled: bool,
    gear: &Gear,
) {
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
    for o in Outcome::listed(controlled) {
        share_row(t, o.name(), counts[o as usize], total);
        if let (Outcome::Stable, Some((within, _))) = (o, gear.limits) {
            share_row(t, "stable within limits", within, total);
        }
    }
}

/// A row of samples: `k` of `total`, their share and its 95 % Wilson interval.
fn share_row(t: &mut String, name: &str, k: u64, total: u64) {
    let (lo, hi) = wilson_interval(k, total);
    let _ = writeln!(
        t,
        "| {name} | {k} | {:.2} % | {:.2} – {:.2} % |",
        100.0 * k as f64 / total as f64,
        100.0 * lo,
        100.0 * hi
    );
}

/// The outcome shares weighed onto the terrain of a `--slope-distribution`.
fn write_terrain(
    t: &mut String,
    path: &Path,
    meta: &arrow_schema::Metadata,
    slopes: &[(f64, Outcome)],
    terrain: &crate::weighting::SlopeDistribution,
    text: &str,
) -> anyhow::Result<()> {
    if meta.contains_key(crate::scenario::METADATA_KEYS[1]) {
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
    let w = crate::weighting::weigh(&scenario, slopes, terrain).map_err(|e| {
        anyhow!(
            "--slope-distribution: {} cannot be weighed onto this terrain: {e}",
            path.display()
        )
    })?;
    let _ = write!(t, "\n{}", crate::weighting::markdown(&w, terrain, text));
    Ok(())
}

/// The allowable slope per sector of relative azimuth.
fn write_allowable(t: &mut String, sectors: &mut [Vec<(f64, bool)>]) {
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
}

/// The peak loads: mean, 99th percentile and largest.
fn write_loads(t: &mut String, loads: &mut [Load]) {
    let _ = writeln!(
        t,
        "\n## Peak loads\n\n| quantity | mean | 99th percentile | largest |\n|---|---:|---:|---:|"
    );
    for l in loads {
        let mean = l.values.iter().sum::<f64>() / l.values.len().max(1) as f64;
        let p99 = quantile(&mut l.values, 0.99);
        let max = l.values.last().copied().unwrap_or(0.0);
        let _ = writeln!(
            t,
            "| {} ({}) | {mean:.4} | {p99:.4} | {max:.4} |",
            l.name, l.unit
        );
    }
}

/// Whether the scenario stored in the file's metadata has its dampers on (`None` where it
/// does not read).
fn dampers(meta: &arrow_schema::Metadata) -> Option<bool> {
    meta.get("touchdown.scenario")
        .and_then(|text| crate::scenario::Scenario::from_toml(text).ok())
        .map(|s| s.damper.enabled)
}

/// The note on dampers that are off, and how to see one sample in detail.
fn write_end(t: &mut String, path: &Path, meta: &arrow_schema::Metadata) {
    if dampers(meta) == Some(false) {
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
    fn of(b: &'a SweepBatch<'_>) -> anyhow::Result<Option<ThrustColumns<'a>>> {
        if !b.has("propellant_kg") {
            return Ok(None);
        }
        let firings = b.u32s("firings")?;
        Ok(Some(ThrustColumns {
            propellant_kg: b.f64s("propellant_kg")?,
            on_time_s: b.f64s("thrust_on_time_s")?,
            firings,
            hold_down_impulse_n_s: b.f64s("hold_down_impulse_n_s")?,
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

    /// Whether the sweep has a control loop (its rows carry propellant).
    fn controlled(&self) -> bool {
        !self.values[0].is_empty()
    }

    /// The section of the report (nothing for a sweep without a control loop).
    fn write(&mut self, t: &mut String) {
        if !self.controlled() {
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

/// The release columns of a batch of a sweep with a descent.
struct ReleaseColumns<'a> {
    time_s: &'a Float64Array,
    altitude_m: &'a Float64Array,
    velocity_m_s: [&'a Float64Array; 3],
}

impl<'a> ReleaseColumns<'a> {
    /// The columns of `b`, or `None` in a sweep without a descent (no `release_time_s`).
    fn of(b: &'a SweepBatch<'_>) -> anyhow::Result<Option<ReleaseColumns<'a>>> {
        if !b.has("release_time_s") {
            return Ok(None);
        }
        Ok(Some(ReleaseColumns {
            time_s: b.f64s("release_time_s")?,
            altitude_m: b.f64s("release_altitude_m")?,
            velocity_m_s: [
                b.f64s("release_vx_m_s")?,
                b.f64s("release_vy_m_s")?,
                b.f64s("release_vz_m_s")?,
            ],
        }))
    }
}

/// The state a descent released its landers in, over a sweep with one: time, footpad
/// height, and the velocity down and along the ground.
#[derive(Default)]
struct Release {
    /// Samples of a sweep with a descent.
    samples: u64,
    /// Of the released samples: release time (s), footpad height (m), vertical velocity
    /// (m/s, up positive), horizontal speed (m/s).
    values: [Vec<f64>; 4],
}

impl Release {
    fn push(&mut self, c: &ReleaseColumns<'_>, i: usize) {
        self.samples += 1;
        let time = c.time_s.value(i);
        // NaN: contact came before the release.
        if time.is_nan() {
            return;
        }
        let [vx, vy, vz] = c.velocity_m_s.map(|v| v.value(i));
        for (v, x) in self
            .values
            .iter_mut()
            .zip([time, c.altitude_m.value(i), vz, vx.hypot(vy)])
        {
            v.push(x);
        }
    }

    /// The section of the report (nothing for a sweep without a descent).
    fn write(&mut self, t: &mut String) {
        if self.samples == 0 {
            return;
        }
        let released = self.values[0].len();
        let first = self.samples - released as u64;
        let _ = write!(
            t,
            "\n## Release of the descent\n\n{released} of {} samples released by the descent \
             law",
            self.samples
        );
        if first > 0 {
            let _ = write!(
                t,
                "; in the other {first} contact came first (`release_time_s` NaN)"
            );
        }
        let _ = writeln!(
            t,
            ". Of the released (the `release_*` columns; velocity in I):\n\n\
             | quantity | mean | smallest | median | 99th percentile | largest |\n\
             |---|---:|---:|---:|---:|---:|"
        );
        if released == 0 {
            return;
        }
        for (v, (name, unit)) in self.values.iter_mut().zip([
            ("release time", "s"),
            ("footpad height at release", "m"),
            ("vertical velocity at release, up", "m/s"),
            ("horizontal speed at release", "m/s"),
        ]) {
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let median = quantile(v, 0.5);
            let p99 = quantile(v, 0.99);
            let (min, max) = (v[0], v[v.len() - 1]);
            let _ = writeln!(
                t,
                "| {name} ({unit}) | {mean:.4} | {min:.4} | {median:.4} | {p99:.4} | {max:.4} |"
            );
        }
    }
}
