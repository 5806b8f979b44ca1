//! Sample index -> inputs, as a pure function of (scenario, seed, index).
//!
//! Sample `i` has a generator seed from a SplitMix64 mix of the sweep seed and `i`; each of
//! its inputs (and its terrain tile and offset) then draws from a `Xoshiro256PlusPlus` of its
//! own, seeded from that seed and the input's name, through the input's inverse CDF. No state
//! is shared between samples or between inputs, so threads, shards and resumption cannot
//! change a sample, any sample can be replayed alone, and scenarios that differ in one input
//! draw the same values for all the others (common random numbers, for paired studies).
//!
//! Logarithms come from the `libm` crate (pure Rust), not the C library, whose versions
//! differ in the last bit between CPUs with and without FMA: a sample's inputs are the same
//! bits on every machine.

use crate::scenario::{
    Control, Design, Dist, INPUT_FIELDS, Inputs, LAW_PARAMETERS, PARAMETER_FIELDS, PARAMETERS,
    Parameter, Scenario,
};
use rand_core::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Everything that makes one sample differ from another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub index: u64,
    /// The seed of this sample's generator.
    pub seed: u64,
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

/// Number of values a sample draws: the inputs (`INPUT_FIELDS`), then the parameters
/// (`PARAMETER_FIELDS`).
pub const VALUES: usize = INPUT_FIELDS.len() + PARAMETERS;

// The quasi-random design gives every value a dimension of the Sobol sequence.
const _: () = assert!(VALUES <= crate::qmc::MAX_DIMENSIONS);

/// The column name of value `k` of a sample (`Sample::values`).
#[must_use]
pub fn value_name(k: usize) -> &'static str {
    if k < INPUT_FIELDS.len() {
        INPUT_FIELDS[k].0
    } else {
        PARAMETER_FIELDS[k - INPUT_FIELDS.len()].0
    }
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

/// A uniform draw strictly inside (0, 1), with 53 random bits: the argument of an
/// inverse CDF, which is infinite at 0 and 1.
pub fn uniform_open01(rng: &mut impl RngCore) -> f64 {
    ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
}

/// The standard normal CDF, `Phi(x)`.
#[must_use]
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// The inverse of the standard normal CDF at `p` in (0, 1): Wichura's algorithm AS 241
/// (PPND16), relative error about 1e-16.
#[must_use]
pub fn normal_quantile(p: f64) -> f64 {
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180625 - q * q;
        return q
            * (((((((r * 2_509.080_928_730_122_7 + 33_430.575_583_588_13) * r
                + 67_265.770_927_008_7)
                * r
                + 45_921.953_931_549_87)
                * r
                + 13_731.693_765_509_46)
                * r
                + 1_971.590_950_306_551_4)
                * r
                + 133.141_667_891_784_38)
                * r
                + 3.387_132_872_796_366_5)
            / (((((((r * 5_226.495_278_852_546 + 28_729.085_735_721_943) * r
                + 39_307.895_800_092_71)
                * r
                + 21_213.794_301_586_597)
                * r
                + 5_394.196_021_424_751)
                * r
                + 687.187_007_492_057_9)
                * r
                + 42.313_330_701_600_91)
                * r
                + 1.0);
    }
    let tail = if q < 0.0 { p } else { 1.0 - p };
    let mut r = (-libm::log(tail)).sqrt();
    let value = if r <= 5.0 {
        r -= 1.6;
        (((((((r * 7.745_450_142_783_414e-4 + 0.022_723_844_989_269_184) * r
            + 0.241_780_725_177_450_6)
            * r
            + 1.270_458_252_452_368_4)
            * r
            + 3.647_848_324_763_204_5)
            * r
            + 5.769_497_221_460_691)
            * r
            + 4.630_337_846_156_545)
            * r
            + 1.423_437_110_749_683_5)
            / (((((((r * 1.050_750_071_644_416_8e-9 + 5.475_938_084_995_345e-4) * r
                + 0.015_198_666_563_616_457)
                * r
                + 0.148_103_976_427_480_07)
                * r
                + 0.689_767_334_985_1)
                * r
                + 1.676_384_830_183_803_8)
                * r
                + 2.053_191_626_637_759)
                * r
                + 1.0)
    } else {
        r -= 5.0;
        (((((((r * 2.010_334_399_292_288_1e-7 + 2.711_555_568_743_487_6e-5) * r
            + 0.001_242_660_947_388_078_4)
            * r
            + 0.026_532_189_526_576_124)
            * r
            + 0.296_560_571_828_504_9)
            * r
            + 1.784_826_539_917_291_3)
            * r
            + 5.463_784_911_164_114)
            * r
            + 6.657_904_643_501_103)
            / (((((((r * 2.044_263_103_389_939_7e-15 + 1.421_511_758_316_446e-7) * r
                + 1.846_318_317_510_054_8e-5)
                * r
                + 7.868_691_311_456_133e-4)
                * r
                + 0.014_875_361_290_850_615)
                * r
                + 0.136_929_880_922_735_8)
                * r
                + 0.599_832_206_555_887_9)
                * r
                + 1.0)
    };
    if q < 0.0 { -value } else { value }
}

