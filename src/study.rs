//! The table of `touchdown study`: the key varied and its values (`--vary`), and per value
//! the outcome shares with 95 % intervals, the allowable slope per azimuth sector and the
//! static tipping limit, read from the value's sweep file; written as Arrow and Markdown.

use crate::output::field;
use crate::output::sweep::SweepFile;
use crate::reference::Outcome;
use crate::scenario::Scenario;
use crate::stats::{
    Allowable, SECTOR_DEG, SECTORS, allowable_slope, relative_azimuth_deg, sector_of,
    wilson_interval,
};
use anyhow::bail;
use arrow_array::{ArrayRef, Float64Array, StringArray, UInt64Array};
use arrow_schema::DataType;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A key and the values it takes (`--vary KEY=MIN:MAX:COUNT`).
#[derive(Debug, Clone, PartialEq)]
pub struct Vary {
    /// The scenario key, its tables' names joined by dots (`lander.footpad_radius_m`).
    pub key: String,
    /// The first value, in the key's units.
    pub min: f64,
    /// The last value, in the key's units.
    pub max: f64,
    /// How many values, evenly spaced from `min` to `max` (1 to 1000).
    pub count: usize,
}

/// Most values one study runs.
const MAX_VALUES: usize = 1000;

impl Vary {
    /// Parses `KEY=MIN:MAX:COUNT`.
    pub fn parse(text: &str) -> Result<Vary, String> {
        let form = "write it KEY=MIN:MAX:COUNT, e.g. lander.footpad_radius_m=0.45:0.9:4";
        let (key, range) = text
            .split_once('=')
            .ok_or_else(|| format!("{text:?} has no '=': {form}"))?;
        let key = key.trim();
        let ok_part = |p: &str| {
            !p.is_empty()
                && p.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        };
        if !key.split('.').all(ok_part) {
            return Err(format!(
                "{key:?} is not a scenario key (names of letters, digits and _ joined by \
                 dots): {form}"
            ));
        }
        if matches!(key, "seed" | "samples" | "design") {
            return Err(format!(
                "{key} is not a key to vary (--seed and --samples set the study's; every \
                 value runs the same design)"
            ));
        }
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let [min, max, count] = parts[..] else {
            return Err(format!("{range:?} is not MIN:MAX:COUNT: {form}"));
        };
        let number = |what: &str, s: &str| -> Result<f64, String> {
            s.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{what} {s:?} is not a number"))
        };
        let (min, max) = (number("MIN", min)?, number("MAX", max)?);
        let count = match count.parse::<usize>() {
            Ok(n) if (1..=MAX_VALUES).contains(&n) => n,
            _ => {
                return Err(format!(
                    "COUNT {count:?} is not a whole number from 1 to {MAX_VALUES}"
                ));
            }
        };
        if count == 1 && min != max {
            return Err(format!(
                "one value from {min} to {max}? COUNT 1 needs MIN = MAX; give COUNT >= 2"
            ));
        }
        if count > 1 && min == max {
            return Err(format!(
                "{count} values all equal to {min}: MIN and MAX must differ"
            ));
        }
        let v = Vary {
            key: key.to_string(),
            min,
            max,
            count,
        };
        let values = v.values();
        if values.windows(2).any(|w| w[0] == w[1]) {
            return Err(format!(
                "{count} values from {min} to {max} are too close to tell apart"
            ));
        }
        Ok(v)
    }

    /// The values, evenly spaced from `min` to `max`, rounded to 12 significant digits (so
    /// that 0.45:0.9:4 gives 0.6, not 0.6000000000000001).
    #[must_use]
    pub fn values(&self) -> Vec<f64> {
        if self.count == 1 {
            return vec![self.min];
        }
        (0..self.count)
            .map(|i| {
                let x = self.min + (self.max - self.min) * i as f64 / (self.count - 1) as f64;
                format!("{x:.11e}").parse().unwrap_or(x)
            })
            .collect()
    }

