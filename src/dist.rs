//! Distributions of the values a sample draws (fixed, uniform, uniform in the logarithm,
//! normal, grid), and their inverse CDFs: a uniform draw in
//! (0, 1) becomes a value of the distribution through `quantile`.
//!
//! Logarithms and the error function come from the `libm` crate (pure Rust), not the C
//! library, whose versions differ in the last bit between CPUs with and without FMA: a
//! sample's inputs are the same bits on every machine.

/// How an input is drawn for each sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dist {
    /// Always this value.
    Fixed(f64),
    /// Uniform on `[min, max]`.
    Uniform {
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// Normal, truncated to `[min, max]` (infinite bounds: not truncated).
    Normal {
        /// Mean of the normal before truncation.
        mean: f64,
        /// Standard deviation of the normal before truncation.
        sd: f64,
        /// Lower truncation bound (`-inf`: none).
        min: f64,
        /// Upper truncation bound (`inf`: none).
        max: f64,
    },
    /// Uniform in the logarithm on `[min, max]`, `0 < min <= max`: each factor of the range
    /// (from `x` to `2 x`, say) is drawn as often wherever it lies; density
    /// `1 / (x ln(max / min))`.
    LogUniform {
        /// Lower bound, above 0.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// `count` evenly spaced values from `min` to `max`; several grid inputs form their
    /// cartesian product, the last one varying fastest with the sample index.
    Grid {
        /// First value.
        min: f64,
        /// Last value.
        max: f64,
        /// Number of values (1: `min` alone).
        count: u64,
    },
}

impl Dist {
    /// The distribution as a scenario writes it, `{ dist = "uniform", min = 1, max = 2 }`.
    #[must_use]
    pub fn toml(&self) -> String {
        match *self {
            Dist::Fixed(x) => format!("{x:?}"),
            Dist::Uniform { min, max } => {
                format!("{{ dist = \"uniform\", min = {min:?}, max = {max:?} }}")
            }
            Dist::Normal { mean, sd, min, max } => {
                let mut s = format!("{{ dist = \"normal\", mean = {mean:?}, sd = {sd:?}");
                if min.is_finite() {
                    s += &format!(", min = {min:?}");
                }
                if max.is_finite() {
                    s += &format!(", max = {max:?}");
                }
                s + " }"
            }
            Dist::LogUniform { min, max } => {
                format!("{{ dist = \"log-uniform\", min = {min:?}, max = {max:?} }}")
            }
            Dist::Grid { min, max, count } => {
                format!("{{ dist = \"grid\", min = {min:?}, max = {max:?}, count = {count} }}")
            }
        }
    }

    /// The smallest and largest value the distribution can produce.
    #[must_use]
    pub fn support(&self) -> (f64, f64) {
        match *self {
            Dist::Fixed(x) => (x, x),
            Dist::Uniform { min, max }
            | Dist::LogUniform { min, max }
            | Dist::Grid { min, max, .. } => (min, max),
            Dist::Normal { min, max, .. } => (min, max),
        }
    }
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
        // In logarithms throughout (`max / min`, or `min` times a power, overflows for the
        // widest ranges), libm's: the same bits on every CPU.
        Dist::LogUniform { min, max } => {
            let (a, b) = (libm::log(min), libm::log(max));
            libm::exp(a + u * (b - a)).clamp(min, max)
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::uniform_open01;
    use rand_core::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

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
    fn log_uniform_draws_have_its_mean_and_spread_evenly_over_factors() {
        // Uniform in ln x on [a, b]: mean (b - a) / ln(b / a), and each of the k equal
        // factors of the range (a q^j to a q^(j+1), q = (b/a)^(1/k)) holds 1/k of the draws.
        // The mean's standard error is sd/sqrt(n), and sd is below (b - a)/2 (a bound loose
        // for the widest range: the bins test it finely); a bin's share's is
        // sqrt(p (1 - p) / n); the bounds are five of each. Three ranges: a narrow one, the
        // 22.5-fold span of Didymos' gravities, and six decades.
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        let n = 200_000;
        for (a, b) in [(2.0, 3.0), (1.05e-5, 2.36e-4), (1e-3, 1e3)] {
            let d = Dist::LogUniform { min: a, max: b };
            let k = 8;
            let mut bins = [0u32; 8];
            let mut sum = 0.0;
            for _ in 0..n {
                let x = quantile(&d, uniform_open01(&mut rng), 0);
                assert!((a..=b).contains(&x), "[{a}, {b}]: {x}");
                sum += x;
                let j = ((x / a).ln() / (b / a).ln() * k as f64) as usize;
                bins[j.min(k - 1)] += 1;
            }
            let mean = sum / n as f64;
            let expected = (b - a) / (b / a).ln();
            assert!(
                (mean - expected).abs() < 5.0 * 0.5 * (b - a) / (n as f64).sqrt(),
                "[{a}, {b}]: mean {mean}, expected {expected}"
            );
            let p = 1.0 / k as f64;
            for (j, &c) in bins.iter().enumerate() {
                let share = f64::from(c) / n as f64;
                assert!(
                    (share - p).abs() < 5.0 * (p * (1.0 - p) / n as f64).sqrt(),
                    "[{a}, {b}]: factor {j} holds {share}"
                );
            }
        }
        // The ends of (0, 1) map onto the ends of the range, and the middle onto the
        // geometric mean.
        let d = Dist::LogUniform { min: 4.0, max: 9.0 };
        assert!((quantile(&d, 0.5, 0) - 6.0).abs() < 1e-14);
        assert!((quantile(&d, 0.0, 0) - 4.0).abs() < 1e-14);
        assert!((quantile(&d, 1.0, 0) - 9.0).abs() < 1e-14);
        // A range wider than a double's ratio: no overflow, the middle still the geometric
        // mean (1).
        let wide = Dist::LogUniform {
            min: 1e-300,
            max: 1e300,
        };
        assert!((quantile(&wide, 0.5, 0) - 1.0).abs() < 1e-12);
        assert!((quantile(&wide, 0.75, 0) / 1e150 - 1.0).abs() < 1e-10);
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
}
