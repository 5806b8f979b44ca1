//! A slice of a sweep's sample range, as a Slurm array task runs it (`--shard K/N`).

use std::ops::Range;

/// The `index`-th of `count` disjoint, contiguous slices of a sweep's sample range (as a
/// Slurm array numbers its tasks: 0 to `count - 1`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This slice's number, from 0.
    pub index: u64,
    /// How many slices the sweep is cut into.
    pub count: u64,
}

impl Shard {
    /// The samples of this shard out of `samples`: `samples * index / count` up to
    /// `samples * (index + 1) / count`, so the shards cover the range once, in order, and
    /// differ in size by one sample at most.
    #[must_use]
    pub fn range(self, samples: u64) -> Range<u64> {
        let at = |k: u64| (u128::from(samples) * u128::from(k) / u128::from(self.count)) as u64;
        at(self.index)..at(self.index + 1)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// `K/N` with `0 <= K < N`.
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("{s:?} is not a shard K/N with K from 0 to N-1 (example: 0/4)");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (u64, u64) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

#[cfg(test)]
mod tests {
    use super::Shard;

    #[test]
    fn shards_cover_the_range_once_in_order() {
        for samples in [0, 1, 3, 4, 7, 1000, 1_000_003, u64::MAX] {
            for count in [1, 2, 3, 4, 7, 16] {
                let ranges: Vec<_> = (0..count)
                    .map(|index| Shard { index, count }.range(samples))
                    .collect();
                assert_eq!(ranges[0].start, 0);
                assert_eq!(ranges[ranges.len() - 1].end, samples);
                for w in ranges.windows(2) {
                    assert_eq!(w[0].end, w[1].start, "{samples} samples in {count} shards");
                }
                let sizes: Vec<u64> = ranges.iter().map(|r| r.end - r.start).collect();
                let (min, max) = (sizes.iter().min().unwrap(), sizes.iter().max().unwrap());
                assert!(max - min <= 1, "{samples} in {count}: sizes {sizes:?}");
            }
        }
    }

    #[test]
    fn shards_parse_as_k_of_n() {
        assert_eq!("0/4".parse(), Ok(Shard { index: 0, count: 4 }));
        assert_eq!("3/4".parse(), Ok(Shard { index: 3, count: 4 }));
        assert_eq!("0/1".parse(), Ok(Shard { index: 0, count: 1 }));
        for bad in ["4/4", "1/0", "0/0", "-1/4", "1", "a/b", "1/4/2", ""] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
