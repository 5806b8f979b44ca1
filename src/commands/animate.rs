//! `touchdown animate`: a trace file as a GIF.

use super::flags::{beside, parse_size};
use super::print::{say, shown, tell};
use std::path::PathBuf;

/// Flags of `touchdown animate`.
#[derive(clap::Args, Debug)]
pub struct AnimateArgs {
    /// A trace file (`touchdown trace` writes one).
    pub trace: PathBuf,
    /// GIF file to write (default: the trace's name with .gif).
    #[arg(long, value_name = "PATH")]
    pub out: Option<PathBuf>,
    /// Frames per second of playback, 1 to 50.
    #[arg(
        long,
        value_name = "N",
        default_value = "15",
        allow_negative_numbers = true
    )]
    pub fps: f64,
    /// Trace seconds per second of playback (default: the trace plays in 15 s, and never
    /// slower than real time; the last frame then stays 2 s).
    #[arg(long, value_name = "X", allow_negative_numbers = true)]
    pub speed: Option<f64>,
    /// Picture size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "640x480", value_parser = parse_size)]
    pub size: (u32, u32),
}

/// Runs `touchdown animate`.
pub fn run(args: &AnimateArgs) -> anyhow::Result<()> {
    let out = beside(&args.trace, args.out.as_ref(), "gif");
    let options = crate::animate::Options {
        fps: args.fps,
        speed: args.speed,
        width: args.size.0,
        height: args.size.1,
    };
    let started = std::time::Instant::now();
    let stop = crate::run::stop_on_signals()?;
    let r = crate::animate::animate(&args.trace, &out, &options, &stop)?;
    if let Some(note) = crate::scene::sparse_note(&args.trace, r.every) {
        tell(&format!("{note}\n"));
    }
    say(
        "the animation's summary",
        &format!(
            "{} frames at {} fps, {}x speed: plays in {:.1} s\nwrote {}: {:.2} MB in {:.1} s\n",
            r.frames,
            args.fps,
            if r.speed >= 10.0 {
                format!("{:.0}", r.speed)
            } else {
                format!("{:.2}", r.speed)
            },
            r.playback_s,
            shown(&out),
            r.bytes as f64 / 1e6,
            started.elapsed().as_secs_f64()
        ),
        &out,
    )
}
