//! The rows of a sweep read once for the report: outcome counts, each sector's slopes and
//! stable samples, the peak loads, and what the gear, ground, thrust and release sections
//! count.

use super::gear::{Gear, GearColumns};
use super::ground::{Ground, GroundColumns};
use super::numbers::Named;
use super::release::{Release, ReleaseColumns};
use super::thrust::{Thrust, ThrustColumns};
use crate::output::sweep::SweepFile;
use crate::reference::Outcome;
use crate::stats::{SECTORS, relative_azimuth_deg, sector_of};
use arrow_array::Float64Array;

/// The peak loads, in the order of `Gathered::loads`: the acceleration, along `Z_B`, the
/// largest leg's normal force, the longest leg's damper stroke, the energy of all legs.
pub(super) const LOADS: [Named; 5] = [
    ("peak_acceleration_m_s2", "peak CG acceleration", "m/s^2"),
    (
        "peak_acceleration_z_body_m_s2",
        "peak acceleration along Z_B",
        "m/s^2",
    ),
    (
        "peak_normal_force_n",
        "peak leg normal force (largest leg)",
        "N",
    ),
    ("stroke_mm", "damper stroke (longest leg)", "mm"),
    (
        "absorbed_j",
        "energy absorbed by the dampers (all legs)",
        "J",
    ),
];

/// What the report gathers from the rows of a sweep.
pub(super) struct Gathered {
    /// Samples per outcome, in the order of `Outcome::ALL`.
    pub(super) counts: [u64; Outcome::ALL.len()],
    /// Per sector of downhill azimuth relative to the lander: each sample's slope and
    /// whether it stood.
    pub(super) sectors: Vec<Vec<(f64, bool)>>,
    /// Each sample's peak loads (`LOADS`).
    pub(super) loads: [Vec<f64>; LOADS.len()],
    pub(super) thrust: Thrust,
    pub(super) release: Release,
    /// Each sample's slope and outcome, where the report weighs them onto a terrain.
    pub(super) slopes: Vec<(f64, Outcome)>,
    pub(super) gear: Gear,
    pub(super) ground: Ground,
}

impl Gathered {
    /// The rows of `file`, gathered; each sample's slope and outcome kept if `keep_slopes`.
    pub(super) fn read(file: &mut SweepFile, keep_slopes: bool) -> anyhow::Result<Gathered> {
        let legs = file.legs();
        let mut gear = Gear::default();
        let mut ground = Ground::default();
        let mut counts = [0u64; Outcome::ALL.len()];
        let mut sectors: Vec<Vec<(f64, bool)>> = vec![Vec::new(); SECTORS];
        let mut loads: [Vec<f64>; LOADS.len()] = Default::default();
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
            let soil = GroundColumns::of(&b, legs)?;
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
                loads[0].push(acc.value(i));
                loads[1].push(acc_z.value(i));
                loads[2].push(max_of(&force));
                loads[3].push(1e3 * max_of(&stroke));
                loads[4].push(energy.iter().map(|c| c.value(i)).sum());
                if let Some(c) = &control {
                    thrust.push(c, i, o);
                }
                if let Some(r) = &released {
                    release.push(r, i);
                }
                gear.push(&gear_columns, i, o);
                if let Some(c) = &soil {
                    ground.push(c, i);
                }
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
            ground,
        })
    }
}
