//! A table of inputs read and checked (`InputTable::read`), attached to the scenario a
//! sweep runs, and reattached to a sweep file's scenario, held to the same bytes.

use super::role::role;
use super::sha256::sha256_hex;
use super::sink::Sink;
use super::source::Source;
use crate::scenario::{Design, INPUT_FIELDS, InputTable, METADATA_KEYS, Parameter, Scenario};
use anyhow::{anyhow, bail};
use std::path::{Path, PathBuf};
use std::sync::Arc;

impl InputTable {
    /// Reads the table at `path` for a sweep of `scenario`, checking every value.
    pub fn read(path: &Path, keep_columns: bool, scenario: &Scenario) -> anyhow::Result<Self> {
        let bytes = std::fs::read(path)
            .map_err(|e| anyhow!("cannot read the input table {}: {e}", path.display()))?;
        let sha256 = sha256_hex(&bytes);
        let source = Source::parse(path, bytes)?;
        let names = source.names();
        let mut roles = Vec::with_capacity(names.len());
        for (j, name) in names.iter().enumerate() {
            if names[..j].contains(name) {
                bail!("{}: column {name} appears twice", path.display());
            }
            roles.push(role(name, keep_columns, scenario, path)?);
        }
        let mut sinks: Vec<Sink> = roles.iter().map(|r| Sink::new(*r)).collect();
        let (rows, kept) = source.fill(&mut sinks, path)?;
        if rows == 0 {
            bail!("{}: the table has no rows", path.display());
        }
        let mut table = InputTable {
            path: path.to_path_buf(),
            format: source.format(),
            sha256,
            rows: rows as u64,
            columns: names.clone(),
            keep_columns,
            values: std::array::from_fn(|_| None),
            sample_seed: None,
            terrain_tile: None,
            terrain_offset_m: [None, None],
            kept,
        };
        for sink in sinks {
            match sink {
                Sink::Value(k, v) => table.values[k] = Some(v),
                Sink::Seed(v) => table.sample_seed = Some(v),
                Sink::Tile(v) => table.terrain_tile = Some(v),
                Sink::Offset(j, v) => table.terrain_offset_m[j] = Some(v),
                Sink::Sample | Sink::Kept => {}
            }
        }
        table.check_terrain(scenario)?;
        Ok(table)
    }

    /// The terrain columns against the surface the sweep will have: a tile the rough
    /// surface has and an offset inside it, or 0 where the surface is flat.
    fn check_terrain(&self, scenario: &Scenario) -> anyhow::Result<()> {
        let rough = &scenario.surface.roughness;
        let k = INPUT_FIELDS.len() + Parameter::RmsHeightM as usize;
        let largest = self.values[k].as_ref().map_or_else(
            || scenario.rms_height_max_m(),
            |c| c.iter().copied().fold(0.0, f64::max),
        );
        let where_ = |row: usize, name: &str, what: String| {
            anyhow!("{}: row {row}, column {name}: {what}", self.path.display())
        };
        if let Some(c) = &self.terrain_tile {
            for (row, &t) in c.iter().enumerate() {
                if largest == 0.0 && t != 0 {
                    return Err(where_(
                        row,
                        "terrain_tile",
                        format!("{t}, but the surface is flat (its only tile is 0)"),
                    ));
                }
                if largest > 0.0 && t as usize >= rough.tiles {
                    return Err(where_(
                        row,
                        "terrain_tile",
                        format!(
                            "{t}, but the surface has tiles 0 to {} (surface.roughness.tiles)",
                            rough.tiles - 1
                        ),
                    ));
                }
            }
        }
        for (j, name) in ["terrain_offset_u_m", "terrain_offset_v_m"]
            .iter()
            .enumerate()
        {
            let Some(c) = &self.terrain_offset_m[j] else {
                continue;
            };
            for (row, &x) in c.iter().enumerate() {
                if largest == 0.0 && x != 0.0 {
                    return Err(where_(
                        row,
                        name,
                        format!("{x}, but the surface is flat (the offset is 0)"),
                    ));
                }
                if largest > 0.0 && !(0.0..rough.tile_size_m).contains(&x) {
                    return Err(where_(
                        row,
                        name,
                        format!(
                            "{x} is outside the tile: values from 0 up to, not including, \
                             {} m (surface.roughness.tile_size_m)",
                            rough.tile_size_m
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Reads the table at `path` and makes `scenario` run it: sample `i` takes row `i`'s
/// values. A parameter the table gives becomes one the scenario draws per sample, over
/// the range of the table's values joined to the scenario's own distribution's if it has
/// one (the terrain is built for the largest roughness of that range, early sliding decided
/// at its worst corner), so that a table of a sweep's own draws runs as that sweep did.
pub fn attach(scenario: &mut Scenario, path: &Path, keep_columns: bool) -> anyhow::Result<()> {
    if scenario.design == Design::SobolIndices {
        bail!(
            "--inputs {}: the scenario's design is \"sobol-indices\", whose samples come in \
             blocks made from each other; a table gives each sample its own row (use design \
             \"independent\" or \"sobol-sequence\")",
            path.display()
        );
    }
    let table = InputTable::read(path, keep_columns, scenario)?;
    for p in Parameter::ALL {
        let k = INPUT_FIELDS.len() + p as usize;
        if let Some(c) = &table.values[k] {
            let (min, max) = c
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            // Where the scenario draws it already and the table stays within its
            // distribution's range, the distribution stays: nothing that depends on it
            // changes (the tiles' roughness, the worst corner, a grid's digits), and the
            // table's values run as the scenario's own.
            scenario.sampled[p as usize] = match scenario.sampled[p as usize] {
                Some(d) if d.support().0 <= min && max <= d.support().1 => Some(d),
                Some(d) => Some(crate::scenario::Dist::Uniform {
                    min: d.support().0.min(min),
                    max: d.support().1.max(max),
                }),
                None => Some(crate::scenario::Dist::Uniform { min, max }),
            };
        }
    }
    scenario.table = Some(Arc::new(table));
    Ok(())
}

/// Gives `scenario` the table of inputs that the run whose file `file` has metadata
/// `meta` ran with, if any: the table at `given` (the command line's `--inputs`) or where
/// the metadata says it was, holding it to the same bytes (SHA-256) and way of reading.
pub fn reattach(
    scenario: &mut Scenario,
    meta: &arrow_schema::Metadata,
    given: Option<&Path>,
    file: &Path,
) -> anyhow::Result<()> {
    let Some(sha256) = meta.get(METADATA_KEYS[1]) else {
        if let Some(path) = given {
            bail!(
                "--inputs {}: {} did not run a table of inputs",
                path.display(),
                file.display()
            );
        }
        return Ok(());
    };
    let stored = meta.get(METADATA_KEYS[0]).map_or("", String::as_str);
    let path = given.map_or_else(|| PathBuf::from(stored), Path::to_path_buf);
    if given.is_none() && !path.exists() {
        bail!(
            "{} ran the table of inputs {stored}, which is not there: give it with --inputs \
             (its SHA-256 is {sha256})",
            file.display()
        );
    }
    let keep = meta.get(METADATA_KEYS[4]).is_some_and(|v| v == "true");
    attach(scenario, &path, keep)?;
    let table = scenario.table.as_ref().expect("attached");
    if &table.sha256 != sha256 {
        bail!(
            "{} is not the table of inputs {} ran: its SHA-256 is {}, the sweep's {sha256}",
            path.display(),
            file.display(),
            table.sha256
        );
    }
    Ok(())
}
