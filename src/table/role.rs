//! What a column of the user's table is to the sweep: a value (an input, a parameter or a
//! control law's parameter), the seed, the terrain, the sample index or a column passed
//! through; result columns refused.

use crate::scenario::{
    FALL_INPUTS, FIRST_LAW_VALUE, FIRST_STATE_VALUE, Geometry, INPUT_FIELDS, Parameter, Scenario,
    Start, VALUES, value_key, value_name,
};
use anyhow::{anyhow, bail};
use std::path::Path;

/// What a column of the table is to the sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Role {
    /// Value `k` of a sample (`Sample::values`).
    Value(usize),
    Seed,
    Tile,
    /// Terrain offset, downhill (0) or cross-slope (1).
    Offset(usize),
    /// The sample index: it must be the row's.
    Sample,
    /// Passed through to the output.
    Kept,
}

/// The role of column `name` in a sweep of `scenario`; refuses a result column, a
/// parameter the scenario cannot take per sample, and (without `keep`) an unknown column.
pub(super) fn role(
    name: &str,
    keep: bool,
    scenario: &Scenario,
    path: &Path,
) -> anyhow::Result<Role> {
    if let Some(k) = (0..VALUES).find(|&k| value_name(k) == name) {
        if k >= FIRST_STATE_VALUE {
            if scenario.initial.touchdown.is_none() {
                bail!(
                    "{}: column {name} ({}): the scenario gives no touchdown state (no \
                     initial.normal_speed_m_s with initial.start = \"touchdown\")",
                    path.display(),
                    value_key(k)
                );
            }
        } else if k >= FIRST_LAW_VALUE {
            let law = k - FIRST_LAW_VALUE;
            let given = scenario
                .control
                .as_ref()
                .is_some_and(|c| c.parameters()[law].is_some());
            if !given {
                let key = value_key(k);
                let table = key.rsplit_once('.').map_or(key.as_str(), |(t, _)| t);
                bail!(
                    "{}: column {name} ({key}): the scenario has no [{table}], whose law \
                     this parameter belongs to",
                    path.display()
                );
            }
        } else if FALL_INPUTS.contains(&k) && scenario.initial.start == Start::State {
            bail!(
                "{}: column {name} ({}): the scenario gives the touchdown state \
                 (initial.normal_speed_m_s), which replaces the fall and the velocity errors",
                path.display(),
                value_key(k)
            );
        } else if k >= INPUT_FIELDS.len() {
            let p = Parameter::ALL[k - INPUT_FIELDS.len()];
            let refuse =
                |why: &str| anyhow!("{}: column {name} ({}): {why}", path.display(), p.key());
            match p {
                Parameter::CrushStrengthPsi if !scenario.damper.enabled => {
                    return Err(refuse(
                        "the scenario has damper.enabled = false, no cartridge to crush",
                    ));
                }
                Parameter::CrushStrengthPsi if scenario.damper.stages.len() > 1 => {
                    return Err(refuse(
                        "the scenario's damper has several stages (damper.stages): one crush \
                         strength per sample is for a single-stage cartridge",
                    ));
                }
                Parameter::MassKg | Parameter::CgHeightM | Parameter::GravityMS2
                    if scenario.control.is_some() =>
                {
                    return Err(refuse(
                        "not drawn per sample in a scenario with a control loop (its thrust \
                         limits and descent are planned for one lander)",
                    ));
                }
                Parameter::CgHeightM if matches!(scenario.lander.geometry, Geometry::Tips(_)) => {
                    return Err(refuse(
                        "the scenario places the footpads by lander.leg_tips_m, not by a CG \
                         height",
                    ));
                }
                _ => {}
            }
        }
        return Ok(Role::Value(k));
    }
    match name {
        "sample_seed" => return Ok(Role::Seed),
        "terrain_tile" => return Ok(Role::Tile),
        "terrain_offset_u_m" => return Ok(Role::Offset(0)),
        "terrain_offset_v_m" => return Ok(Role::Offset(1)),
        "sample" => return Ok(Role::Sample),
        _ => {}
    }
    if is_result_column(name) {
        bail!(
            "{}: column {name} is a result of a sweep, not one of its inputs: give the \
             input columns alone (or rename it to keep it with --keep-columns)",
            path.display()
        );
    }
    if keep {
        return Ok(Role::Kept);
    }
    bail!(
        "{}: unknown column {name}: the sweep's input columns are sample_seed, {}, \
         terrain_tile, terrain_offset_u_m and terrain_offset_v_m; --keep-columns passes other \
         columns through to the output",
        path.display(),
        (0..VALUES).map(value_name).collect::<Vec<_>>().join(", ")
    )
}

/// Whether `name` is a column that a sweep writes as a result (of any lander, with any
/// control loop); `sample` and `sample_seed` have roles of their own (`role`), and so have
/// the control laws' parameters, inputs among the control columns.
pub(super) fn is_result_column(name: &str) -> bool {
    const RESULTS: [&str; 13] = [
        "outcome",
        "decided_s",
        "steps",
        "final_tilt_deg",
        "max_tilt_deg",
        "displacement_m",
        "peak_acceleration_m_s2",
        "peak_acceleration_z_body_m_s2",
        "bounces",
        "first_contact_s",
        "max_penetration_m",
        "legs_bottomed",
        "limits_broken",
    ];
    const LEG_RESULTS: [&str; 11] = [
        "_peak_normal_force_n",
        "_stroke_m",
        "_absorbed_j",
        "_peak_axial_force_n",
        "_peak_axial_force_s",
        "_peak_side_force_n",
        "_peak_side_force_s",
        "_stroke_margin_m",
        "_bottomed",
        "_sinkage_m",
        "_soil_absorbed_j",
    ];
    let leg = name.strip_prefix("leg").is_some_and(|rest| {
        let digits = rest.chars().take_while(char::is_ascii_digit).count();
        digits > 0 && LEG_RESULTS.contains(&&rest[digits..])
    });
    RESULTS.contains(&name)
        || leg
        || crate::output::sweep::CONTROL_COLUMNS
            .iter()
            .any(|c| c.0 == name && !(0..VALUES).any(|k| value_name(k) == name))
}

#[cfg(test)]
mod tests {
    use super::is_result_column;

    #[test]
    fn result_columns_are_told_from_inputs() {
        for name in [
            "outcome",
            "leg3_stroke_m",
            "leg12_absorbed_j",
            "leg1_bottomed",
            "leg0_sinkage_m",
            "leg2_soil_absorbed_j",
            "limits_broken",
            "propellant_kg",
        ] {
            assert!(is_result_column(name), "{name}");
        }
        for name in [
            "slope_deg",
            "leg_count",
            "legs_stroke_m",
            "my_column",
            "hold_down_thrust_n",
        ] {
            assert!(!is_result_column(name), "{name}");
        }
    }
}
