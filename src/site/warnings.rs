//! What a landing-site map warns of, in words that name the likely cause: a body whose
//! size, density or gravity no small body has (a model in kilometres read with `--units
//! m`, a density not in kg/m^3), and samples of the map's sweep that diverged or never
//! touched the ground (a gravity far off, from the density or the units, or a lander made
//! for another gravity). docs/MODEL.md, "Landing sites".

use super::SweepTally;
use crate::shape::G;

/// Densities of small bodies, kg/m^3: from comets (about 500) to metal (about 8,000),
/// with room either side.
pub const DENSITY_RANGE_KG_M3: (f64, f64) = (100.0, 10_000.0);

/// Sizes of the bodies a lander visits, m, as the volume-equivalent diameter: from
/// boulder-sized asteroids (tens of metres) to Ceres (940 km).
pub const DIAMETER_RANGE_M: (f64, f64) = (10.0, 1.0e6);

/// Gravities at the surface of small bodies, m/s^2: from a 10 m rubble pile (about 3e-6)
/// to Ceres (0.28).
pub const GRAVITY_RANGE_M_S2: (f64, f64) = (1.0e-6, 1.0);

/// What the warnings say of the body.
#[derive(Debug, Clone, Copy)]
pub struct BodyFigures<'a> {
    /// The units of the shape file, as given (`m` or `km`).
    pub units: &'a str,
    /// Metres per unit.
    pub metres_per_unit: f64,
    /// The volume, m^3.
    pub volume_m3: f64,
    /// The density, kg/m^3.
    pub density_kg_m3: f64,
}

impl BodyFigures<'_> {
    /// The diameter of a sphere of the body's volume, m.
    #[must_use]
    pub fn diameter_m(&self) -> f64 {
        (6.0 * self.volume_m3 / std::f64::consts::PI).cbrt()
    }

    /// The gravity at the surface of a sphere of the body's volume and density, m/s^2:
    /// `(2/3) pi G rho D`.
    #[must_use]
    pub fn gravity_m_s2(&self) -> f64 {
        2.0 / 3.0 * std::f64::consts::PI * G * self.density_kg_m3 * self.diameter_m()
    }

    /// Where the body's figures come from, for a message.
    fn provenance(&self) -> String {
        format!(
            "--density {} kg/m^3, the shape in --units {}",
            super::given_number(self.density_kg_m3),
            self.units
        )
    }
}

/// The warning for a body whose size, density or gravity lies outside what small bodies
/// have ([`DIAMETER_RANGE_M`], [`DENSITY_RANGE_KG_M3`], [`GRAVITY_RANGE_M_S2`]), naming
/// the flag to check; `None` for a plausible body.
#[must_use]
pub fn implausible_body(b: &BodyFigures<'_>) -> Option<String> {
    let (d, g, rho) = (b.diameter_m(), b.gravity_m_s2(), b.density_kg_m3);
    let mass = rho * b.volume_m3;
    let mut why = Vec::new();
    let other = if b.metres_per_unit == 1.0 { "km" } else { "m" };
    // The size the other unit would give.
    let as_other = d * if other == "km" { 1000.0 } else { 1e-3 };
    if d < DIAMETER_RANGE_M.0 {
        why.push(format!(
            "it is {d:.3e} m across (the diameter of a sphere of its volume), smaller than any \
             body a lander visits: are the coordinates in {other}? (--units {other} makes it \
             {as_other:.4e} m)"
        ));
    } else if d > DIAMETER_RANGE_M.1 {
        why.push(format!(
            "it is {d:.3e} m across (the diameter of a sphere of its volume), larger than any \
             asteroid or comet (Ceres: 9.4e5 m): are the coordinates in {other}? (--units \
             {other} makes it {as_other:.4e} m)"
        ));
    }
    if !(DENSITY_RANGE_KG_M3.0..=DENSITY_RANGE_KG_M3.1).contains(&rho) {
        why.push(format!(
            "--density {} kg/m^3 is no small body's (comets about 500, metal about 8000): \
             is it in kg/m^3?",
            super::given_number(rho)
        ));
    }
    if !(GRAVITY_RANGE_M_S2.0..=GRAVITY_RANGE_M_S2.1).contains(&g) {
        why.push(format!(
            "its gravity, about {g:.3e} m/s^2 at the surface (a mass of {mass:.3e} kg), lies \
             outside any small body's ({:e} to {} m/s^2)",
            GRAVITY_RANGE_M_S2.0, GRAVITY_RANGE_M_S2.1
        ));
    }
    (!why.is_empty()).then(|| {
        format!(
            "implausible for a small body ({}): {}",
            b.provenance(),
            why.join("; ")
        )
    })
}

