//! `touchdown animate`: a GIF of one touchdown from its trace file.
//!
//! Each frame is drawn in an orthographic view (equal scales on every axis) with plotters
//! on a bitmap: the slope as a shaded patch with a 1 m grid, the lander's shadow along the
//! normal, the CG's trail, then the lander's parts back to front (the body's faces that face
//! the camera, the struts with their dampers' stroke, the footpads, the contact-force
//! arrows and the thrust plumes), and the captions. Frames map onto one fixed palette, and
//! each stores only the rectangle that changed, its unchanged pixels transparent, so that
//! a still camera costs little.

//!
//! `timing.rs` the options and the frames' clock; `render.rs` the driver; `camera.rs` the
//! view; `ground.rs`, `rocks.rs`, `lander.rs`, `parts.rs` and `captions.rs` what a frame
//! shows (`rocks.rs` also the footprints and sunk footpads on regolith);
//! `palette.rs` and `encode.rs` the GIF's colours and frames.

mod camera;
mod captions;
mod encode;
mod ground;
mod lander;
mod palette;
mod parts;
mod render;
mod rocks;
mod timing;

pub use render::{Rendered, animate};
pub use timing::{
    DEFAULT_PLAYBACK_S, FINAL_HOLD_CS, MAX_FRAMES, Options, check, default_speed, frame_count,
    frame_delay_cs, frame_times,
};
