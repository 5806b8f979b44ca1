//! The orthographic view of the frames: the camera's axes and scale, still or following
//! the CG in glides, and where a point of I falls in the picture.

use crate::scene::{Footprint, Ground, RockShape, Scene};
use glam::DVec3;

/// Where the camera looks: the point at the picture's centre (the view's axes and scale
/// stay fixed, in `View`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Camera {
    /// The point at the picture's centre, in I.
    pub(super) target: DVec3,
}

/// What stays fixed over the frames: the scene, the view's axes and scale, the ground.
pub(super) struct View<'a> {
    /// The trace drawn.
    pub(super) scene: &'a Scene,
    /// The picture's rightward direction in I.
    pub(super) right: DVec3,
    /// The picture's upward direction in I.
    pub(super) up: DVec3,
    /// Towards the viewer, in I.
    pub(super) back: DVec3,
    /// Pixels per metre.
    pub(super) scale: f64,
    /// The picture's width, pixels.
    pub(super) width: f64,
    /// The picture's height, pixels.
    pub(super) height: f64,
    /// Whether the whole path fits the picture (a still camera) or the camera follows.
    pub(super) still: Option<DVec3>,
    /// The ground patch under the path.
    pub(super) ground: Ground,
    /// The CG's path, thinned to points at least 5 mm apart, with their times.
    pub(super) path: Vec<(f64, DVec3)>,
    /// Unit direction towards the light, in I.
    pub(super) light: DVec3,
    /// The rocks on the ground patch that show at this scale.
    pub(super) rocks: Vec<RockShape>,
    /// The footprints on regolith, in order of lift-off.
    pub(super) footprints: Vec<Footprint>,
}

/// Camera elevation above the horizontal, deg, and its azimuth from the downhill
/// direction's side (a three-quarter view from slightly downhill).
const ELEVATION_DEG: f64 = 24.0;
const AZIMUTH_FROM_SIDE_DEG: f64 = 20.0;

/// Frames a following camera takes to glide to the lander.
const GLIDE_FRAMES: usize = 12;

