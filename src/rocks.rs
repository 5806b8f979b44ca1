//! Builds the rock tiles of a scenario (MODEL.md section 4, "Rocks"): per tile a Poisson
//! number of hemispherical rocks, diameters from Golombek and Rapp's size-frequency model,
//! centres uniform on the tile, and each rock's abundance threshold for thinning.
//!
//! The tiles depend on the scenario seed alone and are built once per run, for the largest
//! abundance `k_max` the scenario draws; a sample of abundance `k` keeps the rocks whose
//! threshold is at most `k`, which are exactly a field of abundance `k` (`threshold`).

use crate::rng::{splitmix64, uniform_open01, uniform01};
use crate::scenario::Rocks as Field;
use kernels::rocks::{Rock, Rocks};
use rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Apart from terrain's tiles (`0x7E44_A1F0_...`) and from the per-sample streams.
const STREAM: u64 = 0x80C4_5D0E_0000_0000;

/// A cell's side aims at this (a footpad of radius up to 0.25 m then reads at most 4 cells).
const CELL_TARGET_M: f64 = 0.5;

/// At most this many cells in all tiles (4 bytes each: 16 MB).
const MAX_CELLS_IN_ALL: f64 = 4_194_304.0;

/// The rock tiles of a scenario, built for `field.abundance` (a scenario that draws the
/// abundance passes its largest value, as for the terrain's RMS height), or `None` for no
/// rocks (an abundance of 0).
#[must_use]
pub fn build(field: &Field, seed: u64) -> Option<Rocks> {
    let k_max = field.abundance;
    if k_max <= 0.0 {
        return None;
    }
    let size = field.tile_size_m;
    let mean = field.rocks_per_m2(k_max) * size * size;
    let q = Field::exponent_per_m(k_max);
    let tiles = (0..field.tiles)
        .map(|tile| {
            // A stream per tile, apart from every other stream by the constant.
            let mut rng =
                Xoshiro256PlusPlus::seed_from_u64(splitmix64(seed ^ STREAM ^ tile as u64));
            let count = poisson(&mut rng, mean);
            (0..count)
                .map(|_| {
                    let d = diameter(&mut rng, field.diameter_min_m, field.diameter_max_m, q);
                    let (u_m, v_m) = (position(&mut rng, size), position(&mut rng, size));
                    let w = uniform_open01(&mut rng);
                    Rock {
                        u_m,
                        v_m,
                        radius_m: 0.5 * d,
                        threshold: threshold(d, w, k_max),
                    }
                })
                .collect()
        })
        .collect();
    let by_size = (size / CELL_TARGET_M).floor();
    let by_memory = (MAX_CELLS_IN_ALL / field.tiles as f64).sqrt().floor();
    let cells = by_size.min(by_memory).max(1.0) as usize;
    Some(Rocks::new(size, cells, tiles))
}

/// A Poisson number of mean `mean`: the arrivals of a unit-rate Poisson process up to
/// time `mean`, from exponential gaps (as many draws as rocks, which are bounded).
fn poisson(rng: &mut Xoshiro256PlusPlus, mean: f64) -> usize {
    let mut count = 0;
    let mut t = -libm::log(uniform_open01(rng));
    while t <= mean {
        count += 1;
        t -= libm::log(uniform_open01(rng));
    }
    count
}

/// A diameter in `[d_min, d_max]` of density proportional to `exp(-q D) / D^2` (Golombek
/// and Rapp's number density, MODEL.md section 4): by rejection from the density
/// proportional to `1 / D^2` (drawn by its inverse CDF), accepting with probability
/// `exp(-q (D - d_min))`, at most 1.
fn diameter(rng: &mut Xoshiro256PlusPlus, d_min: f64, d_max: f64, q: f64) -> f64 {
    let (a, b) = (1.0 / d_min, 1.0 / d_max);
    loop {
        let d = 1.0 / (a - uniform01(rng) * (a - b));
        if uniform01(rng) < libm::exp(-q * (d - d_min)) {
            return d.clamp(d_min, d_max);
        }
    }
}

/// A uniform coordinate in `[0, size)` (a product that rounds up to `size` wraps to 0).
fn position(rng: &mut Xoshiro256PlusPlus, size: f64) -> f64 {
    let x = uniform01(rng) * size;
    if x < size { x } else { 0.0 }
}

