//! What the ground holds besides its patch: the rocks, as shaded hemispheres, and on
//! regolith the footprints left and the holes of the footpads sunk in it.
//!
//! Every rock is drawn with the background (far to near, over the grid); those that may
//! overlap the lander are drawn again among its parts, so that a rock in front of a leg
//! hides it and a footpad on a rock's top shows over it. A sunk footpad is seen through its
//! hole: the hole's opening at the surface, darker ground, and of the footpad only what the
//! opening shows.

use super::camera::{Camera, View};
use super::palette::{FOOTPAD, GROUND, shade};
use super::parts::Part;
use crate::plot::canvas::{Area, drawing};
use crate::scene::{Pose, RockShape};
use glam::DVec3;
use plotters::prelude::*;

/// The rocks' colour, a grey of the palette's.
const ROCK: RGBColor = RGBColor(172, 168, 162);

/// Rocks smaller than this in the picture are not drawn, pixels of radius.
const SMALLEST_PX: f64 = 0.75;

/// A point in the picture with its depth.
type Point = (f64, f64, f64);

impl View<'_> {
    /// The rocks of the scene within the ground patch large enough to see at this scale.
    pub(super) fn visible_rocks(&self) -> Vec<RockShape> {
        let mut rocks = self.scene.rocks(&self.ground);
        rocks.retain(|r| r.radius_m * self.scale >= SMALLEST_PX);
        rocks
    }

    /// Every rock, far to near, onto the background.
    pub(super) fn draw_rocks(&self, root: &Area<'_>, c: Camera) -> anyhow::Result<()> {
        let mut drawn: Vec<(f64, Part)> = self
            .rocks
            .iter()
            .filter_map(|r| self.rock_part(c, r))
            .collect();
        drawn.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, part) in drawn {
            part.draw(root)?;
        }
        Ok(())
    }

    /// The rocks that may overlap the lander at `pose`, onto `parts` (drawn again over the
    /// background, in depth order with the lander's parts).
    pub(super) fn near_rocks(&self, c: Camera, pose: &Pose, parts: &mut Vec<(f64, Part)>) {
        let (x, y, _) = self.project(c, pose.cg);
        let reach = self.scene.sketch.reach_m() * self.scale + 4.0;
        for r in &self.rocks {
            let (rx, ry, _) = self.project(c, r.centre);
            let size = r.radius_m * self.scale;
            if (rx - x).abs() <= reach + size && (ry - y).abs() <= reach + size {
                parts.extend(self.rock_part(c, r));
            }
        }
    }

    /// A rock as a part: the facets of its dome that face the viewer, Lambert-shaded, and
    /// its outline; its depth is its centre's (a footpad on its top is nearer, one behind
    /// it farther). `None` when it is outside the picture.
    fn rock_part(&self, c: Camera, r: &RockShape) -> Option<(f64, Part)> {
        let n = self.scene.surface.normal;
        let centre = self.project(c, r.centre);
        let px = r.radius_m * self.scale;
        if centre.0 < -px - 2.0
            || centre.0 > self.width + px + 2.0
            || centre.1 < -2.0 * px - 2.0
            || centre.1 > self.height + px + 2.0
        {
            return None;
        }
        let (u, v) = (self.scene.surface.tangent_u, self.scene.surface.tangent_v);
        // Rings from the base to the top and sectors around: fewer for small rocks.
        let (rings, sectors) = if px < 6.0 { (2, 8) } else { (4, 14) };
        let at = |ring: usize, sector: usize| {
            let e = std::f64::consts::FRAC_PI_2 * ring as f64 / rings as f64;
            let a = std::f64::consts::TAU * sector as f64 / sectors as f64;
            e.cos() * (a.cos() * u + a.sin() * v) + e.sin() * n
        };
        let mut facets = Vec::new();
        for ring in 0..rings {
            for sector in 0..sectors {
                let corners = [
                    at(ring, sector),
                    at(ring, sector + 1),
                    at(ring + 1, sector + 1),
                    at(ring + 1, sector),
                ];
                let normal = corners.iter().sum::<DVec3>().normalize_or(n);
                if normal.dot(self.back) <= 0.0 {
                    continue;
                }
                let pts: Vec<(i32, i32)> = corners
                    .iter()
                    .map(|d| self.pixel(c, r.centre + *d * r.radius_m))
                    .collect();
                facets.push((pts, shade(ROCK, self.brightness(normal))));
            }
        }
        let outline = self
            .rock_outline(r)
            .iter()
            .map(|p| self.pixel(c, *p))
            .collect();
        Some((centre.2, Part::Rock(facets, outline, shade(ROCK, 0.5))))
    }

    /// The outline of a rock in I: over its dome where the sky shows behind it, then along
    /// the near half of its base.
    fn rock_outline(&self, r: &RockShape) -> Vec<DVec3> {
        let n = self.scene.surface.normal;
        // `w` across the view in the base plane; the dome's silhouette is the great circle
        // across the view, from `w` over the top (`up`) to `-w`; the base's near half from
        // `-w` through `near` back to `w`.
        let w = n
            .cross(self.back)
            .normalize_or(self.scene.surface.tangent_u);
        let up = self.back.cross(w).normalize_or(n);
        let up = if up.dot(n) < 0.0 { -up } else { up };
        let near = n.cross(w);
        let near = if near.dot(self.back) < 0.0 {
            -near
        } else {
            near
        };
        (0..=24)
            .map(|k| {
                let a = std::f64::consts::PI * f64::from(k) / 12.0;
                let d = if k <= 12 {
                    a.cos() * w + a.sin() * up
                } else {
                    a.cos() * w - a.sin() * near
                };
                r.centre + d * r.radius_m
            })
            .collect()
    }

    /// On regolith, the footprints left by `pose.t_s` and the hole of every footpad sunk
    /// now, over the background; each sunk footpad, as much of it as its hole shows, onto
    /// `parts`. Returns the sunk legs (whose pistons end at the surface).
    pub(super) fn draw_sinkage(
        &self,
        root: &Area<'_>,
        c: Camera,
        pose: &Pose,
        parts: &mut Vec<(f64, Part)>,
    ) -> anyhow::Result<Vec<bool>> {
        let mut sunk = vec![false; pose.tips.len()];
        if !self.scene.on_regolith() {
            return Ok(sunk);
        }
        let radius = self.scene.sketch.footpad_radius_m;
        let hole = shade(GROUND, 0.45);
        let dark = |pts: Vec<Point>| -> anyhow::Result<()> {
            let pts: Vec<(i32, i32)> = pts
                .iter()
                .map(|p| (p.0.round() as i32, p.1.round() as i32))
                .collect();
            root.draw(&Polygon::new(pts.clone(), hole.filled()))
                .map_err(drawing)?;
            let mut edge = pts;
            edge.push(edge[0]);
            root.draw(&PathElement::new(edge, shade(GROUND, 0.35).stroke_width(1)))
                .map_err(drawing)?;
            Ok(())
        };
        for f in self
            .footprints
            .iter()
            .take_while(|f| f.lifted_s <= pose.t_s)
        {
            dark(self.disc(c, f.centre, radius))?;
        }
        for (k, tip) in pose.tips.iter().enumerate() {
            if !(tip.is_finite() && self.scene.sinkage_m(k, pose.t_s) > 0.0) {
                continue;
            }
            sunk[k] = true;
            // The footpad under the ground, dashed; its hole's opening over it.
            let under = self.disc(c, *tip, radius);
            for pair in under.chunks_exact(2) {
                let ends = pair
                    .iter()
                    .map(|p| (p.0.round() as i32, p.1.round() as i32));
                root.draw(&PathElement::new(
                    ends.collect::<Vec<_>>(),
                    FOOTPAD.stroke_width(1),
                ))
                .map_err(drawing)?;
            }
            let opening = self.disc(c, self.on_plane(*tip), radius);
            dark(opening.clone())?;
            let pad = clip(&self.disc(c, *tip, radius), &opening);
            if pad.len() >= 3 {
                parts.push((self.project(c, *tip).2, Part::Face(pad, FOOTPAD)));
            }
        }
        Ok(sunk)
    }
}

