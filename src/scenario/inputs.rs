//! The `[inputs]` table: the distribution of every sampled input.

use super::error::ScenarioError;
use super::reader::Reader;
pub use crate::dist::Dist;
use toml::Value;

/// Declares the inputs once: the struct `Inputs`, their names and units (`INPUT_FIELDS`),
/// the ranges they must stay in and their order in an array.
macro_rules! inputs {
    ($( $(#[$doc:meta])* $field:ident [$unit:literal] $range:expr ),* $(,)?) => {
        /// The inputs that every sample draws, in the order they are drawn and written.
        /// `T` is `Dist` in a scenario and `f64` in a sample.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct Inputs<T> {
            $( $(#[$doc])* pub $field: T, )*
        }

        /// Names and units of the sampled inputs, in drawing order.
        pub const INPUT_FIELDS: [(&str, &str); 12] = [$( (stringify!($field), $unit) ),*];

        /// The range each input (`INPUT_FIELDS`, in order) must stay in.
        const INPUT_RANGES: [Range; 12] = [$( $range ),*];

        impl<T: Copy> Inputs<T> {
            /// The inputs in the order of `INPUT_FIELDS`.
            #[must_use]
            pub fn to_array(&self) -> [T; 12] {
                [$( self.$field ),*]
            }

            /// The inverse of `to_array`.
            #[must_use]
            pub fn from_array(a: [T; 12]) -> Self {
                let [$( $field ),*] = a;
                Inputs { $( $field ),* }
            }
        }
    };
}

inputs! {
    /// Slope angle from horizontal.
    slope_deg ["deg"] Range {
        min: 0.0,
        max: 90.0,
        max_open: true,
        text: "values from 0 up to, not including, 90 deg",
    },
    /// Downhill direction, measured in the X_I Y_I plane from X_I (the lander's yaw is 0).
    downhill_azimuth_deg ["deg"] ANY,
    /// Height of the ballistic fall before touchdown (touchdown speed `sqrt(2 g0 h)`).
    release_height_m ["m"] Range::at_least(0.0, "values of at least 0 m"),
    /// Residual velocity error along X of the attitude reference frame.
    velocity_error_x_m_s ["m/s"] ANY,
    /// Residual velocity error along Y.
    velocity_error_y_m_s ["m/s"] ANY,
    /// Residual velocity error along Z.
    velocity_error_z_m_s ["m/s"] ANY,
    /// Roll error `phi`.
    roll_deg ["deg"] ANY,
    /// Pitch error `theta`.
    pitch_deg ["deg"] ANY,
    /// Yaw `psi`.
    yaw_deg ["deg"] ANY,
    /// Residual body rate about X_B.
    rate_x_deg_s ["deg/s"] ANY,
    /// Residual body rate about Y_B.
    rate_y_deg_s ["deg/s"] ANY,
    /// Residual body rate about Z_B.
    rate_z_deg_s ["deg/s"] ANY,
}

/// Declares the parameters once: the enum `Parameter`, their keys, names and units
/// (`PARAMETER_FIELDS`) and whether they must be greater than 0 (else at least 0).
macro_rules! parameters {
    ($( $(#[$doc:meta])* $variant:ident = $table:literal . $name:ident [$unit:literal]
        positive: $positive:literal ),* $(,)?) => {
        /// The scenario parameters that may be drawn per sample like the inputs: a
        /// distribution in place of the number at their key (`Parameter::key`). Each drawn
        /// one is a column of the sweep, named as here, after the inputs'.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum Parameter {
            $( $(#[$doc])* $variant, )*
        }

        /// Number of `Parameter`s.
        pub const PARAMETERS: usize = [$( stringify!($variant) ),*].len();

        /// Names (the column's and the key's last part) and units of the parameters, in the
        /// order of `Parameter::ALL`.
        pub const PARAMETER_FIELDS: [(&str, &str); PARAMETERS] =
            [$( (stringify!($name), $unit) ),*];

        /// Whether each parameter (`Parameter::ALL`) must be greater than 0 (else at least 0).
        const PARAMETER_POSITIVE: [bool; PARAMETERS] = [$( $positive ),*];

        impl Parameter {
            /// Every parameter, in column order.
            pub const ALL: [Parameter; PARAMETERS] = [$( Parameter::$variant ),*];

            /// The column name.
            #[must_use]
            pub fn name(self) -> &'static str {
                PARAMETER_FIELDS[self as usize].0
            }

            /// The scenario key, with its table (none for a key at the top of the file).
            #[must_use]
            pub fn key(self) -> &'static str {
                let key = match self {
                    $( Parameter::$variant => concat!($table, ".", stringify!($name)), )*
                };
                key.strip_prefix('.').unwrap_or(key)
            }
        }
    };
}

parameters! {
    /// `lander.mass_kg` (the inertia stays as given).
    MassKg = "lander".mass_kg ["kg"] positive: true,
    /// `lander.cg_height_m`: every footpad this far below the CG.
    CgHeightM = "lander".cg_height_m ["m"] positive: true,
    /// `surface.stiffness_n_per_m`.
    StiffnessNPerM = "surface".stiffness_n_per_m ["N/m"] positive: true,
    /// `surface.damping_n_s_per_m`.
    DampingNSPerM = "surface".damping_n_s_per_m ["N s/m"] positive: false,
    /// `surface.friction_coefficient`.
    FrictionCoefficient = "surface".friction_coefficient ["1"] positive: false,
    /// `damper.crush_strength_psi` (a single-stage cartridge).
    CrushStrengthPsi = "damper".crush_strength_psi ["psi"] positive: true,
    /// `surface.roughness.rms_height_m`: the terrain tiles, built for the largest value,
    /// scaled to each sample's.
    RmsHeightM = "surface.roughness".rms_height_m ["m"] positive: false,
    /// `lander.footpad_area_m2`: the area of each footpad's sole (regolith and rocks).
    FootpadAreaM2 = "lander".footpad_area_m2 ["m^2"] positive: true,
    /// `surface.regolith.bekker_k_c`: Bekker's cohesive modulus, N/m^(n+1).
    BekkerKC = "surface.regolith".bekker_k_c ["N/m^(n+1)"] positive: false,
    /// `surface.regolith.bekker_k_phi`: Bekker's frictional modulus, N/m^(n+2).
    BekkerKPhi = "surface.regolith".bekker_k_phi ["N/m^(n+2)"] positive: false,
    /// `surface.regolith.bekker_n`: Bekker's sinkage exponent.
    BekkerN = "surface.regolith".bekker_n ["1"] positive: true,
    /// `surface.regolith.unloading_modulus_pa_per_m`: the slope of the elastic unloading
    /// line, pressure per depth.
    UnloadingModulusPaPerM = "surface.regolith".unloading_modulus_pa_per_m ["Pa/m"]
        positive: true,
    /// `surface.regolith.cohesion_pa`: the soil's cohesion (passive earth pressure).
    CohesionPa = "surface.regolith".cohesion_pa ["Pa"] positive: false,
    /// `surface.regolith.friction_angle_deg`: the soil's internal friction angle.
    FrictionAngleDeg = "surface.regolith".friction_angle_deg ["deg"] positive: false,
    /// `surface.regolith.bulk_density_kg_m3`: the soil's bulk density.
    BulkDensityKgM3 = "surface.regolith".bulk_density_kg_m3 ["kg/m^3"] positive: false,
    /// `surface.rocks.abundance`: Golombek and Rapp's `k`, the fraction of the surface
    /// covered by rocks.
    RockAbundance = "surface.rocks".abundance ["1"] positive: false,
    /// `gravity_m_s2`: the gravity along -Z_I (a landing site's, `touchdown site`). A fall
    /// from `inputs.release_height_m` falls in the sample's gravity.
    GravityMS2 = "".gravity_m_s2 ["m/s^2"] positive: false,
}

/// The built-in control laws' parameters a sample may draw (`Control::parameters`).
pub const LAW_PARAMETERS: usize = 9;

/// The law parameters, in the order of `Control::parameters`: column name, the name of the
/// stream a sample draws it from (`rng::stream`), scenario key, and the range of its values.
const LAW_FIELDS: [(&str, &str, &str, Range); LAW_PARAMETERS] = {
    const AT_LEAST_0: Range = Range::at_least(0.0, "values of at least 0");
    const ABOVE_0: Range = Range::at_least(f64::MIN_POSITIVE, "values greater than 0");
    [
        (
            "hold_down_thrust_n",
            "hold_down_thrust_n",
            "control.hold_down.thrust_n",
            AT_LEAST_0,
        ),
        (
            "hold_down_duration_s",
            "hold_down_duration_s",
            "control.hold_down.duration_s",
            AT_LEAST_0,
        ),
        (
            "attitude_kp_n_m_per_rad",
            "kp_n_m_per_rad",
            "control.attitude_hold.kp_n_m_per_rad",
            AT_LEAST_0,
        ),
        (
            "attitude_kd_n_m_s_per_rad",
            "kd_n_m_s_per_rad",
            "control.attitude_hold.kd_n_m_s_per_rad",
            AT_LEAST_0,
        ),
        (
            "descent_start_altitude_m",
            "descent_start_altitude_m",
            "control.descent.start_altitude_m",
            ABOVE_0,
        ),
        (
            "descent_start_speed_m_s",
            "descent_start_speed_m_s",
            "control.descent.start_speed_m_s",
            AT_LEAST_0,
        ),
        (
            "descent_braking_m_s2",
            "descent_braking_m_s2",
            "control.descent.braking_m_s2",
            ABOVE_0,
        ),
        (
            "descent_gain_per_s",
            "descent_gain_per_s",
            "control.descent.gain_per_s",
            ABOVE_0,
        ),
        (
            "descent_release_speed_m_s",
            "descent_release_speed_m_s",
            "control.descent.release_speed_m_s",
            ABOVE_0,
        ),
    ]
};

/// Where the law parameters start in `Sample::values`.
pub const FIRST_LAW_VALUE: usize = INPUT_FIELDS.len() + PARAMETERS;

/// The inputs a touchdown state given in `[initial]` replaces, positions in
/// `INPUT_FIELDS`: the release height and the three velocity errors (fixed at 0 with it).
pub const FALL_INPUTS: std::ops::Range<usize> = 2..6;

/// Number of values of the touchdown state a scenario may give (`INITIAL_FIELDS`).
pub const STATE_VALUES: usize = 3;

/// The touchdown state a scenario may give in `[initial]` (`Start::State`), each value
/// fixed or drawn per sample like a parameter: column name (its stream's too), key in
/// `[initial]`, unit, and the range of its values.
const STATE_FIELDS: [(&str, &str, &str, Range); STATE_VALUES] = [
    (
        "initial_normal_speed_m_s",
        "normal_speed_m_s",
        "m/s",
        Range::at_least(0.0, "values of at least 0 m/s (towards the surface)"),
    ),
    (
        "initial_tangential_speed_m_s",
        "tangential_speed_m_s",
        "m/s",
        Range::at_least(0.0, "values of at least 0 m/s"),
    ),
    (
        "initial_tangential_azimuth_deg",
        "tangential_azimuth_deg",
        "deg",
        ANY,
    ),
];

/// Column names and units of the touchdown state's values (`STATE_VALUES`), in the order of
/// `Sample::touchdown`.
pub const INITIAL_FIELDS: [(&str, &str); STATE_VALUES] = [
    (STATE_FIELDS[0].0, STATE_FIELDS[0].2),
    (STATE_FIELDS[1].0, STATE_FIELDS[1].2),
    (STATE_FIELDS[2].0, STATE_FIELDS[2].2),
];

/// Where the touchdown state's values start in `Sample::values`.
pub const FIRST_STATE_VALUE: usize = FIRST_LAW_VALUE + LAW_PARAMETERS;

/// Number of values a sample draws: the inputs (`INPUT_FIELDS`), the parameters
/// (`PARAMETER_FIELDS`), the built-in control laws' parameters (0 in a sample of a
/// scenario without that law), then the touchdown state (`INITIAL_FIELDS`; 0 in a sample
/// of a scenario that gives none).
pub const VALUES: usize = FIRST_STATE_VALUE + STATE_VALUES;

/// The column name of value `k` of a sample (`Sample::values`).
#[must_use]
pub fn value_name(k: usize) -> &'static str {
    if k < INPUT_FIELDS.len() {
        INPUT_FIELDS[k].0
    } else if k < FIRST_LAW_VALUE {
        PARAMETER_FIELDS[k - INPUT_FIELDS.len()].0
    } else if k < FIRST_STATE_VALUE {
        LAW_FIELDS[k - FIRST_LAW_VALUE].0
    } else {
        STATE_FIELDS[k - FIRST_STATE_VALUE].0
    }
}

/// The unit of value `k` of a sample, as its column's.
#[must_use]
pub fn value_unit(k: usize) -> &'static str {
    if k < INPUT_FIELDS.len() {
        INPUT_FIELDS[k].1
    } else if k < FIRST_LAW_VALUE {
        PARAMETER_FIELDS[k - INPUT_FIELDS.len()].1
    } else if k < FIRST_STATE_VALUE {
        LAW_UNITS[k - FIRST_LAW_VALUE]
    } else {
        STATE_FIELDS[k - FIRST_STATE_VALUE].2
    }
}

/// The units of the law parameters, in the order of `LAW_FIELDS`.
const LAW_UNITS: [&str; LAW_PARAMETERS] = [
    "N",
    "s",
    "N m/rad",
    "N m s/rad",
    "m",
    "m/s",
    "m/s^2",
    "1/s",
    "m/s",
];

/// The name of the stream value `k` of a sample draws from (`rng::stream`): its column
/// name, but for the attitude hold's gains, whose streams kept their first names.
#[must_use]
pub fn stream_name(k: usize) -> &'static str {
    if (FIRST_LAW_VALUE..FIRST_STATE_VALUE).contains(&k) {
        LAW_FIELDS[k - FIRST_LAW_VALUE].1
    } else {
        value_name(k)
    }
}