/// The value of `dist` at `u` in (0, 1): its inverse CDF (the grid coordinate for grids).
/// Increasing in `u`, so the same `u` gives two distributions' values in the same order.
#[must_use]
pub fn quantile(dist: &Dist, u: f64, grid_index: u64) -> f64 {
    match *dist {
        Dist::Fixed(x) => x,
        Dist::Uniform { min, max } => min + (max - min) * u,
        Dist::Normal { mean, sd, min, max } => {
            let (a, b) = ((min - mean) / sd, (max - mean) / sd);
            // In the upper tail, work with the lower tail of -z, where the CDF keeps its
            // digits (Phi(a) and Phi(b) near 1 would lose them).
            let z = if a > 0.0 {
                let (lo, hi) = (normal_cdf(-b), normal_cdf(-a));
                -normal_quantile(hi - u * (hi - lo))
            } else {
                let (lo, hi) = (normal_cdf(a), normal_cdf(b));
                normal_quantile(lo + u * (hi - lo))
            };
            (mean + sd * z).clamp(min, max)
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

/// A 64-bit key of a name: FNV-1a, then SplitMix64's mix.
fn name_key(name: &str) -> u64 {
    let fnv = name.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    splitmix64(fnv)
}

/// The random stream of one quantity (an input, by its column name) of the sample whose
/// generator seed is `sample_seed`: a generator of its own, so that no quantity's draws
/// depend on another's distribution, or on which others exist.
#[must_use]
pub fn stream(sample_seed: u64, name: &str) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(sample_seed ^ name_key(name))
}

/// The grid coordinates of sample `index`: mixed radix over the grid distributions of
/// `dists`, the last varying fastest, cycling through the product of the grid sizes.
fn grid_indices<const N: usize>(dists: &[Dist; N], index: u64) -> [u64; N] {
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
fn grid_dists(scenario: &Scenario) -> [Dist; VALUES + LAW_PARAMETERS] {
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

/// The inputs of sample `index` of `scenario`.
///
/// With `design = "sobol-indices"` (Saltelli's design), samples come in blocks of `d + 2`
/// for the `d` inputs drawn at random (`design_inputs`): block `j` is base point `j`, whose
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
    let table = scenario.table.as_deref();
    let seed = table
        .and_then(|t| t.sample_seed(index))
        .unwrap_or_else(|| sample_seed(scenario.seed, index));
    let dists = value_dists(scenario);
    let grid = grid_indices(&grid_dists(scenario), index);
    let mut values = [0.0; VALUES];
    // With the quasi-random design, the q-th value drawn from a distribution takes
    // coordinate q of point `index` of the scrambled Sobol sequence.
    let mut dimension = 0;
    for (k, ((v, d), g)) in values.iter_mut().zip(&dists).zip(grid).enumerate() {
        if let Some(x) = table.and_then(|t| t.value(k, index)) {
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
            d => quantile(d, uniform_open01(&mut stream(seed, value_name(k))), g),
        };
    }
    let rough = &scenario.surface.roughness;
    let (terrain_tile, terrain_offset_m) = if scenario.rms_height_max_m() > 0.0 {
        let tile = (stream(seed, "terrain_tile").next_u64() % rough.tiles as u64) as u32;
        let offset = [
            rough.tile_size_m * uniform01(&mut stream(seed, "terrain_offset_u_m")),
            rough.tile_size_m * uniform01(&mut stream(seed, "terrain_offset_v_m")),
        ];
        (tile, offset)
    } else {
        (0, [0.0, 0.0])
    };
    let (terrain_tile, terrain_offset_m) = match table.map(|t| t.terrain(index)) {
        Some((tile, [u, v])) => (
            tile.unwrap_or(terrain_tile),
            [
                u.unwrap_or(terrain_offset_m[0]),
                v.unwrap_or(terrain_offset_m[1]),
            ],
        ),
        None => (terrain_tile, terrain_offset_m),
    };
    let mut s = Sample {
        index,
        seed,
        inputs: Inputs::from_array([0.0; INPUT_FIELDS.len()]),
        parameters: [0.0; PARAMETERS],
        terrain_tile,
        terrain_offset_m,
        law_cell: index % law_grid_size(scenario.control.as_ref()),
    };
    s.set_values(values);
    s
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
    fn normal_quantiles_match_known_values_and_invert_the_cdf() {
        // Reference quantiles to 16 digits (R's qnorm); AS 241 is good to about 1e-16
        // relative, so 1e-14 leaves room for the last digits of the reference.
        for (p, z) in [
            (0.5, 0.0),
            (0.975, 1.959_963_984_540_054),
            (0.9, 1.281_551_565_544_600_5),
            (0.999, 3.090_232_306_167_813_5),
            (0.1, -1.281_551_565_544_600_5),
            (1e-10, -6.361_340_902_404_056),
        ] {
            let got = normal_quantile(p);
            assert!(
                (got - z).abs() <= 1e-14 * z.abs().max(1.0),
                "p {p}: {got} vs {z}"
            );
        }
        // The CDF of the quantile is the probability again, across the whole range.
        for i in 1..2000 {
            let p = f64::from(i) / 2000.0;
            let back = normal_cdf(normal_quantile(p));
            assert!((back - p).abs() <= 1e-15 + 1e-14 * p, "p {p}: {back}");
        }
        // And far in the tails, relative to p: an error dx in the quantile x moves p by
        // |x| dx relative, about 37 * 4e-15 at 1e-300.
        for p in [1e-20, 1e-100, 1e-200, 1e-300] {
            let x = normal_quantile(p);
            let back = normal_cdf(x);
            assert!(((back - p) / p).abs() < 1e-12, "p {p}: x {x}, back {back}");
        }
    }

    #[test]
    fn inverse_cdf_draws_have_the_moments_of_their_distributions() {
        // 200 000 draws: the standard error of a mean is sd/447, of a variance about
        // sd^2 * sqrt(2/n) = 0.32 %; the bounds are five standard errors.
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let n = 200_000;
        let normal = Dist::Normal {
            mean: 2.0,
            sd: 3.0,
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
        };
        let (mut s, mut s2) = (0.0, 0.0);
        for _ in 0..n {
            let x = (quantile(&normal, uniform_open01(&mut rng), 0) - 2.0) / 3.0;
            s += x;
            s2 += x * x;
        }
        let mean = s / n as f64;
        assert!(mean.abs() < 5.0 / (n as f64).sqrt(), "mean {mean}");
        assert!((s2 / n as f64 - 1.0).abs() < 5.0 * (2.0 / n as f64).sqrt());
        let uniform = Dist::Uniform { min: 0.0, max: 1.0 };
        let u: f64 = (0..n)
            .map(|_| quantile(&uniform, uniform_open01(&mut rng), 0))
            .sum::<f64>()
            / n as f64;
        assert!((u - 0.5).abs() < 5.0 * (1.0 / 12.0 / n as f64).sqrt());
    }

    #[test]
    fn truncated_normals_stay_in_bounds_with_the_truncated_mean() {
        // Mean of N(0, 1) truncated to [a, b]: (phi(a) - phi(b)) / (Phi(b) - Phi(a)); its
        // standard error is below 1/sqrt(n), bound five of them. Lower tail, both sides of
        // the mean, and far up the upper tail (where the CDF near 1 would lose its digits).
        let phi = |x: f64| (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        let n = 100_000;
        for (a, b) in [
            (-3.0, -1.0),
            (-0.5, 2.0),
            (0.5, 1.0),
            (5.0, 6.0),
            (8.0, f64::INFINITY),
        ] {
            let d = Dist::Normal {
                mean: 0.0,
                sd: 1.0,
                min: a,
                max: b,
            };
            let mut sum = 0.0;
            for _ in 0..n {
                let x = quantile(&d, uniform_open01(&mut rng), 0);
                assert!((a..=b).contains(&x), "[{a}, {b}]: {x}");
                sum += x;
            }
            let upper = if b.is_finite() { phi(b) } else { 0.0 };
            // Upper-tail masses from the complement, for their digits.
            let mass = normal_cdf(-a) - normal_cdf(-b);
            let expected = (phi(a) - upper) / mass;
            let got = sum / n as f64;
            assert!(
                (got - expected).abs() < 5.0 / (n as f64).sqrt(),
                "[{a}, {b}]: mean {got}, expected {expected}"
            );
        }
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
        let control = s.control.clone().unwrap();
        let pick = |i| {
            let x = sample(&s, i);
            let g = law_grid(&control, x.law_cell);
            (x.inputs.slope_deg, g[0], g[1])
        };
        assert_eq!(pick(0), (0.0, 0, 0));
        assert_eq!(pick(1), (0.0, 0, 1));
        assert_eq!(pick(4), (0.0, 1, 0));
        assert_eq!(pick(36), (10.0, 0, 0));
        assert_eq!(pick(107), (20.0, 8, 3));
        assert_eq!(pick(108), (0.0, 0, 0));
        // Every law parameter the scenario has not is at 0; without a control loop
        // nothing joins the grid.
        assert!(law_grid(&control, 35)[2..].iter().all(|&g| g == 0));
        assert_eq!(sample(&Scenario::default(), 5).law_cell, 0);
    }
}
