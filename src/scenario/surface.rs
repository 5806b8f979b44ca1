//! The `[surface]` table and its `[surface.roughness]`: the contact law and the terrain.

use super::error::ScenarioError;
use super::inputs::{Sampled, read_parameter};
use super::reader::table;
use super::regolith::{Regolith, read_regolith};
use super::rocks::{Rocks, read_rocks};

/// What the ground under the footpads is (MODEL.md section 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceKind {
    /// The elastic plane: a spring-damper at every footpad (the default).
    Elastic,
    /// Regolith that gives way: `[surface.regolith]` (MODEL.md section 5.1).
    Regolith,
}

impl SurfaceKind {
    /// The word of each kind in a scenario file.
    pub const WORDS: [(&'static str, SurfaceKind); 2] = [
        ("elastic", SurfaceKind::Elastic),
        ("regolith", SurfaceKind::Regolith),
    ];
}

table! {
    /// Gaussian-smoothed random terrain (MODEL.md section 4).
    #[derive(Debug, Clone, PartialEq)]
    pub struct Roughness;
    fn read_roughness(r, sampled: &mut Sampled) with key {
        /// RMS height of the field; 0 means a flat plane.
        rms_height_m: f64 = read_parameter(r, key, sampled)?,
        /// Spacing of the grid's nodes.
        node_spacing_m: f64 = r.positive(key)?,
        /// Standard deviation of the Gaussian smoothing kernel.
        smoothing_length_m: f64 = r.non_negative(key)?,
        /// Side of one square, periodic tile.
        tile_size_m: f64 = r.f64_where(
            key,
            &format!("a tile of 4 to 4096 nodes per side at node_spacing_m = {node_spacing_m} m"),
            |x| (4.0..=4096.0).contains(&(x / node_spacing_m).round()),
        )?,
        /// Number of precomputed tiles; each sample draws one and a random offset.
        tiles: usize = {
            let tiles: usize = r.integer(key, 1, 1024)?;
            let nodes = (tile_size_m / node_spacing_m).round();
            if nodes * nodes * tiles as f64 > 64.0e6 {
                return Err(ScenarioError::Invalid {
                    key: r.key_path(key),
                    value: tiles.to_string(),
                    allowed: format!(
                        "at most 64 million terrain nodes in all ({nodes} x {nodes} per tile)"
                    ),
                });
            }
            tiles
        },
    }
}

table! {
    /// The surface and the contact law (MODEL.md sections 4, 5, 10).
    #[derive(Debug, Clone, PartialEq)]
    pub struct Surface;
    fn read_surface(r, sampled: &mut Sampled) with key {
        /// What the ground is: `"elastic"` or `"regolith"`.
        kind: SurfaceKind = r.or(key, "elastic").word(key, &SurfaceKind::WORDS)?,
        /// Normal contact stiffness per leg.
        stiffness_n_per_m: f64 = read_parameter(r, key, sampled)?,
        /// Normal contact damping per leg.
        damping_n_s_per_m: f64 = read_parameter(r, key, sampled)?,
        /// Coulomb friction coefficient.
        friction_coefficient: f64 = read_parameter(r, key, sampled)?,
        /// Stiffness of the stick-slip tangential spring.
        friction_stiffness_n_per_m: f64 = r.positive(key)?,
        /// Damping of the stick-slip tangential spring.
        friction_damping_n_s_per_m: f64 = r.non_negative(key)?,
        /// The terrain, `[surface.roughness]`.
        roughness: Roughness = r.section(key, |t| read_roughness(t, sampled))?,
        /// The rocks, `[surface.rocks]` (none where its abundance is 0, the default).
        rocks: Rocks = r.section(key, |t| read_rocks(t, sampled))?,
        /// The soil, `[surface.regolith]`, with `kind = "regolith"` (its defaults where the
        /// file leaves the table out); `None` on the elastic plane.
        regolith: Option<Regolith> = match kind {
            SurfaceKind::Regolith => Some(r.section(key, |t| read_regolith(t, sampled))?),
            SurfaceKind::Elastic => match r.take(key) {
                None => None,
                Some(v) => {
                    return Err(r.error(
                        key,
                        &v,
                        "no [surface.regolith] table unless surface.kind = \"regolith\"",
                    ));
                }
            },
        },
    }
}
