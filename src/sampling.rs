//! Sample index -> inputs, as a pure function of (scenario, seed, index).
//!
//! Sample `i` has a generator seed from a SplitMix64 mix of the sweep seed and `i`; each of
//! its inputs (and its terrain tile and offset) then draws from a `Xoshiro256PlusPlus` of its
//! own, seeded from that seed and the input's name, through the input's inverse CDF. No state
//! is shared between samples or between inputs, so threads, shards and resumption cannot
//! change a sample, any sample can be replayed alone, and scenarios that differ in one input
//! draw the same values for all the others (common random numbers, for paired studies).
//!
//! The streams are `rng`'s, the inverse CDFs `dist`'s; what a scenario draws is
//! `scenario::draws`'s.

use crate::dist::quantile;
use crate::rng::{sample_seed, stream, uniform_open01, uniform01};
use crate::scenario::{
    Design, Dist, INPUT_FIELDS, Inputs, LAW_PARAMETERS, PARAMETERS, STATE_VALUES, Sample, Scenario,
    VALUES, design_inputs, design_position, grid_indices, stream_name, value_dists,
};
use rand_core::RngCore;

/// The inputs of sample `index` of `scenario`.
///
/// With `design = "sobol-indices"` (Saltelli's design), samples come in blocks of `d + 2`
/// for the `d` values drawn at random (`design_inputs`: inputs, parameters and control-law
/// parameters): block `j` is base point `j`, whose
/// rows A and B are the independent draws `2 j` and `2 j + 1`, followed by AB_1 ... AB_d,
/// each A with one varied input taken from B. The rows AB_q keep A's sample seed, terrain
/// tile and offset, so whatever else a sample draws (sensor noise, thruster errors) is A's
/// too: only input `q` differs between A and AB_q. `design_position` gives a sample's place.
///
/// Common random numbers: each input draws one uniform from its own stream (`stream`, keyed
/// by the sample's seed and the input's name) and maps it through its inverse CDF. So two
/// scenarios that differ in one input's distribution give every other input the same
/// value, sample by sample, and paired comparisons between them are paired; a fixed or grid
/// input simply leaves its stream unused.
#[must_use]
pub fn sample(scenario: &Scenario, index: u64) -> Sample {
    if scenario.design == Design::SobolIndices {
        let varied = design_inputs(scenario);
        let (base, matrix) = design_position(index, varied.len());
        let a = drawn(scenario, 2 * base);
        let b = drawn(scenario, 2 * base + 1);
        let mut s = match matrix {
            0 => a,
            1 => b,
            m => {
                let mut values = a.values();
                let k = varied[m - 2];
                values[k] = b.values()[k];
                let mut ab = a;
                ab.set_values(values);
                ab
            }
        };
        s.index = index;
        return s;
    }
    drawn(scenario, index)
}

/// Mixed into the sweep's seed for the scrambling of the Sobol sequence.
const SOBOL_KEY: u64 = 0x5eed_0f50_b01d_5e9a;

/// The independent draw `index` of `scenario`'s inputs (with the quasi-random design, the
/// inputs drawn from a distribution from point `index` of the Sobol sequence).
///
/// With a table of inputs (`Scenario::table`), row `index` gives the values it has (and,
/// where it has them, the sample's seed and terrain); the others are drawn as without one.
fn drawn(scenario: &Scenario, index: u64) -> Sample {
    // The table's row, read once (a file's rows come in blocks, behind a lock).
    let row = scenario.table.as_deref().map(|t| t.row(index));
    let seed = row
        .and_then(|r| r.sample_seed)
        .unwrap_or_else(|| sample_seed(scenario.seed, index));
    let dists = value_dists(scenario);
    let grid = grid_indices(&dists, index);
    let mut values = [0.0; VALUES];
    // With the quasi-random design, the q-th value drawn from a distribution takes
    // coordinate q of point `index` of the scrambled Sobol sequence.
    let mut dimension = 0;
    for (k, ((v, d), g)) in values.iter_mut().zip(&dists).zip(grid).enumerate() {
        if let Some(x) = row.and_then(|r| r.values[k]) {
            *v = x;
            continue;
        }
        // A fixed value draws nothing: its stream is left alone.
        *v = match d {
            Dist::Fixed(x) => *x,
            d if scenario.design == Design::SobolSequence => {
                let u = crate::qmc::sobol_point(index, dimension, scenario.seed ^ SOBOL_KEY);
                dimension += 1;
                quantile(d, u, g)
            }
            d => quantile(d, uniform_open01(&mut stream(seed, stream_name(k))), g),
        };
    }
    let rough = &scenario.surface.roughness;
    let (terrain_tile, terrain_offset_m) = tile_draw(
        seed,
        scenario.rms_height_max_m() > 0.0,
        ["terrain_tile", "terrain_offset_u_m", "terrain_offset_v_m"],
        rough.tiles,
        rough.tile_size_m,
    );
    let (terrain_tile, terrain_offset_m) = match row {
        Some(r) => (
            r.terrain_tile.unwrap_or(terrain_tile),
            [0, 1].map(|j| r.terrain_offset_m[j].unwrap_or(terrain_offset_m[j])),
        ),
        None => (terrain_tile, terrain_offset_m),
    };
    // The rock tile and offset, from streams of their own (no table gives them).
    let rocks = &scenario.surface.rocks;
    let (rock_tile, rock_offset_m) = tile_draw(
        seed,
        scenario.rock_abundance_max() > 0.0,
        ["rock_tile", "rock_offset_u_m", "rock_offset_v_m"],
        rocks.tiles,
        rocks.tile_size_m,
    );
    let mut s = Sample {
        index,
        seed,
        inputs: Inputs::from_array([0.0; INPUT_FIELDS.len()]),
        parameters: [0.0; PARAMETERS],
        terrain_tile,
        terrain_offset_m,
        rock_tile,
        rock_offset_m,
        law: [0.0; LAW_PARAMETERS],
        touchdown: [0.0; STATE_VALUES],
    };
    s.set_values(values);
    s
}

