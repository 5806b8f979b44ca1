//! The report as Markdown, for people: it reads on a terminal and pastes into a design note.

use super::data::{Provenance, Report, Sector};
use super::numbers::{Share, Summary, percent};
use crate::reference::Outcome;
use crate::stats::{ALLOWABLE_STABLE, MIN_SAMPLES};
use std::fmt::Write as _;

/// The report `r` as Markdown.
pub(super) fn markdown(r: &Report) -> String {
    let mut t = String::new();
    write_outcomes(&mut t, &r.provenance, &r.outcomes, r.stable_within_limits);
    if let Some(gear) = &r.gear {
        gear.write(&mut t);
    }
    if let Some(ground) = &r.ground {
        ground.write(&mut t);
    }
    if let Some(terrain) = &r.terrain {
        let _ = write!(
            t,
            "\n{}",
            crate::weighting::markdown(&terrain.weighted, &terrain.description, &terrain.text)
        );
    }
    write_allowable(&mut t, &r.allowable);
    write_loads(&mut t, &r.loads);
    t.push_str(&crate::exceedance::markdown(&r.exceedance));
    if let Some(thrust) = &r.thrust {
        thrust.write(&mut t);
    }
    if let Some(release) = &r.release {
        release.write(&mut t);
    }
    write_end(&mut t, &r.provenance);
    t
}

/// The title, the samples and the outcome shares with their intervals; with `[limits]`,
/// the stable samples within them after the stable ones.
fn write_outcomes(
    t: &mut String,
    p: &Provenance,
    outcomes: &[(Outcome, Share)],
    within_limits: Option<Share>,
) {
    let _ = writeln!(t, "# touchdown report: {}\n", p.sweep.display());
    let _ = writeln!(
        t,
        "{} samples, seed {}, {}.\n",
        p.samples,
        p.seed.as_deref().unwrap_or("?"),
        p.engine.as_deref().unwrap_or("?")
    );
    if let Some((_, note)) = &p.interrupted {
        let _ = writeln!(t, "**{note}.**\n");
    }
    let _ = writeln!(t, "## Outcomes\n");
    let _ = writeln!(
        t,
        "| outcome | samples | share | 95 % interval |\n|---|---:|---:|---:|"
    );
    for (o, share) in outcomes {
        share.row(t, o.name());
        if let (Outcome::Stable, Some(within)) = (o, within_limits) {
            within.row(t, "stable within limits");
        }
    }
}

/// The allowable slope per sector of relative azimuth.
fn write_allowable(t: &mut String, sectors: &[Sector]) {
    let _ = writeln!(
        t,
        "\n## Allowable slope\n\nThe largest slope at or below which at least {stable:.0} % of \
         the samples are stable, per sector of downhill azimuth relative to the lander \
         (`downhill_azimuth_deg - yaw_deg`); only slopes with at least {MIN_SAMPLES} samples \
         at or below them count (\"too few samples\": the sector has fewer). The 95 % \
         interval runs from the largest slope whose stable share's 95 % Wilson interval lies \
         at or above {stable:.0} % to the largest whose interval still reaches it.\n",
        stable = 100.0 * ALLOWABLE_STABLE
    );
    let _ = writeln!(
        t,
        "| azimuth sector | samples | stable | allowable slope | 95 % interval |\n|---|---:|---:|---:|---:|"
    );
    for s in sectors {
        let _ = writeln!(
            t,
            "| {:.0}–{:.0} deg | {} | {:.1} % | {} | {} |",
            s.azimuth_deg.0,
            s.azimuth_deg.1,
            s.samples,
            percent(s.stable, s.samples.max(1)),
            s.allowable.cell(),
            s.allowable.interval_cell()
        );
    }
}

/// The peak loads: mean, 99th percentile and largest.
fn write_loads(t: &mut String, loads: &[Summary]) {
    let _ = writeln!(
        t,
        "\n## Peak loads\n\n| quantity | mean | 99th percentile | largest |\n|---|---:|---:|---:|"
    );
    for l in loads {
        let _ = writeln!(
            t,
            "| {} ({}) | {:.4} | {:.4} | {:.4} |",
            l.name, l.unit, l.mean, l.p99, l.max
        );
    }
}

/// The note on dampers that are off, and how to see one sample in detail.
fn write_end(t: &mut String, p: &Provenance) {
    if p.dampers == Some(false) {
        let _ = writeln!(
            t,
            "\nThe dampers are off in this scenario (`damper.enabled = false`): the legs are \
             rigid struts, so stroke and absorbed energy are 0."
        );
    }
    let _ = writeln!(
        t,
        "\n## One sample in detail\n\n`touchdown trace --sweep {} --sample I` runs the sample \
         of index I (the `sample` column) again with this file's scenario and seed and writes \
         its time history; `touchdown plot` draws it.",
        p.sweep.display()
    );
}
