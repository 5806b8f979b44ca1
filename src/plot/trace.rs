//! Pictures of a trace file: CG position, velocity, acceleration and attitude; per leg
//! penetration, normal force, friction force and stroke; the 3D path of the CG and the
//! footpads over the slope; the acceleration along Z_B (the instruments' shock). A trace of
//! a scenario with a control loop adds the thrust (on the lander, each thruster's firings,
//! the propellant used) and what the sensors read against the true state.

use super::canvas::{Area, FONT, Line, SERIES_COLOURS, drawing, line_panel, save_png, span};
use crate::output::columns::Table;
use crate::output::trace::PHASE_COLUMN;
use anyhow::anyhow;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Time axis label of every panel.
const TIME: &str = "time (s)";

/// A trace, with what its captions say.
struct Trace {
    t: Table,
    time: Vec<f64>,
    legs: usize,
    /// Thrusters of the control loop (0 without one).
    thrusters: usize,
    /// Unit normal of the slope plane, in I.
    normal: [f64; 3],
    /// "sample N: OUTCOME at T s", for the captions.
    about: String,
}

impl Trace {
    fn read(path: &Path) -> anyhow::Result<Trace> {
        let t = Table::read(path, |_| true)?;
        if t.rows == 0 {
            anyhow::bail!("{} holds no steps", path.display());
        }
        let time = t.column("t_s", path)?.to_vec();
        let legs = t.legs("normal_force_n");
        let thrusters = (0..)
            .take_while(|j| t.columns.contains_key(&format!("thruster{j}_thrust_n")))
            .count();
        let input = |name: &str| -> anyhow::Result<f64> {
            t.meta
                .get(&format!("touchdown.input.{name}"))
                .and_then(|v| v.parse().ok())
                .ok_or_else(|| anyhow!("{}: no input {name} in its metadata", path.display()))
        };
        let (sa, ca) = input("slope_deg")?.to_radians().sin_cos();
        let (sb, cb) = input("downhill_azimuth_deg")?.to_radians().sin_cos();
        let meta = |k: &str| t.meta.get(k).map_or("?", String::as_str).to_string();
        let decided = t
            .meta
            .get("touchdown.decided_s")
            .and_then(|v| v.parse::<f64>().ok())
            .map_or("?".to_string(), |v| format!("{v:.3}"));
        let about = format!(
            "sample {} of seed {}: {} at {decided} s",
            meta("touchdown.sample"),
            meta("touchdown.seed"),
            meta("touchdown.outcome"),
        );
        Ok(Trace {
            time,
            legs,
            thrusters,
            normal: [sa * cb, sa * sb, ca],
            about,
            t,
        })
    }

    /// Column `name` against time, as a line labelled `label` in colour `k`, scaled by
    /// `scale`.
    fn line(&self, name: &str, label: &str, k: usize, scale: f64) -> anyhow::Result<Line> {
        let y = self
            .t
            .columns
            .get(name)
            .ok_or_else(|| anyhow!("the trace has no column {name}"))?;
        Ok(Line {
            label: label.to_string(),
            colour: SERIES_COLOURS[k % SERIES_COLOURS.len()],
            points: self
                .time
                .iter()
                .copied()
                .zip(y.iter().map(|v| v * scale))
                .collect(),
        })
    }

    /// Column `what` of every leg against time, scaled by `scale`.
    fn per_leg(&self, what: &str, scale: f64) -> anyhow::Result<Vec<Line>> {
        (0..self.legs)
            .map(|k| self.line(&format!("leg{k}_{what}"), &format!("leg {k}"), k, scale))
            .collect()
    }

    /// The tilt of Z_B from the slope normal against time, deg.
    fn tilt(&self) -> anyhow::Result<Line> {
        let q = |n: &str| {
            self.t
                .columns
                .get(n)
                .ok_or_else(|| anyhow!("the trace has no column {n}"))
        };
        let (w, x, y, z) = (q("qw")?, q("qx")?, q("qy")?, q("qz")?);
        let n = self.normal;
        let points = (0..self.time.len())
            .map(|i| {
                // Z_B in I: the third column of the rotation matrix of the quaternion.
                let zb = [
                    2.0 * (x[i] * z[i] + w[i] * y[i]),
                    2.0 * (y[i] * z[i] - w[i] * x[i]),
                    1.0 - 2.0 * (x[i] * x[i] + y[i] * y[i]),
                ];
                let c = zb[0] * n[0] + zb[1] * n[1] + zb[2] * n[2];
                (self.time[i], c.clamp(-1.0, 1.0).acos().to_degrees())
            })
            .collect();
        Ok(Line {
            label: "tilt from the slope normal".to_string(),
            colour: SERIES_COLOURS[3],
            points,
        })
    }

