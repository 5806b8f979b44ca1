//! Reading a scenario from TOML and refusing what cannot run: every key checked as it is
//! read (`reader`), then the checks across tables (a lander that cannot stand, a design
//! without random inputs, a run too short to land). The editing of a scenario's text for
//! the provenance of a file (`with_seed`, `with_design`) is here too.

use super::damper::StrutAxes;
use super::definition::{Design, Scenario, read_scenario};
use super::draws::{design_inputs, value_dists};
use super::error::ScenarioError;
use super::initial::Start;
use super::inputs::{Dist, FALL_INPUTS, Parameter, value_key};
use super::lander::Geometry;
use super::reader::Reader;

impl Default for Scenario {
    /// The default scenario: default.toml, the scenario of an empty file.
    fn default() -> Self {
        Scenario::from_toml("").expect("the default scenario is valid")
    }
}

/// The scenario text `text` with its top-level `seed` set to `seed` (replaced where the text
/// has one, added before its first key where not), so that a file stores the scenario that
/// ran, seed included. Comments and layout stay. The text must read as a scenario.
#[must_use]
pub fn with_seed(text: &str, seed: u64) -> String {
    if Scenario::from_toml(text).is_ok_and(|s| s.seed == seed) {
        return text.to_string();
    }
    with_top_level(text, "seed", &seed.to_string())
}

/// The scenario text `text` with its top-level `design` set to `design` (as `with_seed`).
#[must_use]
pub fn with_design(text: &str, design: Design) -> String {
    if Scenario::from_toml(text).is_ok_and(|s| s.design == design) {
        return text.to_string();
    }
    with_top_level(text, "design", &design.toml())
}

/// `text` with the top-level line `key = value`, in place of the one it has or before its
/// first key.
fn with_top_level(text: &str, key: &str, value: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let top_level = lines
        .iter()
        .position(|l| l.trim_start().starts_with('['))
        .unwrap_or(lines.len());
    let is_key = |l: &str| {
        l.trim_start()
            .strip_prefix(key)
            .is_some_and(|rest| rest.trim_start().starts_with('='))
    };
    let line = format!("{key} = {value}");
    let mut out: Vec<String> = lines.iter().map(ToString::to_string).collect();
    match lines[..top_level].iter().position(|l| is_key(l)) {
        Some(i) => out[i] = line,
        None => {
            let first_key = lines
                .iter()
                .position(|l| {
                    let t = l.trim();
                    !t.is_empty() && !t.starts_with('#')
                })
                .unwrap_or(lines.len());
            out.insert(first_key, line);
        }
    }
    let mut edited = out.join("\n");
    if text.ends_with('\n') {
        edited.push('\n');
    }
    edited
}

impl Scenario {
    /// Reads a scenario file.
    pub fn from_file(path: &std::path::Path) -> Result<Scenario, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|e| ScenarioError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Scenario::from_toml(&text)
    }

    /// Reads and validates a scenario from TOML text; missing keys take their defaults.
    pub fn from_toml(text: &str) -> Result<Scenario, ScenarioError> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            ScenarioError::Syntax(e.to_string().trim().to_string())
        })?;
        let s = read_scenario(&mut Reader::top(table))?;
        s.check_leg_counts()?;
        s.check_can_land()?;
        s.check_design()?;
        s.check_sampled()?;
        if let Some(limits) = &s.limits {
            limits.check(&s.damper)?;
        }
        s.check_touchdown_state()?;
        s.check_regolith()?;
        Ok(s)
    }

    /// Refuses a design that cannot run: the Sobol-index design needs inputs drawn at random
    /// (fixed ones carry no variance to share out) and no grid (a grid is not random).
    fn check_design(&self) -> Result<(), ScenarioError> {
        if self.design == Design::Independent {
            return Ok(());
        }
        let word = self.design.toml();
        let invalid = |value: String, allowed: &str| ScenarioError::Invalid {
            key: "design".to_string(),
            value,
            allowed: allowed.to_string(),
        };
        let dists = value_dists(self);
        if let Some(k) = (0..dists.len()).find(|&k| matches!(dists[k], Dist::Grid { .. })) {
            let key = value_key(k);
            return Err(invalid(
                word,
                &format!(
                    "inputs, parameters and control law parameters drawn at random: {key} \
                     is a grid (give it a uniform distribution over the same range)"
                ),
            ));
        }
        // The quasi-random design gives every value drawn from a distribution a dimension
        // of the Sobol sequence, of which `qmc` has direction numbers for so many.
        let drawn = design_inputs(self).len();
        if self.design == Design::SobolSequence && drawn > crate::qmc::MAX_DIMENSIONS {
            return Err(invalid(
                word,
                &format!(
                    "at most {} values drawn from a distribution ({drawn} are): fix some, \
                     or use design = \"independent\"",
                    crate::qmc::MAX_DIMENSIONS
                ),
            ));
        }
        if self.design == Design::SobolIndices && design_inputs(self).is_empty() {
            return Err(invalid(
                word,
                "at least one input drawn from a distribution (every input is fixed: there \
                 is no variance to share out)",
            ));
        }
        Ok(())
    }

    /// Refuses parameters drawn per sample where the model cannot take them per sample: a
    /// crush strength without a damper, and the mass or CG height of a lander with a control
    /// loop (its thrust limits and descent are planned for one lander).
    fn check_sampled(&self) -> Result<(), ScenarioError> {
        let refuse = |p: Parameter, why: &str| {
            let dist = self.sampled[p as usize].expect("a sampled parameter");
            Err(ScenarioError::Invalid {
                key: p.key().to_string(),
                value: dist.toml(),
                allowed: why.to_string(),
            })
        };
        if self.sampled[Parameter::CrushStrengthPsi as usize].is_some() && !self.damper.enabled {
            return refuse(
                Parameter::CrushStrengthPsi,
                "a number while damper.enabled = false (no cartridge to crush): enable the \
                 damper to draw its crush strength per sample",
            );
        }
        if self.control.is_some() {
            for p in [
                Parameter::MassKg,
                Parameter::CgHeightM,
                Parameter::GravityMS2,
            ] {
                if self.sampled[p as usize].is_some() {
                    return refuse(
                        p,
                        "a number in a scenario with a control loop (its thrust limits and \
                         descent are planned for one lander; not yet drawn per sample)",
                    );
                }
            }
        }
        Ok(())
    }
}