    /// The key's last name (`footpad_radius_m` of `lander.footpad_radius_m`).
    #[must_use]
    pub fn leaf(&self) -> &str {
        self.key.rsplit('.').next().unwrap_or(&self.key)
    }
}

/// What the table, its Markdown and its picture say about the study.
pub struct About<'a> {
    /// The varied key (`Vary::key`).
    pub key: &'a str,
    /// The key and its values.
    pub vary: &'a Vary,
    /// The scenario file, as the command line named it.
    pub scenario: String,
    /// The seed of every value's sweep.
    pub seed: u64,
    /// Samples per value.
    pub samples: u64,
    /// The base scenario's TOML text, its seed applied.
    pub base_text: &'a str,
}

/// One value's line of the table.
pub struct Row {
    /// The varied key's value.
    pub value: f64,
    /// The value's sweep file.
    pub file: PathBuf,
    /// Samples of the value's sweep.
    pub samples: u64,
    /// Samples per outcome, in the order of `Outcome::ALL`.
    pub counts: [u64; Outcome::ALL.len()],
    /// Whether the value's sweep has a control loop (only then may a lander end `held`).
    pub controlled: bool,
    /// The allowable slope per sector (as `touchdown report` finds it).
    pub allowable: [Allowable; SECTORS],
    /// The least static tipping limit over each sector's azimuths (none where the gear
    /// stands on no slope).
    pub static_limit: [Option<f64>; SECTORS],
    /// The least and the greatest static tipping limit over all azimuths.
    pub static_range: Option<(f64, f64)>,
}

impl Row {
    /// The line of the value `value`, whose sweep of `scenario` with `samples` samples is
    /// the file `path`.
    pub fn read(value: f64, path: &Path, scenario: &Scenario, samples: u64) -> anyhow::Result<Row> {
        let mut file = SweepFile::open(path)?;
        let controlled = file.schema().field_with_name("propellant_kg").is_ok();
        let mut counts = [0u64; Outcome::ALL.len()];
        let mut sectors: Vec<Vec<(f64, bool)>> = vec![Vec::new(); SECTORS];
        let mut rows = 0;
        for b in file.batches() {
            let b = b?;
            let (slope, azimuth, yaw) = (
                b.f64s("slope_deg")?,
                b.f64s("downhill_azimuth_deg")?,
                b.f64s("yaw_deg")?,
            );
            for (i, o) in b.outcomes()?.into_iter().enumerate() {
                counts[o as usize] += 1;
                let relative = relative_azimuth_deg(azimuth.value(i), yaw.value(i));
                sectors[sector_of(relative)].push((slope.value(i), o == Outcome::Stable));
            }
            rows += b.rows();
        }
        if rows as u64 != samples {
            bail!(
                "{} holds {rows} samples, not the {samples} of the study",
                path.display()
            );
        }
        let allowable: [Allowable; SECTORS] =
            std::array::from_fn(|k| allowable_slope(&mut sectors[k]));
        let tips = scenario.lander.tips_m();
        // Every 0.5 deg of azimuth.
        let limit = |deg: f64| crate::stability::static_limit_deg(&tips, deg);
        let static_limit = std::array::from_fn(|k| {
            (0..=(2.0 * SECTOR_DEG) as usize)
                .filter_map(|j| limit(k as f64 * SECTOR_DEG + 0.5 * j as f64))
                .reduce(f64::min)
        });
        let all: Vec<f64> = (0..720).filter_map(|j| limit(0.5 * f64::from(j))).collect();
        let static_range = (!all.is_empty()).then(|| {
            (
                all.iter().copied().fold(f64::INFINITY, f64::min),
                all.iter().copied().fold(0.0, f64::max),
            )
        });
        Ok(Row {
            value,
            file: path.to_path_buf(),
            samples,
            counts,
            controlled,
            allowable,
            static_limit,
            static_range,
        })
    }

