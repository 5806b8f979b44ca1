//! A trace file as something to look at (`touchdown plot`, `animate`, `view`): the trace
//! read once (`Trace`), the lander's shape in B, the surface it lands on (with its rocks
//! and, on regolith, the footprints left), and its pose at any time.
//!
//! The trace holds the motion; its metadata holds the scenario and the sample, from which
//! the lander's geometry, the slope and the terrain tile are derived again. The shape drawn
//! is a sketch: the model's lander is a rigid body with point footpads, so the body (an
//! octagonal prism, the thesis's lander), the struts' length and the footpad discs are
//! proportions of the leg geometry, while every footpad is drawn where the trace has it.

mod footprints;
mod ground;
mod pose;
mod read;
mod rocks;
mod sketch;
mod trace;

pub use footprints::Footprint;
pub use ground::Ground;
pub use pose::Pose;
pub use read::Scene;
pub use rocks::RockShape;
pub use sketch::{LegSketch, Sketch, ThrusterSketch};
pub use trace::{Trace, sparse_note};
