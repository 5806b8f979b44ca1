//! The envelope as text: the Markdown summary (the boundary per panel and row, with its
//! interval) and the CSV table of cells.

use super::plane::{Axis, Envelope, Facing, Panel, Row};
use crate::reference::Outcome;
use crate::stats::{ALLOWABLE_STABLE, Allowable, MIN_SAMPLES, wilson_interval};
use std::fmt::Write as _;

/// `v` with three significant digits of the axis's span.
fn num(v: f64, axis: &Axis) -> String {
    let span = (axis.hi - axis.lo).abs().max(1e-300);
    let decimals = (2.0 - span.log10().floor()).clamp(0.0, 9.0) as usize;
    format!("{v:.decimals$}")
}

/// A panel's title: its slope band and facing.
#[must_use]
pub fn panel_title(p: &Panel) -> String {
    let (lo, hi) = p.slope_deg;
    let band = if hi > lo {
        format!("slope {lo}–{hi} deg")
    } else {
        format!("slope {lo} deg")
    };
    match p.facing {
        Facing::All => band,
        f => format!("{band}, {}", f.name()),
    }
}

/// The Markdown cells of a row's boundary and its interval.
fn boundary_cells(b: Allowable, x: &Axis) -> (String, String) {
    match b {
        Allowable::TooFewSamples(n) => (format!("too few samples ({n})"), "–".to_string()),
        Allowable::NoSlope { below_deg } => (
            format!("none with ≥ {:.0} % stable", 100.0 * ALLOWABLE_STABLE),
            format!("below {}", num(below_deg, x)),
        ),
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => (
            num(slope_deg, x),
            format!("{}–{}", num(low_deg, x), num(high_deg, x)),
        ),
    }
}

/// The Markdown summary of an envelope: what it holds and left out, and per panel and
/// row of cells the samples, the stable share and the 99 %-stable boundary along x with
/// its 95 % interval.
#[must_use]
pub fn markdown(e: &Envelope) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "# touchdown envelope: {}\n", e.path.display());
    if let Some(note) = &e.interrupted {
        let _ = writeln!(t, "**{note}.**\n");
    }
    let _ = write!(
        t,
        "{} samples, seed {}: {} in the panels",
        e.rows,
        e.seed,
        e.samples()
    );
    for (n, why) in [
        (
            e.never_touched,
            "never touched the surface (null touchdown state)",
        ),
        (e.no_value, "have no value of x or y (null or not finite)"),
        (e.outside_bands, "have a slope outside the bands"),
    ] {
        if n > 0 {
            let _ = write!(t, "; {n} {why}, left out");
        }
    }
    let _ = writeln!(
        t,
        ".\n\nx: `{}`, {} bins from {} to {}; y: `{}`, {} bins from {} to {}.\n",
        e.x.label(),
        e.x.bins,
        num(e.x.lo, &e.x),
        num(e.x.hi, &e.x),
        e.y.label(),
        e.y.bins,
        num(e.y.lo, &e.y),
        num(e.y.hi, &e.y)
    );
    let _ = writeln!(
        t,
        "The 99 %-stable boundary of a row of cells: the largest x at or below which at \
         least {:.0} % of the row's samples are stable (the rule of `report`'s allowable \
         slope, along x; only values with at least {MIN_SAMPLES} samples at or below them \
         count), with its 95 % interval.",
        100.0 * ALLOWABLE_STABLE
    );
    for p in &e.panels {
        write_panel(&mut t, e, p);
    }
    t
}