    fn time_range(&self) -> std::ops::Range<f64> {
        span(self.time.iter().copied(), 0.0)
    }

    /// Column `name`, or an error naming it.
    fn column(&self, name: &str) -> anyhow::Result<&[f64]> {
        self.t
            .columns
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| anyhow!("the trace has no column {name}"))
    }

    /// `values` against time as a staircase: each row's value holds until the next row (a
    /// thrust is constant over a step); null rows (NaN) left out.
    fn held(&self, label: &str, k: usize, values: &[f64]) -> Line {
        let mut points = Vec::with_capacity(2 * values.len());
        for (i, (&t, &v)) in self.time.iter().zip(values).enumerate() {
            if !v.is_finite() {
                continue;
            }
            points.push((t, v));
            if let Some(&next) = self.time.get(i + 1) {
                points.push((next, v));
            }
        }
        Line {
            label: label.to_string(),
            colour: SERIES_COLOURS[k % SERIES_COLOURS.len()],
            points,
        }
    }

    /// Column `name` against time as a staircase (`held`), scaled by `scale`.
    fn held_column(&self, name: &str, label: &str, k: usize, scale: f64) -> anyhow::Result<Line> {
        let v: Vec<f64> = self.column(name)?.iter().map(|v| v * scale).collect();
        Ok(self.held(label, k, &v))
    }

    /// The control loop's phases and the times they start, in order.
    fn phases(&self) -> Vec<(f64, &str)> {
        let Some(phase) = self.t.texts.get(PHASE_COLUMN) else {
            return Vec::new();
        };
        let mut out: Vec<(f64, &str)> = Vec::new();
        for (t, p) in self.time.iter().zip(phase) {
            if out.last().is_none_or(|last| last.1 != p) {
                out.push((*t, p));
            }
        }
        out
    }

    /// The intervals in which thruster `j` fires: from a row with thrust to the next row
    /// without, joined where they touch.
    fn firings(&self, j: usize) -> anyhow::Result<Vec<(f64, f64)>> {
        let thrust = self.column(&format!("thruster{j}_thrust_n"))?;
        let mut out: Vec<(f64, f64)> = Vec::new();
        for (i, (&t, &f)) in self.time.iter().zip(thrust).enumerate() {
            if f <= 0.0 {
                continue;
            }
            let end = self.time.get(i + 1).copied().unwrap_or(t);
            match out.last_mut() {
                Some(last) if last.1 >= t => last.1 = end,
                _ => out.push((t, end)),
            }
        }
        Ok(out)
    }
}

