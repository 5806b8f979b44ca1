//! `touchdown animate`: a GIF of one touchdown from its trace file.
//!
//! Each frame is drawn in an orthographic view (equal scales on every axis) with plotters
//! on a bitmap: the slope as a shaded patch with a 1 m grid, the lander's shadow along the
//! normal, the CG's trail, then the lander's parts back to front (the body's faces that face
//! the camera, the struts with their dampers' stroke, the footpads, the contact-force
//! arrows and the thrust plumes), and the captions. Frames map onto one fixed palette, and
//! each stores only the rectangle that changed, its unchanged pixels transparent, so that
//! a still camera costs little.

use crate::output::AtomicFile;
use crate::plot::canvas::{FONT, OUTCOME_COLOURS, drawing, register_font};
use crate::reference::Outcome;
use crate::scene::{Ground, Pose, Scene};
use anyhow::{anyhow, bail};
use glam::DVec3;
use plotters::prelude::*;
use std::borrow::Cow;
use std::path::Path;

/// How to render an animation.
#[derive(Debug, Clone, Copy)]
pub struct Options {
    /// Frames per second of playback.
    pub fps: f64,
    /// Trace seconds per second of playback (default: `default_speed`).
    pub speed: Option<f64>,
    pub width: u32,
    pub height: u32,
}

/// Playback that a trace takes by default, s.
pub const DEFAULT_PLAYBACK_S: f64 = 15.0;

/// Most frames an animation has (at 15 fps, 11 minutes of playback).
pub const MAX_FRAMES: usize = 10_000;

/// How long the last frame stays before the loop starts again, in 1/100 s.
pub const FINAL_HOLD_CS: u16 = 200;

/// The speed a trace of `duration_s` plays at by default: in `DEFAULT_PLAYBACK_S`, never
/// slower than real time.
#[must_use]
pub fn default_speed(duration_s: f64) -> f64 {
    (duration_s / DEFAULT_PLAYBACK_S).max(1.0)
}

/// The number of frames of a trace from `t0` to `t1` played at `speed` and `fps`: one every
/// `speed / fps` trace seconds from `t0`, and one at `t1`.
#[must_use]
pub fn frame_count(t0: f64, t1: f64, speed: f64, fps: f64) -> f64 {
    ((t1 - t0) * fps / speed - 1e-9).ceil().max(0.0) + 1.0
}

/// The times of the frames (`frame_count` of them, at most `MAX_FRAMES`).
#[must_use]
pub fn frame_times(t0: f64, t1: f64, speed: f64, fps: f64) -> Vec<f64> {
    let step = speed / fps;
    let frames = frame_count(t0, t1, speed, fps).min(MAX_FRAMES as f64) as usize;
    (0..frames)
        .map(|k| (t0 + k as f64 * step).min(t1))
        .collect()
}

/// The delay of frame `k` of `frames` at `fps`, in 1/100 s: the frames keep to the clock
/// (each ends at the nearest 1/100 s to `(k + 1) / fps`), and the last stays
/// `FINAL_HOLD_CS` longer.
#[must_use]
pub fn frame_delay_cs(k: usize, frames: usize, fps: f64) -> u16 {
    let at = |k: usize| (100.0 * k as f64 / fps).round() as i64;
    let d = (at(k + 1) - at(k)).clamp(1, 65_000) as u16;
    if k + 1 == frames {
        d + FINAL_HOLD_CS
    } else {
        d
    }
}

/// What `animate` wrote.
#[derive(Debug, Clone, Copy)]
pub struct Rendered {
    pub frames: usize,
    pub speed: f64,
    /// Playback of one loop, the final hold included, s.
    pub playback_s: f64,
    pub bytes: u64,
    /// The trace's rows are every `every` steps.
    pub every: u64,
}

/// Checks the options: a clear message for each wrong one.
pub fn check(o: &Options) -> anyhow::Result<()> {
    if !(o.fps >= 1.0 && o.fps <= 50.0) {
        bail!(
            "--fps {}: from 1 to 50 (a GIF counts time in 1/100 s, and viewers show frames \
             shorter than 2/100 s at 1/10 s)",
            o.fps
        );
    }
    if let Some(s) = o.speed
        && !(s.is_finite() && s > 0.0 && s <= 1e4)
    {
        bail!("--speed {s}: a playback speed greater than 0 and at most 10000");
    }
    if !(160..=1920).contains(&o.width) || !(120..=1080).contains(&o.height) {
        bail!(
            "--size {}x{}: from 160x120 to 1920x1080 pixels",
            o.width,
            o.height
        );
    }
    Ok(())
}