/// The scenario key of value `k` of a sample (`inputs.slope_deg`, `lander.mass_kg`,
/// `control.hold_down.thrust_n`, `initial.normal_speed_m_s`).
#[must_use]
pub fn value_key(k: usize) -> String {
    if k < INPUT_FIELDS.len() {
        format!("inputs.{}", INPUT_FIELDS[k].0)
    } else if k < FIRST_LAW_VALUE {
        Parameter::ALL[k - INPUT_FIELDS.len()].key().to_string()
    } else if k < FIRST_STATE_VALUE {
        LAW_FIELDS[k - FIRST_LAW_VALUE].2.to_string()
    } else {
        format!("initial.{}", STATE_FIELDS[k - FIRST_STATE_VALUE].1)
    }
}

/// The distribution of each parameter drawn per sample, `None` where the scenario gives a
/// number (which its own field holds); indexed by `Parameter as usize`.
pub type Sampled = [Option<Dist>; PARAMETERS];

/// Reads the parameter at `key` of `r` (`Parameter::key`): a number (greater than 0 or at
/// least 0, as `PARAMETER_FIELDS` says), or a distribution whose values all are, recorded in
/// `sampled`. Gives the number, or the distribution's median: the value of the scenario's
/// own field, which the sweep's samples replace by their draws.
pub(super) fn read_parameter(
    r: &mut Reader,
    key: &'static str,
    sampled: &mut Sampled,
) -> Result<f64, ScenarioError> {
    let path = r.key_path(key);
    let which = Parameter::ALL
        .into_iter()
        .find(|p| p.key() == path)
        .expect("a key of `Parameter`");
    let (number, values, min) = if PARAMETER_POSITIVE[which as usize] {
        (
            "a number greater than 0",
            "values greater than 0",
            f64::MIN_POSITIVE,
        )
    } else {
        ("a number of at least 0", "values of at least 0", 0.0)
    };
    match r.take(key) {
        None => r.f64(key),
        Some(v @ Value::Table(_)) => {
            let dist = read_dist(r, key, &v, &Range::at_least(min, values))?;
            let median = match dist {
                Dist::Grid { count, .. } => crate::dist::quantile(&dist, 0.5, count / 2),
                _ => crate::dist::quantile(&dist, 0.5, 0),
            };
            if !matches!(dist, Dist::Fixed(_)) {
                sampled[which as usize] = Some(dist);
            }
            Ok(median)
        }
        Some(v) => {
            let x = r.number(key, &v)?;
            if x >= min {
                Ok(x)
            } else {
                Err(r.error(key, &v, number))
            }
        }
    }
}

