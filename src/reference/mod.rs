//! The scalar reference model: one lander, f64, glam, written like the equations of
//! MODEL.md. It drives `touchdown trace` and is the oracle the SIMD kernels must agree with.
//!
//! Files mirror the kernels: `rigid_body`, `contact`, `regolith`, `honeycomb`, `step`,
//! `outcome`;
//! `model` holds the parameters, `run` one whole sample, `touchdown` the state in which
//! a sample met the surface, and `strut` what it did to the struts.

pub mod contact;
pub mod honeycomb;
pub mod model;
pub mod outcome;
pub mod regolith;
pub mod rigid_body;
pub mod run;
pub mod step;
pub mod strut;
pub mod touchdown;

pub use model::Model;
pub use outcome::{Outcome, Summary};
pub use run::{initial_state, run};
pub use step::{State, StepReport};