/// Writes the trace's pictures, named by `name`; returns their paths.
pub(super) fn plot(path: &Path, name: &dyn Fn(&str) -> PathBuf) -> anyhow::Result<Vec<PathBuf>> {
    let tr = Trace::read(path)?;
    let mut written = Vec::new();

    let cg = name("cg");
    save_png(&cg, (1100, 1300), |root| {
        let root = root
            .titled(&format!("CG and attitude, {}", tr.about), (FONT, 22))
            .map_err(drawing)?;
        let p = root.split_evenly((4, 1));
        let xyz = |prefix: &str, unit: &str| -> anyhow::Result<Vec<Line>> {
            ["x", "y", "z"]
                .iter()
                .enumerate()
                .map(|(k, axis)| {
                    tr.line(
                        &format!("{prefix}{axis}_{unit}"),
                        &format!("{axis} (along {}_I)", axis.to_uppercase()),
                        k,
                        1.0,
                    )
                })
                .collect()
        };
        let position = xyz("", "m")?;
        line_panel(
            &p[0],
            "CG position",
            (TIME, "position (m)"),
            tr.time_range(),
            &position,
        )?;
        line_panel(
            &p[1],
            "CG velocity",
            (TIME, "velocity (m/s)"),
            tr.time_range(),
            &xyz("v", "m_s")?,
        )?;
        line_panel(
            &p[2],
            "CG acceleration dv/dt (gravity included)",
            (TIME, "acceleration (m/s²)"),
            tr.time_range(),
            &xyz("a", "m_s2")?,
        )?;
        let attitude = vec![
            tr.line("roll_deg", "roll", 0, 1.0)?,
            tr.line("pitch_deg", "pitch", 1, 1.0)?,
            tr.line("yaw_deg", "yaw", 2, 1.0)?,
            tr.tilt()?,
        ];
        line_panel(
            &p[3],
            "attitude: Euler angles, R_IB = Rz(yaw) Ry(pitch) Rx(roll)",
            (TIME, "angle (deg)"),
            tr.time_range(),
            &attitude,
        )
    })?;
    written.push(cg);

    let legs = name("legs");
    save_png(&legs, (1100, 1300), |root| {
        let root = root
            .titled(&format!("Legs, {}", tr.about), (FONT, 22))
            .map_err(drawing)?;
        let p = root.split_evenly((4, 1));
        let range = tr.time_range();
        line_panel(
            &p[0],
            "footpad penetration below the surface (negative: clearance, shown down to -5 mm)",
            (TIME, "penetration (mm)"),
            range.clone(),
            &tr.per_leg("penetration_m", 1e3)?
                .into_iter()
                .map(|mut l| {
                    // Clearance in flight reaches metres; the contact depth is millimetres.
                    l.points.iter_mut().for_each(|p| p.1 = p.1.max(-5.0));
                    l
                })
                .collect::<Vec<_>>(),
        )?;
        line_panel(
            &p[1],
            "normal contact force",
            (TIME, "force (N)"),
            range.clone(),
            &tr.per_leg("normal_force_n", 1.0)?,
        )?;
        line_panel(
            &p[2],
            "friction force",
            (TIME, "force (N)"),
            range.clone(),
            &tr.per_leg("friction_force_n", 1.0)?,
        )?;
        line_panel(
            &p[3],
            "damper stroke",
            (TIME, "stroke (mm)"),
            range,
            &tr.per_leg("stroke_m", 1e3)?,
        )
    })?;
    written.push(legs);

    let path3d = name("path-3d");
    save_png(&path3d, (1000, 900), |root| path_3d(root, &tr))?;
    written.push(path3d);

    let shock = name("accel-z-body");
    save_png(&shock, (1100, 800), |root| {
        let root = root
            .titled(
                &format!(
                    "Acceleration along Z_B (the instruments' shock), {}",
                    tr.about
                ),
                (FONT, 20),
            )
            .map_err(drawing)?;
        let p = root.split_evenly((2, 1));
        let line = tr.line(
            "accel_z_body_m_s2",
            "contact acceleration along Z_B",
            0,
            1.0,
        )?;
        let peak =
            line.points.iter().copied().fold(
                (0.0, 0.0),
                |m: (f64, f64), q| if q.1.abs() > m.1.abs() { q } else { m },
            );
        line_panel(
            &p[0],
            &format!(
                "whole touchdown; peak {:.4} m/s² at {:.3} s",
                peak.1, peak.0
            ),
            (TIME, "acceleration (m/s²)"),
            tr.time_range(),
            std::slice::from_ref(&line),
        )?;
        let window = peak.0 - 0.1..peak.0 + 0.3;
        let zoom = Line {
            points: line
                .points
                .iter()
                .copied()
                .filter(|q| window.contains(&q.0))
                .collect(),
            ..line
        };
        line_panel(
            &p[1],
            "around the peak",
            (TIME, "acceleration (m/s²)"),
            window,
            std::slice::from_ref(&zoom),
        )
    })?;
    written.push(shock);

    if tr.thrusters > 0 {
        let thrust = name("thrust");
        save_png(&thrust, (1100, 1300), |root| thrust_picture(root, &tr))?;
        written.push(thrust);
        if tr.t.columns.contains_key("sensed_tilt_deg") {
            let sensors = name("sensors");
            save_png(&sensors, (1100, 1300), |root| sensors_picture(root, &tr))?;
            written.push(sensors);
        }
    }
    Ok(written)
}

