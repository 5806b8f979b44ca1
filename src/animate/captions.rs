//! The captions of a frame: what the sample is, the time, tilt and phase, the playback
//! speed, the outcome once decided, a scale bar and the axes of I.

use super::camera::View;
use super::palette::{AXES, BACKGROUND, INK, OUTCOME};
use crate::plot::canvas::{Area, FONT, drawing};
use crate::reference::Outcome;
use crate::scene::Pose;
use glam::DVec3;
use plotters::prelude::*;

/// Text `t` at pixel `at` in the captions' font, of `size` and `colour`.
fn text_at(
    root: &Area<'_>,
    t: &str,
    at: (i32, i32),
    size: f64,
    colour: RGBColor,
) -> anyhow::Result<()> {
    root.draw(&Text::new(
        t.to_string(),
        at,
        (FONT, size).into_font().color(&colour),
    ))
    .map_err(drawing)
}

impl View<'_> {
    /// The captions (what the sample is, the time, tilt and phase, the playback speed,
    /// the outcome once decided), a scale bar and the axes of I.
    pub(super) fn draw_captions(
        &self,
        root: &Area<'_>,
        pose: &Pose,
        speed: f64,
    ) -> anyhow::Result<()> {
        let s = self.scene;
        let outcome = Outcome::from_name(&s.trace.outcome);
        let colour = outcome.map_or(INK, |o| OUTCOME[o as usize]);
        let big = (self.height / 30.0).clamp(11.0, 22.0);
        let small = (big * 0.8).max(10.0);
        let text = |t: &str, at, size, colour| text_at(root, t, at, size, colour);
        let pad = (big * 0.5) as i32;
        // The captions on a veil, so that the trail or ground under them does not hide them;
        // wide enough for the longest second line (the same in every frame).
        let veil = (
            2 * pad + (0.55 * (big * s.trace.about.len() as f64).max(small * 90.0)) as i32,
            pad + (big * 2.6) as i32,
        );
        root.draw(&Rectangle::new(
            [(0, 0), veil],
            BACKGROUND.mix(0.8).filled(),
        ))
        .map_err(drawing)?;
        text(&s.trace.about, (pad, pad), big, colour)?;
        let mut line = format!(
            "t = {:.2} s    tilt {:.1} deg    slope {:.1} deg",
            pose.t_s,
            pose.tilt_deg,
            s.trace.slope_deg()
        );
        // The lowest footpad's height above the surface along its normal, while it is clear
        // of it (a descent starts metres up, far above the ground the picture shows).
        let n = s.surface.normal;
        let height = pose
            .tips
            .iter()
            .filter(|t| t.is_finite())
            .map(|t| n.dot(*t) - self.ground_height(*t))
            .fold(f64::INFINITY, f64::min);
        if height.is_finite() && height >= 0.01 {
            line.push_str(&format!("    {height:.2} m off the slope"));
        }
        if let Some(p) = pose.phase.as_deref().filter(|p| !p.is_empty()) {
            line.push_str(&format!("    {p}"));
        }
        text(&line, (pad, pad + (big * 1.4) as i32), small, INK)?;
        let speed_text = if (speed - speed.round()).abs() < 0.05 {
            format!("{:.0}x speed", speed)
        } else {
            format!("{speed:.1}x speed")
        };
        let w = self.width as i32;
        text(
            &speed_text,
            (
                w - pad - (small * 0.55 * speed_text.len() as f64) as i32,
                pad,
            ),
            small,
            INK,
        )?;
        if pose.t_s >= s.trace.decided_s - 1e-9 {
            let word = s.trace.outcome.to_uppercase();
            let size = big * 1.8;
            text(
                &word,
                (
                    w / 2 - (size * 0.34 * word.len() as f64) as i32,
                    pad + (big * 3.0) as i32,
                ),
                size,
                colour,
            )?;
        }
        self.draw_scale_and_axes(root, big, small, pad)
    }

    /// A scale bar of a round length near a sixth of the width, and the axes of I from a
    /// corner (`big` and `small` the captions' text sizes, `pad` their margin).
    fn draw_scale_and_axes(
        &self,
        root: &Area<'_>,
        big: f64,
        small: f64,
        pad: i32,
    ) -> anyhow::Result<()> {
        let text = |t: &str, at, size, colour| text_at(root, t, at, size, colour);
        let (w, h) = (self.width as i32, self.height as i32);
        // A scale bar of a round length near a sixth of the width.
        let want = self.width / 6.0 / self.scale;
        let bar = [0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0]
            .into_iter()
            .rfind(|l| *l <= want)
            .unwrap_or(0.1);
        let (x0, y0) = (pad + 4, h - pad - 6);
        let x1 = x0 + (bar * self.scale).round() as i32;
        root.draw(&PathElement::new(
            vec![(x0, y0), (x1, y0)],
            INK.stroke_width(2),
        ))
        .map_err(drawing)?;
        for x in [x0, x1] {
            root.draw(&PathElement::new(
                vec![(x, y0 - 5), (x, y0 + 1)],
                INK.stroke_width(2),
            ))
            .map_err(drawing)?;
        }
        let label = if bar < 1.0 {
            format!("{:.0} cm", bar * 100.0)
        } else {
            format!("{bar:.0} m")
        };
        text(&label, (x0, y0 - 8 - small as i32), small, INK)?;
        // The axes of I, from a corner.
        let origin = (w - pad - (big * 2.5) as i32, h - pad - (big * 2.5) as i32);
        let length = big * 1.8;
        for (k, (axis, name)) in [(DVec3::X, "X"), (DVec3::Y, "Y"), (DVec3::Z, "Z")]
            .iter()
            .enumerate()
        {
            let (dx, dy) = (axis.dot(self.right) * length, -axis.dot(self.up) * length);
            let end = (origin.0 + dx.round() as i32, origin.1 + dy.round() as i32);
            root.draw(&PathElement::new(
                vec![origin, end],
                AXES[k].stroke_width(2),
            ))
            .map_err(drawing)?;
            text(name, (end.0 + 2, end.1 - small as i32 / 2), small, AXES[k])?;
        }
        Ok(())
    }
}
