//! The `[control]` table: the control loop, its sensors and its laws (MODEL.md section 7).

use super::error::ScenarioError;
use super::inputs::{Dist, LAW_PARAMETERS, read_dist_at_least};
use super::reader::{Reader, table};

table! {
    /// The control loop: its rate, latency, sensors and laws. Laws combine by phase: from a
    /// descent start, `descent` brakes the lander to release it at the release height;
    /// before contact is sensed, `attitude_hold` (if given) holds the attitude through the
    /// descent and the fall; once it is sensed, `hold_down` (if given) pushes the lander
    /// onto the surface; after it, nothing fires.
    #[derive(Debug, Clone, PartialEq)]
    pub struct Control;
    fn read_control(r) with key {
        /// Control instants per second: the sensors are read and a command issued at
        /// `t = k / rate_hz`.
        rate_hz: f64 = r.or(key, 10.0).f64_where(key, "a rate from 0.1 to 1000 Hz", |x| {
            (0.1..=1000.0).contains(&x)
        })?,
        /// Whole control periods between a reading and the period its command acts in.
        latency_periods: u32 = r.or(key, 1).integer(key, 0, 16)?,
        /// Sensor errors, `[control.sensors]`.
        sensors: Sensors = r.section(key, read_sensors)?,
        /// `[control.hold_down]`, if given.
        hold_down: Option<HoldDown> = r.optional(key, read_hold_down)?,
        /// `[control.attitude_hold]`, if given.
        attitude_hold: Option<AttitudeHold> = r.optional(key, read_attitude_hold)?,
        /// `[control.descent]`, if given.
        descent: Option<Descent> = r.optional(key, read_descent)?,
        /// A law of the user's own, by the name its program registered it under
        /// (`control::register_law`): it commands in every phase, in place of the built-in
        /// laws.
        law: Option<String> = match r.take(key) {
            None => None,
            Some(toml::Value::String(s)) if !s.is_empty() => Some(s),
            Some(v) => {
                return Err(r.error(
                    key,
                    &v,
                    "the name (a string) of a law the program running the sweep registered",
                ));
            }
        },
    }
}

table! {
    /// Sensor errors: the white noise of each reading (a new draw at every control instant)
    /// and the bias of each sample (drawn once), both normal with these standard
    /// deviations, per axis.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Sensors;
    fn read_sensors(r) with key {
        /// Attitude noise, deg.
        attitude_noise_deg: f64 = r.or(key, 0.0).non_negative(key)?,
        /// Attitude bias, deg.
        attitude_bias_deg: f64 = r.or(key, 0.0).non_negative(key)?,
        /// Rate noise, deg/s.
        rate_noise_deg_s: f64 = r.or(key, 0.0).non_negative(key)?,
        /// Rate bias, deg/s.
        rate_bias_deg_s: f64 = r.or(key, 0.0).non_negative(key)?,
        /// Velocity noise, m/s.
        velocity_noise_m_s: f64 = r.or(key, 0.0).non_negative(key)?,
        /// Velocity bias, m/s.
        velocity_bias_m_s: f64 = r.or(key, 0.0).non_negative(key)?,
        /// Altitude noise, m.
        altitude_noise_m: f64 = r.or(key, 0.0).non_negative(key)?,
        /// Altitude bias, m.
        altitude_bias_m: f64 = r.or(key, 0.0).non_negative(key)?,
    }
}

impl Default for Sensors {
    /// Perfect sensors: the defaults of `[control.sensors]`.
    fn default() -> Self {
        read_sensors(&mut Reader::new("control.sensors", toml::Table::new()))
            .expect("the default sensors are valid")
    }
}

table! {
    /// `hold_down`: once contact is sensed, thrust along `-Z_B` through the CG.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct HoldDown;
    fn read_hold_down(r) with key {
        /// Mean thrust over a control period, N.
        thrust_n: Dist = read_dist_at_least(r.or(key, 20.0), key, 0.0, "thrusts of at least 0 N")?,
        /// How long it pushes, from the instant contact is sensed, s.
        duration_s: Dist =
            read_dist_at_least(r.or(key, 10.0), key, 0.0, "durations of at least 0 s")?,
        /// Whether it stops sooner, at the first instant at which the sensed speed and rate
        /// have stayed below the rest thresholds (`[outcome]`) for `outcome.hold_time_s`.
        until_rest: bool = r.or(key, false).bool(key)?,
        /// Whether it stops sooner, at the first instant at which the sensed tilt of `Z_B`
        /// from the surface normal exceeds this, deg (absent: it pushes at any tilt).
        stop_tilt_deg: Option<f64> = r.given(key, |r| {
            r.f64_where(
                key,
                "a tilt greater than 0 and less than 90 deg (past 90 deg the lander has tipped)",
                |x| x > 0.0 && x < 90.0,
            )
        })?,
    }
}

