//! Landers and samples made by hand for the closed-form tests (`validation`, `thrust`).

use touchdown::scenario::Sample;
use touchdown::scenario::{AttitudeReference, Geometry, Inputs, Scenario};

/// Inputs with every value zero: level ground, no fall, no errors, no rates.
pub(crate) fn quiet() -> Inputs<f64> {
    Inputs::from_array([0.0; 12])
}

/// A hand-made sample on a flat surface (the parameters, which no scenario of these tests
/// draws, at the default scenario's values).
pub(crate) fn sample_of(inputs: Inputs<f64>) -> Sample {
    let default = Scenario::default();
    Sample {
        index: 0,
        seed: 0,
        inputs,
        parameters: touchdown::scenario::Parameter::ALL.map(|p| default.parameter(p)),
        terrain_tile: 0,
        terrain_offset_m: [0.0; 2],
        rock_tile: 0,
        rock_offset_m: [0.0; 2],
        law: [0.0; touchdown::scenario::LAW_PARAMETERS],
        touchdown: [0.0; touchdown::scenario::STATE_VALUES],
    }
}

/// A hand-made sample of `scenario`: `sample_of`, with the control laws' parameters at the
/// scenario's numbers (0 for a law it has not; no scenario of these tests draws them).
pub(crate) fn sample_in(scenario: &Scenario, inputs: Inputs<f64>) -> Sample {
    Sample {
        law: touchdown::sampling::sample(scenario, 0).law,
        ..sample_of(inputs)
    }
}

/// A lander standing on a slope: aligned with the surface, lowest footpad on it, at rest.
pub(crate) fn standing(geometry: Geometry, friction: f64) -> Scenario {
    let mut s = Scenario::default();
    s.lander.geometry = geometry;
    s.surface.friction_coefficient = friction;
    s.initial.attitude_reference = AttitudeReference::Surface;
    s.initial.clearance_m = 0.0;
    s
}

/// A regular gear with the default CG height.
pub(crate) fn regular(legs: usize, footpad_radius_m: f64, first_leg_azimuth_deg: f64) -> Geometry {
    Geometry::Regular {
        legs,
        footpad_radius_m,
        cg_height_m: CG_HEIGHT_M,
        first_leg_azimuth_deg,
    }
}

/// CG height of the default gear above its footpad plane, m (MODEL.md section 3).
pub(crate) const CG_HEIGHT_M: f64 = 0.428936;

/// Which part of the gear faces downhill.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Facing {
    Side,
    Leg,
    Between,
}

impl Facing {
    /// Downhill azimuth for a gear whose first leg is at `first_leg_deg`, deg.
    pub(crate) fn azimuth_deg(self, legs: usize, first_leg_deg: f64) -> f64 {
        let sector = 360.0 / legs as f64;
        first_leg_deg
            + match self {
                Facing::Leg => 0.0,
                Facing::Side => sector / 2.0,
                Facing::Between => sector / 4.0,
            }
    }
}

/// Time a lander has to fall over once past the limit: its tilt grows like exp(t/tau),
/// tau = sqrt(I_edge / (m g L)) ~ 8 s for these gears, from ~0.01 rad to past 90 deg.
pub(crate) const FALL_WITHIN_S: f64 = 400.0;

/// The slope at which `falls_at(slope)` turns from false to true, bracketed by bisection to
/// 1/64 deg between `stays` and `falls` (which must bracket it), deg.
pub(crate) fn tipping_slope_between(
    stays: f64,
    falls: f64,
    mut falls_at: impl FnMut(f64) -> bool,
) -> f64 {
    let (mut stays, mut falls) = (stays, falls);
    while falls - stays > 1.0 / 64.0 {
        let mid = 0.5 * (stays + falls);
        if falls_at(mid) {
            falls = mid;
        } else {
            stays = mid;
        }
    }
    0.5 * (stays + falls)
}

/// Inputs of a slope with its downhill azimuth, nothing else.
pub(crate) fn on_slope(slope_deg: f64, downhill_azimuth_deg: f64) -> Inputs<f64> {
    Inputs {
        slope_deg,
        downhill_azimuth_deg,
        ..quiet()
    }
}
