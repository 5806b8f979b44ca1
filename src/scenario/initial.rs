//! The `[initial]` table: the initial state besides the sampled inputs.

use super::reader::table;

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
    }
}