/// The thrust of a control loop: on the lander (hold-down along -Z_B, across it, and the
/// sum of the thrusters' magnitudes) with the loop's phases, its moment about the CG, when
/// each thruster fires, and the propellant used.
fn thrust_picture(root: &Area<'_>, tr: &Trace) -> anyhow::Result<()> {
    let root = root
        .titled(&format!("Thrust, {}", tr.about), (FONT, 22))
        .map_err(drawing)?;
    let p = root.split_evenly((4, 1));
    let range = tr.time_range();
    let (x, y, z) = (
        tr.column("thrust_b_x_n")?,
        tr.column("thrust_b_y_n")?,
        tr.column("thrust_b_z_n")?,
    );
    let down: Vec<f64> = z.iter().map(|v| -v).collect();
    let across: Vec<f64> = x.iter().zip(y).map(|(x, y)| x.hypot(*y)).collect();
    let phases: Vec<String> = tr
        .phases()
        .iter()
        .map(|(t, p)| format!("{p} from {t:.2} s"))
        .collect();
    let caption = if phases.is_empty() {
        "thrust on the lander".to_string()
    } else {
        format!(
            "thrust on the lander; control phases: {}",
            phases.join(", ")
        )
    };
    line_panel(
        &p[0],
        &caption,
        (TIME, "force (N)"),
        range.clone(),
        &[
            tr.held("hold-down: along -Z_B", 0, &down),
            tr.held("across Z_B", 1, &across),
            tr.held_column(
                "thrust_total_n",
                "sum of the firing thrusters' thrusts",
                2,
                1.0,
            )?,
        ],
    )?;
    let moment = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(k, axis)| {
            tr.held_column(
                &format!("thrust_moment_b_{axis}_n_m"),
                &format!("about {}_B", axis.to_uppercase()),
                k,
                1.0,
            )
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    line_panel(
        &p[1],
        "thrust moment about the CG",
        (TIME, "moment (N m)"),
        range.clone(),
        &moment,
    )?;
    firing_panel(&p[2], tr, range.clone())?;
    line_panel(
        &p[3],
        "propellant used",
        (TIME, "propellant (g)"),
        range,
        &[tr.line("propellant_used_kg", "propellant used", 0, 1e3)?],
    )
}

/// When each thruster fires: a bar per firing on the thruster's row, thruster 0 on top;
/// each row is labelled with the thruster's number and its thrust as built.
fn firing_panel(area: &Area<'_>, tr: &Trace, range: std::ops::Range<f64>) -> anyhow::Result<()> {
    let n = tr.thrusters;
    let top = 0.5;
    let bottom = 0.5 - n as f64;
    let thrusts = (0..n)
        .map(|j| {
            Ok(tr
                .column(&format!("thruster{j}_thrust_n"))?
                .iter()
                .copied()
                .fold(0.0, f64::max))
        })
        .collect::<anyhow::Result<Vec<f64>>>()?;
    let mut chart = ChartBuilder::on(area)
        .caption("firings: when each thruster is on", (FONT, 18))
        .margin(8)
        .x_label_area_size(38)
        .y_label_area_size(104)
        .build_cartesian_2d(range.clone(), bottom..top)
        .map_err(drawing)?;
    // Row j at y = -j: a tick label per whole value, none between (`+ 0.0` makes the -0
    // of row 0 a 0).
    let label = |v: &f64| {
        let j = -v.round() + 0.0;
        if (v + j).abs() < 1e-6 && j >= 0.0 && j < n as f64 {
            let thrust = thrusts[j as usize];
            if thrust > 0.0 {
                format!("{j:.0}: {thrust:.2} N")
            } else {
                format!("{j:.0}")
            }
        } else {
            String::new()
        }
    };
    chart
        .configure_mesh()
        .x_desc(TIME)
        .y_desc("thruster: thrust as built")
        .y_labels(n + 1)
        .y_label_formatter(&label)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(drawing)?;
    let width = range.end - range.start;
    for j in 0..n {
        let colour = SERIES_COLOURS[j % SERIES_COLOURS.len()];
        let y = -(j as f64);
        // A firing shorter than a pixel still shows: at least 1/2000 of the time axis.
        chart
            .draw_series(tr.firings(j)?.into_iter().map(|(a, b)| {
                Rectangle::new(
                    [(a, y - 0.3), (b.max(a + width / 2000.0), y + 0.3)],
                    colour.filled(),
                )
            }))
            .map_err(drawing)?;
    }
    Ok(())
}

/// What the control loop's sensors read at its control instants (held until the next)
/// against the true state: tilt, body rates, CG velocity and altitude.
fn sensors_picture(root: &Area<'_>, tr: &Trace) -> anyhow::Result<()> {
    let root = root
        .titled(
            &format!(
                "Sensed (held from each control instant) and true, {}",
                tr.about
            ),
            (FONT, 22),
        )
        .map_err(drawing)?;
    let p = root.split_evenly((4, 1));
    let range = tr.time_range();
    let pair = |truth: &str, sensed: &str, label: &str, k: usize| -> anyhow::Result<[Line; 2]> {
        Ok([
            tr.line(truth, &format!("{label}, true"), k, 1.0)?,
            tr.held_column(sensed, &format!("{label}, sensed"), k + 4, 1.0)?,
        ])
    };
    line_panel(
        &p[0],
        "tilt: angle between Z_B and Z_I (up)",
        (TIME, "tilt (deg)"),
        range.clone(),
        &pair("tilt_deg", "sensed_tilt_deg", "tilt", 0)?,
    )?;
    let rates: Vec<Line> = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(k, a)| {
            pair(
                &format!("rate_{a}_deg_s"),
                &format!("sensed_rate_{a}_deg_s"),
                &format!("about {}_B", a.to_uppercase()),
                k,
            )
        })
        .collect::<anyhow::Result<Vec<_>>>()?
        .into_iter()
        .flatten()
        .collect();
    line_panel(
        &p[1],
        "body rates",
        (TIME, "rate (deg/s)"),
        range.clone(),
        &rates,
    )?;
    let velocity: Vec<Line> = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(k, a)| {
            pair(
                &format!("v{a}_m_s"),
                &format!("sensed_v{a}_m_s"),
                &format!("along {}_I", a.to_uppercase()),
                k,
            )
        })
        .collect::<anyhow::Result<Vec<_>>>()?
        .into_iter()
        .flatten()
        .collect();
    line_panel(
        &p[2],
        "CG velocity",
        (TIME, "velocity (m/s)"),
        range.clone(),
        &velocity,
    )?;
    line_panel(
        &p[3],
        "CG altitude above the surface plane",
        (TIME, "altitude (m)"),
        range,
        &pair("altitude_m", "sensed_altitude_m", "altitude", 0)?,
    )
}

