//! Shards: interleaved slices of a sweep's points, for running one sweep as several jobs.
use crate::model::InputError;

/// The K-th of N disjoint slices of a sweep (1 ≤ K ≤ N): the points with `point mod N = K − 1`.
/// Interleaved rather than contiguous so that every shard gets a like mix of fast and slow walks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// K, 1-based (Slurm's `SLURM_ARRAY_TASK_ID` with `--array=1-N`).
    pub index: usize,
    /// N.
    pub count: usize,
}

/// Largest shard count.
pub(crate) const MAX_SHARDS: usize = 1_000_000;

/// A shard `text` that is not K/N with whole numbers 1 ≤ K ≤ N ≤ 1 000 000.
#[derive(Debug, thiserror::Error)]
pub enum ShardError {
    /// A text without `/`.
    #[error("`{text}` must be K/N with whole numbers 1 ≤ K ≤ N ≤ {MAX_SHARDS}")]
    Shape {
        /// The text given.
        text: String,
    },
    /// K or N is not a whole number.
    #[error(
        "`{text}`: `{part}` is not a whole number; K/N with whole numbers 1 ≤ K ≤ N ≤ {MAX_SHARDS}"
    )]
    Part {
        /// The text given.
        text: String,
        /// The part that is not a whole number, trimmed.
        part: String,
    },
    /// K or N is not in 1 ≤ K ≤ N ≤ 1 000 000.
    #[error("`{text}` is out of range: K/N with whole numbers 1 ≤ K ≤ N ≤ {MAX_SHARDS}")]
    Range {
        /// The text given.
        text: String,
    },
}

impl Shard {
    /// The whole sweep, 1/1.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Parse `K/N` with 1 ≤ K ≤ N ≤ 1 000 000.
    pub fn parse(text: &str) -> Result<Shard, InputError> {
        let bad = |e: ShardError| InputError::bad_value("shard", e);
        let (k, n) = text.split_once('/').ok_or_else(|| {
            let text = text.into();
            bad(ShardError::Shape { text })
        })?;
        let whole = |t: &str| {
            t.trim().parse::<i64>().map_err(|_| {
                let (text, part) = (text.into(), t.trim().into());
                bad(ShardError::Part { text, part })
            })
        };
        let (index, count) = (whole(k)?, whole(n)?);
        if index < 1 || count < 1 || index > count || count > MAX_SHARDS as i64 {
            let text = text.into();
            return Err(bad(ShardError::Range { text }));
        }
        Ok(Shard {
            index: index as usize,
            count: count as usize,
        })
    }

    /// Whether point `p` belongs to this shard.
    pub(crate) fn contains(&self, p: usize) -> bool {
        p % self.count == self.index - 1
    }

    /// The shard's points of a sweep of `total` points, increasing, from `from` on.
    pub(crate) fn points(&self, total: usize, from: usize) -> impl Iterator<Item = usize> + use<> {
        let first = self.index - 1;
        let start = if from <= first {
            first
        } else {
            first + (from - first).div_ceil(self.count) * self.count
        };
        (start..total).step_by(self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shard_specs_are_validated() {
        assert_eq!(Shard::parse("1/1").unwrap(), Shard::ALL);
        assert_eq!(
            Shard::parse(" 3 / 8 ").unwrap(),
            Shard { index: 3, count: 8 }
        );
        for bad in [
            "0/4",
            "5/4",
            "1/0",
            "0/0",
            "-1/4",
            "1",
            "1/2/3",
            "a/4",
            "1.5/4",
            "",
            "2/2000000",
        ] {
            let e = Shard::parse(bad).unwrap_err();
            assert!(matches!(e, InputError::BadValue { .. }), "{bad}: {e}");
            let text = e.to_string();
            assert!(
                text.starts_with("shard:") && text.contains("1 ≤ K ≤ N"),
                "{bad}: {text}"
            );
        }
    }

    #[test]
    fn shard_points_start_where_asked() {
        let s = Shard { index: 2, count: 3 };
        assert_eq!(s.points(10, 0).collect::<Vec<_>>(), vec![1, 4, 7]);
        assert_eq!(s.points(10, 2).collect::<Vec<_>>(), vec![4, 7]);
        assert_eq!(s.points(10, 4).collect::<Vec<_>>(), vec![4, 7]);
        assert_eq!(s.points(10, 8).count(), 0);
        assert_eq!(Shard::ALL.points(3, 1).collect::<Vec<_>>(), vec![1, 2]);
    }

    proptest::proptest! {
        /// The N shards of a sweep are disjoint and together hold every point exactly once, and
        /// `points(total, from)` is `contains` filtered from `from` on.
        #[test]
        fn shards_partition_the_product(total in 0usize..500, count in 1usize..40, from in 0usize..520) {
            let mut seen = vec![0u32; total];
            for index in 1..=count {
                let shard = Shard { index, count };
                let points: Vec<usize> = shard.points(total, 0).collect();
                let filtered: Vec<usize> = (0..total).filter(|&p| shard.contains(p)).collect();
                proptest::prop_assert_eq!(&points, &filtered);
                let later: Vec<usize> = shard.points(total, from).collect();
                let want: Vec<usize> = filtered.iter().copied().filter(|&p| p >= from).collect();
                proptest::prop_assert_eq!(later, want);
                for p in points {
                    seen[p] += 1;
                }
            }
            proptest::prop_assert!(seen.iter().all(|&n| n == 1));
        }
    }
}