    /// The share of outcome `o` and its 95 % interval.
    pub fn share(&self, o: usize) -> (f64, f64, f64) {
        let (lo, hi) = wilson_interval(self.counts[o], self.samples);
        (self.counts[o] as f64 / self.samples as f64, lo, hi)
    }
}

/// The name of sector `k`, as columns use it: `0_45`.
fn sector_name(k: usize) -> String {
    format!(
        "{:.0}_{:.0}",
        k as f64 * SECTOR_DEG,
        (k + 1) as f64 * SECTOR_DEG
    )
}

/// The allowable slope of a sector and its interval as three nullable numbers: slope, low,
/// high (no slope: none, 0, the bound below which it would lie; too few samples: none).
fn allowable_columns(a: Allowable) -> [Option<f64>; 3] {
    match a {
        Allowable::TooFewSamples(_) => [None; 3],
        Allowable::NoSlope { below_deg } => [None, Some(0.0), Some(below_deg)],
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => [Some(slope_deg), Some(low_deg), Some(high_deg)],
    }
}

/// The fields of the study's table and their columns, in step.
struct Columns {
    fields: Vec<arrow_schema::Field>,
    columns: Vec<ArrayRef>,
}

/// The study's own files in its folder `dir`, beside the values' sweeps: the table
/// (Arrow), its Markdown and its picture.
#[must_use]
pub fn table_files(dir: &Path) -> [PathBuf; 3] {
    ["study.arrow", "study.md", "study.png"].map(|f| dir.join(f))
}

/// Writes the study's table to `path` (Arrow IPC file).
pub fn write_table(path: &Path, rows: &[Row], about: &About<'_>) -> anyhow::Result<()> {
    use arrow_array::RecordBatch;
    use arrow_schema::Schema;
    let mut c = Columns {
        fields: vec![
            field(
                about.key,
                DataType::Float64,
                "",
                "the value of the varied scenario key",
            ),
            field(
                "samples",
                DataType::UInt64,
                "",
                "samples of the value's sweep",
            ),
        ],
        columns: vec![
            Arc::new(Float64Array::from_iter_values(rows.iter().map(|r| r.value))),
            Arc::new(UInt64Array::from_iter_values(
                rows.iter().map(|r| r.samples),
            )),
        ],
    };
    outcome_columns(&mut c, rows);
    sector_columns(&mut c, rows);
    static_range_columns(&mut c, rows);
    c.fields.push(field(
        "sweep_file",
        DataType::Utf8,
        "",
        "the value's sweep file, in the study's folder",
    ));
    c.columns
        .push(Arc::new(StringArray::from_iter_values(rows.iter().map(
            |r| {
                r.file
                    .file_name()
                    .unwrap_or_default()
                    .to_string_lossy()
                    .into_owned()
            },
        ))));
    let schema = Arc::new(Schema::new(c.fields).with_metadata(table_metadata(about)));
    let batch = RecordBatch::try_new(schema.clone(), c.columns)?;
    let failed = |e| crate::output::cannot_write(path, e);
    let (file, out) = crate::output::AtomicFile::create(path)?;
    let mut w = crate::output::IpcWriter::new(&file, out, &schema).map_err(failed)?;
    w.write(&batch).map_err(|e| failed(e.into()))?;
    let mut out = w.finish().map_err(|e| failed(e.into()))?;
    std::io::Write::flush(&mut out).map_err(|e| failed(e.into()))?;
    file.commit(out)
}

/// The outcomes a study lists: `held` only where a value's lander can be held.
fn listed(rows: &[Row]) -> impl Iterator<Item = Outcome> {
    let held = Outcome::Held as usize;
    Outcome::listed(rows.iter().any(|r| r.controlled || r.counts[held] > 0))
}

