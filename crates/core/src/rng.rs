//! The maze random number generator and every random choice a generator makes.
//!
//! Determinism is a product promise: the same seed must give the same maze with every
//! future version of our dependencies. So the generator is a named, portable stream
//! cipher (ChaCha with 8 rounds, from `rand_chacha`), keyed by a documented derivation,
//! and the only operations built on it are the small functions below, written here
//! rather than borrowed from `rand`, whose distributions may change between releases.
//!
//! Seed derivation: the 32-byte ChaCha key is the seed as 8 little-endian bytes
//! followed by the 24 ASCII bytes of [`KEY_DOMAIN`]; the nonce (stream) is 0.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Fills key bytes 8..32, so vrep-maze keys never collide with other ChaCha uses.
pub const KEY_DOMAIN: &[u8; 24] = b"vrep-maze layout rng v1\0";

/// The random stream behind one maze. Build it with [`MazeRng::from_seed`].
#[derive(Debug, Clone)]
pub struct MazeRng {
    inner: ChaCha8Rng,
    /// Unused bits of the last word drawn by [`bits`](Self::bits), lowest first.
    pool: u32,
    /// How many bits of `pool` are still unused.
    pool_left: u32,
}

impl MazeRng {
    /// The stream for `seed`, keyed as the module documentation says.
    pub fn from_seed(seed: u64) -> Self {
        let mut key = [0u8; 32];
        key[..8].copy_from_slice(&seed.to_le_bytes());
        key[8..].copy_from_slice(KEY_DOMAIN);
        Self {
            inner: ChaCha8Rng::from_seed(key),
            pool: 0,
            pool_left: 0,
        }
    }

    /// The next 32 raw bits of the stream.
    pub fn next_u32(&mut self) -> u32 {
        self.inner.next_u32()
    }

    /// A uniform integer in `0..n` (Lemire's multiply-and-reject method on 32-bit draws).
    ///
    /// # Panics
    /// If `n` is 0: there is no integer to choose.
    pub fn below(&mut self, n: u32) -> u32 {
        assert!(n > 0, "below(0) has no value to return");
        // Reject the low products that would make some results one draw more likely: those
        // below `threshold = 2^32 mod n`. As `threshold < n`, a low part of at least `n` is
        // always accepted, so the division is only paid for the rare low parts under `n`
        // (the same draws are accepted and rejected as with an up-front threshold).
        let mut product = u64::from(self.next_u32()) * u64::from(n);
        if (product as u32) < n {
            let threshold = n.wrapping_neg() % n;
            while (product as u32) < threshold {
                product = u64::from(self.next_u32()) * u64::from(n);
            }
        }
        (product >> 32) as u32
    }

    /// `k` uniform random bits (`1 <= k <= 16`) as the low bits of the result.
    ///
    /// Bits are handed out from a pool, lowest first: when fewer than `k` unused bits
    /// remain, the rest are dropped and a fresh word is drawn with [`next_u32`](Self::next_u32).
    /// So a coin flip (`bits(1)`) costs 1/32 of a draw and a choice among four directions
    /// (`bits(2)`) 1/16. The pool is separate from the other functions: they never see or
    /// consume pooled bits, but every call still advances one shared, seed-determined stream.
    #[inline]
    pub fn bits(&mut self, k: u32) -> u32 {
        debug_assert!((1..=16).contains(&k), "bits({k}) outside 1..=16");
        if self.pool_left < k {
            self.pool = self.next_u32();
            self.pool_left = 32;
        }
        let value = self.pool & ((1 << k) - 1);
        self.pool >>= k;
        self.pool_left -= k;
        value
    }

    /// A fair coin flip: one pooled bit (see [`bits`](Self::bits)).
    #[inline]
    pub fn coin(&mut self) -> bool {
        self.bits(1) == 1
    }

    /// A uniform index into a slice of length `len` (`len` must fit in `u32`).
    pub fn index(&mut self, len: usize) -> usize {
        let n = u32::try_from(len).expect("random index range exceeds u32");
        self.below(n) as usize
    }

