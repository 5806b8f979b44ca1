//! What a scenario draws per sample: the distribution of each value (`Sample::values`:
//! inputs, parameters and control-law parameters), their grid, and the values a
//! Sobol-index design varies.

use super::control::Control;
use super::definition::Scenario;
use super::inputs::{Dist, FIRST_LAW_VALUE, FIRST_STATE_VALUE, LAW_PARAMETERS, Parameter, VALUES};

/// The distribution of each value of `scenario`'s samples (`Sample::values`): a parameter
/// that the scenario does not sample is fixed at its value, a law parameter of a law the
/// scenario has not, and the touchdown state of a scenario that gives none, at 0.
#[must_use]
pub fn value_dists(scenario: &Scenario) -> [Dist; VALUES] {
    let inputs = scenario.inputs.to_array();
    let laws = law_dists(scenario.control.as_ref());
    std::array::from_fn(|k| {
        if k < inputs.len() {
            inputs[k]
        } else if k < FIRST_LAW_VALUE {
            let p = Parameter::ALL[k - inputs.len()];
            scenario.sampled[p as usize].unwrap_or(Dist::Fixed(scenario.parameter(p)))
        } else if k < FIRST_STATE_VALUE {
            laws[k - FIRST_LAW_VALUE]
        } else {
            scenario
                .initial
                .touchdown
                .map_or(Dist::Fixed(0.0), |t| t[k - FIRST_STATE_VALUE])
        }
    })
}

/// The grid coordinates of sample `index`: mixed radix over the grid distributions of
/// `dists`, the last varying fastest, cycling through the product of the grid sizes.
pub fn grid_indices<const N: usize>(dists: &[Dist; N], index: u64) -> [u64; N] {
    let mut out = [0u64; N];
    let mut rest = index;
    for (o, d) in out.iter_mut().zip(dists).rev() {
        if let Dist::Grid { count, .. } = d {
            *o = rest % count;
            rest /= count;
        }
    }
    out
}

/// The distributions of the control laws' parameters (`Control::parameters`; a fixed 0
/// where the scenario has no such law).
fn law_dists(control: Option<&Control>) -> [Dist; LAW_PARAMETERS] {
    control
        .map_or([None; LAW_PARAMETERS], Control::parameters)
        .map(|d| d.unwrap_or(Dist::Fixed(0.0)))
}

/// Number of points of the grid (1 when no value is a grid). The law parameters, the last
/// values, vary fastest on it.
#[must_use]
pub fn grid_size(scenario: &Scenario) -> u128 {
    value_dists(scenario)
        .iter()
        .map(|d| match d {
            Dist::Grid { count, .. } => u128::from(*count),
            _ => 1,
        })
        .product()
}

/// The values that a Sobol-index design varies: those drawn from a distribution (not
/// fixed), as positions in `Sample::values` (`value_name` names them): inputs, parameters
/// and law parameters alike.
#[must_use]
pub fn design_inputs(scenario: &Scenario) -> Vec<usize> {
    value_dists(scenario)
        .iter()
        .enumerate()
        .filter(|(_, d)| !matches!(d, Dist::Fixed(_)))
        .map(|(k, _)| k)
        .collect()
}

/// The number of cells of the grid of the control laws' parameters (1: none on a grid).
#[must_use]
pub fn law_grid_size(control: Option<&Control>) -> u64 {
    law_dists(control)
        .iter()
        .map(|d| match d {
            Dist::Grid { count, .. } => *count,
            _ => 1,
        })
        .product()
}

/// Where sample `index` sits in a Sobol-index design of `inputs` varied inputs: its base
/// point and its matrix (0: A, 1: B, `2 + q`: AB_q, A with varied input `q` from B).
#[must_use]
pub fn design_position(index: u64, inputs: usize) -> (u64, usize) {
    let block = inputs as u64 + 2;
    (index / block, (index % block) as usize)
}
