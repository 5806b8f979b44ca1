//! `touchdown view`: one self-contained HTML page of a trace, with the lander in 3D (orbit,
//! zoom), a time slider with play and pause, and the CG's and legs' histories in small
//! charts whose cursor follows the slider.
//!
//! The page is `viewer.html` with the trace spliced in as JSON: nothing is fetched, so it
//! opens from a mail attachment or a folder with no network. A long trace is resampled to
//! `MAX_TIMES` times; the forces and thrusts keep their peak over each interval, so no
//! impact or firing in the trace's rows falls between two of them.
//!
//! With rocks or on regolith, `ground.js` is spliced into the page too: the rocks as shaded
//! hemispheres, the footprints, each sunk footpad veiled by the ground under its hole, and
//! under the pointer a rock's radius or a footpad's sinkage. A page without them is the
//! template alone, byte for byte as before.

use crate::output::AtomicFile;
use crate::scene::{Ground, Scene};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

pub mod packed;
pub mod site;

/// The page, with `PLACEHOLDER` where the trace goes.
const TEMPLATE: &str = include_str!("viewer.html");
const PLACEHOLDER: &str = "\"__TOUCHDOWN_TRACE_JSON__\"";

/// The page's drawing of rocks, footprints and sunk footpads, and where it goes into the
/// page: a page without rocks or regolith is `TEMPLATE` alone, as before them.
const GROUND_JS: &str = include_str!("ground.js");
/// `GROUND_JS` goes before this line of `TEMPLATE` (at the script's top level)...
const GROUND_JS_BEFORE: &str = "// ==== 3D view\n";
/// ...the rocks onto the cached ground layer at the end of `renderGround`...
const ROCKS_LAYER_AT: &str = "}\nfunction drawGround(ctx) {";
const ROCKS_LAYER_CALL: &str = "  groundRocks(g, A, ox, oy, s);\n";
/// ...and the rocks near the lander, footprints and holes among the lander's parts.
const GROUND_PRIMS_AT: &str = "  // Painter's algorithm: far to near.\n  prims.sort(";
const GROUND_PRIMS_CALL: &str = "  groundPrims(prims, poly, P, ps, s);\n";

/// Most times a page holds.
pub const MAX_TIMES: usize = 4000;

/// Thrusters per chart of the page: as many entries as a chart's legend shows in its
/// narrowest width (260 pixels) as it shows four legs.
const THRUSTERS_PER_CHART: usize = 4;

/// What `view` wrote.
#[derive(Debug, Clone, Copy)]
pub struct Written {
    /// Times the page holds.
    pub times: usize,
    /// Rows of the trace.
    pub rows: usize,
    /// Size of the page, bytes.
    pub bytes: u64,
    /// The trace's rows are every `every` steps.
    pub every: u64,
}

/// Writes the page of the trace at `trace` to `out`.
pub fn view(trace: &Path, out: &Path) -> anyhow::Result<Written> {
    crate::output::check_output_path(out)?;
    let scene = Scene::read(trace)?;
    let (json, times) = trace_json(&scene);
    let template = if scene.model.rocks.is_some() || scene.on_regolith() {
        with_ground(TEMPLATE)
    } else {
        TEMPLATE.to_string()
    };
    let page = template.replacen(PLACEHOLDER, &json.replace("</", "<\\/"), 1);
    let (file, mut sink) = AtomicFile::create(out)?;
    sink.write_all(page.as_bytes())
        .and_then(|()| sink.flush())
        .map_err(|e| crate::output::cannot_write(out, e))?;
    file.commit(sink)?;
    Ok(Written {
        times,
        rows: scene.trace.time.len(),
        bytes: page.len() as u64,
        every: scene.trace.every,
    })
}

/// `template` with the drawing of rocks, footprints and sunk footpads spliced in (each
/// place found once in `TEMPLATE`: a unit test checks).
fn with_ground(template: &str) -> String {
    let at = |place: &str, what: &str| format!("{what}{place}");
    template
        .replacen(GROUND_JS_BEFORE, &at(GROUND_JS_BEFORE, GROUND_JS), 1)
        .replacen(ROCKS_LAYER_AT, &at(ROCKS_LAYER_AT, ROCKS_LAYER_CALL), 1)
        .replacen(GROUND_PRIMS_AT, &at(GROUND_PRIMS_AT, GROUND_PRIMS_CALL), 1)
}

