//! The one reader of a trace file: its columns checked, and what its metadata says (the
//! scenario, the sample's own values, the outcome and its caption), for every picture of a
//! trace (`touchdown plot`, `animate`, `view`).

use crate::output::columns::Table;
use crate::scenario::{Dist, INPUT_FIELDS, Parameter, Sample, Scenario, value_name};
use anyhow::{anyhow, bail};
use glam::DVec3;
use std::path::Path;

/// The columns every trace has that a picture needs.
const BODY_COLUMNS: [&str; 8] = ["t_s", "x_m", "y_m", "z_m", "qw", "qx", "qy", "qz"];

/// A trace file read and checked: its rows, and the sample they are the motion of.
pub struct Trace {
    /// "sample N of seed S: OUTCOME at T s".
    pub about: String,
    /// The outcome's name, as the trace stores it.
    pub outcome: String,
    /// When the outcome was decided, s.
    pub decided_s: f64,
    /// The scenario stored in the trace, with its seed, and a table's parameters taken as
    /// drawn ones (`Scenario::sampled`).
    pub scenario: Scenario,
    /// The sample's values: the trace's own (a table's, where its sweep ran one).
    pub sample: Sample,
    /// The time of every row, s (finite and not decreasing).
    pub time: Vec<f64>,
    /// Legs with columns in the trace.
    pub legs: usize,
    /// Thrusters of the control loop with columns in the trace (0 without one).
    pub thrusters: usize,
    /// The trace's rows are every `every` steps (`touchdown trace --every`).
    pub every: u64,
    table: Table,
}

/// What a trace of every N steps leaves out, for a note to its user.
#[must_use]
pub fn sparse_note(trace: &Path, every: u64) -> Option<String> {
    (every > 1).then(|| {
        format!(
            "touchdown: note: {} holds one row every {every} steps (trace --every {every}): \
             the motion between rows is interpolated, and forces and firings between rows do \
             not show",
            trace.display()
        )
    })
}

/// Refuses a table that is not a trace of touchdown with rows and the columns of a body.
fn check_table(path: &Path, table: &Table) -> anyhow::Result<()> {
    match table.meta.get("touchdown.kind").map(String::as_str) {
        Some("trace") => {}
        Some(kind) => bail!(
            "{} is not a trace file of touchdown (it is a {kind} file; `touchdown trace \
             --sweep {} --sample I` writes the trace of its sample I)",
            path.display(),
            path.display()
        ),
        None => bail!("{} is not a trace file of touchdown", path.display()),
    }
    if table.rows < 2 {
        bail!(
            "{} holds {} rows: nothing moves",
            path.display(),
            table.rows
        );
    }
    for c in BODY_COLUMNS {
        table.column(c, path)?;
    }
    if let Some((name, c)) = table.columns.iter().find(|(_, c)| c.len() != table.rows) {
        bail!(
            "{}: column {name} has {} values in {} rows",
            path.display(),
            c.len(),
            table.rows
        );
    }
    Ok(())
}

/// Metadata entry `k` of the trace at `path`, or an error naming it.
fn meta<'a>(table: &'a Table, path: &Path, k: &str) -> anyhow::Result<&'a String> {
    table
        .meta
        .get(k)
        .ok_or_else(|| anyhow!("{}: no {k} in its metadata", path.display()))
}

/// Metadata entry `k` as a number.
fn number(table: &Table, path: &Path, k: &str) -> anyhow::Result<f64> {
    meta(table, path, k)?
        .parse()
        .map_err(|_| anyhow!("{}: {k} is not a number", path.display()))
}

/// The scenario (with its seed), the sample's index and the sample itself as the trace's
/// metadata stores them.
fn stored_sample(table: &Table, path: &Path) -> anyhow::Result<(Scenario, u64, Sample)> {
    let meta = |k: &str| meta(table, path, k);
    let number = |k: &str| number(table, path, k);
    let mut scenario = Scenario::from_toml(meta("touchdown.scenario")?)
        .map_err(|e| anyhow!("the scenario stored in {}: {e}", path.display()))?;
    scenario.seed = meta("touchdown.seed")?
        .parse()
        .map_err(|_| anyhow!("{}: its seed is not a whole number", path.display()))?;
    let index: u64 = meta("touchdown.sample")?
        .parse()
        .map_err(|_| anyhow!("{}: its sample is not a whole number", path.display()))?;
    // The trace's own values decide (a table's, where its sweep ran one): its inputs
    // and parameters, and its terrain tile and offset where it stores them (an older
    // trace: drawn again, the same for a sweep without a table).
    let mut drawn = crate::sampling::sample(&scenario, index);
    let mut values = drawn.values();
    for (k, v) in values.iter_mut().enumerate() {
        let kind = if k < INPUT_FIELDS.len() {
            "input"
        } else {
            "parameter"
        };
        let key = format!("touchdown.{kind}.{}", value_name(k));
        if k < 2 || table.meta.contains_key(&key) {
            *v = number(&key)?;
        }
    }
    drawn.set_values(values);
    if let Ok(tile) = meta("touchdown.terrain_tile") {
        drawn.terrain_tile = tile
            .parse()
            .map_err(|_| anyhow!("{}: its terrain tile is not a whole number", path.display()))?;
        drawn.terrain_offset_m = [
            number("touchdown.terrain_offset_u_m")?,
            number("touchdown.terrain_offset_v_m")?,
        ];
    }
    // A parameter unlike the scenario's (a table's) is taken per sample as a drawn one.
    for p in Parameter::ALL {
        let x = drawn.parameters[p as usize];
        if scenario.sampled[p as usize].is_none() && !x.is_nan() && x != scenario.parameter(p) {
            scenario.sampled[p as usize] = Some(Dist::Uniform { min: x, max: x });
        }
    }
    Ok((scenario, index, drawn))
}

