//! The Markdown summary of a landing-site map: the body (size, gravity, slopes,
//! roughness) and how landings end over its surface, by area.

use super::estimate::{GravityDraw, LeastWindow, Window};
use super::{SAFE_P_STABLE, SHARE_OUTCOMES, SLOPE_LIMIT_DEG, Site, SweepTally};
use std::fmt::Write as _;

/// What the summary says of the map's sweep.
pub struct Sweep<'a> {
    /// Where the lander comes from (the scenario file, or the default scenario).
    pub scenario: &'a str,
    /// Samples of the sweep.
    pub samples: u64,
    /// The slopes (deg) and gravities (m/s^2) it drew.
    pub slope_range_deg: (f64, f64),
    /// See `slope_range_deg`.
    pub gravity_range_m_s2: (f64, f64),
    /// How it drew the gravities over their range.
    pub gravity_draw: GravityDraw,
    /// The window a facet's shares count samples in.
    pub window: Window,
    /// What its samples did beyond the shares (diverged, held, never touched).
    pub tally: SweepTally,
    /// `simulation.t_max_s` of its scenario, s.
    pub t_max_s: f64,
    /// The warnings on its samples (`super::warnings::sweep_failures`), written as notes.
    pub warnings: Vec<String>,
    /// The window of a facet a lander could stand on that expects the fewest samples.
    pub least_window: Option<LeastWindow>,
    /// `--window-samples`, where it set the samples.
    pub window_samples: Option<u64>,
}

/// The area-weighted quantile `q` of `values` (value, area): the smallest value with at
/// least the share `q` of the area at or below it.
fn area_quantile(values: &mut [(f64, f64)], q: f64) -> f64 {
    values.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = values.iter().map(|v| v.1).sum();
    let mut below = 0.0;
    for (x, a) in values.iter() {
        below += a;
        if below >= q * total {
            return *x;
        }
    }
    values.last().map_or(f64::NAN, |v| v.0)
}