/// The probability `r(D, k) = n_k(D) / n_kmax(D)` that a rock of diameter `d` of a field
/// of abundance `k_max` is one of a field of abundance `k <= k_max`.
///
/// With `q(k) = 1.79 + 0.152 / k`, `k q(k) = 1.79 k + 0.152` and `q(k) - q(k_max) = 0.152
/// (1 / k - 1 / k_max)`, so `r = (1.79 k + 0.152) / (1.79 k_max + 0.152) exp(-0.152 D (1 / k
/// - 1 / k_max))`: both factors increase with `k`, are 1 at `k_max` and the second tends to
/// 0 with `k`. So `r` rises monotonically from 0 to 1 over `(0, k_max]`, and keeping a rock
/// iff `r(D, k) >= w`, with `w` uniform, keeps it with probability `r`: thinning a Poisson
/// field of density `n_kmax` by `r` leaves a Poisson field of density exactly `n_k`.
fn kept_share(d: f64, k: f64, k_max: f64) -> f64 {
    (1.79 * k + 0.152) / (1.79 * k_max + 0.152) * libm::exp(-0.152 * d * (1.0 / k - 1.0 / k_max))
}

/// The abundance at which a rock of diameter `d` with uniform draw `w` appears: the `k` in
/// `(0, k_max]` where `kept_share(d, k, k_max) = w`, the smallest at which it is kept.
///
/// In `x = 1 / k` the logarithm of the share, `f(x) = ln(1.79 / x + 0.152) - 0.152 d x` less
/// constants, falls and is convex; Newton's method from `x = 1 / k_max` (where the share is
/// 1, at least `w`) then climbs to the root from below without overshooting, quadratically:
/// a handful of logarithms per rock, where a bisection to 1e-12 takes forty exponentials.
fn threshold(d: f64, w: f64, k_max: f64) -> f64 {
    let target = libm::log(w) + libm::log(1.79 * k_max + 0.152) - 0.152 * d / k_max;
    let mut x = 1.0 / k_max;
    for _ in 0..100 {
        let f = libm::log(1.79 / x + 0.152) - 0.152 * d * x;
        let falls = 1.79 / (x * (1.79 + 0.152 * x)) + 0.152 * d;
        let step = (f - target) / falls;
        x += step;
        if step.abs() <= 1e-15 * x {
            break;
        }
    }
    // Rounding may leave the root a hair low, where the share is just below `w`.
    let mut k = (1.0 / x).min(k_max);
    while k < k_max && kept_share(d, k, k_max) < w {
        k = k.next_up();
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// 64 tiles of 40 m: about 100,000 m², 64,000 rocks at k = 0.03 and 340,000 at 0.2.
    fn field(k: f64) -> Field {
        Field {
            diameter_min_m: 0.1,
            diameter_max_m: 2.0,
            tile_size_m: 40.0,
            tiles: 64,
            abundance: k,
        }
    }

    /// Simpson's rule for `f` over `[a, b]` in 4096 intervals.
    fn integral(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
        let n = 4096;
        let h = (b - a) / n as f64;
        let inner: f64 = (1..n)
            .map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(a + h * i as f64))
            .sum();
        (f(a) + inner + f(b)) * h / 3.0
    }

    /// The rocks present at `k` (threshold at most `k`), over all tiles.
    fn present(rocks: &Rocks, k: f64) -> Vec<Rock> {
        (0..rocks.tiles())
            .flat_map(|t| rocks.rocks(t).iter().copied())
            .filter(|r| r.threshold <= k)
            .collect()
    }

    /// Checks the fractional area of the rocks present at `k` of diameter `d` or more
    /// against Golombek and Rapp's `F_k(d) - F_k(D_max)`, and returns `(measured, expected,
    /// sigma)`.
    ///
    /// The rocks of a tile are a Poisson field of density `n_k`, so their summed area over
    /// the tiles' area `A` is compound Poisson: its variance is `A` times the integral of
    /// `n_k(x) (pi x^2 / 4)^2` over the diameters counted, and the share's `sigma` is the
    /// square root of that over `A^2`. The tolerance is 4 sigma: a correct field fails one
    /// of the 12 comparisons with probability about 1e-3 (and a fixed seed makes it the same
    /// answer every run).
    fn area_share(rocks: &Rocks, k: f64, d: f64) -> (f64, f64, f64) {
        let f = field(k);
        let area = f.tile_size_m * f.tile_size_m * f.tiles as f64;
        let covered: f64 = present(rocks, k)
            .iter()
            .filter(|r| 2.0 * r.radius_m >= d)
            .map(|r| PI * r.radius_m * r.radius_m)
            .sum();
        let measured = covered / area;
        let expected = Field::fractional_area(k, d) - Field::fractional_area(k, f.diameter_max_m);
        let variance = integral(d, f.diameter_max_m, |x| {
            Field::number_density(k, x) * (PI * x * x / 4.0).powi(2)
        }) / area;
        let sigma = variance.sqrt();
        eprintln!(
            "k {k}, D >= {d} m: {measured:.6} measured, {expected:.6} expected, sigma {sigma:.6}"
        );
        assert!(
            (measured - expected).abs() < 4.0 * sigma,
            "k {k}, D >= {d}: {measured} against {expected} (sigma {sigma})"
        );
        (measured, expected, sigma)
    }

    /// Checks the number of rocks present at `k` against its Poisson mean (4 sigma).
    fn count(rocks: &Rocks, k: f64) {
        let mean = field(k).mean_rocks(k);
        let n = present(rocks, k).len() as f64;
        eprintln!(
            "k {k}: {n} rocks, {mean:.1} expected, sigma {:.1}",
            mean.sqrt()
        );
        assert!(
            (n - mean).abs() < 4.0 * mean.sqrt(),
            "{n} rocks against {mean}"
        );
    }

    #[test]
    fn no_abundance_has_no_rocks() {
        assert!(build(&field(0.0), 1).is_none());
    }

    #[test]
    fn the_field_covers_golombek_and_rapps_fractional_area() {
        for k in [0.03, 0.07, 0.15] {
            let rocks = build(&field(k), 11).unwrap();
            count(&rocks, k);
            for d in [0.1, 0.3, 0.6] {
                area_share(&rocks, k, d);
            }
            assert!(rocks.top_m() <= 1.0);
        }
    }

    #[test]
    fn a_thinned_field_covers_the_smaller_abundances_area() {
        // Built for k_max = 0.2, the rocks of threshold at most 0.05 are a field of 0.05.
        let rocks = build(&field(0.2), 12).unwrap();
        count(&rocks, 0.2);
        count(&rocks, 0.05);
        for d in [0.1, 0.3, 0.6] {
            area_share(&rocks, 0.05, d);
        }
        let all = present(&rocks, 0.2);
        assert!(all.iter().all(|r| r.threshold > 0.0 && r.threshold <= 0.2));
    }

    #[test]
    fn a_threshold_solves_the_kept_share() {
        // The share at the threshold reaches w, and 1e-12 below it does not (the share's
        // relative slope in k, 0.152 D / k and more, is at least 0.07 here).
        let w_all = [1e-12, 0.01, 0.5, 0.999, 1.0 - 1e-12];
        for (d, w) in [0.1, 0.3, 1.5, 2.0]
            .into_iter()
            .flat_map(|d| w_all.map(|w| (d, w)))
        {
            let k = threshold(d, w, 0.2);
            assert!(k > 0.0 && k <= 0.2);
            assert!(kept_share(d, k, 0.2) >= w, "{d} {w}");
            assert!(kept_share(d, k * (1.0 - 1e-12), 0.2) < w, "{d} {w}");
        }
        assert_eq!(kept_share(0.7, 0.2, 0.2), 1.0);
    }

    #[test]
    fn the_seed_decides_the_tiles() {
        let small = Field {
            tiles: 4,
            tile_size_m: 10.0,
            ..field(0.07)
        };
        let a = build(&small, 5).unwrap();
        assert_eq!(a, build(&small, 5).unwrap());
        let b = build(&small, 6).unwrap();
        assert_ne!(a.rocks(0), b.rocks(0));
        assert_ne!(a.rocks(0), a.rocks(1));
        assert_eq!((a.tiles(), a.cells(), a.tile_size_m()), (4, 20, 10.0));
    }
}