/// Per outcome: its samples, its share and the share's 95 % interval.
fn outcome_columns(c: &mut Columns, rows: &[Row]) {
    for o in listed(rows) {
        let k = o as usize;
        let name = o.name();
        c.fields.push(field(
            name,
            DataType::UInt64,
            "",
            &format!("samples {name}"),
        ));
        c.columns.push(Arc::new(UInt64Array::from_iter_values(
            rows.iter().map(|r| r.counts[k]),
        )));
        for (j, (suffix, what)) in [
            ("share", "share of the samples"),
            ("low", "95 % Wilson interval of the share, low end"),
            ("high", "95 % Wilson interval of the share, high end"),
        ]
        .iter()
        .enumerate()
        {
            c.fields.push(field(
                &format!("{name}_{suffix}"),
                DataType::Float64,
                "",
                &format!("{name}: {what}"),
            ));
            c.columns
                .push(Arc::new(Float64Array::from_iter_values(rows.iter().map(
                    |r| {
                        let (p, lo, hi) = r.share(k);
                        [p, lo, hi][j]
                    },
                ))));
        }
    }
}

/// Per sector: the allowable slope and its interval, and the least static tipping limit.
fn sector_columns(c: &mut Columns, rows: &[Row]) {
    for k in 0..SECTORS {
        let s = sector_name(k);
        for (j, (suffix, what)) in [
            (
                "",
                "allowable slope (touchdown report's; empty: none, or too few samples)",
            ),
            ("_low", "95 % interval of the allowable slope, low end"),
            ("_high", "95 % interval of the allowable slope, high end"),
        ]
        .iter()
        .enumerate()
        {
            c.fields.push(
                field(
                    &format!("allowable_slope_{s}{suffix}_deg"),
                    DataType::Float64,
                    "deg",
                    &format!("sector {s} deg of downhill azimuth relative to the lander: {what}"),
                )
                .with_nullable(true),
            );
            c.columns.push(Arc::new(Float64Array::from_iter(
                rows.iter().map(|r| allowable_columns(r.allowable[k])[j]),
            )));
        }
        c.fields.push(
            field(
                &format!("static_limit_{s}_deg"),
                DataType::Float64,
                "deg",
                &format!(
                    "the least static tipping limit over sector {s} deg (empty: the gear stands \
                 on no slope)"
                ),
            )
            .with_nullable(true),
        );
        c.columns.push(Arc::new(Float64Array::from_iter(
            rows.iter().map(|r| r.static_limit[k]),
        )));
    }
}

/// The least and the greatest static tipping limit over all azimuths.
fn static_range_columns(c: &mut Columns, rows: &[Row]) {
    for (j, which) in ["least", "greatest"].iter().enumerate() {
        c.fields.push(
            field(
                &format!("static_limit_{which}_deg"),
                DataType::Float64,
                "deg",
                &format!("the {which} static tipping limit over azimuth"),
            )
            .with_nullable(true),
        );
        c.columns.push(Arc::new(Float64Array::from_iter(
            rows.iter()
                .map(|r| r.static_range.map(|(lo, hi)| [lo, hi][j])),
        )));
    }
}

