//! One sample: the values it drew (its inputs, parameters and control-law parameters), its
//! generator seed and its terrain tile and offset. `sampling` draws it; the physics runs it.

use super::inputs::{
    FIRST_LAW_VALUE, FIRST_STATE_VALUE, INPUT_FIELDS, Inputs, LAW_PARAMETERS, PARAMETERS,
    STATE_VALUES, VALUES,
};

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
    /// Which rock tile this sample lands on (0 without rocks).
    pub rock_tile: u32,
    /// Offset of the landing point in the rock tile, along the slope's tangent axes, m.
    pub rock_offset_m: [f64; 2],
    /// The value of each built-in control law's parameter (`Control::parameters`) for this
    /// sample: its draw, or the scenario's number (0 where the scenario has no such law).
    pub law: [f64; LAW_PARAMETERS],
    /// The touchdown state the scenario gives (`INITIAL_FIELDS`: speed towards the surface,
    /// speed along it and its azimuth from downhill), its draw or the scenario's number; 0
    /// where the scenario gives none.
    pub touchdown: [f64; STATE_VALUES],
}

impl Sample {
    /// The inputs, then the parameters, the law parameters and the touchdown state.
    #[must_use]
    pub fn values(&self) -> [f64; VALUES] {
        let inputs = self.inputs.to_array();
        std::array::from_fn(|k| {
            if k < inputs.len() {
                inputs[k]
            } else if k < FIRST_LAW_VALUE {
                self.parameters[k - inputs.len()]
            } else if k < FIRST_STATE_VALUE {
                self.law[k - FIRST_LAW_VALUE]
            } else {
                self.touchdown[k - FIRST_STATE_VALUE]
            }
        })
    }

    /// Sets the inputs, parameters, law parameters and touchdown state from `values` (as
    /// `values` gives them).
    pub fn set_values(&mut self, values: [f64; VALUES]) {
        let n = INPUT_FIELDS.len();
        self.inputs = Inputs::from_array(std::array::from_fn(|k| values[k]));
        self.parameters = std::array::from_fn(|k| values[n + k]);
        self.law = std::array::from_fn(|k| values[FIRST_LAW_VALUE + k]);
        self.touchdown = std::array::from_fn(|k| values[FIRST_STATE_VALUE + k]);
    }
}
