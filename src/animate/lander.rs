//! The lander over the background: its shadow, the CG's trail, and its parts back to front
//! (body faces, struts and dampers, footpads, contact-force arrows, thrust plumes).

use super::camera::{Camera, View};
use super::palette::{BODY, FOOTPAD, FORCE, GROUND, PISTON, STRUT, TRAIL, shade};
use super::parts::{Part, hull};
use crate::plot::canvas::{Area, drawing};
use crate::scene::Pose;
use glam::DVec3;
use plotters::prelude::*;

/// Point `p` of B in I at `pose`.
fn world(pose: &Pose, p: DVec3) -> DVec3 {
    pose.cg + pose.attitude * p
}

impl View<'_> {
    /// The lander and its captions over the background in `rgb`.
    pub(super) fn draw_frame(
        &self,
        rgb: &mut [u8],
        c: Camera,
        pose: &Pose,
        speed: f64,
    ) -> anyhow::Result<()> {
        let root = BitMapBackend::with_buffer(rgb, (self.width as u32, self.height as u32))
            .into_drawing_area();
        self.draw_shadow(&root, c, pose)?;
        self.draw_trail(&root, c, pose)?;

        // The lander's parts (and the rocks beside it), far to near.
        let mut parts = self.body_faces(c, pose);
        let sunk = self.draw_sinkage(&root, c, pose, &mut parts)?;
        self.near_rocks(c, pose, &mut parts);
        self.leg_parts(c, pose, &sunk, &mut parts);
        self.plumes(c, pose, &mut parts);
        parts.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, part) in parts {
            part.draw(&root)?;
        }

        self.draw_captions(&root, pose, speed)?;
        root.present().map_err(drawing)?;
        Ok(())
    }

    /// `p` moved along the normal onto the surface.
    pub(super) fn on_plane(&self, p: DVec3) -> DVec3 {
        let n = self.scene.surface.normal;
        p - n * n.dot(p) + n * self.ground_height(p)
    }

    /// A disc of `radius` around `centre` in the surface plane, as 14 points in the picture.
    pub(super) fn disc(&self, c: Camera, centre: DVec3, radius: f64) -> Vec<(f64, f64, f64)> {
        let (u, v) = (self.scene.surface.tangent_u, self.scene.surface.tangent_v);
        (0..14)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from(i) / 14.0;
                self.project(c, centre + radius * (a.cos() * u + a.sin() * v))
            })
            .collect()
    }

    /// The shadow along the normal on the surface: the body's outline and the footpads.
    fn draw_shadow(&self, root: &Area<'_>, c: Camera, pose: &Pose) -> anyhow::Result<()> {
        let sk = &self.scene.sketch;
        let dark = shade(GROUND, 0.6);
        let mut outline: Vec<(f64, f64)> = sk
            .bottom
            .iter()
            .chain(&sk.top)
            .map(|p| world(pose, *p))
            .filter(|p| p.is_finite())
            .map(|p| {
                let (x, y, _) = self.project(c, self.on_plane(p));
                (x, y)
            })
            .collect();
        let outline = hull(&mut outline);
        if outline.len() >= 3 {
            let pts: Vec<(i32, i32)> = outline
                .iter()
                .map(|p| (p.0.round() as i32, p.1.round() as i32))
                .collect();
            root.draw(&Polygon::new(pts, dark.filled()))
                .map_err(drawing)?;
        }
        for tip in pose.tips.iter().filter(|t| t.is_finite()) {
            let pts: Vec<(i32, i32)> = self
                .disc(c, self.on_plane(*tip), sk.footpad_radius_m)
                .iter()
                .map(|p| (p.0.round() as i32, p.1.round() as i32))
                .collect();
            root.draw(&Polygon::new(pts, dark.filled()))
                .map_err(drawing)?;
        }
        Ok(())
    }

    /// The CG's trail so far.
    fn draw_trail(&self, root: &Area<'_>, c: Camera, pose: &Pose) -> anyhow::Result<()> {
        let trail: Vec<(i32, i32)> = self
            .path
            .iter()
            .take_while(|(t, _)| *t <= pose.t_s)
            .map(|(_, p)| self.pixel(c, *p))
            .chain(std::iter::once(self.pixel(c, pose.cg)))
            .collect();
        if trail.len() >= 2 {
            root.draw(&PathElement::new(trail, TRAIL.stroke_width(2)))
                .map_err(drawing)?;
        }
        Ok(())
    }

    /// The body's faces that face the camera, shaded, with their depths.
    fn body_faces(&self, c: Camera, pose: &Pose) -> Vec<(f64, Part)> {
        let sk = &self.scene.sketch;
        let mut parts: Vec<(f64, Part)> = Vec::new();
        let faces = (0..8)
            .map(|k| {
                vec![
                    sk.bottom[k],
                    sk.bottom[(k + 1) % 8],
                    sk.top[(k + 1) % 8],
                    sk.top[k],
                ]
            })
            .chain([sk.top.clone(), sk.bottom.iter().rev().copied().collect()]);
        for face in faces {
            let w: Vec<DVec3> = face.iter().map(|p| world(pose, *p)).collect();
            let normal = (w[1] - w[0]).cross(w[2] - w[0]).normalize_or_zero();
            if !normal.is_finite() || normal.dot(self.back) <= 0.0 {
                continue;
            }
            let pts: Vec<(f64, f64, f64)> = w.iter().map(|p| self.project(c, *p)).collect();
            let depth = pts.iter().map(|p| p.2).sum::<f64>() / pts.len() as f64;
            parts.push((depth, Part::Face(pts, shade(BODY, self.brightness(normal)))));
        }
        parts
    }

    /// Each leg's struts, damper piston, footpad and contact-force arrow, onto `parts`; a
    /// `sunk` leg's piston ends at the surface, and its footpad is `draw_sinkage`'s.
    fn leg_parts(&self, c: Camera, pose: &Pose, sunk: &[bool], parts: &mut Vec<(f64, Part)>) {
        let sk = &self.scene.sketch;
        let n = self.scene.surface.normal;
        let px = self.scale;
        for (k, leg) in sk.legs.iter().enumerate() {
            let tip = pose.tips[k];
            if !tip.is_finite() {
                continue;
            }
            let hip = world(pose, leg.hip);
            let tube_end = world(pose, leg.hip + 0.6 * (leg.tip0 - leg.hip));
            let mount = world(pose, leg.mount);
            let seg = |a: DVec3, b: DVec3, colour: RGBColor, width: f64| {
                let (pa, pb) = (self.project(c, a), self.project(c, b));
                (
                    0.5 * (pa.2 + pb.2),
                    Part::Segment(pa, pb, colour, width.max(1.0).round() as u32),
                )
            };
            parts.push(seg(hip, mount, STRUT, 0.012 * px));
            if sunk.get(k) == Some(&true) {
                // The strut and piston down to where they enter the ground.
                let above = |p: DVec3| n.dot(p) - self.ground_height(p);
                let clipped = |a: DVec3, b: DVec3| {
                    let (ha, hb) = (above(a), above(b));
                    (ha > 0.0).then(|| {
                        if hb < 0.0 {
                            a + (b - a) * (ha / (ha - hb))
                        } else {
                            b
                        }
                    })
                };
                if let Some(end) = clipped(hip, tube_end) {
                    parts.push(seg(hip, end, STRUT, 0.03 * px));
                }
                if let Some(end) = clipped(tube_end, tip) {
                    parts.push(seg(tube_end, end, shade(PISTON, 1.0), 0.016 * px));
                }
            } else {
                parts.push(seg(hip, tube_end, STRUT, 0.03 * px));
                parts.push(seg(tube_end, tip, shade(PISTON, 1.0), 0.016 * px));
                // The footpad: a disc in the surface plane.
                let depth = self.project(c, tip).2;
                parts.push((
                    depth,
                    Part::Face(self.disc(c, tip, sk.footpad_radius_m), FOOTPAD),
                ));
            }
            // The contact force along the normal, on a logarithmic length scale: the
            // weight's share of a leg at rest draws 8 cm, 100 times it 55 cm.
            let f = pose.normal_n[k];
            let rest =
                self.scene.model.mass_kg * self.scene.model.gravity_m_s2 / sk.legs.len() as f64;
            if f > 1e-3 * rest {
                let length = 0.12 * (1.0 + f / rest).ln();
                let (a, b) = (self.project(c, tip), self.project(c, tip + n * length));
                parts.push((a.2.max(b.2) + 1e-3, Part::Arrow(a, b, FORCE)));
            }
        }
    }

    /// The plume of every firing thruster, onto `parts`.
    fn plumes(&self, c: Camera, pose: &Pose, parts: &mut Vec<(f64, Part)>) {
        let q = pose.attitude;
        let px = self.scale;
        for (j, t) in self.scene.sketch.thrusters.iter().enumerate() {
            let f = pose.thrust_n.get(j).copied().unwrap_or(0.0);
            if f <= 0.0 || t.max_thrust_n <= 0.0 {
                continue;
            }
            let nozzle = world(pose, t.position);
            let length = 0.1 + 0.3 * (f / t.max_thrust_n).min(1.5);
            let end = nozzle - (q * t.direction) * length;
            let (a, b) = (self.project(c, nozzle), self.project(c, end));
            parts.push((0.5 * (a.2 + b.2), Part::Plume(a, b, 0.3 * length * px)));
        }
    }
}