/// Writes the GIF of the trace at `trace` to `out`.
pub fn animate(trace: &Path, out: &Path, o: &Options) -> anyhow::Result<Rendered> {
    check(o)?;
    crate::output::check_output_path(out)?;
    crate::scene::refuse_overwriting(trace, out)?;
    let scene = Scene::read(trace)?;
    register_font()?;
    let (t0, t1) = scene.span_s();
    let speed = o.speed.unwrap_or_else(|| default_speed(t1 - t0));
    let frames = frame_count(t0, t1, speed, o.fps);
    if frames > MAX_FRAMES as f64 {
        bail!(
            "--speed {speed} at --fps {}: {frames:.0} frames for the {:.3} s of {}, more than \
             {MAX_FRAMES}; a larger --speed or a smaller --fps",
            o.fps,
            t1 - t0,
            trace.display()
        );
    }
    let times = frame_times(t0, t1, speed, o.fps);
    let (w, h) = (o.width as usize, o.height as usize);
    let view = View::new(&scene, o.width, o.height);
    let palette = Palette::new();

    let (file, mut sink) = AtomicFile::create(out)?;
    let context = |e: gif::EncodingError| anyhow!("cannot write {}: {e}", out.display());
    let mut counted = Counted {
        inner: &mut sink,
        bytes: 0,
    };
    {
        let mut encoder =
            gif::Encoder::new(&mut counted, o.width as u16, o.height as u16, &palette.rgb)
                .map_err(context)?;
        encoder.set_repeat(gif::Repeat::Infinite).map_err(context)?;
        let mut rgb = vec![0u8; w * h * 3];
        let mut previous: Option<Vec<u8>> = None;
        let mut since = t0;
        let cameras = view.cameras(&times);
        let mut background: Option<(Camera, Vec<u8>)> = None;
        let mut playback_cs = 0u64;
        for (k, &t) in times.iter().enumerate() {
            let pose = scene.pose(since, t);
            since = t;
            let camera = cameras[k];
            // The ground and grid depend on the camera alone: drawn again when it moves.
            match &background {
                Some((at, pixels)) if *at == camera => rgb.copy_from_slice(pixels),
                _ => {
                    view.draw_ground(&mut rgb, camera)?;
                    background = Some((camera, rgb.clone()));
                }
            }
            view.draw_frame(&mut rgb, camera, &pose, speed)?;
            let indexed = palette.index(&rgb);
            let delay = frame_delay_cs(k, times.len(), o.fps);
            playback_cs += u64::from(delay);
            let frame = changed_frame(previous.as_deref(), &indexed, w, h, delay);
            encoder.write_frame(&frame).map_err(context)?;
            previous = Some(indexed);
        }
        drop(encoder);
        let bytes = counted.bytes;
        file.commit(sink)?;
        Ok(Rendered {
            frames: times.len(),
            speed,
            playback_s: playback_cs as f64 / 100.0,
            bytes,
            every: scene.every,
        })
    }
}

/// A writer that counts what passes.
struct Counted<'a, W: std::io::Write> {
    inner: &'a mut W,
    bytes: u64,
}

impl<W: std::io::Write> std::io::Write for Counted<'_, W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.bytes += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// The palette index that marks a pixel unchanged since the previous frame.
const TRANSPARENT: u8 = 255;

/// The GIF frame of `now` after `before`: the rectangle of the pixels that changed, those
/// that did not transparent (the first frame whole).
fn changed_frame<'a>(
    before: Option<&[u8]>,
    now: &'a [u8],
    w: usize,
    h: usize,
    delay: u16,
) -> gif::Frame<'a> {
    let whole = |buffer: Cow<'a, [u8]>, transparent| gif::Frame {
        delay,
        dispose: gif::DisposalMethod::Keep,
        transparent,
        width: w as u16,
        height: h as u16,
        buffer,
        ..gif::Frame::default()
    };
    let Some(before) = before else {
        return whole(Cow::Borrowed(now), None);
    };
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
    for y in 0..h {
        let row = y * w;
        for x in 0..w {
            if before[row + x] != now[row + x] {
                x0 = x0.min(x);
                x1 = x1.max(x + 1);
                y0 = y0.min(y);
                y1 = y1.max(y + 1);
            }
        }
    }
    if x1 <= x0 {
        // Nothing changed: one transparent pixel carries the delay.
        return gif::Frame {
            width: 1,
            height: 1,
            buffer: Cow::Owned(vec![TRANSPARENT]),
            ..whole(Cow::Borrowed(&[]), Some(TRANSPARENT))
        };
    }
    let mut buffer = Vec::with_capacity((x1 - x0) * (y1 - y0));
    for y in y0..y1 {
        for x in x0..x1 {
            let i = y * w + x;
            buffer.push(if before[i] == now[i] {
                TRANSPARENT
            } else {
                now[i]
            });
        }
    }
    gif::Frame {
        left: x0 as u16,
        top: y0 as u16,
        width: (x1 - x0) as u16,
        height: (y1 - y0) as u16,
        ..whole(Cow::Owned(buffer), Some(TRANSPARENT))
    }
}