/// One panel's section of the summary.
fn write_panel(t: &mut String, e: &Envelope, p: &Panel) {
    let n = p.samples();
    let stable: u64 = p.rows.iter().map(|r| r.stable).sum();
    let _ = write!(
        t,
        "\n## {}: {n} samples, {:.1} % stable",
        panel_title(p),
        100.0 * stable as f64 / n.max(1) as f64
    );
    if e.limits {
        let _ = write!(t, ", {} broke a limit", p.limits_broken());
    }
    let _ = writeln!(
        t,
        "\n\n| {} | samples | stable | boundary: {} | 95 % interval |\n|---|---:|---:|---:|---:|",
        e.y.label(),
        e.x.label()
    );
    for (j, r) in p.rows.iter().enumerate() {
        let (b, interval) = boundary_cells(r.boundary, &e.x);
        let share = if r.samples == 0 {
            "–".to_string()
        } else {
            format!("{:.1} %", 100.0 * r.stable as f64 / r.samples as f64)
        };
        let _ = writeln!(
            t,
            "| {}–{} | {} | {share} | {b} | {interval} |",
            num(e.y.edge(j), &e.y),
            num(e.y.edge(j + 1), &e.y),
            r.samples
        );
    }
}

/// The CSV fields of a row's boundary: the value, and the ends of its interval (empty
/// where there is none; a row with no boundary has only the upper end).
fn boundary_fields(r: &Row) -> [String; 3] {
    match r.boundary {
        Allowable::TooFewSamples(_) => [String::new(), String::new(), String::new()],
        Allowable::NoSlope { below_deg } => [String::new(), String::new(), below_deg.to_string()],
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => [
            slope_deg.to_string(),
            low_deg.to_string(),
            high_deg.to_string(),
        ],
    }
}

/// Writes the CSV table of an envelope to `out`, row by row (a million cells make about
/// 100 MB of text, never held): one row per cell (panel by panel, y bin by y bin, x bin
/// by x bin), with its slope band and facing, its x and y ranges, its samples per outcome,
/// the stable share with its 95 % Wilson interval, the samples that broke a limit (empty
/// without a `limits_broken` column), its row's samples and boundary, and the columns
/// of the sweep that x and y are (`x_column`, `y_column`: last, so that a reader of the
/// columns before them, by name or by place, reads them as before).
pub fn write_csv(e: &Envelope, out: &mut impl std::io::Write) -> std::io::Result<()> {
    write!(
        out,
        "panel,slope_min_deg,slope_max_deg,facing,x_min,x_max,y_min,y_max,samples,"
    )?;
    for o in Outcome::ALL {
        write!(out, "{},", o.name())?;
    }
    out.write_all(
        b"stable_share,stable_share_low,stable_share_high,limits_broken,\
         row_samples,row_boundary_x,row_boundary_low_x,row_boundary_high_x,x_column,y_column\n",
    )?;
    // Column names are identifiers (letters, digits, `_`, `.`): no quoting is needed, but
    // a name with a comma or quote is quoted all the same.
    let (x_column, y_column) = (csv_field(&e.x.name), csv_field(&e.y.name));
    let (nx, ny) = (e.x.bins, e.y.bins);
    for (k, p) in e.panels.iter().enumerate() {
        for j in 0..ny {
            let row = &p.rows[j];
            let [b, lo, hi] = boundary_fields(row);
            for i in 0..nx {
                let c = p.cell(i, j, nx);
                let n = c.samples();
                write!(
                    out,
                    "{k},{},{},{},{},{},{},{},{n},",
                    p.slope_deg.0,
                    p.slope_deg.1,
                    p.facing.name(),
                    e.x.edge(i),
                    e.x.edge(i + 1),
                    e.y.edge(j),
                    e.y.edge(j + 1)
                )?;
                for count in c.counts {
                    write!(out, "{count},")?;
                }
                if n == 0 {
                    out.write_all(b",,,")?;
                } else {
                    let (l, h) = wilson_interval(c.stable(), n);
                    write!(out, "{},{l},{h},", c.stable() as f64 / n as f64)?;
                }
                if e.limits {
                    write!(out, "{}", c.limits_broken)?;
                }
                writeln!(out, ",{},{b},{lo},{hi},{x_column},{y_column}", row.samples)?;
            }
        }
    }
    Ok(())
}

/// `text` as one CSV field: as it is, or quoted (quotes doubled) where it holds a comma, a
/// quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}