    /// `true` with probability `numerator / denominator`.
    pub fn chance(&mut self, numerator: u32, denominator: u32) -> bool {
        self.below(denominator) < numerator
    }

    /// Shuffles `items` in place (Fisher-Yates, from the back, one [`index`](Self::index) per step).
    ///
    /// The draws do not depend on the items, so they are taken in batches and the slots
    /// about to be swapped are prefetched first: on large slices the cache misses then
    /// overlap instead of stalling one by one. Draws and swaps happen in exactly the
    /// plain algorithm's order, so the result is the same.
    pub fn shuffle<T>(&mut self, items: &mut [T]) {
        self.shuffle_back(items, items.len().saturating_sub(1));
    }

    /// The first `steps` steps of [`shuffle`](Self::shuffle): afterwards the last `steps`
    /// items are where the whole shuffle leaves them, and shuffling the items before them
    /// (with this function or `shuffle`) finishes exactly the same shuffle. So a caller can
    /// hand out the finished tail while the head is still being shuffled.
    ///
    /// # Panics
    /// If `steps` is `items.len()` or more (the first item is never a step of its own),
    /// unless both are 0.
    pub fn shuffle_back<T>(&mut self, items: &mut [T], steps: usize) {
        const BATCH: usize = 64;
        assert!(
            steps < items.len() || steps == 0,
            "{steps} shuffle steps on {} items",
            items.len()
        );
        let mut picks = [0usize; BATCH];
        let mut last = items.len().saturating_sub(1);
        let end = last - steps;
        while last > end {
            let count = BATCH.min(last - end);
            for (step, pick) in picks[..count].iter_mut().enumerate() {
                *pick = self.index(last - step + 1);
            }
            for &pick in &picks[..count] {
                prefetch(&items[pick]);
            }
            for (step, &pick) in picks[..count].iter().enumerate() {
                items.swap(last - step, pick);
            }
            last -= count;
        }
    }
}