impl Scenario {
    /// Refuses a soil that cannot bear or has no passive pressure: Bekker's two moduli
    /// both 0 (nothing holds a footpad up), or a friction angle of 90 deg or more (Rankine's
    /// `K_p` is infinite), in any sample.
    fn check_regolith(&self) -> Result<(), ScenarioError> {
        if self.surface.regolith.is_none() {
            return Ok(());
        }
        let range = |p: Parameter| {
            self.sampled[p as usize].map_or((self.parameter(p), self.parameter(p)), |d| d.support())
        };
        let invalid = |key: &str, value: f64, allowed: &str| ScenarioError::Invalid {
            key: format!("surface.regolith.{key}"),
            value: value.to_string(),
            allowed: allowed.to_string(),
        };
        let phi = range(Parameter::FrictionAngleDeg).1;
        if phi >= 90.0 {
            return Err(invalid("friction_angle_deg", phi, "an angle below 90 deg"));
        }
        let (k_c, k_phi) = (range(Parameter::BekkerKC).0, range(Parameter::BekkerKPhi).0);
        if k_c <= 0.0 && k_phi <= 0.0 {
            return Err(invalid(
                "bekker_k_phi",
                k_phi,
                "a soil that bears: bekker_k_c or bekker_k_phi greater than 0 in every sample",
            ));
        }
        Ok(())
    }

    /// Refuses a touchdown state given (`Start::State`) beside a fall or velocity errors:
    /// the state replaces them, so `release_height_m` and `velocity_error_*` must be 0.
    fn check_touchdown_state(&self) -> Result<(), ScenarioError> {
        if self.initial.start != Start::State {
            return Ok(());
        }
        let inputs = self.inputs.to_array();
        for k in FALL_INPUTS {
            if inputs[k] != Dist::Fixed(0.0) {
                return Err(invalid(
                    &value_key(k),
                    inputs[k].toml(),
                    "0 with the touchdown state given in [initial] (initial.normal_speed_m_s): \
                     the state replaces the fall and the velocity errors, so fix \
                     inputs.release_height_m and inputs.velocity_error_x_m_s, _y_m_s and _z_m_s \
                     at 0"
                        .into(),
                ));
            }
        }
        Ok(())
    }
}

/// An invalid value of `key`.
fn invalid(key: &str, value: String, allowed: String) -> ScenarioError {
    ScenarioError::Invalid {
        key: key.to_string(),
        value,
        allowed,
    }
}

/// A vector as the messages show it, `[x, y, z]`.
fn show(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", v[0], v[1], v[2])
}

impl Scenario {
    /// Refuses set-ups that defeat themselves: a lander that cannot stand on its legs, dampers
    /// that can never stroke, a hold time no run can reach, no gravity, or a run too short
    /// for the lander to reach the surface.
    fn check_can_land(&self) -> Result<(), ScenarioError> {
        self.check_can_stand()?;
        self.check_dampers_stroke()?;
        self.check_can_reach()
    }

