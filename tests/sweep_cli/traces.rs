//! Rows against traces: sweep rows hold the inputs and outcomes of `touchdown trace` of
//! their samples, traced from the scenario and seed and from the sweep file alone.

use super::{ROUGH, SweepFile, check_sweep_file, read_sweep, sweep};
use crate::common::{Run, SHORT, TempDir, touchdown};
use std::collections::BTreeSet;
use touchdown::reference::Outcome;
use touchdown::scenario::INPUT_FIELDS;

/// The `terrain_tile N (offset U m, V m)` line of a trace's printout, as printed.
fn trace_terrain(run: &Run) -> Option<(u32, String, String)> {
    let line = run
        .stdout
        .lines()
        .find_map(|l| l.trim_start().strip_prefix("terrain_tile "))?;
    let parse = || -> Option<(u32, String, String)> {
        let (tile, rest) = line.trim_start().split_once(" (offset ")?;
        let (u, v) = rest.strip_suffix(" m)")?.split_once(" m, ")?;
        Some((tile.parse().ok()?, u.to_string(), v.to_string()))
    };
    Some(parse().unwrap_or_else(|| panic!("cannot read the terrain line {line:?} of {run}")))
}

/// Checks that sweep rows hold the inputs and the outcome of `touchdown trace --sample i`
/// with the flags `source` (`--scenario F --seed S`, or `--sweep FILE`), and that the trace
/// stores the scenario text the sweep stored (seed included).
fn check_rows_against_traces(dir: &TempDir, source: &[&str], seed: &str, file: &SweepFile) {
    let rows = file.rows() as u64;
    let outcomes = file.strings("outcome");
    // The first samples, the last one, and the first of every outcome that occurs.
    let mut indices: BTreeSet<u64> = [0, 1, 2, rows - 1].into();
    for o in Outcome::ALL {
        if let Some(i) = outcomes.iter().position(|x| x == o.name()) {
            indices.insert(i as u64);
        }
    }
    let sample_seeds = file.u64s("sample_seed");
    let tiles = file.u32s("terrain_tile");
    let (offset_u, offset_v) = (
        file.f64s("terrain_offset_u_m"),
        file.f64s("terrain_offset_v_m"),
    );
    let inputs: Vec<Vec<f64>> = INPUT_FIELDS.iter().map(|(n, _)| file.f64s(n)).collect();

    let mut failures = Vec::new();
    for i in indices {
        let k = i as usize;
        let index = i.to_string();
        let out = format!("trace-{i}.arrow");
        let args = [
            &["trace"],
            source,
            &["--sample", &index, "--every", "1e9", "--out", &out],
        ]
        .concat();
        let run = touchdown(dir.path(), &args);
        run.assert_ok();
        let trace = read_sweep(&dir.join(&out)); // an Arrow IPC file too
        let meta = |key: &str| {
            trace
                .meta(key)
                .unwrap_or_else(|| panic!("trace {i} has no {key}"))
                .to_string()
        };
        let mut problems = Vec::new();
        if meta("touchdown.sample") != index || meta("touchdown.seed") != seed {
            problems.push(format!(
                "trace of sample {} of seed {}",
                meta("touchdown.sample"),
                meta("touchdown.seed")
            ));
        }
        if meta("touchdown.sample_seed") != sample_seeds[k].to_string() {
            problems.push(format!(
                "sample_seed: row {}, trace {}",
                sample_seeds[k],
                meta("touchdown.sample_seed")
            ));
        }
        for ((name, _), column) in INPUT_FIELDS.iter().zip(&inputs) {
            let text = meta(&format!("touchdown.input.{name}"));
            let traced: f64 = text
                .parse()
                .unwrap_or_else(|_| panic!("trace {i}: {name} = {text:?} is not a number"));
            if traced.to_bits() != column[k].to_bits() {
                problems.push(format!("{name}: row {:?}, trace {traced:?}", column[k]));
            }
        }
        if trace.meta("touchdown.scenario") != file.meta("touchdown.scenario") {
            problems.push(format!(
                "scenario text: sweep {:?}, trace {:?}",
                file.meta("touchdown.scenario"),
                trace.meta("touchdown.scenario")
            ));
        }
        if meta("touchdown.outcome") != outcomes[k] {
            problems.push(format!(
                "outcome: row (kernel) {}, trace (reference) {}",
                outcomes[k],
                meta("touchdown.outcome")
            ));
        }
        // The trace prints the terrain tile and offsets (to the mm) on rough terrain only.
        let row_terrain = (
            tiles[k],
            format!("{:.3}", offset_u[k]),
            format!("{:.3}", offset_v[k]),
        );
        match trace_terrain(&run) {
            Some(t) if t != row_terrain => {
                problems.push(format!("terrain: row {row_terrain:?}, trace {t:?}"));
            }
            None if (tiles[k], offset_u[k], offset_v[k]) != (0, 0.0, 0.0) => {
                problems.push(format!("terrain: row {row_terrain:?} on a flat surface"));
            }
            _ => {}
        }
        if !problems.is_empty() {
            failures.push(format!(
                "sample {i}:\n    {}\n{run}",
                problems.join("\n    ")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "rows of the sweep (seed {seed}) differ from their traces `touchdown trace {}`:\n\n{}",
        source.join(" "),
        failures.join("\n\n")
    );
}

#[test]
fn rows_hold_the_inputs_and_outcomes_of_their_traces() {
    let dir = TempDir::new("sweep-vs-trace");
    for (name, text, seed, samples) in [
        ("short.toml", SHORT, "5", "3000"),
        ("rough.toml", ROUGH, "9", "2000"),
    ] {
        dir.write(name, text);
        let out = format!("{name}.arrow");
        let (_, s) = sweep(
            &dir,
            &[
                "--scenario",
                name,
                "--seed",
                seed,
                "--samples",
                samples,
                "--out",
                &out,
            ],
        );
        let file = check_sweep_file(&dir.join(&out), &s, seed.parse().unwrap(), text);
        // Traced from the scenario and seed, and from the sweep file alone.
        check_rows_against_traces(&dir, &["--scenario", name, "--seed", seed], seed, &file);
        check_rows_against_traces(&dir, &["--sweep", &out], seed, &file);
    }
}
