//! The clock of an animation: its options, the frames' times and their delays.

use anyhow::bail;

/// How to render an animation.
#[derive(Debug, Clone, Copy)]
pub struct Options {
    /// Frames per second of playback.
    pub fps: f64,
    /// Trace seconds per second of playback (default: `default_speed`).
    pub speed: Option<f64>,
    /// Width of the picture, pixels.
    pub width: u32,
    /// Height of the picture, pixels.
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
}