table! {
    /// `descent`: the last manoeuvre before the free fall (seed chapter 1). The sample
    /// starts (`initial.start = "descent"`) with the lowest footpad `start_altitude_m` above
    /// the touchdown point, descending at `start_speed_m_s` (plus the velocity-error inputs:
    /// the navigation errors). At every control instant the law asks for the acceleration
    /// `gain_per_s (h'_ref - h') n + g` (gravity compensated) along the surface normal `n`,
    /// where `h` is the sensed height of the footpads (the altimeter's CG altitude less the
    /// CG's height above the footpads), `h' = n . v` its rate from the sensed velocity, and
    /// `h'_ref = -sqrt(2 braking_m_s2 (h - h_r))` above the release height `h_r` (the
    /// sample's `release_height_m`), 0 at or below it. At the first instant at or below
    /// `h_r` with `|h'|` below `release_speed_m_s` it releases the lander (the burn stops at
    /// once: its commands still waiting out the latency are dropped): the fall that
    /// follows, and the residual velocity, come from the law and its sensors. Velocity
    /// along the surface changes no height and is left as it is (the navigation error),
    /// unless `null_lateral_velocity`: then the law asks for `gain_per_s (h'_ref n - v) + g`,
    /// nulling it at the same rate (thrusters that push pure along +-X_B and +-Y_B needed).
    /// Each parameter may be drawn per sample (`control::DescentDraw`).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Descent;
    fn read_descent(r) with key {
        /// Height of the lowest footpad above the touchdown point at the start, m.
        start_altitude_m: Dist = greater_than_0(r.or(key, 30.0), key)?,
        /// Deceleration the reference profile plans with, m/s^2.
        braking_m_s2: Dist = greater_than_0(r.or(key, 0.01), key)?,
        /// Approach-rate error gain, 1/s.
        gain_per_s: Dist = greater_than_0(r.or(key, 0.5), key)?,
        /// Release once at the release height and this slow, m/s.
        release_speed_m_s: Dist = greater_than_0(r.or(key, 0.01), key)?,
        /// Descent speed along `-Z_I` at the start (plus the velocity errors), m/s.
        start_speed_m_s: Dist =
            read_dist_at_least(r.or(key, 0.3), key, 0.0, "speeds of at least 0 m/s")?,
        /// Null the velocity along the surface too (lateral thrusters needed).
        null_lateral_velocity: bool = r.or(key, false).bool(key)?,
    }
}

/// A value of `[control.descent]`: a number or distribution greater than 0 (at least the
/// smallest positive number).
fn greater_than_0(r: &mut Reader, key: &'static str) -> Result<Dist, ScenarioError> {
    read_dist_at_least(r, key, f64::MIN_POSITIVE, "values greater than 0")
}

/// What `attitude_hold` aligns `Z_B` with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// The local vertical `Z_I`.
    Vertical,
    /// The surface normal (the lander knows the slope beneath it).
    Normal,
}

table! {
    /// `attitude_hold`: a PD law on the tilt of `Z_B` from its target and on the body rates.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct AttitudeHold;
    fn read_attitude_hold(r) with key {
        /// What it aligns `Z_B` with.
        target: Target = r
            .or(key, "vertical")
            .word(key, &[("vertical", Target::Vertical), ("normal", Target::Normal)])?,
        /// Torque per radian of tilt error, N m/rad.
        kp_n_m_per_rad: Dist =
            read_dist_at_least(r.or(key, 20.0), key, 0.0, "gains of at least 0 N m/rad")?,
        /// Torque per rad/s of body rate, N m s/rad.
        kd_n_m_s_per_rad: Dist =
            read_dist_at_least(r.or(key, 40.0), key, 0.0, "gains of at least 0 N m s/rad")?,
        /// Tilt errors below this give no proportional torque, deg.
        deadband_deg: f64 = r.or(key, 0.0).non_negative(key)?,
    }
}

impl Control {
    /// The distributions of the law parameters (`LAW_PARAMETERS`): hold-down thrust and
    /// duration, attitude-hold `kp` and `kd`, the descent's start altitude and speed,
    /// braking, gain and release speed; `None` where the scenario has no such law. They
    /// are the last values of a sample (`Sample::values`, from `FIRST_LAW_VALUE`).
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

    /// The distributions of the law parameters, as `parameters` orders them, to change.
    pub fn parameters_mut(&mut self) -> [Option<&mut Dist>; LAW_PARAMETERS] {
        let (h, a, d) = (
            self.hold_down.as_mut(),
            self.attitude_hold.as_mut(),
            self.descent.as_mut(),
        );
        let (h0, h1) = h.map_or((None, None), |h| {
            (Some(&mut h.thrust_n), Some(&mut h.duration_s))
        });
        let (a0, a1) = a.map_or((None, None), |a| {
            (Some(&mut a.kp_n_m_per_rad), Some(&mut a.kd_n_m_s_per_rad))
        });
        let [d0, d1, d2, d3, d4] = d.map_or([None, None, None, None, None], |d| {
            [
                Some(&mut d.start_altitude_m),
                Some(&mut d.start_speed_m_s),
                Some(&mut d.braking_m_s2),
                Some(&mut d.gain_per_s),
                Some(&mut d.release_speed_m_s),
            ]
        });
        [h0, h1, a0, a1, d0, d1, d2, d3, d4]
    }
}
