//! The `[surface.rocks]` table: a field of hemispherical rocks whose sizes follow Golombek
//! and Rapp's model of the cumulative fractional area (MODEL.md section 4, "Rocks"), and the
//! model's closed forms, which the reader (to bound the rocks in memory) and the builder of
//! the tiles (`crate::rocks`) share.

use super::error::ScenarioError;
use super::inputs::{Parameter, Sampled, read_parameter};
use super::reader::{Reader, table};

/// The most rocks a scenario may ask for, on average over all its tiles (32 bytes each, and
/// 4 bytes per cell they overlap: about 200 MB at most).
pub const MAX_ROCKS: f64 = 4.0e6;

/// The largest rock abundance `k` (cumulative fractional area) a scenario may give or draw:
/// above the rockiest sites measured (MODEL.md section 4, "Rocks").
pub const MAX_ABUNDANCE: f64 = 0.5;

table! {
    /// Rocks on the surface (MODEL.md section 4, "Rocks"): hemispheres of diameters from
    /// `diameter_min_m` to `diameter_max_m`, as many of each size as Golombek and Rapp's
    /// model of abundance `abundance` gives, in `tiles` square periodic tiles.
    #[derive(Debug, Clone, PartialEq)]
    pub struct Rocks;
    /// Reads `[surface.rocks]`; a key the file leaves out takes default.toml's value, else
    /// the one given here (no rocks).
    fn read_rocks(r, sampled: &mut Sampled) with key {
        /// Smallest rock diameter in the field, m.
        diameter_min_m: f64 = r.or(key, 0.1).positive(key)?,
        /// Largest rock diameter in the field, m.
        diameter_max_m: f64 = {
            let d = r.or(key, 2.0).f64(key)?;
            check(r, key, d, d > diameter_min_m, || {
                format!("a diameter greater than diameter_min_m = {diameter_min_m} m")
            })?
        },
        /// Side of one square, periodic tile, m.
        tile_size_m: f64 = {
            let size = r.or(key, 20.0).f64(key)?;
            check(r, key, size, size >= 2.0 * diameter_max_m, || {
                format!("at least twice diameter_max_m, {} m", 2.0 * diameter_max_m)
            })?
        },
        /// Number of precomputed tiles; each sample draws one and a random offset.
        tiles: usize = r.or(key, 8).integer(key, 1, 1024)?,
        /// Rock abundance `k`: the fraction of the surface covered by rocks of any size
        /// (Golombek and Rapp's cumulative fractional area at diameter 0); 0 means no rocks.
        /// May be drawn per sample: the tiles are built for its largest value and thinned.
        abundance: f64 = {
            let k = read_parameter(r.or(key, 0.0), key, sampled)?;
            let path = r.key_path(key);
            let drawn = Parameter::ALL
                .into_iter()
                .find(|p| p.key() == path)
                .and_then(|p| sampled[p as usize]);
            let largest = drawn.map_or(k, |d| d.support().1);
            let shown = match drawn {
                Some(_) => format!("a distribution reaching {largest}"),
                None => largest.to_string(),
            };
            if largest > MAX_ABUNDANCE {
                return Err(ScenarioError::Invalid {
                    key: path,
                    value: shown,
                    allowed: format!("an abundance from 0 to {MAX_ABUNDANCE}"),
                });
            }
            let field = Rocks {
                diameter_min_m,
                diameter_max_m,
                tile_size_m,
                tiles,
                abundance: largest,
            };
            let mean = field.mean_rocks(largest);
            if mean > MAX_ROCKS {
                return Err(ScenarioError::Invalid {
                    key: r.key_path("tiles"),
                    value: tiles.to_string(),
                    allowed: format!(
                        "at most {MAX_ROCKS:e} rocks in all; at abundance {largest}, diameters \
                         from {diameter_min_m} m and tiles of {tile_size_m} m there are about \
                         {:.0} per tile: fewer or smaller tiles, or a larger diameter_min_m",
                        mean / tiles as f64
                    ),
                });
            }
            k
        },
    }
}

