//! The `[initial]` table: the initial state besides the sampled inputs.

use super::error::ScenarioError;
use super::inputs::{
    Dist, FIRST_STATE_VALUE, INITIAL_FIELDS, STATE_VALUES, read_state_value, value_key,
};
use super::reader::{Reader, table};

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
    /// `start = "touchdown"` with the touchdown state given (`Initial::touchdown`): the
    /// velocity at the end of the fall in the surface's frame, in place of the fall and the
    /// velocity errors.
    State,
}

table! {
    /// The initial state besides the sampled inputs.
    #[derive(Debug, Clone, PartialEq)]
    pub struct Initial;
    fn read_initial(r) with key {
        /// Against what the attitude errors and the fall velocity are taken.
        attitude_reference: AttitudeReference = r.word(
            key,
            &[
                ("vertical", AttitudeReference::Vertical),
                ("surface", AttitudeReference::Surface),
            ],
        )?,
        /// Height of the lowest footpad above the surface at touchdown, m.
        clearance_m: f64 = r.non_negative(key)?,
        /// Where a sample starts.
        start: Start = r.word(
            key,
            &[
                ("touchdown", Start::Touchdown),
                ("release", Start::Release),
                ("descent", Start::Descent),
            ],
        )?,
        /// The touchdown state, where the file gives it (`start = "touchdown"`, which it
        /// makes `Start::State`): the distributions of the speed towards the surface, the
        /// speed along it and its azimuth from downhill (`INITIAL_FIELDS`; the last two 0
        /// where not given).
        touchdown: Option<[Dist; STATE_VALUES]> = read_touchdown(r, &mut start)?,
    }
}

/// Reads the touchdown state of `[initial]` (`r`), if the file gives it: the speed towards
/// the surface, then optionally the speed along it and its azimuth. Refused with a start
/// other than `"touchdown"`, which it turns into `Start::State`.
fn read_touchdown(
    r: &mut Reader,
    start: &mut Start,
) -> Result<Option<[Dist; STATE_VALUES]>, ScenarioError> {
    let mut given = [None; STATE_VALUES];
    for (j, g) in given.iter_mut().enumerate() {
        *g = read_state_value(r, j)?;
    }
    let Some(j) = given.iter().position(Option::is_some) else {
        return Ok(None);
    };
    let key = value_key(FIRST_STATE_VALUE + j);
    let refuse = |allowed: &str| ScenarioError::Invalid {
        key: key.clone(),
        value: given[j].expect("given").toml(),
        allowed: allowed.to_string(),
    };
    if *start != Start::Touchdown {
        return Err(refuse(
            "initial.start = \"touchdown\" with it: the touchdown state is the state at the \
             first contact, which a start at the release or a descent does not give",
        ));
    }
    let Some(normal) = given[0] else {
        return Err(refuse(&format!(
            "a touchdown state given whole: add initial.normal_speed_m_s (the speed \
             towards the surface, {}) beside it",
            INITIAL_FIELDS[0].1
        )));
    };
    *start = Start::State;
    Ok(Some([
        normal,
        given[1].unwrap_or(Dist::Fixed(0.0)),
        given[2].unwrap_or(Dist::Fixed(0.0)),
    ]))
}