    /// Refuses footpads at or above the CG, fewer than three off one line, or around a CG
    /// outside their support polygon.
    fn check_can_stand(&self) -> Result<(), ScenarioError> {
        let tips = self.lander.tips_m();
        let tips_key = match self.lander.geometry {
            Geometry::Regular { .. } => "lander.cg_height_m",
            Geometry::Tips(_) => "lander.leg_tips_m",
        };
        if let Some((k, t)) = tips.iter().enumerate().find(|(_, t)| t[2] >= 0.0) {
            return Err(invalid(
                tips_key,
                format!("footpad {k} at {}", show(*t)),
                "every footpad below the CG (z < 0 in B, the CG at the origin): a lander \
                 cannot stand on footpads at or above its CG"
                    .into(),
            ));
        }
        let hull = crate::stability::support_polygon(&tips);
        let area: f64 = (0..hull.len())
            .map(|i| {
                let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
                0.5 * (a[0] * b[1] - a[1] * b[0])
            })
            .sum();
        let size = tips.iter().map(|t| t[0].hypot(t[1])).fold(0.0, f64::max);
        if hull.len() < 3 || area <= 1e-9 * size * size {
            return Err(invalid(
                tips_key,
                format!("{} footpads", tips.len()),
                "at least three footpads not on one line (seen along Z_B): otherwise the \
                 support polygon has no area and the lander cannot stand"
                    .into(),
            ));
        }
        if crate::stability::static_limit_deg(&tips, 0.0).is_none() {
            return Err(invalid(
                tips_key,
                format!("{} footpads", tips.len()),
                "footpads around the CG: the CG (the origin of B) must be above the inside of \
                 their support polygon, or the lander falls over even on level ground"
                    .into(),
            ));
        }
        Ok(())
    }