/// `x`, the value of `key`, where `ok`, else the error saying what is `allowed` (checked
/// here rather than by `Reader::f64_where`, which leaves a default unchecked: these checks
/// bind a default against the keys the file gives).
fn check(
    r: &Reader,
    key: &str,
    x: f64,
    ok: bool,
    allowed: impl FnOnce() -> String,
) -> Result<f64, ScenarioError> {
    if ok {
        Ok(x)
    } else {
        Err(ScenarioError::Invalid {
            key: r.key_path(key),
            value: x.to_string(),
            allowed: allowed(),
        })
    }
}

/// Intervals of Simpson's rule over `ln D` in `Rocks::rocks_per_m2` (the integrand is
/// smooth and varies by a factor `e^(q D)` at most: the rule's error is below 1e-12).
const SIMPSON_INTERVALS: usize = 2048;

impl Rocks {
    /// Golombek and Rapp's exponent `q(k) = 1.79 + 0.152 / k` at abundance `k`, per m.
    #[must_use]
    pub fn exponent_per_m(k: f64) -> f64 {
        1.79 + 0.152 / k
    }

    /// The cumulative fractional area `F_k(D) = k exp(-q(k) D)`: the fraction of the surface
    /// covered by rocks of diameter `diameter_m` or larger, at abundance `k`.
    #[must_use]
    pub fn fractional_area(k: f64, diameter_m: f64) -> f64 {
        k * libm::exp(-Self::exponent_per_m(k) * diameter_m)
    }

    /// Rocks per m² per m of diameter at `diameter_m` and abundance `k`: the area `-dF/dD`
    /// of the rocks of that diameter over the area `pi D^2 / 4` of one,
    /// `n_k(D) = 4 k q exp(-q D) / (pi D^2)`.
    #[must_use]
    pub fn number_density(k: f64, diameter_m: f64) -> f64 {
        let q = Self::exponent_per_m(k);
        4.0 * k * q * libm::exp(-q * diameter_m) / (std::f64::consts::PI * diameter_m * diameter_m)
    }