/// The range an input must stay in, for validation.
#[derive(Clone, Copy)]
struct Range {
    min: f64,
    max: f64,
    max_open: bool,
    text: &'static str,
}

impl Range {
    /// Values of at least `min` (`text` says so).
    const fn at_least(min: f64, text: &'static str) -> Range {
        Range {
            min,
            max: f64::INFINITY,
            max_open: false,
            text,
        }
    }

    fn holds(&self, x: f64) -> bool {
        x >= self.min && (x < self.max || (!self.max_open && x <= self.max))
    }
}

const ANY: Range = Range {
    min: f64::NEG_INFINITY,
    max: f64::INFINITY,
    max_open: false,
    text: "any finite value",
};

/// Whether `x` is a value that value `k` of a sample (`Sample::values`: the
/// inputs, the parameters, then the law parameters) may take; if not, what the values may
/// be.
pub fn check_value(k: usize, x: f64) -> Result<(), &'static str> {
    let range = if k < INPUT_RANGES.len() {
        INPUT_RANGES[k]
    } else if k >= FIRST_STATE_VALUE {
        STATE_FIELDS[k - FIRST_STATE_VALUE].3
    } else if k >= FIRST_LAW_VALUE {
        LAW_FIELDS[k - FIRST_LAW_VALUE].3
    } else if PARAMETER_POSITIVE[k - INPUT_RANGES.len()] {
        Range::at_least(f64::MIN_POSITIVE, "values greater than 0")
    } else {
        Range::at_least(0.0, "values of at least 0")
    };
    if x.is_finite() && range.holds(x) {
        Ok(())
    } else {
        Err(range.text)
    }
}