/// The table's provenance: kind, engine, the varied key and its values, seed, samples and
/// the base scenario.
fn table_metadata(about: &About<'_>) -> std::collections::HashMap<String, String> {
    [
        ("touchdown.kind", "study".to_string()),
        ("touchdown.engine", crate::output::ENGINE.to_string()),
        ("touchdown.study.key", about.key.to_string()),
        (
            "touchdown.study.values",
            format!("{}:{}:{}", about.vary.min, about.vary.max, about.vary.count),
        ),
        ("touchdown.seed", about.seed.to_string()),
        ("touchdown.samples", about.samples.to_string()),
        ("touchdown.scenario", about.base_text.to_string()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect()
}

/// A Markdown cell of an allowable slope and its interval.
fn allowable_cell(a: Allowable) -> String {
    match a {
        Allowable::TooFewSamples(n) => format!("too few ({n})"),
        Allowable::NoSlope { below_deg } => format!("none (< {below_deg:.1})"),
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => format!("{slope_deg:.1} ({low_deg:.1}–{high_deg:.1})"),
    }
}

/// The study as Markdown.
pub fn markdown(rows: &[Row], about: &About<'_>) -> String {
    let mut t = String::new();
    let v = about.vary;
    let _ = writeln!(
        t,
        "# touchdown study: {} from {} to {} ({} values)\n",
        about.key, v.min, v.max, v.count
    );
    let _ = writeln!(
        t,
        "{}, seed {}, {} samples per value: every value meets the same landers (each sample \
         draws its inputs from its own seed), so differences between values are paired.\n",
        about.scenario, about.seed, about.samples
    );
    let _ = writeln!(t, "## Outcomes (share, 95 % interval)\n");
    let leaf = about.vary.leaf();
    let _ = write!(t, "| {leaf} | samples |");
    let outcomes: Vec<usize> = listed(rows).map(|o| o as usize).collect();
    for &k in &outcomes {
        let _ = write!(t, " {} |", Outcome::ALL[k].name());
    }
    let _ = write!(t, "\n|---:|---:|");
    t.push_str(&"---:|".repeat(outcomes.len()));
    t.push('\n');
    for r in rows {
        let _ = write!(t, "| {} | {} |", r.value, r.samples);
        for &k in &outcomes {
            let (p, lo, hi) = r.share(k);
            let _ = write!(
                t,
                " {:.2} % ({:.2}–{:.2}) |",
                100.0 * p,
                100.0 * lo,
                100.0 * hi
            );
        }
        t.push('\n');
    }
    let _ = writeln!(
        t,
        "\n## Allowable slope per sector (deg, 95 % interval)\n\nSectors of downhill azimuth \
         relative to the lander, as in `touchdown report`; \"none (< x)\": no slope has 99 % \
         of the samples at or below it stable, and the true allowable slope (if any) lies \
         below x. Static limit: the least and the greatest static tipping limit over azimuth.\n"
    );
    let _ = write!(t, "| {leaf} |");
    for k in 0..SECTORS {
        let _ = write!(
            t,
            " {:.0}–{:.0} |",
            k as f64 * SECTOR_DEG,
            (k + 1) as f64 * SECTOR_DEG
        );
    }
    let _ = write!(t, " static limit |\n|---:|");
    t.push_str(&"---:|".repeat(SECTORS + 1));
    t.push('\n');
    for r in rows {
        let _ = write!(t, "| {} |", r.value);
        for a in r.allowable {
            let _ = write!(t, " {} |", allowable_cell(a));
        }
        let _ = writeln!(
            t,
            " {} |",
            r.static_range
                .map_or("none".to_string(), |(lo, hi)| format!("{lo:.1}–{hi:.1}"))
        );
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_evenly_spaced_and_rounded() {
        let v = Vary::parse("lander.footpad_radius_m=0.45:0.9:4").unwrap();
        assert_eq!(v.key, "lander.footpad_radius_m");
        assert_eq!(v.leaf(), "footpad_radius_m");
        assert_eq!(v.values(), vec![0.45, 0.6, 0.75, 0.9]);
        let down = Vary::parse("x=1:0:3").unwrap();
        assert_eq!(down.values(), vec![1.0, 0.5, 0.0]);
        assert_eq!(Vary::parse("x=2:2:1").unwrap().values(), vec![2.0]);
    }

    #[test]
    fn bad_vary_is_refused_with_the_reason() {
        for (bad, says) in [
            ("lander.footpad_radius_m", "no '='"),
            ("=1:2:3", "not a scenario key"),
            ("a..b=1:2:3", "not a scenario key"),
            ("seed=1:2:3", "not a key to vary"),
            ("x=1:2", "not MIN:MAX:COUNT"),
            ("x=a:2:3", "MIN \"a\" is not a number"),
            ("x=1:inf:3", "MAX \"inf\" is not a number"),
            ("x=1:2:0", "COUNT"),
            ("x=1:2:1.5", "COUNT"),
            ("x=1:2:1", "COUNT 1 needs MIN = MAX"),
            ("x=1:1:3", "must differ"),
            ("x=1:1.0000000000001:3", "too close"),
        ] {
            let e = Vary::parse(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }
}