    /// Rocks per m² at abundance `k` with diameters in this field's range: the integral of
    /// `number_density` from `diameter_min_m` to `diameter_max_m` (0 for `k = 0`).
    #[must_use]
    pub fn rocks_per_m2(&self, k: f64) -> f64 {
        if k <= 0.0 {
            return 0.0;
        }
        // Over s = ln D the integrand is n_k(D) D, smooth across the range.
        let (a, b) = (
            libm::log(self.diameter_min_m),
            libm::log(self.diameter_max_m),
        );
        let h = (b - a) / SIMPSON_INTERVALS as f64;
        let f = |i: usize| {
            let d = libm::exp(a + h * i as f64);
            Self::number_density(k, d) * d
        };
        let inner: f64 = (1..SIMPSON_INTERVALS)
            .map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(i))
            .sum();
        (f(0) + inner + f(SIMPSON_INTERVALS)) * h / 3.0
    }

    /// The mean number of rocks over all tiles at abundance `k`.
    #[must_use]
    pub fn mean_rocks(&self, k: f64) -> f64 {
        self.rocks_per_m2(k) * self.tile_size_m * self.tile_size_m * self.tiles as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `[surface.rocks]` of `text` read, with the distributions it draws.
    fn read(text: &str) -> (Result<Rocks, ScenarioError>, Sampled) {
        let mut sampled: Sampled = [None; super::super::inputs::PARAMETERS];
        let table: toml::Table = text.parse().unwrap();
        let rocks = read_rocks(&mut Reader::new("surface.rocks", table), &mut sampled);
        (rocks, sampled)
    }

    /// The error's key and what it allows.
    fn refused(text: &str) -> (String, String) {
        match read(text).0 {
            Err(ScenarioError::Invalid { key, allowed, .. }) => (key, allowed),
            other => panic!("{text}: {other:?}"),
        }
    }

    #[test]
    fn bad_sizes_are_refused_naming_the_key() {
        let (key, allowed) = refused("diameter_min_m = 0.0");
        assert_eq!(
            (key.as_str(), allowed.as_str()),
            ("surface.rocks.diameter_min_m", "a number greater than 0")
        );
        // The default largest diameter (2 m) is checked against a given smallest one.
        let (key, allowed) = refused("diameter_min_m = 3.0");
        assert_eq!(key, "surface.rocks.diameter_max_m");
        assert!(
            allowed.contains("greater than diameter_min_m = 3 m"),
            "{allowed}"
        );
        let (key, allowed) = refused("diameter_max_m = 12.0");
        assert_eq!(key, "surface.rocks.tile_size_m");
        assert!(
            allowed.contains("at least twice diameter_max_m, 24 m"),
            "{allowed}"
        );
        assert_eq!(refused("tiles = 0").0, "surface.rocks.tiles");
        assert_eq!(refused("tiles = 1025").0, "surface.rocks.tiles");
    }

    /// Reads the abundance, which `read_parameter` knows by its `Parameter` (issue 32: the
    /// lead adds `surface.rocks.abundance` to `Parameter` when wiring `Surface`, then drops
    /// the `ignore`).
    #[test]
    fn the_abundance_is_a_parameter_from_0_to_a_half() {
        let (rocks, sampled) = read("");
        let rocks = rocks.unwrap();
        assert_eq!(rocks.abundance, 0.0);
        assert_eq!((rocks.diameter_min_m, rocks.diameter_max_m), (0.1, 2.0));
        assert_eq!((rocks.tile_size_m, rocks.tiles), (20.0, 8));
        assert!(sampled.iter().all(Option::is_none));
        let (rocks, sampled) = read("abundance = { dist = \"uniform\", min = 0.0, max = 0.2 }");
        assert_eq!(rocks.unwrap().abundance, 0.1);
        assert_eq!(sampled.iter().flatten().count(), 1);
        let (key, allowed) = refused("abundance = 0.6");
        assert_eq!(
            (key.as_str(), allowed.as_str()),
            ("surface.rocks.abundance", "an abundance from 0 to 0.5")
        );
        match read("abundance = { dist = \"uniform\", min = 0.0, max = 0.6 }").0 {
            Err(ScenarioError::Invalid { value, .. }) => {
                assert_eq!(value, "a distribution reaching 0.6");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(refused("abundance = -0.1").0, "surface.rocks.abundance");
        // 1024 tiles of 100 m at k = 0.2 from 0.1 m: 3.3 rocks per m², 34 million.
        let (key, allowed) = refused("abundance = 0.2\ntile_size_m = 100.0\ntiles = 1024");
        assert_eq!(key, "surface.rocks.tiles");
        assert!(allowed.contains("about 33279 per tile"), "{allowed}");
        assert!(matches!(
            read("diameters_max_m = 1.0").0,
            Err(ScenarioError::UnknownKey { .. })
        ));
    }

    #[test]
    fn the_number_density_integrates_to_the_fractional_area() {
        // The area of the rocks from D_min to D_max, pi D^2 / 4 times n_k, integrated by the
        // rule of `rocks_per_m2` (midpoints here), is F_k(D_min) - F_k(D_max).
        let field = Rocks {
            diameter_min_m: 0.1,
            diameter_max_m: 2.0,
            tile_size_m: 20.0,
            tiles: 8,
            abundance: 0.07,
        };
        let n = 200_000;
        let h = 1.9 / n as f64;
        let (mut count, mut area) = (0.0, 0.0);
        for i in 0..n {
            let d = 0.1 + h * (i as f64 + 0.5);
            count += Rocks::number_density(0.07, d) * h;
            area += Rocks::number_density(0.07, d) * std::f64::consts::PI * d * d / 4.0 * h;
        }
        let expected = Rocks::fractional_area(0.07, 0.1) - Rocks::fractional_area(0.07, 2.0);
        // The midpoint rule's error is h^2 / 24 times the second derivative: below 1e-9.
        assert!(
            (area - expected).abs() < 1e-8 * expected,
            "{area} {expected}"
        );
        assert!((field.rocks_per_m2(0.07) - count).abs() < 1e-8 * count);
        assert!((field.mean_rocks(0.07) - count * 3200.0).abs() < 1e-8 * count * 3200.0);
        assert_eq!(field.rocks_per_m2(0.0), 0.0);
    }
}