/// A number as JSON: f32 precision (the page draws it), `null` when not finite.
fn num(out: &mut String, v: f64) {
    if v.is_finite() {
        let _ = write!(out, "{}", v as f32);
    } else {
        out.push_str("null");
    }
}

fn vec3(out: &mut String, v: glam::DVec3) {
    out.push('[');
    for (k, x) in v.to_array().into_iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        num(out, x);
    }
    out.push(']');
}

/// A string as JSON.
fn text(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

fn numbers(out: &mut String, values: impl IntoIterator<Item = f64>) {
    out.push('[');
    for (k, v) in values.into_iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        num(out, v);
    }
    out.push(']');
}

/// The trace as the page reads it (its keys are the page's contract); returns it and the
/// number of times it holds.
fn trace_json(scene: &Scene) -> (String, usize) {
    let (t0, t1) = scene.trace.span_s();
    // Every row of a short trace; a long one at MAX_TIMES evenly spaced times.
    let times: Vec<f64> = if scene.trace.time.len() <= MAX_TIMES {
        scene.trace.time.clone()
    } else {
        (0..MAX_TIMES)
            .map(|k| t0 + (t1 - t0) * k as f64 / (MAX_TIMES - 1) as f64)
            .collect()
    };
    let resampled = scene.trace.time.len() > MAX_TIMES;
    let mut o = String::with_capacity(times.len() * 64 * 10);
    o.push('{');
    o.push_str("\"title\":");
    text(&mut o, &scene.trace.about);
    o.push_str(",\"outcome\":");
    text(&mut o, &scene.trace.outcome);
    o.push_str(",\"decided_s\":");
    num(&mut o, scene.trace.decided_s);
    o.push_str(",\"slope_deg\":");
    num(&mut o, scene.trace.slope_deg());
    o.push_str(",\"downhill_azimuth_deg\":");
    num(&mut o, scene.trace.downhill_azimuth_deg());
    o.push_str(",\"normal\":");
    vec3(&mut o, scene.surface.normal);
    let ground = sketch_and_ground(&mut o, scene);
    o.push_str("},\"time\":");
    numbers(&mut o, times.iter().copied());
    rocks_and_footprints(&mut o, scene, &ground, &times);

    series(&mut o, scene, &times, resampled);
    charts(&mut o, scene);
    o.push_str("]}");
    (o, times.len())
}

/// The lander's sketch (body, legs, footpads, thrusters) and the ground patch under its
/// path, as the page's keys `body` to `ground`; returns the patch.
fn sketch_and_ground(o: &mut String, scene: &Scene) -> Ground {
    let sk = &scene.sketch;
    o.push_str(",\"body\":{\"bottom\":[");
    for (k, p) in sk.bottom.iter().enumerate() {
        if k > 0 {
            o.push(',');
        }
        vec3(o, *p);
    }
    o.push_str("],\"top\":[");
    for (k, p) in sk.top.iter().enumerate() {
        if k > 0 {
            o.push(',');
        }
        vec3(o, *p);
    }
    o.push_str("]},\"legs\":[");
    for (k, l) in sk.legs.iter().enumerate() {
        if k > 0 {
            o.push(',');
        }
        o.push_str("{\"hip\":");
        vec3(o, l.hip);
        o.push_str(",\"mount\":");
        vec3(o, l.mount);
        o.push_str(",\"tip0\":");
        vec3(o, l.tip0);
        o.push_str(",\"axis\":");
        vec3(o, l.axis);
        o.push('}');
    }
    o.push_str("],\"footpad_radius_m\":");
    num(o, sk.footpad_radius_m);
    o.push_str(",\"thrusters\":[");
    for (j, t) in sk.thrusters.iter().enumerate() {
        if j > 0 {
            o.push(',');
        }
        o.push_str("{\"position\":");
        vec3(o, t.position);
        o.push_str(",\"direction\":");
        vec3(o, t.direction);
        o.push_str(",\"max_thrust_n\":");
        num(o, t.max_thrust_n);
        o.push('}');
    }
    let g = scene.ground(2.0 * sk.reach_m() + 1.0, 0.1, 40_000);
    let g = if g.heights.is_none() {
        scene.ground(2.0 * sk.reach_m() + 1.0, 0.5, 40_000)
    } else {
        g
    };
    o.push_str("],\"ground\":{\"origin\":");
    vec3(o, g.origin);
    o.push_str(",\"u\":");
    vec3(o, g.u);
    o.push_str(",\"v\":");
    vec3(o, g.v);
    o.push_str(",\"spacing_m\":");
    num(o, g.spacing_m);
    let _ = write!(o, ",\"nu\":{},\"nv\":{},\"heights\":", g.nu, g.nv);
    match &g.heights {
        Some(h) => numbers(o, h.iter().copied()),
        None => o.push_str("null"),
    }
    g
}