// Colours of the picture.
const BACKGROUND: RGBColor = RGBColor(250, 250, 252);
const GROUND: RGBColor = RGBColor(158, 146, 132);
const BODY: RGBColor = RGBColor(214, 162, 42);
const STRUT: RGBColor = RGBColor(70, 72, 80);
const PISTON: RGBColor = RGBColor(175, 178, 186);
const FOOTPAD: RGBColor = RGBColor(55, 58, 66);
const TRAIL: RGBColor = RGBColor(31, 119, 180);
const FORCE: RGBColor = RGBColor(214, 39, 40);
const PLUME: RGBColor = RGBColor(110, 190, 255);
const INK: RGBColor = RGBColor(20, 20, 24);
/// Outcome colours in the order of `Outcome::ALL`, as the sweep plots draw them.
const OUTCOME: [RGBColor; 5] = OUTCOME_COLOURS;
/// X_I, Y_I, Z_I of the axis triad.
const AXES: [RGBColor; 3] = [
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(31, 119, 180),
];

/// Brightness levels a shaded material takes (so that its shades are palette entries).
const SHADES: usize = 20;

/// A material's colour at brightness `b` (about 0.3 to 1.15), on one of `SHADES` levels.
fn shade(c: RGBColor, b: f64) -> RGBColor {
    let level = ((b - 0.3) / 0.85 * (SHADES - 1) as f64)
        .round()
        .clamp(0.0, (SHADES - 1) as f64);
    let b = 0.3 + 0.85 * level / (SHADES - 1) as f64;
    let f = |x: u8| (f64::from(x) * b).round().clamp(0.0, 255.0) as u8;
    RGBColor(f(c.0), f(c.1), f(c.2))
}

/// The fixed palette of every frame: the shades of the materials, blends of the inks into
/// the background (the edges of text), greys, and a coarse colour cube for the rest;
/// `TRANSPARENT` last. Pixels map to their nearest entry through a table of 15-bit colours.
struct Palette {
    rgb: Vec<u8>,
    lookup: Vec<u8>,
}

impl Palette {
    fn new() -> Palette {
        let mut colours: Vec<RGBColor> = vec![BACKGROUND];
        for m in [GROUND, BODY, PISTON] {
            colours
                .extend((0..SHADES).map(|l| shade(m, 0.3 + 0.85 * l as f64 / (SHADES - 1) as f64)));
        }
        let blend = |c: RGBColor, f: f64| {
            let m = |a: u8, b: u8| (f64::from(a) * f + f64::from(b) * (1.0 - f)).round() as u8;
            RGBColor(
                m(c.0, BACKGROUND.0),
                m(c.1, BACKGROUND.1),
                m(c.2, BACKGROUND.2),
            )
        };
        for ink in [TRAIL, FORCE, PLUME, STRUT, FOOTPAD]
            .into_iter()
            .chain(OUTCOME)
            .chain(AXES)
        {
            colours.extend((1..=6).map(|l| blend(ink, l as f64 / 6.0)));
        }
        colours.extend((0..32).map(|l| {
            let g = (l * 255 / 31) as u8;
            RGBColor(g, g, g)
        }));
        for r in 0..4u8 {
            for g in 0..4u8 {
                for b in 0..4u8 {
                    colours.push(RGBColor(r * 85, g * 85, b * 85));
                }
            }
        }
        colours.dedup();
        colours.truncate(255);
        let mut rgb: Vec<u8> = colours.iter().flat_map(|c| [c.0, c.1, c.2]).collect();
        rgb.resize(256 * 3, 0);
        let lookup = (0..1u32 << 15)
            .map(|c| {
                let (r, g, b) = (
                    ((c >> 10) & 31) * 255 / 31,
                    ((c >> 5) & 31) * 255 / 31,
                    (c & 31) * 255 / 31,
                );
                let d = |p: &RGBColor| {
                    let (dr, dg, db) = (
                        i64::from(p.0) - i64::from(r),
                        i64::from(p.1) - i64::from(g),
                        i64::from(p.2) - i64::from(b),
                    );
                    3 * dr * dr + 4 * dg * dg + 2 * db * db
                };
                (0..colours.len())
                    .min_by_key(|&i| d(&colours[i]))
                    .unwrap_or(0) as u8
            })
            .collect();
        Palette { rgb, lookup }
    }

