//! The hot code of the touchdown engine: many landers advanced together, structure of
//! arrays, by fixed-step kernels over the SIMD type of `lane`. No I/O, no threads, no
//! allocation per step. The scalar reference model in the `touchdown` crate has the same
//! modules with the same names, in the same order, for reading side by side.

pub mod block;
pub mod contact;
pub mod honeycomb;
pub mod isa;
pub mod lane;
pub mod outcome;
pub mod params;
pub mod regolith;
pub mod rigid_body;
pub mod rocks;
pub mod step;
pub mod terrain;
pub mod vec3;
