//! The `[[thrusters]]` array and the `[propulsion]` table: where the thrusters sit, how
//! hard they push, and what their propellant gives (MODEL.md section 7).

use super::error::ScenarioError;
use super::reader::{Reader, table};
use toml::Value;

table! {
    /// One thruster, fixed in B: every key required.
    #[derive(Debug, Clone, PartialEq)]
    pub struct Thruster;
    fn read_thruster(r) with key {
        /// Where its force acts, in B (the CG at the origin), m.
        position_m: [f64; 3] = {
            let v = need(r, key)?.value(key)?;
            r.vec3(key, &v)?
        },
        /// Unit direction of the force it puts on the lander, in B (its plume points the
        /// other way).
        direction: [f64; 3] = {
            let v = need(r, key)?.value(key)?;
            let direction = r.vec3(key, &v)?;
            let n = direction.iter().map(|x| x * x).sum::<f64>().sqrt();
            if n < 1e-9 {
                return Err(r.error(key, &v, "a non-zero vector [x, y, z] in B"));
            }
            direction.map(|x| x / n)
        },
        /// Thrust when on, N.
        max_thrust_n: f64 = need(r, key)?.positive(key)?,
        /// Shortest firing (the minimum impulse bit is this times the thrust), s: on-times
        /// are whole multiples of it.
        min_on_time_s: f64 = need(r, key)?.positive(key)?,
    }
}

table! {
    /// The propellant and the thrusters' sampled errors.
    #[derive(Debug, Clone, PartialEq)]
    pub struct Propulsion;
    fn read_propulsion(r) with key {
        /// Specific impulse, s: propellant used is the thrust's integral over `isp g0`.
        isp_s: f64 = r.or(key, 220.0).positive(key)?,
        /// Standard deviation of each thruster's thrust magnitude, as a fraction of its
        /// `max_thrust_n`, drawn per sample and thruster (normal, truncated at 3 sd).
        thrust_error_sd: f64 = r.or(key, 0.0).f64_where(key, "a fraction from 0 to 0.3", |x| {
            (0.0..=0.3).contains(&x)
        })?,
        /// Standard deviation of each thruster's misalignment about each of the two axes
        /// across its direction, drawn per sample and thruster (normal, truncated at 3 sd),
        /// deg.
        misalignment_sd_deg: f64 = r.or(key, 0.0).f64_where(
            key,
            "an angle from 0 to 10 deg",
            |x| (0.0..=10.0).contains(&x),
        )?,
    }
}

/// Standard gravity, the `g0` of the specific impulse, m/s^2.
pub const G0_M_S2: f64 = 9.806_65;

pub(super) fn read_thrusters(top: &mut Reader) -> Result<Vec<Thruster>, ScenarioError> {
    let Some(v) = top.take("thrusters") else {
        return Ok(Vec::new());
    };
    let allowed = "an array of tables [[thrusters]], each with position_m = [x, y, z], \
                   direction = [x, y, z] (the force on the lander, in B), max_thrust_n and \
                   min_on_time_s";
    let Value::Array(a) = v.clone() else {
        return Err(top.error("thrusters", &v, allowed));
    };
    if a.len() > MAX_THRUSTERS {
        return Err(top.error(
            "thrusters",
            &v,
            &format!("at most {MAX_THRUSTERS} thrusters"),
        ));
    }
    let mut out = Vec::new();
    for (i, t) in a.into_iter().enumerate() {
        let Value::Table(t) = t else {
            return Err(top.error("thrusters", &v, allowed));
        };
        out.push(read_thruster(&mut Reader::new(
            &format!("thrusters[{i}]"),
            t,
        ))?);
    }
    Ok(out)
}

/// `r`, to read a key every thruster gives, or the error that it is missing.
fn need<'r>(r: &'r mut Reader, key: &'static str) -> Result<&'r mut Reader, ScenarioError> {
    if r.has(key) {
        return Ok(r);
    }
    Err(ScenarioError::Invalid {
        key: r.key_path(key),
        value: "nothing".into(),
        allowed: "a value: every thruster gives position_m, direction, max_thrust_n and \
                  min_on_time_s"
            .into(),
    })
}

/// The most thrusters a scenario may have.
pub const MAX_THRUSTERS: usize = 32;