/// The summary of `site`.
#[must_use]
pub fn markdown(site: &Site, sweep: &Sweep<'_>) -> String {
    let b = &site.body;
    let f = &site.facets;
    let area: f64 = f.iter().map(|f| f.area_m2).sum();
    let share = |keep: &dyn Fn(&super::SiteFacet) -> bool| {
        // `+ 0.0`: an empty sum is -0.0, which would print as "-0.00".
        100.0 * f.iter().filter(|x| keep(x)).map(|x| x.area_m2).sum::<f64>() / area + 0.0
    };
    let mean = |v: &dyn Fn(&super::SiteFacet) -> f64| {
        f.iter().map(|x| v(x) * x.area_m2).sum::<f64>() / area
    };
    let g_min = f
        .iter()
        .map(|x| x.gravity_m_s2)
        .fold(f64::INFINITY, f64::min);
    let g_max = f.iter().map(|x| x.gravity_m_s2).fold(0.0, f64::max);
    let mut slopes: Vec<(f64, f64)> = f.iter().map(|x| (x.slope_deg, x.area_m2)).collect();
    let median = area_quantile(&mut slopes, 0.5);
    let steepest = f.iter().map(|x| x.slope_deg).fold(0.0, f64::max);
    let mut rough: Vec<(f64, f64)> = f.iter().map(|x| (x.roughness_deg, x.area_m2)).collect();
    let rough_median = area_quantile(&mut rough, 0.5);
    let roughest = f.iter().map(|x| x.roughness_deg).fold(0.0, f64::max);
    let mut s = String::new();
    let _ = writeln!(s, "# Landing sites on {}\n", b.name);
    let _ = writeln!(s, "| the body | |\n|---|---|");
    let _ = writeln!(
        s,
        "| shape | {} facets, {} vertices; volume {:.4e} m^3, surface {:.4e} m^2 |",
        f.len(),
        b.vertices.len(),
        b.volume_m3,
        b.area_m2
    );
    let _ = writeln!(
        s,
        "| mass | {:.4e} kg (density {} kg/m^3) |",
        b.mass_kg,
        super::given_number(b.density_kg_m3)
    );
    // Shown to the centimetre, without a "-0.00".
    let c = b
        .centre_of_mass_m
        .map(|x| if x.abs() < 0.005 { 0.0 } else { x });
    let _ = writeln!(
        s,
        "| centre of mass | ({:.2}, {:.2}, {:.2}) m from the origin at constant density (the spin is about the origin) |",
        c[0], c[1], c[2]
    );
    let _ = writeln!(
        s,
        "| spin | period {} h about ({:.4}, {:.4}, {:.4}) |",
        super::given_number(b.spin_period_h),
        b.spin_axis[0],
        b.spin_axis[1],
        b.spin_axis[2]
    );
    let _ = writeln!(
        s,
        "| effective gravity | {g_min:.4e} to {g_max:.4e} m/s^2 (ratio {:.3}), mean {:.4e} by area |",
        g_max / g_min,
        mean(&|x| x.gravity_m_s2)
    );
    let _ = writeln!(
        s,
        "| slope | mean {:.2} deg by area, median {median:.2}, steepest {steepest:.2}; below 10 / 20 / 30 deg: {:.1} / {:.1} / {:.1} % of the surface |",
        mean(&|x| x.slope_deg),
        share(&|x| x.slope_deg < 10.0),
        share(&|x| x.slope_deg < 20.0),
        share(&|x| x.slope_deg < 30.0),
    );
    let _ = writeln!(
        s,
        "| roughness | mean {:.2} deg by area, median {rough_median:.2}, roughest {roughest:.2} (the RMS angle between a facet's normal and its three neighbours': the relief the model resolves, not simulated) |",
        mean(&|x| x.roughness_deg),
    );
    let _ = writeln!(
        s,
        "\n## Landings\n\nThe lander of {}, {} samples over slopes {:.2}-{:.2} deg and \
         gravities {:.4e}-{:.4e} m/s^2{}; each facet counts the samples within {} deg of its \
         slope and {} % of its gravity.\n",
        sweep.scenario,
        sweep.samples,
        sweep.slope_range_deg.0,
        sweep.slope_range_deg.1,
        sweep.gravity_range_m_s2.0,
        sweep.gravity_range_m_s2.1,
        match sweep.gravity_draw {
            GravityDraw::Uniform => "",
            GravityDraw::LogUniform => " (uniformly in the logarithm)",
        },
        sweep.window.slope_deg,
        100.0 * sweep.window.gravity_fraction
    );
    let t = &sweep.tally;
    let of = |k: u64| 100.0 * k as f64 / t.samples.max(1) as f64;
    let _ = write!(
        s,
        "Of the sweep's {} samples, {} ({:.2} %) diverged and {} ({:.2} %) never touched the \
         ground before simulation.t_max_s = {} s",
        t.samples,
        t.diverged,
        of(t.diverged),
        t.untouched,
        of(t.untouched),
        sweep.t_max_s
    );
    if t.held > 0 {
        let _ = write!(s, "; {} ({:.2} %) were held by thrust", t.held, of(t.held));
    }
    let _ = writeln!(
        s,
        " (all counted in the facets' samples; the diverged and held in none of their shares, \
         those that never touched as bouncing or tipped).\n"
    );
    for w in &sweep.warnings {
        let _ = writeln!(s, "> **Warning**: {w}.\n");
    }
    // An area of none reads "0 m^2", not "0.0000e0 m^2".
    let m2 = |fraction: f64| {
        let m2 = fraction * area;
        if m2 == 0.0 {
            "0".to_string()
        } else {
            format!("{m2:.4e}")
        }
    };
    let (sure, point) = (
        site.safe_area_fraction(),
        site.safe_area_fraction_point_estimate(),
    );
    let _ = writeln!(
        s,
        "**P(stable) >= {SAFE_P_STABLE} with 95 % confidence (the low end of its Wilson \
         interval) on {:.2} % of the surface** ({} m^2); by the point estimate (its share of \
         samples alone) on {:.2} % ({} m^2).\n",
        100.0 * sure,
        m2(sure),
        100.0 * point,
        m2(point),
    );
    let p = |x: &super::SiteFacet| x.p_stable().map(|s| s.p);
    let _ = writeln!(
        s,
        "| P(stable), point estimate | share of the surface |\n|---|---|"
    );
    for (label, keep) in [
        (
            "below 0.5",
            &(|x: Option<f64>| x.is_some_and(|p| p < 0.5)) as &dyn Fn(Option<f64>) -> bool,
        ),
        ("0.5 to 0.9", &|x: Option<f64>| {
            x.is_some_and(|p| (0.5..0.9).contains(&p))
        }),
        ("0.9 to 0.99", &|x: Option<f64>| {
            x.is_some_and(|p| (0.9..SAFE_P_STABLE).contains(&p))
        }),
        ("0.99 or more", &|x: Option<f64>| {
            x.is_some_and(|p| p >= SAFE_P_STABLE)
        }),
    ] {
        let _ = writeln!(s, "| {label} | {:.2} % |", share(&|x| keep(p(x))));
    }
    // Facets without shares, by why: too steep (past 90 deg the effective gravity points
    // off the ground, a spin near its limit: a row of its own when there is such a facet),
    // or no sample in the window (a window too fine or too few samples: what the map does
    // not know, never counted as steep).
    let off = |x: &super::SiteFacet| x.slope_deg > 90.0;
    let _ = writeln!(
        s,
        "| none: too steep to stand on ({SLOPE_LIMIT_DEG} deg or more) | {:.2} % |",
        share(&|x| p(x).is_none() && !x.standing() && !off(x))
    );
    if f.iter().any(off) {
        let _ = writeln!(
            s,
            "| none: the effective gravity points off the ground (slope over 90 deg) | {:.2} % |",
            share(&|x| p(x).is_none() && off(x))
        );
    }
    let _ = writeln!(
        s,
        "| none: no samples in its window (more --samples, or wider windows) | {:.2} % |",
        share(&|x| p(x).is_none() && x.standing())
    );
    let with: Vec<&super::SiteFacet> = f.iter().filter(|x| x.shares.is_some()).collect();
    let with_area: f64 = with.iter().map(|x| x.area_m2).sum();
    if with.is_empty() {
        let _ = writeln!(s, "\nNo facet has shares: no mean share by area.");
    } else {
        let _ = writeln!(s, "\n| outcome | mean share by area |\n|---|---|");
        for (k, o) in SHARE_OUTCOMES.iter().enumerate() {
            let m = with
                .iter()
                .map(|x| x.shares.map_or(0.0, |s| s[k].p) * x.area_m2)
                .sum::<f64>()
                / with_area;
            let _ = writeln!(s, "| {} | {:.4} |", o.name(), m);
        }
    }
    // Of the facets a lander could stand on: a facet without samples counts its 0.
    let mut n: Vec<u64> = f
        .iter()
        .filter(|x| x.standing())
        .map(|x| x.samples)
        .collect();
    n.sort_unstable();
    if let (Some(lo), Some(mid)) = (n.first(), n.get(n.len() / 2)) {
        let _ = writeln!(
            s,
            "\nSamples per facet a lander could stand on: {lo} at least, {mid} median."
        );
    }
    if let Some(w) = sweep.least_window {
        let sized = sweep.window_samples.map_or(String::new(), |n| {
            format!(
                " (--window-samples {n}: the sweep's {} samples were set for it)",
                sweep.samples
            )
        });
        let _ = writeln!(
            s,
            "The least-served window expects {:.1} samples{sized}: facet {}, slope {:.2} deg, \
             gravity {:.4e} m/s^2.",
            w.expected, w.facet, w.slope_deg, w.gravity_m_s2
        );
    }
    s
}
