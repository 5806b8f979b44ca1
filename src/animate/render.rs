//! The animation's driver: the trace read into a scene, each frame drawn over its ground,
//! mapped onto the palette and written to the GIF as what changed.

use super::camera::{Camera, View};
use super::encode::changed_frame;
use super::palette::Palette;
use super::timing::{
    MAX_FRAMES, Options, check, default_speed, frame_count, frame_delay_cs, frame_times,
};
use crate::output::AtomicFile;
use crate::output::cannot_write;
use crate::plot::canvas::register_font;
use crate::run::Interrupted;
use crate::scene::Scene;
use anyhow::{anyhow, bail};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// What `animate` wrote.
#[derive(Debug, Clone, Copy)]
pub struct Rendered {
    /// Frames written.
    pub frames: usize,
    /// Trace seconds per second of playback.
    pub speed: f64,
    /// Playback of one loop, the final hold included, s.
    pub playback_s: f64,
    /// Size of the GIF, bytes.
    pub bytes: u64,
    /// The trace's rows are every `every` steps.
    pub every: u64,
}

/// Writes the GIF of the trace at `trace` to `out`. A signal in `stop` (its number, 0 for
/// none: `run::stop_on_signals`) ends it before the next frame with an `Interrupted` error,
/// its unfinished file removed.
pub fn animate(
    trace: &Path,
    out: &Path,
    o: &Options,
    stop: &AtomicUsize,
) -> anyhow::Result<Rendered> {
    check(o)?;
    crate::output::check_output_path(out)?;
    let scene = Scene::read(trace)?;
    register_font()?;
    let (t0, t1) = scene.trace.span_s();
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
    let context = |e: gif::EncodingError| match e {
        gif::EncodingError::Io(io) => cannot_write(out, io),
        e => anyhow!("cannot write {}: {e}", out.display()),
    };
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
            stopped(stop, out)?;
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
        std::io::Write::flush(&mut sink).map_err(|e| context(e.into()))?;
        file.commit(sink)?;
        Ok(Rendered {
            frames: times.len(),
            speed,
            playback_s: playback_cs as f64 / 100.0,
            bytes,
            every: scene.trace.every,
        })
    }
}

/// The `Interrupted` error of a signal in `stop`, if one came: the GIF to `out` is left
/// unwritten (dropped, its unfinished file is removed).
fn stopped(stop: &AtomicUsize, out: &Path) -> anyhow::Result<()> {
    let signal = stop.load(Ordering::Relaxed);
    if signal == 0 {
        return Ok(());
    }
    let name = crate::run::signal_name(signal);
    Err(Interrupted {
        code: (128 + signal).min(255) as u8,
        message: format!(
            "interrupted by {name}: {} not written (its unfinished frames removed)",
            out.display()
        ),
    }
    .into())
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
