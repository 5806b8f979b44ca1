//! Random streams: a sample's generator seed from the sweep's seed and its index, and one
//! generator per named quantity of a sample, so that no quantity's draws depend on another's.
//! The seeding is SplitMix64 (a bijective 64-bit mix); the generators are
//! `Xoshiro256PlusPlus`.

use rand_core::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

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
