//! Refusing a control loop that cannot work, before any work: checked against the
//! scenario's thrusters (through their allocation) and the laws this program registers.

use super::allocation::{Allocation, PURE_TOLERANCE};
use super::laws::{registered, registered_names};
use crate::scenario::{Control, Scenario, ScenarioError, Start};

/// Refuses a control loop that cannot work: one without thrusters or without a law, a
/// hold-down the thrusters cannot push pure along `-Z_B` (or not as hard as asked), an
/// attitude hold they cannot turn about `X_B` and `Y_B`, a descent they cannot brake, or a
/// descent start without a descent law (and the other way round).
pub fn check(s: &Scenario) -> Result<(), ScenarioError> {
    check_descent_start(s)?;
    let Some(c) = &s.control else {
        return Ok(());
    };
    check_law(s, c)?;
    check_timing(s, c)?;
    check_thrust(s, c)
}

/// An invalid value of `key`.
fn invalid(key: &str, value: String, allowed: String) -> ScenarioError {
    ScenarioError::Invalid {
        key: key.to_string(),
        value,
        allowed,
    }
}

/// Refuses a descent start without a descent law, and the other way round.
fn check_descent_start(s: &Scenario) -> Result<(), ScenarioError> {
    let descent = s.control.as_ref().and_then(|c| c.descent);
    let descent_start = s.initial.start == Start::Descent;
    if descent_start && descent.is_none() {
        return Err(invalid(
            "initial.start",
            "\"descent\"".into(),
            "\"touchdown\" or \"release\", unless [control.descent] gives the descent and \
             its law (with [[thrusters]] to brake it)"
                .into(),
        ));
    }
    if descent.is_some() && !descent_start {
        return Err(invalid(
            "control.descent",
            "a descent law".into(),
            "initial.start = \"descent\" with it: the law brakes a descent that the sample \
             starts in"
                .into(),
        ));
    }
    Ok(())
}

/// Refuses a loop without thrusters, without a law, with both a law of the user's and the
/// built-in ones, or naming a law this program does not register.
fn check_law(s: &Scenario, c: &Control) -> Result<(), ScenarioError> {
    if s.thrusters.is_empty() {
        return Err(invalid(
            "control",
            "a control loop".into(),
            "[[thrusters]] for it to fire: a control loop without thrusters does nothing".into(),
        ));
    }
    if let Some(name) = &c.law {
        if registered(name).is_none() {
            let known: Vec<String> = registered_names()
                .iter()
                .map(|n| format!("{n:?}"))
                .collect();
            return Err(invalid(
                "control.law",
                format!("{name:?}"),
                if known.is_empty() {
                    "the name of a law registered by the program running the sweep; this \
                     program registers none (the `touchdown` binary has only the built-in \
                     laws: a program that embeds touchdown registers its own, see \
                     examples/user_law.rs)"
                        .into()
                } else {
                    format!(
                        "one of the laws this program registers: {}",
                        known.join(", ")
                    )
                },
            ));
        }
        if c.hold_down.is_some() || c.attitude_hold.is_some() || c.descent.is_some() {
            return Err(invalid(
                "control.law",
                format!("{name:?}"),
                "either a law of your own or the built-in laws ([control.hold_down], \
                 [control.attitude_hold], [control.descent]), not both: your law commands \
                 in every phase"
                    .into(),
            ));
        }
    } else if c.hold_down.is_none() && c.attitude_hold.is_none() && c.descent.is_none() {
        return Err(invalid(
            "control",
            "no law".into(),
            "a law for the loop to run: [control.hold_down], [control.attitude_hold], \
             [control.descent] or law = \"NAME\" (one of your own)"
                .into(),
        ));
    }
    Ok(())
}

