//! The `[initial]` table: the initial state besides the sampled inputs.

use super::error::ScenarioError;
use super::reader::Reader;

/// Against what the attitude errors and the fall velocity are taken (MODEL.md section 8).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AttitudeReference {
    /// `Z_B` up along `Z_I`: on a slope the lander meets the surface tilted.
    Vertical,
    /// `Z_B` along the surface normal: a lander that aligned itself before release.
    Surface,
}

/// Where a sample starts (MODEL.md section 8).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// At the end of the free fall, the fall not stepped: its velocity comes from the
    /// release height.
    Touchdown,
    /// At the release, `release_height_m` above the touchdown point, the fall stepped (a
    /// control loop acts during it).
    Release,
    /// Descending under power from `[control.descent]`'s start altitude: the descent law
    /// brakes the lander and releases it at `release_height_m`.
    Descent,
}

/// The initial state besides the sampled inputs.
#[derive(Debug, Clone, PartialEq)]
pub struct Initial {
    pub attitude_reference: AttitudeReference,
    /// Height of the lowest footpad above the surface at touchdown, m.
    pub clearance_m: f64,
    pub start: Start,
}

pub(super) fn read_initial(top: &mut Reader, d: &Initial) -> Result<Initial, ScenarioError> {
    let Some(mut r) = top.table("initial")? else {
        return Ok(d.clone());
    };
    let reference = match d.attitude_reference {
        AttitudeReference::Vertical => "vertical",
        AttitudeReference::Surface => "surface",
    };
    let attitude_reference =
        match r.word("attitude_reference", reference, &["vertical", "surface"])? {
            "surface" => AttitudeReference::Surface,
            _ => AttitudeReference::Vertical,
        };
    let clearance_m = r.non_negative("clearance_m", d.clearance_m)?;
    let start = match r.word(
        "start",
        match d.start {
            Start::Touchdown => "touchdown",
            Start::Release => "release",
            Start::Descent => "descent",
        },
        &["touchdown", "release", "descent"],
    )? {
        "release" => Start::Release,
        "descent" => Start::Descent,
        _ => Start::Touchdown,
    };
    r.finish()?;
    Ok(Initial {
        attitude_reference,
        clearance_m,
        start,
    })
}