/// Hints the CPU to start loading `item`'s cache line; no effect on results.
#[inline(always)]
pub(crate) fn prefetch<T>(item: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: prefetching is a hint that never faults, on a valid reference besides.
    unsafe {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>(std::ptr::from_ref(item).cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = item;
}

/// A fresh seed from the operating system, for runs that give none.
pub fn os_seed() -> u64 {
    rand::random()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stream_for_a_seed_never_changes() {
        // Pinned values: if these change, every maze changes. Never re-bless casually.
        let mut rng = MazeRng::from_seed(42);
        let first: Vec<u32> = (0..4).map(|_| rng.next_u32()).collect();
        let mut again = MazeRng::from_seed(42);
        let second: Vec<u32> = (0..4).map(|_| again.next_u32()).collect();
        assert_eq!(first, second);
        assert_eq!(first, PINNED_SEED_42);
    }

    const PINNED_SEED_42: [u32; 4] = [1356390841, 868802478, 2533333241, 1611238984];

    #[test]
    fn different_seeds_give_different_streams() {
        let a = MazeRng::from_seed(1).next_u32();
        let b = MazeRng::from_seed(2).next_u32();
        assert_ne!(a, b);
    }

    #[test]
    fn below_stays_in_range_and_hits_every_value() {
        let mut rng = MazeRng::from_seed(7);
        let mut seen = [0u32; 7];
        for _ in 0..7000 {
            let v = rng.below(7);
            seen[v as usize] += 1;
        }
        assert!(seen.iter().all(|&c| (800..1200).contains(&c)), "{seen:?}");
        assert_eq!(rng.below(1), 0);
    }

    #[test]
    fn batched_shuffle_matches_plain_fisher_yates() {
        for len in [0, 1, 2, 15, 16, 17, 33, 1000] {
            let mut rng = MazeRng::from_seed(len as u64);
            let mut reference = MazeRng::from_seed(len as u64);
            let mut items: Vec<u32> = (0..len).collect();
            let mut expected = items.clone();
            rng.shuffle(&mut items);
            for last in (1..expected.len()).rev() {
                let pick = reference.index(last + 1);
                expected.swap(last, pick);
            }
            assert_eq!(items, expected, "len {len}");
            assert_eq!(rng.next_u32(), reference.next_u32());
        }
    }

    #[test]
    fn a_shuffle_finished_in_pieces_is_the_same_shuffle() {
        for (len, piece) in [(2, 1), (100, 1), (100, 7), (1000, 64), (1000, 999)] {
            let mut whole: Vec<u32> = (0..len).collect();
            let mut rng = MazeRng::from_seed(5);
            rng.shuffle(&mut whole);
            let mut pieces: Vec<u32> = (0..len).collect();
            let mut again = MazeRng::from_seed(5);
            let mut rest = &mut pieces[..];
            while rest.len() > piece {
                again.shuffle_back(rest, piece);
                let at = rest.len() - piece;
                rest = &mut rest[..at];
            }
            again.shuffle(rest);
            assert_eq!(pieces, whole, "len {len}, pieces of {piece}");
            assert_eq!(again.next_u32(), rng.next_u32());
        }
    }

    #[test]
    fn shuffle_is_a_permutation() {
        let mut rng = MazeRng::from_seed(3);
        let mut items: Vec<u32> = (0..100).collect();
        rng.shuffle(&mut items);
        assert_ne!(items, (0..100).collect::<Vec<_>>());
        items.sort_unstable();
        assert_eq!(items, (0..100).collect::<Vec<_>>());
    }

    /// `below` as first written (threshold computed up front), the reference the lazy
    /// version must match draw for draw: mazes from dfs/prim/kruskal are pinned by it.
    fn reference_below(rng: &mut MazeRng, n: u32) -> u32 {
        let threshold = n.wrapping_neg() % n;
        loop {
            let product = u64::from(rng.next_u32()) * u64::from(n);
            if (product as u32) >= threshold {
                return (product >> 32) as u32;
            }
        }
    }

    #[test]
    fn lazy_below_matches_the_reference_draw_for_draw() {
        let mut rng = MazeRng::from_seed(42);
        let mut reference = MazeRng::from_seed(42);
        for n in [1, 2, 3, 4, 7, 1000, 3_000_000_019, u32::MAX, (1 << 31) + 1] {
            for _ in 0..2000 {
                assert_eq!(rng.below(n), reference_below(&mut reference, n), "n = {n}");
            }
        }
        assert_eq!(rng.next_u32(), reference.next_u32());
    }

    #[test]
    fn bits_come_from_the_pool_lowest_first() {
        let mut rng = MazeRng::from_seed(42);
        let mut again = MazeRng::from_seed(42);
        let word = again.next_u32();
        let twos: Vec<u32> = (0..16).map(|_| rng.bits(2)).collect();
        let expected: Vec<u32> = (0..16).map(|i| (word >> (2 * i)) & 3).collect();
        assert_eq!(twos, expected);
        // The 17th pair needs a fresh word; 3 bits leave 2 unused, so 3 more draw again.
        assert_eq!(rng.bits(3), again.next_u32() & 7);
        let mut counts = [0u32; 2];
        for _ in 0..10_000 {
            counts[usize::from(rng.coin())] += 1;
        }
        assert!(
            counts.iter().all(|&c| (4800..5200).contains(&c)),
            "{counts:?}"
        );
    }

    #[test]
    fn batched_shuffle_is_plain_fisher_yates() {
        for len in [0, 1, 2, 31, 32, 33, 100, 1000] {
            let mut batched: Vec<usize> = (0..len).collect();
            MazeRng::from_seed(len as u64).shuffle(&mut batched);
            let mut plain: Vec<usize> = (0..len).collect();
            let mut rng = MazeRng::from_seed(len as u64);
            for last in (1..len).rev() {
                let pick = rng.index(last + 1);
                plain.swap(last, pick);
            }
            assert_eq!(batched, plain, "len {len}");
        }
    }

    #[test]
    fn chance_follows_its_ratio() {
        let mut rng = MazeRng::from_seed(9);
        let hits = (0..10_000).filter(|_| rng.chance(1, 4)).count();
        assert!((2300..2700).contains(&hits), "{hits}");
    }
}