/// Reads the `[inputs]` table: every input a number or a distribution.
pub(super) fn read_inputs(r: &mut Reader) -> Result<Inputs<Dist>, ScenarioError> {
    let mut out = [Dist::Fixed(0.0); 12];
    for (i, (name, _)) in INPUT_FIELDS.iter().enumerate() {
        let v = r.value(name)?;
        out[i] = read_dist(r, name, &v, &INPUT_RANGES[i])?;
    }
    r.finish()?;
    Ok(Inputs::from_array(out))
}

/// Reads the touchdown state's value `j` (`INITIAL_FIELDS`) at its key of `[initial]` (`r`):
/// a number or a distribution within its range, `None` where the file does not give it.
pub(super) fn read_state_value(r: &mut Reader, j: usize) -> Result<Option<Dist>, ScenarioError> {
    let (_, key, _, range) = STATE_FIELDS[j];
    match r.take(key) {
        None => Ok(None),
        Some(v) => read_dist(r, key, &v, &range).map(Some),
    }
}

/// Reads `key` of `r` as a number or a `{ dist = ..., ... }` table whose values are all at
/// least `min` (`text` says so in an error), or gives its default where it is absent: a
/// scenario parameter that may be sampled like any input.
pub(super) fn read_dist_at_least(
    r: &mut Reader,
    key: &'static str,
    min: f64,
    text: &'static str,
) -> Result<Dist, ScenarioError> {
    let v = r.value(key)?;
    read_dist(r, key, &v, &Range::at_least(min, text))
}

