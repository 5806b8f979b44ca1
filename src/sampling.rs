//! Sample index -> inputs, as a pure function of (scenario, seed, index).
//!
//! Sample `i` seeds its own `Xoshiro256PlusPlus` from a SplitMix64 mix of the sweep seed
//! and `i`, then draws the inputs in the fixed order of `INPUT_FIELDS`, then its terrain
//! tile and offset. No state is shared between samples, so threads, shards and resumption
//! cannot change a sample, and any sample can be replayed alone.
//!
//! Logarithms and cosines come from the `libm` crate (pure Rust), not the C library, whose
//! versions differ in the last bit between CPUs with and without FMA: a sample's inputs are
//! the same bits on every machine.

use crate::scenario::{Dist, INPUT_FIELDS, Inputs, Scenario};
use rand_core::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Everything that makes one sample differ from another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub index: u64,
    /// The seed of this sample's generator.
    pub seed: u64,
    pub inputs: Inputs<f64>,
    /// Which precomputed terrain tile this sample lands on (0 on a flat surface).
    pub terrain_tile: u32,
    /// Offset of the landing point in the tile, along the slope's tangent axes, m.
    pub terrain_offset_m: [f64; 2],
}

/// SplitMix64's output function: a bijective mix of 64 bits.
#[must_use]
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The generator seed of sample `index` of a sweep with seed `seed`.
#[must_use]
pub fn sample_seed(seed: u64, index: u64) -> u64 {
    splitmix64(seed ^ splitmix64(index))
}

/// A uniform draw in [0, 1) with 53 random bits.
pub fn uniform01(rng: &mut impl RngCore) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A standard normal draw (Box-Muller, cosine branch only, so one draw uses two uniforms).
pub fn standard_normal(rng: &mut impl RngCore) -> f64 {
    let u1 = 1.0 - uniform01(rng); // in (0, 1]: the logarithm stays finite
    let u2 = uniform01(rng);
    (-2.0 * libm::log(u1)).sqrt() * libm::cos(std::f64::consts::TAU * u2)
}

/// Draws one value of `dist`; `grid_index` is this input's coordinate on its grid.
fn draw(dist: &Dist, rng: &mut impl RngCore, grid_index: u64) -> f64 {
    match *dist {
        Dist::Fixed(x) => x,
        Dist::Uniform { min, max } => min + (max - min) * uniform01(rng),
        Dist::Normal { mean, sd, min, max } => {
            // Rejection: validation guarantees that [min, max] holds at least 1 % of the
            // mass, so 10 000 tries fail with probability below 1e-43.
            for _ in 0..10_000 {
                let x = mean + sd * standard_normal(rng);
                if x >= min && x <= max {
                    return x;
                }
            }
            mean.clamp(min, max)
        }
        Dist::Grid { min, max, count } => {
            if count <= 1 {
                min
            } else {
                min + (max - min) * grid_index as f64 / (count - 1) as f64
            }
        }
    }
}

/// The grid coordinates of sample `index`: mixed radix over the grid inputs, the last
/// grid input varying fastest, cycling through the product of the grid sizes.
fn grid_indices(dists: &[Dist; 12], index: u64) -> [u64; 12] {
    let mut out = [0u64; 12];
    let mut rest = index;
    for (o, d) in out.iter_mut().zip(dists).rev() {
        if let Dist::Grid { count, .. } = d {
            *o = rest % count;
            rest /= count;
        }
    }
    out
}

/// Number of points of the input grid (1 when no input is a grid).
#[must_use]
pub fn grid_size(scenario: &Scenario) -> u128 {
    scenario
        .inputs
        .to_array()
        .iter()
        .map(|d| match d {
            Dist::Grid { count, .. } => u128::from(*count),
            _ => 1,
        })
        .product()
}

/// The inputs of sample `index` of `scenario`.
#[must_use]
pub fn sample(scenario: &Scenario, index: u64) -> Sample {
    let seed = sample_seed(scenario.seed, index);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let dists = scenario.inputs.to_array();
    let grid = grid_indices(&dists, index);
    let mut values = [0.0; INPUT_FIELDS.len()];
    for ((v, d), g) in values.iter_mut().zip(&dists).zip(grid) {
        *v = draw(d, &mut rng, g);
    }
    let rough = &scenario.surface.roughness;
    let (terrain_tile, terrain_offset_m) = if rough.rms_height_m > 0.0 {
        let tile = (rng.next_u64() % rough.tiles as u64) as u32;
        let offset = [
            rough.tile_size_m * uniform01(&mut rng),
            rough.tile_size_m * uniform01(&mut rng),
        ];
        (tile, offset)
    } else {
        (0, [0.0, 0.0])
    };
    Sample {
        index,
        seed,
        inputs: Inputs::from_array(values),
        terrain_tile,
        terrain_offset_m,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn uniform_and_normal_moments() {
        // 200 000 draws: the standard error of a mean is sd/447, of a variance about
        // sd^2 * sqrt(2/n) = 0.32 %; the bounds are five standard errors.
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let n = 200_000;
        let (mut s, mut s2) = (0.0, 0.0);
        for _ in 0..n {
            let x = standard_normal(&mut rng);
            s += x;
            s2 += x * x;
        }
        let mean = s / n as f64;
        assert!(mean.abs() < 5.0 / (n as f64).sqrt(), "mean {mean}");
        assert!((s2 / n as f64 - 1.0).abs() < 5.0 * (2.0 / n as f64).sqrt());
        let u: f64 = (0..n).map(|_| uniform01(&mut rng)).sum::<f64>() / n as f64;
        assert!((u - 0.5).abs() < 5.0 * (1.0 / 12.0 / n as f64).sqrt());
    }

    #[test]
    fn truncated_normal_stays_in_bounds() {
        let d = Dist::Normal {
            mean: 0.0,
            sd: 1.0,
            min: 0.5,
            max: 1.0,
        };
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        for _ in 0..10_000 {
            let x = draw(&d, &mut rng, 0);
            assert!((0.5..=1.0).contains(&x));
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
}
