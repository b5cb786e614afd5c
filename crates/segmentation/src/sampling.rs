//! Minimal samples of Algorithm 1 step 1, reproducible per seed.
//!
//! Hypothesis `j` draws its sample from its own ChaCha8 stream `j` under a
//! key expanded from the seed, so the samples — and with them the labels —
//! are the same for any number of threads and do not depend on anything but
//! the seed, the index and the number of points.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// SplitMix64's output function (Steele, Lea, Flood 2014): a bijective mix
/// of 64 bits.
///
/// ```
/// assert_eq!(segmentation::splitmix64(0), 0xe220a8397b1dcdaf);
/// ```
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The RNG of hypothesis `index` (Algorithm 1 step 1): a ChaCha8 key of four
/// successive SplitMix64 outputs starting from `seed`, and stream number
/// `index`.
///
/// ```
/// use rand::Rng;
/// let mut a = segmentation::hypothesis_rng(12345, 7);
/// let mut b = segmentation::hypothesis_rng(12345, 7);
/// let mut c = segmentation::hypothesis_rng(12345, 8);
/// let (x, y, z): (u64, u64, u64) = (a.gen(), b.gen(), c.gen());
/// assert_eq!(x, y);
/// assert_ne!(x, z);
/// ```
pub fn hypothesis_rng(seed: u64, index: usize) -> ChaCha8Rng {
    let mut state = seed;
    let mut key = [0u8; 32];
    for chunk in key.chunks_exact_mut(8) {
        state = splitmix64(state);
        chunk.copy_from_slice(&state.to_le_bytes());
    }
    let mut rng = ChaCha8Rng::from_seed(key);
    rng.set_stream(index as u64);
    rng
}

/// The minimal sample of hypothesis `index`: `mss_size` distinct indices
/// drawn uniformly from `0..n` (Algorithm 1 step 1). Needs `mss_size ≤ n`.
pub fn minimal_sample(seed: u64, index: usize, n: usize, mss_size: usize) -> Vec<usize> {
    let mut rng = hypothesis_rng(seed, index);
    rand::seq::index::sample(&mut rng, n, mss_size).into_vec()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix_matches_the_reference_sequence() {
        // The first outputs of SplitMix64 seeded with 1234567 (Vigna's
        // splitmix64.c): each output is the mix of the state advanced once.
        let mut state: u64 = 1234567;
        let mut outputs = Vec::new();
        for _ in 0..3 {
            outputs.push(splitmix64(state));
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        }
        assert_eq!(
            outputs,
            [
                6457827717110365317,
                3203168211198807973,
                9817491932198370423
            ]
        );
    }

    #[test]
    fn samples_are_distinct_in_range_and_reproducible() {
        for j in 0..200 {
            let s = minimal_sample(1, j, 30, 8);
            assert_eq!(s.len(), 8);
            let mut d = s.clone();
            d.sort_unstable();
            d.dedup();
            assert_eq!(d.len(), 8);
            assert!(s.iter().all(|&i| i < 30));
            assert_eq!(s, minimal_sample(1, j, 30, 8));
        }
        assert_ne!(minimal_sample(1, 0, 1000, 8), minimal_sample(2, 0, 1000, 8));
        assert_ne!(minimal_sample(1, 0, 1000, 8), minimal_sample(1, 1, 1000, 8));
    }
}
