//! The `[control]` table: the control loop, its sensors and its laws (MODEL.md section 7).

use super::error::ScenarioError;
use super::inputs::{Dist, read_dist_at_least};
use super::reader::Reader;

/// The control loop: its rate, latency, sensors and laws. Laws combine by phase: from a
/// descent start, `descent` brakes the lander to release it at the release height;
/// before contact is sensed, `attitude_hold` (if given) holds the attitude through the
/// descent and the fall; once it is sensed, `hold_down` (if given) pushes the lander onto
/// the surface; after it, nothing fires.
#[derive(Debug, Clone, PartialEq)]
pub struct Control {
    /// Control instants per second: the sensors are read and a command issued at
    /// `t = k / rate_hz`.
    pub rate_hz: f64,
    /// Whole control periods between a reading and the period its command acts in.
    pub latency_periods: u32,
    pub sensors: Sensors,
    pub hold_down: Option<HoldDown>,
    pub attitude_hold: Option<AttitudeHold>,
    pub descent: Option<Descent>,
    /// A law of the user's own, by the name its program registered it under
    /// (`control::register_law`): it commands in every phase, in place of the built-in
    /// laws.
    pub law: Option<String>,
}

/// Sensor errors: the white noise of each reading (a new draw at every control instant)
/// and the bias of each sample (drawn once), both normal with these standard deviations,
/// per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensors {
    pub attitude_noise_deg: f64,
    pub attitude_bias_deg: f64,
    pub rate_noise_deg_s: f64,
    pub rate_bias_deg_s: f64,
    pub velocity_noise_m_s: f64,
    pub velocity_bias_m_s: f64,
    pub altitude_noise_m: f64,
    pub altitude_bias_m: f64,
}

/// `hold_down`: once contact is sensed, thrust along `-Z_B` through the CG.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HoldDown {
    /// Mean thrust over a control period, N.
    pub thrust_n: Dist,
    /// How long it pushes, from the instant contact is sensed, s.
    pub duration_s: Dist,
    /// Whether it stops sooner, at the first instant at which the sensed speed and rate
    /// have stayed below the rest thresholds (`[outcome]`) for `outcome.hold_time_s`.
    pub until_rest: bool,
}

/// `descent`: the last manoeuvre before the free fall (seed chapter 1). The sample starts
/// (`initial.start = "descent"`) with the lowest footpad `start_altitude_m` above the
/// touchdown point, descending at `start_speed_m_s` (plus the velocity-error inputs: the
/// navigation errors). At every control instant the law asks for the acceleration
/// `gain_per_s (h'_ref - h') n + g` (gravity compensated) along the surface normal `n`,
/// where `h` is the sensed height of the footpads (the altimeter's CG altitude less the
/// CG's height above the footpads), `h' = n . v` its rate from the sensed velocity, and
/// `h'_ref = -sqrt(2 braking_m_s2 (h - h_r))` above the release height `h_r` (the sample's
/// `release_height_m`), 0 at or below it. At the first instant at or below `h_r` with
/// `|h'|` below `release_speed_m_s` it releases the lander (the burn stops at once: its
/// commands still waiting out the latency are dropped): the fall that follows, and the
/// residual velocity, come from the law and its sensors. Velocity along the surface
/// changes no height and is left as it is (the navigation error). Each parameter may be
/// drawn per sample (`control::DescentDraw`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Descent {
    pub start_altitude_m: Dist,
    pub start_speed_m_s: Dist,
    /// Deceleration the reference profile plans with, m/s^2.
    pub braking_m_s2: Dist,
    /// Approach-rate error gain, 1/s.
    pub gain_per_s: Dist,
    pub release_speed_m_s: Dist,
}

/// What `attitude_hold` aligns `Z_B` with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// The local vertical `Z_I`.
    Vertical,
    /// The surface normal (the lander knows the slope beneath it).
    Normal,
}

/// `attitude_hold`: a PD law on the tilt of `Z_B` from its target and on the body rates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AttitudeHold {
    pub target: Target,
    /// Torque per radian of tilt error, N m/rad.
    pub kp_n_m_per_rad: Dist,
    /// Torque per rad/s of body rate, N m s/rad.
    pub kd_n_m_s_per_rad: Dist,
    /// Tilt errors below this give no proportional torque, deg.
    pub deadband_deg: f64,
}

impl Default for Sensors {
    fn default() -> Self {
        Sensors {
            attitude_noise_deg: 0.0,
            attitude_bias_deg: 0.0,
            rate_noise_deg_s: 0.0,
            rate_bias_deg_s: 0.0,
            velocity_noise_m_s: 0.0,
            velocity_bias_m_s: 0.0,
            altitude_noise_m: 0.0,
            altitude_bias_m: 0.0,
        }
    }
}

/// The law parameters a sample may draw, in the order they join the inputs' grid (after
/// the inputs, the last varying fastest) and of `Control::parameters`.
pub const LAW_PARAMETERS: usize = 9;

