//! `IdBits`: one bit per id (a vertex id or a component's root), the set several stages build
//! to let most ids skip a search or a walk (speed: a bit per point keeps the set in cache where a
//! `bool` per point or a sorted list would miss).
//!
//! It owns only the words and their bit arithmetic; what a set bit means is its user's.

use alloc::vec;
use alloc::vec::Vec;

/// A set of ids below a bound fixed at creation; ids at or past the bound are never in it.
#[derive(Debug, Clone)]
pub(crate) struct IdBits {
    /// Bit `i % 64` of word `i / 64`: whether `i` is in the set.
    words: Vec<u64>,
}

impl IdBits {
    /// The empty set of ids below `bound`.
    pub(crate) fn new(bound: usize) -> IdBits {
        IdBits {
            words: vec![0; bound.div_ceil(64)],
        }
    }

    /// The set of `ids`, sized to hold the largest of them.
    pub(crate) fn of(ids: impl Iterator<Item = usize> + Clone) -> IdBits {
        let mut set = IdBits::new(ids.clone().max().map_or(0, |i| i + 1));
        ids.for_each(|i| set.insert(i));
        set
    }

    /// Adds `i`, which must be below the bound.
    #[inline]
    pub(crate) fn insert(&mut self, i: usize) {
        self.words[i / 64] |= 1 << (i % 64);
    }

    /// Adds `i` when `yes` (without a branch: the repair and local outlier removal set one bit
    /// per vertex of the whole set, where a branch would be mispredicted on scattered points).
    #[inline]
    pub(crate) fn insert_if(&mut self, i: usize, yes: bool) {
        self.words[i / 64] |= u64::from(yes) << (i % 64);
    }

    /// Whether `i` is in the set (never for an id at or past the bound).
    #[inline]
    pub(crate) fn contains(&self, i: usize) -> bool {
        self.words
            .get(i / 64)
            .is_some_and(|w| w >> (i % 64) & 1 == 1)
    }

    /// The ids in the set, ascending.
    pub(crate) fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        self.words.iter().enumerate().flat_map(|(word, &bits)| {
            let mut rest = bits;
            core::iter::from_fn(move || {
                (rest != 0).then(|| {
                    let bit = rest.trailing_zeros() as usize;
                    rest &= rest - 1;
                    word * 64 + bit
                })
            })
        })
    }

    /// How many ids below `i` are in the set, when `i` is; `word_ranks` must be
    /// [`word_ranks`](IdBits::word_ranks) of this set. A rank among the set's ids in O(1).
    #[inline]
    pub(crate) fn rank(&self, i: usize, word_ranks: &[u32]) -> Option<usize> {
        let (word, bit) = (i / 64, i % 64);
        let bits = self.words[word];
        (bits >> bit & 1 == 1)
            .then(|| (word_ranks[word] + (bits & ((1u64 << bit) - 1)).count_ones()) as usize)
    }

    /// Per word, how many ids the words before it hold (for [`rank`](IdBits::rank)), and how
    /// many the set holds in all.
    pub(crate) fn word_ranks(&self) -> (Vec<u32>, u32) {
        let mut count = 0u32;
        let ranks = self
            .words
            .iter()
            .map(|word| {
                let before = count;
                count += word.count_ones();
                before
            })
            .collect();
        (ranks, count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_in_the_set_only_once_inserted_and_ranks_count_those_below() {
        let ids = [0usize, 5, 63, 64, 65, 130];
        let set = IdBits::of(ids.iter().copied());
        for i in 0..200 {
            assert_eq!(set.contains(i), ids.contains(&i), "{i}");
        }
        let (ranks, count) = set.word_ranks();
        assert_eq!(count, 6);
        for (r, &i) in ids.iter().enumerate() {
            assert_eq!(set.rank(i, &ranks), Some(r));
        }
        assert_eq!(set.rank(1, &ranks), None);
        assert!(set.iter().eq(ids.iter().copied()));
        let mut chosen = IdBits::new(10);
        for i in 0..10 {
            chosen.insert_if(i, i % 3 == 0);
        }
        assert!((0..10).all(|i| chosen.contains(i) == (i % 3 == 0)));
        assert!(!IdBits::of(core::iter::empty()).contains(0));
    }
}
