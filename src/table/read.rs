//! A table of inputs read and checked (`read`), attached to the scenario a
//! sweep runs, and reattached to a sweep file's scenario, held to the same bytes.

use super::check::check;
use super::role::{Role, role};
use super::rows::FileRows;
use super::sha256::file_sha256;
use super::source::{Kind, head};
use crate::scenario::{
    Design, FIRST_LAW_VALUE, FIRST_STATE_VALUE, INPUT_FIELDS, InputTable, METADATA_KEYS, Parameter,
    Scenario, VALUES,
};
use anyhow::bail;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A table read and checked, and the least and greatest value of each of its value
/// columns.
type Read = (InputTable, [Option<(f64, f64)>; VALUES]);

/// Reads the table at `path` for a sweep of `scenario`, checking every value, holding
/// none: its head (the columns' names, each refused before any row is read if the sweep
/// has no use for it), its bytes (their SHA-256, and a CSV file's text), then its cells.
/// The sweep reads its rows again, block by block, as it goes (`FileRows`).
fn read(path: &Path, keep_columns: bool, scenario: &Scenario) -> anyhow::Result<Read> {
    let head = head(path)?;
    let names = head.names.clone();
    let mut seen = std::collections::HashSet::with_capacity(names.len());
    let mut roles: Vec<Role> = Vec::with_capacity(names.len());
    for name in &names {
        if !seen.insert(name.as_str()) {
            bail!("{}: column {name} appears twice", path.display());
        }
        roles.push(role(name, keep_columns, scenario, path)?);
    }
    let sha256 = file_sha256(path, head.kind == Kind::Csv)?;
    let checked = check(path, &head, &roles, scenario)?;
    let format = head.kind.format();
    let source = FileRows::new(
        path,
        head,
        checked.marks,
        checked.rows,
        &roles,
        &checked.csv_types,
    );
    let table = InputTable {
        path: path.to_path_buf(),
        format,
        sha256,
        rows: checked.rows,
        columns: names,
        keep_columns,
        source: Box::new(source),
    };
    Ok((table, checked.ranges))
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
    let (table, ranges) = read(path, keep_columns, scenario)?;
    for p in Parameter::ALL {
        let k = INPUT_FIELDS.len() + p as usize;
        if let Some((min, max)) = ranges[k] {
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
    if let Some(state) = scenario.initial.touchdown.as_mut() {
        // The touchdown state the table gives, drawn per sample as its columns say.
        for (j, d) in state.iter_mut().enumerate() {
            if let Some((min, max)) = ranges[FIRST_STATE_VALUE + j] {
                let (lo, hi) = d.support();
                if !(lo <= min && max <= hi && !matches!(d, crate::scenario::Dist::Fixed(_))) {
                    *d = crate::scenario::Dist::Uniform {
                        min: lo.min(min),
                        max: hi.max(max),
                    };
                }
            }
        }
    }
    widen_laws(scenario, &ranges, path)?;
    scenario.table = Some(Arc::new(table));
    Ok(())
}

/// A law parameter the table gives, as a parameter: its distribution in the scenario
/// widened to the table's range where it does not hold it, so that the checks of the
/// control loop (`control::check`: a hold-down thrust the thrusters give, a hold-down
/// shorter than the run...) hold the table's values to what they hold the scenario's.
fn widen_laws(
    scenario: &mut Scenario,
    ranges: &[Option<(f64, f64)>; VALUES],
    path: &Path,
) -> anyhow::Result<()> {
    let Some(control) = scenario.control.as_mut() else {
        return Ok(());
    };
    for (j, dist) in control.parameters_mut().into_iter().enumerate() {
        if let (Some(d), Some((min, max))) = (dist, ranges[FIRST_LAW_VALUE + j]) {
            let (lo, hi) = d.support();
            if !(lo <= min && max <= hi) {
                *d = crate::scenario::Dist::Uniform {
                    min: lo.min(min),
                    max: hi.max(max),
                };
            }
        }
    }
    crate::control::check(scenario).map_err(|e| {
        anyhow::anyhow!(
            "--inputs {}: with the table's values of the control laws' parameters, {e}",
            path.display()
        )
    })
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
