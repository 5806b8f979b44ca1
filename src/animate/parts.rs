//! The parts of the lander as drawn (faces, segments, arrows, plumes in pixels with their
//! depth, and the rocks beside them), and the convex hull of its shadow.

use super::palette::{PLUME, shade};
use crate::plot::canvas::{Area, drawing};
use plotters::prelude::*;

/// A part of the lander in the picture (points with their depth).
pub(super) enum Part {
    Face(Vec<(f64, f64, f64)>, RGBColor),
    Segment((f64, f64, f64), (f64, f64, f64), RGBColor, u32),
    Arrow((f64, f64, f64), (f64, f64, f64), RGBColor),
    /// From the nozzle to the plume's end, with its half-width there in pixels.
    Plume((f64, f64, f64), (f64, f64, f64), f64),
    /// A rock: its facets with their shades, then its outline in a colour.
    Rock(Vec<(Vec<(i32, i32)>, RGBColor)>, Vec<(i32, i32)>, RGBColor),
}

impl Part {
    /// Draws the part on `root`.
    pub(super) fn draw(&self, root: &Area<'_>) -> anyhow::Result<()> {
        let p = |q: &(f64, f64, f64)| (q.0.round() as i32, q.1.round() as i32);
        match self {
            Part::Face(pts, colour) => {
                let pts: Vec<(i32, i32)> = pts.iter().map(p).collect();
                root.draw(&Polygon::new(pts.clone(), colour.filled()))
                    .map_err(drawing)?;
                let mut edge = pts;
                edge.push(edge[0]);
                root.draw(&PathElement::new(
                    edge,
                    shade(*colour, 0.75).stroke_width(1),
                ))
                .map_err(drawing)?;
            }
            Part::Segment(a, b, colour, width) => {
                root.draw(&PathElement::new(
                    vec![p(a), p(b)],
                    colour.stroke_width(*width),
                ))
                .map_err(drawing)?;
            }
            Part::Arrow(a, b, colour) => {
                let (dx, dy) = (b.0 - a.0, b.1 - a.1);
                let len = dx.hypot(dy);
                root.draw(&PathElement::new(vec![p(a), p(b)], colour.stroke_width(3)))
                    .map_err(drawing)?;
                if len > 4.0 {
                    let (ux, uy) = (dx / len, dy / len);
                    let head = len.min(12.0);
                    let base = (b.0 - ux * head, b.1 - uy * head);
                    let side = (-uy * head * 0.45, ux * head * 0.45);
                    let tri = vec![
                        p(b),
                        p(&(base.0 + side.0, base.1 + side.1, 0.0)),
                        p(&(base.0 - side.0, base.1 - side.1, 0.0)),
                    ];
                    root.draw(&Polygon::new(tri, colour.filled()))
                        .map_err(drawing)?;
                }
            }
            Part::Rock(facets, outline, edge) => {
                for (pts, colour) in facets {
                    root.draw(&Polygon::new(pts.clone(), colour.filled()))
                        .map_err(drawing)?;
                }
                root.draw(&PathElement::new(outline.clone(), edge.stroke_width(1)))
                    .map_err(drawing)?;
            }
            Part::Plume(a, b, half_width) => {
                let (dx, dy) = (b.0 - a.0, b.1 - a.1);
                let len = dx.hypot(dy);
                if len < 2.0 {
                    root.draw(&Circle::new(
                        p(a),
                        half_width.max(2.0) as i32,
                        PLUME.filled(),
                    ))
                    .map_err(drawing)?;
                } else {
                    let side = (-dy / len * half_width, dx / len * half_width);
                    let tri = vec![
                        p(a),
                        p(&(b.0 + side.0, b.1 + side.1, 0.0)),
                        p(&(b.0 - side.0, b.1 - side.1, 0.0)),
                    ];
                    root.draw(&Polygon::new(tri, PLUME.filled()))
                        .map_err(drawing)?;
                }
            }
        }
        Ok(())
    }
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
pub(super) fn hull(points: &mut [(f64, f64)]) -> Vec<(f64, f64)> {
    points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    if points.len() < 3 {
        return points.to_vec();
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(2 * points.len());
    for pass in 0..2 {
        let start = out.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for &p in iter {
            while out.len() >= start + 2 && cross(out[out.len() - 2], out[out.len() - 1], p) <= 0.0
            {
                out.pop();
            }
            out.push(p);
        }
        out.pop();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_a_square_and_its_centre() {
        let mut p = vec![(0.0, 0.0), (1.0, 0.0), (0.5, 0.5), (1.0, 1.0), (0.0, 1.0)];
        let h = hull(&mut p);
        assert_eq!(h.len(), 4);
        assert!(!h.contains(&(0.5, 0.5)));
    }
}
