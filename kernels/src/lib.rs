//! The hot code of the touchdown engine: no I/O, no threads, no allocation per step.
#![warn(missing_docs)]

pub mod terrain;