    /// The palette indices of an RGB picture.
    fn index(&self, rgb: &[u8]) -> Vec<u8> {
        rgb.chunks_exact(3)
            .map(|p| {
                let key = (usize::from(p[0] >> 3) << 10)
                    | (usize::from(p[1] >> 3) << 5)
                    | usize::from(p[2] >> 3);
                self.lookup[key]
            })
            .collect()
    }
}

/// Where the camera looks: the point at the picture's centre (the view's axes and scale
/// stay fixed, in `View`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Camera {
    target: DVec3,
}

/// What stays fixed over the frames: the scene, the view's axes and scale, the ground.
struct View<'a> {
    scene: &'a Scene,
    right: DVec3,
    up: DVec3,
    back: DVec3,
    scale: f64,
    width: f64,
    height: f64,
    /// Whether the whole path fits the picture (a still camera) or the camera follows.
    still: Option<DVec3>,
    ground: Ground,
    /// The CG's path, thinned to points at least 5 mm apart, with their times.
    path: Vec<(f64, DVec3)>,
    light: DVec3,
}

/// Camera elevation above the horizontal, deg, and its azimuth from the downhill
/// direction's side (a three-quarter view from slightly downhill).
const ELEVATION_DEG: f64 = 24.0;
const AZIMUTH_FROM_SIDE_DEG: f64 = 20.0;

/// Frames a following camera takes to glide to the lander.
const GLIDE_FRAMES: usize = 12;