/// A tile among `tiles` and an offset on a tile of side `size_m`, each from the stream
/// named in `names` (tile, offset along u, along v); tile 0 at no offset where `on` is
/// false (no such surface: nothing is drawn).
fn tile_draw(seed: u64, on: bool, names: [&str; 3], tiles: usize, size_m: f64) -> (u32, [f64; 2]) {
    if !on {
        return (0, [0.0, 0.0]);
    }
    let tile = (stream(seed, names[0]).next_u64() % tiles as u64) as u32;
    let offset = [
        size_m * uniform01(&mut stream(seed, names[1])),
        size_m * uniform01(&mut stream(seed, names[2])),
    ];
    (tile, offset)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::grid_size;

    #[test]
    fn a_sample_is_a_pure_function_of_seed_and_index() {
        let s = Scenario::default();
        assert_eq!(sample(&s, 12345), sample(&s, 12345));
        assert_ne!(sample(&s, 1).inputs, sample(&s, 2).inputs);
        let mut other = s.clone();
        other.seed = 2;
        assert_ne!(sample(&s, 1).inputs, sample(&other, 1).inputs);
    }

    #[test]
    fn changing_one_input_leaves_the_others_as_they_were() {
        // Common random numbers: every input keeps its values, sample by sample, whatever
        // another input's distribution (sampled, fixed, truncated, a grid) and whether
        // roughness adds the terrain draws.
        let base = Scenario::default();
        let changes: [fn(&mut Scenario); 5] = [
            |s| s.inputs.rate_y_deg_s = Dist::Fixed(5.0),
            |s| {
                s.inputs.roll_deg = Dist::Normal {
                    mean: 1.0,
                    sd: 4.0,
                    min: -3.0,
                    max: 8.0,
                }
            },
            |s| {
                s.inputs.slope_deg = Dist::Grid {
                    min: 0.0,
                    max: 40.0,
                    count: 9,
                }
            },
            |s| {
                s.inputs.yaw_deg = Dist::Uniform {
                    min: 0.0,
                    max: 360.0,
                }
            },
            |s| s.surface.roughness.rms_height_m = 0.02,
        ];
        for (k, change) in changes.iter().enumerate() {
            let mut other = base.clone();
            change(&mut other);
            let (a, b) = (base.inputs.to_array(), other.inputs.to_array());
            for i in 0..1000 {
                let (x, y) = (
                    sample(&base, i).inputs.to_array(),
                    sample(&other, i).inputs.to_array(),
                );
                for (j, (name, _)) in INPUT_FIELDS.iter().enumerate() {
                    if a[j] == b[j] {
                        assert_eq!(
                            x[j].to_bits(),
                            y[j].to_bits(),
                            "change {k}: sample {i}: {name}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn grids_form_a_product_last_fastest() {
        let mut s = Scenario::default();
        s.inputs.slope_deg = Dist::Grid {
            min: 0.0,
            max: 40.0,
            count: 5,
        };
        s.inputs.downhill_azimuth_deg = Dist::Grid {
            min: 0.0,
            max: 90.0,
            count: 3,
        };
        assert_eq!(grid_size(&s), 15);
        let pick = |i| {
            let x = sample(&s, i).inputs;
            (x.slope_deg, x.downhill_azimuth_deg)
        };
        assert_eq!(pick(0), (0.0, 0.0));
        assert_eq!(pick(1), (0.0, 45.0));
        assert_eq!(pick(3), (10.0, 0.0));
        assert_eq!(pick(14), (40.0, 90.0));
        assert_eq!(pick(15), (0.0, 0.0));
    }

    #[test]
    fn law_parameters_on_a_grid_follow_the_inputs_last_fastest() {
        let mut text = String::from(
            "[inputs]\nslope_deg = { dist = \"grid\", min = 0.0, max = 20.0, count = 3 }\n",
        );
        for (x, y) in [(0.3, 0.0), (-0.3, 0.0), (0.0, 0.3), (0.0, -0.3)] {
            text += &format!(
                "[[thrusters]]\nposition_m = [{x}, {y}, 0.3]\ndirection = [0.0, 0.0, -1.0]\n\
                 max_thrust_n = 10.0\nmin_on_time_s = 0.02\n"
            );
        }
        text += "[control]\n[control.hold_down]\n\
                 thrust_n = { dist = \"grid\", min = 0.0, max = 40.0, count = 9 }\n\
                 duration_s = { dist = \"grid\", min = 5.0, max = 20.0, count = 4 }\n";
        let s = Scenario::from_toml(&text).unwrap();
        assert_eq!(grid_size(&s), 3 * 9 * 4);
        let pick = |i| {
            let x = sample(&s, i);
            (x.inputs.slope_deg, x.law[0], x.law[1])
        };
        assert_eq!(pick(0), (0.0, 0.0, 5.0));
        assert_eq!(pick(1), (0.0, 0.0, 10.0));
        assert_eq!(pick(4), (0.0, 5.0, 5.0));
        assert_eq!(pick(36), (10.0, 0.0, 5.0));
        assert_eq!(pick(107), (20.0, 40.0, 20.0));
        assert_eq!(pick(108), (0.0, 0.0, 5.0));
        // Every law parameter of a law the scenario has not is 0.
        assert!(sample(&s, 35).law[2..].iter().all(|&x| x == 0.0));
        assert!(
            sample(&Scenario::default(), 5)
                .law
                .iter()
                .all(|&x| x == 0.0)
        );
    }
}