/// Reads a number or a `{ dist = ..., ... }` table.
fn read_dist(r: &Reader, key: &str, v: &Value, range: &Range) -> Result<Dist, ScenarioError> {
    let allowed_forms = "a number, or { dist = \"fixed\", value = x }, { dist = \"uniform\", min = a, max = b }, \
        { dist = \"log-uniform\", min = a, max = b } with a above 0, \
        { dist = \"normal\", mean = m, sd = s } with optional min and max to truncate it, \
        or { dist = \"grid\", min = a, max = b, count = n }";
    let dist = match v {
        Value::Float(_) | Value::Integer(_) => Dist::Fixed(r.number(key, v)?),
        Value::Table(t) => {
            let mut t = Reader::new(&r.key_path(key), t.clone());
            let kinds = ["fixed", "uniform", "log-uniform", "normal", "grid"].map(|k| (k, k));
            let kind = t.given("dist", |t| t.word("dist", &kinds))?.unwrap_or("");
            let need = |t: &mut Reader, k: &'static str| -> Result<f64, ScenarioError> {
                if !t.has(k) {
                    return Err(r.error(key, v, &format!("`{k}` in a {kind:?} distribution")));
                }
                t.f64(k)
            };
            let dist = match kind {
                "fixed" => Dist::Fixed(need(&mut t, "value")?),
                "uniform" => {
                    let (min, max) = (need(&mut t, "min")?, need(&mut t, "max")?);
                    if min > max {
                        return Err(r.error(key, v, "min at most max"));
                    }
                    Dist::Uniform { min, max }
                }
                "log-uniform" => {
                    let (min, max) = (need(&mut t, "min")?, need(&mut t, "max")?);
                    if min.is_nan() || min <= 0.0 {
                        return Err(r.error(key, v, "min above 0 (uniform in the logarithm)"));
                    }
                    if min > max {
                        return Err(r.error(key, v, "min at most max"));
                    }
                    Dist::LogUniform { min, max }
                }
                "normal" => {
                    let mean = need(&mut t, "mean")?;
                    let sd = need(&mut t, "sd")?;
                    if sd <= 0.0 {
                        return Err(r.error(key, v, "sd greater than 0"));
                    }
                    let min = t.given("min", |t| t.f64("min"))?;
                    let max = t.given("max", |t| t.f64("max"))?;
                    let (min, max) = (
                        min.unwrap_or(f64::NEG_INFINITY),
                        max.unwrap_or(f64::INFINITY),
                    );
                    if min >= max {
                        return Err(r.error(key, v, "min below max"));
                    }
                    // Truncation by rejection: the interval must hold a fair share of the
                    // normal's mass, or drawing would take too long.
                    let phi =
                        |x: f64| 0.5 * libm::erfc(-(x - mean) / (sd * std::f64::consts::SQRT_2));
                    if phi(max) - phi(min) < 0.01 {
                        return Err(r.error(
                            key,
                            v,
                            "a truncation interval [min, max] that holds at least 1 % of the normal's probability",
                        ));
                    }
                    Dist::Normal { mean, sd, min, max }
                }
                "grid" => {
                    let (min, max) = (need(&mut t, "min")?, need(&mut t, "max")?);
                    if !t.has("count") {
                        return Err(r.error(key, v, "`count` in a \"grid\" distribution"));
                    }
                    let count = t.integer("count", 1, i64::MAX)?;
                    if min > max {
                        return Err(r.error(key, v, "min at most max"));
                    }
                    Dist::Grid { min, max, count }
                }
                _ => return Err(r.error(key, v, allowed_forms)),
            };
            t.finish()?;
            dist
        }
        _ => return Err(r.error(key, v, allowed_forms)),
    };
    let (lo, hi) = dist.support();
    if !(range.holds(lo) && range.holds(hi)) {
        let why = if lo.is_infinite() || hi.is_infinite() {
            format!(
                "{}; an untruncated normal reaches any value, so give min and max",
                range.text
            )
        } else {
            range.text.to_string()
        };
        return Err(r.error(key, v, &why));
    }
    Ok(dist)
}