/// Refuses settings that defeat themselves: a thruster whose shortest firing is longer
/// than a control period (commanded one period at a time, it never fires), and a hold-down
/// that cannot end before `simulation.t_max_s` (the run would end under thrust).
fn check_timing(s: &Scenario, c: &Control) -> Result<(), ScenarioError> {
    let period = 1.0 / c.rate_hz;
    for (i, t) in s.thrusters.iter().enumerate() {
        // A relative margin for the rounding of 1 / rate_hz.
        if t.min_on_time_s > period * (1.0 + 1e-12) {
            return Err(invalid(
                &format!("thrusters[{i}].min_on_time_s"),
                format!("{} s", t.min_on_time_s),
                format!(
                    "at most one control period, 1 / control.rate_hz = {period} s: commanded \
                     one period at a time, a thruster whose shortest firing is longer never \
                     fires"
                ),
            ));
        }
    }
    if let Some(h) = &c.hold_down {
        let longest = h.duration_s.support().1;
        let t_max = s.simulation.t_max_s;
        if longest >= t_max {
            return Err(invalid(
                "control.hold_down.duration_s",
                format!("up to {longest} s"),
                format!(
                    "less than simulation.t_max_s = {t_max} s: a hold-down begins at the first \
                     contact, so one this long is still pushing when the run ends, and the \
                     outcome is decided under thrust"
                ),
            ));
        }
    }
    Ok(())
}

/// Refuses a descent the thrusters cannot brake, a hold-down they cannot push pure along
/// `-Z_B` (or not as hard as asked), an attitude hold they cannot turn about `X_B` and `Y_B`.
fn check_thrust(s: &Scenario, c: &Control) -> Result<(), ScenarioError> {
    let allocation = Allocation::new(&s.thrusters);
    if let Some(d) = &c.descent {
        // Braking at `braking_m_s2` against gravity, upright: along +Z_B, pure.
        let braking = d.braking_m_s2.support().1;
        let need = s.lander.mass_kg * (s.gravity_m_s2 + braking);
        let capacity = allocation.unit[4]
            .as_ref()
            .map_or(0.0, |u| 1.0 / u.iter().copied().fold(0.0, f64::max));
        if capacity < need {
            return Err(invalid(
                "control.descent.braking_m_s2",
                format!("up to {braking}"),
                format!(
                    "a braking the thrusters can give: against gravity it needs mass_kg \
                     (gravity_m_s2 + braking_m_s2) = {need:.4} N along +Z_B through the CG, \
                     and they give at most {capacity:.4} N so (thrusters pushing along +Z_B, \
                     placed symmetrically about the CG)"
                ),
            ));
        }
    }
    if c.descent.is_some_and(|d| d.null_lateral_velocity) && !(0..4).all(|k| allocation.can(k)) {
        return Err(invalid(
            "control.descent.null_lateral_velocity",
            "true".into(),
            "thrusters that push pure both ways along X_B and Y_B (for example, four \
             pushing along +-X_B and +-Y_B through the CG) to null the velocity along the \
             surface, or false"
                .into(),
        ));
    }
    if let Some(h) = &c.hold_down {
        let most = h.thrust_n.support().1;
        if most > 0.0 {
            let Some(unit) = &allocation.unit[5] else {
                return Err(invalid(
                    "control.hold_down",
                    "[[thrusters]]".into(),
                    "thrusters that together push along -Z_B through the CG with no torque \
                     (for example, several pushing along -Z_B placed symmetrically about \
                     the CG)"
                        .into(),
                ));
            };
            // The unit allocation is shrunk by the ridge of `nnls` (about 1e-9 of it), so
            // the capacity it implies is that much short: the full thrust of the cluster is
            // allowed within `PURE_TOLERANCE`.
            let capacity = 1.0 / unit.iter().copied().fold(0.0, f64::max);
            if most > capacity * (1.0 + PURE_TOLERANCE) {
                return Err(invalid(
                    "control.hold_down.thrust_n",
                    format!("up to {most} N"),
                    format!(
                        "at most {capacity:.4} N: the most the thrusters give along -Z_B \
                         through the CG with no torque"
                    ),
                ));
            }
        }
    }
    if c.attitude_hold.is_some() && !(6..10).all(|k| allocation.can(k)) {
        return Err(invalid(
            "control.attitude_hold",
            "[[thrusters]]".into(),
            "thrusters that give a pure torque both ways about X_B and Y_B (couples: pairs \
             of opposite forces on either side of the CG)"
                .into(),
        ));
    }
    Ok(())
}