    /// Refuses damper struts that do not point down (they would never stroke).
    fn check_dampers_stroke(&self) -> Result<(), ScenarioError> {
        if self.damper.enabled {
            let axes: Vec<[f64; 3]> = match &self.damper.strut_axes {
                StrutAxes::All(a) => vec![*a],
                StrutAxes::PerLeg(a) => a.clone(),
            };
            let limit = -kernels::honeycomb::MIN_STRUT_NORMAL;
            if let Some(a) = axes.iter().find(|a| a[2] >= limit) {
                return Err(invalid(
                    "damper.strut_axis",
                    show(*a),
                    format!(
                        "struts that point down, from the hip to the footpad (Z component \
                         below {limit} in B): along this one the load of a lander standing on \
                         its legs never compresses the cartridge, so the dampers would never \
                         stroke"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Refuses a hold time longer than the run, no gravity, and a run too short for the
    /// nominal touchdown to reach the surface.
    fn check_can_reach(&self) -> Result<(), ScenarioError> {
        if self.outcome.hold_time_s > self.simulation.t_max_s {
            return Err(invalid(
                "outcome.hold_time_s",
                format!("{} s", self.outcome.hold_time_s),
                format!(
                    "at most simulation.t_max_s = {} s: no lander can be held at rest longer \
                     than the run lasts, so none could be stable",
                    self.simulation.t_max_s
                ),
            ));
        }
        // A drawn gravity: its least value (the slowest fall) must be above 0 too.
        let drawn_gravity = self.sampled[Parameter::GravityMS2 as usize];
        let gravity = drawn_gravity.map_or(self.gravity_m_s2, |d| d.support().0);
        if gravity <= 0.0 {
            return Err(invalid(
                "gravity_m_s2",
                drawn_gravity.map_or_else(|| self.gravity_m_s2.to_string(), |d| d.toml()),
                "a gravity greater than 0: without it no lander comes to rest on its legs or \
                 tips over (the default is 0.0168 m/s^2)"
                    .into(),
            ));
        }
        // The nominal touchdown (the highest release, no velocity error) must reach the
        // surface from its starting gap before t_max: else (nearly) no sample ever touches.
        let height = self.inputs.release_height_m.support().1;
        let (v, gap) = match self.initial.start {
            Start::State => (
                self.initial.touchdown.map_or(0.0, |t| t[0].support().1),
                self.initial.clearance_m,
            ),
            Start::Touchdown => ((2.0 * gravity * height).sqrt(), self.initial.clearance_m),
            Start::Release => (0.0, height + self.initial.clearance_m),
            // Unbraked from the descent's start: a bound (the law brakes, then releases),
            // enough to refuse a run that could not land even so.
            Start::Descent => {
                self.control
                    .as_ref()
                    .and_then(|c| c.descent)
                    .map_or((0.0, 0.0), |d| {
                        (
                            d.start_speed_m_s.support().0,
                            d.start_altitude_m.support().1 + self.initial.clearance_m,
                        )
                    })
            }
        };
        let reach_s = 2.0 * gap / (v + (v * v + 2.0 * gravity * gap).sqrt());
        if reach_s > self.simulation.t_max_s {
            return Err(invalid(
                "simulation.t_max_s",
                format!("{} s", self.simulation.t_max_s),
                format!(
                    "a run long enough to reach the surface: {from} in gravity_m_s2 = {g} \
                     m/s^2 the lander needs {reach_s:.3e} s, so no sample would ever touch it",
                    from = match self.initial.start {
                        Start::State => format!(
                            "from initial.clearance_m = {gap} m at {v:.4} m/s (the largest \
                             initial.normal_speed_m_s)"
                        ),
                        Start::Touchdown => format!(
                            "from initial.clearance_m = {gap} m at {v:.4} m/s (released from \
                             inputs.release_height_m up to {height} m)"
                        ),
                        Start::Release => format!(
                            "released at rest (initial.start = \"release\") from \
                             inputs.release_height_m up to {height} m above initial.clearance_m \
                             = {} m",
                            self.initial.clearance_m
                        ),
                        Start::Descent => format!(
                            "even unbraked, from control.descent.start_altitude_m above \
                             initial.clearance_m ({gap} m) at control.descent.start_speed_m_s \
                             = {v} m/s"
                        ),
                    },
                    g = gravity
                ),
            ));
        }
        Ok(())
    }

    fn check_leg_counts(&self) -> Result<(), ScenarioError> {
        if let StrutAxes::PerLeg(axes) = &self.damper.strut_axes
            && axes.len() != self.leg_count()
        {
            return Err(ScenarioError::Invalid {
                key: "damper.strut_axis".into(),
                value: format!("{} axes", axes.len()),
                allowed: format!(
                    "one axis for all legs or one per leg ({} legs)",
                    self.leg_count()
                ),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::reader::DEFAULT_TOML;
    use super::*;

    #[test]
    fn default_file_is_the_default_scenario() {
        assert_eq!(
            Scenario::from_toml(DEFAULT_TOML).unwrap(),
            Scenario::default()
        );
    }

    #[test]
    fn empty_file_is_the_default_scenario() {
        assert_eq!(Scenario::from_toml("").unwrap(), Scenario::default());
    }

    #[test]
    fn the_stored_text_carries_the_seed_that_ran() {
        let with = |text: &str, seed| {
            let edited = with_seed(text, seed);
            let s = Scenario::from_toml(&edited).unwrap();
            let mut expected = Scenario::from_toml(text).unwrap();
            expected.seed = seed;
            assert_eq!(s, expected, "{edited}");
            edited
        };
        // Replaced in place, comments kept.
        let text = "# study\nseed = 1   # the seed\nsamples = 10\n[lander]\nmass_kg = 90.0\n";
        assert_eq!(
            with(text, 7),
            "# study\nseed = 7\nsamples = 10\n[lander]\nmass_kg = 90.0\n"
        );
        // Added before the first key (a table header here), after the opening comments.
        let text = "# study\n\n[lander]\nmass_kg = 90.0\n";
        assert_eq!(
            with(text, 7),
            "# study\n\nseed = 7\n[lander]\nmass_kg = 90.0\n"
        );
        // A `seed` key inside a table is not the scenario's seed; unchanged when it agrees.
        let text = "[lander]\nmass_kg = 90.0\n";
        assert!(with(text, 3).starts_with("seed = 3\n"));
        assert_eq!(with(DEFAULT_TOML, 1), DEFAULT_TOML);
        let default = with(DEFAULT_TOML, 42);
        assert!(default.contains("\nseed = 42\n") && !default.contains("\nseed = 1\n"));
    }

    #[test]
    fn distributions_parse() {
        let s = Scenario::from_toml(
            r#"[inputs]
            slope_deg = { dist = "grid", min = 0, max = 40, count = 5 }
            roll_deg = { dist = "normal", mean = 0.0, sd = 2.0, min = -5.0, max = 5.0 }
            yaw_deg = 30
            pitch_deg = { dist = "fixed", value = 1.5 }"#,
        )
        .unwrap();
        assert_eq!(
            s.inputs.slope_deg,
            Dist::Grid {
                min: 0.0,
                max: 40.0,
                count: 5
            }
        );
        assert_eq!(s.inputs.yaw_deg, Dist::Fixed(30.0));
        assert_eq!(s.inputs.pitch_deg, Dist::Fixed(1.5));
        assert!(matches!(s.inputs.roll_deg, Dist::Normal { min, .. } if min == -5.0));
    }
}
