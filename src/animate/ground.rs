//! The background of a frame: the ground patch shaded face by face, its grid of whole
//! metres, its rocks and the slab's sides that face the viewer.

use super::camera::{Camera, View};
use super::palette::{BACKGROUND, GROUND, shade};
use crate::plot::canvas::drawing;
use glam::DVec3;
use plotters::prelude::*;

impl View<'_> {
    /// The background of a frame: the ground patch, shaded face by face, and its grid of
    /// whole metres.
    pub(super) fn draw_ground(&self, rgb: &mut [u8], c: Camera) -> anyhow::Result<()> {
        let root = BitMapBackend::with_buffer(rgb, (self.width as u32, self.height as u32))
            .into_drawing_area();
        root.fill(&BACKGROUND).map_err(drawing)?;
        let g = &self.ground;
        let mut quads = Vec::with_capacity(g.nu * g.nv);
        for j in 0..g.nv.saturating_sub(1) {
            for i in 0..g.nu.saturating_sub(1) {
                let p = [
                    g.node(i, j),
                    g.node(i + 1, j),
                    g.node(i + 1, j + 1),
                    g.node(i, j + 1),
                ];
                let pts: Vec<(f64, f64, f64)> = p.iter().map(|q| self.project(c, *q)).collect();
                if pts.iter().all(|q| q.0 < -2.0)
                    || pts.iter().all(|q| q.0 > self.width + 2.0)
                    || pts.iter().all(|q| q.1 < -2.0)
                    || pts.iter().all(|q| q.1 > self.height + 2.0)
                {
                    continue;
                }
                let n = (p[1] - p[0]).cross(p[3] - p[0]).normalize_or(g.normal);
                let n = if n.dot(g.normal) < 0.0 { -n } else { n };
                let depth = pts.iter().map(|q| q.2).sum::<f64>();
                // Coarser steps than the lander's: the ground changes
                // whole when the camera moves, and fewer shades keep the frames small.
                let b = (self.brightness(n) * 8.0).round() / 8.0;
                quads.push((depth, pts, shade(GROUND, b)));
            }
        }
        quads.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, pts, colour) in quads {
            let pts: Vec<(i32, i32)> = pts
                .iter()
                .map(|q| (q.0.round() as i32, q.1.round() as i32))
                .collect();
            root.draw(&Polygon::new(pts, colour.filled()))
                .map_err(drawing)?;
        }
        // Grid lines on whole metres (or on whole nodes, where nodes are farther apart).
        let step = g.spacing_m.max(1.0);
        let on_line = |x: f64| ((x / step) - (x / step).round()).abs() < 1e-6;
        let line = shade(GROUND, 0.62);
        let (u0, v0) = (g.origin.dot(g.u), g.origin.dot(g.v));
        for i in (0..g.nu).filter(|i| on_line(u0 + *i as f64 * g.spacing_m)) {
            let pts: Vec<(i32, i32)> = (0..g.nv).map(|j| self.pixel(c, g.node(i, j))).collect();
            root.draw(&PathElement::new(pts, line.stroke_width(1)))
                .map_err(drawing)?;
        }
        for j in (0..g.nv).filter(|j| on_line(v0 + *j as f64 * g.spacing_m)) {
            let pts: Vec<(i32, i32)> = (0..g.nu).map(|i| self.pixel(c, g.node(i, j))).collect();
            root.draw(&PathElement::new(pts, line.stroke_width(1)))
                .map_err(drawing)?;
        }
        self.draw_rocks(&root, c)?;
        // The patch's edges that face the viewer, as a slab's sides hanging 0.3 m down.
        let (nu, nv) = (g.nu, g.nv);
        let edges: [(Vec<(usize, usize)>, DVec3); 4] = [
            ((0..nu).map(|i| (i, 0)).collect(), -g.v),
            ((0..nu).map(|i| (i, nv - 1)).collect(), g.v),
            ((0..nv).map(|j| (0, j)).collect(), -g.u),
            ((0..nv).map(|j| (nu - 1, j)).collect(), g.u),
        ];
        for (nodes, outward) in edges {
            if outward.dot(self.back) <= 0.0 {
                continue;
            }
            let side = shade(
                GROUND,
                if outward.dot(self.light) > 0.0 {
                    0.75
                } else {
                    0.5
                },
            );
            for pair in nodes.windows(2) {
                let (a, b) = (g.node(pair[0].0, pair[0].1), g.node(pair[1].0, pair[1].1));
                let drop = DVec3::Z * 0.3;
                let pts = vec![
                    self.pixel(c, a),
                    self.pixel(c, b),
                    self.pixel(c, b - drop),
                    self.pixel(c, a - drop),
                ];
                root.draw(&Polygon::new(pts, side.filled()))
                    .map_err(drawing)?;
            }
        }
        root.present().map_err(drawing)?;
        Ok(())
    }
}