/// With rocks, the page's key `rocks`: `[x, y, z, radius]` of each rock on the patch
/// `ground` (its base's centre in I); on regolith, `regolith`, each leg's sinkage at
/// `times` (`sinkage_m`: 0 above the ground or on a rock) and the `footprints`, each
/// `{leg, t, p, depth_m}` (lift-off time, centre on the ground, deepest sinkage). Nothing
/// on the elastic plane without rocks (its page stays as it was).
fn rocks_and_footprints(o: &mut String, scene: &Scene, ground: &Ground, times: &[f64]) {
    if scene.model.rocks.is_some() {
        o.push_str(",\"rocks\":[");
        for (k, r) in scene.rocks(ground).iter().enumerate() {
            if k > 0 {
                o.push(',');
            }
            numbers(o, r.centre.to_array().into_iter().chain([r.radius_m]));
        }
        o.push(']');
    }
    if scene.on_regolith() {
        o.push_str(",\"regolith\":true,\"sinkage_m\":[");
        for leg in 0..scene.trace.legs {
            if leg > 0 {
                o.push(',');
            }
            numbers(o, times.iter().map(|t| scene.sinkage_m(leg, *t)));
        }
        o.push_str("],\"footprints\":[");
        for (k, f) in scene.footprints().iter().enumerate() {
            if k > 0 {
                o.push(',');
            }
            let _ = write!(o, "{{\"leg\":{},\"t\":", f.leg);
            num(o, f.lifted_s);
            o.push_str(",\"p\":");
            vec3(o, f.centre);
            o.push_str(",\"depth_m\":");
            num(o, f.depth_m);
            o.push('}');
        }
        o.push(']');
    }
}

/// The state columns between rows and the forces and thrusts at their peak, at `times`
/// (`resampled`: the peaks since the previous time), the tilt and the phases.
fn series(o: &mut String, scene: &Scene, times: &[f64], resampled: bool) {
    // The state columns between rows; the forces and thrusts at their peak since the
    // previous time (when resampled).
    let mut state: Vec<String> = [
        "x_m", "y_m", "z_m", "vx_m_s", "vy_m_s", "vz_m_s", "qw", "qx", "qy", "qz",
    ]
    .map(String::from)
    .to_vec();
    let mut peaks: Vec<String> = Vec::new();
    for k in 0..scene.trace.legs {
        for c in ["tip_x_m", "tip_y_m", "tip_z_m", "stroke_m", "penetration_m"] {
            state.push(format!("leg{k}_{c}"));
        }
        for c in ["normal_force_n", "friction_force_n"] {
            peaks.push(format!("leg{k}_{c}"));
        }
    }
    for j in 0..scene.trace.thrusters {
        peaks.push(format!("thruster{j}_thrust_n"));
    }
    o.push_str(",\"series\":{");
    let mut first = true;
    let mut key = |o: &mut String, name: &str| {
        if !first {
            o.push(',');
        }
        first = false;
        text(o, name);
        o.push(':');
    };
    for name in &state {
        key(o, name);
        numbers(o, times.iter().map(|t| scene.trace.value(name, *t)));
    }
    // On regolith each leg's sinkage (`Scene::sinkage_m`), for its chart.
    if scene.on_regolith() {
        for leg in 0..scene.trace.legs {
            key(o, &format!("leg{leg}_sinkage_m"));
            numbers(o, times.iter().map(|t| scene.sinkage_m(leg, *t)));
        }
    }
    for name in &peaks {
        key(o, name);
        numbers(
            o,
            times.iter().enumerate().map(|(k, t)| {
                let since = if resampled && k > 0 { times[k - 1] } else { *t };
                scene.trace.peak_between(name, since, *t)
            }),
        );
    }
    key(o, "tilt_deg");
    numbers(o, times.iter().map(|t| scene.pose(*t, *t).tilt_deg));
    o.push_str("},\"phase\":");
    match scene.trace.phases() {
        Some(_) => {
            o.push('[');
            for (k, t) in times.iter().enumerate() {
                if k > 0 {
                    o.push(',');
                }
                text(o, scene.pose(*t, *t).phase.as_deref().unwrap_or(""));
            }
            o.push(']');
        }
        None => o.push_str("null"),
    }
}

