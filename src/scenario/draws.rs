//! What a scenario draws per sample: the distribution of each value (`Sample::values`),
//! the grid of grid inputs and of the control laws' parameters, and the inputs a Sobol-index
//! design varies.

use super::control::{Control, LAW_PARAMETERS};
use super::definition::Scenario;
use super::inputs::{Dist, Parameter, VALUES};

/// The distribution of each value of `scenario`'s samples (`Sample::values`): a parameter
/// that the scenario does not sample is fixed at its value.
#[must_use]
pub fn value_dists(scenario: &Scenario) -> [Dist; VALUES] {
    let inputs = scenario.inputs.to_array();
    std::array::from_fn(|k| {
        if k < inputs.len() {
            inputs[k]
        } else {
            let p = Parameter::ALL[k - inputs.len()];
            scenario.sampled[p as usize].unwrap_or(Dist::Fixed(scenario.parameter(p)))
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

/// The distributions on the grid of `scenario`: its inputs and parameters, then its
/// control laws' parameters, which therefore vary fastest.
pub fn grid_dists(scenario: &Scenario) -> [Dist; VALUES + LAW_PARAMETERS] {
    let values = value_dists(scenario);
    let laws = law_dists(scenario.control.as_ref());
    std::array::from_fn(|k| {
        if k < values.len() {
            values[k]
        } else {
            laws[k - values.len()]
        }
    })
}

/// The grid coordinate of each law parameter of the sample in law cell `law_cell`
/// (`Sample::law_cell`) of a loop `control`: the law parameters vary fastest on the
/// grid, so their digits are those of the cell alone.
#[must_use]
pub fn law_grid(control: &Control, law_cell: u64) -> [u64; LAW_PARAMETERS] {
    grid_indices(&law_dists(Some(control)), law_cell)
}

/// Number of points of the grid (1 when no input or law parameter is a grid).
#[must_use]
pub fn grid_size(scenario: &Scenario) -> u128 {
    grid_dists(scenario)
        .iter()
        .map(|d| match d {
            Dist::Grid { count, .. } => u128::from(*count),
            _ => 1,
        })
        .product()
}

/// The inputs and parameters that a Sobol-index design varies: those drawn from a
/// distribution (not fixed), as positions in `Sample::values` (`value_name` names them).
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
