//! One sample: the values it drew (its inputs and parameters), its generator seed, its
//! terrain tile and offset and its cell of the control laws' grid. `sampling` draws it;
//! the physics runs it.

use super::inputs::{INPUT_FIELDS, Inputs, PARAMETERS, VALUES};

/// Everything that makes one sample differ from another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The sample's index in its sweep (its row).
    pub index: u64,
    /// The seed of this sample's generator.
    pub seed: u64,
    /// The inputs it drew (`INPUT_FIELDS`).
    pub inputs: Inputs<f64>,
    /// The value of each scenario parameter (`Parameter`) for this sample: its draw where
    /// the scenario samples it, else the scenario's value.
    pub parameters: [f64; PARAMETERS],
    /// Which precomputed terrain tile this sample lands on (0 on a flat surface).
    pub terrain_tile: u32,
    /// Offset of the landing point in the tile, along the slope's tangent axes, m.
    pub terrain_offset_m: [f64; 2],
    /// The sample's cell of the grid of the control laws' parameters (0 where none is on a
    /// grid; `law_grid` gives each parameter's coordinate): their values are drawn with the
    /// control loop.
    pub law_cell: u64,
}

impl Sample {
    /// The inputs, then the parameters.
    #[must_use]
    pub fn values(&self) -> [f64; VALUES] {
        let inputs = self.inputs.to_array();
        std::array::from_fn(|k| {
            if k < inputs.len() {
                inputs[k]
            } else {
                self.parameters[k - inputs.len()]
            }
        })
    }

    /// Sets the inputs and parameters from `values` (as `values` gives them).
    pub fn set_values(&mut self, values: [f64; VALUES]) {
        let n = INPUT_FIELDS.len();
        self.inputs = Inputs::from_array(std::array::from_fn(|k| values[k]));
        self.parameters = std::array::from_fn(|k| values[n + k]);
    }
}