/// The charts under the view.
fn charts(o: &mut String, scene: &Scene) {
    o.push_str(",\"charts\":[");
    let chart = |o: &mut String, title: &str, lines: &[(String, String, f64)]| {
        o.push_str("{\"title\":");
        text(o, title);
        o.push_str(",\"lines\":[");
        for (k, (label, series, scale)) in lines.iter().enumerate() {
            if k > 0 {
                o.push(',');
            }
            o.push_str("{\"label\":");
            text(o, label);
            o.push_str(",\"series\":");
            text(o, series);
            o.push_str(",\"scale\":");
            num(o, *scale);
            o.push('}');
        }
        o.push_str("]}");
    };
    let per_leg = |c: &str, scale: f64| -> Vec<(String, String, f64)> {
        (0..scene.trace.legs)
            .map(|k| (format!("leg {k}"), format!("leg{k}_{c}"), scale))
            .collect()
    };
    let xyz = |prefix: &str, suffix: &str| -> Vec<(String, String, f64)> {
        ["x", "y", "z"]
            .iter()
            .map(|a| (a.to_string(), format!("{prefix}{a}{suffix}"), 1.0))
            .collect()
    };
    chart(o, "CG position (m)", &xyz("", "_m"));
    o.push(',');
    chart(o, "CG velocity (m/s)", &xyz("v", "_m_s"));
    o.push(',');
    chart(
        o,
        "tilt from the slope normal (deg)",
        &[("tilt".to_string(), "tilt_deg".to_string(), 1.0)],
    );
    o.push(',');
    chart(
        o,
        "normal force per leg (N)",
        &per_leg("normal_force_n", 1.0),
    );
    // Only what the lander has: a stroke with dampers, a sinkage on regolith.
    if scene.model.honeycomb.is_some() {
        o.push(',');
        chart(
            o,
            "damper stroke per leg (mm)",
            &per_leg("stroke_m", 1000.0),
        );
    }
    if scene.on_regolith() {
        o.push(',');
        chart(
            o,
            "footpad sinkage per leg (mm)",
            &per_leg("sinkage_m", 1000.0),
        );
    }
    // The thrusters in charts of at most four, as the legs: a chart's legend is one row
    // across it, and twelve entries there showed five.
    let n = scene.trace.thrusters;
    for first in (0..n).step_by(THRUSTERS_PER_CHART) {
        o.push(',');
        let last = (first + THRUSTERS_PER_CHART).min(n) - 1;
        let lines: Vec<(String, String, f64)> = (first..=last)
            .map(|j| {
                (
                    format!("thruster {j}"),
                    format!("thruster{j}_thrust_n"),
                    1.0,
                )
            })
            .collect();
        let title = if n <= THRUSTERS_PER_CHART {
            "thrust per thruster (N)".to_string()
        } else {
            format!("thrust of thrusters {first}-{last} of 0-{} (N)", n - 1)
        };
        chart(o, &title, &lines);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ground_s_drawing_goes_into_the_page_at_each_of_its_places_once() {
        for place in [GROUND_JS_BEFORE, ROCKS_LAYER_AT, GROUND_PRIMS_AT] {
            assert_eq!(TEMPLATE.matches(place).count(), 1, "{place:?}");
        }
        let page = with_ground(TEMPLATE);
        assert!(page.contains(&format!("{GROUND_JS}{GROUND_JS_BEFORE}")));
        assert!(page.contains(&format!("{ROCKS_LAYER_CALL}{ROCKS_LAYER_AT}")));
        assert!(page.contains(&format!("{GROUND_PRIMS_CALL}{GROUND_PRIMS_AT}")));
        assert_eq!(page.matches(PLACEHOLDER).count(), 1);
    }
}