/// Colours of the axis names X_I, Y_I, Z_I of the 3D path (red, green, blue as in most 3D
/// tools; darker than any series colour, and none of them).
const AXIS_COLOURS: [RGBColor; 3] = [
    RGBColor(170, 20, 20),
    RGBColor(20, 120, 20),
    RGBColor(20, 20, 170),
];

/// The CG and footpad paths in 3D over a patch of the slope plane. Equal scales on all
/// axes, so that the path's shape is true.
fn path_3d(root: &Area<'_>, tr: &Trace) -> anyhow::Result<()> {
    let col = |n: &str| {
        tr.t.columns
            .get(n)
            .map(Vec::as_slice)
            .ok_or_else(|| anyhow!("the trace has no column {n}"))
    };
    let path = |x: &str, y: &str, z: &str| -> anyhow::Result<Vec<(f64, f64, f64)>> {
        let (x, y, z) = (col(x)?, col(y)?, col(z)?);
        Ok((0..x.len()).map(|i| (x[i], y[i], z[i])).collect())
    };
    let mut paths = vec![("CG".to_string(), path("x_m", "y_m", "z_m")?)];
    for k in 0..tr.legs {
        paths.push((
            format!("footpad {k}"),
            path(
                &format!("leg{k}_tip_x_m"),
                &format!("leg{k}_tip_y_m"),
                &format!("leg{k}_tip_z_m"),
            )?,
        ));
    }
    let all = || paths.iter().flat_map(|p| p.1.iter());
    let rx = span(all().map(|p| p.0), 0.0);
    let ry = span(all().map(|p| p.1), 0.0);
    let rz = span(all().map(|p| p.2), 0.0);
    let half = [&rx, &ry, &rz]
        .iter()
        .map(|r| 0.5 * (r.end - r.start))
        .fold(0.5, f64::max)
        * 1.05;
    let mid = |r: &std::ops::Range<f64>| 0.5 * (r.start + r.end);
    let (cx, cy, cz) = (mid(&rx), mid(&ry), mid(&rz));
    // plotters draws its second axis upwards: the chart's axes are (X_I, Z_I, Y_I).
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!("Path of the CG and footpads, {}", tr.about),
            (FONT, 20),
        )
        .margin(20)
        .build_cartesian_3d(
            cx - half..cx + half,
            cz - half..cz + half,
            cy - half..cy + half,
        )
        .map_err(drawing)?;
    chart.with_projection(|mut p| {
        p.yaw = 0.7;
        p.pitch = 0.35;
        p.scale = 0.85;
        p.into_matrix()
    });
    chart
        .configure_axes()
        .light_grid_style(RGBColor(235, 235, 235))
        .max_light_lines(4)
        .label_style((FONT, 12))
        .draw()
        .map_err(drawing)?;
    // The slope plane n . p = 0 (its mean, on rough terrain) as a grid of lines.
    let n = tr.normal;
    if n[2] > 1e-6 {
        let grey = RGBColor(170, 170, 170);
        let height = |x: f64, y: f64| -(n[0] * x + n[1] * y) / n[2];
        let steps = 8;
        for i in 0..=steps {
            let f = -half + 2.0 * half * f64::from(i) / f64::from(steps);
            for line in [
                [(cx + f, cy - half), (cx + f, cy + half)],
                [(cx - half, cy + f), (cx + half, cy + f)],
            ] {
                let pts: Vec<(f64, f64, f64)> = (0..=20)
                    .map(|j| {
                        let s = f64::from(j) / 20.0;
                        let x = line[0].0 + s * (line[1].0 - line[0].0);
                        let y = line[0].1 + s * (line[1].1 - line[0].1);
                        (x, height(x, y), y)
                    })
                    .filter(|p| (p.1 - cz).abs() <= half)
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts, grey.stroke_width(1)))
                    .map_err(drawing)?;
            }
        }
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64, f64)>>())
            .map_err(drawing)?
            .label("slope plane")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], grey.stroke_width(1))
            });
    }
    for (k, (label, pts)) in paths.iter().enumerate() {
        let colour = if k == 0 {
            BLACK
        } else {
            SERIES_COLOURS[(k - 1) % SERIES_COLOURS.len()]
        };
        let width = if k == 0 { 3 } else { 1 };
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|p| (p.0, p.2, p.1)),
                colour.stroke_width(width),
            ))
            .map_err(drawing)?
            .label(label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(width))
            });
    }
    // Start and end of the CG's path.
    let cg = &paths[0].1;
    for (p, what) in [(cg[0], "start"), (cg[cg.len() - 1], "end")] {
        chart
            .draw_series([EmptyElement::at((p.0, p.2, p.1))
                + Circle::new((0, 0), 5, BLACK.filled())
                + Text::new(what, (8, -18), (FONT, 15))])
            .map_err(drawing)?;
    }
    // Axis names beside the middle of the edges that carry their tick labels (seen from
    // this side, X_I ticks run along the front-left edge at Y_I max, Y_I ticks along the
    // front-right edge at X_I max), in the colours of AXIS_COLOURS.
    for ((text, at, offset), colour) in [
        ("X_I (m)", (cx, cz - half, cy + half), (-110, 40)),
        ("Y_I (m)", (cx + half, cz - half, cy), (50, 40)),
        ("Z_I, up (m)", (cx - half, cz + half, cy + half), (-40, -30)),
    ]
    .into_iter()
    .zip(AXIS_COLOURS)
    {
        chart
            .draw_series([EmptyElement::at(at)
                + Text::new(text, offset, (FONT, 15).into_font().color(&colour))])
            .map_err(drawing)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(RGBColor(160, 160, 160))
        .label_font((FONT, 13))
        .draw()
        .map_err(drawing)?;
    Ok(())
}
