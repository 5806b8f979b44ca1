//! Pictures of a trace file: CG position, velocity, acceleration and attitude; per leg
//! penetration, normal force, friction force and stroke; the 3D path of the CG and the
//! footpads over the slope; the acceleration along Z_B (the instruments' shock). A trace of
//! a scenario with a control loop adds the thrust (on the lander, each thruster's firings,
//! the propellant used) and what the sensors read against the true state.
//!
//! The trace is read by `scene::Trace` (as `animate` and `view` read it); `series.rs` makes
//! its columns lines, `pictures.rs` writes the pictures, `path.rs` and `thrust.rs` draw the
//! 3D path and the control loop's.

mod path;
mod pictures;
mod series;
mod thrust;

pub(super) use pictures::{PICTURES, plot};