impl<'a> View<'a> {
    /// The view of `scene` in a picture of `width` by `height` pixels.
    pub(super) fn new(scene: &'a Scene, width: u32, height: u32) -> View<'a> {
        let az = (scene.trace.downhill_azimuth_deg() - 90.0 + AZIMUTH_FROM_SIDE_DEG).to_radians();
        let el = ELEVATION_DEG.to_radians();
        let back = DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let right = DVec3::Z.cross(back).normalize();
        let up = back.cross(right);
        let (width, height) = (f64::from(width), f64::from(height));
        let reach_m = scene.sketch.reach_m();
        let path_all = scene.trace.cg_path();
        let mut path: Vec<(f64, DVec3)> = Vec::new();
        for (t, p) in scene.trace.time.iter().zip(&path_all) {
            if path.last().is_none_or(|(_, q)| q.distance(*p) >= 0.005) && p.is_finite() {
                path.push((*t, *p));
            }
        }
        if let (Some(last), Some(p)) = (path_all.last(), path.last())
            && last.is_finite()
            && *last != p.1
        {
            path.push((scene.trace.span_s().1, *last));
        }
        // Frame the whole path with the lander around it when that keeps the lander at
        // least a quarter of the picture's height; else follow it at that size.
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (_, p) in &path {
            for (k, axis) in [right, up].iter().enumerate() {
                lo[k] = lo[k].min(axis.dot(*p));
                hi[k] = hi[k].max(axis.dot(*p));
            }
        }
        let margin = 1.25 * reach_m;
        let (span_x, span_y) = (hi[0] - lo[0] + 2.0 * margin, hi[1] - lo[1] + 2.0 * margin);
        let closest = height / (3.2 * reach_m);
        let farthest = height / (8.0 * reach_m);
        let fit = (width / span_x).min(height / span_y);
        let (scale, still) = if fit >= farthest {
            let mid = (lo[0] + hi[0]) / 2.0 * right + (lo[1] + hi[1]) / 2.0 * up;
            (fit.min(closest), Some(mid))
        } else {
            (height / (4.5 * reach_m), None)
        };
        // The ground under the path, a margin of twice the lander's reach around it: its
        // edges against the background show the slope.
        let rough = scene.model.terrain.is_some();
        let ground = scene.ground(2.5 * reach_m, if rough { 0.1 } else { 0.5 }, 60_000);
        let light = (0.35 * right + 0.6 * back + 0.9 * DVec3::Z).normalize();
        let mut view = View {
            scene,
            right,
            up,
            back,
            scale,
            width,
            height,
            still,
            ground,
            path,
            light,
            rocks: Vec::new(),
            footprints: scene.footprints(),
        };
        view.rocks = view.visible_rocks();
        view
    }

    /// The camera of the first frame.
    pub(super) fn start_camera(&self) -> Camera {
        Camera {
            target: self
                .still
                .unwrap_or_else(|| self.path.first().map_or(DVec3::ZERO, |p| p.1)),
        }
    }

    /// The camera of each frame at `times`: still, or following the CG in glides. The
    /// camera stays put while the CG is in the middle part of the picture; once it leaves
    /// that, the camera glides over `GLIDE_FRAMES` frames to where the CG will be at the
    /// glide's end, and stays put again. A still camera between glides is what keeps the
    /// frames small (an unchanged ground is not stored again).
    pub(super) fn cameras(&self, times: &[f64]) -> Vec<Camera> {
        let mut c = self.start_camera();
        if self.still.is_some() {
            return vec![c; times.len()];
        }
        let cg = |k: usize| {
            let t = times[k.min(times.len() - 1)];
            let s = self.scene;
            DVec3::new(
                s.trace.value("x_m", t),
                s.trace.value("y_m", t),
                s.trace.value("z_m", t),
            )
        };
        let (bx, by) = (
            0.25 * self.width / self.scale,
            0.2 * self.height / self.scale,
        );
        let mut out = Vec::with_capacity(times.len());
        let mut glide: Option<(DVec3, DVec3, usize)> = None;
        for k in 0..times.len() {
            if glide.is_none() {
                let d = cg(k) - c.target;
                if d.is_finite() && (d.dot(self.right).abs() > bx || d.dot(self.up).abs() > by) {
                    let to = cg(k + GLIDE_FRAMES - 1);
                    let to = if to.is_finite() { to } else { cg(k) };
                    glide = Some((c.target, to, k));
                }
            }
            if let Some((from, to, start)) = glide {
                let f = ((k - start + 1) as f64 / GLIDE_FRAMES as f64).min(1.0);
                // Smoothstep: the glide starts and ends at rest.
                let e = f * f * (3.0 - 2.0 * f);
                c = Camera {
                    target: from + (to - from) * e,
                };
                if f >= 1.0 {
                    glide = None;
                }
            }
            out.push(c);
        }
        out
    }

    /// Where `p` falls in the picture, and its depth (larger: nearer the viewer).
    pub(super) fn project(&self, c: Camera, p: DVec3) -> (f64, f64, f64) {
        let d = p - c.target;
        (
            0.5 * self.width + self.scale * d.dot(self.right),
            0.5 * self.height - self.scale * d.dot(self.up),
            d.dot(self.back),
        )
    }

    /// The pixel `p` falls on.
    pub(super) fn pixel(&self, c: Camera, p: DVec3) -> (i32, i32) {
        let (x, y, _) = self.project(c, p);
        (x.round() as i32, y.round() as i32)
    }

    /// Lambert brightness of a face of normal `n`.
    pub(super) fn brightness(&self, n: DVec3) -> f64 {
        0.5 + 0.6 * n.dot(self.light).max(0.0)
    }

    /// Height of the terrain at `p` along the normal (0 on a plane).
    pub(super) fn ground_height(&self, p: DVec3) -> f64 {
        let s = &self.scene.surface;
        s.height(self.scene.model.terrain.as_ref(), p).0
    }
}
