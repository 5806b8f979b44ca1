//! The pictures of a trace file, one PNG each: CG and attitude, legs, the 3D path, the
//! instruments' shock, and with a control loop the thrust and the sensors.

use super::path::path_3d;
use super::series::{Series, TIME};
use super::thrust::{sensors_picture, thrust_picture};
use crate::plot::canvas::{Area, FONT, Line, drawing, line_panel, save_png};
use std::path::{Path, PathBuf};

/// The pictures of a trace, by the end of their names: the last two with a control loop
/// only (thrust; sensors where the loop senses).
pub(crate) const PICTURES: [&str; 6] =
    ["cg", "legs", "path-3d", "accel-z-body", "thrust", "sensors"];

/// Writes the trace's pictures, named by `name`; returns their paths.
pub(crate) fn plot(path: &Path, name: &dyn Fn(&str) -> PathBuf) -> anyhow::Result<Vec<PathBuf>> {
    let tr = Series::read(path)?;
    let mut written = Vec::new();
    let [cg, legs, path3d, shock, thrust, sensors] = PICTURES.map(name);

    save_png(&cg, (1100, 1300), |root| cg_picture(root, &tr))?;
    written.push(cg);

    save_png(&legs, (1100, 1300), |root| legs_picture(root, &tr))?;
    written.push(legs);

    save_png(&path3d, (1000, 900), |root| path_3d(root, &tr))?;
    written.push(path3d);

    save_png(&shock, (1100, 800), |root| shock_picture(root, &tr))?;
    written.push(shock);

    if tr.trace.thrusters > 0 {
        save_png(&thrust, (1100, 1300), |root| thrust_picture(root, &tr))?;
        written.push(thrust);
        if tr.trace.has_column("sensed_tilt_deg") {
            save_png(&sensors, (1100, 1300), |root| sensors_picture(root, &tr))?;
            written.push(sensors);
        }
    }
    Ok(written)
}

/// CG position, velocity and acceleration, and the attitude with the tilt from the slope
/// normal.
fn cg_picture(root: &Area<'_>, tr: &Series) -> anyhow::Result<()> {
    let root = tr.titled(root, "CG and attitude")?;
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
}

/// Per leg: the footpad's penetration, the normal and friction forces, the damper stroke.
fn legs_picture(root: &Area<'_>, tr: &Series) -> anyhow::Result<()> {
    let root = root
        .titled(&format!("Legs, {}", tr.about()), (FONT, 22))
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
}

/// The acceleration along Z_B over the whole touchdown and around its peak.
fn shock_picture(root: &Area<'_>, tr: &Series) -> anyhow::Result<()> {
    let root = root
        .titled(
            &format!(
                "Acceleration along Z_B (the instruments' shock), {}",
                tr.about()
            ),
            (FONT, 20),
        )
        .map_err(drawing)?;
    let p = root.split_evenly((2, 1));
    // With thrusters the accelerometer reads the thrust too (a passive trace's label as
    // before: there it is the contact alone).
    let label = if tr.trace.thrusters > 0 {
        "specific force over the mass along Z_B (contact and thrust)"
    } else {
        "contact acceleration along Z_B"
    };
    let line = tr.line("accel_z_body_m_s2", label, 0, 1.0)?;
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
}
