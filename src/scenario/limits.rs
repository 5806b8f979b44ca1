//! The `[limits]` table: what the gear team allows a touchdown to do to the lander (issue
//! 30 point 3, MODEL.md section 9), and which of it a sample broke.
//!
//! The decision (`Limits::broken`) lives here, with the data, so that the reference's
//! summary and the sweep's kernels alike can ask for it from the layers above.

use super::damper::Damper;
use super::error::ScenarioError;
use super::reader::table;

table! {
    /// Structural limits, each optional: a sample that goes beyond one broke it.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Limits;
    fn read_limits(r) with key {
        /// Allowable peak axial strut load of any leg, N.
        axial_force_n: Option<f64> = r.given(key, |r| r.positive(key))?,
        /// Allowable peak side load across any strut, N.
        side_force_n: Option<f64> = r.given(key, |r| r.positive(key))?,
        /// Allowable peak CG acceleration (the `peak_acceleration_m_s2` column), m/s^2.
        acceleration_m_s2: Option<f64> = r.given(key, |r| r.positive(key))?,
        /// Least damper stroke margin left at the end in any leg, m (0: no leg may bottom).
        stroke_margin_m: Option<f64> = r.given(key, |r| r.non_negative(key))?,
    }
}

/// The limits, in the order of `limits_broken`: their names and their keys.
pub const LIMIT_NAMES: [(&str, &str); 4] = [
    ("axial_force", "axial_force_n"),
    ("side_force", "side_force_n"),
    ("acceleration", "acceleration_m_s2"),
    ("stroke_margin", "stroke_margin_m"),
];

/// What a sample did against the limits: its largest loads and acceleration, and its least
/// stroke margin (`None` without dampers) and whether a leg bottomed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loads {
    /// The largest peak axial strut load of the legs, N.
    pub axial_force_n: f64,
    /// The largest peak side load of the legs, N.
    pub side_force_n: f64,
    /// The peak CG acceleration, m/s^2.
    pub acceleration_m_s2: f64,
    /// The least stroke margin of the legs at the end, m (`None` without dampers).
    pub stroke_margin_m: Option<f64>,
    /// Whether a leg's damper bottomed.
    pub bottomed: bool,
}

/// A set of broken limits, bit `i` for `LIMIT_NAMES[i]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Broken(pub u8);

impl Broken {
    /// Whether limit `i` (of `LIMIT_NAMES`) is broken.
    #[must_use]
    pub fn has(self, i: usize) -> bool {
        self.0 & (1 << i) != 0
    }

    /// The names of the broken limits in the order of `LIMIT_NAMES`, joined by `,` (empty
    /// when none is broken).
    #[must_use]
    pub fn names(self) -> String {
        let names: Vec<&str> = (0..LIMIT_NAMES.len())
            .filter(|&i| self.has(i))
            .map(|i| LIMIT_NAMES[i].0)
            .collect();
        names.join(",")
    }

    /// The set that `names` (as `names` writes it) names; a name it does not know is
    /// not in it.
    #[must_use]
    pub fn parse(names: &str) -> Broken {
        let bits = LIMIT_NAMES
            .iter()
            .enumerate()
            .filter(|(_, (name, _))| names.split(',').any(|n| n == *name))
            .fold(0, |b, (i, _)| b | (1 << i));
        Broken(bits)
    }
}

impl Limits {
    /// The limits `loads` broke: a load or acceleration above its limit, a stroke margin
    /// below its minimum or a leg bottomed (a bottomed cartridge has no margin left, so it
    /// breaks even a minimum of 0). A NaN breaks nothing.
    #[must_use]
    pub fn broken(&self, loads: &Loads) -> Broken {
        let above = |limit: Option<f64>, x: f64| limit.is_some_and(|l| x > l);
        let short = self.stroke_margin_m.is_some_and(|least| {
            loads.bottomed || loads.stroke_margin_m.is_some_and(|m| m < least)
        });
        let bits = [
            above(self.axial_force_n, loads.axial_force_n),
            above(self.side_force_n, loads.side_force_n),
            above(self.acceleration_m_s2, loads.acceleration_m_s2),
            short,
        ];
        Broken(
            bits.iter()
                .enumerate()
                .fold(0, |b, (i, &x)| b | (u8::from(x) << i)),
        )
    }

    /// Refuses a minimum stroke margin without dampers (there is no stroke to keep), and
    /// one of the whole usable stroke or more, which leaves no stroke to use: every sample
    /// that strokes at all would break it (and beyond the stroke, every sample).
    pub(super) fn check(&self, damper: &Damper) -> Result<(), ScenarioError> {
        let Some(m) = self.stroke_margin_m else {
            return Ok(());
        };
        let refuse = |allowed: String| {
            Err(ScenarioError::Invalid {
                key: "limits.stroke_margin_m".to_string(),
                value: format!("{m} m"),
                allowed,
            })
        };
        if !damper.enabled {
            return refuse(
                "no minimum stroke margin while damper.enabled = false (rigid legs have no \
                 stroke): enable the damper, or leave the key out"
                    .to_string(),
            );
        }
        let stroke_m: f64 = damper.stages.iter().map(|s| s.stroke_m).sum();
        if m >= stroke_m {
            let of = if damper.stages.len() == 1 {
                "damper.usable_stroke_m".to_string()
            } else {
                format!("the {} damper.stages' stroke_m summed", damper.stages.len())
            };
            return refuse(format!(
                "a margin less than the damper's usable stroke, {stroke_m} m ({of}): a margin \
                 of the whole stroke or more leaves none to use, so every sample that strokes \
                 at all would break it"
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::{Broken, Limits, Loads};

    #[test]
    fn broken_limits_are_named_in_order() {
        let limits = Limits {
            axial_force_n: Some(10.0),
            side_force_n: Some(5.0),
            acceleration_m_s2: None,
            stroke_margin_m: Some(0.0),
        };
        let loads = Loads {
            axial_force_n: 10.5,
            side_force_n: 5.0,
            acceleration_m_s2: 1e9,
            stroke_margin_m: Some(0.0),
            bottomed: true,
        };
        assert_eq!(limits.broken(&loads).names(), "axial_force,stroke_margin");
        let within = Loads {
            axial_force_n: 10.0,
            bottomed: false,
            stroke_margin_m: Some(0.01),
            ..loads
        };
        assert_eq!(limits.broken(&within).names(), "");
    }

    #[test]
    fn names_read_back_to_the_set() {
        for bits in 0..16 {
            let b = Broken(bits);
            assert_eq!(Broken::parse(&b.names()), b);
        }
    }
}
