//! The `[[thrusters]]` array and the `[propulsion]` table: where the thrusters sit, how
//! hard they push, and what their propellant gives (MODEL.md section 7).

use super::error::ScenarioError;
use super::reader::Reader;
use toml::Value;

/// One thruster, fixed in B.
#[derive(Debug, Clone, PartialEq)]
pub struct Thruster {
    /// Where its force acts, in B (the CG at the origin), m.
    pub position_m: [f64; 3],
    /// Unit direction of the force it puts on the lander, in B (its plume points the
    /// other way).
    pub direction: [f64; 3],
    /// Thrust when on, N.
    pub max_thrust_n: f64,
    /// Shortest firing (the minimum impulse bit is this times the thrust), s: on-times are
    /// whole multiples of it.
    pub min_on_time_s: f64,
}

/// The propellant and the thrusters' sampled errors.
#[derive(Debug, Clone, PartialEq)]
pub struct Propulsion {
    /// Specific impulse, s: propellant used is the thrust's integral over `isp g0`.
    pub isp_s: f64,
    /// Standard deviation of each thruster's thrust magnitude, as a fraction of its
    /// `max_thrust_n`, drawn per sample and thruster (normal, truncated at 3 sd).
    pub thrust_error_sd: f64,
    /// Standard deviation of each thruster's misalignment about each of the two axes
    /// across its direction, drawn per sample and thruster (normal, truncated at 3 sd), deg.
    pub misalignment_sd_deg: f64,
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
        let mut r = Reader::new(&format!("thrusters[{i}]"), t);
        let need = |r: &mut Reader, k: &'static str| -> Result<Value, ScenarioError> {
            r.take(k).ok_or_else(|| ScenarioError::Invalid {
                key: r.key_path(k),
                value: "nothing".into(),
                allowed: "a value: every thruster gives position_m, direction, max_thrust_n \
                          and min_on_time_s"
                    .into(),
            })
        };
        let p = need(&mut r, "position_m")?;
        let position_m = r.vec3("position_m", &p)?;
        let d = need(&mut r, "direction")?;
        let direction = r.vec3("direction", &d)?;
        let n = direction.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n < 1e-9 {
            return Err(r.error("direction", &d, "a non-zero vector [x, y, z] in B"));
        }
        let direction = direction.map(|x| x / n);
        let m = need(&mut r, "max_thrust_n")?;
        let max_thrust_n = positive(&r, "max_thrust_n", &m)?;
        let m = need(&mut r, "min_on_time_s")?;
        let min_on_time_s = positive(&r, "min_on_time_s", &m)?;
        r.finish()?;
        out.push(Thruster {
            position_m,
            direction,
            max_thrust_n,
            min_on_time_s,
        });
    }
    Ok(out)
}

fn positive(r: &Reader, key: &str, v: &Value) -> Result<f64, ScenarioError> {
    let x = r.number(key, v)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(r.error(key, v, "a number greater than 0"))
    }
}

/// The most thrusters a scenario may have.
pub const MAX_THRUSTERS: usize = 32;

pub(super) fn read_propulsion(
    top: &mut Reader,
    d: &Propulsion,
) -> Result<Propulsion, ScenarioError> {
    let Some(mut r) = top.table("propulsion")? else {
        return Ok(d.clone());
    };
    let isp_s = r.positive("isp_s", d.isp_s)?;
    let thrust_error_sd = r.f64_where(
        "thrust_error_sd",
        d.thrust_error_sd,
        "a fraction from 0 to 0.3",
        |x| (0.0..=0.3).contains(&x),
    )?;
    let misalignment_sd_deg = r.f64_where(
        "misalignment_sd_deg",
        d.misalignment_sd_deg,
        "an angle from 0 to 10 deg",
        |x| (0.0..=10.0).contains(&x),
    )?;
    r.finish()?;
    Ok(Propulsion {
        isp_s,
        thrust_error_sd,
        misalignment_sd_deg,
    })
}