/// The warnings for samples of the map's sweep that diverged or never touched the ground,
/// each with its likely cause at the body's gravities `gravities` (m/s^2, the least and the
/// greatest of the facets'); none when every sample touched and none diverged. `fall_run`:
/// whether the samples start at their release and fall (else at touchdown, with the speed
/// of the fall).
#[must_use]
pub fn sweep_failures(
    tally: &SweepTally,
    body: &BodyFigures<'_>,
    gravities: (f64, f64),
    (t_max_s, fall_run): (f64, bool),
) -> Vec<String> {
    let share = |k: u64| 100.0 * k as f64 / tally.samples.max(1) as f64;
    let (g_min, g_max) = gravities;
    let mut out = Vec::new();
    if tally.diverged > 0 {
        let cause = if g_max > GRAVITY_RANGE_M_S2.1 {
            format!(
                "the body's gravity, up to {g_max:.3e} m/s^2 ({}), is far beyond any small \
                 body's, and the lander's contact cannot follow it: check --density \
                 (kg/m^3) and --units",
                body.provenance()
            )
        } else {
            format!(
                "at gravities of {g_min:.3e} to {g_max:.3e} m/s^2 ({}): check them, and the \
                 scenario's lander and time step for this gravity",
                body.provenance()
            )
        };
        out.push(format!(
            "{} of the {} samples ({:.2} %) diverged (a non-finite or exploding state: counted \
             in the facets' samples, in none of their shares): {cause}",
            tally.diverged,
            tally.samples,
            share(tally.diverged)
        ));
    }
    if tally.untouched > 0 {
        let mut causes = Vec::new();
        if tally.untouched_steep > 0 {
            // Shown rounded down, so that "or more" holds of the value printed.
            let slope = (tally.untouched_steep_slope_deg * 10.0).floor() / 10.0;
            causes.push(format!(
                "{} turned over in flight, all on slopes of {slope:.1} deg or more, where a \
                 lander released upright already leans that far from the ground's normal",
                tally.untouched_steep
            ));
        }
        let rest = tally.untouched - tally.untouched_steep;
        if rest > 0 {
            let (h, v) = (tally.untouched_release_m, tally.untouched_rising_m_s);
            let rise = format!(
                "an upward velocity error of {v:.3} m/s lifts it for {:.0} s",
                2.0 * v / g_min
            );
            let fall = if fall_run {
                format!(
                    "a lander takes {:.0} s to fall {h:.3} m and {rise}",
                    (2.0 * h / g_min).sqrt()
                )
            } else {
                format!(
                    "a fall of {h:.3} m ends at only {:.3e} m/s, and {rise}",
                    (2.0 * g_min * h).sqrt()
                )
            };
            causes.push(format!(
                "{rest} at the body's gravity, as low as {g_min:.3e} m/s^2 ({}), where {fall} \
                 (the run lasts {t_max_s} s): if that is not the body's gravity, check \
                 --density and --units; if it is, give the scenario a release and a run for \
                 it (inputs.release_height_m, inputs.velocity_error_z_m_s, \
                 simulation.t_max_s)",
                body.provenance(),
            ));
        }
        out.push(format!(
            "{} of the {} samples ({:.2} %) never touched the ground before \
             simulation.t_max_s = {t_max_s} s (counted as bouncing, or tipped where they \
             turned over in flight): {}",
            tally.untouched,
            tally.samples,
            share(tally.untouched),
            causes.join("; ")
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body(units: &str, metres_per_unit: f64, radius_m: f64, density: f64) -> BodyFigures<'_> {
        BodyFigures {
            units,
            metres_per_unit,
            volume_m3: 4.0 / 3.0 * std::f64::consts::PI * radius_m.powi(3),
            density_kg_m3: density,
        }
    }

    #[test]
    fn a_body_s_size_density_and_gravity_are_judged_against_small_bodies() {
        // Didymos (390 m in radius at 2170 kg/m^3): 2.366e-4 m/s^2 by (4/3) pi G rho R.
        let didymos = body("km", 1000.0, 390.0, 2170.0);
        assert!((didymos.gravity_m_s2() / 2.3660e-4 - 1.0).abs() < 1e-4);
        assert_eq!(implausible_body(&didymos), None);
        // Its model in km read as metres: 0.39 m in radius.
        let w = implausible_body(&body("m", 1.0, 0.39, 2170.0)).expect("a warning");
        assert!(
            w.contains("7.800e-1 m across") && w.contains("--units km"),
            "{w}"
        );
        assert!(w.contains("its gravity, about 2.366e-7"), "{w}");
        // A density of 1e12 kg/m^3 names the density.
        let w = implausible_body(&body("km", 1000.0, 390.0, 1e12)).expect("a warning");
        assert!(
            w.contains("--density 1000000000000 kg/m^3 is no small body's"),
            "{w}"
        );
        // Metres read as kilometres, a body larger than Ceres.
        let w = implausible_body(&body("km", 1000.0, 2.0e6, 2000.0)).expect("a warning");
        assert!(
            w.contains("larger than any asteroid") && w.contains("--units m"),
            "{w}"
        );
    }
}
