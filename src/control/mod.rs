//! The control loop (MODEL.md section 7): sensors with noise and bias, a latency of whole
//! control periods, the built-in laws, the mapping of a commanded force and torque onto
//! the thrusters, and the thrust each lander gets until its next control event.
//!
//! The loop runs between steps, once per event of a lander (a control instant, or a
//! thruster switching off), for the kernels' lanes and the scalar reference alike: both
//! call `LaneControl::event` with the lander's true state and apply the thrust it returns
//! until the next event. The step never passes an event, so a thrust is constant over
//! every step it acts in.
//!
//! From the ground up: what the loop reads (`sensors`) and hands the step (`thrust`), the
//! `allocation` of a wrench to the thrusters, the `laws` and their registry, the `model` a
//! sweep keeps, its `check`, and each lander's loop (`lane`).

mod allocation;
mod check;
mod lane;
mod laws;
mod model;
mod noise;
mod sensors;
mod thrust;

pub use allocation::{Allocation, Wrench, quantise, quantise_carrying};
pub use check::check;
pub use lane::{ControlReport, ControlSummary, LaneControl, Phase};
pub use laws::{
    DescentDraw, LAW_MEMORY, Law, LawCommand, NamedLaw, attitude_torque, descent_force,
    register_law, registered, registered_names,
};
pub use model::ControlModel;
pub use sensors::{Sensed, Truth};
pub use thrust::Thrust;