/// The convex polygon `subject` clipped to the convex polygon `window` (Sutherland and
/// Hodgman), in the picture; depths are carried along.
fn clip(subject: &[Point], window: &[Point]) -> Vec<Point> {
    let area: f64 = (0..window.len())
        .map(|i| {
            let (a, b) = (window[i], window[(i + 1) % window.len()]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    let sign = if area < 0.0 { -1.0 } else { 1.0 };
    let mut out = subject.to_vec();
    for i in 0..window.len() {
        let (a, b) = (window[i], window[(i + 1) % window.len()]);
        let side = |p: &Point| sign * ((b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0));
        let input = std::mem::take(&mut out);
        for j in 0..input.len() {
            let (p, q) = (input[j], input[(j + 1) % input.len()]);
            let (sp, sq) = (side(&p), side(&q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let f = sp / (sp - sq);
                out.push((
                    p.0 + f * (q.0 - p.0),
                    p.1 + f * (q.1 - p.1),
                    p.2 + f * (q.2 - p.2),
                ));
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_clipped_by_a_shifted_square_is_their_overlap() {
        let square = |x: f64| {
            vec![
                (x, 0.0, 0.0),
                (x + 2.0, 0.0, 0.0),
                (x + 2.0, 2.0, 0.0),
                (x, 2.0, 0.0),
            ]
        };
        let overlap = clip(&square(0.0), &square(1.0));
        let xs: Vec<f64> = overlap.iter().map(|p| p.0).collect();
        assert_eq!(overlap.len(), 4);
        assert!(xs.iter().all(|x| (1.0..=2.0).contains(x)), "{overlap:?}");
        // Either orientation of the window.
        let mut reversed = square(1.0);
        reversed.reverse();
        assert_eq!(clip(&square(0.0), &reversed).len(), 4);
        assert!(clip(&square(0.0), &square(5.0)).is_empty());
    }
}
