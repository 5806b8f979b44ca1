//! touchdown: Monte Carlo touchdown simulation of legged landers on asteroids.
//!
//! `scenario` reads and validates the inputs, `sampling` turns a sample index into inputs,
//! `reference` is the scalar physics of one lander, `output` writes Arrow files.

pub mod animate;
pub mod boundary;
pub mod cli;
pub mod compare;
pub mod control;
pub mod dist;
pub mod output;
pub mod plot;
pub mod qmc;
pub mod reference;
pub mod report;
pub mod rng;
pub mod sampling;
pub mod scenario;
pub mod scene;
pub mod sensitivity;
pub mod slope;
pub mod stability;
pub mod stats;
pub mod study;
pub mod sweep;
pub mod table;
pub mod terrain;
pub mod view;
pub mod weighting;
