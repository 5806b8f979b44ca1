//! Builds the rough-terrain tiles of a scenario (MODEL.md section 4, thesis 3.4.2.2):
//! white-noise node heights, a periodic Gaussian blur, then scaling to the requested RMS.
//!
//! The tiles depend on the scenario seed alone and are built once per run; every sample
//! picks a tile and an offset (see `sampling`), so memory does not grow with the samples.

use crate::dist::normal_quantile;
use crate::rng::{splitmix64, uniform_open01};
use crate::scenario::Roughness;
use kernels::terrain::Terrain;
use rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// The terrain of a scenario, or `None` for a flat surface.
#[must_use]
pub fn build(roughness: &Roughness, seed: u64) -> Option<Terrain> {
    if roughness.rms_height_m <= 0.0 {
        return None;
    }
    let n = (roughness.tile_size_m / roughness.node_spacing_m).round() as usize;
    let sigma_nodes = roughness.smoothing_length_m / roughness.node_spacing_m;
    let kernel = gaussian_kernel(sigma_nodes, n);
    let mut heights = Vec::with_capacity(n * n * roughness.tiles);
    for tile in 0..roughness.tiles {
        // A stream per tile, apart from the per-sample streams by the constant.
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(splitmix64(
            seed ^ 0x7E44_A1F0_0000_0000 ^ tile as u64,
        ));
        let noise: Vec<f64> = (0..n * n)
            .map(|_| normal_quantile(uniform_open01(&mut rng)))
            .collect();
        let mut h = blur_periodic(&noise, n, &kernel);
        let mean = h.iter().sum::<f64>() / h.len() as f64;
        let rms = (h.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / h.len() as f64).sqrt();
        let scale = if rms > 0.0 {
            roughness.rms_height_m / rms
        } else {
            0.0
        };
        for x in &mut h {
            *x = (*x - mean) * scale;
        }
        heights.extend_from_slice(&h);
    }
    Some(Terrain::new(n, roughness.node_spacing_m, heights))
}

/// Normalised weights of a Gaussian of `sigma` nodes, reaching 3 sigma (at most half a tile).
fn gaussian_kernel(sigma: f64, n: usize) -> Vec<f64> {
    if sigma < 1e-9 {
        return vec![1.0];
    }
    let reach = ((3.0 * sigma).ceil() as usize).min(n / 2);
    let mut k: Vec<f64> = (0..=2 * reach)
        .map(|i| {
            let x = i as f64 - reach as f64;
            libm::exp(-0.5 * x * x / (sigma * sigma))
        })
        .collect();
    let sum: f64 = k.iter().sum();
    k.iter_mut().for_each(|w| *w /= sum);
    k
}

/// Separable convolution of an `n` x `n` periodic field with `kernel` (odd length).
fn blur_periodic(field: &[f64], n: usize, kernel: &[f64]) -> Vec<f64> {
    let reach = (kernel.len() / 2) as isize;
    let wrap = |i: isize| i.rem_euclid(n as isize) as usize;
    let mut rows = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..n {
            rows[j * n + i] = kernel
                .iter()
                .enumerate()
                .map(|(k, w)| w * field[j * n + wrap(i as isize + k as isize - reach)])
                .sum();
        }
    }
    let mut out = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..n {
            out[j * n + i] = kernel
                .iter()
                .enumerate()
                .map(|(k, w)| w * rows[wrap(j as isize + k as isize - reach) * n + i])
                .sum();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn roughness(rms: f64) -> Roughness {
        Roughness {
            rms_height_m: rms,
            node_spacing_m: 0.05,
            smoothing_length_m: 0.15,
            tile_size_m: 3.2,
            tiles: 3,
        }
    }

    #[test]
    fn flat_has_no_terrain() {
        assert!(build(&roughness(0.0), 1).is_none());
    }

    #[test]
    fn tiles_have_the_requested_rms_and_zero_mean() {
        for rms in [0.005, 0.02] {
            let t = build(&roughness(rms), 9).unwrap();
            assert_eq!((t.nodes(), t.tiles()), (64, 3));
            let n2 = 64 * 64;
            for tile in t.heights_m().chunks(n2) {
                let mean = tile.iter().sum::<f64>() / n2 as f64;
                let r = (tile.iter().map(|x| x * x).sum::<f64>() / n2 as f64).sqrt();
                assert!(mean.abs() < 1e-12, "mean {mean}");
                assert!((r - rms).abs() < 1e-12 * rms.max(1.0), "rms {r}");
            }
        }
    }

    #[test]
    fn smoothing_correlates_neighbours() {
        // A Gaussian blur of sigma = 3 nodes makes neighbouring heights nearly equal: the
        // correlation of a field blurred with sigma s at lag 1 is exp(-1 / (4 s^2)) = 0.97.
        let t = build(&roughness(0.01), 2).unwrap();
        let h = &t.heights_m()[..64 * 64];
        let (mut c, mut v) = (0.0, 0.0);
        for j in 0..64 {
            for i in 0..64 {
                c += h[j * 64 + i] * h[j * 64 + (i + 1) % 64];
                v += h[j * 64 + i] * h[j * 64 + i];
            }
        }
        let rho = c / v;
        assert!(
            (rho - (-1.0f64 / 36.0).exp()).abs() < 0.02,
            "lag-1 correlation {rho}"
        );
    }
}