impl Control {
    /// The distributions of the law parameters (`LAW_PARAMETERS`): hold-down thrust and
    /// duration, attitude-hold `kp` and `kd`, the descent's start altitude and speed,
    /// braking, gain and release speed; `None` where the scenario has no such law.
    #[must_use]
    pub fn parameters(&self) -> [Option<Dist>; LAW_PARAMETERS] {
        let (h, a, d) = (
            self.hold_down.as_ref(),
            self.attitude_hold.as_ref(),
            self.descent.as_ref(),
        );
        [
            h.map(|h| h.thrust_n),
            h.map(|h| h.duration_s),
            a.map(|a| a.kp_n_m_per_rad),
            a.map(|a| a.kd_n_m_s_per_rad),
            d.map(|d| d.start_altitude_m),
            d.map(|d| d.start_speed_m_s),
            d.map(|d| d.braking_m_s2),
            d.map(|d| d.gain_per_s),
            d.map(|d| d.release_speed_m_s),
        ]
    }
}

pub(super) fn read_control(top: &mut Reader) -> Result<Option<Control>, ScenarioError> {
    let Some(mut r) = top.table("control")? else {
        return Ok(None);
    };
    let rate_hz = r.f64_where("rate_hz", 10.0, "a rate from 0.1 to 1000 Hz", |x| {
        (0.1..=1000.0).contains(&x)
    })?;
    let latency_periods = r.integer("latency_periods", 1, 0, 16)? as u32;
    let d = Sensors::default();
    let sensors = match r.table("sensors")? {
        None => d,
        Some(mut s) => {
            let out = Sensors {
                attitude_noise_deg: s.non_negative("attitude_noise_deg", d.attitude_noise_deg)?,
                attitude_bias_deg: s.non_negative("attitude_bias_deg", d.attitude_bias_deg)?,
                rate_noise_deg_s: s.non_negative("rate_noise_deg_s", d.rate_noise_deg_s)?,
                rate_bias_deg_s: s.non_negative("rate_bias_deg_s", d.rate_bias_deg_s)?,
                velocity_noise_m_s: s.non_negative("velocity_noise_m_s", d.velocity_noise_m_s)?,
                velocity_bias_m_s: s.non_negative("velocity_bias_m_s", d.velocity_bias_m_s)?,
                altitude_noise_m: s.non_negative("altitude_noise_m", d.altitude_noise_m)?,
                altitude_bias_m: s.non_negative("altitude_bias_m", d.altitude_bias_m)?,
            };
            s.finish()?;
            out
        }
    };
    let hold_down = match r.table("hold_down")? {
        None => None,
        Some(mut h) => {
            let out = HoldDown {
                thrust_n: read_dist_at_least(
                    &mut h,
                    "thrust_n",
                    Dist::Fixed(20.0),
                    0.0,
                    "thrusts of at least 0 N",
                )?,
                duration_s: read_dist_at_least(
                    &mut h,
                    "duration_s",
                    Dist::Fixed(10.0),
                    0.0,
                    "durations of at least 0 s",
                )?,
                until_rest: h.bool("until_rest", false)?,
            };
            h.finish()?;
            Some(out)
        }
    };
    let attitude_hold = match r.table("attitude_hold")? {
        None => None,
        Some(mut a) => {
            let target = match a.word("target", "vertical", &["vertical", "normal"])? {
                "normal" => Target::Normal,
                _ => Target::Vertical,
            };
            let out = AttitudeHold {
                target,
                kp_n_m_per_rad: read_dist_at_least(
                    &mut a,
                    "kp_n_m_per_rad",
                    Dist::Fixed(20.0),
                    0.0,
                    "gains of at least 0 N m/rad",
                )?,
                kd_n_m_s_per_rad: read_dist_at_least(
                    &mut a,
                    "kd_n_m_s_per_rad",
                    Dist::Fixed(40.0),
                    0.0,
                    "gains of at least 0 N m s/rad",
                )?,
                deadband_deg: a.non_negative("deadband_deg", 0.0)?,
            };
            a.finish()?;
            Some(out)
        }
    };
    let descent = match r.table("descent")? {
        None => None,
        Some(mut d) => {
            // Greater than 0: at least the smallest positive number.
            let mut positive = |key: &'static str, default: f64| {
                read_dist_at_least(
                    &mut d,
                    key,
                    Dist::Fixed(default),
                    f64::MIN_POSITIVE,
                    "values greater than 0",
                )
            };
            let start_altitude_m = positive("start_altitude_m", 30.0)?;
            let braking_m_s2 = positive("braking_m_s2", 0.01)?;
            let gain_per_s = positive("gain_per_s", 0.5)?;
            let release_speed_m_s = positive("release_speed_m_s", 0.01)?;
            let out = Descent {
                start_altitude_m,
                start_speed_m_s: read_dist_at_least(
                    &mut d,
                    "start_speed_m_s",
                    Dist::Fixed(0.3),
                    0.0,
                    "speeds of at least 0 m/s",
                )?,
                braking_m_s2,
                gain_per_s,
                release_speed_m_s,
            };
            d.finish()?;
            Some(out)
        }
    };
    let law = match r.take("law") {
        None => None,
        Some(toml::Value::String(s)) if !s.is_empty() => Some(s),
        Some(v) => {
            return Err(r.error(
                "law",
                &v,
                "the name (a string) of a law the program running the sweep registered",
            ));
        }
    };
    r.finish()?;
    Ok(Some(Control {
        rate_hz,
        latency_periods,
        sensors,
        hold_down,
        attitude_hold,
        descent,
        law,
    }))
}
