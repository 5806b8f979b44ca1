//! The pictures of a control loop's trace: the thrust (on the lander, its moment, each
//! thruster's firings, the propellant used) and what the sensors read against the truth.

use super::series::{Series, TIME};
use crate::plot::canvas::{
    Area, FONT, Line, SERIES_COLOURS, drawing, line_panel, line_panel_legend_clear,
};
use plotters::prelude::*;

/// The thrust of a control loop: on the lander (hold-down along -Z_B, across it, and the
/// sum of the thrusters' magnitudes) with the loop's phases, its moment about the CG, when
/// each thruster fires, and the propellant used.
pub(super) fn thrust_picture(root: &Area<'_>, tr: &Series) -> anyhow::Result<()> {
    let root = tr.titled(root, "Thrust")?;
    let p = root.split_evenly((4, 1));
    let range = tr.time_range();
    let (x, y, z) = (
        tr.trace.column_named("thrust_b_x_n")?,
        tr.trace.column_named("thrust_b_y_n")?,
        tr.trace.column_named("thrust_b_z_n")?,
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
    line_panel_legend_clear(
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
    line_panel_legend_clear(
        &p[1],
        "thrust moment about the CG",
        (TIME, "moment (N m)"),
        range.clone(),
        &moment,
    )?;
    firing_panel(&p[2], tr, range.clone())?;
    line_panel_legend_clear(
        &p[3],
        "propellant used",
        (TIME, "propellant (g)"),
        range,
        &[tr.line("propellant_used_kg", "propellant used", 0, 1e3)?],
    )
}

/// When each thruster fires: a bar per firing on the thruster's row, thruster 0 on top;
/// each row is labelled with the thruster's number and its thrust as built.
fn firing_panel(area: &Area<'_>, tr: &Series, range: std::ops::Range<f64>) -> anyhow::Result<()> {
    let n = tr.trace.thrusters;
    let top = 0.5;
    let bottom = 0.5 - n as f64;
    let thrusts = (0..n)
        .map(|j| {
            Ok(tr
                .trace
                .column_named(&format!("thruster{j}_thrust_n"))?
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
pub(super) fn sensors_picture(root: &Area<'_>, tr: &Series) -> anyhow::Result<()> {
    let root = tr.titled(root, "Sensed (held from each control instant) and true")?;
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