impl<'a> View<'a> {
    fn new(scene: &'a Scene, width: u32, height: u32) -> View<'a> {
        let az = (scene.downhill_azimuth_deg - 90.0 + AZIMUTH_FROM_SIDE_DEG).to_radians();
        let el = ELEVATION_DEG.to_radians();
        let back = DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let right = DVec3::Z.cross(back).normalize();
        let up = back.cross(right);
        let (width, height) = (f64::from(width), f64::from(height));
        let reach_m = scene.sketch.reach_m();
        let path_all = scene.cg_path();
        let mut path: Vec<(f64, DVec3)> = Vec::new();
        for (t, p) in scene.time.iter().zip(&path_all) {
            if path.last().is_none_or(|(_, q)| q.distance(*p) >= 0.005) && p.is_finite() {
                path.push((*t, *p));
            }
        }
        if let (Some(last), Some(p)) = (path_all.last(), path.last())
            && last.is_finite()
            && *last != p.1
        {
            path.push((scene.span_s().1, *last));
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
        View {
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
        }
    }

    /// The camera of the first frame.
    fn start_camera(&self) -> Camera {
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
    fn cameras(&self, times: &[f64]) -> Vec<Camera> {
        let mut c = self.start_camera();
        if self.still.is_some() {
            return vec![c; times.len()];
        }
        let cg = |k: usize| {
            let t = times[k.min(times.len() - 1)];
            let s = self.scene;
            DVec3::new(s.value("x_m", t), s.value("y_m", t), s.value("z_m", t))
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
    fn project(&self, c: Camera, p: DVec3) -> (f64, f64, f64) {
        let d = p - c.target;
        (
            0.5 * self.width + self.scale * d.dot(self.right),
            0.5 * self.height - self.scale * d.dot(self.up),
            d.dot(self.back),
        )
    }

    fn pixel(&self, c: Camera, p: DVec3) -> (i32, i32) {
        let (x, y, _) = self.project(c, p);
        (x.round() as i32, y.round() as i32)
    }

    /// Lambert brightness of a face of normal `n`.
    fn brightness(&self, n: DVec3) -> f64 {
        0.5 + 0.6 * n.dot(self.light).max(0.0)
    }

    /// The background of a frame: the ground patch, shaded face by face, and its grid of
    /// whole metres.
    fn draw_ground(&self, rgb: &mut [u8], c: Camera) -> anyhow::Result<()> {
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

    /// The lander and its captions over the background in `rgb`.
    fn draw_frame(&self, rgb: &mut [u8], c: Camera, pose: &Pose, speed: f64) -> anyhow::Result<()> {
        let root = BitMapBackend::with_buffer(rgb, (self.width as u32, self.height as u32))
            .into_drawing_area();
        let sk = &self.scene.sketch;
        let q = pose.attitude;
        let world = |p: DVec3| pose.cg + q * p;
        let n = self.scene.surface.normal;
        let px = self.scale;

        // The shadow along the normal on the surface: the body's outline and the footpads.
        let on_plane = |p: DVec3| p - n * n.dot(p) + n * self.ground_height(p);
        let dark = shade(GROUND, 0.6);
        let mut outline: Vec<(f64, f64)> = sk
            .bottom
            .iter()
            .chain(&sk.top)
            .map(|p| world(*p))
            .filter(|p| p.is_finite())
            .map(|p| {
                let (x, y, _) = self.project(c, on_plane(p));
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
        let (u, v) = (self.scene.surface.tangent_u, self.scene.surface.tangent_v);
        let disc = |centre: DVec3, radius: f64| -> Vec<(f64, f64, f64)> {
            (0..14)
                .map(|i| {
                    let a = std::f64::consts::TAU * f64::from(i) / 14.0;
                    self.project(c, centre + radius * (a.cos() * u + a.sin() * v))
                })
                .collect()
        };
        for tip in pose.tips.iter().filter(|t| t.is_finite()) {
            let pts: Vec<(i32, i32)> = disc(on_plane(*tip), sk.footpad_radius_m)
                .iter()
                .map(|p| (p.0.round() as i32, p.1.round() as i32))
                .collect();
            root.draw(&Polygon::new(pts, dark.filled()))
                .map_err(drawing)?;
        }

        // The CG's trail so far.
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

        // The lander's parts, far to near.
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
            let w: Vec<DVec3> = face.iter().map(|p| world(*p)).collect();
            let normal = (w[1] - w[0]).cross(w[2] - w[0]).normalize_or_zero();
            if !normal.is_finite() || normal.dot(self.back) <= 0.0 {
                continue;
            }
            let pts: Vec<(f64, f64, f64)> = w.iter().map(|p| self.project(c, *p)).collect();
            let depth = pts.iter().map(|p| p.2).sum::<f64>() / pts.len() as f64;
            parts.push((depth, Part::Face(pts, shade(BODY, self.brightness(normal)))));
        }
        for (k, leg) in sk.legs.iter().enumerate() {
            let tip = pose.tips[k];
            if !tip.is_finite() {
                continue;
            }
            let hip = world(leg.hip);
            let tube_end = world(leg.hip + 0.6 * (leg.tip0 - leg.hip));
            let mount = world(leg.mount);
            let seg = |a: DVec3, b: DVec3, colour: RGBColor, width: f64| {
                let (pa, pb) = (self.project(c, a), self.project(c, b));
                (
                    0.5 * (pa.2 + pb.2),
                    Part::Segment(pa, pb, colour, width.max(1.0).round() as u32),
                )
            };
            parts.push(seg(hip, mount, STRUT, 0.012 * px));
            parts.push(seg(hip, tube_end, STRUT, 0.03 * px));
            parts.push(seg(tube_end, tip, shade(PISTON, 1.0), 0.016 * px));
            // The footpad: a disc in the surface plane.
            let depth = self.project(c, tip).2;
            parts.push((depth, Part::Face(disc(tip, sk.footpad_radius_m), FOOTPAD)));
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
        for (j, t) in sk.thrusters.iter().enumerate() {
            let f = pose.thrust_n.get(j).copied().unwrap_or(0.0);
            if f <= 0.0 || t.max_thrust_n <= 0.0 {
                continue;
            }
            let nozzle = world(t.position);
            let length = 0.1 + 0.3 * (f / t.max_thrust_n).min(1.5);
            let end = nozzle - (q * t.direction) * length;
            let (a, b) = (self.project(c, nozzle), self.project(c, end));
            parts.push((0.5 * (a.2 + b.2), Part::Plume(a, b, 0.3 * length * px)));
        }
        parts.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, part) in parts {
            part.draw(&root)?;
        }

        self.draw_captions(&root, pose, speed)?;
        root.present().map_err(drawing)?;
        Ok(())
    }

    /// Height of the terrain at `p` along the normal (0 on a plane).
    fn ground_height(&self, p: DVec3) -> f64 {
        let s = &self.scene.surface;
        s.height(self.scene.model.terrain.as_ref(), p).0
    }

    /// The captions (what the sample is, the time, tilt and phase, the playback speed,
    /// the outcome once decided), a scale bar and the axes of I.
    fn draw_captions(&self, root: &Area<'_>, pose: &Pose, speed: f64) -> anyhow::Result<()> {
        let s = self.scene;
        let outcome = Outcome::from_name(&s.outcome);
        let colour = outcome.map_or(INK, |o| OUTCOME[o as usize]);
        let big = (self.height / 30.0).clamp(11.0, 22.0);
        let small = (big * 0.8).max(10.0);
        let text = |t: &str, at: (i32, i32), size: f64, colour: RGBColor| {
            root.draw(&Text::new(
                t.to_string(),
                at,
                (FONT, size).into_font().color(&colour),
            ))
            .map_err(drawing)
        };
        let pad = (big * 0.5) as i32;
        // The captions on a veil, so that the trail or ground under them does not hide them;
        // wide enough for the longest second line (the same in every frame).
        let veil = (
            2 * pad + (0.55 * (big * s.about.len() as f64).max(small * 90.0)) as i32,
            pad + (big * 2.6) as i32,
        );
        root.draw(&Rectangle::new(
            [(0, 0), veil],
            BACKGROUND.mix(0.8).filled(),
        ))
        .map_err(drawing)?;
        text(&s.about, (pad, pad), big, colour)?;
        let mut line = format!(
            "t = {:.2} s    tilt {:.1} deg    slope {:.1} deg",
            pose.t_s, pose.tilt_deg, s.slope_deg
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
        let (w, h) = (self.width as i32, self.height as i32);
        text(
            &speed_text,
            (
                w - pad - (small * 0.55 * speed_text.len() as f64) as i32,
                pad,
            ),
            small,
            INK,
        )?;
        if pose.t_s >= s.decided_s - 1e-9 {
            let word = s.outcome.to_uppercase();
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

/// A drawing area of a frame.
type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

/// A part of the lander in the picture (points with their depth).
enum Part {
    Face(Vec<(f64, f64, f64)>, RGBColor),
    Segment((f64, f64, f64), (f64, f64, f64), RGBColor, u32),
    Arrow((f64, f64, f64), (f64, f64, f64), RGBColor),
    /// From the nozzle to the plume's end, with its half-width there in pixels.
    Plume((f64, f64, f64), (f64, f64, f64), f64),
}

impl Part {
    fn draw(&self, root: &Area<'_>) -> anyhow::Result<()> {
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
fn hull(points: &mut [(f64, f64)]) -> Vec<(f64, f64)> {
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
    fn frames_keep_to_the_clock() {
        // 120 s at 8x and 20 fps: 15 s of playback, 301 frames, 5/100 s each.
        let t = frame_times(0.0, 120.0, 8.0, 20.0);
        assert_eq!(t.len(), 301);
        assert_eq!(t[300], 120.0);
        let total: u32 = (0..t.len())
            .map(|k| u32::from(frame_delay_cs(k, t.len(), 20.0)))
            .sum();
        assert_eq!(total, 301 * 5 + u32::from(FINAL_HOLD_CS));
        // 15 fps: delays of 7, 7 and 6 keep 20 frames at 1.33 s.
        let d: Vec<u16> = (0..20).map(|k| frame_delay_cs(k, 100, 15.0)).collect();
        assert_eq!(d.iter().map(|x| u32::from(*x)).sum::<u32>(), 133);
        assert!(d.iter().all(|x| *x == 6 || *x == 7));
    }

    #[test]
    fn the_palette_leaves_the_transparent_index_free() {
        let p = Palette::new();
        assert_eq!(p.rgb.len(), 256 * 3);
        assert!(p.lookup.iter().all(|i| *i != TRANSPARENT));
    }

    #[test]
    fn hull_of_a_square_and_its_centre() {
        let mut p = vec![(0.0, 0.0), (1.0, 0.0), (0.5, 0.5), (1.0, 1.0), (0.0, 1.0)];
        let h = hull(&mut p);
        assert_eq!(h.len(), 4);
        assert!(!h.contains(&(0.5, 0.5)));
    }
}
