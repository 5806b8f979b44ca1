//! The `[surface]` table and its `[surface.roughness]`: the contact law and the terrain.

use super::error::ScenarioError;
use super::inputs::{Parameter, Sampled, read_parameter};
use super::reader::Reader;

/// Gaussian-smoothed random terrain (MODEL.md section 4).
#[derive(Debug, Clone, PartialEq)]
pub struct Roughness {
    /// RMS height of the field; 0 means a flat plane.
    pub rms_height_m: f64,
    pub node_spacing_m: f64,
    /// Standard deviation of the Gaussian smoothing kernel.
    pub smoothing_length_m: f64,
    /// Side of one square, periodic tile.
    pub tile_size_m: f64,
    /// Number of precomputed tiles; each sample draws one and a random offset.
    pub tiles: usize,
}

/// The surface and the contact law (MODEL.md sections 4, 5, 10).
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    pub stiffness_n_per_m: f64,
    pub damping_n_s_per_m: f64,
    pub friction_coefficient: f64,
    /// Stiffness of the stick-slip tangential spring.
    pub friction_stiffness_n_per_m: f64,
    /// Damping of the stick-slip tangential spring.
    pub friction_damping_n_s_per_m: f64,
    pub roughness: Roughness,
}

pub(super) fn read_surface(
    top: &mut Reader,
    d: &Surface,
    sampled: &mut Sampled,
) -> Result<Surface, ScenarioError> {
    let Some(mut r) = top.table("surface")? else {
        return Ok(d.clone());
    };
    let stiffness_n_per_m = read_parameter(
        &mut r,
        Parameter::StiffnessNPerM,
        d.stiffness_n_per_m,
        true,
        sampled,
    )?;
    let damping_n_s_per_m = read_parameter(
        &mut r,
        Parameter::DampingNSPerM,
        d.damping_n_s_per_m,
        false,
        sampled,
    )?;
    let friction_coefficient = read_parameter(
        &mut r,
        Parameter::FrictionCoefficient,
        d.friction_coefficient,
        false,
        sampled,
    )?;
    let friction_stiffness_n_per_m =
        r.positive("friction_stiffness_n_per_m", d.friction_stiffness_n_per_m)?;
    let friction_damping_n_s_per_m =
        r.non_negative("friction_damping_n_s_per_m", d.friction_damping_n_s_per_m)?;
    let dr = &d.roughness;
    let roughness = match r.table("roughness")? {
        None => dr.clone(),
        Some(mut t) => {
            let rms_height_m = read_parameter(
                &mut t,
                Parameter::RmsHeightM,
                dr.rms_height_m,
                false,
                sampled,
            )?;
            let node_spacing_m = t.positive("node_spacing_m", dr.node_spacing_m)?;
            let smoothing_length_m = t.non_negative("smoothing_length_m", dr.smoothing_length_m)?;
            let tile_size_m = t.f64_where(
                "tile_size_m",
                dr.tile_size_m,
                &format!(
                    "a tile of 4 to 4096 nodes per side at node_spacing_m = {node_spacing_m} m"
                ),
                |x| (4.0..=4096.0).contains(&(x / node_spacing_m).round()),
            )?;
            let tiles = t.integer("tiles", dr.tiles as i64, 1, 1024)? as usize;
            let nodes = (tile_size_m / node_spacing_m).round();
            if nodes * nodes * tiles as f64 > 64.0e6 {
                return Err(ScenarioError::Invalid {
                    key: "surface.roughness.tiles".into(),
                    value: tiles.to_string(),
                    allowed: format!(
                        "at most 64 million terrain nodes in all ({nodes} x {nodes} per tile)"
                    ),
                });
            }
            t.finish()?;
            Roughness {
                rms_height_m,
                node_spacing_m,
                smoothing_length_m,
                tile_size_m,
                tiles,
            }
        }
    };
    r.finish()?;
    Ok(Surface {
        stiffness_n_per_m,
        damping_n_s_per_m,
        friction_coefficient,
        friction_stiffness_n_per_m,
        friction_damping_n_s_per_m,
        roughness,
    })
}