impl Trace {
    /// Reads the trace file at `path`; refuses, saying why, a file that is missing, cut
    /// off, not a trace of touchdown, or holding no rows.
    pub fn read(path: &Path) -> anyhow::Result<Trace> {
        if !path.is_file() {
            bail!("{}: no such trace file", path.display());
        }
        let table = Table::read(path, |_| true)?;
        check_table(path, &table)?;
        let (scenario, index, sample) = stored_sample(&table, path)?;
        let legs = table.legs("tip_x_m");
        let thrusters = (0..)
            .take_while(|j| table.columns.contains_key(&format!("thruster{j}_thrust_n")))
            .count();
        let time = table.column("t_s", path)?.to_vec();
        if time.iter().any(|t| !t.is_finite()) || time.windows(2).any(|w| w[1] < w[0]) {
            bail!("{}: its times do not increase", path.display());
        }
        let every = meta(&table, path, "touchdown.every")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(1);
        let outcome = meta(&table, path, "touchdown.outcome")?.clone();
        let decided_s = number(&table, path, "touchdown.decided_s")?;
        Ok(Trace {
            about: format!(
                "sample {index} of seed {}: {outcome} at {decided_s:.3} s",
                scenario.seed
            ),
            outcome,
            decided_s,
            scenario,
            sample,
            time,
            legs,
            thrusters,
            every,
            table,
        })
    }

    /// The slope the sample lands on, deg.
    #[must_use]
    pub fn slope_deg(&self) -> f64 {
        self.sample.inputs.slope_deg
    }

    /// The azimuth of the slope's downhill direction, deg.
    #[must_use]
    pub fn downhill_azimuth_deg(&self) -> f64 {
        self.sample.inputs.downhill_azimuth_deg
    }

    /// The first and last time of the trace, s.
    #[must_use]
    pub fn span_s(&self) -> (f64, f64) {
        (self.time[0], self.time[self.time.len() - 1])
    }

    /// What the control loop flew, as the trace's metadata stores it: the value of the
    /// sweep's control column `name` (`touchdown.control.NAME`: law parameters, propellant,
    /// release state); `None` where the trace has none (no control loop, or a trace of an
    /// older touchdown), or it is no number.
    #[must_use]
    pub fn control_value(&self, name: &str) -> Option<f64> {
        self.table
            .meta
            .get(&format!("touchdown.control.{name}"))
            .and_then(|v| v.parse().ok())
    }

    /// Whether the trace has column `name`.
    #[must_use]
    pub fn has_column(&self, name: &str) -> bool {
        self.table.columns.contains_key(name)
    }

    /// Column `name` (every trace has those a pose reads: checked by `read`; empty for a
    /// column the trace lacks).
    #[must_use]
    pub fn column(&self, name: &str) -> &[f64] {
        self.table.columns.get(name).map_or(&[], Vec::as_slice)
    }

    /// Column `name`, or an error naming it.
    pub fn column_named(&self, name: &str) -> anyhow::Result<&[f64]> {
        self.table
            .columns
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| anyhow!("the trace has no column {name}"))
    }

    /// The control loop's phase per row, if the trace has one.
    #[must_use]
    pub fn phases(&self) -> Option<&[String]> {
        self.table
            .texts
            .get(crate::output::trace::PHASE_COLUMN)
            .map(Vec::as_slice)
    }

    /// The row at or before `t` and the fraction of the way to the next.
    #[must_use]
    pub fn locate(&self, t: f64) -> (usize, f64) {
        let n = self.time.len();
        let i = self.time.partition_point(|&x| x <= t).clamp(1, n) - 1;
        if i + 1 >= n {
            return (n - 1, 0.0);
        }
        let (a, b) = (self.time[i], self.time[i + 1]);
        let f = if b > a {
            ((t - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (i, f)
    }

    /// Column `name` at row and fraction `(i, f)` (`locate`), between rows linearly.
    #[must_use]
    pub fn at(&self, name: &str, (i, f): (usize, f64)) -> f64 {
        let c = self.column(name);
        match (c.get(i), c.get(i + 1)) {
            (Some(a), Some(b)) if f > 0.0 => a + f * (b - a),
            (Some(a), _) => *a,
            _ => f64::NAN,
        }
    }

    /// The largest value of column `name` over the rows that act in `(from, to]` (the row
    /// in force at `from` included), NaN rows left out.
    #[must_use]
    pub fn peak(&self, name: &str, rows: std::ops::RangeInclusive<usize>) -> f64 {
        let c = self.column(name);
        c.get(rows)
            .unwrap_or(&[])
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    }

    /// Column `name` at time `t`, between rows linearly (NaN for a column the trace lacks).
    #[must_use]
    pub fn value(&self, name: &str, t: f64) -> f64 {
        self.at(name, self.locate(t))
    }

    /// The largest value of column `name` over the rows in force from `since` to `t`.
    #[must_use]
    pub fn peak_between(&self, name: &str, since: f64, t: f64) -> f64 {
        self.peak(name, self.locate(since.min(t)).0..=self.locate(t).0)
    }

    /// The CG at every row.
    #[must_use]
    pub fn cg_path(&self) -> Vec<DVec3> {
        let (x, y, z) = (self.column("x_m"), self.column("y_m"), self.column("z_m"));
        (0..self.time.len())
            .map(|i| DVec3::new(x[i], y[i], z[i]))
            .collect()
    }
}
